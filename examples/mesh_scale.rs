//! Meshes at scale: a Luneburg lens bounded by a triangulated sphere (a cube sphere: six
//! faces of N × N cells, two triangles a cell, written as a binary PLY) against the analytic
//! sphere of `scenes/luneburg.toml`, rendered at 200 × 150. For each size: PLY load and BVH
//! build time, the mesh's bytes per triangle (vertices, indices, BVH), the process's resident
//! memory per triangle after the scene is built and at its peak (each size runs in a process
//! of its own, so peaks do not carry over), and the render time against the analytic lens's.
//!
//! First, the time to read the same meshes from an OBJ and from a binary PLY file.
//!
//! `-- --one N` runs one size (the cube sphere of N cells a face; with `--ico`, the icosphere
//! split N times; with `--obj`, read from an OBJ instead of a binary PLY) and prints its
//! fields; `-- --build N` times the cube sphere's construction alone (its checks, BVH and
//! empty core; median of 7); `-- --analytic` renders the analytic lens once and prints its
//! time. `bench/mesh_build.sh` alternates builds with these.
//!
//! `cargo run --release --example mesh_scale` (sizes 1.2·10⁴, 1.3·10⁵, 1.3·10⁶ and 10⁷
//! triangles; the PLY files go to out/, 10⁷ triangles ≈ 0.2 GB) or `-- --sizes 30,330`.

use grinlight::scene::load::parse_scene;
use grinlight::scene::mesh::{load_triangles, ObjTriangles};
use grinlight::scene::ply::load_ply;
use grinlight::shapes::{Primitive, TriangleMesh};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The cube sphere of radius `radius` with `n` × `n` cells a face: vertices, and triangles
/// (0-based) winding counter-clockwise seen from outside (outward normals).
fn cube_sphere(n: usize, radius: f64) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let faces: [([f64; 3], [f64; 3], [f64; 3]); 6] = [
        ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
        ([-1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]),
        ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
        ([0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
        ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        ([0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]),
    ];
    let (mut vertices, mut triangles) = (Vec::new(), Vec::new());
    for (f, (c, u, v)) in faces.iter().enumerate() {
        for j in 0..=n {
            for i in 0..=n {
                let (a, b) = (
                    2.0 * i as f64 / n as f64 - 1.0,
                    2.0 * j as f64 / n as f64 - 1.0,
                );
                let p: Vec<f64> = (0..3).map(|k| c[k] + a * u[k] + b * v[k]).collect();
                let len = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
                vertices.push([0, 1, 2].map(|k| (radius * p[k] / len) as f32));
            }
        }
        // u × v = c on every face above, so (i, j) → (i + 1, j) → (i + 1, j + 1) turns
        // counter-clockwise seen from outside.
        let base = f * (n + 1) * (n + 1);
        let at = |i: usize, j: usize| (base + j * (n + 1) + i) as u32;
        for j in 0..n {
            for i in 0..n {
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                triangles.push([a, b, c]);
                triangles.push([a, c, d]);
            }
        }
    }
    (vertices, triangles)
}

/// The icosphere of radius `radius`: an icosahedron's faces split `k` times into four
/// (20·4ᵏ triangles), every vertex pushed out to the sphere; counter-clockwise seen from
/// outside.
fn icosphere(k: usize, radius: f64) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut points: Vec<[f64; 3]> = vec![
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ];
    let mut triangles: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    let unit = |p: [f64; 3]| {
        let l = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        p.map(|c| c / l)
    };
    for p in &mut points {
        *p = unit(*p);
    }
    for _ in 0..k {
        let mut middle = std::collections::HashMap::new();
        let mut split = |a: u32, b: u32, points: &mut Vec<[f64; 3]>| {
            *middle.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let (p, q) = (points[a as usize], points[b as usize]);
                points.push(unit([0, 1, 2].map(|i| p[i] + q[i])));
                points.len() as u32 - 1
            })
        };
        triangles = triangles
            .iter()
            .flat_map(|&[a, b, c]| {
                let (ab, bc, ca) = (
                    split(a, b, &mut points),
                    split(b, c, &mut points),
                    split(c, a, &mut points),
                );
                [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
            })
            .collect();
    }
    let vertices = points
        .iter()
        .map(|p| p.map(|c| (radius * c) as f32))
        .collect();
    (vertices, triangles)
}

/// Writes the cube sphere of radius `radius` with `n` × `n` cells a face to `path` as an OBJ
/// (or, for a path ending in .ply, a binary little-endian PLY); returns its triangles.
fn write_cube_sphere(path: &Path, n: usize, radius: f64) -> std::io::Result<usize> {
    write_mesh(path, cube_sphere(n, radius))
}

/// Writes `mesh` (vertices, triangles) to `path` as an OBJ (or, for a path ending in .ply,
/// a binary little-endian PLY); returns its triangles.
fn write_mesh(
    path: &Path,
    (vertices, triangles): (Vec<[f32; 3]>, Vec<[u32; 3]>),
) -> std::io::Result<usize> {
    let mut out = std::io::BufWriter::new(std::fs::File::create(path)?);
    if path.extension().is_some_and(|e| e == "ply") {
        write!(
            out,
            "ply\nformat binary_little_endian 1.0\nelement vertex {}\nproperty float x\n\
             property float y\nproperty float z\nelement face {}\n\
             property list uchar int vertex_indices\nend_header\n",
            vertices.len(),
            triangles.len()
        )?;
        for v in &vertices {
            for c in v {
                out.write_all(&c.to_le_bytes())?;
            }
        }
        for t in &triangles {
            out.write_all(&[3])?;
            for i in t {
                out.write_all(&(*i as i32).to_le_bytes())?;
            }
        }
    } else {
        for v in &vertices {
            writeln!(out, "v {} {} {}", v[0], v[1], v[2])?;
        }
        for t in &triangles {
            writeln!(out, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1)?;
        }
    }
    out.flush()?;
    Ok(triangles.len())
}

/// The time to read the cube sphere of `n` cells a face from an OBJ and from a binary PLY
/// (the readers alone, median of 3), as a table row.
fn read_times(n: usize) -> String {
    std::fs::create_dir_all("out").unwrap();
    let time = |path: &Path, read: &dyn Fn(&Path) -> Result<ObjTriangles, String>| {
        median(
            (0..3)
                .map(|_| {
                    let t = Instant::now();
                    std::hint::black_box(read(path).expect("reads"));
                    t.elapsed().as_secs_f64()
                })
                .collect(),
        )
    };
    let (obj, ply) = (
        PathBuf::from(format!("out/mesh_read_{n}.obj")),
        PathBuf::from(format!("out/mesh_read_{n}.ply")),
    );
    let triangles = write_cube_sphere(&obj, n, 0.5).expect("write the OBJ");
    write_cube_sphere(&ply, n, 0.5).expect("write the PLY");
    let row = format!(
        "| {:.3e} | {:.3} | {:.3} |",
        triangles as f64,
        time(&obj, &|p| load_triangles(p)),
        time(&ply, &|p| load_ply(p))
    );
    std::fs::remove_file(&obj).ok();
    std::fs::remove_file(&ply).ok();
    row
}

/// A field of /proc/self/status in bytes (VmRSS, VmHWM).
fn status_bytes(field: &str) -> f64 {
    let text = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    text.lines()
        .find(|l| l.starts_with(field))
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|kb| kb.parse::<f64>().ok())
        .map_or(f64::NAN, |kb| kb * 1024.0)
}

/// The Luneburg scene at 200 × 150 with its lens bounded by `mesh` (None: the analytic sphere).
fn scene_text(mesh: Option<&Path>) -> String {
    let text = std::fs::read_to_string("scenes/luneburg.toml").expect("run from the repository");
    let text = text.replace("width = 400\nheight = 300", "width = 200\nheight = 150");
    match mesh {
        None => text,
        Some(path) => text.replace(
            "type = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 0.5\nmaterial = \"luneburg\"",
            &format!(
                "type = \"mesh\"\nfile = \"{}\"\nmaterial = \"luneburg\"",
                path.display()
            ),
        ),
    }
}

/// Which sphere bounds the lens.
#[derive(Clone, Copy)]
enum Sphere {
    /// A cube sphere of N × N cells a face (12 N² triangles).
    Cube(usize),
    /// An icosphere split N times (20·4ᴺ triangles).
    Ico(usize),
}

impl Sphere {
    /// From the command line: `N`, or `N --ico`.
    fn from_args(args: &[String], n: usize) -> Self {
        match args.iter().any(|a| a == "--ico") {
            true => Sphere::Ico(n),
            false => Sphere::Cube(n),
        }
    }

    fn mesh(self, radius: f64) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
        match self {
            Sphere::Cube(n) => cube_sphere(n, radius),
            Sphere::Ico(k) => icosphere(k, radius),
        }
    }

    fn name(self) -> String {
        match self {
            Sphere::Cube(n) => format!("cube{n}"),
            Sphere::Ico(k) => format!("ico{k}"),
        }
    }
}

/// One size, in this process: prints a table row's fields as `key=value` lines. The file
/// (binary PLY, or OBJ with `obj`) is written by a process of its own first, so that this
/// one's peak memory is the load's and the render's.
fn one(sphere: Sphere, obj: bool) {
    std::fs::create_dir_all("out").unwrap();
    let name = format!(
        "out/mesh_scale_{}.{}",
        sphere.name(),
        if obj { "obj" } else { "ply" }
    );
    let file = std::env::current_dir().unwrap().join(name);
    let mut write = std::process::Command::new(std::env::current_exe().unwrap());
    write.args(["--write", &file.display().to_string()]);
    match sphere {
        Sphere::Cube(n) => write.arg(n.to_string()),
        Sphere::Ico(k) => write.args([k.to_string(), "--ico".into()]),
    };
    assert!(
        write.status().expect("run the writer").success(),
        "write the mesh"
    );
    let triangles = match sphere {
        Sphere::Cube(n) => 12 * n * n,
        Sphere::Ico(k) => 20 << (2 * k),
    };
    let rss0 = status_bytes("VmRSS:");
    let t = Instant::now();
    let (scene, settings) = parse_scene(Path::new("scenes/luneburg.toml"), scene_text(Some(&file)))
        .expect("the mesh scene parses");
    let load = t.elapsed().as_secs_f64();
    let rss1 = status_bytes("VmRSS:");
    let bytes = scene
        .accel
        .primitives()
        .iter()
        .find_map(|p| match p {
            Primitive::Mesh(m) => Some(m.bytes()),
            _ => None,
        })
        .expect("a mesh");
    let t = Instant::now();
    grinlight::render::render(&scene, &settings, &()).expect("render");
    let render = t.elapsed().as_secs_f64();
    let peak = status_bytes("VmHWM:");
    let tri = triangles as f64;
    println!("triangles={triangles}");
    println!("load={load}");
    println!("mesh_bytes={}", bytes as f64 / tri);
    println!("rss={}", (rss1 - rss0) / tri);
    println!("peak={}", peak / tri);
    println!("render={render}");
    std::fs::remove_file(&file).ok();
}

/// The analytic lens's render time (s).
fn analytic_render() -> f64 {
    let (scene, settings) =
        parse_scene(Path::new("scenes/luneburg.toml"), scene_text(None)).unwrap();
    let t = Instant::now();
    grinlight::render::render(&scene, &settings, &()).unwrap();
    t.elapsed().as_secs_f64()
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if let Some(i) = args.iter().position(|a| a == "--one") {
        let n = args[i + 1].parse().expect("--one N");
        one(
            Sphere::from_args(&args, n),
            args.iter().any(|a| a == "--obj"),
        );
        return;
    }
    if let Some(i) = args.iter().position(|a| a == "--write") {
        let n = args[i + 2].parse().expect("--write PATH N");
        write_mesh(
            Path::new(&args[i + 1]),
            Sphere::from_args(&args, n).mesh(0.5),
        )
        .expect("write the mesh");
        return;
    }
    if let Some(i) = args.iter().position(|a| a == "--build") {
        let n = args[i + 1].parse().expect("--build N");
        let (vertices, triangles) = cube_sphere(n, 0.5);
        let times = (0..7)
            .map(|_| {
                let (v, t) = (vertices.clone(), triangles.clone());
                let start = Instant::now();
                std::hint::black_box(TriangleMesh::new(v, t, None, None).expect("a mesh"));
                start.elapsed().as_secs_f64()
            })
            .collect();
        println!("build={}", median(times));
        return;
    }
    if args.iter().any(|a| a == "--analytic") {
        println!("render={}", analytic_render());
        return;
    }
    let sizes: Vec<usize> = args
        .iter()
        .position(|a| a == "--sizes")
        .map(|i| {
            args[i + 1]
                .split(',')
                .map(|s| s.parse().expect("--sizes N,N,…"))
                .collect()
        })
        .unwrap_or_else(|| vec![32, 104, 330, 913]);
    let analytic = median((0..3).map(|_| analytic_render()).collect());
    println!("Reading the cube sphere's file (the reader alone, median of 3):\n");
    println!("| triangles | OBJ (s) | binary PLY (s) |\n|---|---|---|");
    for &n in &sizes {
        println!("{}", read_times(n));
    }
    println!("\nanalytic sphere: render {analytic:.2} s (200 × 150, median of 3)\n");
    println!("| triangles | PLY load + BVH (s) | mesh bytes/triangle | RSS after build, bytes/triangle | peak RSS, bytes/triangle | render (s) | render / analytic |");
    println!("|---|---|---|---|---|---|---|");
    let exe = std::env::current_exe().unwrap();
    for n in sizes {
        let out = std::process::Command::new(&exe)
            .args(["--one", &n.to_string()])
            .output()
            .expect("run one size");
        let text = String::from_utf8_lossy(&out.stdout);
        let field = |k: &str| -> f64 {
            text.lines()
                .find_map(|l| l.strip_prefix(&format!("{k}=")))
                .and_then(|v| v.parse().ok())
                .unwrap_or(f64::NAN)
        };
        if !out.status.success() {
            println!(
                "| N = {n}: failed: {} |",
                String::from_utf8_lossy(&out.stderr).trim()
            );
            continue;
        }
        println!(
            "| {:.3e} | {:.2} | {:.1} | {:.1} | {:.1} | {:.2} | {:.2}× |",
            field("triangles"),
            field("load"),
            field("mesh_bytes"),
            field("rss"),
            field("peak"),
            field("render"),
            field("render") / analytic
        );
    }
}
