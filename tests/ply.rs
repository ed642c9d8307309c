//! PLY meshes: the same mesh written as OBJ and as PLY (ASCII, binary little and big endian,
//! with properties and elements the reader must read past) gives the same triangles, and a
//! damaged PLY file is an error naming the element and record; Mitsuba's serialized meshes read
//! as Mitsuba reads them.

use grinlight::scene::mesh::load_triangles;
use grinlight::scene::ply::load_ply;
use std::path::{Path, PathBuf};

/// An octahedron whose top half is triangles and whose bottom is one square and four
/// triangles (a square face is fanned), with normals.
const VERTICES: [[f32; 3]; 6] = [
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [-1.0, 0.0, 0.0],
    [0.0, -1.0, 0.0],
    [0.0, 0.0, 1.5],
    [0.25, -0.5, -1.0],
];
const FACES: [&[u32]; 6] = [
    &[0, 1, 4],
    &[1, 2, 4],
    &[2, 3, 4],
    &[3, 0, 4],
    &[0, 3, 2, 1],
    &[0, 5, 3],
];

fn normal(v: [f32; 3]) -> [f32; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|c| c / l)
}

fn obj_text() -> String {
    let mut s = String::new();
    for v in VERTICES {
        s += &format!("v {} {} {}\n", v[0], v[1], v[2]);
    }
    for f in FACES {
        let corners: Vec<String> = f.iter().map(|i| (i + 1).to_string()).collect();
        s += &format!("f {}\n", corners.join(" "));
    }
    s
}

/// The PLY header of the mesh in `format`: vertices with a colour between position and
/// normal, faces with a flag before their index list, and an `edge` element after them.
fn ply_header(format: &str) -> String {
    format!(
        "ply\nformat {format} 1.0\ncomment written by the test\nelement vertex 6\nproperty float \
         x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\n\
         property uchar blue\nproperty double nx\nproperty double ny\nproperty double nz\n\
         element face 6\nproperty int flags\nproperty list uchar int vertex_indices\nelement \
         edge 2\nproperty int vertex1\nproperty int vertex2\nend_header\n"
    )
}

fn ply_ascii() -> Vec<u8> {
    let mut s = ply_header("ascii");
    for v in VERTICES {
        let n = normal(v);
        s += &format!(
            "{} {} {} 200 100 50 {} {} {}\n",
            v[0], v[1], v[2], n[0], n[1], n[2]
        );
    }
    for f in FACES {
        let corners: Vec<String> = f.iter().map(|i| i.to_string()).collect();
        s += &format!("7 {} {}\n", f.len(), corners.join(" "));
    }
    s += "0 1\n1 2\n";
    s.into_bytes()
}

fn ply_binary(big: bool) -> Vec<u8> {
    let format = if big {
        "binary_big_endian"
    } else {
        "binary_little_endian"
    };
    let mut out = ply_header(format).into_bytes();
    let mut put = |bytes: &[u8]| {
        let mut b = bytes.to_vec();
        if big {
            b.reverse();
        }
        out.extend_from_slice(&b);
    };
    for v in VERTICES {
        for c in v {
            put(&c.to_le_bytes());
        }
        for c in [200u8, 100, 50] {
            put(&[c]);
        }
        for c in normal(v) {
            put(&f64::from(c).to_le_bytes());
        }
    }
    for f in FACES {
        put(&7i32.to_le_bytes());
        put(&[f.len() as u8]);
        for &i in f {
            put(&(i as i32).to_le_bytes());
        }
    }
    for (a, b) in [(0i32, 1i32), (1, 2)] {
        put(&a.to_le_bytes());
        put(&b.to_le_bytes());
    }
    out
}

/// A file of `bytes` in the test's own directory.
fn file(name: &str, bytes: &[u8]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("grinlight-ply-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

/// Every PLY form gives the OBJ's positions and triangles (the square fanned from its first
/// corner, as the OBJ reader does), and the normals the file gives; the colours, the face
/// flags and the edges are read past.
#[test]
fn ply_in_every_format_reads_as_the_same_obj() {
    let obj = load_triangles(&file("octahedron.obj", obj_text().as_bytes())).unwrap();
    assert_eq!(obj.triangles.len(), 7);
    for (name, bytes) in [
        ("ascii.ply", ply_ascii()),
        ("little.ply", ply_binary(false)),
        ("big.ply", ply_binary(true)),
    ] {
        let ply = load_ply(&file(name, &bytes)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(ply.positions, obj.positions, "{name}");
        assert_eq!(ply.triangles, obj.triangles, "{name}");
        let normals = ply.normals.expect("the file gives normals");
        for (n, v) in normals.iter().zip(VERTICES) {
            let want = normal(v);
            assert!(
                (0..3).all(|k| (n[k] - want[k]).abs() < 1e-7),
                "{name}: {n:?}"
            );
        }
        assert!(ply.texcoords.is_none());
    }
}

/// A gzip-compressed PLY file (`.ply.gz`, as pbrt's scenes ship them) reads as the PLY does,
/// alone and as a scene's mesh; damaged compressed data is an error naming the file.
#[test]
fn a_gzipped_ply_file_reads_as_the_ply() {
    use std::io::Write;
    let plain = ply_binary(false);
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    gz.write_all(&plain).unwrap();
    let path = file("little.ply.gz", &gz.finish().unwrap());
    let (a, b) = (
        load_ply(&path).unwrap(),
        load_ply(&file("plain.ply", &plain)).unwrap(),
    );
    assert_eq!((a.positions, a.triangles), (b.positions, b.triangles));
    assert_eq!(
        mesh_triangles(&format!("file = \"{}\"\n", path.display())),
        Ok(7)
    );
    let e = load_ply(&file("broken.ply.gz", &[0x1f, 0x8b, 8, 0, 1, 2]))
        .err()
        .unwrap();
    assert!(
        e.contains("broken.ply.gz: the gzip-compressed data is damaged"),
        "{e}"
    );
}

/// The number of triangles of the one mesh of a scene of a diffuse material and a `mesh`
/// shape with the keys `mesh` (or the scene's error).
fn mesh_triangles(mesh: &str) -> Result<usize, String> {
    let text = format!(
        "[[material]]\nname = \"m\"\ntype = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]\n\n\
         [[shape]]\ntype = \"mesh\"\nmaterial = \"m\"\n{mesh}"
    );
    let (scene, _) = grinlight::scene::load::parse_scene(Path::new("mesh.toml"), text)
        .map_err(|e| e.to_string())?;
    Ok(scene
        .accel
        .primitives()
        .iter()
        .find_map(|p| match p {
            grinlight::shapes::Primitive::Mesh(m) => Some(m.len()),
            _ => None,
        })
        .expect("a mesh"))
}

/// A scene's mesh may be a PLY file: it loads as the OBJ does.
#[test]
fn a_scene_mesh_may_be_a_ply_file() {
    let ply = file("scene_mesh.ply", &ply_binary(false));
    assert_eq!(
        mesh_triangles(&format!("file = \"{}\"\n", ply.display())),
        Ok(7)
    );
}

/// Damaged files are errors that name the file and where: data that ends early (the record
/// it ends in), a list count or a corner that is negative or not a whole number, a vertex,
/// normal or texture coordinate that is not finite, a face of two corners, a vertex line with
/// a number too many, a header without `end_header` or with an unknown type, a count of
/// records the file cannot hold.
#[test]
fn a_damaged_ply_file_is_an_error_naming_where() {
    let good = ply_binary(false);
    let cut = good.len() - 20;
    let ascii = String::from_utf8(ply_ascii()).unwrap();
    let cases: [(&str, Vec<u8>, &str); 11] = [
        (
            "cut.ply",
            good[..cut].to_vec(),
            "face 6: the data ends early",
        ),
        (
            "index.ply",
            ascii.replace("7 3 0 5 3", "7 3 0 9 3").into_bytes(),
            "face 6: corner 9 names no vertex (the file has 6)",
        ),
        (
            "nan.ply",
            ascii.replacen("1 0 0 200", "nan 0 0 200", 1).into_bytes(),
            "vertex 1: a position that is not three finite numbers",
        ),
        (
            "two.ply",
            ascii.replace("7 3 0 5 3", "7 2 0 5").into_bytes(),
            "face 6: a face of fewer than three corners",
        ),
        (
            "count.ply",
            ascii.replace("7 3 0 5 3", "7 -3 0 5 3").into_bytes(),
            "face 6: its list `vertex_indices` is said to hold -3 items: not a count",
        ),
        (
            "fraction.ply",
            ascii.replace("7 3 0 5 3", "7 3 0 4.5 3").into_bytes(),
            "face 6: corner 4.5 names no vertex",
        ),
        (
            "normal.ply",
            ascii
                .replacen("200 100 50 1 0 0", "200 100 50 inf 0 0", 1)
                .into_bytes(),
            "a normal or texture coordinate that is not finite",
        ),
        (
            // A count no file could hold is not trusted with memory.
            "huge.ply",
            ply_header("binary_little_endian")
                .replace("element vertex 6", "element vertex 999999999999999")
                .bytes()
                .chain(
                    good[ply_header("binary_little_endian").len()..]
                        .iter()
                        .copied(),
                )
                .collect(),
            "the data ends early",
        ),
        (
            "header.ply",
            ascii.replace("end_header", "end").into_bytes(),
            "not a PLY file: no `end_header`",
        ),
        (
            // A vertex line with a number too many: named, not read as the next record.
            "extra.ply",
            ascii
                .replacen("200 100 50 1 0 0", "200 100 50 1 0 0 0.6", 1)
                .into_bytes(),
            "vertex 1: 1 more number(s) on its line than the header's properties of `vertex`",
        ),
        (
            "type.ply",
            ascii
                .replace("property uchar red", "property colour red")
                .into_bytes(),
            "header line 8: an unknown type (`property colour red`)",
        ),
    ];
    for (name, bytes, want) in cases {
        let path = file(name, &bytes);
        let err = load_ply(&path)
            .err()
            .unwrap_or_else(|| panic!("{name} loaded"));
        assert!(
            err.contains(want) && err.contains(&path.display().to_string()),
            "{name}: {err}"
        );
    }
}

/// What a header may hold that is not data: a comment that says `end_header` (only a line of
/// its own ends the header), and an element of no properties however many records it claims
/// (it holds no bytes: a trillion of them read in no time, as nothing).
#[test]
fn a_comment_and_an_element_of_no_properties_are_read_past() {
    let ascii = String::from_utf8(ply_ascii()).unwrap();
    let want = load_ply(&file("plain.ply", ascii.as_bytes())).unwrap();
    for (name, text) in [
        (
            "comment.ply",
            ascii.replacen("ply\n", "ply\ncomment a header ends at end_header\n", 1),
        ),
        (
            "junk.ply",
            ascii.replacen("end_header", "element junk 1000000000000\nend_header", 1),
        ),
    ] {
        let start = std::time::Instant::now();
        let got = load_ply(&file(name, text.as_bytes())).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(got.triangles, want.triangles, "{name}");
        assert!(start.elapsed().as_secs_f64() < 1.0, "{name}");
    }
}

/// Mitsuba's serialized meshes: the fixtures `bench/mitsuba_serialized.py` wrote and checked
/// that Mitsuba 3.9.1 reads as meant (versions 4 and 3, two meshes each: a tetrahedron in f32
/// with normals and texture coordinates, a quad in f64 with vertex colours to read past) read
/// as the same meshes; a damaged file or a mesh the file lacks is an error naming it.
#[test]
fn mitsuba_serialized_meshes_read_as_mitsuba_reads_them() {
    use grinlight::scene::serialized::{load_serialized, parse};
    let tetra: Vec<[f32; 3]> = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ]
    .map(|p: [f32; 3]| [0.5 * p[0] + 0.25, 0.5 * p[1] - 0.5, 0.5 * p[2] + 1.0])
    .to_vec();
    let quad: Vec<[f32; 3]> = [
        [-1.0, 0.0, -1.0],
        [1.0, 0.0, -1.0],
        [1.0, 0.0, 1.0],
        [-1.0, 0.0, 1.0],
    ]
    .map(|p: [f32; 3]| p.map(|c| 1.5 * c))
    .to_vec();
    for version in [4, 3] {
        let path = PathBuf::from(format!("tests/data/mitsuba/meshes_v{version}.serialized"));
        let m = load_serialized(&path, 0).unwrap();
        assert_eq!(m.positions, tetra, "v{version}");
        assert_eq!(m.triangles, [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]);
        assert_eq!(
            m.texcoords.unwrap(),
            [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.5, 0.5]]
        );
        assert_eq!(m.normals.unwrap()[0], [-1.0, -1.0, -1.0]);
        let m = load_serialized(&path, 1).unwrap();
        assert_eq!(m.positions, quad, "v{version}");
        assert_eq!(m.triangles, [[0, 2, 1], [0, 3, 2]]);
        assert!(m.normals.is_none() && m.texcoords.is_none());
        let e = load_serialized(&path, 2).err().unwrap();
        assert!(e.contains("mesh 2: the file holds 2"), "{e}");
    }
    let good = std::fs::read("tests/data/mitsuba/meshes_v4.serialized").unwrap();
    let mut wrong = good.clone();
    wrong[0] = 0;
    for (bytes, words) in [
        (wrong, "not a Mitsuba serialized mesh"),
        (
            good[..40].to_vec(),
            "the positions: the compressed data ends early",
        ),
        (b"\x1c\x04\x07\x00".to_vec(), "version 7"),
    ] {
        let e = parse(&bytes, 0).err().unwrap();
        assert!(e.contains(words), "{e}");
    }
}

/// A scene's mesh may be a mesh of a Mitsuba serialized file, picked by `shape_index`;
/// `shape_index` on another file is refused.
#[test]
fn a_scene_mesh_may_be_a_mesh_of_a_serialized_file() {
    let serialized = std::fs::canonicalize("tests/data/mitsuba/meshes_v4.serialized").unwrap();
    let with =
        |extra: &str| mesh_triangles(&format!("file = \"{}\"\n{extra}", serialized.display()));
    assert_eq!(with(""), Ok(4));
    assert_eq!(with("shape_index = 1\n"), Ok(2));
    let e = with("shape_index = 5\n").err().unwrap();
    assert!(e.contains("mesh 5: the file holds 2"), "{e}");
    let obj = file("serialized_obj.obj", obj_text().as_bytes());
    let e = mesh_triangles(&format!("file = \"{}\"\nshape_index = 1\n", obj.display()))
        .err()
        .unwrap();
    assert!(
        e.contains("shape_index picks a mesh of a Mitsuba .serialized file"),
        "{e}"
    );
}
