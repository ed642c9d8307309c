//! Photon mapping and the render against exact answers and an independent reference.

use glam::DVec3;
use grinlight::compare::{mean_ratios, read_exr_layer, MeanRatios};
use grinlight::photon::{shoot, Batch, Photons, Sources};
use grinlight::scene::load::parse_scene;
use grinlight::transport::Tracer;
use std::f64::consts::PI;
use std::path::Path;

fn render(
    (scene, settings): &(grinlight::scene::Scene, grinlight::settings::Settings),
    threads: usize,
) -> grinlight::film::Film {
    let settings = grinlight::settings::Settings {
        threads,
        ..settings.clone()
    };
    grinlight::render::render(scene, &settings, &()).unwrap().0
}

/// A black (albedo 0) disk of radius R at distance h below a source: photons are stored at
/// their first hit only, so the stored flux is the flux onto the disk. Point light of
/// intensity I: I·2π(1 − cos θ), tan θ = R/h; a sphere light of radiance L and radius a, all
/// of it above the disk's plane: the same with I = π L a². LED of power P with I ∝ cos^m θ (a 1 µm disk,
/// facing the receiver): P(1 − cos^{m+1} θ). An octahedral mesh lamp: Lambert's polygon
/// formula over the faces each point of the disk sees, integrated over the disk. Binomial noise of 2·10⁵ photons with a hit
/// fraction f ≥ 0.2 is ≤ 0.5 % relative; tolerance 2 %.
#[test]
fn photon_flux_onto_a_disk_matches_the_closed_form() {
    let (r, h) = (1.0f64, 1.5f64);
    let cos_t = h / (r * r + h * h).sqrt();
    let receiver = "[[material]]\nname = \"black\"\ntype = \"diffuse\"\nalbedo = [0, 0, 0]\n\
        [[shape]]\ntype = \"disk\"\ncenter = [0, 0, 0]\nnormal = [0, 1, 0]\nradius = 1.0\nmaterial = \"black\"\n";
    let m = 2.0;
    let cases = [
        (
            "[[light]]\ntype = \"point\"\nposition = [0, 1.5, 0]\nintensity = [1, 2, 3]\n",
            [1.0, 2.0, 3.0].map(|i| i * 2.0 * PI * (1.0 - cos_t)),
        ),
        // A Lambertian sphere of radiance L and radius a lights every point that sees all of
        // it as a point of intensity π L a² at its centre does.
        (
            "[[light]]\ntype = \"sphere\"\ncenter = [0, 1.5, 0]\nradius = 0.2\nradiance = [1, 2, 3]\n",
            [1.0, 2.0, 3.0].map(|l| PI * l * 0.04 * 2.0 * PI * (1.0 - cos_t)),
        ),
        (
            "[[light]]\ntype = \"led\"\ncenter = [0, 1.5, 0]\nnormal = [0, -1, 0]\nradius = 1e-6\npower = 0.5\nm = 2.0\n",
            [0.5 * (1.0 - cos_t.powf(m + 1.0)); 3],
        ),
    ];
    let octahedron = octahedral_lamp(DVec3::new(0.0, 1.5, 0.0), 0.2);
    let mesh_flux = octahedron.flux_onto_disk(r);
    let mesh = (
        octahedron.light("[1, 2, 3]"),
        [1.0, 2.0, 3.0].map(|l| l * mesh_flux),
    );
    for (light, want) in cases.into_iter().chain([(mesh.0.as_str(), mesh.1)]) {
        let (scene, settings) =
            parse_scene(Path::new("flux.toml"), format!("{receiver}{light}")).unwrap();
        let tracer = Tracer::new(&scene, &settings.trace);
        let sources = Sources::new(&tracer);
        let photons = Photons::all(Batch::Global, 0, 0, 200_000);
        let (sink, stats) = shoot(&tracer, &sources, photons, &|| false);
        let photons = sink.photons.photons();
        assert_eq!(stats.photons_emitted, 200_000);
        let sum = photons.iter().fold([0.0f64; 3], |acc, p| {
            [0, 1, 2].map(|c| acc[c] + p.power[c] as f64)
        });
        for c in 0..3 {
            assert!(
                (sum[c] / want[c] - 1.0).abs() < 0.02,
                "{light}: channel {c}: {} vs {}",
                sum[c],
                want[c]
            );
        }
    }
}

/// A regular octahedron of triangles wound outward, an emitting mesh.
struct OctahedralLamp {
    corners: [DVec3; 6],
    faces: Vec<[usize; 3]>,
}

/// The octahedron of corners `center` ± `a` along each axis.
fn octahedral_lamp(center: DVec3, a: f64) -> OctahedralLamp {
    let corners = [
        DVec3::X,
        -DVec3::X,
        DVec3::Y,
        -DVec3::Y,
        DVec3::Z,
        -DVec3::Z,
    ]
    .map(|d| center + a * d);
    let mut faces = Vec::new();
    for x in [0, 1] {
        for y in [2, 3] {
            for z in [4, 5] {
                let [p, q, r] = [x, y, z].map(|i| corners[i]);
                let outward = (q - p).cross(r - p).dot(p + q + r - 3.0 * center) > 0.0;
                faces.push(match outward {
                    true => [x, y, z],
                    false => [x, z, y],
                });
            }
        }
    }
    OctahedralLamp { corners, faces }
}

impl OctahedralLamp {
    /// Its `[[light]]` of `radiance`, given inline.
    fn light(&self, radiance: &str) -> String {
        let points: Vec<String> = (self.corners.iter())
            .map(|c| format!("{}, {}, {}", c.x, c.y, c.z))
            .collect();
        let indices: Vec<String> = (self.faces.iter())
            .map(|f| format!("{}, {}, {}", f[0], f[1], f[2]))
            .collect();
        format!(
            "[[light]]\ntype = \"mesh\"\npoints = [{}]\nindices = [{}]\nradiance = {radiance}\n",
            points.join(", "),
            indices.join(", ")
        )
    }

    /// The irradiance per unit radiance at `x` on a surface of unit normal `m`: Lambert's
    /// polygon formula (Arvo 1995), (1/2) Σ Θᵢ m·(rᵢ × rᵢ₊₁)/|rᵢ × rᵢ₊₁|, summed over
    /// the faces that face `x` (of a convex emitter, the ones it sees, none hiding another).
    fn irradiance(&self, x: DVec3, m: DVec3) -> f64 {
        let mut e = 0.0;
        for f in &self.faces {
            let [a, b, c] = f.map(|i| self.corners[i]);
            if (b - a).cross(c - a).dot(x - a) <= 0.0 {
                continue;
            }
            for (p, q) in [(a, b), (b, c), (c, a)] {
                let (u, v) = (p - x, q - x);
                e += 0.5 * u.angle_between(v) * m.dot(u.cross(v).normalize());
            }
        }
        e.abs()
    }

    /// The flux per unit radiance onto the disk of radius `r` about the origin facing +y: its
    /// irradiance integrated on a 400 × 400 polar midpoint grid (7e-7 from a 1600 × 1600 one's).
    fn flux_onto_disk(&self, r: f64) -> f64 {
        let n = 400;
        let mut flux = 0.0;
        for i in 0..n {
            let rho = r * (i as f64 + 0.5) / n as f64;
            for j in 0..n {
                let phi = std::f64::consts::TAU * (j as f64 + 0.5) / n as f64;
                let x = DVec3::new(rho * phi.cos(), 0.0, rho * phi.sin());
                flux += self.irradiance(x, DVec3::Y) * rho;
            }
        }
        flux * (r / n as f64) * (std::f64::consts::TAU / n as f64)
    }
}

/// `scenes/cornell_diffuse.toml` against the independent Mitsuba reference (16384 spp), at
/// 128 × 128 (the reference averaged over 2 × 2 pixels). The render is deterministic (fixed
/// seed); its noise with 64 stratified samples per pixel and 4·10⁵ photons is ~0.3 % of a
/// block's mean away from the emitter and ~1 % on the blocks holding the emitter's edge.
/// The photon estimate's own bias is largest in the room's corners (the k-nearest disk
/// reaches past the wall's edge): ~2 % there, measured. Bars: mean ratio
/// within 1 %, every 16 × 16 block within 3 %.
#[test]
fn cornell_diffuse_matches_the_reference() {
    let mut scene = grinlight::scene::load_scene(Path::new("scenes/cornell_diffuse.toml")).unwrap();
    scene.1.spp = 64;
    scene.1.photons.gather = 2;
    scene.1.photons.global = 400_000;
    let camera = scene.0.camera.as_mut().unwrap();
    (camera.width, camera.height) = (128, 128);
    let film = render(&scene, 0);
    let reference = read_exr_layer(Path::new("refs/cornell_diffuse.reference.exr"), None).unwrap();
    let reference = reference.downsample(reference.width / 128).pixels;
    let MeanRatios { overall, blocks } =
        mean_ratios(&film.layer("beauty").unwrap(), &reference, 128, 16);
    let worst = blocks.iter().map(|r| (r - 1.0).abs()).fold(0.0, f64::max);
    println!("mean ratio {overall:.4}, worst block {worst:.4}");
    assert!((overall - 1.0).abs() < 0.01, "mean ratio {overall}");
    assert_eq!(blocks.len(), 64);
    assert!(worst < 0.03, "a block is off by {worst}: {blocks:?}");
    // The components add up, and each is finite and non-negative.
    let [beauty, direct, caustic, secondary, emitted] =
        ["beauty", "direct", "caustic", "secondary", "emitted"].map(|n| film.layer(n).unwrap());
    for i in 0..128 * 128 {
        for c in 0..3 {
            let parts = [&direct, &caustic, &secondary, &emitted].map(|l| l[i][c]);
            assert!(parts.iter().all(|v| v.is_finite() && *v >= 0.0));
            let sum: f32 = parts.iter().sum();
            assert!((beauty[i][c] - sum).abs() <= 1e-5 * sum.max(1.0));
        }
    }
}

/// The same seed gives the same EXR with 1 and 2 threads, with both photon maps, two
/// progressive passes and a curved (GRIN) object in view.
#[test]
fn one_and_two_threads_write_the_same_exr() {
    let mut scene = grinlight::scene::load_scene(Path::new("scenes/cornell_caustic.toml")).unwrap();
    scene.1.spp = 2;
    scene.1.passes = 2;
    scene.1.photons.global = 20_000;
    scene.1.photons.caustic = 20_000;
    scene.1.photons.gather = 2;
    let camera = scene.0.camera.as_mut().unwrap();
    (camera.width, camera.height) = (40, 30);
    let dir = std::env::temp_dir().join(format!("grinlight-det-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut bytes = Vec::new();
    for threads in [1, 2] {
        let path = dir.join(format!("t{threads}.exr"));
        render(&scene, threads).write_exr(&path).unwrap();
        bytes.push(std::fs::read(&path).unwrap());
    }
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(bytes[0] == bytes[1], "the EXR depends on the thread count");
    let luneburg = grinlight::scene::load_scene(Path::new("scenes/luneburg.toml")).unwrap();
    let mut small = luneburg;
    small.1.spp = 1;
    small.1.photons.global = 5_000;
    small.1.photons.caustic = 5_000;
    let camera = small.0.camera.as_mut().unwrap();
    (camera.width, camera.height) = (24, 18);
    let (a, b) = (render(&small, 1), render(&small, 2));
    assert!(
        a.planes() == b.planes(),
        "the Luneburg render depends on the thread count"
    );
    // A dispersive scene: hero wavelengths drawn from the samples' streams, photons of one
    // wavelength each.
    let mut rainbow = grinlight::scene::load_scene(Path::new("scenes/rainbow.toml")).unwrap();
    rainbow.1.spp = 1;
    rainbow.1.passes = 1;
    rainbow.1.photons.caustic = 20_000;
    let camera = rainbow.0.camera.as_mut().unwrap();
    (camera.width, camera.height) = (24, 12);
    let (a, b) = (render(&rainbow, 1), render(&rainbow, 2));
    assert!(
        a.planes() == b.planes(),
        "the rainbow render depends on the thread count"
    );
}

/// A closed diffuse sphere (albedo a) whose inside emits radiance Le uniformly — here a
/// point light at the centre of intensity I, which gives every inner point the irradiance
/// of a uniform emitter, E₀ = I/R² — reaches L = (a/π)·E₀/(1 − a) in total: direct a E₀/π
/// plus secondary a² E₀/(π(1 − a)) (the inside of a sphere sees itself, so each bounce adds
/// a uniform irradiance a·E). Camera at the centre; with 2·10⁵ photons and 32 gather rays
/// per sample the image mean is within 1 % of the total (noise ~0.3 %), tolerance 2 %.
#[test]
fn furnace_sphere_reaches_the_analytic_radiance() {
    let (a, i, r) = (0.5f64, 3.0f64, 2.0f64);
    let text = format!(
        "[camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, -1]\nfov_y_deg = 60\nwidth = 16\nheight = 16\n\
         [render]\nspp = 4\ngather = 32\nphotons = 200000\n\
         [[material]]\nname = \"grey\"\ntype = \"diffuse\"\nalbedo = [{a}, {a}, {a}]\n\
         [[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = {r}\nmaterial = \"grey\"\n\
         [[light]]\ntype = \"point\"\nposition = [0, 0, 0.0]\nintensity = [{i}, {i}, {i}]\n"
    );
    let scene = parse_scene(Path::new("furnace.toml"), text).unwrap();
    let film = render(&scene, 0);
    let e0 = i / (r * r);
    let mean = |n: &str| {
        film.layer(n)
            .unwrap()
            .iter()
            .map(|p| p[0] as f64)
            .sum::<f64>()
            / 256.0
    };
    let (direct, secondary, beauty) = (mean("direct"), mean("secondary"), mean("beauty"));
    println!("direct {direct:.5}, secondary {secondary:.5}, beauty {beauty:.5}");
    let want_direct = a * e0 / PI;
    let want_total = want_direct / (1.0 - a);
    // Direct light from a point light is exact per sample; the film holds f32 (ε ≈ 6e-8).
    assert!(
        (direct / want_direct - 1.0).abs() < 1e-6,
        "direct {direct} vs {want_direct}"
    );
    assert!(
        (beauty / want_total - 1.0).abs() < 0.02,
        "total {beauty} vs {want_total}"
    );
}

use crate::common;

/// A meshed lens renders as the analytic one: `scenes/luneburg.toml` at 96 × 72 with its lens
/// as the analytic sphere and as a smooth 2 048-triangle octahedral sphere (the file's exact
/// normals, scaled to R = 0.5). The mesh's render must differ from the analytic one no more
/// than two analytic renders of different seeds differ from each other: over 8 × 8-pixel
/// blocks, the RMS of the relative difference (mesh, seed 1) − (sphere, seed 0) within 1.25×
/// that of (sphere, seed 1) − (sphere, seed 0) (measured 0.124 against 0.125), and the whole
/// image's mean within 0.5 % of the sphere's at the same seed, where the noise largely cancels
/// (measured 0.22 %; between seeds the mean moves by ~1 %).
#[test]
fn a_tessellated_luneburg_lens_renders_as_the_analytic_one() {
    let dir = std::env::temp_dir().join(format!("grinlight-lens-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("ball.obj"), common::sphere_obj(4, true)).unwrap();
    let text = std::fs::read_to_string("scenes/luneburg.toml")
        .unwrap()
        .replace("width = 400\nheight = 300", "width = 96\nheight = 72");
    let mesh = text.replace(
        "type = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 0.5\nmaterial = \"luneburg\"",
        "type = \"mesh\"\nfile = \"ball.obj\"\nscale = 0.5\nmaterial = \"luneburg\"",
    );
    assert_ne!(mesh, text, "the lens's shape was replaced");
    let beauty = |text: &str, seed: u64| {
        let (scene, mut settings) = parse_scene(&dir.join("lens.toml"), text.to_string()).unwrap();
        settings.seed = seed;
        render(&(scene, settings), 0).layer("beauty").unwrap()
    };
    let reference = beauty(&text, 0);
    let rms = |img: &[[f32; 3]]| {
        let MeanRatios { overall, blocks } = mean_ratios(img, &reference, 96, 8);
        let r =
            (blocks.iter().map(|b| (b - 1.0).powi(2)).sum::<f64>() / blocks.len() as f64).sqrt();
        (overall, r)
    };
    let (noise_mean, noise) = rms(&beauty(&text, 1));
    let (mesh_mean, tessellated) = rms(&beauty(&mesh, 1));
    let same_seed = mesh_mean / noise_mean;
    println!(
        "block RMS against the analytic lens (seed 0): analytic seed 1 {noise:.4} (mean ratio \
         {noise_mean:.4}), mesh seed 1 {tessellated:.4} (mean ratio {mesh_mean:.4}); mesh / \
         sphere at seed 1: {same_seed:.4}"
    );
    assert!(
        tessellated <= 1.25 * noise,
        "{tessellated} vs noise {noise}"
    );
    assert!((same_seed - 1.0).abs() < 0.005, "{same_seed}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Image textures: an 8 × 8 sRGB PNG whose quadrants are red, green / blue, 50 % grey (top row
/// first) on a quad that fills a 64 × 64 view, u along its first edge and v along its second
/// (bottom to top), and on the same square as an OBJ mesh with those (u, v) as its `vt`. The
/// albedo layer at the quadrants' centres (u, v = ¼ or ¾) must be their
/// linear values (sRGB 128 → 0.2158) to 1e-6: there the bilinear lookup and a pixel's jitter
/// see one colour — also through an OBJ whose v counts from the top (`v_from_top`, and
/// `flip_v` with it); and a one-colour JPEG its colour. Also a 2 × 1 texture's lookup against its definition, wrapped and between
/// texel centres (1e-12), and finite for a NaN (u, v).
#[test]
fn textures_put_their_texels_where_the_surface_coordinates_say() {
    use grinlight::texture::{srgb_decode, Texture};
    let grey = srgb_decode(128.0 / 255.0) as f64;
    assert!((grey - 0.2158).abs() < 1e-4, "{grey}");
    let t = Texture::from_texels(2, 1, vec![[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]]);
    for (u, want) in [
        (0.25, 0.0),
        (0.75, 1.0),
        (0.5, 0.5),
        (1.25, 0.0),
        (-0.25, 1.0),
        (0.0, 0.5),
    ] {
        let got = t.at(glam::DVec2::new(u, 0.5)).0.x;
        assert!((got - want).abs() < 1e-12, "u {u}: {got} vs {want}");
    }
    assert!(
        t.at(glam::DVec2::NAN).0.is_finite(),
        "a NaN (u, v) reads a texel"
    );
    let dir = std::env::temp_dir().join(format!("grinlight-tex-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let texels: [[u8; 3]; 4] = [[255, 0, 0], [0, 255, 0], [0, 0, 255], [128, 128, 128]];
    let img = image::RgbImage::from_fn(8, 8, |x, y| {
        image::Rgb(texels[(y / 4 * 2 + x / 4) as usize])
    });
    img.save(dir.join("t.png")).unwrap();
    let text = "[[material]]\nname = \"t\"\ntype = \"diffuse\"\ntexture = \"t.png\"\n\
                [[shape]]\ntype = \"quad\"\nvertices = [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]\nmaterial = \"t\"\n\
                [[light]]\ntype = \"environment\"\nsky = \"checker\"\n\
                [camera]\nposition = [0, 0, 2]\nlook_at = [0, 0, 0]\nfov_y_deg = 53.13010235415598\nwidth = 64\nheight = 64\n\
                [render]\nspp = 4\nphotons = 1000\ncaustic_photons = 0\ngather = 0\n";
    // The same square as an OBJ mesh whose `vt` give its corners the quad's (u, v).
    std::fs::write(
        dir.join("sq.obj"),
        "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
         f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n",
    )
    .unwrap();
    let mesh = text.replace(
        "type = \"quad\"\nvertices = [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]",
        "type = \"mesh\"\nfile = \"sq.obj\"",
    );
    assert_ne!(mesh, text, "the quad was replaced");
    // The same (u, v) from a file whose v counts from the image's top row down (a Mitsuba PLY's
    // or serialized mesh's), read as such; and from one whose v the reading turns over (a
    // Mitsuba OBJ's `flip_tex_coords`) and then counts from the top.
    std::fs::write(
        dir.join("top.obj"),
        "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 1\nvt 1 1\nvt 1 0\nvt 0 0\n\
         f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n",
    )
    .unwrap();
    let from_top = mesh.replace("file = \"sq.obj\"", "file = \"top.obj\"\nv_from_top = true");
    let flipped = mesh.replace(
        "file = \"sq.obj\"",
        "file = \"sq.obj\"\nflip_v = true\nv_from_top = true",
    );
    let linear = |c: [u8; 3]| c.map(|v| srgb_decode(v as f32 / 255.0));
    for (shape, text) in [
        ("quad", text),
        ("mesh", mesh.as_str()),
        ("mesh, v from the top", from_top.as_str()),
        ("mesh, v flipped and from the top", flipped.as_str()),
    ] {
        let scene = parse_scene(&dir.join("s.toml"), text.to_string()).unwrap();
        let albedo = render(&scene, 0).layer("albedo").unwrap();
        // Quadrant (i, j) from the top-left is centred at u = (i + ½)/2, v = 1 − (j + ½)/2:
        // pixel (64 u, 64 (1 − v)) from the top-left.
        for (k, &texel) in texels.iter().enumerate() {
            let (i, j) = (k % 2, k / 2);
            let (x, y) = (16 + 32 * i, 16 + 32 * j);
            let got = albedo[y * 64 + x];
            let want = linear(texel);
            println!("{shape} texel ({i}, {j}): albedo {got:?}, texel {want:?}");
            for c in 0..3 {
                assert!(
                    (got[c] - want[c]).abs() < 1e-6,
                    "{shape} ({i}, {j}): {got:?} vs {want:?}"
                );
            }
        }
    }
    // A JPEG texture of one colour: its decoded texel (JPEG stores a flat block's colour to
    // within a level of 255 after the colour transform; bar 2 levels, in sRGB).
    let colour = [200u8, 120, 40];
    image::RgbImage::from_pixel(16, 16, image::Rgb(colour))
        .save(dir.join("t.jpg"))
        .unwrap();
    let jpeg = text.replace("texture = \"t.png\"", "texture = \"t.jpg\"");
    let scene = parse_scene(&dir.join("s.toml"), jpeg).unwrap();
    let got = render(&scene, 0).layer("albedo").unwrap()[32 * 64 + 32];
    for c in 0..3 {
        let level = grinlight::color::srgb_encode(got[c]) * 255.0;
        assert!(
            (level - colour[c] as f32).abs() <= 2.0,
            "JPEG texel {got:?}: sRGB level {level} vs {}",
            colour[c]
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A Gaussian pixel filter weighs the film around each pixel as it says at the image's edge:
/// a white square fills the view exactly (nothing beyond it), so a pixel's albedo is the
/// share of the filter that falls on the image. pbrt's filter (σ ½, r 1.5, beyond the image)
/// gives a pixel in the first column the share ∫ f over [−½, 1.5] / ∫ f over [−1.5, 1.5]
/// (by a midpoint sum of f here, not the renderer's closed form), and the corner pixel its
/// square; Mitsuba's (inside the image only) gives 1 everywhere, exactly. A sample's albedo
/// is 0 or 1: with 4096 samples along the column's 16 middle pixels its standard error is
/// at most √(¼/4096) ≈ 0.008 (independent samples; stratified ones scatter less), bar 0.03;
/// the corner's 256 samples at most 0.031, bar 0.1.
#[test]
fn a_gaussian_filter_weighs_the_film_beyond_the_image_only_when_asked() {
    let (sigma, radius) = (0.5f64, 1.5f64);
    let f = |x: f64| {
        ((-x * x / (2.0 * sigma * sigma)).exp() - (-radius * radius / (2.0 * sigma * sigma)).exp())
            .max(0.0)
    };
    let integral = |a: f64, b: f64| {
        let n = 100_000;
        let h = (b - a) / n as f64;
        (0..n).map(|k| f(a + (k as f64 + 0.5) * h)).sum::<f64>() * h
    };
    let edge_share = integral(-0.5, radius) / integral(-radius, radius);
    let dir = std::env::temp_dir().join(format!("grinlight-filter-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (reach, beyond, edge, corner) in [
        (
            "beyond the image",
            true,
            edge_share,
            edge_share * edge_share,
        ),
        ("inside the image", false, 1.0, 1.0),
    ] {
        let text = format!(
            "[[material]]\nname = \"white\"\ntype = \"diffuse\"\nalbedo = 1\n\
             [[shape]]\ntype = \"quad\"\nvertices = [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]\nmaterial = \"white\"\n\
             [[light]]\ntype = \"environment\"\nsky = \"uniform\"\n\
             [camera]\nposition = [0, 0, 2]\nlook_at = [0, 0, 0]\nfov_y_deg = 53.13010235415598\nwidth = 32\nheight = 32\n\
             filter = \"gaussian\"\nfilter_stddev = {sigma}\nfilter_radius = {radius}\nfilter_beyond_image = {beyond}\n\
             [render]\nspp = 256\nphotons = 1000\ncaustic_photons = 0\ngather = 0\n"
        );
        let scene = parse_scene(&dir.join("s.toml"), text).unwrap();
        let albedo = render(&scene, 0).layer("albedo").unwrap();
        let column: f64 = (8..24).map(|y| f64::from(albedo[y * 32][0])).sum::<f64>() / 16.0;
        let corner_got = f64::from(albedo[0][0]);
        let middle = f64::from(albedo[16 * 32 + 16][0]);
        println!("{reach}: first column {column} ({edge}), corner {corner_got} ({corner}), middle {middle}");
        assert!(
            (column - edge).abs() < 0.03,
            "{reach}: first column {column} vs {edge}"
        );
        assert!(
            (corner_got - corner).abs() < 0.1,
            "{reach}: corner {corner_got} vs {corner}"
        );
        assert!((middle - 1.0).abs() < 1e-6, "{reach}: middle {middle}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A cropped camera renders its window of the image and nothing else: each of the window's
/// pixels is the whole image's pixel bit for bit (both integrators, every layer; a pixel's
/// numbers are keyed by its place in the image), with a box filter everywhere and with a
/// Gaussian (σ ½, r 2) wherever its support lies inside the window; at the window's edges the
/// Gaussian's support ends there (as at an image's edge), so the pixels on them differ.
#[test]
fn a_crop_renders_its_window_of_the_image_pixel_for_pixel() {
    let text = std::fs::read_to_string("scenes/cornell_diffuse.toml")
        .unwrap()
        .replace("width = 256\nheight = 256\n", "width = 48\nheight = 40\n")
        .replace("spp = 16\n", "spp = 4\n");
    let (x, y, w, h) = (10usize, 6usize, 24usize, 20usize);
    for filter in ["box", "gaussian"] {
        let text = text.replace(
            "height = 40\n",
            &format!("height = 40\nfilter = \"{filter}\"\n"),
        );
        let cropped = text.replace(
            "height = 40\n",
            &format!("height = 40\ncrop = [{x}, {y}, {w}, {h}]\n"),
        );
        assert_ne!(cropped, text, "the crop was set");
        let path = Path::new("scenes/cornell_diffuse.toml");
        let (whole_scene, settings) = parse_scene(path, text.clone()).unwrap();
        let (crop_scene, _) = parse_scene(path, cropped).unwrap();
        for integrator in grinlight::settings::IntegratorKind::ALL {
            let settings = grinlight::settings::Settings {
                integrator,
                threads: 2,
                ..settings.clone()
            };
            let whole = grinlight::render::render(&whole_scene, &settings, &())
                .unwrap()
                .0;
            let part = grinlight::render::render(&crop_scene, &settings, &())
                .unwrap()
                .0;
            for layer in ["beauty", "albedo"] {
                let (a, b) = (whole.layer(layer).unwrap(), part.layer(layer).unwrap());
                assert_eq!(b.len(), w * h, "{filter} {integrator:?}: the window's size");
                let (mut inner, mut cut) = (0, 0);
                for (j, i) in (0..h).flat_map(|j| (0..w).map(move |i| (j, i))) {
                    let edge = i.min(j).min(w - 1 - i).min(h - 1 - j);
                    if filter == "gaussian" && edge < 2 {
                        cut += usize::from(b[j * w + i] != a[(y + j) * 48 + x + i]);
                        continue;
                    }
                    inner += 1;
                    assert_eq!(
                        b[j * w + i],
                        a[(y + j) * 48 + x + i],
                        "{filter} {integrator:?} {layer}: window pixel ({i}, {j})"
                    );
                }
                assert!(inner >= (w - 4) * (h - 4));
                if filter == "gaussian" && layer == "beauty" {
                    assert!(
                        cut > 0,
                        "{integrator:?}: the filter's support ends at the window"
                    );
                }
            }
        }
    }
}

/// A pixel's samples split at a dielectric in proportion to its reflectance: a glass slab
/// (n = 1.5, 1 thick) seen at 70° incidence under a uniform sky of radiance 1, a black floor
/// below it. A path leaves upward after 0, 2, 4, … internal reflections, so a pixel sees the
/// slab's reflectance 2F/(1 + F) with F the unpolarised Fresnel reflectance at 70° (each
/// reflection within the slab meets the same F). With each sample choosing its branches
/// independently a 16-sample pixel would scatter about it by √(R(1 − R)/16) ≈ 0.11; the
/// first choices are stratified over the pixel, so the first split is exact and the later
/// ones (each stratified alone, not jointly) scatter less. Bars: the 64 × 64 pixels' RMS
/// deviation below 0.6 of the independent one (measured 0.46; independent choices would give
/// 1 ± 0.02 of it), and their mean within three standard errors (RMS / 64) of 2F/(1 + F).
#[test]
fn a_pixel_splits_at_a_dielectric_in_proportion_to_its_reflectance() {
    let theta = 70f64.to_radians();
    let (x, y) = (theta.sin(), -theta.cos());
    let text = format!(
        "[camera]\nposition = [{px}, 1, 0]\nlook_at = [0, 0, 0]\nfov_y_deg = 1\nwidth = 64\nheight = 64\n\
         [render]\nspp = 16\ngather = 0\nphotons = 1000\n\
         [[light]]\ntype = \"environment\"\nsky = \"uniform\"\n\
         [[material]]\nname = \"glass\"\ntype = \"dielectric\"\nior = 1.5\n\
         [[material]]\nname = \"black\"\ntype = \"diffuse\"\nalbedo = [0, 0, 0]\n\
         [[shape]]\ntype = \"box\"\nmin = [-50, -1, -50]\nmax = [50, 0, 50]\nmaterial = \"glass\"\n\
         [[shape]]\ntype = \"quad\"\nvertices = [[-500, -2, -500], [-500, -2, 500], [500, -2, 500], [500, -2, -500]]\nmaterial = \"black\"\n",
        px = -x / -y,
    );
    let scene = parse_scene(Path::new("slab.toml"), text).unwrap();
    let film = render(&scene, 0);
    let (ci, n) = (theta.cos(), 1.5f64);
    let ct = (1.0 - (theta.sin() / n).powi(2)).sqrt();
    let rs = ((ci - n * ct) / (ci + n * ct)).powi(2);
    let rp = ((n * ci - ct) / (n * ci + ct)).powi(2);
    let f = 0.5 * (rs + rp);
    let want = 2.0 * f / (1.0 + f);
    let values: Vec<f64> = film
        .layer("beauty")
        .unwrap()
        .iter()
        .map(|p| p[1] as f64)
        .collect();
    let mean = values.iter().sum::<f64>() / values.len() as f64;
    let rms = (values.iter().map(|v| (v - want).powi(2)).sum::<f64>() / values.len() as f64).sqrt();
    let independent = (want * (1.0 - want) / 16.0).sqrt();
    println!("F {f:.4}, slab {want:.4}: mean {mean:.4}, pixels' RMS deviation {rms:.4} (independent choices: {independent:.4})");
    assert!(rms < 0.6 * independent, "{rms} vs {independent}");
    let standard_error = rms / (values.len() as f64).sqrt();
    assert!(
        (mean - want).abs() < 3.0 * standard_error,
        "{mean} vs {want}"
    );
}

/// A boundary between equal indices is no surface to light: a floor and a wall lit by a point
/// light (then a spot, the sun, a quad lamp and a uniform sky, each alone) and seen from above, alone and with the floor's middle inside a box of a medium of index 1 behind an index-matched
/// boundary (Mitsuba's `null`). Light samples reach through the box (the path tracer, which
/// finds a point light by light samples alone, would read the floor black inside it were the
/// boundary a specular surface), and photons through it (from the light, and from the wall)
/// are the floor's direct and global light, not a caustic: each integrator's image mean with the box is its own without, the path tracer's
/// to 1e-4 (its paths cross the box drawing no number; only the crossing's 1e-9 offsets
/// differ), the photon mapper's to 1 % (its photons' noise). A box of index 1.5 in its place
/// is a glass block, through which the path tracer sees no point light: under half the light.
#[test]
fn an_index_matched_boundary_is_no_surface_to_light() {
    let room = "[camera]\nposition = [0, 3, 0.01]\nlook_at = [0, 0, 0]\nfov_y_deg = 40\nwidth = 32\nheight = 32\n\
                [render]\nspp = 8\nphotons = 40000\ncaustic_photons = 40000\nmax_depth = 8\n\
                [[material]]\nname = \"floor\"\ntype = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]\n\
                [[shape]]\ntype = \"quad\"\nvertices = [[-2, 0, -2], [-2, 0, 2], [2, 0, 2], [2, 0, -2]]\nmaterial = \"floor\"\n\
                [[shape]]\ntype = \"quad\"\nvertices = [[1, 0, -2], [1, 1.2, -2], [1, 1.2, 2], [1, 0, 2]]\nmaterial = \"floor\"\n";
    let boxed = |plain: &str, n: f64| {
        format!(
            "{plain}[[medium]]\nname = \"inside\"\nprofile = \"uniform\"\nn = {n}\n\
             [[material]]\nname = \"boundary\"\ntype = \"dielectric\"\nior = {n}\n\
             [[shape]]\ntype = \"box\"\nmin = [-0.8, -0.5, -0.8]\nmax = [0.8, 0.6, 0.8]\nmaterial = \"boundary\"\ninterior = \"inside\"\n"
        )
    };
    let mean = |text: &str, integrator: &str| {
        let text = format!("{text}\n").replace(
            "[render]\n",
            &format!("[render]\nintegrator = \"{integrator}\"\n"),
        );
        let scene = parse_scene(Path::new("s.toml"), text).unwrap();
        let beauty = render(&scene, 2).layer("beauty").unwrap();
        beauty.iter().map(|p| p[0] as f64).sum::<f64>() / beauty.len() as f64
    };
    // Every kind of light: found by light samples alone (point, spot, parallel), by both
    // strategies (a quad lamp), and a sky; open scenes under the sun and the sky.
    let lights = [
        ("point", "type = \"point\"\nposition = [0.3, 1.5, 0.2]\nintensity = [5, 5, 5]"),
        ("spot", "type = \"spot\"\nposition = [0.3, 1.5, 0.2]\nintensity = [5, 5, 5]\ncone_deg = 50"),
        ("sun", "type = \"directional\"\ndirection = [-0.3, -1, 0.2]\nirradiance = [1, 1, 1]"),
        ("lamp", "type = \"quad\"\nvertices = [[-0.3, 1.5, -0.3], [0.3, 1.5, -0.3], [0.3, 1.5, 0.3], [-0.3, 1.5, 0.3]]\nradiance = [4, 4, 4]"),
        ("sky", "type = \"environment\"\nsky = \"uniform\"\nradiance = [0.5, 0.5, 0.5]"),
    ];
    let point = format!("{room}[[light]]\n{}\n", lights[0].1);
    for (light, block) in lights {
        let plain = format!("{room}[[light]]\n{block}\n");
        for (integrator, bar) in [("path", 1e-4), ("photon_map", 0.01)] {
            let alone = mean(&plain, integrator);
            let matched = mean(&boxed(&plain, 1.0), integrator);
            println!(
                "{light}, {integrator}: floor alone {alone:.6}, in an index-matched box {matched:.6}"
            );
            assert!(alone > 0.01, "{light}, {integrator}: {alone}");
            assert!(
                (matched / alone - 1.0).abs() < bar,
                "{light}, {integrator}: {matched} vs {alone}"
            );
        }
    }
    let (plain, boxed) = (point.as_str(), |n| boxed(&point, n));
    let glass = mean(&boxed(1.5), "path");
    let alone = mean(plain, "path");
    assert!(glass < 0.5 * alone, "glass block: {glass} vs {alone}");
}

/// An emitting mesh lights a room as the surface it is: the quad lamp given as a mesh of its
/// two triangles lights it as the quad lamp does (the path tracer draws points uniformly over
/// the same area either way, from the same numbers: over seeds 1–6 the image means' ratio was
/// 0.9996–1.0009; bar 0.2 %), and an octahedral mesh lamp, seen by the camera, lights it the
/// same through the path tracer (light samples, and BSDF samples weighed by the density at
/// the triangle they hit) and the photon mapper (photons from its faces): over seeds 1–6 the
/// ratio was 0.9984–1.0031 (the photon mapper's kernel bias and both estimates' noise), and
/// with a uniform sky and the sun lighting the room too 0.9984–1.0030; bar 1 %.
#[test]
fn an_emitting_mesh_lights_a_room_as_its_surface_does() {
    let room = "[camera]\nposition = [0, 1.2, 3.5]\nlook_at = [0, 0.6, 0]\nfov_y_deg = 50\nwidth = 32\nheight = 32\n\
                [render]\nspp = 16\nphotons = 100000\ncaustic_photons = 20000\nmax_depth = 8\n\
                [[material]]\nname = \"grey\"\ntype = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]\n\
                [[shape]]\ntype = \"quad\"\nvertices = [[-2, 0, -2], [-2, 0, 2], [2, 0, 2], [2, 0, -2]]\nmaterial = \"grey\"\n\
                [[shape]]\ntype = \"quad\"\nvertices = [[-2, 0, -1], [2, 0, -1], [2, 2, -1], [-2, 2, -1]]\nmaterial = \"grey\"\n";
    let mean = |light: &str, integrator: &str| {
        let text = format!("{room}{light}").replace(
            "[render]\n",
            &format!("[render]\nintegrator = \"{integrator}\"\n"),
        );
        let scene = parse_scene(Path::new("s.toml"), text).unwrap();
        let beauty = render(&scene, 2).layer("beauty").unwrap();
        beauty.iter().map(|p| p[0] as f64).sum::<f64>() / beauty.len() as f64
    };
    let quad = "[[light]]\ntype = \"quad\"\nvertices = [[-0.3, 1.5, -0.3], [0.3, 1.5, -0.3], [0.3, 1.5, 0.3], [-0.3, 1.5, 0.3]]\nradiance = [4, 4, 4]\n";
    let triangles = "[[light]]\ntype = \"mesh\"\npoints = [-0.3, 1.5, -0.3, 0.3, 1.5, -0.3, 0.3, 1.5, 0.3, -0.3, 1.5, 0.3]\nindices = [0, 1, 2, 0, 2, 3]\nradiance = [4, 4, 4]\n";
    let (as_quad, as_mesh) = (mean(quad, "path"), mean(triangles, "path"));
    println!("quad lamp {as_quad:.6}, as two triangles {as_mesh:.6}");
    assert!(
        (as_mesh / as_quad - 1.0).abs() < 2e-3,
        "{as_mesh} vs {as_quad}"
    );
    let lamp = octahedral_lamp(DVec3::new(0.2, 0.8, 0.0), 0.25).light("[3, 3, 3]");
    let (path, photons) = (mean(&lamp, "path"), mean(&lamp, "photon_map"));
    println!("octahedral lamp: path tracer {path:.6}, photon mapper {photons:.6}");
    assert!(path > 0.05, "{path}");
    assert!((photons / path - 1.0).abs() < 0.01, "{photons} vs {path}");
    // Open to a sky and under the sun as well: the lamp's light among theirs.
    let open = format!(
        "{lamp}[[light]]\ntype = \"environment\"\nsky = \"uniform\"\nradiance = [0.2, 0.2, 0.2]\n\
         [[light]]\ntype = \"directional\"\ndirection = [-0.3, -1, 0.2]\nirradiance = [0.5, 0.5, 0.5]\n"
    );
    let (path, photons) = (mean(&open, "path"), mean(&open, "photon_map"));
    println!("octahedral lamp, sky and sun: path tracer {path:.6}, photon mapper {photons:.6}");
    assert!((photons / path - 1.0).abs() < 0.01, "{photons} vs {path}");
}

/// A camera that hides emitters leaves out what its first chain meets before any specular
/// surface — the sky and an emitting quad seen directly — and nothing else: the same sky and
/// quad in a mirror ball, and the light both cast on the floor, are as a camera that shows
/// them sees them, bit for bit (the same numbers are drawn), in both integrators. Each pixel's
/// class comes from its footprint's corners and centre traced here, analytically.
#[test]
fn a_camera_that_hides_emitters_leaves_out_only_what_it_sees_directly() {
    #[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
    enum Seen {
        Sky,
        Light,
        Ball,
        Floor,
    }
    let (centre, radius) = (DVec3::new(0.7, 0.5, 0.0), 0.5);
    let class = |o: DVec3, d: DVec3| -> Seen {
        let oc = o - centre;
        let (b, c) = (oc.dot(d), oc.length_squared() - radius * radius);
        let ball = (b * b - c >= 0.0).then(|| -b - (b * b - c).sqrt());
        let t_light = -o.z / d.z;
        let p = o + t_light * d;
        let light = (t_light > 0.0 && (-1.2..=-0.2).contains(&p.x) && (0.3..=1.0).contains(&p.y))
            .then_some(t_light);
        let t_floor = -o.y / d.y;
        let q = o + t_floor * d;
        let floor = (t_floor > 0.0 && q.x.abs() <= 3.0 && q.z.abs() <= 3.0).then_some(t_floor);
        let nearest = [
            (ball, Seen::Ball),
            (light, Seen::Light),
            (floor, Seen::Floor),
        ]
        .into_iter()
        .filter_map(|(t, s)| t.filter(|t| *t > 0.0).map(|t| (t, s)))
        .min_by(|a, b| a.0.total_cmp(&b.0));
        nearest.map_or(Seen::Sky, |(_, s)| s)
    };
    let text = |hide: bool| {
        format!(
            "[[material]]\nname = \"white\"\ntype = \"diffuse\"\nalbedo = 0.5\n\
             [[material]]\nname = \"mirror\"\ntype = \"conductor\"\nmetal = \"perfect\"\n\
             [[shape]]\ntype = \"quad\"\nvertices = [[-3, 0, -3], [-3, 0, 3], [3, 0, 3], [3, 0, -3]]\nmaterial = \"white\"\n\
             [[shape]]\ntype = \"sphere\"\ncenter = [0.7, 0.5, 0]\nradius = 0.5\nmaterial = \"mirror\"\n\
             [[light]]\ntype = \"quad\"\nvertices = [[-1.2, 0.3, 0], [-0.2, 0.3, 0], [-0.2, 1.0, 0], [-1.2, 1.0, 0]]\nradiance = 4\n\
             [[light]]\ntype = \"environment\"\nsky = \"uniform\"\nradiance = 0.5\n\
             [camera]\nposition = [0, 1, 4]\nlook_at = [0, 0.5, 0]\nfov_y_deg = 40\nwidth = 48\nheight = 32\nhide_emitters = {hide}\n\
             [render]\nspp = 4\nphotons = 20000\ncaustic_photons = 20000\n"
        )
    };
    let path = Path::new("hide_emitters.toml");
    let shown = parse_scene(path, text(false)).unwrap();
    let hidden = parse_scene(path, text(true)).unwrap();
    let camera = shown.0.camera.as_ref().unwrap();
    let seen = |px: u32, py: u32| -> Option<Seen> {
        let corners = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0), (0.5, 0.5)];
        let classes: Vec<Seen> = corners
            .iter()
            .map(|&(u, v)| {
                let film = grinlight::camera::FilmPoint {
                    px,
                    py,
                    u,
                    v,
                    lens: glam::DVec2::ZERO,
                };
                let ray = camera.ray(film);
                class(ray.origin, ray.direction)
            })
            .collect();
        classes
            .iter()
            .all(|c| *c == classes[0])
            .then_some(classes[0])
    };
    for integrator in grinlight::settings::IntegratorKind::ALL {
        let with = |s: &(grinlight::scene::Scene, grinlight::settings::Settings)| {
            let settings = grinlight::settings::Settings {
                integrator,
                ..s.1.clone()
            };
            let film = grinlight::render::render(&s.0, &settings, &()).unwrap().0;
            let layer = |name| film.layer(name).unwrap().to_vec();
            (layer("beauty"), layer("emitted"))
        };
        let (shown_beauty, shown_emitted) = with(&shown);
        let (hidden_beauty, hidden_emitted) = with(&hidden);
        let mut counts = std::collections::HashMap::new();
        for (i, ((sb, se), (hb, he))) in (shown_beauty.iter().zip(&shown_emitted))
            .zip(hidden_beauty.iter().zip(&hidden_emitted))
            .enumerate()
        {
            let (px, py) = ((i % 48) as u32, (i / 48) as u32);
            for c in 0..3 {
                // Only the emitted layer changes, and only downward.
                let rest = sb[c] - se[c];
                assert!(
                    (hb[c] - he[c] - rest).abs() <= 1e-5 * sb[c].abs() + 1e-6,
                    "{integrator:?} pixel ({px}, {py}): beauty {} − emitted {} against {rest}",
                    hb[c],
                    he[c]
                );
                assert!(he[c] <= se[c] + 1e-6, "{integrator:?} ({px}, {py})");
            }
            let Some(what) = seen(px, py) else { continue };
            *counts.entry(what).or_insert(0) += 1;
            match what {
                Seen::Sky | Seen::Light => {
                    assert_eq!(*hb, [0.0; 3], "{integrator:?} {what:?} ({px}, {py})");
                    assert!(sb[0] >= 0.5 * 0.999, "{integrator:?} {what:?} ({px}, {py})");
                }
                Seen::Ball | Seen::Floor => {
                    assert_eq!(hb, sb, "{integrator:?} {what:?} ({px}, {py})");
                }
            }
        }
        println!("{integrator:?}: pixels by what they see {counts:?}");
        for what in [Seen::Sky, Seen::Light, Seen::Ball, Seen::Floor] {
            assert!(
                counts.get(&what).copied().unwrap_or(0) >= 8,
                "{what:?}: {counts:?}"
            );
        }
    }
}
