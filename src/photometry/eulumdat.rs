//! EULUMDAT (`.ldt`) photometric files: type C photometry in fixed lines — the symmetry
//! indicator Isym (line 3), the numbers of C planes Mc and of γ angles Ng (lines 4 and 6), the
//! lamp sets (line 26 on: their count, then per field one line a set), ten direct ratios, the
//! Mc C angles, the Ng γ angles, and the intensities (cd per 1000 lm of lamp flux) of the
//! planes the symmetry keeps: all Mc (Isym 0), one (1: rotationally symmetric), Mc/2 + 1 from
//! C = 0° to 180° (2: symmetric to the C0–C180 plane), Mc/2 + 1 from C = 270° through 0° to
//! 90° (3: symmetric to the C90–C270 plane), Mc/4 + 1 from 0° to 90° (4: both planes), as the
//! format's description by Stockmar (1990) counts them. Intensities are in candela: cd/klm
//! times the lamp sets' total flux over 1000, times the conversion factor (line 24).

use super::{Goniogram, Web};

/// A file's lines, numbered from 1, read in order.
struct Lines<'t, I: Iterator<Item = (usize, &'t str)>>(I);

impl<'t, I: Iterator<Item = (usize, &'t str)>> Lines<'t, I> {
    /// The next line (trimmed) and its number.
    fn text(&mut self, what: &str) -> Result<(usize, &'t str), String> {
        self.0
            .next()
            .map(|(i, l)| (i + 1, l.trim()))
            .ok_or_else(|| format!("the file ends before its {what}"))
    }

    /// The next line as a finite number (a decimal comma read as a point).
    fn number(&mut self, what: &str) -> Result<f64, String> {
        let (n, text) = self.text(what)?;
        text.replace(',', ".")
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| format!("line {n}, {what}: '{text}' is not a number"))
    }
}

/// The goniogram of a EULUMDAT file's `text`, or why it cannot be read.
pub fn parse(text: &str) -> Result<Goniogram, String> {
    let mut lines = Lines(text.lines().enumerate());
    let whole = |x: f64, what: &str, most: f64| -> Result<usize, String> {
        match x.fract() == 0.0 && (0.0..=most).contains(&x) {
            true => Ok(x as usize),
            false => Err(format!(
                "{what} must be a whole number from 0 to {most}, got {x}"
            )),
        }
    };
    lines.text("company")?;
    let _type = lines.number("type indicator")?;
    let symmetry = whole(
        lines.number("symmetry indicator")?,
        "the symmetry indicator",
        4.0,
    )?;
    let mc = whole(
        lines.number("number of C planes")?,
        "the number of C planes",
        100_000.0,
    )?;
    let _dc = lines.number("distance between C planes")?;
    let ng = whole(
        lines.number("number of γ angles")?,
        "the number of γ angles",
        100_000.0,
    )?;
    let _dg = lines.number("distance between γ angles")?;
    for what in [
        "report number",
        "luminaire name",
        "luminaire number",
        "file name",
        "date and user",
    ] {
        lines.text(what)?;
    }
    for what in [
        "length",
        "width",
        "height",
        "luminous length",
        "luminous width",
        "luminous height C0",
        "luminous height C90",
        "luminous height C180",
        "luminous height C270",
        "downward flux fraction",
        "light output ratio",
    ] {
        lines.number(what)?;
    }
    let conversion = lines.number("conversion factor")?;
    let _tilt = lines.number("tilt")?;
    let sets = whole(
        lines.number("number of lamp sets")?,
        "the number of lamp sets",
        1000.0,
    )?;
    let mut flux = 0.0;
    for field in [
        "number of lamps",
        "lamp type",
        "total lamp flux",
        "colour",
        "colour rendering",
        "wattage",
    ] {
        for _ in 0..sets {
            match field {
                "total lamp flux" => flux += lines.number(field)?,
                _ => {
                    lines.text(field)?;
                }
            }
        }
    }
    for _ in 0..10 {
        lines.number("direct ratios")?;
    }
    let cs = (0..mc)
        .map(|_| lines.number("C angles"))
        .collect::<Result<Vec<f64>, String>>()?;
    let gammas = (0..ng)
        .map(|_| lines.number("γ angles"))
        .collect::<Result<Vec<f64>, String>>()?;
    let stored = match symmetry {
        0 => mc,
        1 => 1,
        2 | 3 => mc / 2 + 1,
        _ => mc / 4 + 1,
    };
    let values = (0..stored * ng)
        .map(|_| lines.number("intensities"))
        .collect::<Result<Vec<f64>, String>>()?;
    if ng < 2 || mc == 0 || (symmetry != 1 && mc % 4 != 0) {
        return Err(format!(
            "{mc} C planes and {ng} γ angles: a table needs two γ angles and, unless rotationally symmetric, a multiple of 4 planes"
        ));
    }
    let ascending = |a: &[f64]| a.windows(2).all(|w| w[0] < w[1]);
    if !ascending(&gammas) || gammas[0] < 0.0 || gammas[ng - 1] > 180.0 {
        return Err("the γ angles must rise within 0 to 180°".into());
    }
    if !ascending(&cs) || cs[0] != 0.0 || cs[mc - 1] >= 360.0 {
        return Err("the C angles must rise from 0 to below 360°".into());
    }
    let even = cs
        .iter()
        .enumerate()
        .all(|(i, c)| (c - i as f64 * 360.0 / mc as f64).abs() < 1e-6);
    if symmetry > 1 && !even {
        return Err("a symmetric table's C planes must be evenly spaced".into());
    }
    let scale = flux / 1000.0 * conversion;
    if scale <= 0.0 || values.iter().any(|&v| v < 0.0) {
        return Err("intensities must be ≥ 0 and the lamp flux and conversion factor > 0".into());
    }
    // Every plane of the full turn, from the stored plane its symmetry maps it to.
    let column = |k: usize| values[k * ng..(k + 1) * ng].to_vec();
    let stored_at = |i: usize| -> usize {
        let c = cs[i];
        let folded = match symmetry {
            0 => return i,
            1 => return 0,
            2 => match c <= 180.0 {
                true => c,
                false => 360.0 - c,
            },
            3 => {
                // Mirrored about C90–C270 into 270° … 90°, counted from 270°.
                let m = match (90.0..=270.0).contains(&c) {
                    true => 180.0 - c,
                    false => c,
                };
                (m - 270.0).rem_euclid(360.0)
            }
            _ => {
                let half = if c <= 180.0 { c } else { 360.0 - c };
                if half <= 90.0 {
                    half
                } else {
                    180.0 - half
                }
            }
        };
        // The stored plane at that angle: planes are evenly spaced by the C list's step.
        let step = 360.0 / mc as f64;
        ((folded / step).round() as usize).min(stored - 1)
    };
    let planes: Vec<f64> = (0..mc).flat_map(|i| column(stored_at(i))).collect();
    Ok(Goniogram::new(
        Web::C,
        gammas.iter().map(|g| g.to_radians()).collect(),
        cs.iter().map(|c| c.to_radians()).collect(),
        planes.into_iter().map(|v| v * scale).collect(),
    ))
}
