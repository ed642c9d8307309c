//! A pixel's footprint measured by ray differentials through the camera path's chain
//! (`integrator::footprint`), against the closed forms of first-order optics.

use grinlight::camera::FilmPoint;
use grinlight::integrator::direct::camera_path;
use grinlight::integrator::footprint::{Eye, Way};
use grinlight::integrator::CameraRay;
use grinlight::scene::load::parse_scene;
use grinlight::transport::chain::{Carried, Choices};
use grinlight::transport::{Stats, Tracer, Vertex};
use std::path::Path;

/// Pixels across the film: the centre pixel's centre lies on the axis, and a pixel is
/// 0.36 mrad wide, so half a pixel off the axis the third-order aberrations of the lenses
/// below are ~1e-6 of the first-order footprint.
const RES: u32 = 1001;

/// A camera at z = 5 looking down −z (40° vertical field, [`RES`] pixels square) at a diffuse
/// wall at z = 0, with `between` in front of it.
fn scene(between: &str) -> String {
    format!(
        "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov_y_deg = 40\nwidth = {RES}\nheight = {RES}\n\
         [[material]]\nname = \"wall\"\ntype = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]\n\
         [[material]]\nname = \"glass\"\ntype = \"dielectric\"\nior = 1.5\n\
         [[material]]\nname = \"mirror\"\ntype = \"mirror\"\n\
         [[shape]]\ntype = \"quad\"\nvertices = [[-9, -9, 0], [9, -9, 0], [9, 9, 0], [-9, 9, 0]]\nmaterial = \"wall\"\n\
         {between}\
         [[light]]\ntype = \"point\"\nposition = [0, 3, 3]\nintensity = [1, 1, 1]\n"
    )
}

/// The width a pixel spans at unit distance along the axis: 2 tan(20°)/[`RES`].
fn pixel_width() -> f64 {
    2.0 * 20f64.to_radians().tan() / RES as f64
}

/// The footprint's half width at the visible point of the centre pixel's ray (every
/// dielectric choice refracting), with the way the path took there.
fn measure(text: &str) -> Option<(f64, Way)> {
    let film = centre();
    let (scene, settings) = parse_scene(Path::new("footprint.toml"), text.to_string()).unwrap();
    let tracer = Tracer::new(&scene, &settings.trace);
    let camera = scene.camera.as_ref().unwrap();
    let grinlight::camera::PrimaryRay { origin, direction } = camera.ray(film);
    let ray = CameraRay {
        origin,
        direction,
        choices: Choices::new([0.999; Choices::COUNT]),
        first: Default::default(),
        film,
    };
    let carried = Carried::on(&tracer);
    let rng = grinlight::sample_stream::SampleStream::Independent(rand_pcg::Pcg64Mcg::new(7));
    let mut stats = Stats::default();
    let mut beams = Default::default();
    let c = camera_path(
        carried,
        ray,
        &mut beams,
        &mut None,
        &mut rng.clone(),
        &mut stats,
    );
    let Some(Vertex::Surface(v)) = c.visible.map(|vp| vp.vertex) else {
        panic!("the ray through {film:?} reaches no surface");
    };
    let way = Way {
        prim: v.prim,
        bounces: c.bounces,
        curved: c.curved,
    };
    Eye::new(camera)
        .half_width(&ray, carried, &rng, &v, way, &mut stats)
        .map(|h| (h, way))
}

/// Asserts that the footprint at the end of the centre pixel's ray in scene `text`, reached after
/// `bounces` specular bounces, is that of a wall seen straight on at `distance` — half the
/// pixel width times it — within the relative `tolerance`.
fn assert_footprint(text: &str, bounces: u32, distance: f64, tolerance: f64) {
    let (h, way) = measure(text).expect("a footprint");
    assert_eq!(way.bounces, bounces);
    let want = 0.5 * distance * pixel_width();
    assert!((h / want - 1.0).abs() < tolerance, "{h} vs {want}");
}

/// The centre of the centre pixel: its ray runs along the axis.
fn centre() -> FilmPoint {
    FilmPoint::pixel_centre(RES / 2, RES / 2)
}

/// Seen straight on, a pixel spans its width times the distance: half of it at distance 5
/// (the map from the film to a plane is projective: at the axis its differences over half a
/// pixel are its derivatives to ~1e-7 relative; tolerance 1e-6).
#[test]
fn a_wall_seen_straight_on_spans_the_pixel_width_times_the_distance() {
    assert_footprint(&scene(""), 0, 5.0, 1e-6);
}

/// Through a plane glass plate of thickness t and index n the wall looks nearer by
/// t(1 − 1/n) (the plate's apparent thickness is t/n, paraxially): the footprint is the pixel
/// width times 5 − t(1 − 1/n) (paraxial error ~1e-7 relative at 0.2 mrad; tolerance 1e-5).
#[test]
fn through_a_glass_plate_the_wall_is_nearer_by_the_plates_apparent_thinning() {
    let plate =
        "[[shape]]\ntype = \"box\"\nmin = [-9, -9, 1]\nmax = [9, 9, 3]\nmaterial = \"glass\"\n";
    // Refracted into and out of the plate.
    assert_footprint(&scene(plate), 2, 5.0 - 2.0 * (1.0 - 1.0 / 1.5), 1e-5);
}

/// Through a glass ball the wall is seen through a thick lens: a ball's principal planes both
/// lie at its centre and its focal length is f = nR/(2(n − 1)), so a ray leaving the eye at a
/// small angle θ meets the wall at θ(d₁ + d₂ − d₁d₂/f), d₁ and d₂ the eye's and the wall's
/// distances from the centre (the ray-transfer matrix from eye to wall). Ball of radius 1 at
/// z = 2.5, n = 1.5: f = 1.5, d₁ = d₂ = 2.5, so the footprint is 0.8333 pixel widths, not 5.
/// Half a pixel off the axis the ball's spherical aberration is ~1e-6 of it; tolerance 1e-5.
#[test]
fn through_a_glass_ball_the_wall_is_magnified_by_the_thick_lens() {
    let ball =
        "[[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 2.5]\nradius = 1\nmaterial = \"glass\"\n";
    let f = 1.5 * 1.0 / (2.0 * 0.5);
    assert_footprint(&scene(ball), 2, 2.5 + 2.5 - 2.5 * 2.5 / f, 1e-5);
}

/// In a plane mirror the wall is seen at the unfolded distance: the camera at z = 5 looks down
/// −z at a mirror at 45° through the origin (the plane z = x), which sends the view along −x
/// to a wall at x = −3: 5 + 3 = 8.
#[test]
fn in_a_plane_mirror_the_footprint_is_the_unfolded_distance_times_the_pixel() {
    let camera = format!(
        "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov_y_deg = 40\nwidth = {RES}\nheight = {RES}\n"
    );
    let text = "\
         [[material]]\nname = \"wall\"\ntype = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]\n\
         [[material]]\nname = \"mirror\"\ntype = \"mirror\"\n\
         [[shape]]\ntype = \"quad\"\nvertices = [[-1, -1, -1], [1, -1, 1], [1, 1, 1], [-1, 1, -1]]\nmaterial = \"mirror\"\n\
         [[shape]]\ntype = \"quad\"\nvertices = [[-3, -9, -9], [-3, 9, -9], [-3, 9, 9], [-3, -9, 9]]\nmaterial = \"wall\"\n\
         [[light]]\ntype = \"point\"\nposition = [-2, 0, 0]\nintensity = [1, 1, 1]\n";
    assert_footprint(&(camera + text), 1, 8.0, 1e-6);
}

/// A sample beside an edge: where a neighbour does not take the sample's way (it misses the
/// glass the sample went through), the footprint is measured from the neighbour on the other
/// side; where neither neighbour along an axis does (a ball of a hundredth of a pixel), it is
/// not known.
#[test]
fn the_footprint_is_measured_from_the_side_that_took_the_same_way() {
    // The plate of the test above, its right edge half a pixel's width (at unit distance)
    // right of the axis: the centre's ray and its left-hand neighbour's cross it, the
    // right-hand neighbour's (at x = pixel_width at the plate's face, 2 from the eye) passes
    // beside it.
    let edge = format!(
        "[[shape]]\ntype = \"box\"\nmin = [-9, -9, 1]\nmax = [{}, 9, 3]\nmaterial = \"glass\"\n",
        0.5 * pixel_width()
    );
    assert_footprint(&scene(&edge), 2, 5.0 - 2.0 * (1.0 - 1.0 / 1.5), 1e-5);
    // A ball on the axis a hundredth of a pixel across at distance 2.5.
    let tiny =
        "[[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 2.5]\nradius = 4e-6\nmaterial = \"glass\"\n";
    assert!(measure(&scene(tiny)).is_none());
}
