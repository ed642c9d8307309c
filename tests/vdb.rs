//! OpenVDB volumes as `grid` media: `tests/data/plume.vdb`, written by
//! OpenVDB 10.0.1 itself (`tests/data/make_plume_vdb.py`; Blosc-compressed float grids over
//! two root nodes, a vec3 grid), loads and its values match the field it was written from;
//! malformed or missing files and wrong keys are file:line:col errors, never a panic.

use glam::DVec3;
use grinlight::media::{GridQuantity, GLADSTONE_DALE_AIR, STANDARD_PRESSURE};
use grinlight::scene::load::parse_scene;
use grinlight::scene::vdb;
use std::path::Path;

const PLUME: &str = "tests/data/plume.vdb";

/// The fixture's index space: voxel (i, j, k) at (0.3, 0.1, −0.2) + 0.05·(i, j, k), the box
/// i ∈ −3..=8, j ∈ 0..=9, k ∈ 0..=7.
fn world(i: i32, j: i32, k: i32) -> DVec3 {
    DVec3::new(0.3, 0.1, -0.2) + 0.05 * DVec3::new(i as f64, j as f64, k as f64)
}

fn temperature(i: i32, j: i32, k: i32) -> f64 {
    let q = (i * i + (j - 4) * (j - 4) + (k - 3) * (k - 3)) as f64;
    300.0 + 40.0 * (-q / 16.0).exp()
}

/// Every voxel of the box as the script wrote it: the active ones their value rounded to f32
/// (the file holds floats; Python's and Rust's exp may differ in the last f64 bit, which moves
/// the f32 by at most one unit: 3e-5 K here), the inactive ones (T < 300.5 K) the background.
#[test]
fn a_vdb_grid_loads_with_its_voxels_and_place() {
    let t = vdb::read(Path::new(PLUME), Some("temperature"), Some(300.0)).unwrap();
    assert_eq!(t.dims, [12, 10, 8]);
    assert!(
        (t.min - world(-3, 0, 0)).abs().max_element() < 1e-12,
        "{}",
        t.min
    );
    assert!(
        (t.max - world(8, 9, 7)).abs().max_element() < 1e-12,
        "{}",
        t.max
    );
    let (mut active, mut inactive) = (0, 0);
    for (n, v) in t.values.iter().enumerate() {
        let (i, j, k) = (n % 12, n / 12 % 10, n / 120);
        let want = temperature(i as i32 - 3, j as i32, k as i32);
        if want >= 300.5 {
            active += 1;
            assert!(
                (v - want as f32 as f64).abs() <= 3e-5,
                "({i},{j},{k}): {v} vs {want}"
            );
        } else {
            inactive += 1;
            assert_eq!(*v, 300.0, "({i},{j},{k})");
        }
    }
    assert!(
        active > 800 && inactive > 50,
        "{active} active, {inactive} inactive"
    );
    // The density grid is active everywhere: no background needed; found by name.
    let d = vdb::read(Path::new(PLUME), Some("density"), None).unwrap();
    for (n, v) in d.values.iter().enumerate() {
        let (i, j, k) = (
            (n % 12) as f64 - 3.0,
            (n / 12 % 10) as f64,
            (n / 120) as f64,
        );
        assert_eq!(*v, (1.2 - 0.001 * (i + 2.0 * j + 3.0 * k)) as f32 as f64);
    }
}

/// In a scene: `file = "plume.vdb"` with `grid`, `background` and `quantity = "temperature"`
/// gives air's index at every voxel (the ideal gas and Gladstone–Dale, as for text grids).
#[test]
fn a_vdb_temperature_grid_is_a_medium_of_air() {
    let scene = format!(
        "ambient = \"plume\"\n[[medium]]\nname = \"plume\"\nprofile = \"grid\"\nfile = \"{}\"\n\
         grid = \"temperature\"\nbackground = 300\nquantity = \"temperature\"\ninterpolation = \"cubic\"\n",
        std::fs::canonicalize(PLUME).unwrap().display()
    );
    let (scene, settings) = parse_scene(Path::new("plume.toml"), scene).unwrap();
    let tracer = grinlight::transport::Tracer::new(&scene, &settings.trace);
    let air = GridQuantity::Temperature {
        pressure: STANDARD_PRESSURE,
        gladstone_dale: GLADSTONE_DALE_AIR,
    };
    for (i, j, k) in [(0, 4, 3), (2, 5, 1), (-3, 0, 0), (8, 9, 7)] {
        let want = temperature(i, j, k);
        let stored = if want >= 300.5 {
            want as f32 as f64
        } else {
            300.0
        };
        let n = tracer
            .index(Some(grinlight::ids::MediumId::new(0)), world(i, j, k))
            .unwrap();
        let expected = air.index(stored).unwrap();
        // Cubic interpolation reproduces the nodes to rounding (1e-15 of n).
        assert!(
            (n - expected).abs() < 1e-12,
            "({i},{j},{k}): {n} vs {expected}"
        );
    }
}

/// A heterogeneous medium's density from a VDB grid (`density_file`, `density_grid`): at every
/// voxel it is the stored value, and it scales σa (absorption) and σs alike.
#[test]
fn a_vdb_density_grid_scales_the_medium_coefficients() {
    let scene = format!(
        "ambient = \"smoke\"\n[[medium]]\nname = \"smoke\"\nprofile = \"uniform\"\nn = 1\n\
         scattering = 2\nabsorption = 0.5\ndensity_file = \"{}\"\ndensity_grid = \"density\"\n",
        std::fs::canonicalize(PLUME).unwrap().display()
    );
    let (scene, settings) = parse_scene(Path::new("smoke.toml"), scene).unwrap();
    let tracer = grinlight::transport::Tracer::new(&scene, &settings.trace);
    let density = scene
        .media()
        .scattering(grinlight::ids::MediumId::new(0))
        .unwrap()
        .density
        .clone()
        .unwrap();
    for (i, j, k) in [(0, 4, 3), (2, 5, 1), (-3, 0, 0), (8, 9, 7)] {
        let stored = (1.2 - 0.001 * (i + 2 * j + 3 * k) as f64) as f32 as f64;
        let p = world(i, j, k);
        // Trilinear interpolation reproduces the nodes to rounding.
        assert!((density.at(p) - stored).abs() < 1e-12, "({i},{j},{k})");
        let sigma_a = tracer
            .participating(grinlight::ids::MediumId::new(0))
            .sigma_a(p);
        assert!(
            (sigma_a.x - 0.5 * stored).abs() < 1e-12,
            "({i},{j},{k}): σa {sigma_a}"
        );
    }
}

/// Wrong or damaged input ends in an error naming the scene file, line and key and the VDB
/// file and what is wrong — never a panic.
#[test]
fn bad_vdb_input_is_a_clear_error() {
    let dir = std::env::temp_dir().join(format!("grinlight-vdb-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bytes = std::fs::read(PLUME).unwrap();
    std::fs::write(dir.join("plume.vdb"), &bytes).unwrap();
    std::fs::write(dir.join("half.vdb"), &bytes[..bytes.len() / 2]).unwrap();
    std::fs::write(dir.join("text.vdb"), "not a volume\n").unwrap();
    let mut header_only = bytes[..64].to_vec();
    header_only.extend(std::iter::repeat_n(0xAB, 256));
    std::fs::write(dir.join("garbage.vdb"), header_only).unwrap();
    let medium = |keys: &str| {
        let path = dir.join("s.toml");
        let text =
            format!("ambient = \"p\"\n[[medium]]\nname = \"p\"\nprofile = \"grid\"\n{keys}\n");
        std::fs::write(&path, &text).unwrap();
        grinlight::scene::load::load_scene(&path)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default()
    };
    let cases = [
        ("file = \"gone.vdb\"", "gone.vdb: cannot read"),
        ("file = \"text.vdb\"", "not a VDB file"),
        ("file = \"half.vdb\"\ngrid = \"density\"", "half.vdb"),
        ("file = \"garbage.vdb\"\ngrid = \"density\"", "garbage.vdb"),
        ("file = \"plume.vdb\"", "name the grid to read with `grid`"),
        ("file = \"plume.vdb\"\ngrid = \"pressure\"", "has no grid 'pressure' (it has 'density'"),
        ("file = \"plume.vdb\"\ngrid = \"velocity\"", "is a Tree_vec3s_5_4_3"),
        ("file = \"plume.vdb\"\ngrid = \"temperature\"", "give `background`"),
        (
            "file = \"plume.vdb\"\ngrid = \"density\"\ndims = [2, 2, 2]",
            "leave out `bounds`, `dims` and `values`",
        ),
        (
            "file = \"plume.vdb\"\ngrid = \"temperature\"\nquantity = \"temperature\"\nbackground = -4",
            "key `background`: -4: -4 is not a temperature",
        ),
    ];
    for (keys, want) in cases {
        let e = medium(keys);
        assert!(e.contains(want), "{keys}: {e:?} lacks {want:?}");
        assert!(e.contains("s.toml:"), "{keys}: {e} names no scene line");
    }
    // A density's background below zero is the background's fault, not the file's.
    let path = dir.join("d.toml");
    std::fs::write(
        &path,
        "[[medium]]\nname = \"fog\"\nprofile = \"uniform\"\nn = 1\nscattering = 1\n\
         density_file = \"plume.vdb\"\ndensity_grid = \"temperature\"\n\
         density_background = -1\n",
    )
    .unwrap();
    let e = grinlight::scene::load::load_scene(&path)
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("key `density_background`"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A Mitsuba `.vol` grid as a medium's `density_file` (the smoke of
/// `scenes/mitsuba/smoke_box.xml`): its 12 × 10 × 8 values are the density at the nodes
/// `density_bounds` spans; `density_dims` or `density_values` beside it, and a damaged file,
/// are errors naming the key.
#[test]
fn a_mitsuba_volume_is_a_density_grid() {
    use grinlight::scene::vol;
    let vol_path = std::fs::canonicalize("scenes/mitsuba/smoke.vol").unwrap();
    let (dims, values) = vol::read(&vol_path).unwrap();
    assert_eq!(dims, [12, 10, 8]);
    let dir = std::env::temp_dir().join(format!("grinlight-vol-scene-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = |extra: &str, file: &Path| {
        format!(
            "ambient = \"smoke\"\n[[light]]\ntype = \"point\"\nposition = [0, 2, 0]\n\
             intensity = [1, 1, 1]\n[[medium]]\nname = \"smoke\"\nprofile = \"uniform\"\nn = 1\n\
             scattering = 0.5\ndensity_bounds = [[-1, -1, -1], [1, 1, 1]]\n\
             density_file = \"{}\"\n{extra}",
            file.display()
        )
    };
    let (s, _) = parse_scene(&dir.join("s.toml"), scene("", &vol_path)).unwrap();
    let smoke = s.ambient().unwrap();
    let density = s
        .media()
        .scattering(smoke)
        .unwrap()
        .density
        .clone()
        .unwrap();
    // Node (i, j, k) at −1 + 2 (i, j, k)/(dims − 1): the file's value there.
    for (i, j, k) in [(0, 0, 0), (11, 9, 7), (5, 3, 2), (7, 8, 1)] {
        let p = DVec3::new(
            -1.0 + 2.0 * i as f64 / 11.0,
            -1.0 + 2.0 * j as f64 / 9.0,
            -1.0 + 2.0 * k as f64 / 7.0,
        );
        let want = values[(k * 10 + j) * 12 + i];
        assert!((density.at(p) - want).abs() < 1e-12, "({i}, {j}, {k})");
    }
    let refused = |text: String, words: &str| {
        let Err(e) = parse_scene(&dir.join("s.toml"), text) else {
            panic!("read: {words}")
        };
        let e = e.to_string();
        assert!(e.contains(words), "{e}");
    };
    refused(
        scene("density_dims = [12, 10, 8]\n", &vol_path),
        "a Mitsuba .vol file gives the grid's values and their count",
    );
    let bad = dir.join("bad.vol");
    std::fs::write(&bad, &std::fs::read(&vol_path).unwrap()[..1000]).unwrap();
    refused(
        scene("", &bad),
        "bytes of values where 12 × 10 × 8 f32 values take 3840",
    );
    // A file of one value along x, and one holding a NaN: errors naming the file's key.
    let header = |dims: [i32; 3]| {
        let mut b = b"VOL\x03".to_vec();
        for n in [1, dims[0], dims[1], dims[2], 1] {
            b.extend(n.to_le_bytes());
        }
        b.extend(
            [0f32, 0.0, 0.0, 1.0, 1.0, 1.0]
                .iter()
                .flat_map(|x| x.to_le_bytes()),
        );
        b
    };
    for (dims, values, words) in [
        (
            [1, 2, 2],
            [1f32; 4].to_vec(),
            "key `density_file`: dims must be at least 2",
        ),
        (
            [2, 2, 2],
            vec![1.0, f32::NAN, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0],
            "key `density_file`: value #1 is NaN",
        ),
    ] {
        let mut b = header(dims);
        b.extend(values.iter().flat_map(|x| x.to_le_bytes()));
        std::fs::write(&bad, b).unwrap();
        refused(scene("", &bad), words);
    }
    std::fs::remove_dir_all(&dir).ok();
}
