//! Scene files: every shipped scene loads; malformed ones fail with file:line:col and the key.

use grinlight::error::Error;
use grinlight::scene::load::parse_scene;
use std::path::Path;

#[test]
fn every_shipped_scene_loads() {
    let mut count = 0;
    for entry in std::fs::read_dir("scenes").unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let (scene, _) = grinlight::scene::load_scene(&path).unwrap_or_else(|e| panic!("{e}"));
            // A scene holds something to look at or to trace: a camera or a medium.
            assert!(
                scene.camera.is_some() || scene.medium_names().count() > 0,
                "{}",
                path.display()
            );
            count += 1;
        }
    }
    assert!(count > 0);
}

/// (scene text, expected line, expected column, text the message must contain)
const BAD: &[(&str, usize, usize, &str)] = &[
    // Unknown key: at the key.
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = 1.5\ncolour = 3\n", 5, 1, "unknown key `colour`"),
    // Missing key: at the table.
    ("[[medium]]\nname = \"a\"\nprofile = \"sech\"\nn0 = 1.5\n", 1, 1, "key `g`: is missing"),
    // Wrong type.
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = \"high\"\n", 4, 1, "key `n`: unknown material 'high' (known: BK7, F2, fused_silica, water)"),
    // Wavelength: an unknown spectrum, a malformed one, a band outside 360–830 nm, a
    // parabolic rod with both `a` and `g`.
    ("[[light]]\ntype = \"point\"\nposition = [0, 0, 0]\nintensity = 1\nspectrum = \"D50\"\n", 5, 1, "unknown spectrum 'D50'"),
    // A spectrum gives the colour: the power key must be one number (or equal RGB).
    ("[[light]]\ntype = \"point\"\nposition = [0, 0, 0]\nintensity = [1, 0.5, 0.5]\nspectrum = \"E\"\n", 5, 1, "gives its power as one number"),
    ("[[light]]\ntype = \"point\"\nposition = [0, 0, 0]\nintensity = 1\nspectrum = { gaussian = [450.0] }\n", 5, 1, "bad `gaussian` spectrum"),
    ("[[light]]\ntype = \"point\"\nposition = [0, 0, 0]\nintensity = 1\nspectrum = { gaussian = [450.0, 20.0, \"x\"] }\n", 5, 1, "key `spectrum`: expected a number, got string"),
    // A measured table: rising wavelengths, powers ≥ 0, power somewhere in 360–830 nm.
    ("[[light]]\ntype = \"point\"\nposition = [0, 0, 0]\nintensity = 1\nspectrum = { table = [[500, 1], [450, 2]] }\n", 5, 1, "the wavelengths rising"),
    ("[[light]]\ntype = \"point\"\nposition = [0, 0, 0]\nintensity = 1\nspectrum = { table = [[450, 1], [500, -2]] }\n", 5, 1, "the powers ≥ 0"),
    ("[[light]]\ntype = \"point\"\nposition = [0, 0, 0]\nintensity = 1\nspectrum = { table = [[900, 1], [950, 2]] }\n", 5, 1, "no power between 360 and 830 nm"),
    ("[[light]]\ntype = \"point\"\nposition = [0, 0, 0]\nintensity = 1\nspectrum = { table = [[450, 1, 3]] }\n", 5, 1, "expected pairs"),
    ("[[receiver]]\nname = \"r\"\ncenter = [0, 0, 0]\nsize = [1, 1]\nbins = [2, 2]\nbands = [[300.0, 400.0]]\n", 6, 1, "each band is [lo_nm, hi_nm]"),
    ("[[medium]]\nname = \"a\"\nprofile = \"parabolic\"\nn0 = 1.5\na = 0.1\ng = 0.3\n", 5, 1, "give exactly one of `a`"),
    // The exact black holes: a charge is required of reissner_nordstrom, and not negative.
    ("[[medium]]\nname = \"a\"\nprofile = \"reissner_nordstrom\"\nrs = 1.0\n", 1, 1, "key `q`: is missing"),
    ("[[medium]]\nname = \"a\"\nprofile = \"reissner_nordstrom\"\nrs = 1.0\nq = -0.1\n", 5, 1, "key `q`: must be ≥ 0"),
    ("[[medium]]\nname = \"a\"\nprofile = \"schwarzschild\"\nrs = 1.0\nq = 0.1\n", 5, 1, "unknown key `q`"),
    // Unknown profile.
    ("[[medium]]\nname = \"a\"\nprofile = \"wobbly\"\n", 3, 1, "unknown profile 'wobbly'"),
    // n ≤ 0.
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = -1.0\n", 4, 1, "key `n`: must be > 0"),
    // Zero radius.
    ("[[medium]]\nname = \"l\"\nprofile = \"luneburg\"\nradius = 0.0\n", 4, 1, "key `radius`"),
    // Negative absorption.
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = 1.5\nabsorption = -0.1\n", 5, 1, "key `absorption`: must not be negative"),
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = 1.5\nabsorption = [1, nan, 1]\n", 5, 1, "key `absorption`: must be finite"),
    // An absorption differing by channel where photons carry single wavelengths or book a
    // budget: in a dispersive medium, beside a fluorescent layer, with receivers.
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = \"BK7\"\nabsorption = [1, 2, 3]\n", 5, 1, "key `absorption`: differs by channel, which only images' RGB paths carry"),
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = 1\nabsorption = [1, 2, 3]\n[[material]]\nname = \"m\"\ntype = \"diffuse\"\nalbedo = 0.5\n\
      fluorescence = { excitation = 0.5, emission = { gaussian = [600, 20] }, quantum_yield = 0.5 }\n", 5, 1, "key `absorption`: differs by channel"),
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = 1\nabsorption = [1, 2, 3]\n[[receiver]]\nname = \"r\"\ncenter = [0, 0, 0]\nsize = [1, 1]\nbins = [2, 2]\n", 5, 1, "key `absorption`: differs by channel"),
    // Scattering: σs negative or NaN, |g| ≥ 1, an unknown phase function.
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = 1\nscattering = -1\n", 5, 1, "key `scattering`: must not be negative"),
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = 1\nscattering = [1, nan, 1]\n", 5, 1, "key `scattering`"),
    // σs over wavelength: negative somewhere in the visible, overflowing there, a bad law.
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = 1\nscattering = { cauchy = [-1, 0.3] }\n", 5, 1, "key `scattering`: must be ≥ 0 and finite from 360 to 830 nm"),
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = 1\nscattering = { angstrom = [1, 550, 3000] }\n", 5, 1, "key `scattering`: must be ≥ 0 and finite from 360 to 830 nm"),
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = 1\nscattering = { angstrom = [-1, 550, 4] }\n", 5, 1, "key `scattering`: angstrom takes [value ≥ 0 at nm, nm > 0, exponent]"),
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = 1\nscattering = { rayleigh = 1 }\n", 5, 1, "key `scattering`: unknown dispersion model 'rayleigh'"),
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = 1\nscattering = 1\nphase = { hg = 1.0 }\n", 6, 1, "key `phase`: hg takes one mean cosine g with −1 < g < 1"),
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = 1\nscattering = 1\nphase = { hg = -1.5 }\n", 6, 1, "key `phase`: hg takes one mean cosine g with −1 < g < 1"),
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = 1\nscattering = 1\nphase = \"mie\"\n", 6, 1, "key `phase`: expected \"isotropic\", \"rayleigh\" or { hg = g }"),
    // Density: a negative value, a count that does not match `density_dims`, a missing key.
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = 1\nscattering = 1\ndensity_bounds = [[0, 0, 0], [1, 1, 1]]\ndensity_dims = [2, 2, 2]\ndensity_values = [1, 1, 1, 1, 1, 1, -1, 1]\n", 8, 1, "key `density_values`: value #6 is -1: a density must be finite and ≥ 0"),
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = 1\nscattering = 1\ndensity_bounds = [[0, 0, 0], [1, 1, 1]]\ndensity_dims = [2, 2, 3]\ndensity_values = [1, 1, 1, 1, 1, 1, 1, 1]\n", 8, 1, "key `density_values`: expected 12 values (dims product), got 8"),
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = 1\nscattering = 1\ndensity_bounds = [[0, 0, 0], [1, 1, 1]]\ndensity_values = [1, 1, 1, 1, 1, 1, 1, 1]\n", 1, 1, "key `density_dims`: is missing"),
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = 1\nscattering = 1\ndensity_bounds = [[0, 0, 0], [1, 1, 1]]\ndensity_dims = [2, 2, 2]\ndensity_values = [1, 1, 1, 1, 1, 1, 1, 1]\ndensity_end = [[0, 2, 0], [1, 1, 1]]\n", 9, 1, "key `density_end`: the box's min must lie below its max"),
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = 1\nscattering = 1\ndensity_bounds = [[0, 0, 0], [1, 1, 1]]\ndensity_dims = [2, 2, 2]\ndensity_values = [1, 1, 1, 1, 1, 1, 1, 1]\ndensity_end = [[0, 0, 0]]\n", 9, 1, "key `density_end`: expected [[min x, y, z], [max x, y, z]]"),
    // Radial tables: r not from 0, lengths differing, n ≤ 0.
    ("[[medium]]\nname = \"t\"\nprofile = \"radial_table\"\nr = [0.1, 0.2]\nn = [1.5, 1.4]\n", 4, 1, "key `r`: must start at 0"),
    ("[[medium]]\nname = \"t\"\nprofile = \"radial_table\"\nr = [0.0, 0.2, 0.3]\nn = [1.5, 1.4]\n", 5, 1, "key `n`: `r` and `n` need the same number"),
    ("[[medium]]\nname = \"t\"\nprofile = \"radial_table\"\nr = [0.0, 0.2]\nn = [1.5, 0.0]\n", 5, 1, "key `n`: every value must be"),
    // Height tables: h not increasing, n ≤ 0.
    ("[[medium]]\nname = \"t\"\nprofile = \"height_table\"\nh = [0.0, 0.2, 0.1]\nn = [1.5, 1.4, 1.3]\n", 4, 1, "key `h`: must increase strictly"),
    ("[[medium]]\nname = \"t\"\nprofile = \"height_table\"\nh = [0.0, 0.2]\nn = [1.5, -1.0]\n", 5, 1, "key `n`: every value must be"),
    // Negative rs.
    ("[[medium]]\nname = \"bh\"\nprofile = \"black_hole\"\nrs = -0.01\n", 4, 1, "key `rs`"),
    // Negative charge, indented key.
    ("[[medium]]\nname = \"bh\"\nprofile = \"black_hole\"\nrs = 0.01\n  q = -0.1\n", 5, 3, "key `q`"),
    // Zero axis.
    ("[[medium]]\nname = \"f\"\nprofile = \"parabolic\"\nn0 = 1.5\na = 0.1\naxis = [0, 0, 0]\n", 6, 1, "key `axis`: must be a non-zero"),
    // Vector of the wrong length.
    ("[[medium]]\nname = \"f\"\nprofile = \"linear\"\nn0 = 1.0\ngradient = [0.0, 1.0]\n", 5, 1, "key `gradient`: expected 3 numbers"),
    // Duplicate name (second table).
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = 1.0\n\n[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = 2.0\n", 7, 1, "already defined"),
    // Empty name.
    ("[[medium]]\nname = \"\"\nprofile = \"uniform\"\nn = 1.0\n", 2, 1, "key `name`"),
    // Name of the wrong type.
    ("[[medium]]\nname = 3\nprofile = \"uniform\"\nn = 1.0\n", 2, 1, "expected a string"),
    // Grid: wrong count.
    ("[[medium]]\nname = \"g\"\nprofile = \"grid\"\nbounds = [[0,0,0],[1,1,1]]\ndims = [2,2,2]\nvalues = [1.0, 1.0]\n", 6, 1, "expected 8 values"),
    // Grid: non-positive value.
    ("[[medium]]\nname = \"g\"\nprofile = \"grid\"\nbounds = [[0,0,0],[1,1,1]]\ndims = [2,2,2]\nvalues = [1,1,1,1,1,1,1,0]\n", 6, 1, "value #7"),
    // Grid: too few nodes.
    ("[[medium]]\nname = \"g\"\nprofile = \"grid\"\nbounds = [[0,0,0],[1,1,1]]\ndims = [1,2,2]\nvalues = [1,1,1,1]\n", 5, 1, "key `dims`"),
    // Grid: negative dims.
    ("[[medium]]\nname = \"g\"\nprofile = \"grid\"\nbounds = [[0,0,0],[1,1,1]]\ndims = [2,-2,2]\nvalues = [1,1,1,1]\n", 5, 1, "non-negative integers"),
    // Grid: empty box.
    ("[[medium]]\nname = \"g\"\nprofile = \"grid\"\nbounds = [[0,0,0],[0,1,1]]\ndims = [2,2,2]\nvalues = [1,1,1,1,1,1,1,1]\n", 4, 1, "key `bounds`"),
    // Grid: both values and file.
    ("[[medium]]\nname = \"g\"\nprofile = \"grid\"\nbounds = [[0,0,0],[1,1,1]]\ndims = [2,2,2]\nvalues = [1,1,1,1,1,1,1,1]\nfile = \"x.txt\"\n", 6, 1, "exactly one"),
    // Grid: missing file.
    ("[[medium]]\nname = \"g\"\nprofile = \"grid\"\nbounds = [[0,0,0],[1,1,1]]\ndims = [2,2,2]\nfile = \"no_such_grid.txt\"\n", 6, 1, "cannot read"),
    // An interpolation that does not exist.
    ("[[medium]]\nname = \"g\"\nprofile = \"grid\"\nbounds = [[0,0,0],[1,1,1]]\ndims = [2,2,2]\nvalues = [1,1,1,1,1,1,1,1]\ninterpolation = \"quintic\"\n", 7, 1, "expected linear or cubic"),
    // A texture that is not there.
    ("[[material]]\nname = \"m\"\ntype = \"diffuse\"\ntexture = \"no_such_texture.png\"\n", 4, 1, "key `texture`: cannot read"),
    // Grid quantities: a temperature ≤ 0, a negative density, an unknown quantity, a pressure
    // ≤ 0.
    ("[[medium]]\nname = \"g\"\nprofile = \"grid\"\nbounds = [[0,0,0],[1,1,1]]\ndims = [2,2,2]\nvalues = [300,300,300,300,300,300,300,0]\nquantity = \"temperature\"\n", 6, 1, "value #7: 0 is not a temperature"),
    ("[[medium]]\nname = \"g\"\nprofile = \"grid\"\nbounds = [[0,0,0],[1,1,1]]\ndims = [2,2,2]\nvalues = [1,1,1,-1,1,1,1,1]\nquantity = \"density\"\n", 6, 1, "value #3: -1 is not a density"),
    ("[[medium]]\nname = \"g\"\nprofile = \"grid\"\nbounds = [[0,0,0],[1,1,1]]\ndims = [2,2,2]\nvalues = [1,1,1,1,1,1,1,1]\nquantity = \"pressure\"\n", 7, 1, "expected index, density or temperature"),
    ("[[medium]]\nname = \"g\"\nprofile = \"grid\"\nbounds = [[0,0,0],[1,1,1]]\ndims = [2,2,2]\nvalues = [300,300,300,300,300,300,300,300]\nquantity = \"temperature\"\npressure = 0\n", 8, 1, "key `pressure`: must be > 0"),
    // Not TOML at all.
    ("[[medium]\nname = 1\n", 1, 9, "invalid table header"),
    // Unknown top-level table.
    ("[kamera]\nfov = 3\n", 1, 2, "unknown field `kamera`"),
    // Camera: missing position (at the table), unknown key, look_at = position, both fovs.
    ("[camera]\nlook_at = [0, 0, 0]\nfov_y_deg = 40\n", 1, 1, "[camera]: key `position`: is missing"),
    ("[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\nfov_y_deg = 40\nfov = 3\n", 5, 1, "unknown key `fov`"),
    ("[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 1]\nfov_y_deg = 40\n", 3, 1, "look_at equals position"),
    ("[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\nfov_y_deg = 40\nfov_x_deg = 50\n", 4, 1, "exactly one of `fov_y_deg`"),
    ("[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\nfov_y_deg = 190\n", 4, 1, "(0°, 179°)"),
    ("[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\nprojection = \"fisheye\"\n", 4, 1, "unknown value 'fisheye' (perspective, orthographic)"),
    ("[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\nprojection = \"orthographic\"\nfov_y_deg = 40\nview_height = 2\n", 5, 1, "an orthographic camera has no field of view"),
    ("[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\nprojection = \"orthographic\"\n", 1, 1, "key `view_height`: is missing"),
    ("[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\nprojection = \"orthographic\"\nview_height = -1\n", 5, 1, "key `view_height`"),
    ("[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\nfov_y_deg = 40\nfilter = \"tent\"\n", 5, 1, "key `filter`: unknown value 'tent' (box, gaussian)"),
    ("[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\nfov_y_deg = 40\nfilter_stddev = 0.5\n", 5, 1, "key `filter_stddev`: is a Gaussian filter's"),
    ("[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\nfov_y_deg = 40\nfilter = \"gaussian\"\nfilter_stddev = 20\n", 6, 1, "key `filter_stddev`: must be at most 8 pixels"),
    ("[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\nfov_y_deg = 40\nfilter = \"gaussian\"\nfilter_stddev = nan\n", 6, 1, "key `filter_stddev`"),
    // Render: unknown stepper, negative tolerance.
    ("[render]\nstepper = \"euler\"\n", 2, 1, "key `stepper`"),
    ("[render]\ntolerance = -1e-9\n", 2, 1, "key `tolerance`: must be > 0"),
    // Material: unknown type, albedo above 1, dielectric without interior.
    ("[[material]]\nname = \"m\"\ntype = \"velvet\"\n", 3, 1, "unknown material type 'velvet'"),
    ("[[material]]\nname = \"m\"\ntype = \"diffuse\"\nalbedo = [0.5, 1.5, 0.5]\n", 4, 1, "reflectance must be ≤ 1"),
    ("[[material]]\nname = \"m\"\ntype = \"dielectric\"\n", 1, 1, "exactly one of `ior` and `interior`"),
    ("[[material]]\nname = \"m\"\ntype = \"dielectric\"\ninterior = \"nothing\"\n", 4, 1, "no medium named 'nothing'"),
    // Glossy materials: roughness below 0, NaN or above 1; an unknown metal; eta without k,
    // k without eta, both metal and eta; negative k or η over wavelength; a plastic with a smooth coat or a coat of index ≤ 1;
    // a negative k.
    ("[[material]]\nname = \"m\"\ntype = \"conductor\"\nmetal = \"Au\"\nroughness = -0.1\n", 5, 1, "key `roughness`: must be a microfacet α in [0, 1]"),
    ("[[material]]\nname = \"m\"\ntype = \"conductor\"\nmetal = \"Au\"\nroughness = nan\n", 5, 1, "key `roughness`: must be finite, got NaN"),
    ("[[material]]\nname = \"m\"\ntype = \"dielectric\"\nior = 1.5\nroughness = 2\n", 5, 1, "key `roughness`: must be a microfacet α in [0, 1]"),
    ("[[material]]\nname = \"m\"\ntype = \"conductor\"\nmetal = \"Pt\"\n", 4, 1, "unknown metal 'Pt' (Ag, Al, Au, Cu, perfect)"),
    ("[[material]]\nname = \"m\"\ntype = \"conductor\"\nmetal = \"Au\"\nroughness = 0.2\ndistribution = \"phong\"\n", 6, 1, "key `distribution`: unknown distribution 'phong' (expected ggx or beckmann)"),
    ("[[material]]\nname = \"m\"\ntype = \"conductor\"\neta = [0.2, 0.4, 1.4]\n", 4, 1, "key `eta`: `eta` needs `k`"),
    ("[[material]]\nname = \"m\"\ntype = \"conductor\"\nk = 3\n", 4, 1, "key `k`: `k` needs `eta`"),
    ("[[material]]\nname = \"m\"\ntype = \"conductor\"\nmetal = \"Au\"\neta = 1\nk = 1\n", 4, 1, "give `metal` or `eta` and `k`"),
    ("[[material]]\nname = \"m\"\ntype = \"conductor\"\n", 1, 1, "a conductor needs `metal`"),
    ("[[material]]\nname = \"m\"\ntype = \"conductor\"\neta = 1\nk = -1\n", 5, 1, "key `k`: must not be negative"),
    ("[[material]]\nname = \"m\"\ntype = \"conductor\"\neta = 1\nk = { cauchy = [-0.5] }\n", 5, 1, "key `k`: k must be ≥ 0 from 360 to 830 nm"),
    ("[[material]]\nname = \"m\"\ntype = \"conductor\"\neta = { cauchy = [-1] }\nk = 3\n", 4, 1, "key `eta`: must be > 0 from 360 to 830 nm"),
    ("[[material]]\nname = \"m\"\ntype = \"plastic\"\nalbedo = 0.5\nroughness = 0\n", 5, 1, "a plastic's coat is rough"),
    ("[[material]]\nname = \"m\"\ntype = \"plastic\"\nalbedo = 0.5\nior = 1.0\n", 5, 1, "key `ior`: the coat's index"),
    // Shape: negative radius, unknown material, missing mesh file, non-parallelogram quad.
    ("[[material]]\nname = \"m\"\ntype = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]\n[[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = -1\nmaterial = \"m\"\n", 8, 1, "key `radius`: must be > 0"),
    ("[[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"nope\"\n", 5, 1, "no material named 'nope'"),
    ("[[shape]]\ntype = \"mesh\"\nfile = \"no_such_mesh.obj\"\nmaterial = \"m\"\n", 3, 1, "cannot read scenes/no_such_mesh.obj"),
    ("[[shape]]\ntype = \"quad\"\nvertices = [[0,0,0],[1,0,0],[1,2,0],[0,1,0]]\nmaterial = \"m\"\n", 3, 1, "not a parallelogram"),
    // A round shape's frame of surface coordinates: three unit orthogonal axes, z along a
    // cylinder's axis; not on a quad; `v_from_top` only with it.
    ("[[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nuv_frame = [[1, 0, 0], [0.1, 1, 0], [0, 0, 1]]\nmaterial = \"m\"\n", 5, 1, "three unit, orthogonal axes"),
    ("[[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nuv_frame = [[1, 0, 0], [0, 1, 0]]\nmaterial = \"m\"\n", 5, 1, "expected three axes"),
    ("[[shape]]\ntype = \"cylinder\"\nbase = [0, 0, 0]\nradius = 1\nheight = 1\nuv_frame = [[0, 1, 0], [0, 0, 1], [1, 0, 0]]\nmaterial = \"m\"\n", 6, 1, "z must be along the cylinder's axis"),
    ("[[shape]]\ntype = \"quad\"\nvertices = [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]\nuv_frame = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]\nmaterial = \"m\"\n", 4, 1, "only a sphere, a cylinder or a disk takes a frame"),
    ("[[material]]\nname = \"m\"\ntype = \"diffuse\"\nalbedo = 0.5\n[[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nv_from_top = true\nmaterial = \"m\"\n", 9, 1, "unknown key `v_from_top`"),
    // A mesh given by its points: an index naming no point, points not in threes, both a file and points.
    ("[[shape]]\ntype = \"mesh\"\npoints = [0, 0, 0, 1, 0, 0, 0, 1, 0]\nindices = [0, 1, 3]\nmaterial = \"m\"\n", 4, 1, "key `indices`: triangle 1 names vertex 3: indices are whole numbers from 0 to 2"),
    ("[[shape]]\ntype = \"mesh\"\npoints = [0, 0, 0, 1, 0, 0, 0, 1]\nindices = [0, 1, 2]\nmaterial = \"m\"\n", 3, 1, "key `points`: expected 3 numbers a vertex, got 8 numbers"),
    ("[[shape]]\ntype = \"mesh\"\nfile = \"a.obj\"\npoints = [0, 0, 0, 1, 0, 0, 0, 1, 0]\nindices = [0, 1, 2]\nmaterial = \"m\"\n", 3, 1, "give either `file` or `points` and `indices`"),
    ("[[shape]]\ntype = \"mesh\"\npoints = [0, 0, 0, 1, 0, 0, 0, 1, 0]\nindices = [0, 1, 2]\nuv = [0, 0, 1, 0]\nmaterial = \"m\"\n", 5, 1, "key `uv`: expected 2 numbers for each of the 3 points, got 4 numbers"),
    // Light: zero-area quad, missing environment file, LED with negative power, unknown type.
    ("[[light]]\ntype = \"quad\"\nvertices = [[0,0,0],[1,0,0],[2,0,0],[1,0,0]]\nradiance = [1, 1, 1]\n", 3, 1, "zero area"),
    ("[[light]]\ntype = \"environment\"\nfile = \"no_such_sky.exr\"\n", 3, 1, "cannot read"),
    ("[[light]]\ntype = \"led\"\ncenter = [0, 0, 0]\nradius = 0.1\npower = -2\n", 5, 1, "key `power`: must be > 0"),
    ("[[light]]\ntype = \"laser\"\n", 2, 1, "unknown light type 'laser'"),
    // An emissive material (a surface that emits is a light; on a shape it would light nothing).
    ("[[material]]\nname = \"glow\"\ntype = \"emissive\"\nradiance = [1, 1, 1]\n[[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"glow\"\n", 3, 1, "would light nothing"),
    // Ambient naming nothing.
    ("ambient = \"space\"\n", 1, 11, "no medium named 'space'"),
    // Infinite index.
    ("[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = inf\n", 4, 1, "must be finite"),
    // Non-finite vector component.
    ("[[medium]]\nname = \"e\"\nprofile = \"exponential\"\nn0 = 1.0\ngradient = [0.0, nan, 0.0]\n", 5, 1, "key `gradient`: must be finite"),
    // [[medium]] that is not an array of tables.
    ("medium = 3\n", 1, 10, "invalid type"),
];

#[test]
fn malformed_scenes_are_rejected_with_file_line_and_column() {
    for (i, (text, line, col, needle)) in BAD.iter().enumerate() {
        let path = Path::new("scenes/bad.toml");
        let err = match parse_scene(path, text.to_string()) {
            Ok(_) => panic!("case {i} was accepted:\n{text}"),
            Err(e) => e,
        };
        let msg = err.to_string();
        println!("case {i}: {msg}");
        match err {
            Error::Scene {
                path: p,
                line: l,
                col: c,
                message,
            } => {
                assert_eq!(p, path);
                assert!(
                    message.contains(needle),
                    "case {i}: '{message}' lacks '{needle}'"
                );
                assert_eq!((l, c), (*line, *col), "case {i}: {msg}");
                assert!(
                    msg.starts_with(&format!("scenes/bad.toml:{l}:{c}: ")),
                    "case {i}: {msg}"
                );
            }
            other => panic!("case {i}: not a scene error: {other}"),
        }
    }
}

#[test]
fn a_grid_file_is_read_relative_to_the_scene() {
    let dir = std::env::temp_dir().join(format!("grinlight-grid-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("n.txt"), "1 1.2\n1 1.2\n1 1.2\n1 1.2\n").unwrap();
    let text = "[[medium]]\nname = \"g\"\nprofile = \"grid\"\nbounds = [[0,0,0],[1,1,1]]\ndims = [2,2,2]\nfile = \"n.txt\"\n";
    let (scene, _) = parse_scene(&dir.join("scene.toml"), text.to_string()).unwrap();
    let s = scene
        .medium("g")
        .unwrap()
        .sample(glam::DVec3::new(0.25, 0.5, 0.5))
        .unwrap();
    // Trilinear: n = 1 + 0.2 x, ∇n = (0.2, 0, 0), exactly.
    assert!(
        (s.n - 1.05).abs() < 1e-15 && (s.grad - glam::DVec3::new(0.2, 0.0, 0.0)).length() < 1e-15
    );
    std::fs::remove_dir_all(&dir).unwrap();
    let missing = scene.medium("nope").err().expect("no such medium");
    assert!(missing.to_string().contains("no medium named 'nope'"));
}

/// A density on a medium that neither absorbs nor scatters would scale nothing: the scene
/// loads with a warning at the key.
#[test]
fn a_density_that_scales_nothing_is_a_warning() {
    let text = "[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = 1\n\
                density_bounds = [[0, 0, 0], [1, 1, 1]]\ndensity_dims = [2, 2, 2]\n\
                density_values = [1, 1, 1, 1, 1, 1, 1, 1]\n";
    let (description, _) =
        grinlight::scene::load::parse_description(Path::new("d.toml"), text.to_string()).unwrap();
    let said = description.warnings.join("\n");
    assert!(
        said.starts_with("d.toml:7:1: ") && said.contains("and this medium has neither"),
        "{said}"
    );
}

/// A scene's `time_budget` or `target_error` without `passes` renders as many passes as it
/// takes, as the command line's options do; with `passes` that many at most; with neither,
/// one.
#[test]
fn a_time_budget_in_the_scene_renders_as_many_passes_as_fit() {
    let camera = "[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\nfov_y_deg = 40\n";
    for (render, passes) in [
        ("time_budget = 30", u32::MAX),
        ("target_error = 0.01", u32::MAX),
        ("time_budget = 30\npasses = 5", 5),
        ("spp = 2", 1),
    ] {
        let text = format!("{camera}[render]\n{render}\n");
        let (_, settings) = grinlight::scene::load::parse_scene(Path::new("t.toml"), text).unwrap();
        assert_eq!(settings.passes, passes, "{render}");
    }
}

/// A phase function on a medium that does not scatter is a warning at its key; a scattering
/// coefficient given as a table of zeros is σs = 0, allowed (a table of indices must stay > 0).
#[test]
fn a_phase_without_scattering_is_a_warning_and_a_zero_table_is_no_scattering() {
    let text = "[[medium]]\nname = \"a\"\nprofile = \"uniform\"\nn = 1\nphase = { hg = 0.5 }\n\
                [[medium]]\nname = \"b\"\nprofile = \"uniform\"\nn = 1\n\
                scattering = { table = [[400, 0], [700, 0]] }\n";
    let (description, _) =
        grinlight::scene::load::parse_description(Path::new("p.toml"), text.to_string()).unwrap();
    let said = description.warnings.join("\n");
    assert!(
        said.starts_with("p.toml:5:1: ") && said.contains("does not scatter"),
        "{said}"
    );
    let scene = description.build();
    assert!(!scene.media().any_scatters());
    let index =
        "[[medium]]\nname = \"c\"\nprofile = \"uniform\"\nn = { table = [[400, 0], [700, 1.5]] }\n";
    let e = grinlight::scene::load::parse_description(Path::new("i.toml"), index.to_string())
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("key `n`") && e.contains("> 0"), "{e}");
}

/// A mesh given in the scene by its points and indices (as a converted pbrt scene writes it)
/// is the mesh of the OBJ file with the same vertices and faces: the same image, byte for byte.
#[test]
fn a_mesh_given_by_its_points_renders_as_its_obj_file() {
    let dir = std::env::temp_dir().join(format!("grinlight-inline-mesh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let obj = dir.join("tetra.obj");
    std::fs::write(
        &obj,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\n\
         f 1/1 3/3 2/2\nf 1/1 2/2 4/4\nf 1/1 4/4 3/3\nf 2/2 3/3 4/4\n",
    )
    .unwrap();
    let head = "[camera]\nposition = [2, 1.5, 3]\nlook_at = [0.3, 0.3, 0.3]\nfov_x_deg = 40\nwidth = 24\nheight = 16\n\
                [render]\nintegrator = \"path\"\nspp = 4\nthreads = 1\n\
                [[light]]\ntype = \"point\"\nposition = [2, 3, 2]\nintensity = [20, 20, 20]\n\
                [[material]]\nname = \"m\"\ntype = \"diffuse\"\nalbedo = [0.7, 0.5, 0.3]\n\
                [[shape]]\ntype = \"mesh\"\nmaterial = \"m\"\nmatrix = [1, 0, 0, 0.1, 0, 2, 0, 0, 0, 0, 1, -0.2]\n";
    let from_file = format!("{head}file = \"{}\"\n", obj.display());
    let inline = format!(
        "{head}points = [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1]\nindices = [0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]\n\
         uv = [0, 0, 1, 0, 0, 1, 1, 1]\n"
    );
    let render = |text: String| {
        let (scene, settings) = parse_scene(Path::new("mesh.toml"), text).expect("loads");
        grinlight::render::render(&scene, &settings, &())
            .unwrap()
            .0
            .layer("beauty")
            .unwrap()
    };
    let (a, b) = (render(from_file), render(inline));
    assert!(a.iter().any(|p| p[0] > 0.0), "the mesh is seen");
    assert_eq!(a, b);
}

/// A mesh light's keys are read as a mesh shape's and refused by file, line and key: a mesh
/// whose triangles all have zero area, a `flip` that is not a boolean, a key it does not take.
#[test]
fn a_mesh_lights_bad_keys_are_refused_by_line_and_key() {
    let light = |keys: &str| {
        let text = format!("[[light]]\ntype = \"mesh\"\nradiance = [1, 1, 1]\n{keys}\n");
        grinlight::scene::load::parse_description(Path::new("m.toml"), text)
            .err()
            .map(|e| e.to_string())
    };
    let flat = "points = [0, 0, 0, 1, 0, 0, 2, 0, 0]\nindices = [0, 1, 2]";
    let e = light(flat).expect("a line is no emitter");
    assert!(
        e.starts_with("m.toml:4:1: ") && e.contains("key `points`") && e.contains("zero area"),
        "{e}"
    );
    let good = "points = [0, 0, 0, 1, 0, 0, 0, 0, 1]\nindices = [0, 1, 2]";
    assert_eq!(light(good), None);
    let e = light(&format!("{good}\nflip = 1")).expect("flip is a boolean");
    assert!(e.contains("flip"), "{e}");
    let e = light(&format!("{good}\ncolour = [1, 1, 1]")).expect("an unknown key");
    assert!(e.contains("colour"), "{e}");
}
