//! Hostile and extreme input, as a careless or unlucky user gives it: bad scene keys, broken
//! files (OBJ, images, grids), absurd command-line values. Every case runs the real binary in
//! a directory of its own and must end within 10 s either in a clear error (exit 1 or 2, the
//! expected words, no panic) or in a success whose every output (EXR layers, CSV values,
//! report) is finite.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// A small scene that renders in a few milliseconds: an 8 × 8 view of a lit diffuse quad.
const BASE: &str = "[camera]\nposition = [0, 0, 3]\nlook_at = [0, 0, 0]\nfov_y_deg = 40\nwidth = 8\nheight = 8\n\
[render]\nspp = 1\nphotons = 2000\ncaustic_photons = 2000\ngather = 1\nreceiver_photons = 2000\n\
[[material]]\nname = \"white\"\ntype = \"diffuse\"\nalbedo = 0.5\n\
[[shape]]\ntype = \"quad\"\nvertices = [[-1,-1,0],[1,-1,0],[1,1,0],[-1,1,0]]\nmaterial = \"white\"\n";

const LIGHT: &str = "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nintensity = 1\n";

/// A Mitsuba scene of an 8 × 8 box-filtered view, 1 sample, a point light and `body`.
fn mitsuba(body: &str) -> Vec<u8> {
    format!(
        "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><sampler type=\"independent\"><integer name=\"sample_count\" value=\"1\"/></sampler>\
         <film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/><rfilter type=\"box\"/></film></sensor>\n\
         <emitter type=\"point\"><point name=\"position\" value=\"0, 0, 2\"/></emitter>\n{body}\n</scene>\n"
    )
    .into_bytes()
}

/// A Mitsuba scene case: `s.xml` of [`mitsuba`]`(body)`, rendered.
fn xml_case(name: &'static str, body: &str, expect: Expect) -> Case {
    Case {
        name,
        files: vec![("s.xml", mitsuba(body))],
        args: args("render s.xml"),
        expect,
    }
}

/// A pbrt scene of an 8 × 8 box-filtered view, 1 sample, a point light and a world `body`.
fn pbrt(body: &str) -> Vec<u8> {
    format!(
        "Scale -1 1 1\nLookAt 0 0 5 0 0 0 0 1 0\nCamera \"perspective\"\nSampler \"independent\" \"integer pixelsamples\" 1\n\
         Film \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 8\nPixelFilter \"box\"\nWorldBegin\n\
         LightSource \"point\" \"point3 from\" [0 0 5]\n{body}\n"
    )
    .into_bytes()
}

/// A pbrt scene case: `s.pbrt` of [`pbrt`]`(body)`, rendered.
fn pbrt_case(name: &'static str, body: &str, expect: Expect) -> Case {
    Case {
        name,
        files: vec![("s.pbrt", pbrt(body))],
        args: args("render s.pbrt"),
        expect,
    }
}

/// What a case must end in.
enum Expect {
    /// Failure whose standard error contains this.
    Error(&'static str),
    /// Success with finite outputs; standard output contains this.
    Finite(&'static str),
}

struct Case {
    name: &'static str,
    /// Files to create: (name, content).
    files: Vec<(&'static str, Vec<u8>)>,
    /// Arguments (after the program name).
    args: Vec<String>,
    expect: Expect,
}

fn scene(extra: &str) -> Vec<u8> {
    format!("{BASE}{extra}").into_bytes()
}

/// An image file's bytes in `format`, `w` × `h` pixels of `value` (R, G and B).
fn image_bytes(w: u32, h: u32, value: f32, format: image::ImageFormat) -> Vec<u8> {
    let mut bytes = std::io::Cursor::new(Vec::new());
    let img = image::Rgb32FImage::from_pixel(w, h, image::Rgb([value; 3]));
    match format {
        image::ImageFormat::Png => image::DynamicImage::ImageRgb32F(img)
            .into_rgb8()
            .write_to(&mut bytes, format),
        _ => img.write_to(&mut bytes, format),
    }
    .unwrap();
    bytes.into_inner()
}

fn render(extra_args: &str) -> Vec<String> {
    let mut v = vec!["render".to_string(), "s.toml".to_string()];
    v.extend(extra_args.split_whitespace().map(str::to_string));
    v
}

fn args(s: &str) -> Vec<String> {
    s.split_whitespace().map(str::to_string).collect()
}

/// A scene case: `s.toml` = BASE + `extra` (+ other files), rendered.
fn scene_case(name: &'static str, extra: &str, expect: Expect) -> Case {
    Case {
        name,
        files: vec![("s.toml", scene(extra))],
        args: render(""),
        expect,
    }
}

/// A scene with a mesh shape reading `m.obj` of `obj` content (and a light).
fn mesh_case(name: &'static str, obj: &str, extra: &str, expect: Expect) -> Case {
    let shape = format!(
        "{LIGHT}[[shape]]\ntype = \"mesh\"\nfile = \"m.obj\"\nmaterial = \"white\"\n{extra}"
    );
    Case {
        name,
        files: vec![
            ("s.toml", scene(&shape)),
            ("m.obj", obj.as_bytes().to_vec()),
        ],
        args: render(""),
        expect,
    }
}

/// A 2 × 2 EXR (one RGB layer) whose pixel (1, 0) has `value`.
/// A 2 × 2 grey PNG's bytes.
fn png_2x2() -> Vec<u8> {
    let mut bytes = Vec::new();
    image::RgbImage::from_pixel(2, 2, image::Rgb([128, 128, 128]))
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .unwrap();
    bytes
}

fn exr_with(value: f32) -> Vec<u8> {
    let path = std::env::temp_dir().join(format!(
        "grinlight-hostile-{}-{}.exr",
        std::process::id(),
        value.to_bits()
    ));
    exr::prelude::write_rgb_file(&path, 2, 2, |x, y| {
        if (x, y) == (1, 0) {
            (value, value, value)
        } else {
            (0.5, 0.5, 0.5)
        }
    })
    .unwrap();
    let bytes = std::fs::read(&path).unwrap();
    std::fs::remove_file(&path).unwrap();
    bytes
}

/// A scene case whose space is filled with the medium of `medium` (its keys), lit.
fn ambient_case(name: &'static str, medium: &str, expect: Expect) -> Case {
    Case {
        name,
        files: vec![(
            "s.toml",
            format!("ambient = \"a\"\n{BASE}{LIGHT}[[medium]]\nname = \"a\"\n{medium}\n")
                .into_bytes(),
        )],
        args: render(""),
        expect,
    }
}

/// A partial file's magic line of this version.
const PARTIAL: &[u8] = b"GRINLIGHT PARTIAL 3\n";

fn env_case(name: &'static str, image: Vec<u8>, expect: Expect) -> Case {
    Case {
        name,
        files: vec![
            (
                "s.toml",
                scene("[[light]]\ntype = \"environment\"\nfile = \"sky.exr\"\n"),
            ),
            ("sky.exr", image),
        ],
        args: render(""),
        expect,
    }
}

fn cases() -> Vec<Case> {
    use Expect::{Error, Finite};
    let grid = |extra: &str| {
        format!("{LIGHT}[[medium]]\nname = \"g\"\nprofile = \"grid\"\nbounds = [[0,0,0],[1,1,1]]\n{extra}")
    };
    let receiver =
        |extra: &str| format!("{LIGHT}[[receiver]]\nname = \"r\"\ncenter = [0, 0, 0.5]\n{extra}");
    let mut v = vec![
        // Scene keys: numbers out of range, negative, NaN, infinite, zero.
        // Polarization: sheets' axes and retardances, the switch.
        scene_case("polarizer of a zero axis", "[[material]]\nname = \"p\"\ntype = \"polarizer\"\naxis = [0, 0, 0]\n", Error("must be a non-zero vector")),
        scene_case("polarizer of a NaN axis", "[[material]]\nname = \"p\"\ntype = \"polarizer\"\naxis = [nan, 1, 0]\n", Error("axis")),
        scene_case("polarizer without an axis", "[[material]]\nname = \"p\"\ntype = \"polarizer\"\n", Error("axis")),
        scene_case("retarder of a NaN retardance", "[[material]]\nname = \"p\"\ntype = \"retarder\"\nfast_axis = [1, 0, 0]\nretardance_deg = nan\n", Error("retardance_deg")),
        scene_case("retarder of 1e300 degrees", "[[material]]\nname = \"p\"\ntype = \"retarder\"\nfast_axis = [1, 0, 0]\nretardance_deg = 1e300\n", Error("retardance_deg")),
        scene_case("pane of index 0", "[[material]]\nname = \"p\"\ntype = \"thin_dielectric\"\nior = 0\n", Error("ior")),
        scene_case("pane of a NaN index", "[[material]]\nname = \"p\"\ntype = \"thin_dielectric\"\nior = nan\n", Error("ior")),
        scene_case("pane of index 1e300", "[[material]]\nname = \"p\"\ntype = \"thin_dielectric\"\nior = 1e300\n", Error("ior")),
        scene_case("pane without an index", "[[material]]\nname = \"p\"\ntype = \"thin_dielectric\"\n", Error("ior")),
        Case {
            files: vec![("s.toml", [b"ambient = \"f\"\n".to_vec(), scene(&format!("{LIGHT}[[medium]]\nname = \"f\"\nprofile = \"uniform\"\nn = 1.5\nscattering = 0.5\n[[material]]\nname = \"p\"\ntype = \"thin_dielectric\"\nior = 1.0001\n[[shape]]\ntype = \"quad\"\nmaterial = \"p\"\nvertices = [[-1, 0, -1], [1, 0, -1], [1, 0.001, 1], [-1, 0.001, 1]]\n"))].concat())],
            ..scene_case("pane less dense than its fog, seen at grazing angles", "", Finite("wrote"))
        },
        scene_case("crop beyond the image", "", Error("")).with_scene_replace("height = 8\n", "height = 8\ncrop = [4, 0, 8, 8]\n", "must be non-empty and lie within the 8×8 image"),
        scene_case("empty crop", "", Error("")).with_scene_replace("height = 8\n", "height = 8\ncrop = [0, 0, 0, 8]\n", "must be non-empty"),
        scene_case("crop of three numbers", "", Error("")).with_scene_replace("height = 8\n", "height = 8\ncrop = [0, 0, 8]\n", "expected 4 integers, got 3"),
        scene_case("negative crop", "", Error("")).with_scene_replace("height = 8\n", "height = 8\ncrop = [-1, 0, 4, 4]\n", "expected non-negative integers"),
        Case { name: "crop outside an image made smaller", files: vec![("s.toml", String::from_utf8(scene(LIGHT)).unwrap().replacen("height = 8\n", "height = 8\ncrop = [2, 2, 6, 6]\n", 1).into_bytes())], args: render("--width 4"), expect: Error("crop 6×6 at (2, 2) does not lie within the 4×8 image") },
        Case { name: "crop inside", files: vec![("s.toml", String::from_utf8(scene(LIGHT)).unwrap().replacen("height = 8\n", "height = 8\ncrop = [2, 2, 4, 4]\n", 1).into_bytes())], args: render(""), expect: Finite("wrote") },
        scene_case("camera polarizer at NaN degrees", "", Error("")).with_scene_replace("height = 8\n", "height = 8\npolarizer_deg = nan\n", "polarizer_deg"),
        scene_case("camera polarizer at 1e300 degrees", "", Error("")).with_scene_replace("height = 8\n", "height = 8\npolarizer_deg = 1e300\n", "polarizer_deg"),
        scene_case("camera polarizer as a word", "", Error("")).with_scene_replace("height = 8\n", "height = 8\npolarizer_deg = \"up\"\n", "polarizer_deg"),
        Case {
            files: vec![("s.toml", String::from_utf8(scene(&format!("{LIGHT}[[material]]\nname = \"g\"\ntype = \"dielectric\"\nior = 1.5\n[[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 0.5]\nradius = 0.5\nmaterial = \"g\"\n"))).unwrap().replacen("height = 8\n", "height = 8\npolarizer_deg = 30\n", 1).into_bytes())],
            ..scene_case("a camera polarizer over glass (polarized: photons and camera)", "", Finite("wrote"))
        },
        scene_case("polarized as a word", "", Error("")).with_scene_replace("spp = 1", "spp = 1\npolarized = \"yes\"", "polarized"),
        scene_case("a camera looking through a polarizer edge on", &format!("{LIGHT}[[material]]\nname = \"p\"\ntype = \"polarizer\"\naxis = [0, 0, 1]\n[[shape]]\ntype = \"quad\"\nmaterial = \"p\"\nvertices = [[-1, 0, -1], [1, 0, -1], [1, 0, 1], [-1, 0, 1]]\n"), Finite("wrote")),
        scene_case("glass behind a retarder (polarized: photons and camera)", &format!("{LIGHT}[[material]]\nname = \"g\"\ntype = \"dielectric\"\nior = 1.5\n[[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 0.5\nmaterial = \"g\"\n[[material]]\nname = \"p\"\ntype = \"retarder\"\nfast_axis = [1, 1, 0]\nretardance_deg = 90\n[[shape]]\ntype = \"quad\"\nmaterial = \"p\"\nvertices = [[-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]]\n"), Finite("wrote")),
        scene_case("luminaire without its file", "[[light]]\ntype = \"goniometric\"\nfile = \"no.ies\"\nposition = [0, 0, 1]\n", Error("s.toml:")),
        Case {
            files: vec![
                ("s.toml", scene("[[light]]\ntype = \"goniometric\"\nfile = \"l.ies\"\nposition = [0, 0, 1]\n")),
                ("l.ies", b"IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 3 1 1 2 0 0 0\n1 1 10\n0 45 nan\n0\n1 1 1\n".to_vec()),
            ],
            ..scene_case("luminaire of a NaN angle", "", Error("not a number"))
        },
        Case {
            files: vec![
                ("s.toml", scene("[[light]]\ntype = \"goniometric\"\nfile = \"l.ies\"\nposition = [0, 0, 1]\n")),
                ("l.ies", b"IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n0 0\n".to_vec()),
            ],
            ..scene_case("luminaire that sends nothing", "", Error("finite power > 0"))
        },
        Case {
            files: vec![
                ("s.toml", scene("[[light]]\ntype = \"goniometric\"\nfile = \"l.ies\"\nposition = [0, 0, 1]\n")),
                ("l.ies", b"IESNA:LM-63-2002\nTILT=NONE\n1 -1 1e300 2 1 1 2 0 0 0\n1e300 1 10\n0 90\n0\n5 1\n".to_vec()),
            ],
            ..scene_case("luminaire of 1e600 candela", "", Error("finite power > 0"))
        },
        Case {
            files: vec![
                ("s.toml", scene("[[light]]\ntype = \"goniometric\"\nfile = \"l.ies\"\nposition = [0, 0, 1]\ndirection = [1, 0, 0]\nc0 = [2, 0, 0]\n")),
                ("l.ies", b"IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n5 1\n".to_vec()),
            ],
            ..scene_case("luminaire whose C = 0 is its nadir", "", Error("must not be parallel"))
        },
        Case {
            files: vec![
                ("s.toml", scene("[[light]]\ntype = \"goniometric\"\nfile = \"l.exr\"\nposition = [0, 0, 1]\n")),
                ("l.exr", image_bytes(4, 2, 1.0, image::ImageFormat::OpenExr)),
            ],
            ..scene_case("intensity image not square", "", Error("is square; this one is 4 × 2"))
        },
        Case {
            files: vec![
                ("s.toml", scene("[[light]]\ntype = \"goniometric\"\nfile = \"l.exr\"\nposition = [0, 0, 1]\n")),
                ("l.exr", image_bytes(4, 4, f32::NAN, image::ImageFormat::OpenExr)),
            ],
            ..scene_case("intensity image of NaN", "", Error("intensities are finite and ≥ 0"))
        },
        Case {
            files: vec![
                ("s.toml", scene("[[light]]\ntype = \"goniometric\"\nfile = \"l.png\"\nposition = [0, 0, 1]\n")),
                ("l.png", image_bytes(4, 4, 0.5, image::ImageFormat::Png)),
            ],
            ..scene_case("intensity image of 8-bit levels", "", Error("floating-point pixels"))
        },
        Case {
            files: vec![
                ("s.toml", scene("[[light]]\ntype = \"goniometric\"\nfile = \"l.exr\"\nposition = [0, 0, 1]\n")),
                ("l.exr", image_bytes(4, 4, 0.0, image::ImageFormat::OpenExr)),
            ],
            ..scene_case("intensity image all black", "", Error("finite power > 0"))
        },
        Case {
            files: vec![
                ("s.toml", scene("[[light]]\ntype = \"goniometric\"\nfile = \"l.ies\"\nposition = [0, 0, 1]\nflip_v = true\n")),
                ("l.ies", b"IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n5 1\n".to_vec()),
            ],
            ..scene_case("a table's rows flipped", "", Error("is an intensity image's"))
        },
        Case {
            files: vec![
                ("s.toml", scene("[[light]]\ntype = \"environment\"\nfile = \"sky.exr\"\nprojection = \"equal_area\"\n")),
                ("sky.exr", image_bytes(4, 2, 1.0, image::ImageFormat::OpenExr)),
            ],
            ..scene_case("equal-area sky not square", "", Error("is square; this one is 4 × 2"))
        },
        Case {
            files: vec![
                ("s.toml", scene("[[light]]\ntype = \"environment\"\nfile = \"sky.png\"\nprojection = \"equal_area\"\n")),
                ("sky.png", image_bytes(4, 4, 0.5, image::ImageFormat::Png)),
            ],
            ..scene_case("equal-area sky of 8-bit levels", "", Error("floating-point pixels"))
        },
        Case {
            files: vec![
                ("s.toml", scene("[[light]]\ntype = \"environment\"\nfile = \"sky.exr\"\nprojection = \"equal_area\"\nfilter = \"bilinear\"\n")),
                ("sky.exr", image_bytes(4, 4, 1.0, image::ImageFormat::OpenExr)),
            ],
            ..scene_case("equal-area sky read bilinearly", "", Error("by nearest pixel"))
        },
        Case {
            files: vec![
                ("s.toml", scene("[[light]]\ntype = \"environment\"\nfile = \"sky.exr\"\nflip_v = true\n")),
                ("sky.exr", image_bytes(4, 2, 1.0, image::ImageFormat::OpenExr)),
            ],
            ..scene_case("lat-long sky's rows flipped", "", Error("is an equal-area map's"))
        },
        Case {
            files: vec![
                ("s.toml", scene("[[light]]\ntype = \"environment\"\nfile = \"sky.exr\"\nprojection = \"equal_area\"\n")),
                ("sky.exr", image_bytes(8, 8, 1.0, image::ImageFormat::OpenExr)),
            ],
            ..scene_case("equal-area sky", "", Finite("wrote"))
        },
        scene_case("intensity 1e308", "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nintensity = 1e308\n", Error("out of range")),
        scene_case("camera at 1e308", "[[light]]\ntype = \"point\"\nposition = [0, 0, 1e308]\nintensity = 1\n", Error("out of range")),
        scene_case("negative intensity", "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nintensity = -1\n", Error("must not be negative")),
        scene_case("NaN intensity", "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nintensity = nan\n", Error("must be finite")),
        scene_case("infinite radiance", "[[light]]\ntype = \"quad\"\nvertices = [[0,0,1],[1,0,1],[1,1,1],[0,1,1]]\nradiance = inf\n", Error("must be finite")),
        scene_case("sphere radius 1e31", &format!("{LIGHT}[[shape]]\ntype = \"sphere\"\ncenter = [0,0,0]\nradius = 1e31\nmaterial = \"white\"\n"), Error("out of range")),
        scene_case("zero-area quad", &format!("{LIGHT}[[shape]]\ntype = \"quad\"\nvertices = [[0,0,0],[0,0,0],[0,0,0],[0,0,0]]\nmaterial = \"white\"\n"), Error("zero area")),
        scene_case("albedo 1.5", "[[material]]\nname = \"m\"\ntype = \"diffuse\"\nalbedo = 1.5\n", Error("must be ≤ 1")),
        scene_case("ior 0", "[[material]]\nname = \"g\"\ntype = \"dielectric\"\nior = 0\n", Error("must be > 0")),
        scene_case("spp 0 in the scene", "", Error("")).with_scene_replace("spp = 1", "spp = 0", "integer ≥ 1"),
        scene_case("spp -1 in the scene", "", Error("")).with_scene_replace("spp = 1", "spp = -1", "integer ≥ 1"),
        scene_case("spp 1.5 in the scene", "", Error("")).with_scene_replace("spp = 1", "spp = 1.5", "integer ≥ 1"),
        scene_case("width 0", "", Error("")).with_scene_replace("width = 8", "width = 0", "integer ≥ 1"),
        scene_case("width 70000", "", Error("")).with_scene_replace("width = 8", "width = 70000", "at most 65536"),
        scene_case("fov 0", "", Error("")).with_scene_replace("fov_y_deg = 40", "fov_y_deg = 0", "(0°, 179°)"),
        scene_case("passes 0", "", Error("")).with_scene_replace("spp = 1", "spp = 1\npasses = 0", "integer ≥ 1"),
        scene_case("knn 0", "", Error("")).with_scene_replace("spp = 1", "spp = 1\nknn = 0", "integer ≥ 1"),
        scene_case("max_depth 0", "", Error("")).with_scene_replace("spp = 1", "spp = 1\nmax_depth = 0", "integer ≥ 1"),
        scene_case("radius 0", "", Error("")).with_scene_replace("spp = 1", "spp = 1\nradius = 0", "key `radius`: must be a number in (0, 1e30], got 0"),
        scene_case("tolerance 0", "", Error("")).with_scene_replace("spp = 1", "spp = 1\ntolerance = 0", "must be > 0"),
        scene_case("unknown control", "", Error("")).with_scene_replace("spp = 1", "spp = 1\ncontrol = \"wild\"", "unknown control"),
        scene_case("fixed step 0", "", Error("")).with_scene_replace("spp = 1", "spp = 1\ncontrol = \"fixed\"\nstep = 0", "must be > 0"),
        scene_case("world radius -1", "", Error("")).with_scene_replace("spp = 1", "spp = 1\nworld_radius = -1", "key `world_radius`: must be a number in (0, 1e30], got -1"),
        scene_case("time budget 0", "", Error("")).with_scene_replace("spp = 1", "spp = 1\ntime_budget = 0", "key `time_budget`: must be a number in (0, 1e30], got 0"),
        scene_case("target error -0.1", "", Error("")).with_scene_replace("spp = 1", "spp = 1\ntarget_error = -0.1", "key `target_error`: must be a number in (0, 1e30], got -0.1"),
        scene_case("target error nan", "", Error("")).with_scene_replace("spp = 1", "spp = 1\ntarget_error = nan", "key `target_error`: must be a number in (0, 1e30], got NaN"),
        scene_case("dangling material", &format!("{LIGHT}[[shape]]\ntype = \"sphere\"\ncenter = [0,0,0]\nradius = 1\nmaterial = \"nope\"\n"), Error("no material named 'nope'")),
        scene_case("unknown table", "[lens]\nf = 3\n", Error("unknown field `lens`")),
        scene_case("two cameras", "[camera]\nposition = [0,0,1]\n", Error("duplicate key")),
        scene_case("LED m < 0", "[[light]]\ntype = \"led\"\ncenter = [0,0,1]\nradius = 0.1\npower = 1\nm = -1\n", Error("must be ≥ 0")),
        scene_case("spot cone 0", "[[light]]\ntype = \"spot\"\nposition = [0,0,1]\nintensity = 1\ncone_deg = 0\n", Error("(0°, 180°]")),
        scene_case("black hole q < 0", &format!("{LIGHT}[[medium]]\nname = \"b\"\nprofile = \"black_hole\"\nrs = 1\nq = -1\n"), Error("key `q`")),
        scene_case("radial table not increasing", &format!("{LIGHT}[[medium]]\nname = \"t\"\nprofile = \"radial_table\"\nr = [0, 0.5, 0.2]\nn = [1.5, 1.4, 1.3]\n"), Error("key `r`")),
        scene_case("receiver bins 0", &receiver("size = [1, 1]\nbins = [0, 4]\n"), Error("key `bins`")),
        scene_case("receiver size < 0", &receiver("size = [-1, 1]\nbins = [4, 4]\n"), Error("key `size`")),
        scene_case("receiver up along normal", &receiver("size = [1, 1]\nbins = [4, 4]\nup = [0, 0, 1]\n"), Error("must not be parallel")),
        scene_case("output path the scene", "[output]\npath = \"s.toml\"\n", Error("must name an EXR")),
        scene_case("output dir missing", &format!("{LIGHT}[output]\npath = \"nowhere/x.exr\"\n"), Error("does not exist")),
        // Grids.
        scene_case("grid dims overflow", &grid("dims = [4294967296, 4294967296, 4294967296]\nvalues = [1, 1]\n"), Error("more nodes than can be addressed")),
        scene_case("grid negative value", &grid("dims = [2, 2, 2]\nvalues = [1, 1, 1, 1, 1, 1, 1, -1]\n"), Error("value #7")),
        Case {
            name: "grid file not numbers",
            files: vec![("s.toml", scene(&grid("dims = [2, 2, 2]\nfile = \"g.txt\"\n"))), ("g.txt", b"1 1 1 x 1 1 1 1".to_vec())],
            args: render(""),
            expect: Error("value #3 'x' is not a number"),
        },
        Case {
            name: "grid file too long",
            files: vec![("s.toml", scene(&grid("dims = [2, 2, 2]\nfile = \"g.txt\"\n"))), ("g.txt", b"1 1 1 1\n1 1 1 1 1".to_vec())],
            args: render(""),
            expect: Error("more than the 8 values of dims [2, 2, 2] (line 2)"),
        },
        Case {
            // A word of a megabyte comes back cut, not whole.
            name: "grid file endless word",
            files: vec![("s.toml", scene(&grid("dims = [2, 2, 2]\nfile = \"g.txt\"\n"))), ("g.txt", [b"1 ".to_vec(), vec![b'x'; 300_000], b"\n".to_vec()].concat())],
            args: render(""),
            expect: Error("value #1 'xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx…' is not a number"),
        },
        Case {
            name: "grid file too short",
            files: vec![("s.toml", scene(&grid("dims = [2, 2, 2]\nfile = \"g.txt\"\n"))), ("g.txt", b"1 1 1".to_vec())],
            args: render(""),
            expect: Error("expected 8 values"),
        },
        // OBJ files.
        mesh_case("missing mesh", "", "", Error("")).without_file("m.obj", "cannot read"),
        mesh_case("empty mesh", "", "", Error("no faces")),
        Case {
            name: "binary garbage mesh",
            files: vec![
                ("s.toml", scene(&format!("{LIGHT}[[shape]]\ntype = \"mesh\"\nfile = \"m.obj\"\nmaterial = \"white\"\n"))),
                ("m.obj", vec![0xff, 0xfe, 0x00, 0x12, 0x80, b'\n', 0xc3, 0x28]),
            ],
            args: render(""),
            expect: Error("line 1 is not text"),
        },
        mesh_case("NaN vertex", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "", Error("m.obj: line 2: a vertex (v) needs 3 finite numbers")),
        mesh_case("inf vertex", "v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n", "", Error("line 3")),
        mesh_case("short vertex", "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "", Error("line 1")),
        mesh_case("index out of range", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n", "", Error("line 4: corner `7`: vertex index 7 does not exist")),
        mesh_case("index zero", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "", Error("index 0 does not exist")),
        mesh_case("relative index too far", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", "", Error("index -4 does not exist")),
        mesh_case("two-corner face", "v 0 0 0\nv 1 0 0\nf 1 2\n", "", Error("line 3: a face needs at least 3 corners")),
        mesh_case("zero-area faces", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n", "", Error("key `file`: m.obj: all 1 triangles have zero area (each face's corners lie on a line)")),
        mesh_case("bad normal index", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n", "", Error("normal index 2 does not exist")),
        mesh_case("degenerate mesh", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n", "", Error("all 1 triangles have zero area")),
        mesh_case("mesh scaled beyond range", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "scale = 1e29\ntranslate = [1e30, 0, 0]\n", Error("beyond")),
        mesh_case("a sound mesh", "v -1 -1 0.5\nv 1 -1 0.5\nv 0 1 0.5\nf 1 2 3\n", "", Finite("rendered")),
        // Environment images.
        env_case("environment NaN pixel", exr_with(f32::NAN), Error("(x 1, y 0)")),
        // Keys a converted Mitsuba scene writes, given wrong by hand.
        Case { name: "environment filter unknown", files: vec![("s.toml", scene("[[light]]\ntype = \"environment\"\nfile = \"sky.exr\"\nfilter = \"cubic\"\n")), ("sky.exr", exr_with(1.0))], args: render(""), expect: Error("unknown value 'cubic' (nearest, bilinear)") },
        Case { name: "environment matrix not a rotation", files: vec![("s.toml", scene("[[light]]\ntype = \"environment\"\nsky = \"uniform\"\nmatrix = [2, 0, 0, 0, 1, 0, 0, 0, 1]\n"))], args: render(""), expect: Error("must be a rotation") },
        Case { name: "environment matrix and rotation_deg", files: vec![("s.toml", scene("[[light]]\ntype = \"environment\"\nsky = \"uniform\"\nmatrix = [1, 0, 0, 0, 1, 0, 0, 0, 1]\nrotation_deg = 3\n"))], args: render(""), expect: Error("give either `matrix` or `rotation_deg`") },
        scene_case("spot falloff_curve unknown", "[[light]]\ntype = \"spot\"\nposition = [0, 0, 1]\nintensity = 1\ncone_deg = 30\nfalloff_curve = \"cubic\"\n", Error("key `falloff_curve`: unknown value 'cubic' (smoothstep, linear)")),
        scene_case("checkerboard of one colour", "[[material]]\nname = \"c\"\ntype = \"diffuse\"\ncheckerboard = [[1, 0, 0]]\n", Error("expected two colours")),
        scene_case("checkerboard beyond 1", "[[material]]\nname = \"c\"\ntype = \"diffuse\"\ncheckerboard = [[1, 0, 0], [2, 0, 0]]\n", Error("each in [0, 1]")),
        scene_case("checkerboard and texture", "[[material]]\nname = \"c\"\ntype = \"diffuse\"\ncheckerboard = [[1, 0, 0], [0, 0, 0]]\ntexture = \"t.png\"\n", Error("either `texture` or `checkerboard`")),
        Case { name: "texture_wrap unknown", files: vec![("s.toml", scene("[[material]]\nname = \"c\"\ntype = \"diffuse\"\ntexture = \"t.png\"\ntexture_wrap = \"tile\"\n")), ("t.png", png_2x2())], args: render(""), expect: Error("key `texture_wrap`: unknown value 'tile' (repeat, clamp, mirror)") },
        scene_case("checkerboard_uv of 4 numbers", "[[material]]\nname = \"c\"\ntype = \"diffuse\"\ncheckerboard = [[1, 0, 0], [0, 0, 0]]\ncheckerboard_uv = [1, 0, 0, 1]\n", Error("expected 6 numbers")),
        mesh_case("mesh matrix flat", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "matrix = [1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0]\n", Error("flattens the mesh")),
        mesh_case("mesh matrix and scale", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "matrix = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0]\nscale = 2\n", Error("give either `matrix`")),
        mesh_case("mesh matrix of 9 numbers", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "matrix = [1, 0, 0, 0, 1, 0, 0, 0, 1]\n", Error("expected the 12 numbers")),
        mesh_case("mesh matrix moved", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "matrix = [0, -1, 0, 0.5, 1, 0, 0, 0, 0, 0, 1, -0.5]\n", Finite("wrote")),
        env_case("environment inf pixel", exr_with(f32::INFINITY), Error("not finite")),
        env_case("environment negative pixel", exr_with(-1.0), Error("not finite non-negative")),
        env_case("environment not an image", b"hello".to_vec(), Error("cannot read")),
        env_case("a sound environment", exr_with(2.0), Finite("rendered")),
        // Command-line values.
        Case { name: "--spp 0", files: vec![("s.toml", scene(LIGHT))], args: render("--spp 0"), expect: Error("--spp") },
        Case { name: "--passes 0", files: vec![("s.toml", scene(LIGHT))], args: render("--passes 0"), expect: Error("--passes") },
        Case { name: "--shard 0/3", files: vec![("s.toml", scene(LIGHT))], args: render("--shard 0/3"), expect: Error("K out of range") },
        Case { name: "--shard 4/3", files: vec![("s.toml", scene(LIGHT))], args: render("--shard 4/3"), expect: Error("K out of range") },
        Case { name: "--shard 2", files: vec![("s.toml", scene(LIGHT))], args: render("--shard 2"), expect: Error("no '/'") },
        Case { name: "--shard a/b", files: vec![("s.toml", scene(LIGHT))], args: render("--shard a/b"), expect: Error("not a whole number") },
        Case { name: "--target-error -1", files: vec![("s.toml", scene(LIGHT))], args: render("--target-error -1"), expect: Error("--target-error must be a number in (0, 1e30], got -1") },
        Case { name: "--shard with --time-budget", files: vec![("s.toml", scene(LIGHT))], args: render("--shard 1/2 --time-budget 5"), expect: Error("give passes, not time_budget") },
        Case { name: "--resume with nothing saved", files: vec![("s.toml", scene(LIGHT))], args: render("--resume"), expect: Error("nothing to resume") },
        Case { name: "merge a scene file", files: vec![("s.toml", scene(LIGHT))], args: args("merge s.toml -o m.exr"), expect: Error("not a grinlight partial") },
        Case { name: "--knn 0", files: vec![("s.toml", scene(LIGHT))], args: render("--knn 0"), expect: Error("--knn") },
        Case { name: "--receiver-photons 0", files: vec![("s.toml", scene(LIGHT))], args: render("--receiver-photons 0"), expect: Error("--receiver-photons") },
        Case { name: "--checkpoint 0", files: vec![("s.toml", scene(LIGHT))], args: render("--checkpoint 0"), expect: Error("--checkpoint") },
        Case { name: "--threads 100000", files: vec![("s.toml", scene(LIGHT))], args: render("--threads 100000"), expect: Error("per core") },
        Case { name: "65536 × 65536", files: vec![("s.toml", scene(LIGHT))], args: render("--width 65536 --height 65536"), expect: Error("of memory") },
        Case { name: "10^12 photons", files: vec![("s.toml", scene(LIGHT))], args: render("--photons 1000000000000"), expect: Error("of memory") },
        Case { name: "--radius -1", files: vec![("s.toml", scene(LIGHT))], args: render("--radius=-1"), expect: Error("--radius") },
        Case { name: "--time-budget nan", files: vec![("s.toml", scene(LIGHT))], args: render("--time-budget nan"), expect: Error("--time-budget") },
        Case { name: "-o the scene", files: vec![("s.toml", scene(LIGHT))], args: render("-o s.toml"), expect: Error("must end in .exr") },
        Case { name: "-o a png", files: vec![("s.toml", scene(LIGHT))], args: render("-o out.png"), expect: Error("must end in .exr") },
        Case { name: "-o into /proc", files: vec![("s.toml", scene(LIGHT))], args: render("-o /proc/x.exr"), expect: Error("cannot write") },
        Case { name: "-o over a text file", files: vec![("s.toml", scene(LIGHT)), ("notes.exr", b"my notes".to_vec())], args: render("-o notes.exr"), expect: Error("is not an EXR image") },
        Case { name: "-o a directory", files: vec![("s.toml", scene(LIGHT)), ("d.exr/keep", b"x".to_vec())], args: render("-o d.exr"), expect: Error("not a regular file") },
        Case {
            name: "receivers whose files collide",
            files: vec![("s.toml", scene(&format!(
                "{LIGHT}[[receiver]]\nname = \"a\"\ncenter = [0,0,0.5]\nsize = [1,1]\nbins = [4,4]\n\
                 [[receiver]]\nname = \"a.radial\"\ncenter = [0,0,0.6]\nsize = [1,1]\nbins = [4,4]\n"
            )))],
            args: render(""),
            expect: Error("two outputs to one file"),
        },
        Case {
            name: "trace --dir 1e300,1e300,0",
            files: vec![("s.toml", scene("[[medium]]\nname = \"l\"\nprofile = \"luneburg\"\nradius = 1\n"))],
            args: args("trace s.toml --medium l --from -2,0,0 --dir 1e300,1e300,0 --length 0.1"),
            expect: Finite("dir (0.707106781187, 0.707106781187, 0.000000000000)"),
        },
        Case {
            name: "trace --from 1e31",
            files: vec![("s.toml", scene("[[medium]]\nname = \"l\"\nprofile = \"luneburg\"\nradius = 1\n"))],
            args: args("trace s.toml --medium l --from 1e31,0,0 --dir 1,0,0 --length 1"),
            expect: Error("--from"),
        },
        Case {
            name: "trace --length 1e308",
            files: vec![("s.toml", scene("[[medium]]\nname = \"l\"\nprofile = \"luneburg\"\nradius = 1\n"))],
            args: args("trace s.toml --medium l --from 0,0,0 --dir 1,0,0 --length 1e308"),
            expect: Error("--length"),
        },
        Case {
            name: "trace --tol nan",
            files: vec![("s.toml", scene("[[medium]]\nname = \"l\"\nprofile = \"luneburg\"\nradius = 1\n"))],
            args: args("trace s.toml --medium l --from 0,0,0 --dir 1,0,0 --length 1 --tol nan"),
            expect: Error("--tol"),
        },
        Case {
            name: "trace --csv the scene",
            files: vec![("s.toml", scene("[[medium]]\nname = \"l\"\nprofile = \"luneburg\"\nradius = 1\n"))],
            args: args("trace s.toml --medium l --from 0,0,0 --dir 1,0,0 --length 1 --csv s.toml"),
            expect: Error("is an input of this run"),
        },
        Case {
            name: "trace --plot into a missing directory",
            files: vec![("s.toml", scene("[[medium]]\nname = \"l\"\nprofile = \"luneburg\"\nradius = 1\n"))],
            args: args("trace s.toml --medium l --from 0,0,0 --dir 1,0,0 --length 1 --plot no/p.png"),
            expect: Error("does not exist"),
        },
        Case {
            name: "validate --dn 0",
            files: vec![("s.toml", fiber_scene())],
            args: args("validate s.toml --dn 0"),
            expect: Error("--dn"),
        },
        Case {
            name: "validate --max-width -1",
            files: vec![("s.toml", fiber_scene())],
            args: args("validate s.toml --max-width=-1"),
            expect: Error("--max-width"),
        },
        Case {
            name: "validate --plot into a missing directory",
            files: vec![("s.toml", fiber_scene())],
            args: args("validate s.toml --plot no/p.png"),
            expect: Error("does not exist"),
        },
        Case {
            name: "validate --photons 0",
            files: vec![("s.toml", fiber_scene())],
            args: args("validate s.toml --photons 0"),
            expect: Error("--photons"),
        },
        // Extreme but valid: finite results.
        scene_case("intensity 1e30", "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nintensity = 1e30\n", Finite("rendered")),
        scene_case("no light at all", "", Finite("rendered")),
        scene_case("a dark light", "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nintensity = 0\n", Finite("rendered")),
        scene_case("light on the surface", "[[light]]\ntype = \"point\"\nposition = [0, 0, 0]\nintensity = 1\n", Finite("rendered")),
        Case { name: "a sound render with receivers", files: vec![("s.toml", scene(&receiver("size = [1, 1]\nbins = [4, 4]\n")))], args: render(""), expect: Finite("receiver 'r': flux") },
    ];
    // Odd media, meshes and spectra: a finite result in bounded time, or a precise error.
    let radial = |nodes: usize, span: f64| {
        let r: Vec<String> = (0..nodes)
            .map(|i| format!("{:e}", span * i as f64 / (nodes - 1) as f64))
            .collect();
        let n: Vec<String> = (0..nodes)
            .map(|i| format!("{:e}", 1.5 - 0.1 * (i as f64 / (nodes - 1) as f64).powi(2)))
            .collect();
        format!(
            "profile = \"radial_table\"\naxis = [0, 1, 0]\nr = [{}]\nn = [{}]",
            r.join(","),
            n.join(",")
        )
    };
    v.extend([
        ambient_case("emission without absorption", "profile = \"uniform\"\nn = 1\nemission = 1", Error("s.toml:")),
        ambient_case("emission below 0", "profile = \"uniform\"\nn = 1\nabsorption = 1\nemission = [1, -1, 1]", Error("`emission`")),
        ambient_case("emitting medium, photon mapper", "profile = \"uniform\"\nn = 1\nabsorption = 1\nemission = 1", Error("photons are sent only from lights")),
        Case {
            args: render("--integrator path"),
            ..ambient_case("huge emission in a dense medium", "profile = \"uniform\"\nn = 1\nabsorption = 1e12\nemission = 1e12", Finite("rendered"))
        },
        ambient_case("luneburg ambient of radius 1e-6", "profile = \"luneburg\"\nradius = 1e-6", Finite("rendered")),
        ambient_case("luneburg ambient of radius 1e-300", "profile = \"luneburg\"\nradius = 1e-300", Finite("rendered")),
        ambient_case("black_hole of rs 1e-160", "profile = \"black_hole\"\ncenter = [0, 0, -5]\nrs = 1e-160", Finite("rendered")),
        ambient_case("radial_table of 100 000 nodes", &radial(100_000, 0.01), Finite("rendered")),
        ambient_case("a fixed step of 1e-300", "profile = \"linear\"\nn0 = 1.0\ngradient = [0, 0.1, 0]", Error(""))
            .with_scene_replace("spp = 1", "spp = 1\ncontrol = \"fixed\"\nstep = 1e-300", "cannot move a ray"),
        mesh_case("100 000 copies of one triangle", &format!("v -1 -1 0.5\nv 1 -1 0.5\nv 0 1 0.5\n{}", "f 1 2 3\n".repeat(100_000)), "", Finite("rendered")),
        mesh_case("a vertex at 1e38", "v 0 0 0\nv 1e38 0 0\nv 0 1 0\nf 1 2 3\n", "", Error("key `file`: m.obj: vertex 2 lies at")),
        scene_case("a laser line 0.01 nm wide", "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nintensity = 1\nspectrum = { gaussian = [532, 0.01] }\n", Finite("rendered")),
        scene_case("cauchy of 100 000 terms", &format!("[[material]]\nname = \"g\"\ntype = \"dielectric\"\nior = {{ cauchy = [1.5{}] }}\n", ", 0".repeat(100_000)), Error("1 to 16 terms")),
        scene_case("spp 5e9 in the scene", "", Error("")).with_scene_replace("spp = 1", "spp = 5000000000", "must be at most 4294967295"),
        scene_case("gather 70000 in the scene", "", Error("")).with_scene_replace("gather = 1\n", "gather = 70000\n", "must be at most 65536"),
        Case { name: "--gather 70000", files: vec![("s.toml", scene(LIGHT))], args: render("--gather 70000"), expect: Error("--gather must be at most 65536, got 70000") },
        Case { name: "--shard 1/99999999999999999999", files: vec![("s.toml", scene(LIGHT))], args: render("--shard 1/99999999999999999999"), expect: Error("is more than 4294967295 shards") },
        Case { name: "render /dev/zero", files: vec![], args: args("render /dev/zero"), expect: Error("not a regular file") },
        Case { name: "merge /dev/zero", files: vec![], args: args("merge /dev/zero -o m.exr"), expect: Error("not a regular file") },
        Case { name: "a scene of 65 MiB", files: vec![("s.toml", vec![b'#'; 65 << 20])], args: render(""), expect: Error("larger than 64 MiB") },
        Case { name: "a partial of its magic line alone", files: vec![("p.partial", PARTIAL.to_vec())], args: args("merge p.partial -o m.exr"), expect: Error("p.partial: a damaged partial result (it ends inside its header)") },
        Case { name: "a partial of another version", files: vec![("p.partial", b"GRINLIGHT PARTIAL 1\nxyz".to_vec())], args: args("merge p.partial -o m.exr"), expect: Error("of file version 1") },
        Case { name: "a partial with a 4 GiB header", files: vec![("p.partial", [PARTIAL, &[0xff; 4]].concat())], args: args("merge p.partial -o m.exr"), expect: Error("a header of 4294967295 bytes") },
    ]);
    v.extend([
xml_case(
            "mitsuba: a shapegroup holding an instance of itself",
            "<shape type=\"shapegroup\" id=\"g\"><shape type=\"instance\"><ref id=\"g\"/></shape></shape><shape type=\"instance\"><ref id=\"g\"/></shape>",
            Error("s.xml:"),
        ),
                xml_case("Mitsuba: a sphere", "<shape type=\"sphere\"><point name=\"center\" value=\"0, 0, -3\"/></shape>", Finite("wrote")),
        Case {
            name: "Mitsuba: a crop beyond its film",
            files: vec![("s.xml", String::from_utf8(mitsuba("")).unwrap().replacen("<rfilter", "<integer name=\"crop_offset_x\" value=\"4\"/><integer name=\"crop_width\" value=\"6\"/><rfilter", 1).into_bytes())],
            args: args("render s.xml"),
            expect: Error("s.xml:2:"),
        },
        Case { name: "Mitsuba: malformed XML", files: vec![("s.xml", b"<scene version=\"3.0.0\"><shape".to_vec())], args: args("render s.xml"), expect: Error("s.xml:1:") },
        Case { name: "Mitsuba: not a scene", files: vec![("s.xml", b"<html></html>".to_vec())], args: args("render s.xml"), expect: Error("expected a Mitsuba <scene>, found <html>") },
        Case { name: "Mitsuba: version 0.6", files: vec![("s.xml", b"<scene version=\"0.6.0\"></scene>".to_vec())], args: args("render s.xml"), expect: Error("only Mitsuba 2 and 3 scenes") },
        Case { name: "Mitsuba: an empty file", files: vec![("s.xml", Vec::new())], args: args("render s.xml"), expect: Error("malformed XML") },
        xml_case("Mitsuba: an unknown plugin", "<shape type=\"sphere\"><bsdf type=\"hair\"/></shape>", Error("the BSDF 'hair' is not supported")),
        xml_case("Mitsuba: an unknown element", "<shape type=\"sphere\"><colour name=\"x\" value=\"1\"/></shape>", Error("unknown element <colour>")),
        xml_case("Mitsuba: $ without a default", "<shape type=\"sphere\"><float name=\"radius\" value=\"$r\"/></shape>", Error("'$r' has no value")),
        xml_case("Mitsuba: a missing mesh", "<shape type=\"obj\"><string name=\"filename\" value=\"no.obj\"/></shape>", Error("'no.obj' not found")),
        xml_case("Mitsuba: a NaN radius", "<shape type=\"sphere\"><float name=\"radius\" value=\"nan\"/></shape>", Error("is not a number")),
        xml_case("Mitsuba: a huge radius", "<shape type=\"sphere\"><float name=\"radius\" value=\"1e300\"/></shape>", Error("as converted, shape[0].radius")),
        xml_case("Mitsuba: a negative radius", "<shape type=\"sphere\"><float name=\"radius\" value=\"-1\"/></shape>", Error("shape[0].radius")),
        xml_case("Mitsuba: a ref to nothing", "<shape type=\"sphere\"><ref id=\"nothing\"/></shape>", Error("no object has this id")),
        xml_case("Mitsuba: a spectrum that overflows", "<shape type=\"sphere\"><bsdf type=\"diffuse\"><spectrum name=\"reflectance\" value=\"400:1e308, 700:1e308\"/></bsdf></shape>", Error("not a finite number")),
        xml_case("Mitsuba: a light's spectrum that overflows", "<emitter type=\"point\"><spectrum name=\"intensity\" value=\"400:1e308, 700:1e308\"/></emitter>", Error("not a finite number")),
        xml_case("Mitsuba: a spectrum of negative values", "<shape type=\"sphere\"><bsdf type=\"diffuse\"><spectrum name=\"reflectance\" value=\"400:-5, 700:-1\"/></bsdf></shape>", Finite("wrote")),
        xml_case("Mitsuba: a zero rotation axis", "<shape type=\"sphere\"><transform name=\"to_world\"><rotate angle=\"30\"/></transform></shape>", Error("the axis is zero")),
        xml_case("Mitsuba: a flat cube", "<shape type=\"cube\"><transform name=\"to_world\"><scale x=\"0\"/><rotate y=\"1\" angle=\"30\"/></transform></shape>", Error("flattens the cube")),
        Case {
            name: "Mitsuba: an include cycle",
            files: vec![("s.xml", mitsuba("<include filename=\"a.xml\"/>")), ("a.xml", b"<scene version=\"3.0.0\"><include filename=\"a.xml\"/></scene>".to_vec())],
            args: args("render s.xml"),
            expect: Error("a cycle"),
        },
        pbrt_case("pbrt: a sphere", "Shape \"sphere\"", Finite("wrote")),
        pbrt_case(
            "pbrt: an object placed 10⁵ times",
            &format!(
                "ObjectBegin \"o\"\nShape \"trianglemesh\" \"point3 P\" [{}] \"integer indices\" [0 1 2]\nObjectEnd\n{}",
                "0 1 2 ".repeat(20_000),
                "ObjectInstance \"o\"\n".repeat(100_000)
            ),
            Error("100000 object instances write their objects'"),
        ),
        pbrt_case("pbrt: a NaN translation", "Translate nan 0 0\nShape \"sphere\"", Error("s.pbrt:9:11: Translate: expected 3 numbers, found 'nan'")),
        pbrt_case("pbrt: an infinite radius", "Shape \"sphere\" \"float radius\" inf", Error("s.pbrt:9:31: expected a number, found 'inf'")),
        pbrt_case("pbrt: a huge radius", "Shape \"sphere\" \"float radius\" 1e300", Error("as converted, shape[0].radius")),
        pbrt_case("pbrt: a flat mesh", "Scale 1 0 1\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]", Error("flattens the mesh")),
        pbrt_case("pbrt: an index past the points", "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 99]", Error("whole numbers from 0 to 2")),
        pbrt_case("pbrt: a zero rotation axis", "Rotate 30 0 0 0\nShape \"sphere\"", Error("the axis has no length")),
        pbrt_case("pbrt: a flat sphere", "Scale 0 0 0\nShape \"sphere\"", Error("scales unevenly or shears the sphere")),
        pbrt_case("pbrt: an unknown directive", "Sphere 1", Error("'Sphere' is not a pbrt-v4 directive")),
        pbrt_case("pbrt: a parameter without a value", "Shape \"sphere\" \"float radius\"", Error("no value follows")),
        pbrt_case("pbrt: AttributeEnd alone", "AttributeEnd", Error("AttributeEnd without AttributeBegin")),
        Case { name: "pbrt: an empty file", files: vec![("s.pbrt", Vec::new())], args: args("render s.pbrt"), expect: Error("no WorldBegin") },
        Case { name: "pbrt: binary junk", files: vec![("s.pbrt", vec![0xff, 0xfe, 0x00, 0x9c])], args: args("render s.pbrt"), expect: Error("not UTF-8 text") },
        Case { name: "pbrt: damaged gzip", files: vec![("s.pbrt", vec![0x1f, 0x8b, 0x08, 0x00])], args: args("render s.pbrt"), expect: Error("the gzip-compressed data is damaged") },
        Case { name: "pbrt: -D", files: vec![("s.pbrt", pbrt(""))], args: args("render s.pbrt -D r=1"), expect: Error("a pbrt scene has no $parameters") },
        Case { name: "convert over a user's file", files: vec![("s.xml", mitsuba("")), ("out.toml", b"mine".to_vec())], args: args("convert s.xml -o out.toml"), expect: Error("out.toml") },
        Case { name: "convert to its own input", files: vec![("s.xml", mitsuba(""))], args: args("convert s.xml -o s.xml"), expect: Error("should end in .toml") },
        Case { name: "-D without =", files: vec![("s.xml", mitsuba(""))], args: args("render s.xml -D r"), expect: Error("expected NAME=VALUE") },
        Case { name: "-D on a grinlight scene", files: vec![("s.toml", scene(LIGHT))], args: render("-D r=1"), expect: Error("apply to scenes of other renderers") },
    ]);
    v.push(Case {
        name: "trace --dir 0,0,0",
        files: vec![(
            "s.toml",
            scene("[[medium]]\nname = \"l\"\nprofile = \"luneburg\"\nradius = 1\n"),
        )],
        args: args("trace s.toml --medium l --from 0,0,0 --dir 0,0,0 --length 1"),
        expect: Error("--dir must be a non-zero vector"),
    });
    v
}

/// The GRIN fiber of `scenes/fiber_led.toml` with few photons.
fn fiber_scene() -> Vec<u8> {
    std::fs::read_to_string("scenes/fiber_led.toml")
        .unwrap()
        .replace("receiver_photons = 1000000", "receiver_photons = 2000")
        .into_bytes()
}

impl Case {
    /// The case with `from` replaced by `to` in its scene, expecting an error containing
    /// `needle`.
    fn with_scene_replace(mut self, from: &str, to: &str, needle: &'static str) -> Case {
        let text = String::from_utf8(self.files[0].1.clone()).unwrap();
        assert!(text.contains(from), "{}: no '{from}'", self.name);
        self.files[0].1 = text.replacen(from, to, 1).into_bytes();
        self.expect = Expect::Error(needle);
        self
    }

    /// The case without the file `name`, expecting an error containing `needle`.
    fn without_file(mut self, name: &str, needle: &'static str) -> Case {
        self.files.retain(|(n, _)| *n != name);
        self.expect = Expect::Error(needle);
        self
    }
}

/// Runs the binary in `dir` with `args`, killing it after `limit`.
fn run(dir: &Path, args: &[String], limit: Duration) -> (Option<i32>, String, String, Duration) {
    let start = Instant::now();
    let mut child = Command::new(env!("CARGO_BIN_EXE_grinlight"))
        .args(args)
        .current_dir(dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run grinlight");
    loop {
        if child.try_wait().unwrap().is_some() || start.elapsed() > limit {
            break;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    let _ = child.kill();
    let out = child.wait_with_output().unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        start.elapsed(),
    )
}

/// Every number in every EXR layer and CSV cell written in `dir` (besides the `inputs`) is
/// finite.
fn outputs_finite(dir: &Path, inputs: &[(&str, Vec<u8>)]) -> Result<usize, String> {
    let mut checked = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path: PathBuf = entry.unwrap().path();
        if inputs.iter().any(|(n, _)| path.ends_with(n)) {
            continue;
        }
        match path.extension().and_then(|e| e.to_str()) {
            Some("exr") => {
                // Every layer the file holds (layers nothing wrote are left out; beauty never).
                for layer in [
                    "beauty",
                    "direct",
                    "caustic",
                    "secondary",
                    "emitted",
                    "albedo",
                    "normal",
                    grinlight::film::ERROR,
                ] {
                    let px = match grinlight::compare::read_exr_layer(&path, Some(layer)) {
                        Ok(plane) => plane.pixels,
                        Err(e) if layer != "beauty" && e.to_string().contains("no layer") => {
                            continue
                        }
                        Err(e) => return Err(e.to_string()),
                    };
                    if let Some(p) = px.iter().find(|p| !p.iter().all(|c| c.is_finite())) {
                        return Err(format!("{}: layer {layer} holds {p:?}", path.display()));
                    }
                }
                checked += 1;
            }
            Some("csv") => {
                let text = std::fs::read_to_string(&path).unwrap();
                // grinlight's comment line, the header, then the numbers.
                for cell in text.lines().skip(2).flat_map(|l| l.split(',')) {
                    if !cell.parse::<f64>().is_ok_and(f64::is_finite) {
                        return Err(format!("{}: cell '{cell}'", path.display()));
                    }
                }
                checked += 1;
            }
            _ => {}
        }
    }
    Ok(checked)
}

#[test]
fn hostile_input_ends_in_a_clear_error_or_a_finite_result() {
    let cases = cases();
    assert!(cases.len() >= 60, "{} cases", cases.len());
    println!("{} hostile cases", cases.len());
    let root = std::env::temp_dir().join(format!("grinlight-hostile-{}", std::process::id()));
    let mut failures = Vec::new();
    for (k, case) in cases.iter().enumerate() {
        let dir = root.join(format!("case{k}"));
        std::fs::create_dir_all(&dir).unwrap();
        for (name, content) in &case.files {
            let path = dir.join(name);
            std::fs::create_dir_all(path.parent().unwrap()).unwrap();
            std::fs::write(path, content).unwrap();
        }
        let (code, stdout, stderr, took) = run(&dir, &case.args, Duration::from_secs(10));
        let name = case.name;
        let problem = if took >= Duration::from_secs(10) {
            Some(format!("still running after {took:?}"))
        } else if stderr.contains("panicked") {
            Some(format!("panicked: {stderr}"))
        } else {
            match &case.expect {
                Expect::Error(needle) => match code {
                    Some(1) | Some(2) if stderr.contains(needle) && stderr.contains("error") => {
                        None
                    }
                    _ => Some(format!("exit {code:?}, stderr '{stderr}' lacks '{needle}'")),
                },
                Expect::Finite(needle) => {
                    if code != Some(0) {
                        Some(format!("exit {code:?}: {stderr}"))
                    } else if !stdout.contains(needle) {
                        Some(format!("stdout lacks '{needle}': {stdout}"))
                    } else if stdout.contains("NaN") || stdout.contains("inf ") {
                        Some(format!("non-finite report: {stdout}"))
                    } else {
                        outputs_finite(&dir, &case.files).err()
                    }
                }
            }
        };
        if let Some(p) = problem {
            failures.push(format!("{name}: {p}"));
        }
        // No case may leave a temporary file behind.
        let leftovers: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .filter_map(|e| e.ok())
            .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
            .collect();
        if !leftovers.is_empty() {
            failures.push(format!("{name}: left {leftovers:?}"));
        }
    }
    let _ = std::fs::remove_dir_all(&root);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A pipe or a huge file given as an input: every input must be a regular file, so a FIFO
/// given as a mesh, texture, environment, grid, VDB file, scene or partial is refused at once
/// (reading it would block forever), and a partial's header is checked before its payload is
/// read (a 3 GB sparse file given as a partial is refused by its header, not read whole).
#[test]
fn pipes_and_huge_files_are_refused_as_inputs() {
    let root = std::env::temp_dir().join(format!("grinlight-fifo-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    std::fs::create_dir_all(&root).unwrap();
    let light = format!("{BASE}{LIGHT}");
    let cases: Vec<(&str, String, Vec<String>)> = vec![
        ("mesh", format!("{light}[[shape]]\ntype = \"mesh\"\nfile = \"pipe\"\nmaterial = \"white\"\n"), render("")),
        ("texture", format!("{light}[[material]]\nname = \"t\"\ntype = \"diffuse\"\ntexture = \"pipe\"\n"), render("")),
        ("environment", format!("{light}[[light]]\ntype = \"environment\"\nfile = \"pipe\"\n"), render("")),
        ("grid file", format!("{light}[[medium]]\nname = \"g\"\nprofile = \"grid\"\nbounds = [[0,0,0],[1,1,1]]\ndims = [2,2,2]\nfile = \"pipe\"\n"), render("")),
        ("vdb file", format!("{light}[[medium]]\nname = \"g\"\nprofile = \"grid\"\nfile = \"pipe\"\n"), render("")),
        ("scene", light.clone(), args("render pipe")),
        ("partial", light.clone(), args("merge pipe -o m.exr")),
        // A pbrt scene that is a pipe, and one that includes a pipe.
        ("pbrt scene", light.clone(), args("render pipe.pbrt")),
        ("pbrt include", light.clone(), args("render s.pbrt")),
        // A Mitsuba scene that is a pipe, and one that includes a pipe.
        ("xml scene", light.clone(), args("render pipe.xml")),
        ("xml include", light.clone(), args("render s.xml")),
    ];
    let mut failures = Vec::new();
    for (k, (what, scene_text, arguments)) in cases.iter().enumerate() {
        let dir = root.join(format!("case{k}"));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("s.toml"), scene_text).unwrap();
        std::fs::write(dir.join("s.pbrt"), "Include \"pipe.pbrt\"\n").unwrap();
        std::fs::write(
            dir.join("s.xml"),
            "<scene version=\"3.0.0\"><include filename=\"pipe.xml\"/></scene>\n",
        )
        .unwrap();
        for name in ["pipe", "pipe.pbrt", "pipe.xml"] {
            let made = Command::new("mkfifo").arg(dir.join(name)).status().unwrap();
            assert!(made.success(), "mkfifo");
        }
        let (code, _, stderr, took) = run(&dir, arguments, Duration::from_secs(10));
        if took >= Duration::from_secs(10)
            || code != Some(1)
            || !stderr.contains("not a regular file")
        {
            failures.push(format!("{what}: exit {code:?} after {took:?}: {stderr}"));
        }
    }
    // A sparse 2 GB density file (one line of zero bytes): refused after its first MiB, with a
    // message of a few lines, not echoing it.
    let dir = root.join("density");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("s.toml"),
        format!(
            "{light}ambient = \"fog\"\n[[medium]]\nname = \"fog\"\nprofile = \"uniform\"\nn = 1\n\
             scattering = 0.1\ndensity_bounds = [[-1, -1, -1], [1, 1, 1]]\n\
             density_dims = [4, 4, 4]\ndensity_file = \"d.txt\"\n"
        ),
    )
    .unwrap();
    std::fs::File::create(dir.join("d.txt"))
        .unwrap()
        .set_len(2 << 30)
        .unwrap();
    let (code, _, stderr, took) = run(&dir, &render(""), Duration::from_secs(10));
    if took >= Duration::from_secs(10)
        || code != Some(1)
        || !stderr.contains("line 1 is longer than 1 MiB")
        || stderr.len() > 2000
    {
        failures.push(format!(
            "sparse density file: exit {code:?} after {took:?}: {} bytes of error",
            stderr.len()
        ));
    }
    // A sparse 3 GB file that starts like a partial: refused by its header's length.
    let dir = root.join("sparse");
    std::fs::create_dir_all(&dir).unwrap();
    let file = std::fs::File::create(dir.join("big.partial")).unwrap();
    use std::io::Write;
    (&file)
        .write_all(b"GRINLIGHT PARTIAL 3\n\x10\x00\x00\x00")
        .unwrap();
    file.set_len(3 << 30).unwrap();
    let (code, _, stderr, took) = run(
        &dir,
        &args("merge big.partial -o m.exr"),
        Duration::from_secs(10),
    );
    if took >= Duration::from_secs(10)
        || code != Some(1)
        || !stderr.contains(
            "big.partial: a damaged partial result (its header's checksum does not match)",
        )
    {
        failures.push(format!(
            "sparse partial: exit {code:?} after {took:?}: {stderr}"
        ));
    }
    let _ = std::fs::remove_dir_all(&root);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
