//! pbrt-v4 scenes brought in: the Cornell box written for pbrt (`scenes/pbrt/`) rendered from
//! its file against Mitsuba 3's render of its XML twin, the two converted to the same camera,
//! light and materials; pbrt's left-handed camera, its field of view, its light units and
//! `power`, its materials' defaults and roughness as pbrt-v4's source computes them; what
//! cannot be converted exactly refused by file, line and column.

use super::import::{
    compare, convert, dir, f, grinlight_blocks, grinlight_layer_blocks, reference, tables, vec3,
    write,
};
use grinlight::import::{import, load_description, ImportOptions};
use std::f64::consts::PI;
use std::path::Path;
use toml::Value;

/// A pbrt scene of a camera (`camera`: statements before `Camera`, which follows; a box
/// filter; a film of 200 × 100) and a world `body`.
fn scene(camera: &str, body: &str) -> String {
    format!(
        "{camera}\nCamera \"perspective\" \"float fov\" [ 30 ]\nFilm \"rgb\" \"integer xresolution\" [ 200 ] \
         \"integer yresolution\" [ 100 ]\nPixelFilter \"box\"\nWorldBegin\n{body}\n"
    )
}

/// The converted table of `body` under the camera `camera`.
fn converted(name: &str, camera: &str, body: &str) -> toml::Table {
    let d = dir(&format!("pbrt-{name}"));
    let p = write(&d, "s.pbrt", &scene(camera, body));
    convert(&p, &ImportOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// pbrt's homogeneous medium without `sigma_a` absorbs its default (0.0011, 0.0024, 0.014)
/// per mm⁻¹ times `scale`: converted channel by channel.
#[test]
fn a_pbrt_medium_absorbs_channel_by_channel() {
    let t = converted(
        "absorption",
        "",
        "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"float scale\" [ 2 ]\n\
         Material \"dielectric\"\nMediumInterface \"m\" \"\"\nShape \"sphere\"",
    );
    let media = tables(&t, "medium");
    assert!(close(
        vec3(&media[0]["absorption"]),
        [0.0022, 0.0048, 0.028],
        1e-15
    ));
}

fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    (0..3).all(|i| (a[i] - b[i]).abs() <= tol)
}

#[test]
fn the_pbrt_cornell_box_and_window_render_as_mitsuba_renders_their_xml_twins() {
    // The test of the Mitsuba scenes, on the pbrt twins: 192 block-channels, 32 runs (P(|t| >
    // 5) ≈ 0.4 % for the image), image means within 1 %. The Cornell box of triangle meshes;
    // a thin pane across the view of two balls under a uniform infinite light and a sphere
    // lamp.
    for case in ["cornell_box", "window"] {
        let scene = format!("scenes/pbrt/{case}.pbrt");
        let ours = grinlight_blocks(Path::new(&scene), &[], 32, 16);
        let (worst, ratio) = compare(&ours, &reference(case));
        eprintln!("pbrt {case}: largest block z {worst:.2}, mean ratio {ratio:.5}");
        assert!(
            worst < 5.0,
            "{case}: a block differs by {worst:.2} standard errors"
        );
        assert!((ratio - 1.0).abs() < 0.01, "{case}: mean ratio {ratio}");
    }
}

/// pbrt-v4's textures (`imagemap` read by point and bilinearly, with scales and offsets, and a
/// checkerboard) on a turned sphere, an open cylinder and a bilinear patch, converted with
/// their approximations (pbrt's MIP level and filtered checkerboard; the 4 × 4 image is
/// magnified everywhere), render as Mitsuba renders the XML twin: 192 block-channels, 32 runs,
/// every block within 5 standard errors, the image mean within 1 %. Read in grinlight's own
/// coordinates (no `uv_frame` on the sphere and the cylinder), a block reads z 770.
#[test]
fn pbrt_textures_render_as_mitsuba_renders_their_xml_twin() {
    let options = ImportOptions {
        approximate: true,
        ..Default::default()
    };
    let scene = Path::new("scenes/pbrt/textured_shapes.pbrt");
    let ours = grinlight_layer_blocks(scene, &options, 32, 16, false, &["beauty"]).remove(0);
    let (worst, ratio) = compare(&ours, &reference("textured_shapes"));
    eprintln!("pbrt textured_shapes: largest block z {worst:.2}, mean ratio {ratio:.5}");
    assert!(worst < 5.0, "a block differs by {worst:.2} standard errors");
    assert!((ratio - 1.0).abs() < 0.01, "mean ratio {ratio}");
    let refused = match import(scene, &ImportOptions::default()) {
        Ok(_) => panic!("converted exactly"),
        Err(e) => e.to_string(),
    };
    assert!(
        refused.contains("textured_shapes.pbrt:26:1") && refused.contains("MIP level"),
        "{refused}"
    );
}

#[test]
fn the_pbrt_mesh_lights_render_as_mitsuba_renders_their_xml_twin() {
    // An icosphere lamp given in the file and a PLY ribbon turned inside out
    // (ReverseOrientation): the lights convert to the XML twin's placements and sides, and
    // the scene renders as Mitsuba renders the XML (the test of the Mitsuba scenes' bars).
    let options = ImportOptions::default();
    let pbrt = convert(Path::new("scenes/pbrt/mesh_lights.pbrt"), &options).unwrap();
    let xml = convert(Path::new("scenes/mitsuba/mesh_lights.xml"), &options).unwrap();
    let (a, b) = (tables(&pbrt, "light"), tables(&xml, "light"));
    assert_eq!((a.len(), b.len()), (2, 2));
    for (a, b) in a.iter().zip(&b) {
        for key in ["type", "radiance", "matrix", "flip"] {
            assert_eq!(a.get(key), b.get(key), "{key}");
        }
    }
    assert_eq!(a[1]["flip"].as_bool(), Some(true), "the ribbon emits down");
    let ours = grinlight_blocks(Path::new("scenes/pbrt/mesh_lights.pbrt"), &[], 32, 16);
    let (worst, ratio) = compare(&ours, &reference("mesh_lights"));
    eprintln!("pbrt mesh_lights: largest block z {worst:.2}, mean ratio {ratio:.5}");
    assert!(worst < 5.0, "a block differs by {worst:.2} standard errors");
    assert!((ratio - 1.0).abs() < 0.01, "mean ratio {ratio}");
}

#[test]
fn a_pbrt_mesh_light_emits_where_pbrt_says_or_is_refused() {
    let d = dir("pbrt-mesh-light");
    // Three triangles of the plane y = 1 wound to face up (+y), the last four times the size,
    // under a camera mirrored as the usual `Scale -1 1 1` mirrors it (the scene keeps its
    // coordinates: a camera without it sees the world mirrored, and the converted scene is,
    // every winding turned with it).
    let mesh = |extra: &str, normals: &str| {
        scene(
            "Scale -1 1 1",
            &format!(
                "AttributeBegin\n{extra}\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\n\
                 Material \"diffuse\" \"rgb reflectance\" [0 0 0]\n\
                 Shape \"trianglemesh\" \"point3 P\" [0 1 0  0 1 1  1 1 0  2 1 0  2 1 1  3 1 0  4 1 0  4 1 2  6 1 0]\n\
                 \"integer indices\" [0 1 2  3 4 5  6 7 8] {normals}\nAttributeEnd"
            ),
        )
    };
    let light = |text: &str| -> Result<toml::Table, String> {
        let p = write(&d, "s.pbrt", text);
        convert(&p, &ImportOptions::default())
            .map(|t| tables(&t, "light")[0].clone())
            .map_err(|e| e.to_string())
    };
    let plain = light(&mesh("", "")).unwrap();
    assert_eq!(plain["type"].as_str(), Some("mesh"));
    assert_eq!(plain.get("flip"), None);
    // Seen by pbrt's own left-handed camera the scene converts mirrored in x: each winding
    // turns, and the light's side with `flip`.
    let seen_mirrored = mesh("", "").replacen("Scale -1 1 1", "", 1);
    assert_eq!(light(&seen_mirrored).unwrap()["flip"].as_bool(), Some(true));
    // ReverseOrientation, or a mirroring transform, turns pbrt's normal over; both turn it
    // back.
    let reversed = light(&mesh("ReverseOrientation", "")).unwrap();
    assert_eq!(reversed["flip"].as_bool(), Some(true));
    let mirrored = light(&mesh("Scale 1 1 -1", "")).unwrap();
    assert_eq!(mirrored["flip"].as_bool(), Some(true));
    let both = light(&mesh("ReverseOrientation\nScale 1 1 -1", "")).unwrap();
    assert_eq!(both.get("flip"), None);
    // Shading normals decide the side: pointing down, against the winding.
    let down =
        "\"normal N\" [0 -1 0  0 -1 0  0 -1 0  0 -1 0  0 -1 0  0 -1 0  0 -1 0  0 -1 0  0 -1 0]";
    assert_eq!(
        light(&mesh("", down)).unwrap()["flip"].as_bool(),
        Some(true)
    );
    // One corner's normal against the others': refused.
    let split = down.replacen("0 -1 0", "0 1 0", 1);
    let message = light(&mesh("", &split)).unwrap_err();
    assert!(message.contains("emit on different sides"), "{message}");
    // pbrt's `power` is each triangle's: with triangles of different areas their radiances
    // differ.
    let powered = mesh("", "").replace("\"rgb L\" [1 1 1]", "\"float power\" [10]");
    let message = light(&powered).unwrap_err();
    assert!(message.contains("different areas"), "{message}");
}

#[test]
fn the_pbrt_and_mitsuba_cornell_boxes_convert_to_the_same_camera_light_and_materials() {
    let options = ImportOptions::default();
    let pbrt = convert(Path::new("scenes/pbrt/cornell_box.pbrt"), &options).unwrap();
    let xml = convert(Path::new("scenes/mitsuba/cornell_box.xml"), &options).unwrap();
    for key in ["camera", "render"] {
        let (a, b) = (pbrt[key].as_table().unwrap(), xml[key].as_table().unwrap());
        assert_eq!(
            a.keys().collect::<Vec<_>>(),
            b.keys().collect::<Vec<_>>(),
            "{key}"
        );
        for (k, v) in a {
            match v {
                Value::Array(_) => assert!(close(vec3(v), vec3(&b[k]), 1e-12), "{key}.{k}"),
                Value::Float(x) => assert!((x - f(&b[k])).abs() <= 1e-12, "{key}.{k}"),
                other => assert_eq!(other, &b[k], "{key}.{k}"),
            }
        }
    }
    assert_eq!(tables(&pbrt, "material"), tables(&xml, "material"));
    // The light: the same radiance, corners and facing (its corners may start elsewhere).
    let (a, b) = (tables(&pbrt, "light"), tables(&xml, "light"));
    assert_eq!((a.len(), b.len()), (1, 1));
    assert_eq!(a[0]["radiance"], b[0]["radiance"]);
    let corners = |t: &toml::Table| -> Vec<[f64; 3]> {
        t["vertices"].as_array().unwrap().iter().map(vec3).collect()
    };
    let normal = |v: &[[f64; 3]]| {
        let (e1, e2) = (
            glam::DVec3::from(v[1]) - glam::DVec3::from(v[0]),
            glam::DVec3::from(v[3]) - glam::DVec3::from(v[0]),
        );
        e1.cross(e2).normalize()
    };
    let (ca, cb) = (corners(a[0]), corners(b[0]));
    for c in &ca {
        assert!(cb.iter().any(|d| close(*c, *d, 1e-12)), "corner {c:?}");
    }
    assert!((normal(&ca) - normal(&cb)).length() < 1e-12);
    assert!(normal(&ca).y < -0.999, "the light faces down");
}

#[test]
fn pbrts_left_handed_camera_is_converted_with_x_negated() {
    // pbrt shows the camera's +x, cross(up, forward), on the image's right: for this LookAt
    // that is the world's −x. Converted with x negated, the sphere the file puts at x = −1 is
    // at x = +1, right of centre in grinlight's view as in pbrt's.
    let body =
        "AttributeBegin\nTranslate -1 0 0\nShape \"sphere\" \"float radius\" [ 0.5 ]\nAttributeEnd";
    let plain = converted("plain", "LookAt 0 0 5  0 0 0  0 1 0", body);
    let shapes = tables(&plain, "shape");
    assert!(close(vec3(&shapes[0]["center"]), [1.0, 0.0, 0.0], 1e-12));
    let camera = plain["camera"].as_table().unwrap();
    assert!(close(vec3(&camera["position"]), [0.0, 0.0, 5.0], 1e-12));
    assert!(close(vec3(&camera["look_at"]), [0.0, 0.0, 4.0], 1e-12));
    // pbrt's fov spans the shorter side: here the height of a 2 : 1 image.
    let fov_x = 2.0 * (2.0 * (15f64).to_radians().tan()).atan().to_degrees();
    assert!((f(&camera["fov_x_deg"]) - fov_x).abs() < 1e-12);
    let d = dir("pbrt-plain-note");
    let p = write(&d, "s.pbrt", &scene("LookAt 0 0 5  0 0 0  0 1 0", body));
    let told = import(&p, &ImportOptions::default())
        .unwrap()
        .notes
        .join("\n");
    assert!(told.contains("x is negated"), "{told}");
    // The usual `Scale -1 1 1` makes pbrt's camera right-handed: coordinates are kept.
    let mirrored = converted("mirrored", "Scale -1 1 1\nLookAt 0 0 5  0 0 0  0 1 0", body);
    assert!(close(
        vec3(&tables(&mirrored, "shape")[0]["center"]),
        [-1.0, 0.0, 0.0],
        1e-12
    ));
    // Rendered: the sphere (lit by a light at the camera) is right of centre.
    let d = dir("pbrt-handed");
    let p = write(
        &d,
        "s.pbrt",
        &format!(
            "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 30 ]\nFilm \"rgb\" \
             \"integer xresolution\" [ 16 ] \"integer yresolution\" [ 8 ]\nPixelFilter \"box\"\n\
             Sampler \"independent\" \"integer pixelsamples\" [ 4 ]\nWorldBegin\nLightSource \"point\" \
             \"point3 from\" [ 0 0 5 ] \"rgb I\" [ 20 20 20 ]\n{body}\n"
        ),
    );
    let (description, mut settings) =
        grinlight::import::load_description(&p, &ImportOptions::default()).unwrap();
    settings.threads = 1;
    let image = grinlight::render::render(&description.build(), &settings, &())
        .unwrap()
        .0
        .layer("beauty")
        .unwrap();
    let half = |right: bool| -> f64 {
        image
            .iter()
            .enumerate()
            .filter(|(i, _)| (i % 16 >= 8) == right)
            .map(|(_, p)| p[0] as f64)
            .sum()
    };
    assert!(
        half(true) > 0.0 && half(false) == 0.0,
        "{} left, {} right",
        half(false),
        half(true)
    );
}

#[test]
fn pbrts_light_units_and_power_convert_as_pbrt_v4_computes_them() {
    let camera = "Scale -1 1 1\nLookAt 0 0 5  0 0 0  0 1 0";
    let t = converted(
        "lights",
        camera,
        "LightSource \"point\" \"rgb I\" [ 1 2 3 ] \"float scale\" 2 \"point3 from\" [ 1 2 3 ]\n\
         LightSource \"point\" \"rgb I\" [ 1 1 1 ] \"float power\" 100\n\
         LightSource \"spot\" \"rgb I\" [ 1 1 1 ] \"float power\" 10 \"float coneangle\" 40 \
         \"float conedeltaangle\" 10 \"point3 from\" [ 0 1 0 ] \"point3 to\" [ 0 0 0 ]\n\
         LightSource \"distant\" \"rgb L\" [ 1 1 1 ] \"float illuminance\" 5 \"point3 from\" [ 0 1 0 ] \
         \"point3 to\" [ 0 0 0 ]\n\
         LightSource \"infinite\" \"rgb L\" [ 1 1 1 ] \"float illuminance\" 3\n\
         AttributeBegin\nMaterial \"diffuse\" \"rgb reflectance\" [ 0 0 0 ]\n\
         AreaLightSource \"diffuse\" \"rgb L\" [ 1 1 1 ] \"float power\" 6\n\
         Shape \"trianglemesh\" \"point3 P\" [ 0 0 0  2 0 0  2 3 0  0 3 0 ] \"integer indices\" [ 0 1 2  0 2 3 ]\n\
         Shape \"bilinearmesh\" \"point3 P\" [ 0 0 1  2 0 1  0 3 1  2 3 1 ]\n\
         Translate 0 0 2\nShape \"disk\" \"float radius\" 0.5\n\
         Translate 0 0 3\nShape \"sphere\" \"float radius\" 0.25\nAttributeEnd",
    );
    let lights = tables(&t, "light");
    let value = |i: usize, key: &str| vec3(&lights[i][key]);
    assert!(close(value(0, "intensity"), [2.0, 4.0, 6.0], 1e-12));
    assert!(close(value(0, "position"), [1.0, 2.0, 3.0], 1e-12));
    // A point light's power: I = Φ/4π.
    assert!(close(value(1, "intensity"), [100.0 / (4.0 * PI); 3], 1e-12));
    // A spot light's: Φ/(2π((1 − cos start) + (cos start − cos end)/2)); the smoothstep falloff.
    let (end, start) = (40f64.to_radians().cos(), 30f64.to_radians().cos());
    let spot = 10.0 / (2.0 * PI * ((1.0 - start) + 0.5 * (start - end)));
    assert!(close(value(2, "intensity"), [spot; 3], 1e-12));
    assert!(close(value(2, "direction"), [0.0, -1.0, 0.0], 1e-12));
    assert_eq!(
        (f(&lights[2]["cone_deg"]), f(&lights[2]["falloff_deg"])),
        (40.0, 30.0)
    );
    assert_eq!(lights[2]["falloff_curve"].as_str(), Some("smoothstep"));
    // A distant light's illuminance multiplies its L; it travels from `from` to `to`.
    assert!(close(value(3, "irradiance"), [5.0; 3], 1e-12));
    assert!(close(value(3, "direction"), [0.0, -1.0, 0.0], 1e-12));
    // An area light's power is each triangle's: L = Φ/(π A) with A half the rectangle's 6.
    assert!(close(value(4, "radiance"), [6.0 / (PI * 3.0); 3], 1e-12));
    // One bilinear patch is one light: A = 6.
    assert!(close(value(5, "radiance"), [6.0 / (PI * 6.0); 3], 1e-12));
    // A disk: A = π r², facing +z (its winding's side).
    assert!(close(
        value(6, "radiance"),
        [6.0 / (PI * PI * 0.25); 3],
        1e-12
    ));
    assert!(close(value(6, "normal"), [0.0, 0.0, 1.0], 1e-12));
    assert!(close(value(6, "center"), [0.0, 0.0, 2.0], 1e-12));
    // The quads face their triangles' and patch's +z.
    for i in [4, 5] {
        let v: Vec<glam::DVec3> = lights[i]["vertices"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| glam::DVec3::from(vec3(x)))
            .collect();
        assert!((v[1] - v[0]).cross(v[3] - v[0]).z > 0.0, "light {i}");
    }
    // A sphere: A = 4π r², emitting outward.
    assert_eq!(lights[7]["type"].as_str(), Some("sphere"));
    assert!(close(
        value(7, "radiance"),
        [6.0 / (PI * 4.0 * PI * 0.0625); 3],
        1e-12
    ));
    assert!(close(value(7, "center"), [0.0, 0.0, 5.0], 1e-12));
    assert_eq!(f(&lights[7]["radius"]), 0.25);
    // The infinite light's illuminance E: L = E/π.
    assert!(close(value(8, "radiance"), [3.0 / PI; 3], 1e-12));
}

#[test]
fn pbrts_materials_media_and_settings_take_pbrt_v4s_defaults() {
    let camera = "Scale -1 1 1\nLookAt 0 0 5  0 0 0  0 1 0";
    let t = converted(
        "materials",
        camera,
        "Shape \"sphere\"\n\
         Material \"dielectric\" \"float roughness\" 0.09\nShape \"sphere\"\n\
         Material \"dielectric\" \"float roughness\" 0.09 \"bool remaproughness\" false\nShape \"sphere\"\n\
         Material \"conductor\"\nShape \"sphere\"\n\
         Material \"conductor\" \"spectrum eta\" \"metal-Au-eta\" \"spectrum k\" \"metal-Au-k\"\nShape \"sphere\"\n\
         Material \"conductor\" \"rgb eta\" [ 0.2 0.3 0.4 ] \"rgb k\" [ 3 2 1 ]\nShape \"sphere\"\n\
         MakeNamedMedium \"smoke\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [ 0.5 0.5 0.5 ] \
         \"rgb sigma_s\" [ 1 2 3 ] \"float scale\" 2 \"float g\" 0.3\n\
         Material \"dielectric\" \"float eta\" 1.33\nMediumInterface \"smoke\" \"\"\nShape \"sphere\"\n\
         MediumInterface \"\" \"\"\n\
         Material \"thindielectric\" \"float eta\" 1.52\nShape \"sphere\"\n\
         Material \"thindielectric\"\nShape \"sphere\"",
    );
    let render = t["render"].as_table().unwrap();
    assert_eq!(render["spp"].as_integer(), Some(16));
    assert_eq!(render["max_depth"].as_integer(), Some(5));
    let materials = tables(&t, "material");
    let get = |name: &str| -> &toml::Table {
        materials
            .iter()
            .find(|m| m["name"].as_str() == Some(name))
            .unwrap_or_else(|| panic!("{name} in {materials:?}"))
    };
    let shapes = tables(&t, "shape");
    let of = |i: usize| get(shapes[i]["material"].as_str().unwrap());
    assert_eq!(of(0)["type"].as_str(), Some("diffuse"));
    assert!(close(vec3(&of(0)["albedo"]), [0.5; 3], 0.0));
    // pbrt's default index 1.5; its roughness r is α = √r unless remaproughness is false.
    assert_eq!(f(&of(1)["ior"]), 1.5);
    assert!((f(&of(1)["roughness"]) - 0.3).abs() < 1e-15);
    assert_eq!(f(&of(2)["roughness"]), 0.09);
    assert_eq!(of(3)["metal"].as_str(), Some("Cu"));
    assert_eq!(of(4)["metal"].as_str(), Some("Au"));
    assert!(close(vec3(&of(5)["eta"]), [0.2, 0.3, 0.4], 0.0));
    assert!(close(vec3(&of(5)["k"]), [3.0, 2.0, 1.0], 0.0));
    // A glass sphere holding smoke: the medium at the glass's index, σ × scale.
    let media = tables(&t, "medium");
    let smoke = media
        .iter()
        .find(|m| Some(m["name"].as_str().unwrap()) == shapes[6]["interior"].as_str())
        .unwrap();
    assert_eq!(f(&smoke["n"]), 1.33);
    assert_eq!(f(&smoke["absorption"]), 1.0);
    assert!(close(vec3(&smoke["scattering"]), [2.0, 4.0, 6.0], 0.0));
    assert_eq!(f(&smoke["phase"]["hg"]), 0.3);
    // A thin pane keeps no medium inside; its index is pbrt's eta, 1.5 by default.
    for (i, eta) in [(7, 1.52), (8, 1.5)] {
        assert_eq!(of(i)["type"].as_str(), Some("thin_dielectric"));
        assert_eq!(f(&of(i)["ior"]), eta);
        assert!(shapes[i].get("interior").is_none());
    }
}

/// pbrt-v4's Gaussian pixel filter converts exactly — its default (σ ½, radius 1.5) when the
/// file names none, its own σ and radius when it does, beyond the image's edges as pbrt
/// draws it — and a box of radius ½ to grinlight's box (no keys).
#[test]
fn pbrts_gaussian_pixel_filter_converts_with_its_sigma_radius_and_reach() {
    let d = dir("pbrt-filter");
    for (name, statement, expected) in [
        ("default", "", Some((0.5, 1.5))),
        (
            "given",
            "PixelFilter \"gaussian\" \"float sigma\" 0.7 \"float xradius\" 2 \"float yradius\" 2\n",
            Some((0.7, 2.0)),
        ),
        ("box", "PixelFilter \"box\"\n", None),
    ] {
        let p = write(
            &d,
            &format!("{name}.pbrt"),
            &format!("Camera \"perspective\"\n{statement}WorldBegin\n"),
        );
        let t = convert(&p, &ImportOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
        let camera = t["camera"].as_table().unwrap();
        match expected {
            Some((sigma, radius)) => {
                assert_eq!(camera["filter"].as_str(), Some("gaussian"), "{name}");
                assert_eq!(f(&camera["filter_stddev"]), sigma, "{name}");
                assert_eq!(f(&camera["filter_radius"]), radius, "{name}");
                assert_eq!(camera["filter_beyond_image"].as_bool(), Some(true), "{name}");
            }
            None => {
                for key in ["filter", "filter_stddev", "filter_radius", "filter_beyond_image"] {
                    assert!(camera.get(key).is_none(), "{name}: {key}");
                }
            }
        }
    }
}

/// pbrt-v4's EqualAreaSphereToSquare (util/math.cpp), written out: Clarberg's map with the
/// angle by pbrt's 6th-degree minimax polynomial, its coefficients as pbrt prints them.
#[allow(clippy::excessive_precision)]
fn pbrt_sphere_to_square(d: glam::DVec3) -> glam::DVec2 {
    let (x, y, z) = (d.x.abs(), d.y.abs(), d.z.abs());
    let r = (1.0 - z).max(0.0).sqrt();
    let (a, b) = (x.max(y), x.min(y));
    let b = if a == 0.0 { 0.0 } else { b / a };
    let t = [
        0.406758566246788489601959989e-5,
        0.636226545274016134946890922156,
        0.61572017898280213493197203466e-2,
        -0.247333733281268944196501420480,
        0.881770664775316294736387951347e-1,
        0.419038818029165735901852432784e-1,
        -0.251390972343483509333252996350e-1,
    ];
    let mut phi = t.iter().rev().fold(0.0, |acc, c| acc * b + c);
    if x < y {
        phi = 1.0 - phi;
    }
    let (mut u, mut v) = (r - phi * r, phi * r);
    if d.z < 0.0 {
        (u, v) = (1.0 - v, 1.0 - u);
    }
    glam::DVec2::new(0.5 * (u.copysign(d.x) + 1.0), 0.5 * (v.copysign(d.y) + 1.0))
}

/// The pixel (its index in an n × n image, row-major) pbrt-v4's nearest lookup reads toward
/// each of 4000 directions spread over the sphere (`seed` keys them), a direction `w` being
/// `image_frame(w)` in the image's frame; directions within 5·10⁻⁶ of the square's side of a
/// pixel's edge (the bound of pbrt's polynomial against the exact angle, tested below), where
/// the two may pick neighbours, left out.
fn pbrt_pixels(
    seed: u64,
    n: usize,
    image_frame: impl Fn(glam::DVec3) -> glam::DVec3,
) -> Vec<(glam::DVec3, usize)> {
    (0..4000u64)
        .filter_map(|k| {
            let h = grinlight::sampling::mix(k + seed);
            let u = (
                (h >> 32) as f64 / 2f64.powi(32),
                (h & 0xffff_ffff) as f64 / 2f64.powi(32),
            );
            let w = grinlight::sampling::uniform_sphere(u);
            let cell = pbrt_sphere_to_square(image_frame(w)) * n as f64;
            let on_edge = (cell - cell.round()).abs().min_element() < 5e-6 * n as f64;
            let (i, j) = ((cell.x as usize).min(n - 1), (cell.y as usize).min(n - 1));
            (!on_edge).then_some((w, j * n + i))
        })
        .collect()
}

/// The world `light` written in `dir` under a camera whose conversion negates x and under one
/// whose conversion keeps it (`Scale -1 1 1`, pbrt's camera then right-handed): each case's
/// name, file, built scene and the mirror the conversion applied to pbrt's world.
fn built_with_x_negated_and_kept(
    dir: &Path,
    light: &str,
) -> Vec<(
    &'static str,
    std::path::PathBuf,
    grinlight::scene::Scene,
    glam::DVec3,
)> {
    [
        ("negated", "LookAt 0 0 5  0 0 0  0 1 0", -1.0),
        ("kept", "Scale -1 1 1\nLookAt 0 0 5  0 0 0  0 1 0", 1.0),
    ]
    .into_iter()
    .map(|(case, camera, x)| {
        let p = write(dir, &format!("{case}.pbrt"), &scene(camera, light));
        let (description, _) =
            grinlight::import::load_description(&p, &ImportOptions::default()).unwrap();
        (case, p, description.build(), glam::DVec3::new(x, 1.0, 1.0))
    })
    .collect()
}

/// pbrt-v4's map and grinlight's (the angle exact) agree to 5·10⁻⁶ of the square over a grid
/// of directions: pbrt's polynomial errs by about 4·10⁻⁶ of a quadrant.
#[test]
fn pbrts_equal_area_map_is_grinlights_to_its_polynomials_error() {
    for i in 0..60 {
        for j in 0..120 {
            let theta = (i as f64 + 0.5) / 60.0 * PI;
            let phi = j as f64 / 120.0 * std::f64::consts::TAU;
            let d = glam::DVec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            );
            let gap = (pbrt_sphere_to_square(d) - grinlight::equal_area::sphere_to_square(d))
                .abs()
                .max_element();
            assert!(gap < 5e-6, "{d}: {gap}");
        }
    }
}

/// pbrt-v4's `goniometric` light converts to the intensity pbrt computes: toward a world
/// direction w, its image's pixel at EqualAreaSphereToSquare(swapYZ(R⁻¹ w)) — pbrt's map with
/// its own polynomial, written out here from lights.cpp and util/math.cpp — times `I` and
/// `scale`, R the light's rotation. Checked over 4000 directions (those within 5·10⁻⁶ of the square's side of a pixel's
/// edge left out, where the polynomial and grinlight's exact angle may pick neighbours) with
/// the scene's x negated (pbrt's left-handed camera) and kept (`Scale -1 1 1`), which read the
/// image mirrored against each other; and `power` sets the luminous power, 4π/N² × the pixels'
/// sum × scale × the converted colour's luminance, to 1e-12.
#[test]
fn a_pbrt_goniometric_light_sends_the_intensity_pbrt_computes() {
    use glam::{DMat3, DVec3};
    let d = dir("pbrt-goniometric");
    let n = 8usize;
    let values: Vec<f64> = (0..n * n).map(|i| 1.0 + i as f64).collect();
    image::Rgb32FImage::from_fn(n as u32, n as u32, |x, y| {
        let v = values[(y * n as u32 + x) as usize] as f32;
        image::Rgb([v - 0.5, v, v + 0.5])
    })
    .save(d.join("map.exr"))
    .unwrap();
    let rotation =
        DMat3::from_axis_angle(DVec3::new(1.0, 1.0, 0.0).normalize(), 30f64.to_radians());
    let light = "AttributeBegin\nTranslate 1 2 3\nRotate 30 1 1 0\nLightSource \"goniometric\" \
                 \"string filename\" \"map.exr\" \"rgb I\" [ 1 2 3 ] \"float scale\" 2\nAttributeEnd";
    for (case, p, built, mirror) in built_with_x_negated_and_kept(&d, light) {
        let converted = &built.lights[0];
        // pbrt's world direction, its light frame's, and the image's (y and z swapped).
        let image_frame = |w: DVec3| {
            let light_frame = rotation.transpose() * (w * mirror);
            DVec3::new(light_frame.x, light_frame.z, light_frame.y)
        };
        let looked_up = pbrt_pixels(17, n, image_frame);
        assert!(looked_up.len() > 3900, "{case}: {}", looked_up.len());
        for (w, pixel) in looked_up {
            let expected = 2.0 * values[pixel];
            let got = converted.intensity(w).0;
            assert!(
                (got - DVec3::new(1.0, 2.0, 3.0) * expected)
                    .abs()
                    .max_element()
                    < 1e-9 * expected,
                "{case}: toward {w}: {got} against {expected} × (1, 2, 3)"
            );
        }
        assert!(
            close(
                vec3(
                    &tables(&convert(&p, &ImportOptions::default()).unwrap(), "light")[0]
                        ["position"]
                ),
                (DVec3::new(1.0, 2.0, 3.0) * mirror).into(),
                1e-12
            ),
            "{case}"
        );
    }
    // `power`: pbrt's Φ = power × scale for an I of luminance 1; grinlight's power key.
    let p = write(
        &d,
        "power.pbrt",
        &scene(
            "LookAt 0 0 5  0 0 0  0 1 0",
            "LightSource \"goniometric\" \"string filename\" \"map.exr\" \"float power\" 100 \"float scale\" 3",
        ),
    );
    let t = convert(&p, &ImportOptions::default()).unwrap();
    let light = &tables(&t, "light")[0];
    assert_eq!(f(&light["power"]), 300.0);
    assert!(light.get("scale").is_none());
}

/// pbrt-v4's `infinite` light of an image converts to the radiance pbrt looks up: toward a
/// world direction w, the image's pixel at EqualAreaSphereToSquare(R⁻¹ w) (pbrt's polynomial
/// map, written out above) times `scale`, R the light's rotation — over 4000 directions (those
/// within 5·10⁻⁶ of the square's side of a pixel's edge left out), with the scene's x negated and kept. With
/// `illuminance` E, pbrt scales the map by E over its own sum for the upper hemisphere's
/// illuminance, which weighs each pixel by 2π/N² sr where it covers 4π/N²: the converted
/// environment gives a surface facing the map's +z twice E (by quadrature over 1.6·10⁵
/// directions, 1 %: a 64 × 64 map, whose sum at the pixels' centres pbrt takes for the
/// integral), as pbrt renders it.
#[test]
fn a_pbrt_image_infinite_light_shows_the_radiance_pbrt_looks_up() {
    use glam::{DMat3, DVec3};
    let d = dir("pbrt-envmap");
    let n = 16usize;
    let value = |i: usize| 0.1 + (i % 7) as f64 + 3.0 * (i / n) as f64;
    image::Rgb32FImage::from_fn(n as u32, n as u32, |x, y| {
        let v = value((y * n as u32 + x) as usize) as f32;
        image::Rgb([v, 2.0 * v, 0.5 * v])
    })
    .save(d.join("sky.exr"))
    .unwrap();
    let rotation =
        DMat3::from_axis_angle(DVec3::new(1.0, 0.0, 1.0).normalize(), (-75f64).to_radians());
    let light = "AttributeBegin\nRotate -75 1 0 1\nLightSource \"infinite\" \
                 \"string filename\" \"sky.exr\" \"float scale\" 1.5\nAttributeEnd";
    for (case, _, built, mirror) in built_with_x_negated_and_kept(&d, light) {
        let sky = built.environment.as_ref().expect("an environment");
        let looked_up = pbrt_pixels(99, n, |w| rotation.transpose() * (w * mirror));
        assert!(looked_up.len() > 3900, "{case}: {}", looked_up.len());
        for (w, pixel) in looked_up {
            let expected = 1.5 * value(pixel) as f32 as f64;
            let got = sky.radiance(w).0;
            assert!(
                (got - DVec3::new(1.0, 2.0, 0.5) * expected)
                    .abs()
                    .max_element()
                    < 1e-6 * expected,
                "{case}: toward {w}: {got} against {expected} × (1, 2, ½)"
            );
        }
    }
    // Illuminance: the converted sky's irradiance on a surface facing the map's +z, from a
    // finer map (pbrt's sum at the pixels' centres is then within 0.5 % of the integral).
    let fine = 64u32;
    image::Rgb32FImage::from_fn(fine, fine, |x, y| {
        image::Rgb([1.0 + (x + y) as f32 / fine as f32, 1.0, 0.5])
    })
    .save(d.join("fine.exr"))
    .unwrap();
    let p = write(
        &d,
        "illuminance.pbrt",
        &scene(
            "Scale -1 1 1\nLookAt 0 0 5  0 0 0  0 1 0",
            "LightSource \"infinite\" \"string filename\" \"fine.exr\" \"float illuminance\" 10",
        ),
    );
    let (description, _) =
        grinlight::import::load_description(&p, &ImportOptions::default()).unwrap();
    let built = description.build();
    let sky = built.environment.as_ref().unwrap();
    let (rows, cols) = (400, 400);
    let mut irradiance = 0.0;
    for a in 0..rows {
        for b in 0..cols {
            let w = grinlight::sampling::uniform_sphere((
                (a as f64 + 0.5) / rows as f64,
                (b as f64 + 0.5) / cols as f64,
            ));
            if w.z > 0.0 {
                let l = sky.radiance(w).0;
                irradiance += (0.212_639 * l.x + 0.715_169 * l.y + 0.072_192 * l.z) * w.z;
            }
        }
    }
    irradiance *= 4.0 * PI / (rows * cols) as f64;
    println!("irradiance {irradiance} against twice 10");
    assert!(
        (irradiance - 20.0).abs() < 0.01 * 20.0,
        "irradiance {irradiance} against twice 10"
    );
}

/// The message of a scene that does not convert.
/// A pbrt `dielectric` whose index is a spectrum converts to a dispersive index that is pbrt-v4's:
/// its named glass `glass-BK7` and `glass-F11` (Schott's SF11, whose table starts at 370 nm) and
/// inline pairs (400 nm 1.6, 700 nm 1.5) read, at wavelengths on and between pbrt's nodes, pbrt's
/// piecewise-linear n(λ) from its table's values written out here, within 10⁻⁷ — and 1 outside
/// the nodes, where pbrt's spectrum reads 0 and its dielectric takes the index 1. The scene is
/// dispersive; a `float eta` stays one number.
#[test]
fn a_pbrt_dielectric_over_wavelength_converts_to_pbrts_index() {
    let d = dir("pbrt-glass");
    let body = "Material \"dielectric\" \"spectrum eta\" \"glass-BK7\"\nShape \"sphere\"\n\
                Material \"dielectric\" \"spectrum eta\" \"glass-F11\"\nShape \"sphere\"\n\
                Material \"dielectric\" \"spectrum eta\" [ 400 1.6 700 1.5 ]\nShape \"sphere\"\n\
                Material \"dielectric\" \"float eta\" 1.33\nShape \"sphere\"";
    let p = write(&d, "s.pbrt", &scene("", body));
    let (description, _) = load_description(&p, &ImportOptions::default()).unwrap();
    let built = description.build();
    assert!(built.is_dispersive());
    let media = built.media();
    let n = |i: usize, nm: f64| {
        let id = grinlight::ids::MediumId::new(i);
        let at = media.at_wavelength(id, nm);
        let medium = at.as_ref().map_or(media.at(id), |p| p.as_medium());
        medium.sample(glam::DVec3::ZERO).unwrap().n
    };
    let lerp =
        |(x0, n0): (f64, f64), (x1, n1): (f64, f64), x: f64| n0 + (n1 - n0) * (x - x0) / (x1 - x0);
    let bk7 = [
        (344.0, 1.5404466868331),
        (366.0, 1.536090527917),
        (586.0, 1.516865556749),
        (608.0, 1.5159846691816),
    ];
    let sf11 = [(370.0, 1.8700216173234), (391.0, 1.8516255860581)];
    let cases = [
        (0, 360.0, lerp(bk7[0], bk7[1], 360.0)),
        (0, 586.0, bk7[2].1),
        (0, 597.0, lerp(bk7[2], bk7[3], 597.0)),
        (0, 600.3, lerp(bk7[2], bk7[3], 600.3)),
        (1, 365.0, 1.0),
        (1, 369.99, 1.0),
        (1, 370.0, sf11[0].1),
        (1, 380.5, lerp(sf11[0], sf11[1], 380.5)),
        (2, 380.0, 1.0),
        (2, 400.0, 1.6),
        (2, 512.3, lerp((400.0, 1.6), (700.0, 1.5), 512.3)),
        (2, 700.0, 1.5),
        (2, 750.0, 1.0),
        (3, 450.0, 1.33),
    ];
    for (i, nm, want) in cases {
        let got = n(i, nm);
        assert!(
            (got - want).abs() < 1e-7,
            "medium {i} at {nm} nm: {got} against pbrt's {want}"
        );
    }
    assert!(!media.is_dispersive(grinlight::ids::MediumId::new(3)));
}

fn refusal(name: &str, text: &str, options: &ImportOptions) -> String {
    let d = dir(&format!("pbrt-refuse-{name}"));
    let p = write(&d, "s.pbrt", text);
    match convert(&p, options) {
        Ok(_) => panic!("{name}: converted"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn what_pbrt_cannot_convert_is_refused_by_file_line_and_column() {
    let exact = ImportOptions::default();
    let camera = "Scale -1 1 1\nLookAt 0 0 5  0 0 0  0 1 0";
    // The world starts on line 7: a body's first line is line 7.
    let in_world = |body: &str| scene(camera, body);
    for (name, text, words) in [
        (
            "directive",
            in_world("Shpe \"sphere\""),
            "s.pbrt:7:1: 'Shpe' is not a pbrt-v4 directive",
        ),
        (
            "parameter",
            in_world("Shape \"sphere\" \"float radiuss\" 1"),
            "s.pbrt:7:16: Shape \"sphere\": the parameter \"float radiuss\" is not supported",
        ),
        (
            "unended object",
            in_world("ObjectBegin \"o\"\nShape \"sphere\""),
            "s.pbrt:7:1: ObjectBegin \"o\" is never ended",
        ),
        (
            "object defined twice",
            in_world("ObjectBegin \"o\"\nObjectEnd\nObjectBegin \"o\"\nObjectEnd"),
            "s.pbrt:9:1: the object \"o\" is defined again (first at",
        ),
        (
            "nested object",
            in_world("ObjectBegin \"o\"\nObjectBegin \"p\""),
            "s.pbrt:8:1: ObjectBegin inside the definition of \"o\"",
        ),
        (
            "unknown object",
            in_world("ObjectInstance \"o\""),
            "s.pbrt:7:1: no object is named \"o\"",
        ),
        (
            "object with an unended attribute",
            in_world("ObjectBegin \"o\"\nAttributeBegin\nObjectEnd"),
            "s.pbrt:9:1: ObjectEnd with an AttributeBegin inside \"o\" not ended",
        ),
        (
            "area light in an object",
            in_world("ObjectBegin \"o\"\nAreaLightSource \"diffuse\"\nShape \"sphere\"\nObjectEnd"),
            "s.pbrt:9:1: Shape \"sphere\": an area light in an object's definition",
        ),
        ("v3", in_world("WorldEnd"), "WorldEnd is pbrt-v3's"),
        (
            "cylinder light",
            in_world("Material \"diffuse\" \"rgb reflectance\" [0 0 0]\nAreaLightSource \"diffuse\"\nShape \"cylinder\""),
            "s.pbrt:9:1: an area light on a \"cylinder\"",
        ),
        (
            "inward sphere light",
            in_world("Material \"diffuse\" \"rgb reflectance\" [0 0 0]\nAreaLightSource \"diffuse\"\nReverseOrientation\nShape \"sphere\""),
            "s.pbrt:10:1: a sphere light turned inside out",
        ),
        (
            "mixed",
            in_world("Material \"mix\""),
            "the material \"mix\" is not supported",
        ),
        (
            "anisotropic",
            in_world("Material \"conductor\" \"float uroughness\" 0.1 \"float vroughness\" 0.2\nShape \"sphere\""),
            "an anisotropic roughness",
        ),
        (
            "unknown glass",
            in_world("Material \"dielectric\" \"spectrum eta\" \"glass-XYZ\"\nShape \"sphere\""),
            "s.pbrt:7:23: Material \"dielectric\": \"spectrum eta\": \"glass-XYZ\" is not one of pbrt-v4's glasses",
        ),
        (
            "descending index spectrum",
            in_world("Material \"dielectric\" \"spectrum eta\" [ 700 1.5 400 1.6 ]\nShape \"sphere\""),
            "give pairs of wavelength (nm, ascending) and index (> 0)",
        ),
        (
            "dispersive pane",
            in_world("Material \"thindielectric\" \"spectrum eta\" \"glass-BK7\"\nShape \"sphere\""),
            "s.pbrt:7:27: Material \"thindielectric\": \"spectrum eta\" — an index over wavelength",
        ),
        (
            "spectral light of falling wavelengths",
            in_world("LightSource \"point\" \"spectrum I\" [ 700 1 400 1 ]"),
            "s.pbrt:7:21: LightSource \"point\": \"spectrum I\": expected pairs of wavelength",
        ),
        (
            "cold blackbody",
            in_world("LightSource \"point\" \"blackbody I\" -5"),
            "expected one temperature in kelvin, > 0",
        ),
        (
            "partial sphere",
            in_world("Shape \"sphere\" \"float zmax\" 0.5"),
            "a partial shape (zmax 0.5)",
        ),
        (
            "string",
            in_world("Shape \"sphere"),
            "s.pbrt:7:7: a string runs past the end of its line",
        ),
        (
            "bracket",
            in_world("Shape \"sphere\" \"float radius\" [ 1"),
            "s.pbrt:7:16: \"float radius\": the list is not closed",
        ),
        (
            "include",
            in_world("Include \"missing.pbrt\""),
            "s.pbrt:7:1: the file \"missing.pbrt\" is not found",
        ),
        (
            "filter",
            "LookAt 0 0 5 0 0 0 0 1 0\nCamera \"perspective\"\nPixelFilter \"mitchell\"\nWorldBegin\n".into(),
            "s.pbrt:3:1: PixelFilter \"mitchell\": taken as a box of one pixel",
        ),
        (
            "elliptic filter",
            "PixelFilter \"gaussian\" \"float xradius\" 2\n".into(),
            "s.pbrt:1:1: PixelFilter \"gaussian\": xradius 2 ≠ yradius 1.5",
        ),
        (
            "twice",
            in_world("Shape \"sphere\" \"float radius\" 1 \"float radius\" 2"),
            "the parameter 'radius' is given twice",
        ),
        (
            "fraction",
            "Film \"rgb\" \"integer xresolution\" 10.5\n".into(),
            "\"integer xresolution\": 10.5 is not a whole number",
        ),
        (
            "order",
            "Shape \"sphere\"\n".into(),
            "s.pbrt:1:1: Shape belongs after WorldBegin",
        ),
        (
            "camera",
            "Camera \"orthographic\"\n".into(),
            "the camera \"orthographic\" is not supported",
        ),
        (
            "projection",
            in_world("LightSource \"projection\""),
            "the light \"projection\" is not supported",
        ),
        (
            "goniometric without its image",
            in_world("LightSource \"goniometric\""),
            "s.pbrt:7:1: LightSource \"goniometric\": \"string filename\" is missing",
        ),
        (
            "scaled goniometric",
            in_world("Scale 2 2 2\nLightSource \"goniometric\" \"string filename\" \"g.exr\""),
            "s.pbrt:8:1: LightSource \"goniometric\": the transform scales or shears the light",
        ),
        (
            "image sky and L",
            in_world("LightSource \"infinite\" \"string filename\" \"sky.exr\" \"rgb L\" [ 1 1 1 ]"),
            "s.pbrt:7:52: LightSource \"infinite\": an image's infinite light with \"rgb L\" is not supported",
        ),
        (
            "image sky squashed",
            in_world("Scale 1 2 1\nLightSource \"infinite\" \"string filename\" \"sky.exr\""),
            "s.pbrt:8:1: LightSource \"infinite\": the transform scales unevenly or shears the environment",
        ),
        (
            "two cameras",
            "Camera \"perspective\"\nCamera \"perspective\"\n".into(),
            "s.pbrt:2:1: a second Camera (the first at ",
        ),
        (
            "two worlds",
            in_world("WorldBegin"),
            "s.pbrt:7:1: a second WorldBegin",
        ),
        (
            "no world",
            "Camera \"perspective\"\n".into(),
            "the scene has no WorldBegin",
        ),
        (
            "reflecting light",
            in_world("AreaLightSource \"diffuse\"\nShape \"disk\""),
            "s.pbrt:7:1: Shape \"disk\"'s surface reflects light in pbrt",
        ),
        (
            "one-sided medium",
            in_world(
                "MakeNamedMedium \"m\" \"string type\" \"homogeneous\"\nMediumInterface \"m\" \"\"\nShape \"sphere\"",
            ),
            "s.pbrt:9:1: Shape \"sphere\" has a medium inside but its material lets no light in",
        ),
    ] {
        let message = refusal(name, &text, &exact);
        assert!(message.contains(words), "{name}: {message}");
    }
    // An approximation accepted with --approximate, and listed.
    let d = dir("pbrt-approximate");
    let p = write(
        &d,
        "s.pbrt",
        "LookAt 0 0 5 0 0 0 0 1 0\nCamera \"perspective\"\nPixelFilter \"mitchell\"\nWorldBegin\nMaterial \"coateddiffuse\"\nShape \"sphere\"\n",
    );
    let imported = import(
        &p,
        &ImportOptions {
            defines: Vec::new(),
            approximate: true,
        },
    )
    .unwrap();
    let told = imported.approximations.join("\n");
    assert!(
        told.contains("s.pbrt:3:1: PixelFilter \"mitchell\""),
        "{told}"
    );
    assert!(
        told.contains("s.pbrt:5:1: Material \"coateddiffuse\""),
        "{told}"
    );
    assert_eq!(
        tables(&imported.table, "material")[0]["type"].as_str(),
        Some("plastic")
    );
}

/// pbrt textures grinlight cannot read as pbrt-v4 does are refused by file, line and column
/// (with `--approximate`, which every texture needs): a class other than imagemap and
/// checkerboard, a float texture as a reflectance, another mapping, an inverted image, a PNG
/// said to be linear, a checker colour above 1, a name defined twice or never, and shapes
/// whose (u, v) are not pbrt's — a disk, a triangle mesh without `uv`. An unused texture is a
/// note.
#[test]
fn pbrt_textures_grinlight_cannot_read_are_refused() {
    let approximate = ImportOptions {
        defines: Vec::new(),
        approximate: true,
    };
    let camera = "Scale -1 1 1\nLookAt 0 0 5  0 0 0  0 1 0";
    let png = std::fs::canonicalize("scenes/mitsuba/texture.png").unwrap();
    let image = format!("\"string filename\" \"{}\"", png.display());
    // The texture on line 7, the material on line 8, the shape on line 9.
    let textured = |texture: &str, shape: &str| {
        scene(
            camera,
            &format!("{texture}\nMaterial \"diffuse\" \"texture reflectance\" \"t\"\n{shape}"),
        )
    };
    let sphere = "Shape \"sphere\"";
    for (name, text, words) in [
        (
            "marble",
            textured("Texture \"t\" \"spectrum\" \"marble\"", sphere),
            "s.pbrt:7:1: Texture \"t\": the texture \"marble\" is not supported",
        ),
        (
            "float texture",
            textured("Texture \"t\" \"float\" \"checkerboard\"", sphere),
            "s.pbrt:7:1: Texture \"t\": a \"float\" texture as a reflectance",
        ),
        (
            "spherical mapping",
            textured(&format!("Texture \"t\" \"spectrum\" \"imagemap\" {image} \"string mapping\" \"spherical\""), sphere),
            "the mapping \"spherical\" is not supported",
        ),
        (
            "inverted",
            textured(&format!("Texture \"t\" \"spectrum\" \"imagemap\" {image} \"bool invert\" true"), sphere),
            "an inverted image",
        ),
        (
            "linear PNG",
            textured(&format!("Texture \"t\" \"spectrum\" \"imagemap\" {image} \"string encoding\" \"linear\""), sphere),
            "with encoding \"linear\"",
        ),
        (
            "bright checker",
            textured("Texture \"t\" \"spectrum\" \"checkerboard\" \"rgb tex1\" [2 0 0]", sphere),
            "\"rgb tex1\" — give an rgb of three numbers in [0, 1]",
        ),
        (
            "redefined",
            textured("Texture \"t\" \"spectrum\" \"checkerboard\"\nTexture \"t\" \"spectrum\" \"checkerboard\"", sphere),
            "s.pbrt:8:1: Texture \"t\" redefined",
        ),
        (
            "undefined",
            textured("", sphere),
            "s.pbrt:8:20: Material \"diffuse\": \"texture reflectance\" names no texture defined before it",
        ),
        (
            "disk",
            textured("Texture \"t\" \"spectrum\" \"checkerboard\"", "Shape \"disk\""),
            "s.pbrt:9:1: Shape \"disk\": a texture on it: pbrt's disk (u, v)",
        ),
        (
            "mesh without uv",
            textured(
                "Texture \"t\" \"spectrum\" \"checkerboard\"",
                "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]",
            ),
            "s.pbrt:9:1: Shape \"trianglemesh\": a texture on it: it gives no \"uv\"",
        ),
    ] {
        let message = refusal(name, &text, &approximate);
        assert!(message.contains(words), "{name}: {message}");
    }
    let d = dir("pbrt-unused-texture");
    let p = write(
        &d,
        "s.pbrt",
        &scene(
            camera,
            "Texture \"t\" \"spectrum\" \"checkerboard\"\nShape \"sphere\"",
        ),
    );
    let notes = import(&p, &ImportOptions::default())
        .unwrap()
        .notes
        .join("\n");
    assert!(
        notes.contains("s.pbrt:7:1: Texture \"t\" is used by no shape: left out"),
        "{notes}"
    );
}

/// A gzip-compressed pbrt file (`.pbrt.gz`) reads as its text does.
#[test]
fn a_gzipped_pbrt_file_converts_as_its_text() {
    use std::io::Write;
    let text = std::fs::read("scenes/pbrt/cornell_box.pbrt").unwrap();
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    gz.write_all(&text).unwrap();
    let d = dir("pbrt-gz");
    let p = d.join("cornell_box.pbrt.gz");
    std::fs::write(&p, gz.finish().unwrap()).unwrap();
    let options = ImportOptions::default();
    assert_eq!(
        convert(&p, &options).unwrap(),
        convert(Path::new("scenes/pbrt/cornell_box.pbrt"), &options).unwrap()
    );
}

#[test]
fn a_pbrt_include_cycle_is_refused_and_includes_are_read_in_place() {
    let d = dir("pbrt-include");
    write(&d, "a.pbrt", "Include \"b.pbrt\"\n");
    write(&d, "b.pbrt", "Include \"a.pbrt\"\n");
    let p = write(&d, "s.pbrt", "Include \"a.pbrt\"\n");
    let message = convert(&p, &ImportOptions::default())
        .err()
        .unwrap()
        .to_string();
    assert!(
        message.contains("b.pbrt:1:1") && message.contains("includes itself"),
        "{message}"
    );
    write(
        &d,
        "camera.pbrt",
        "Scale -1 1 1\nLookAt 0 0 5  0 0 0  0 1 0\n",
    );
    write(&d, "ball.pbrt", "Shape \"sphere\" \"float radius\" 2\n");
    let p = write(
        &d,
        "main.pbrt",
        "Include \"camera.pbrt\"\nCamera \"perspective\"\nPixelFilter \"box\"\nWorldBegin\nImport \"ball.pbrt\"\n",
    );
    let t = convert(&p, &ImportOptions::default()).unwrap();
    assert_eq!(f(&tables(&t, "shape")[0]["radius"]), 2.0);
    assert!(close(
        vec3(&t["camera"]["position"]),
        [0.0, 0.0, 5.0],
        1e-12
    ));
}

/// pbrt's blackbody emission, normalised to unit luminance and scaled: converted to a light of
/// Planck's spectrum whose luminance is the scale. CIE illuminant A is Planck's spectrum at
/// 2856 K with c₂ = 1.435e-2 m·K, the same shape as at 2863.5 K with today's c₂ (1.438777e-2):
/// its chromaticity (CIE 15:2004) x = 0.44757, y = 0.40745 is met to 1e-3 — grinlight's
/// colours scale each sRGB channel by up to 1e-3 so that D65 is exactly white (measured:
/// x 0.44697, y 0.40725) — and its luminance to 1e-3 (the four digits of sRGB's luminance
/// row).
#[test]
fn a_blackbody_light_has_plancks_colour_and_its_scale_as_luminance() {
    let kelvin = 2856.0 * 1.438_776_877 / 1.435;
    let t = converted(
        "blackbody",
        "Scale -1 1 1\nLookAt 0 0 5  0 0 0  0 1 0",
        &format!(
            "LightSource \"point\" \"blackbody I\" [ {kelvin} ] \"float scale\" 3\n\
             LightSource \"infinite\" \"blackbody L\" [ {kelvin} ] \"float scale\" 3"
        ),
    );
    let lights = tables(&t, "light");
    assert_eq!(f(&lights[0]["spectrum"]["blackbody"]), kelvin);
    let spectrum =
        grinlight::spectrum::Spectrum::new(grinlight::spectrum::emission::Shape::Blackbody {
            kelvin,
        })
        .unwrap();
    let point = spectrum.colour().0 * f(&lights[0]["intensity"]);
    let sky = glam::DVec3::from(vec3(&lights[1]["radiance"]));
    for rgb in [point, sky] {
        let xyz = glam::DMat3::from_cols_array(&[
            0.4124, 0.2126, 0.0193, 0.3576, 0.7152, 0.1192, 0.1805, 0.0722, 0.9505,
        ]) * rgb;
        let (x, y) = (xyz.x / xyz.element_sum(), xyz.y / xyz.element_sum());
        assert!(
            (x - 0.44757).abs() < 1e-3 && (y - 0.40745).abs() < 1e-3,
            "x {x}, y {y}"
        );
        assert!((xyz.y / 3.0 - 1.0).abs() < 1e-3, "Y {}", xyz.y);
    }
}

/// pbrt-v4's `SampledGrid` lookup (util/containers.h), written out here on its own: the values
/// (x fastest) at the sample points (i + ½)/n of the unit cube, trilinear between them, 0 at
/// samples outside the grid.
fn pbrt_grid(values: &[f64], n: [usize; 3], p: [f64; 3]) -> f64 {
    let s = [0, 1, 2].map(|a| p[a] * n[a] as f64 - 0.5);
    let i = s.map(|x| x.floor());
    let d = [0, 1, 2].map(|a| s[a] - i[a]);
    let at = |x: f64, y: f64, z: f64| -> f64 {
        let q = [x, y, z];
        if (0..3).any(|a| q[a] < 0.0 || q[a] >= n[a] as f64) {
            return 0.0;
        }
        values[(q[2] as usize * n[1] + q[1] as usize) * n[0] + q[0] as usize]
    };
    let lerp = |t: f64, a: f64, b: f64| (1.0 - t) * a + t * b;
    let x0 = |y: f64, z: f64| lerp(d[0], at(i[0], y, z), at(i[0] + 1.0, y, z));
    let y0 = |z: f64| lerp(d[1], x0(i[1], z), x0(i[1] + 1.0, z));
    lerp(d[2], y0(i[2]), y0(i[2] + 1.0))
}

/// pbrt's `uniformgrid` medium converts exactly: grinlight's density at 3000 points in and
/// around its box equals pbrt-v4's lookup there (its `SampledGrid`, values falling to 0 half a
/// cell past the outer ones, and no medium outside the box p0–p1) to 1e-12, for a grid of
/// 3 × 2 × 4 made under a transform that moves, scales unevenly and mirrors z, in a scene the
/// import mirrors in x (pbrt's left-handed camera); σa and σs are pbrt's defaults, 1, times
/// `scale`. A grid turned by its transform, a count that is not nx·ny·nz and a negative
/// density are refused by line.
#[test]
fn a_pbrt_uniform_grid_converts_to_the_density_pbrt_looks_up() {
    let values: Vec<f64> = (0..24).map(|i| ((i * 7) % 11) as f64 * 0.3).collect();
    let listed: Vec<String> = values.iter().map(|v| v.to_string()).collect();
    let grid = |transform: &str, density: &str| {
        format!(
            "AttributeBegin\n{transform}\nMakeNamedMedium \"smoke\" \"string type\" \"uniformgrid\" \
             \"integer nx\" 3 \"integer ny\" 2 \"integer nz\" 4 \"float density\" [ {density} ] \
             \"point3 p0\" [ -1 0 0.5 ] \"point3 p1\" [ 2 1 1.5 ] \"float scale\" 0.5\n\
             AttributeEnd\nMaterial \"interface\"\nMediumInterface \"smoke\" \"\"\n\
             Shape \"sphere\" \"float radius\" 20"
        )
    };
    let transform = "Translate 1 2 3\nScale 2 0.5 -1";
    let t = converted("grid", "", &grid(transform, &listed.join(" ")));
    let medium = &tables(&t, "medium")[0];
    assert_eq!(f(&medium["absorption"]), 0.5);
    assert!(close(vec3(&medium["scattering"]), [0.5; 3], 0.0));
    let text = toml::to_string(&t).unwrap();
    let (parsed, _) = grinlight::scene::load::parse_scene(Path::new("grid.toml"), text).unwrap();
    let media = parsed.media();
    let id = media.index(medium["name"].as_str().unwrap()).unwrap();
    let density = media.scattering(id).unwrap().density.clone().unwrap();
    // The file's world in grinlight's: x negated (pbrt's camera), then the medium's transform.
    let to_world = glam::DMat4::from_scale(glam::DVec3::new(-1.0, 1.0, 1.0))
        * glam::DMat4::from_translation(glam::DVec3::new(1.0, 2.0, 3.0))
        * glam::DMat4::from_scale(glam::DVec3::new(2.0, 0.5, -1.0));
    let (p0, p1) = (
        glam::DVec3::new(-1.0, 0.0, 0.5),
        glam::DVec3::new(2.0, 1.0, 1.5),
    );
    use rand::{Rng, SeedableRng};
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(3);
    let mut inside = 0;
    for _ in 0..3000 {
        // Medium-space points over the box and a margin of a third of it each way.
        let u = glam::DVec3::new(rng.gen(), rng.gen(), rng.gen()) * 1.6 - 0.3;
        let local = p0 + (p1 - p0) * u;
        let want = match u.cmpge(glam::DVec3::ZERO).all() && u.cmple(glam::DVec3::ONE).all() {
            true => {
                inside += 1;
                pbrt_grid(&values, [3, 2, 4], u.to_array())
            }
            false => 0.0,
        };
        let got = density.at(to_world.transform_point3(local));
        assert!(
            (got - want).abs() < 1e-12,
            "at {local}: {got} against pbrt's {want}"
        );
    }
    assert!(inside > 500, "{inside} points inside");
    for (transform, density, message) in [
        ("Rotate 30 0 0 1", listed.join(" "), "turns the grid"),
        ("", "1 2 3".to_string(), "3 density values"),
        ("", format!("{} -1", listed[..23].join(" ")), "a density -1"),
    ] {
        let d = dir("pbrt-grid-refused");
        let p = write(&d, "s.pbrt", &scene("", &grid(transform, &density)));
        let e = convert(&p, &ImportOptions::default())
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("s.pbrt:") && e.contains(message), "{e}");
    }
}

/// pbrt-v4's object instancing converts to the shapes it places: each shape of an object's
/// definition with the instance's transform composed with its own (CTM_instance · CTM_shape,
/// pbrt-v4's render-from-instance times render-from-object) and the material and orientation
/// it was defined with. A scene that places two instances of a box of two shapes — one used
/// before its definition, as pbrt-v4 allows — converts to the same shapes, materials and
/// numbers (1e-12) as the same scene written out without instancing.
#[test]
fn pbrt_object_instances_convert_as_the_shapes_they_place() {
    let object = "ObjectBegin \"thing\"\n\
         Material \"diffuse\" \"rgb reflectance\" [0.2 0.4 0.6]\n\
         AttributeBegin\nTranslate 0 0.5 0\nShape \"sphere\" \"float radius\" 0.25\nAttributeEnd\n\
         Material \"conductor\"\nReverseOrientation\n\
         Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 1 1 0] \"integer indices\" [0 1 2]\n\
         ObjectEnd\n";
    let instanced = format!(
        "AttributeBegin\nTranslate 1 2 3\nRotate 30 0 1 0\nObjectInstance \"thing\"\nAttributeEnd\n\
         AttributeBegin\nTranslate 0.5 0 0\nScale 2 2 2\n{object}AttributeEnd\n\
         AttributeBegin\nScale 1 -1 1\nObjectInstance \"thing\"\nAttributeEnd\n"
    );
    // The same shapes written out: the instance's transform, then the one the definition
    // was given under (Translate 0.5 0 0, Scale 2 2 2), then each shape's own.
    let shapes = |placement: &str| {
        format!(
            "AttributeBegin\n{placement}\nTranslate 0.5 0 0\nScale 2 2 2\n\
             Material \"diffuse\" \"rgb reflectance\" [0.2 0.4 0.6]\n\
             AttributeBegin\nTranslate 0 0.5 0\nShape \"sphere\" \"float radius\" 0.25\nAttributeEnd\n\
             Material \"conductor\"\nReverseOrientation\n\
             Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 1 1 0] \"integer indices\" [0 1 2]\n\
             AttributeEnd\n"
        )
    };
    let flat = format!(
        "{}{}",
        shapes("Translate 1 2 3\nRotate 30 0 1 0"),
        shapes("Scale 1 -1 1")
    );
    let camera = "LookAt 0 0 5  0 0 0  0 1 0";
    let light = "LightSource \"point\" \"point3 from\" [0 4 0]\n";
    let a = converted("instanced", camera, &format!("{light}{instanced}"));
    let b = converted("flat", camera, &format!("{light}{flat}"));
    // Each shape with its material's table in place of its name (the flat scene's four
    // Material statements are four materials, the object's two are two).
    let resolved = |t: &toml::Table, key: &str| -> Vec<Value> {
        let materials = tables(t, "material");
        tables(t, key)
            .into_iter()
            .map(|shape| {
                let mut shape = shape.clone();
                if let Some(Value::String(name)) = shape.get("material").cloned() {
                    let mut m = (materials.iter())
                        .find(|m| m["name"].as_str() == Some(name.as_str()))
                        .map(|m| (*m).clone())
                        .unwrap();
                    m.remove("name");
                    shape.insert("material".into(), Value::Table(m));
                }
                Value::Table(shape)
            })
            .collect()
    };
    for key in ["shape", "light"] {
        let (x, y) = (resolved(&a, key), resolved(&b, key));
        assert_eq!(x.len(), y.len(), "{key}: {x:?} against {y:?}");
        for (x, y) in x.iter().zip(&y) {
            assert!(same(x, y), "{key}: {x:?} against {y:?}");
        }
    }
    assert_eq!(tables(&a, "shape").len(), 4, "two instances of two shapes");
}

/// Whether two converted values are equal, numbers to 1e-12.
fn same(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Table(x), Value::Table(y)) => {
            x.len() == y.len() && x.iter().all(|(k, v)| y.get(k).is_some_and(|w| same(v, w)))
        }
        (Value::Array(x), Value::Array(y)) => {
            x.len() == y.len() && x.iter().zip(y).all(|(v, w)| same(v, w))
        }
        (Value::Float(_) | Value::Integer(_), Value::Float(_) | Value::Integer(_)) => {
            let n = |v: &Value| v.as_float().or(v.as_integer().map(|i| i as f64));
            (n(a).unwrap() - n(b).unwrap()).abs() <= 1e-12
        }
        _ => a == b,
    }
}

/// A diffuse or rough material on a mesh whose normals `N` are not its faces' converts only
/// as an approximation (pbrt, as Mitsuba, evaluates it about them; grinlight about each
/// triangle's own); the same mesh with `N` along its face, or with a smooth conductor, or
/// without `N`, exactly.
#[test]
fn a_rough_material_on_a_mesh_with_bent_normals_is_an_approximation() {
    let mesh = |normals: &str| {
        format!(
            "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]{normals}"
        )
    };
    let bent = " \"normal N\" [0 0 1 0.3 0 1 0 0.3 1]";
    let along = " \"normal N\" [0 0 2 0 0 1 0 0 3]";
    for (name, material, normals, exact) in [
        ("diffuse, bent", "Material \"diffuse\"", bent, false),
        (
            "rough conductor, bent",
            "Material \"conductor\" \"float roughness\" 0.1",
            bent,
            false,
        ),
        ("default, bent", "", bent, false),
        (
            "smooth conductor, bent",
            "Material \"conductor\"",
            bent,
            true,
        ),
        (
            "diffuse, along the face",
            "Material \"diffuse\"",
            along,
            true,
        ),
        ("diffuse, no normals", "Material \"diffuse\"", "", true),
    ] {
        let d = dir(&format!("pbrt-bent-{}", name.replace([' ', ','], "")));
        let body = format!("{material}\n{}", mesh(normals));
        let p = write(&d, "s.pbrt", &scene("LookAt 0 0 5  0 0 0  0 1 0", &body));
        match convert(&p, &ImportOptions::default()) {
            Ok(_) => assert!(exact, "{name}: converted exactly"),
            Err(e) => {
                let message = e.to_string();
                assert!(!exact, "{name}: {message}");
                assert!(
                    message.contains("s.pbrt:7:1") && message.contains("interpolated"),
                    "{name}: {message}"
                );
            }
        }
    }
}

/// pbrt-v4's named illuminants as a light's spectrum (pbrt scales a light's spectrum to unit
/// luminance): `stdillum-D65` is an RGB white, the same light as `rgb L [1 1 1]`;
/// `stdillum-A` is CIE illuminant A — Planck's law at 2848 K with the CIE's c₂ = 1.435·10⁻²
/// m·K, 2855.50 K with today's — whose colour is A's chromaticity (0.44757, 0.40745, CIE
/// 15:2004) and whose luminance is the light's scale. Other names, and pairs of wavelength and
/// power that are not pairs or do not rise, are refused by name.
#[test]
fn pbrts_named_illuminants_convert_to_their_light() {
    let camera = "LookAt 0 0 5  0 0 0  0 1 0";
    let d65 = converted(
        "d65",
        camera,
        "LightSource \"point\" \"spectrum I\" \"stdillum-D65\" \"float scale\" 2",
    );
    let white = converted(
        "white",
        camera,
        "LightSource \"point\" \"rgb I\" [1 1 1] \"float scale\" 2",
    );
    assert_eq!(tables(&d65, "light"), tables(&white, "light"));
    let a = converted(
        "stdillum-a",
        camera,
        "LightSource \"point\" \"spectrum I\" \"stdillum-A\" \"float scale\" 3",
    );
    let light = tables(&a, "light")[0];
    let kelvin = f(&light["spectrum"]["blackbody"]);
    assert!((kelvin - 2855.4959).abs() < 1e-3, "{kelvin}");
    let spectrum =
        grinlight::spectrum::Spectrum::new(grinlight::spectrum::emission::Shape::Blackbody {
            kelvin,
        })
        .unwrap();
    let rgb = spectrum.colour().0 * f(&light["intensity"]);
    let xyz = glam::DMat3::from_cols_array(&[
        0.4124, 0.2126, 0.0193, 0.3576, 0.7152, 0.1192, 0.1805, 0.0722, 0.9505,
    ]) * rgb;
    let (x, y) = (xyz.x / xyz.element_sum(), xyz.y / xyz.element_sum());
    println!("illuminant A: x {x:.5}, y {y:.5}, Y {:.5}", xyz.y);
    assert!(
        (x - 0.44757).abs() < 1e-4 && (y - 0.40745).abs() < 1e-4,
        "x {x}, y {y}"
    );
    assert!((xyz.y / 3.0 - 1.0).abs() < 1e-3, "Y {}", xyz.y);
    for (name, light, words) in [
        (
            "a camera's",
            "\"spectrum I\" \"canon_eos_100d_r\"",
            "the spectrum \"canon_eos_100d_r\"",
        ),
        (
            "odd values",
            "\"spectrum I\" [400 1 700]",
            "expected pairs of wavelength",
        ),
        (
            "falling",
            "\"spectrum I\" [700 1 400 2]",
            "expected pairs of wavelength",
        ),
    ] {
        let text = scene(camera, &format!("LightSource \"point\" {light}"));
        let message = refusal(name, &text, &ImportOptions::default());
        assert!(
            message.contains("s.pbrt:6:") && message.contains(words),
            "{name}: {message}"
        );
    }
}

/// pbrt-v4's `cropwindow` and `pixelbounds` become the camera's crop, as pbrt-v4's film
/// computes its pixel bounds (`film.cpp`): a crop window's pairs ordered and clamped to
/// [0, 1], its pixels from ⌈x0·width⌉ to ⌈x1·width⌉ (end excluded; likewise down from the
/// top), winning over pixel bounds, which are clamped to the image. pbrt's Gaussian filter
/// draws beyond the window as beyond the image, so the cropped render is the whole render's
/// window, pixel for pixel.
#[test]
fn pbrts_crop_window_and_pixel_bounds_convert_to_the_cameras_crop() {
    let crop_of = |film: &str| -> Option<Vec<i64>> {
        let d = dir("pbrt-crop");
        let text = format!(
            "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 30 ]\n\
             Film \"rgb\" \"integer xresolution\" [ 200 ] \"integer yresolution\" [ 100 ] {film}\n\
             WorldBegin\nShape \"sphere\"\n"
        );
        let p = write(&d, "s.pbrt", &text);
        let t = convert(&p, &ImportOptions::default()).unwrap();
        t["camera"].get("crop").map(|c| {
            c.as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_integer().unwrap())
                .collect()
        })
    };
    assert_eq!(
        crop_of("\"float cropwindow\" [0.25 0.75 0 0.5]"),
        Some(vec![50, 0, 100, 50])
    );
    assert_eq!(
        crop_of("\"float cropwindow\" [0.8 -1 0.5 0.33]"),
        Some(vec![0, 33, 160, 17])
    );
    assert_eq!(
        crop_of("\"integer pixelbounds\" [10 30 5 300]"),
        Some(vec![10, 5, 20, 95])
    );
    assert_eq!(
        crop_of("\"integer pixelbounds\" [10 30 5 300] \"float cropwindow\" [0 0.5 0 1]"),
        Some(vec![0, 0, 100, 100])
    );
    assert_eq!(crop_of("\"float cropwindow\" [0 1 0 1]"), None);
    let d = dir("pbrt-crop-empty");
    let text = "Film \"rgb\" \"float cropwindow\" [0.5 0.5 0 1]\nWorldBegin\n";
    let message = convert(&write(&d, "s.pbrt", text), &ImportOptions::default())
        .err()
        .unwrap()
        .to_string();
    assert!(
        message.contains("s.pbrt:1:1") && message.contains("is empty"),
        "{message}"
    );
    // The cropped render against the whole one (pbrt's default Gaussian filter).
    let render = |film: &str| {
        let d = dir(&format!("pbrt-crop-render-{}", film.len()));
        let text = format!(
            "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 30 ]\n\
             Film \"rgb\" \"integer xresolution\" [ 24 ] \"integer yresolution\" [ 16 ] {film}\n\
             Sampler \"independent\" \"integer pixelsamples\" 4\n\
             WorldBegin\nLightSource \"point\" \"point3 from\" [1 2 4] \"rgb I\" [20 20 20]\n\
             Material \"diffuse\"\nShape \"sphere\"\n"
        );
        let p = write(&d, "s.pbrt", &text);
        let (description, settings) = load_description(&p, &ImportOptions::default()).unwrap();
        let settings = grinlight::settings::Settings {
            threads: 2,
            ..settings
        };
        grinlight::render::render(&description.build(), &settings, &())
            .unwrap()
            .0
            .layer("beauty")
            .unwrap()
            .to_vec()
    };
    let whole = render("");
    let part = render("\"integer pixelbounds\" [5 17 3 11]");
    assert_eq!(part.len(), 12 * 8);
    for (j, i) in (0..8).flat_map(|j| (0..12).map(move |i| (j, i))) {
        assert_eq!(
            part[j * 12 + i],
            whole[(j + 3) * 24 + i + 5],
            "pixel ({i}, {j}) of the window"
        );
    }
}

/// pbrt-v4's spectrum given as pairs of wavelength and power (its piecewise-linear spectrum, 0
/// beyond its ends, scaled to unit luminance times `scale`): converted to a light whose
/// `spectrum` table holds the very pairs; whose power over bands is pbrt's interpolation's
/// (each band's share against 0.01 nm midpoint sums of it, 1e-9: grinlight integrates the
/// table exactly); whose luminance is `scale` (its intensity times the spectrum's luminance per
/// unit, 1e-12); and whose colour is ∫ r̄(λ)·s(λ) dλ per unit of luminance times `scale`, by
/// 0.01 nm sums (1e-3 of it: grinlight's colours scale each channel by up to 1e-3 so that
/// D65 is exactly white).
#[test]
fn a_pbrt_spectrum_of_pairs_converts_to_a_table_of_its_colour_and_scale() {
    let pairs = [
        (430.0, 0.0),
        (450.0, 2.0),
        (470.0, 0.2),
        (560.0, 0.5),
        (640.0, 0.0),
    ];
    let values: Vec<String> = pairs.iter().map(|(nm, p)| format!("{nm} {p}")).collect();
    let t = converted(
        "pairs",
        "LookAt 0 0 5  0 0 0  0 1 0",
        &format!(
            "LightSource \"point\" \"spectrum I\" [ {} ] \"float scale\" 3",
            values.join(" ")
        ),
    );
    let light = tables(&t, "light")[0];
    let rows = table_rows(light);
    assert_eq!(rows, pairs);
    let at = |nm: f64| {
        pairs
            .windows(2)
            .find(|w| w[0].0 <= nm && nm <= w[1].0)
            .map_or(0.0, |w| {
                w[0].1 + (w[1].1 - w[0].1) * (nm - w[0].0) / (w[1].0 - w[0].0)
            })
    };
    let power = |lo: f64, hi: f64| -> f64 {
        let steps = ((hi - lo) / 0.01).round() as usize;
        (0..steps)
            .map(|k| at(lo + 0.01 * (k as f64 + 0.5)) * 0.01)
            .sum()
    };
    let shape = grinlight::spectrum::emission::Shape::Table(pairs.to_vec().into());
    let spectrum = grinlight::spectrum::Spectrum::new(shape).unwrap();
    let total = power(360.0, 830.0);
    for (lo, hi) in [(430.0, 450.0), (450.0, 500.0), (500.0, 640.0)] {
        let share = spectrum.fraction(lo, hi);
        assert!(
            (share - power(lo, hi) / total).abs() < 1e-9,
            "{lo}–{hi}: {share}"
        );
    }
    let intensity = f(&light["intensity"]);
    assert!((intensity * spectrum.luminance() - 3.0).abs() < 1e-12);
    let colour: glam::DVec3 = (0..47_000)
        .map(|k| 360.0 + 0.01 * (k as f64 + 0.5))
        .map(|nm| grinlight::spectrum::colour::sensor(nm).0 * at(nm) * 0.01)
        .sum();
    let expected = colour * (3.0 / colour.dot(glam::DVec3::new(0.2126, 0.7152, 0.0722)));
    let rgb = spectrum.colour().0 * intensity;
    println!("pairs: rgb {rgb:?} against {expected:?}");
    assert!(
        ((rgb - expected) / expected).abs().max_element() < 1e-3,
        "{rgb} against {expected}"
    );
}

/// pbrt-v4's named illuminants beyond D65 and A — D50, the fluorescent lamps F1–F12 and ACES
/// D60 — convert to tables of pbrt's samples (held at their end values beyond them, as pbrt
/// reads them) at unit luminance times the scale (1e-12). F2's and F11's chromaticities are the
/// CIE's (CIE 15:2004: F2 (0.37208, 0.37529), F11 (0.38052, 0.37713)) to 1e-4 (grinlight's
/// white balance scales each channel by up to 1e-3; measured 3·10⁻⁵), and F2's 405 nm mercury
/// line holds its sample (15.69). pbrt's `stdillum-D50` is converted as pbrt has it: its
/// table (`CIE_Illum_D5000`) has the chromaticity (0.33681, 0.35800) by the CIE 1931 observer
/// (grinlight's tables summed over its samples, which match the CIE's F2 and F11 above to
/// 10⁻⁵), not CIE D50's (0.34567, 0.35850) — to 1e-4.
#[test]
fn pbrts_fluorescent_lamps_and_d50_convert_as_pbrt_has_them() {
    for (name, x0, y0) in [
        ("stdillum-D50", 0.33681, 0.35800),
        ("stdillum-F2", 0.37208, 0.37529),
        ("stdillum-F11", 0.38052, 0.37713),
    ] {
        let t = converted(
            name,
            "LookAt 0 0 5  0 0 0  0 1 0",
            &format!("LightSource \"point\" \"spectrum I\" \"{name}\" \"float scale\" 2"),
        );
        let light = tables(&t, "light")[0];
        let rows = table_rows(light);
        if name == "stdillum-F2" {
            assert!(rows.contains(&(405.0, 15.69)), "{rows:?}");
            assert_eq!(rows[0], (359.0, 1.18));
            assert_eq!(rows[rows.len() - 1].0, 831.0);
        }
        let spectrum = grinlight::spectrum::Spectrum::new(
            grinlight::spectrum::emission::Shape::Table(rows.into()),
        )
        .unwrap();
        let intensity = f(&light["intensity"]);
        assert!((intensity * spectrum.luminance() - 2.0).abs() < 1e-12);
        let rgb = spectrum.colour().0 * intensity;
        let xyz = glam::DMat3::from_cols_array(&[
            0.4124, 0.2126, 0.0193, 0.3576, 0.7152, 0.1192, 0.1805, 0.0722, 0.9505,
        ]) * rgb;
        let (x, y) = (xyz.x / xyz.element_sum(), xyz.y / xyz.element_sum());
        println!("{name}: x {x:.5}, y {y:.5} against {x0}, {y0}");
        assert!(
            (x - x0).abs() < 1e-4 && (y - y0).abs() < 1e-4,
            "{name}: x {x}, y {y}"
        );
    }
}

/// The rows of a converted light's `spectrum = { table = [[nm, power], ...] }`.
fn table_rows(light: &toml::Table) -> Vec<(f64, f64)> {
    light["spectrum"]["table"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| (f(&r[0]), f(&r[1])))
        .collect()
}
