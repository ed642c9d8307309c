//! Primitives against brute force, and the BVH against a loop over all primitives.

use glam::DVec3;
use grinlight::accel::Accel;
use grinlight::curve::CurvedSegment;
use grinlight::shapes::{Disk, Hit, Primitive, Quad, SegmentHits, Triangle};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use crate::common;

fn rv(rng: &mut Pcg64Mcg) -> DVec3 {
    DVec3::new(
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
    )
}

fn primitives(rng: &mut Pcg64Mcg) -> Vec<Primitive> {
    let mut v = Vec::new();
    for _ in 0..6 {
        v.push(Primitive::Sphere {
            center: rv(rng),
            radius: rng.gen_range(0.1..0.6),
        });
        v.push(Primitive::Tube {
            base: rv(rng),
            axis: rv(rng).normalize(),
            radius: rng.gen_range(0.1..0.5),
            height: rng.gen_range(0.2..1.0),
        });
        v.push(Primitive::Quad(Quad {
            origin: rv(rng),
            e1: rv(rng),
            e2: rv(rng),
        }));
        v.push(Primitive::Disk(Disk {
            center: rv(rng),
            normal: rv(rng).normalize(),
            radius: rng.gen_range(0.1..0.7),
            inner: if rng.gen::<bool>() {
                rng.gen_range(0.0..0.1)
            } else {
                0.0
            },
        }));
        v.push(Primitive::triangle(rv(rng), rv(rng), rv(rng)));
    }
    v
}

/// Oracle: the first point on a path x(s), s ∈ (s_min, L], where the primitive's own
/// distance-like function changes sign at an accepted point, by sampling 20 000 points and
/// bisecting (relative accuracy ~1e-15 in s, can only miss crossings closer than L/20000).
fn brute_force(p: &Primitive, path: impl Fn(f64) -> DVec3, s_min: f64, length: f64) -> Option<f64> {
    let g = |s: f64| signed(p, path(s));
    let n = 20_000;
    let mut a = s_min;
    let mut ga = g(a);
    for i in 1..=n {
        let b = s_min + (length - s_min) * i as f64 / n as f64;
        let gb = g(b);
        if ga * gb <= 0.0 && gb != ga {
            let (mut lo, mut hi) = (a, b);
            for _ in 0..200 {
                let m = 0.5 * (lo + hi);
                if (g(m) > 0.0) == (ga > 0.0) {
                    lo = m;
                } else {
                    hi = m;
                }
            }
            let s = 0.5 * (lo + hi);
            if on_primitive(p, path(s)) {
                return Some(s);
            }
        }
        (a, ga) = (b, gb);
    }
    None
}

/// Distance-like implicit functions written out independently of the crate's.
fn signed(p: &Primitive, x: DVec3) -> f64 {
    match *p {
        Primitive::Sphere { center, radius } => (x - center).length() - radius,
        Primitive::Tube {
            base, axis, radius, ..
        } => {
            let d = x - base;
            (d - axis * d.dot(axis)).length() - radius
        }
        Primitive::Quad(Quad { origin, e1, e2 }) => (x - origin).dot(e1.cross(e2).normalize()),
        Primitive::Disk(Disk { center, normal, .. }) => (x - center).dot(normal),
        Primitive::Triangle(Triangle { v0, e1, e2 }) => (x - v0).dot(e1.cross(e2).normalize()),
        Primitive::Mesh(_) => unreachable!("meshes are tested triangle by triangle"),
    }
}

fn on_primitive(p: &Primitive, x: DVec3) -> bool {
    match *p {
        Primitive::Sphere { .. } => true,
        Primitive::Tube {
            base, axis, height, ..
        } => (0.0..=height).contains(&(x - base).dot(axis)),
        Primitive::Quad(Quad { origin, e1, e2 }) => {
            // Barycentric-free test: x in the parallelogram iff both in-plane coordinates in [0,1].
            let n = e1.cross(e2);
            let u = (x - origin).cross(e2).dot(n) / n.length_squared();
            let v = e1.cross(x - origin).dot(n) / n.length_squared();
            (0.0..=1.0).contains(&u) && (0.0..=1.0).contains(&v)
        }
        Primitive::Disk(Disk {
            center,
            radius,
            inner,
            ..
        }) => (inner..=radius).contains(&(x - center).length()),
        Primitive::Triangle(Triangle { v0, e1, e2 }) => {
            let n = e1.cross(e2);
            let u = (x - v0).cross(e2).dot(n) / n.length_squared();
            let v = e1.cross(x - v0).dot(n) / n.length_squared();
            u >= 0.0 && v >= 0.0 && u + v <= 1.0
        }
        Primitive::Mesh(_) => unreachable!("meshes are tested triangle by triangle"),
    }
}

/// Straight rays: every primitive's nearest hit equals the oracle's to 1e-9 relative (the
/// oracle's sampling cannot see hits closer than L/20000 to an edge or grazing; those cases,
/// where the two disagree only about existence within that resolution, are counted, not
/// failed, and must stay rare).
#[test]
fn straight_hits_match_brute_force() {
    let mut rng = Pcg64Mcg::seed_from_u64(5);
    let prims = primitives(&mut rng);
    let (mut hits, mut unresolved) = (0, 0);
    for _ in 0..250 {
        let o = rv(&mut rng) * 2.0;
        let d = rv(&mut rng).normalize();
        for p in &prims {
            let got = p.intersect_ray(o, d, 0.0, 4.0).map(|h| h.t);
            let want = brute_force(p, |s| o + s * d, 0.0, 4.0);
            match (got, want) {
                (Some(g), Some(w)) => {
                    hits += 1;
                    assert!((g - w).abs() <= 1e-9 * w.max(1e-3), "{p:?}: {g} vs {w}");
                    let n = p.intersect_ray(o, d, 0.0, 4.0).unwrap().normal;
                    assert!((n.length() - 1.0).abs() < 1e-12);
                }
                (None, None) => {}
                _ => unresolved += 1,
            }
        }
    }
    println!("{hits} straight hits, {unresolved} unresolved by the oracle");
    assert!(hits > 50 && unresolved * 100 < hits, "{hits} {unresolved}");
}

/// Curved segments (|F| up to 4, lengths up to 2: up to 8 rad of bending) against the oracle.
#[test]
fn curved_hits_match_brute_force() {
    let mut rng = Pcg64Mcg::seed_from_u64(6);
    let prims = primitives(&mut rng);
    let (mut hits, mut unresolved) = (0, 0);
    for _ in 0..150 {
        let seg = CurvedSegment::new(rv(&mut rng) * 1.5, rv(&mut rng), rv(&mut rng) * 4.0);
        let length = rng.gen_range(0.2..2.0);
        for p in &prims {
            let got = p
                .intersect_segment(&seg, &seg.hull(length), 0.0, length)
                .map(|h| h.t);
            let want = brute_force(p, |s| seg.at(s).position, 0.0, length);
            match (got, want) {
                (Some(g), Some(w)) => {
                    hits += 1;
                    assert!((g - w).abs() <= 1e-9 * w.max(1e-3), "{p:?}: {g} vs {w}");
                }
                (None, None) => {}
                _ => unresolved += 1,
            }
        }
    }
    println!("{hits} curved hits, {unresolved} unresolved by the oracle");
    assert!(hits > 50 && unresolved * 50 < hits, "{hits} {unresolved}");
}

/// The nearest of `prims` by `f` (a hit's distance): (index, distance).
fn nearest_of(prims: &[Primitive], f: &dyn Fn(&Primitive) -> Option<f64>) -> Option<(usize, f64)> {
    prims
        .iter()
        .enumerate()
        .filter_map(|(i, p)| f(p).map(|t| (i, t)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
}

/// The BVH returns the same nearest hit as a loop over all primitives, for straight rays and
/// curved segments, on 600 random primitives.
#[test]
fn bvh_equals_a_loop_over_all_primitives() {
    let mut rng = Pcg64Mcg::seed_from_u64(7);
    let prims: Vec<Primitive> = (0..120)
        .flat_map(|_| primitives(&mut rng).into_iter().take(5))
        .collect();
    let accel = Accel::new(prims.clone());
    let nearest = |f: &dyn Fn(&Primitive) -> Option<f64>| nearest_of(&prims, f);
    for _ in 0..300 {
        let o = rv(&mut rng) * 2.0;
        let d = rv(&mut rng).normalize();
        let want = nearest(&|p| p.intersect_ray(o, d, 0.0, 10.0).map(|h| h.t));
        let got = accel
            .intersect_ray(o, d, 0.0, 10.0)
            .map(|b| (b.prim.index(), b.hit.t));
        assert_eq!(got, want);
        let seg = CurvedSegment::new(o, d, rv(&mut rng) * 3.0);
        // Same primitive, same arclength to 1e-12 relative (the refinement's tolerance; the
        // BVH search refines on a shorter bracket once a nearer hit is known).
        let want = nearest(&|p| {
            p.intersect_segment(&seg, &seg.hull(1.5), 0.0, 1.5)
                .map(|h| h.t)
        });
        let got = accel
            .intersect_segment(&seg, &seg.hull(1.5), 0.0, 1.5)
            .map(|b| (b.prim.index(), b.hit.t));
        match (got, want) {
            (Some((gi, gt)), Some((wi, wt))) => assert!(
                gi == wi && (gt - wt).abs() <= 1e-12 * wt,
                "{got:?} vs {want:?}"
            ),
            _ => assert_eq!(got, want),
        }
    }
}

/// Straight rays through scenes of every size find what a loop over the primitives finds,
/// nearest hit and any hit: one primitive (a tree of one leaf) to 600, 80 nested balls, the
/// whole scene 30 000 units from the origin, and rays starting on a surface (where the next
/// surface can be 1e-6 away).
#[test]
fn straight_rays_find_what_a_loop_finds_in_scenes_of_every_size() {
    let mut rng = Pcg64Mcg::seed_from_u64(23);
    let mut scenes: Vec<Vec<Primitive>> = [1, 2, 3, 9, 40, 600]
        .into_iter()
        .map(|n| {
            let mut all = Vec::new();
            while all.len() < n {
                all.extend(primitives(&mut rng));
            }
            all.truncate(n);
            all
        })
        .collect();
    scenes.push(
        (0..80)
            .map(|i| {
                let radius = 1.07f64.powi(i) * 0.01;
                Primitive::Sphere {
                    center: DVec3::new(radius, 0.0, 0.0),
                    radius,
                }
            })
            .collect(),
    );
    let far = DVec3::new(3e4, -1e4, 2e4);
    scenes.push(
        scenes[4]
            .iter()
            .map(|p| match p {
                Primitive::Sphere { center, radius } => Primitive::Sphere {
                    center: *center + far,
                    radius: *radius,
                },
                _ => Primitive::Sphere {
                    center: far + rv(&mut rng),
                    radius: 0.3,
                },
            })
            .collect(),
    );
    for (k, prims) in scenes.iter().enumerate() {
        let accel = Accel::new(prims.clone());
        let centre = match k {
            7 => far,
            _ => DVec3::ZERO,
        };
        let nearest = |f: &dyn Fn(&Primitive) -> Option<f64>| nearest_of(prims, f);
        let (mut hits, mut near) = (0, 0);
        for case in 0..2000 {
            let mut o = centre + rv(&mut rng) * 2.0;
            // Half the rays aimed into a primitive's box.
            let d = match case % 4 < 2 {
                true => rv(&mut rng).normalize(),
                false => {
                    let b = prims[rng.gen_range(0..prims.len())].bounds();
                    let u = DVec3::new(rng.gen(), rng.gen(), rng.gen());
                    (b.lo + (b.hi - b.lo) * u - o).normalize()
                }
            };
            if case % 2 == 1 {
                // From a surface: where a ray met one, leaving it in a new direction.
                let e = rv(&mut rng).normalize();
                match nearest(&|p| p.intersect_ray(o, e, 0.0, 10.0).map(|h| h.t)) {
                    Some((_, t)) => o += e * t,
                    None => continue,
                }
            }
            let t_min = 1e-9;
            let want = nearest(&|p| p.intersect_ray(o, d, t_min, 10.0).map(|h| h.t));
            let got = accel
                .intersect_ray(o, d, t_min, 10.0)
                .map(|b| (b.prim.index(), b.hit.t));
            assert_eq!(got, want, "scene {k}, case {case}");
            assert_eq!(
                accel.blocked(o, d, t_min, 10.0, |_| false),
                want.is_some(),
                "scene {k}, case {case}"
            );
            hits += usize::from(want.is_some());
            near += usize::from(want.is_some_and(|(_, t)| t < 1e-3));
        }
        assert!(hits > 300, "scene {k}: {hits} hits");
        if k >= 4 {
            assert!(near > 0, "scene {k}: no hit nearer than 1e-3");
        }
    }
}

/// A ray that nearly parallels a wall's plane (its x component 1e-9) and starts just inside
/// the wall's box along x (3e-6 from the padded face) meets the wall 100 units on. A box test
/// taking 1/d_x as 1/1.2e-7 (a safe inverse's floor) has it leave the box's x slab after 25
/// units, and would miss. The wall as a quad alone (a tree of one leaf), beside another, and
/// as a mesh of two triangles (its own BVH).
#[test]
fn a_ray_nearly_parallel_to_a_box_face_still_enters_it() {
    use grinlight::shapes::TriangleMesh;
    let wall = |z: f64| {
        Primitive::Quad(Quad {
            origin: DVec3::new(0.0, 0.0, z),
            e1: DVec3::X,
            e2: DVec3::Y,
        })
    };
    let corners = vec![
        [0.0, 0.0, 100.0],
        [1.0, 0.0, 100.0],
        [1.0, 1.0, 100.0],
        [0.0, 1.0, 100.0],
    ];
    let mesh = TriangleMesh::new(corners, vec![[0, 1, 2], [0, 2, 3]], None, None).unwrap();
    let mesh = Primitive::Mesh(std::sync::Arc::new(mesh));
    for walls in [
        vec![wall(100.0)],
        vec![wall(100.0), wall(-5.0)],
        vec![mesh, wall(-5.0)],
    ] {
        let accel = Accel::new(walls);
        let o = DVec3::new(1.0 - 1e-6, 0.5, 0.0);
        let d = DVec3::new(1e-9, 0.0, 1.0).normalize();
        let hit = accel.intersect_ray(o, d, 0.0, 1e3).expect("the far wall");
        assert_eq!(hit.prim.index(), 0);
        assert!((hit.hit.t - 100.0).abs() < 1e-9, "{:?}", hit.hit);
        assert!(accel.blocked(o, d, 0.0, 1e3, |_| false));
    }
}

/// In a room's corner, a ray leaving the floor 1e-6 from the wall, towards it, meets the
/// wall 1.4e-6 on: the traversal enters boxes at any distance (obvhs's wide BVH enters none
/// nearer than 1e-4, and would let the ray through the wall). Rooms of size 1 and 1000,
/// straight and shadow rays.
#[test]
fn a_ray_leaving_a_floor_meets_the_wall_beside_it() {
    for size in [1.0, 1000.0] {
        let quad = |origin: DVec3, e1: DVec3, e2: DVec3| {
            Primitive::Quad(Quad {
                origin: origin * size,
                e1: e1 * size,
                e2: e2 * size,
            })
        };
        let room = vec![
            quad(DVec3::ZERO, DVec3::X, DVec3::Y),
            quad(DVec3::ZERO, DVec3::Y, DVec3::Z),
            quad(DVec3::X, DVec3::Y, DVec3::Z),
            quad(DVec3::ZERO, DVec3::X, DVec3::Z),
            quad(DVec3::Y, DVec3::X, DVec3::Z),
            quad(DVec3::Z, DVec3::X, DVec3::Y),
        ];
        let accel = Accel::new(room);
        let o = DVec3::new(1e-6, 0.5 * size, 0.0);
        let d = DVec3::new(-1.0, 0.0, 1.0).normalize();
        let hit = accel
            .intersect_ray(o, d, 1e-9, 10.0 * size)
            .expect("the wall");
        assert_eq!(hit.prim.index(), 1, "size {size}: {hit:?}");
        assert!((hit.hit.t - 2f64.sqrt() * 1e-6).abs() < 1e-15, "{hit:?}");
        assert!(accel.blocked(o, d, 1e-9, 10.0 * size, |_| false));
    }
}

/// A mesh of 12 000 small triangles scattered through a cube (its BVH's top built first,
/// then its subtrees in parallel) finds the nearest hit a loop over its triangles finds, one
/// `Primitive::triangle` each: straight rays the same distance bit for bit (the same f64
/// test on the same vertices, 200 rays), curved segments to 1e-12 of the arclength (67).
#[test]
fn a_large_mesh_equals_a_loop_over_its_triangles() {
    use grinlight::shapes::TriangleMesh;
    let mut rng = Pcg64Mcg::seed_from_u64(19);
    // Each triangle's corners within 0.06 of its first, which lies in the cube [-1, 1]³.
    let vertices: Vec<[f32; 3]> = (0..12_000)
        .flat_map(|_| {
            let a = rv(&mut rng);
            let (b, c) = (a + 0.06 * rv(&mut rng), a + 0.06 * rv(&mut rng));
            [a, b, c].map(|p| p.as_vec3().to_array())
        })
        .collect();
    let triangles: Vec<[u32; 3]> = (0..12_000u32)
        .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
        .collect();
    let f64_of = |i: u32| DVec3::from(vertices[i as usize].map(f64::from));
    let loose: Vec<Primitive> = triangles
        .iter()
        .map(|t| Primitive::triangle(f64_of(t[0]), f64_of(t[1]), f64_of(t[2])))
        .collect();
    let mesh = TriangleMesh::new(vertices.clone(), triangles, None, None).unwrap();
    let (mut straight, mut curved) = (0, 0);
    for case in 0..200 {
        let o = rv(&mut rng) * 0.9;
        let d = rv(&mut rng).normalize();
        let want = nearest_of(&loose, &|p| p.intersect_ray(o, d, 0.0, 10.0).map(|h| h.t));
        let got = mesh.intersect_ray(o, d, 0.0, 10.0).map(|h| h.t);
        assert_eq!(got, want.map(|(_, t)| t), "case {case}");
        straight += usize::from(got.is_some());
        if case % 3 != 0 {
            continue;
        }
        let seg = CurvedSegment::new(o, d, rv(&mut rng) * 3.0);
        let hull = seg.hull(1.5);
        let want = nearest_of(&loose, &|p| {
            p.intersect_segment(&seg, &hull, 0.0, 1.5).map(|h| h.t)
        });
        let got = mesh.intersect_segment(&seg, &hull, 0.0, 1.5).map(|h| h.t);
        match (got, want) {
            (Some(g), Some((_, w))) => {
                assert!((g - w).abs() <= 1e-12 * 1.5, "case {case}: {g} vs {w}");
                curved += 1;
            }
            (None, None) => {}
            other => panic!("case {case}: {other:?}"),
        }
    }
    assert!(
        straight > 100 && curved > 30,
        "{straight} straight, {curved} curved hits"
    );
}

/// A layered fiber's 60 coaxial tubes and their annular caps (which the accelerator takes out of
/// the BVH and searches by radius) give the same nearest hit as a loop over all primitives: for
/// rays starting inside the stack, a rounding error off a layer boundary (as after a
/// refraction), and outside it, straight and curved.
#[test]
fn coaxial_stack_equals_a_loop_over_all_primitives() {
    let mut rng = Pcg64Mcg::seed_from_u64(11);
    let (base, axis, height) = (DVec3::new(0.1, -0.2, -1.0), rv(&mut rng).normalize(), 2.0);
    let radii: Vec<f64> = (1..=60).map(|i| 0.5 * (i as f64 / 60.0).sqrt()).collect();
    let mut prims: Vec<Primitive> = primitives(&mut rng);
    for (i, &radius) in radii.iter().enumerate() {
        let inner = if i == 0 { 0.0 } else { radii[i - 1] };
        prims.push(Primitive::Tube {
            base,
            axis,
            radius,
            height,
        });
        for (center, normal) in [(base, -axis), (base + axis * height, axis)] {
            prims.push(Primitive::Disk(Disk {
                center,
                normal,
                radius,
                inner,
            }));
        }
    }
    let accel = Accel::new(prims.clone());
    let nearest = |f: &dyn Fn(&Primitive) -> Option<f64>| nearest_of(&prims, f);
    let frame = |h: f64, r: f64, phi: f64| {
        let u = axis.any_orthonormal_vector();
        let v = axis.cross(u);
        base + axis * h + (u * phi.cos() + v * phi.sin()) * r
    };
    let mut stack_hits = 0;
    for case in 0..3000 {
        let phi = rng.gen_range(0.0..std::f64::consts::TAU);
        let h = rng.gen_range(-0.5..height + 0.5);
        let o = match case % 3 {
            0 => frame(h, rng.gen_range(0.0..0.6), phi),
            1 => {
                let r = radii[rng.gen_range(0..radii.len())];
                frame(h, r * (1.0 + rng.gen_range(-1e-12..1e-12)), phi)
            }
            _ => rv(&mut rng) * 2.0,
        };
        let d = rv(&mut rng).normalize();
        let want = nearest(&|p| p.intersect_ray(o, d, 0.0, 10.0).map(|h| h.t));
        let got = accel
            .intersect_ray(o, d, 0.0, 10.0)
            .map(|b| (b.prim.index(), b.hit.t));
        assert_eq!(got, want, "case {case}");
        stack_hits += usize::from(want.is_some_and(|(i, _)| i >= 30));
        if case % 10 == 0 {
            let seg = CurvedSegment::new(o, d, rv(&mut rng) * 3.0);
            let want = nearest(&|p| {
                p.intersect_segment(&seg, &seg.hull(1.5), 0.0, 1.5)
                    .map(|h| h.t)
            });
            let got = accel.intersect_segment(&seg, &seg.hull(1.5), 0.0, 1.5);
            // The refinement stops at 1e-14 of its bracket (≤ the length 1.5), which depends on
            // the nearest hit found so far: allow 1e-12 of the length.
            match (got.map(|b| (b.prim.index(), b.hit.t)), want) {
                (Some((gi, gt)), Some((wi, wt))) => assert!(
                    gi == wi && (gt - wt).abs() <= 1e-12 * 1.5,
                    "segment case {case}: {got:?} vs {want:?}"
                ),
                (got, want) => assert_eq!(got, want, "segment case {case}"),
            }
        }
    }
    assert!(stack_hits > 1000, "{stack_hits} of 3000 rays hit the stack");
}

/// A compact mesh (`TriangleMesh`: f32 vertices shared by index, its own BVH) answers as its
/// triangles do one by one: a subdivided octahedron on the unit sphere (2 048 triangles,
/// vertices stored in f32) inside one `Primitive::Mesh`, against the same f32 vertices as
/// 2 048 f64 `Primitive::Triangle`s in the scene BVH. Straight rays: the same nearest hit,
/// distance and normal, bit for bit (the same f64 test on the same vertices). Curved
/// segments: the same hit to 1e-12 of the length (the root search refines on brackets that
/// depend on the nearest hit found so far), and a capsule the mesh culls holds no crossing.
#[test]
fn a_mesh_answers_as_its_triangles_do() {
    use grinlight::shapes::TriangleMesh;
    let tris = common::octahedral_sphere(4);
    assert_eq!(tris.len(), 2048);
    // Shared vertices, stored in f32.
    let mut vertices: Vec<[f32; 3]> = Vec::new();
    let mut index = |p: DVec3| {
        let v = p.as_vec3().to_array();
        match vertices.iter().position(|&w| w == v) {
            Some(i) => i as u32,
            None => {
                vertices.push(v);
                vertices.len() as u32 - 1
            }
        }
    };
    let triangles: Vec<[u32; 3]> = tris.iter().map(|t| t.map(&mut index)).collect();
    let f64_of = |i: u32| DVec3::from(vertices[i as usize].map(f64::from));
    let loose: Vec<Primitive> = triangles
        .iter()
        .map(|t| Primitive::triangle(f64_of(t[0]), f64_of(t[1]), f64_of(t[2])))
        .collect();
    assert_eq!(vertices.len(), 1026, "an octahedral sphere's vertex count");
    let mesh = TriangleMesh::new(vertices.clone(), triangles, None, None).unwrap();
    let one = Accel::new(vec![Primitive::Mesh(std::sync::Arc::new(mesh))]);
    let many = Accel::new(loose);
    let mut rng = Pcg64Mcg::seed_from_u64(11);
    let (mut hits, mut curved_hits, mut culled) = (0, 0, 0);
    for case in 0..1500 {
        let o = rv(&mut rng) * 1.6;
        let d = rv(&mut rng).normalize();
        let a = one.intersect_ray(o, d, 0.0, 10.0).map(|b| b.hit);
        // A loose triangle's (u, v) is worked out at the point: the mesh's, its corners'
        // weights.
        let b = many.intersect_ray(o, d, 0.0, 10.0).map(|b| Hit {
            uv: Some(many.primitive(b.prim).uv_at(o + b.hit.t * d)),
            ..b.hit
        });
        assert_eq!(a, b, "case {case}");
        hits += usize::from(a.is_some());
        let seg = CurvedSegment::new(o, d, rv(&mut rng) * 3.0);
        let hull = seg.hull(1.5);
        let a = one.intersect_segment(&seg, &hull, 0.0, 1.5).map(|b| b.hit);
        let b = many.intersect_segment(&seg, &hull, 0.0, 1.5).map(|b| b.hit);
        // The mesh culls with its nodes' boxes against the capsule (tighter than the boxes'
        // overlap the scene BVH uses): never a capsule that holds a crossing.
        if !one.may_hit(&hull) {
            assert!(b.is_none(), "case {case}: culled a crossing");
            culled += usize::from(many.may_hit(&hull));
        }
        match (a, b) {
            (Some(x), Some(y)) => {
                assert!(
                    (x.t - y.t).abs() <= 1e-12 * 1.5,
                    "case {case}: {} vs {}",
                    x.t,
                    y.t
                );
                assert!((x.normal - y.normal).length() < 1e-12, "case {case}");
                curved_hits += 1;
            }
            (None, None) => {}
            other => panic!("case {case}: {other:?}"),
        }
    }
    println!(
        "{hits} straight and {curved_hits} curved hits of 1500; {culled} capsules culled by the \
         mesh, not by the loose triangles' BVH"
    );
    assert!(hits > 250 && curved_hits > 250, "too few hits to compare");
}

/// A smooth mesh refracts as the surface it approximates: a glass ball (n = 1.5, radius 1)
/// as the analytic sphere, and as an octahedral sphere of 2 048 triangles given its exact
/// vertex normals (`vn`), faceted (`smooth = false`) and smooth, and without `vn` but with
/// shared vertices and `smooth = true` (normals computed from the faces). 400 rays from outside,
/// aimed within 0.9 of the centre; each one's refracted direction at its first hit against
/// the analytic sphere's. Faceted, the directions err by about the facets' tilt (measured
/// mean 1.3e-2 rad, worst 3.0e-2); smooth, by the shading normal's interpolation error,
/// O(edge²) (3.6e-4, 1.8e-3): the bar is a tenth of the faceted error, on the mean and the
/// worst ray. Normals computed with Max's weights equal the sphere's at its vertices, so they
/// do as well as the file's (area weights, tried first, erred by 2.8e-3 and 1.0e-2: first
/// order on this irregular mesh). Every smooth refraction must stay inside the ball (no leak
/// through the geometric surface).
#[test]
fn a_smooth_mesh_refracts_as_its_surface_does() {
    use grinlight::scene::load::parse_scene;
    use grinlight::transport::{Stats, Tracer};
    let dir = std::env::temp_dir().join(format!("grinlight-smooth-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("ball.obj"), common::sphere_obj(4, true)).unwrap();
    std::fs::write(dir.join("shared.obj"), common::sphere_obj(4, false)).unwrap();
    let scene_with = |shape: &str| {
        parse_scene(
            &dir.join("s.toml"),
            format!(
                "[[medium]]\nname = \"glass\"\nprofile = \"uniform\"\nn = 1.5\n\
                 [[material]]\nname = \"g\"\ntype = \"dielectric\"\ninterior = \"glass\"\n\
                 [[shape]]\n{shape}material = \"g\"\n"
            ),
        )
        .unwrap()
    };
    let scenes = [
        scene_with("type = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\n"),
        scene_with("type = \"mesh\"\nfile = \"ball.obj\"\nsmooth = false\n"),
        scene_with("type = \"mesh\"\nfile = \"ball.obj\"\n"),
        scene_with("type = \"mesh\"\nfile = \"shared.obj\"\nsmooth = true\n"),
    ];
    let refracted = |k: usize, o: DVec3, d: DVec3| {
        let (scene, settings) = &scenes[k];
        let tracer = Tracer::new(scene, &settings.trace);
        let mut stats = Stats::default();
        let hit = tracer
            .next_event(o, d, None, &mut stats)
            .surface_hit()
            .expect("the ray meets the ball");
        let b = tracer
            .vertex(hit, scene.surface(hit.prim), None)
            .and_then(|v| v.scatter((0.0, 0.0, 0.999)))
            .expect("a refraction");
        (b.ray.direction, b.ray.direction.dot(hit.normals.geometric))
    };
    let mut rng = Pcg64Mcg::seed_from_u64(3);
    let (mut flat, mut smooth, mut computed) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..400 {
        let o = rv(&mut rng).normalize() * 3.0;
        let target = rv(&mut rng) * 0.9 / 3f64.sqrt();
        let d = (target - o).normalize();
        let (exact, _) = refracted(0, o, d);
        let (f, _) = refracted(1, o, d);
        let (s, into) = refracted(2, o, d);
        let (c, into_c) = refracted(3, o, d);
        assert!(
            into < 0.0 && into_c < 0.0,
            "a smooth refraction leaves the ball"
        );
        flat.push(f.angle_between(exact));
        smooth.push(s.angle_between(exact));
        computed.push(c.angle_between(exact));
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let worst = |v: &[f64]| v.iter().cloned().fold(0.0, f64::max);
    println!(
        "refraction error (rad): faceted mean {:.2e} worst {:.2e}; smooth mean {:.2e} worst \
         {:.2e}; computed normals mean {:.2e} worst {:.2e}",
        mean(&flat),
        worst(&flat),
        mean(&smooth),
        worst(&smooth),
        mean(&computed),
        worst(&computed)
    );
    for v in [&smooth, &computed] {
        assert!(mean(v) < 0.1 * mean(&flat) && worst(v) < 0.1 * worst(&flat));
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// `may_meet_ball` never rules out a ball the surface enters: for 2 000 random balls around
/// each of the random primitives, every hit within the ball of 400 rays from its centre finds
/// it true. And it rules out what it can: a sphere's surface exactly (balls inside it or
/// beyond it), a planar primitive's by its plane.
#[test]
fn may_meet_ball_holds_every_ball_the_surface_enters() {
    let mut rng = Pcg64Mcg::seed_from_u64(17);
    let prims = primitives(&mut rng);
    let mut entered = 0;
    for p in &prims {
        for _ in 0..2000 {
            let (centre, radius) = (rv(&mut rng) * 1.5, rng.gen_range(0.01..0.5));
            let meets = p.may_meet_ball(centre, radius);
            for _ in 0..400 {
                let d = rv(&mut rng).normalize();
                if let Some(hit) = p.intersect_ray(centre, d, 0.0, radius) {
                    assert!(meets, "{p:?}: hit at {} within {radius} of {centre}", hit.t);
                    entered += 1;
                    break;
                }
            }
        }
    }
    assert!(entered > 1000, "{entered}");
    let sphere = Primitive::Sphere {
        center: DVec3::ZERO,
        radius: 1.0,
    };
    assert!(!sphere.may_meet_ball(DVec3::new(0.0, 0.5, 0.0), 0.4));
    assert!(!sphere.may_meet_ball(DVec3::new(0.0, 1.5, 0.0), 0.4));
    assert!(sphere.may_meet_ball(DVec3::new(0.0, 1.3, 0.0), 0.4));
    let floor = Primitive::Quad(Quad {
        origin: DVec3::new(-1.0, 0.0, -1.0),
        e1: DVec3::new(0.0, 0.0, 2.0),
        e2: DVec3::new(2.0, 0.0, 0.0),
    });
    assert!(!floor.may_meet_ball(DVec3::new(0.0, 0.5, 0.0), 0.4));
    assert!(floor.may_meet_ball(DVec3::new(0.0, 0.3, 0.0), 0.4));
}
