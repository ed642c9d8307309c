//! Geometry a converter reads from another renderer's scene: the look-at frame, affine maps'
//! linear parts and whether they keep shapes' proportions, parallelograms found in pairs of
//! triangles, and whether a mesh's interpolated normals are its faces'.

use glam::{DMat3, DMat4, DVec3};

/// The look-at frame Mitsuba and pbrt both build (world from camera): columns x = up × dir,
/// y = dir × x, dir, and the origin. Mitsuba's camera shows its +x on the image's left, pbrt's
/// on the right. None when the target is the origin or up lies along the view.
pub fn look_at(origin: DVec3, target: DVec3, up: DVec3) -> Option<DMat4> {
    let dir = (target - origin).try_normalize()?;
    let x = up.cross(dir).try_normalize()?;
    let new_up = dir.cross(x);
    Some(DMat4::from_cols(
        x.extend(0.0),
        new_up.extend(0.0),
        dir.extend(0.0),
        origin.extend(1.0),
    ))
}

/// The linear part of an affine map.
pub fn linear(m: &DMat4) -> DMat3 {
    DMat3::from_mat4(*m)
}

/// The scale along each axis of a map that neither turns nor shears — its linear part
/// diagonal, each entry non-zero, negative where it mirrors that axis; None otherwise.
pub fn axis_scales(m: &DMat4) -> Option<DVec3> {
    let l = linear(m);
    let diagonal = DVec3::new(l.x_axis.x, l.y_axis.y, l.z_axis.z);
    let off_diagonal = [
        l.x_axis.y, l.x_axis.z, l.y_axis.x, l.y_axis.z, l.z_axis.x, l.z_axis.y,
    ];
    let axis_aligned = off_diagonal.iter().all(|&x| x == 0.0);
    (axis_aligned && !diagonal.cmpeq(DVec3::ZERO).any()).then_some(diagonal)
}

/// The uniform scale s of a map whose linear part is s times a rotation (None: it shears or
/// scales unevenly, beyond a relative 1e-6).
pub fn similarity(m: &DMat4) -> Option<f64> {
    let l = linear(m);
    let s = [l.x_axis.length(), l.y_axis.length(), l.z_axis.length()];
    let scale = s[0];
    let even = s.iter().all(|&x| (x - scale).abs() <= 1e-6 * scale);
    let square = (l.x_axis.dot(l.y_axis).abs()
        + l.y_axis.dot(l.z_axis).abs()
        + l.x_axis.dot(l.z_axis).abs())
        <= 1e-6 * scale * scale;
    (scale > 0.0 && even && square).then_some(scale)
}

/// The four corners of two triangles that form one parallelogram, ordered v0..v3 around it
/// with its normal on the triangles' side (the other side if flipped).
pub fn parallelogram(triangles: [[DVec3; 3]; 2], flip: bool) -> Option<[DVec3; 4]> {
    let [t, u] = triangles;
    let normal = (t[1] - t[0]).cross(t[2] - t[0]);
    let scale = normal.length().sqrt();
    let same = |p: DVec3, q: DVec3| (p - q).length() <= 1e-9 * scale.max(1e-300);
    // The corner of u not in t.
    let far = u.into_iter().find(|p| !t.iter().any(|q| same(*p, *q)))?;
    if u.iter().filter(|p| t.iter().any(|q| same(**p, *q))).count() != 2 {
        return None;
    }
    // The corner of t opposite the shared edge: the one u lacks.
    let i = (0..3).find(|&i| !u.iter().any(|p| same(*p, t[i])))?;
    let (v0, v1, v3) = (t[i], t[(i + 1) % 3], t[(i + 2) % 3]);
    let v2 = far;
    if !same(v1 + v3 - v0, v2) {
        return None;
    }
    let order = [v0, v1, v2, v3];
    let along = (v1 - v0).cross(v3 - v0).dot(normal) > 0.0;
    let order = if along != flip {
        order
    } else {
        [v0, v3, v2, v1]
    };
    // Both triangles must face the same way.
    let agree = (u[1] - u[0]).cross(u[2] - u[0]).dot(normal) > 0.0;
    agree.then_some(order)
}

/// The area of the triangle of corners a, b, c (length²).
pub fn triangle_area([a, b, c]: &[DVec3; 3]) -> f64 {
    0.5 * (*b - *a).cross(*c - *a).length()
}

/// Which side an emitting mesh's triangles emit from, against their winding's normal
/// (b − a) × (c − a) in the world.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Facing {
    /// Every triangle emits on its winding's side.
    Winding,
    /// Every triangle emits on the other side.
    Against,
    /// Some do, some do not: `against` of the `of` triangles with an area emit against their
    /// winding, and `split` have corners whose normals point to both sides.
    Mixed {
        /// Triangles emitting against their winding.
        against: usize,
        /// Triangles whose corners' normals disagree.
        split: usize,
        /// Triangles with an area.
        of: usize,
    },
}

/// Which side each of a mesh's `triangles` (corners in the world) emits from: its winding's,
/// or where `normals` gives triangle i's corners normals in the world, the side they point to
/// (a renderer that reads the emitting side off the interpolated shading normal); then
/// turned over where `flip`. Triangles without an area are not counted.
pub fn emitting_side(
    triangles: impl Iterator<Item = [DVec3; 3]>,
    normals: Option<&dyn Fn(usize) -> [DVec3; 3]>,
    flip: bool,
) -> Facing {
    let (mut against, mut split, mut of) = (0, 0, 0);
    for (i, [a, b, c]) in triangles.enumerate() {
        let w = (b - a).cross(c - a);
        if w.length_squared() == 0.0 {
            continue;
        }
        of += 1;
        let sides = normals.map_or([true; 3], |n| n(i).map(|n| n.dot(w) > 0.0));
        match sides {
            [true, true, true] => against += usize::from(flip),
            [false, false, false] => against += usize::from(!flip),
            _ => split += 1,
        }
    }
    match (against, split) {
        (0, 0) => Facing::Winding,
        (n, 0) if n == of => Facing::Against,
        _ => Facing::Mixed { against, split, of },
    }
}

/// The angle between `a` and `b` (any lengths, not zero), radians.
fn angle(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

/// The angle within which normals count as one, radians.
pub const FACES_TOLERANCE: f64 = 1e-6;

/// How far the normals a renderer interpolates over a mesh turn from its faces' own (radians,
/// the largest over its corners) — so that a BSDF evaluated about them is evaluated about each
/// triangle's where this is 0 ([`FACES_TOLERANCE`]): the vertex normals `normal` gives
/// (placed) against each triangle's where there are some, else (the renderer averaging the
/// faces at each vertex) the faces meeting at each vertex against the first of them there,
/// which bounds twice the turn of their average. Triangles of no area are passed over.
pub fn normal_turn(
    triangles: &[[u32; 3]],
    corner: &dyn Fn(u32) -> DVec3,
    normal: Option<&dyn Fn(u32) -> DVec3>,
) -> f64 {
    let mut first: std::collections::HashMap<u32, DVec3> = std::collections::HashMap::new();
    let mut turn: f64 = 0.0;
    for t in triangles {
        let [a, b, c] = t.map(corner);
        let w = (b - a).cross(c - a);
        if w.length_squared() == 0.0 {
            continue;
        }
        for &k in t {
            let n = match normal {
                Some(normal) => normal(k),
                None => *first.entry(k).or_insert(w),
            };
            turn = turn.max(angle(n, w));
        }
    }
    turn
}

/// The frame [x, y, z] of a round shape's local axes as its transform turns them: z along `z`,
/// x and y along `x` and `y` (the images of the local x and y) made orthogonal to it and to
/// each other in that order — a similarity turns them orthogonal already, to rounding — so
/// that z keeps the direction of grinlight's axis or normal exactly.
pub fn local_frame(z: DVec3, x: DVec3, y: DVec3) -> [DVec3; 3] {
    let z = z.normalize();
    let x = (x - z * z.dot(x)).normalize();
    let y = (y - z * z.dot(y) - x * x.dot(y)).normalize();
    [x, y, z]
}
