pub mod agreement;
pub mod bigarc;
pub mod chi2;
pub mod quadrature;

use glam::DVec3;

/// The white spherical room of the integrating-sphere furnaces: a Lambertian sphere of
/// radius 1 and albedo `rho` about the origin, the camera at its centre looking toward
/// `look_at` (100° vertical field, 32 × 24), 8 passes of 16 samples and 10⁵ photons of each
/// kind a pass; its lights are the caller's.
pub fn white_spherical_room(rho: f64, look_at: [f64; 3]) -> String {
    let [x, y, z] = look_at;
    format!(
        "[[material]]\nname = \"wall\"\ntype = \"diffuse\"\nalbedo = [{rho}, {rho}, {rho}]\n\
         [[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"wall\"\n\
         [camera]\nposition = [0, 0, 0]\nlook_at = [{x}, {y}, {z}]\nfov_y_deg = 100\n\
         width = 32\nheight = 24\n[render]\nspp = 16\npasses = 8\nphotons = 100000\n\
         caustic_photons = 100000\n"
    )
}

/// An octahedral sphere of radius 1: the octahedron's faces split in four `k` times and
/// projected on the sphere (8·4^k triangles), wound counter-clockwise seen from outside.
pub fn octahedral_sphere(k: usize) -> Vec<[DVec3; 3]> {
    let mut tris: Vec<[DVec3; 3]> = Vec::new();
    for &sx in &[-1.0, 1.0] {
        for &sy in &[-1.0, 1.0] {
            for &sz in &[-1.0, 1.0] {
                let (a, b, c) = (DVec3::X * sx, DVec3::Y * sy, DVec3::Z * sz);
                let flip = (b - a).cross(c - a).dot(a + b + c) < 0.0;
                tris.push(if flip { [a, c, b] } else { [a, b, c] });
            }
        }
    }
    for _ in 0..k {
        tris = tris
            .iter()
            .flat_map(|&[a, b, c]| {
                let (ab, bc, ca) = (
                    (a + b).normalize(),
                    (b + c).normalize(),
                    (c + a).normalize(),
                );
                [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
            })
            .collect();
    }
    tris
}

/// [`octahedral_sphere`] as OBJ text, with its exact sphere normals as `vn` when `normals`,
/// else with its vertices shared by the triangles that meet there (so that normals computed
/// from the faces are smooth).
pub fn sphere_obj(k: usize, normals: bool) -> String {
    let tris = octahedral_sphere(k);
    let mut text = String::new();
    if normals {
        for t in &tris {
            for p in t {
                text += &format!("v {} {} {}\nvn {} {} {}\n", p.x, p.y, p.z, p.x, p.y, p.z);
            }
        }
        for i in 0..tris.len() {
            let (a, b, c) = (3 * i + 1, 3 * i + 2, 3 * i + 3);
            text += &format!("f {a}//{a} {b}//{b} {c}//{c}\n");
        }
        return text;
    }
    let mut vertices: Vec<DVec3> = Vec::new();
    let mut faces = String::new();
    for t in &tris {
        let ids = t.map(|p| match vertices.iter().position(|&q| q == p) {
            Some(i) => i + 1,
            None => {
                vertices.push(p);
                vertices.len()
            }
        });
        faces += &format!("f {} {} {}\n", ids[0], ids[1], ids[2]);
    }
    for p in &vertices {
        text += &format!("v {} {} {}\n", p.x, p.y, p.z);
    }
    text + &faces
}

/// The mean of `values` and its standard error (their spread over √n).
pub fn mean_and_error(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}
