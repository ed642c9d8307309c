//! `[[medium]]` tables ⇒ media. Each profile's keys, units and defaults are listed in
//! `docs/scene-format.md`; lengths are scene units, vectors [x, y, z].

use super::model::{Crystal, Profile};
use super::table::TableReader;
use crate::color::Rgb;
use crate::error::Result;
use crate::math::Bounds3;
use crate::media::{
    Axis, BlackHole, Density, ExactBlackHole, ExponentialMedium, FishEye, GridError, GridMedium,
    GridQuantity, HeightTable, HyperbolicMedium, Interpolation, LinearMedium, Luneburg, Medium,
    ParabolicFiber, Parametric, RadialTable, SechFiber, UniformMedium, GLADSTONE_DALE_AIR,
    STANDARD_PRESSURE,
};
use crate::spectrum::{Dispersion, Excitation, Fluorophore, LAMBDA_D};
use crate::volume::{Absorption, Emission, Fluorescence, Phase, Scattering};
use glam::DVec3;
use std::sync::Arc;
use toml::Value;

/// The profile names a `[[medium]]` table may give.
pub const PROFILES: &[&str] = &[
    "uniform",
    "uniaxial",
    "linear",
    "exponential",
    "parabolic",
    "sech",
    "radial_table",
    "height_table",
    "luneburg",
    "fisheye",
    "hyperbolic",
    "black_hole",
    "schwarzschild",
    "reissner_nordstrom",
    "grid",
];

/// A `[[medium]]` table's `absorption` coefficient σa (1/length, a number or RGB, ≥ 0; 0 or
/// absent: it does not absorb), scaled by `density` if it is heterogeneous.
pub fn read_absorption(
    t: &mut TableReader,
    density: Option<Arc<Density>>,
) -> Result<Option<Absorption>> {
    let sigma_a = t.rgb_or("absorption", Some(Rgb::ZERO))?;
    t.check(
        "absorption",
        sigma_a.0.is_finite(),
        format!("must be finite (1/length), got {sigma_a}"),
    )?;
    Ok((sigma_a.max_element() > 0.0).then_some(Absorption { sigma_a, density }))
}

/// A `[[medium]]` table's `emission` Le (basic radiance, RGB ≥ 0: emitted at the rate σa,
/// [`crate::volume::Emission`]); refused on a medium that does not absorb, which cannot emit.
pub fn read_emission(t: &mut TableReader, absorbs: bool) -> Result<Option<Emission>> {
    if !t.has("emission") {
        return Ok(None);
    }
    let radiance = t.rgb_or("emission", Some(Rgb::ZERO))?;
    t.check(
        "emission",
        radiance.0.is_finite() && radiance.0.min_element() >= 0.0,
        format!("must be finite and ≥ 0 in every channel, got {radiance:?}"),
    )?;
    t.check(
        "emission",
        absorbs || radiance.max_element() == 0.0,
        "a medium emits σa·Le per unit length (Kirchhoff's law): give it an `absorption` > 0",
    )?;
    Ok((radiance.max_element() > 0.0).then_some(Emission { radiance }))
}

/// A `[[medium]]` table's dye, if it holds one: `fluorescence = { absorption = σf over
/// wavelength (1/length, ≥ 0, as `scattering`'s forms), emission = the emitted photons'
/// spectrum (as a light's `spectrum`), quantum_yield = q in [0, 1] }` ([`Fluorescence`]). A dye
/// is spread evenly: refused with a `density`; and a medium that holds one scatters the same
/// in every channel or by a form over wavelength (an RGB σs has no value at one wavelength).
pub fn read_fluorescence(
    t: &mut TableReader,
    density: bool,
    scattering: Option<&Scattering>,
) -> Result<Option<Fluorescence>> {
    let Some(mut f) = t.nested("fluorescence")? else {
        return Ok(None);
    };
    let absorption = absorbing_form(&mut f, "absorption", f64::INFINITY, "≥ 0 and finite")?;
    let fluorophore = read_fluorophore(&mut f)?;
    f.finish()?;
    t.check(
        "fluorescence",
        !density,
        "a dye is spread evenly through its medium: not with a density",
    )?;
    t.check(
        "fluorescence",
        scattering.is_none_or(|s| s.is_spectral() || s.is_grey()),
        "a medium holding a dye scatters the same in every channel or by a form over wavelength (an RGB σs has no value at one wavelength)",
    )?;
    // `absorbing_form` has checked that it absorbs somewhere from 360 to 830 nm.
    let absorption = Excitation::new(absorption, f64::INFINITY)
        .ok_or_else(|| t.error("fluorescence", "the dye absorbs nothing from 360 to 830 nm"))?;
    Ok(Some(Fluorescence {
        absorption,
        fluorophore,
    }))
}

/// A fluorophore's absorption, `key` of its `fluorescence` table `f`: a form over wavelength
/// within [0, `most`] (finite) from 360 to 830 nm (`bounds` in words), above 0 somewhere.
pub fn absorbing_form(
    f: &mut TableReader,
    key: &str,
    most: f64,
    bounds: &str,
) -> Result<Dispersion> {
    let form = f.over_wavelength(key)?;
    let (low, high) = (form.min_visible(), form.max_visible());
    f.check(
        key,
        low >= 0.0 && high.is_finite() && high <= most,
        format!("must be {bounds} from 360 to 830 nm, got {low:?} to {high:?}"),
    )?;
    f.check(key, high > 0.0, "it absorbs nothing from 360 to 830 nm")?;
    Ok(form)
}

/// A `fluorescence` table's fluorophore: `emission` (the emitted photons' spectrum, in the
/// forms of a light's `spectrum`) and `quantum_yield` q in [0, 1].
pub fn read_fluorophore(f: &mut TableReader) -> Result<Fluorophore> {
    let emission = f
        .spectrum_opt("emission")?
        .ok_or_else(|| f.error("emission", "is missing"))?;
    let quantum_yield = f.f64("quantum_yield")?;
    f.check(
        "quantum_yield",
        (0.0..=1.0).contains(&quantum_yield),
        format!("photons emitted per photon absorbed: must be in [0, 1], got {quantum_yield}"),
    )?;
    Ok(Fluorophore {
        emission,
        quantum_yield,
    })
}

/// A `[[medium]]` table's scattering, if it scatters: `scattering` σs (1/length, ≥ 0: a
/// number, RGB, or a form over wavelength such as `{ angstrom = [σs, nm, 4] }` or
/// `{ table = [[nm, σs], ...] }`; 0 or absent: it does not) and `phase` (`"isotropic"`, the
/// default, or `{ hg = g }`, Henyey–Greenstein with −1 < g < 1), scaled by `density` if it is
/// heterogeneous.
pub fn read_scattering(
    t: &mut TableReader,
    density: Option<Arc<Density>>,
) -> Result<Option<Scattering>> {
    let phase_given = t.has("phase");
    let phase = match t.value_opt("phase") {
        None => Phase::Isotropic,
        Some(Value::String(name)) if name == "isotropic" => Phase::Isotropic,
        Some(Value::String(name)) if name == "rayleigh" => Phase::Rayleigh,
        Some(Value::Table(table)) if table.len() == 1 && table.contains_key("hg") => {
            let g = t.numbers_in("phase", &table["hg"])?;
            t.check(
                "phase",
                g.len() == 1 && g[0].abs() < 1.0,
                format!("hg takes one mean cosine g with −1 < g < 1, got {g:?}"),
            )?;
            Phase::HenyeyGreenstein { g: g[0] }
        }
        Some(other) => {
            return Err(t.error(
                "phase",
                format!("expected \"isotropic\", \"rayleigh\" or {{ hg = g }}, got {other}"),
            ))
        }
    };
    let warn_unused_phase = |t: &TableReader, scatters: bool| {
        if phase_given && !scatters {
            t.warn(
                "phase",
                "this medium does not scatter (no `scattering` > 0): its phase function does nothing",
            );
        }
    };
    if !t.is_over_wavelength("scattering") {
        let sigma_s = t.rgb_or("scattering", Some(Rgb::ZERO))?;
        warn_unused_phase(t, sigma_s.max_element() > 0.0);
        return Ok((sigma_s.max_element() > 0.0).then_some(Scattering {
            sigma_s,
            spectrum: None,
            phase,
            density,
        }));
    }
    let spectrum = t.over_wavelength("scattering")?;
    let (least, most) = (spectrum.min_visible(), spectrum.max_visible());
    t.check(
        "scattering",
        least >= 0.0 && most.is_finite(),
        format!("must be ≥ 0 and finite from 360 to 830 nm, got {least:?} to {most:?}"),
    )?;
    warn_unused_phase(t, most > 0.0);
    Ok((most > 0.0).then(|| Scattering::over_wavelength(spectrum, phase, density)))
}

/// The index profile of a `[[medium]]` table. Every index-valued key (`n`, `n0`) and the
/// fiber profiles' shape constants (`a` or `g` of `parabolic`, `g` of `sech`) may depend on
/// wavelength; the medium is dispersive when one of them does.
pub fn read_profile(t: &mut TableReader) -> Result<Profile> {
    let profile = t.string("profile")?;
    Ok(match profile.as_str() {
        "radial_table" | "height_table" | "grid" => Profile::Fixed(read_fixed(t, &profile)?),
        "luneburg" | "black_hole" | "schwarzschild" | "reissner_nordstrom" => {
            Profile::Parametric(read_spherical(t, &profile)?)
        }
        "uniform" => uniform(t.dispersion("n")?),
        "uniaxial" => {
            let mut index = |key: &str| -> Result<Dispersion> {
                let n = t.dispersion(key)?;
                let most = n.max_visible();
                t.check(
                    key,
                    most <= 10.0,
                    format!("must be at most 10 from 360 to 830 nm, got {most:?} there"),
                )?;
                Ok(n)
            };
            let (ordinary, extraordinary) = (index("no")?, index("ne")?);
            Profile::Crystal(Box::new(Crystal {
                ordinary,
                extraordinary,
                axis: t.direction("optic_axis")?,
            }))
        }
        "linear" => {
            let n0 = t.dispersion("n0")?;
            let (gradient, origin) = (t.vec3("gradient")?, t.vec3_or("origin", DVec3::ZERO)?);
            by_wavelength([n0], move |[n0]| {
                Parametric::Linear(LinearMedium {
                    n0,
                    gradient,
                    origin,
                })
            })
        }
        "exponential" => {
            let n0 = t.dispersion("n0")?;
            let (gradient, origin) = (t.vec3("gradient")?, t.vec3_or("origin", DVec3::ZERO)?);
            by_wavelength([n0], move |[n0]| {
                Parametric::Exponential(ExponentialMedium {
                    n0,
                    gradient,
                    origin,
                })
            })
        }
        "parabolic" => {
            let n0 = t.dispersion("n0")?;
            let (shape, is_g) = read_parabolic_shape(t)?;
            let axis = fiber_axis(t)?;
            by_wavelength([n0, shape], move |[n0, shape]| {
                Parametric::Parabolic(ParabolicFiber {
                    n0,
                    a: if is_g { shape * shape } else { shape },
                    axis,
                })
            })
        }
        "sech" => {
            let n0 = t.dispersion("n0")?;
            let g = t.dispersion("g")?;
            let axis = fiber_axis(t)?;
            by_wavelength([n0, g], move |[n0, g]| {
                Parametric::Sech(SechFiber { n0, g, axis })
            })
        }
        // The two constant-curvature media: n0 / (1 ± (r/R)²).
        "fisheye" | "hyperbolic" => {
            let n0 = t.dispersion("n0")?;
            let center = t.vec3_or("center", DVec3::ZERO)?;
            let radius = t.positive("radius")?;
            let hyperbolic = profile == "hyperbolic";
            by_wavelength([n0], move |[n0]| {
                if hyperbolic {
                    Parametric::Hyperbolic(HyperbolicMedium { n0, center, radius })
                } else {
                    Parametric::FishEye(FishEye { n0, center, radius })
                }
            })
        }
        other => {
            return Err(t.error(
                "profile",
                format!(
                    "unknown profile '{other}' (expected one of: {})",
                    PROFILES.join(", ")
                ),
            ))
        }
    })
}

/// The medium `make` builds from `values` evaluated at each wavelength: fixed (built once at
/// [`LAMBDA_D`]) when none of them depends on wavelength.
fn by_wavelength<const N: usize>(
    values: [Dispersion; N],
    make: impl Fn([f64; N]) -> Parametric + Send + Sync + 'static,
) -> Profile {
    let dispersive = values.iter().any(Dispersion::is_dispersive);
    let at = move |nm: f64| make(values.each_ref().map(|d| d.at(nm)));
    if dispersive {
        Profile::Dispersive(Box::new(at))
    } else {
        Profile::Parametric(at(LAMBDA_D))
    }
}

/// A uniform medium of index `n` (a dielectric's `ior`, or `profile = "uniform"`).
pub fn uniform(n: Dispersion) -> Profile {
    by_wavelength([n], |[n]| Parametric::Uniform(UniformMedium { n }))
}

/// The parabolic profile's gradient constant: `a` (1/length²), or `g` (1/length) with
/// a = g², the form GRIN catalogues give per wavelength; exactly one of them. True for `g`.
fn read_parabolic_shape(t: &mut TableReader) -> Result<(Dispersion, bool)> {
    match (t.has("a"), t.has("g")) {
        (true, false) => Ok((t.over_wavelength("a")?, false)),
        (false, true) => Ok((t.dispersion("g")?, true)),
        _ => Err(t.error(
            "a",
            "give exactly one of `a` (1/length²) and `g` (1/length, a = g²)",
        )),
    }
}

/// A fiber's axis: `center` and `axis` (default the z axis through the origin).
fn fiber_axis(t: &mut TableReader) -> Result<Axis> {
    Ok(Axis {
        center: t.vec3_or("center", DVec3::ZERO)?,
        axis: t.direction_or("axis", DVec3::Z)?,
    })
}

/// The spherically symmetric profiles given by their constants (the same at every
/// wavelength): the Luneburg lens and the black holes.
fn read_spherical(t: &mut TableReader, profile: &str) -> Result<Parametric> {
    let center = t.vec3_or("center", DVec3::ZERO)?;
    Ok(match profile {
        "luneburg" => Parametric::Luneburg(Luneburg {
            center,
            radius: t.positive("radius")?,
        }),
        "black_hole" => {
            let rs = t.positive("rs")?;
            let q = t.f64_or("q", 0.0)?;
            t.check("q", q >= 0.0, format!("must be ≥ 0, got {q:?}"))?;
            Parametric::BlackHole(BlackHole::new(center, rs, q))
        }
        _ => {
            let rs = t.positive("rs")?;
            let q = if profile == "schwarzschild" {
                0.0
            } else {
                t.f64("q")?
            };
            t.check("q", q >= 0.0, format!("must be ≥ 0, got {q:?}"))?;
            Parametric::ExactBlackHole(ExactBlackHole { center, rs, q })
        }
    })
}

/// The profiles of data: tables and grids (the same at every wavelength).
fn read_fixed(t: &mut TableReader, profile: &str) -> Result<Box<dyn Medium>> {
    Ok(match profile {
        "radial_table" => {
            let r = t.f64_list("r")?;
            let n = t.f64_list("n")?;
            let axis = fiber_axis(t)?;
            Box::new(RadialTable::new(r, n, axis).map_err(|(key, e)| t.error(key, e))?)
        }
        "height_table" => {
            let h = t.f64_list("h")?;
            let n = t.f64_list("n")?;
            let origin = t.vec3_or("origin", DVec3::ZERO)?;
            let up = t.direction_or("up", DVec3::Y)?;
            Box::new(HeightTable::new(h, n, origin, up).map_err(|(key, e)| t.error(key, e))?)
        }
        _ => Box::new(read_grid(t)?),
    })
}

/// A lattice's nodes as a `[[medium]]` table gives them, under keys named with `prefix`:
/// `bounds`, `dims` and `values` or a text `file`; `bounds` and a Mitsuba `.vol` `file` that
/// gives the other two; or a VDB `file` (with its `grid` name and `background`) that gives all
/// three.
struct Nodes {
    min: DVec3,
    max: DVec3,
    dims: [usize; 3],
    values: Vec<f64>,
    /// The key the values came from (`values` or `file`, prefixed).
    key: String,
    /// The key their count came from (`dims`, or a file that gives it, prefixed).
    dims_key: String,
    /// A VDB file's `background` (the value of its inactive voxels), given.
    background: Option<f64>,
}

fn read_nodes(t: &mut TableReader, prefix: &str) -> Result<Nodes> {
    let key = |name: &str| format!("{prefix}{name}");
    let file = t
        .has(&key("file"))
        .then(|| t.input_file(&key("file")))
        .transpose()?;
    let vdb = file
        .as_ref()
        .filter(|f| f.extension().is_some_and(|e| e.eq_ignore_ascii_case("vdb")));
    if let Some(path) = vdb {
        for name in ["bounds", "dims", "values"] {
            if t.has(&key(name)) {
                return Err(t.error(
                    &key(name),
                    "a VDB file gives the grid's voxels, their place and their count: leave out \
                     `bounds`, `dims` and `values`",
                ));
            }
        }
        let name = t.string_opt(&key("grid"))?;
        let background = t.f64_opt(&key("background"))?;
        let dense = super::vdb::read(path, name.as_deref(), background)
            .map_err(|e| t.error(&key("file"), format!("{}: {e}", path.display())))?;
        return Ok(Nodes {
            min: dense.min,
            max: dense.max,
            dims: dense.dims,
            values: dense.values,
            key: key("file"),
            dims_key: key("file"),
            background,
        });
    }
    let bounds = t.vec3_list(&key("bounds"))?;
    let [min, max] = bounds[..] else {
        return Err(t.error(&key("bounds"), "expected [[min x, y, z], [max x, y, z]]"));
    };
    let mitsuba = file
        .as_ref()
        .filter(|f| f.extension().is_some_and(|e| e.eq_ignore_ascii_case("vol")));
    if let Some(path) = mitsuba {
        for name in ["dims", "values"] {
            if t.has(&key(name)) {
                return Err(t.error(
                    &key(name),
                    "a Mitsuba .vol file gives the grid's values and their count: leave out \
                     `dims` and `values`",
                ));
            }
        }
        let (dims, values) = super::vol::read(path)
            .map_err(|e| t.error(&key("file"), format!("{}: {e}", path.display())))?;
        return Ok(Nodes {
            min,
            max,
            dims,
            values,
            key: key("file"),
            dims_key: key("file"),
            background: None,
        });
    }
    let dims: [usize; 3] = t.counts(&key("dims"))?;
    let values = t.f64_list_opt(&key("values"))?;
    let (values, from) = match (values, &file) {
        (Some(v), None) => (v, key("values")),
        (None, Some(path)) => (read_grid_file(t, &key("file"), path, dims)?, key("file")),
        _ => {
            return Err(t.error(
                &key("values"),
                format!(
                    "give exactly one of `{}` and `{}`",
                    key("values"),
                    key("file")
                ),
            ))
        }
    };
    Ok(Nodes {
        min,
        max,
        dims,
        values,
        key: from,
        dims_key: key("dims"),
        background: None,
    })
}

/// The key of a lattice's table that `e` is about: a bad value that is the VDB file's
/// background is the `background` key's.
fn grid_error_key(e: &GridError, prefix: &str, nodes: &Nodes) -> String {
    match e {
        GridError::TooFewNodes(_) | GridError::TooManyNodes(_) => nodes.dims_key.clone(),
        GridError::EmptyBox => format!("{prefix}bounds"),
        GridError::BadValue { value, .. } if nodes.background == Some(*value) => {
            format!("{prefix}background")
        }
        GridError::BadValue { .. } | GridError::WrongCount { .. } => nodes.key.clone(),
    }
}

/// A `[[medium]]` table's `density` lattice, if it gives one (keys `density_bounds`,
/// `density_dims`, `density_values` or `density_file`, and for a VDB file `density_grid` and
/// `density_background`; `density_end`, the box outside which it is 0): a heterogeneous
/// medium's scale of σa and σs.
pub fn read_density(t: &mut TableReader) -> Result<Option<Arc<Density>>> {
    const PREFIX: &str = "density_";
    if !["file", "bounds", "dims", "values"]
        .iter()
        .any(|k| t.has(&format!("{PREFIX}{k}")))
    {
        return Ok(None);
    }
    let nodes = read_nodes(t, PREFIX)?;
    let mut nodes = nodes;
    let values = std::mem::take(&mut nodes.values);
    let density = Density::new(nodes.min, nodes.max, nodes.dims, values)
        .map_err(|e| t.error(&grid_error_key(&e, PREFIX, &nodes), e))?;
    let end = "density_end";
    if !t.has(end) {
        return Ok(Some(Arc::new(density)));
    }
    let corners = t.vec3_list(end)?;
    let [lo, hi] = corners[..] else {
        return Err(t.error(end, "expected [[min x, y, z], [max x, y, z]]"));
    };
    t.check(
        end,
        lo.is_finite() && hi.is_finite() && lo.cmplt(hi).all(),
        "the box's min must lie below its max on every axis, both finite",
    )?;
    Ok(Some(Arc::new(density.ending_at(Bounds3::new(lo, hi)))))
}

fn read_grid(t: &mut TableReader) -> Result<GridMedium> {
    let mut nodes = read_nodes(t, "")?;
    let quantity = read_grid_quantity(t)?;
    let values = std::mem::take(&mut nodes.values)
        .into_iter()
        .enumerate()
        .map(|(i, v)| {
            quantity
                .index(v)
                .map_err(|e| match nodes.background == Some(v) {
                    true => t.error("background", format!("{}: {e}", crate::error::number(v))),
                    false => t.error(&nodes.key, format!("value #{i}: {e}")),
                })
        })
        .collect::<Result<Vec<f64>>>()?;
    let Nodes { min, max, dims, .. } = nodes;
    let interpolation = match t
        .string_opt("interpolation")?
        .as_deref()
        .unwrap_or("linear")
    {
        "linear" => Interpolation::Linear,
        "cubic" => Interpolation::Cubic,
        other => {
            return Err(t.error(
                "interpolation",
                format!("unknown interpolation '{other}' (expected linear or cubic)"),
            ))
        }
    };
    GridMedium::new(min, max, dims, values, interpolation)
        .map_err(|e| t.error(&grid_error_key(&e, "", &nodes), e))
}

/// A grid's `quantity`: `index` (the default), `density` (kg/m³, with `gladstone_dale` in
/// m³/kg, air's by default) or `temperature` (K, air at `pressure` Pa, 101 325 by default).
fn read_grid_quantity(t: &mut TableReader) -> Result<GridQuantity> {
    let quantity = t.string_opt("quantity")?;
    let gladstone_dale = |t: &mut TableReader| t.positive_or("gladstone_dale", GLADSTONE_DALE_AIR);
    Ok(match quantity.as_deref().unwrap_or("index") {
        "index" => GridQuantity::Index,
        "density" => GridQuantity::Density {
            gladstone_dale: gladstone_dale(t)?,
        },
        "temperature" => GridQuantity::Temperature {
            pressure: t.positive_or("pressure", STANDARD_PRESSURE)?,
            gladstone_dale: gladstone_dale(t)?,
        },
        other => {
            return Err(t.error(
                "quantity",
                format!("unknown quantity '{other}' (expected index, density or temperature)"),
            ))
        }
    })
}

/// The `dims` lattice's node values from a text file of numbers (whitespace between them, `#`
/// starting a comment to the end of its line), read line by line: never more than the
/// lattice's nodes are kept (a file with more is refused at the first extra number), the
/// lattice must fit in memory before any is read, and a word that is not a number is shown
/// cut to a few dozen characters.
fn read_grid_file(
    t: &TableReader,
    key: &str,
    path: &std::path::Path,
    dims: [usize; 3],
) -> Result<Vec<f64>> {
    use std::io::BufRead;
    let fail = |why: String| t.error(key, format!("{}: {why}", path.display()));
    let expected = dims
        .iter()
        .try_fold(1usize, |a, &d| a.checked_mul(d))
        .ok_or_else(|| {
            fail(format!(
                "dims {dims:?} hold more nodes than can be addressed"
            ))
        })?;
    crate::resources::check_memory(
        (expected as u64).saturating_mul(3 * 8),
        &format!("a lattice of {expected} nodes"),
    )
    .map_err(|e| t.error(key, e))?;
    crate::input::check_regular(path)?;
    let file = std::fs::File::open(path).map_err(|e| fail(format!("cannot read it: {e}")))?;
    let mut values = Vec::with_capacity(expected);
    let mut line = String::new();
    let mut reader = std::io::BufReader::new(file);
    for number in 1.. {
        line.clear();
        // A line is read whole: a file of one endless line (no newline) is refused past 1 MiB.
        let read = std::io::Read::take(&mut reader, MAX_LINE_BYTES + 1)
            .read_line(&mut line)
            .map_err(|e| fail(format!("line {number}: {e}")))?;
        if read == 0 {
            break;
        }
        if read as u64 > MAX_LINE_BYTES {
            return Err(fail(format!(
                "line {number} is longer than 1 MiB: not a grid of numbers"
            )));
        }
        crate::interrupt::check(number, "a grid file").map_err(fail)?;
        for w in line.split('#').next().unwrap_or("").split_whitespace() {
            let v = w.parse::<f64>().map_err(|_| {
                fail(format!(
                    "line {number}: value #{} '{}' is not a number",
                    values.len(),
                    crate::error::cut(w)
                ))
            })?;
            if values.len() == expected {
                return Err(fail(format!(
                    "more than the {expected} values of dims {dims:?} (line {number})"
                )));
            }
            values.push(v);
        }
    }
    Ok(values)
}

/// The longest line of a grid's text file read.
const MAX_LINE_BYTES: u64 = 1 << 20;
