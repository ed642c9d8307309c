//! IES LM-63 photometric files (the 1986, 1991, 1995, 2002 and 2019 editions): the header lines
//! (keywords ignored), `TILT=NONE` or `TILT=INCLUDE` (its lamp-tilt table read past: a tilt
//! changes the lamp's output with the luminaire's tilt, which a scene does not have), the
//! numbers that follow, and the candela table of type C photometry, its horizontal symmetry
//! expanded to a full turn: one plane (rotationally symmetric), 0–90° (quadrants), 0–180° or
//! 90–270° (bilateral), 0–360° (or a full turn short of 360°). Intensities are the file's candelas times its multiplier and
//! ballast factor. Type A and B photometry (floodlights, automotive) and external tilt files are
//! refused by name.

use super::Goniogram;

/// The goniogram of an IES file's `text`, or why it cannot be read.
pub fn parse(text: &str) -> Result<Goniogram, String> {
    let mut lines = text.lines();
    let tilt = loop {
        let line = lines
            .next()
            .ok_or("no TILT= line: not an IES LM-63 file")?
            .trim();
        if let Some(rest) = line.strip_prefix("TILT=") {
            break rest.trim().to_string();
        }
    };
    let rest: Vec<&str> = lines.collect();
    let mut numbers = rest
        .iter()
        .flat_map(|l| l.split(|c: char| c.is_whitespace() || c == ','))
        .filter(|w| !w.is_empty());
    let mut next = |what: &str| -> Result<f64, String> {
        let word = numbers
            .next()
            .ok_or_else(|| format!("the file ends before its {what}"))?;
        word.parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| format!("{what}: '{word}' is not a number"))
    };
    let count = |x: f64, what: &str| -> Result<usize, String> {
        match x.fract() == 0.0 && (1.0..=100_000.0).contains(&x) {
            true => Ok(x as usize),
            false => Err(format!(
                "{what} must be a whole number from 1 to 100000, got {x}"
            )),
        }
    };
    match tilt.as_str() {
        "NONE" => {}
        "INCLUDE" => {
            next("lamp-to-luminaire geometry")?;
            let n = count(next("number of tilt angles")?, "the number of tilt angles")?;
            for _ in 0..2 * n {
                next("tilt table")?;
            }
        }
        file => {
            return Err(format!(
                "TILT={file}: a tilt file of its own is not read (give TILT=NONE or INCLUDE)"
            ))
        }
    }
    let _lamps = next("number of lamps")?;
    let _lumens = next("lumens per lamp")?;
    let multiplier = next("candela multiplier")?;
    let n_vertical = count(
        next("number of vertical angles")?,
        "the number of vertical angles",
    )?;
    let n_horizontal = count(
        next("number of horizontal angles")?,
        "the number of horizontal angles",
    )?;
    let photometric_type = next("photometric type")?;
    if photometric_type != 1.0 {
        return Err(format!(
            "photometric type {photometric_type}: only type C (1) is read, not type B (2) or A (3)"
        ));
    }
    let _units = next("units type")?;
    let _width = next("width")?;
    let _length = next("length")?;
    let _height = next("height")?;
    let ballast = next("ballast factor")?;
    // 2002's field for future use; 2019's file-generation type: how the file was made.
    let _future = next("ballast-lamp photometric factor or file-generation type")?;
    let _watts = next("input watts")?;
    let read = |n: usize, what: &str, next: &mut dyn FnMut(&str) -> Result<f64, String>| {
        (0..n)
            .map(|_| next(what))
            .collect::<Result<Vec<f64>, String>>()
    };
    let vertical = read(n_vertical, "vertical angles", &mut next)?;
    let horizontal = read(n_horizontal, "horizontal angles", &mut next)?;
    let candela = read(n_vertical * n_horizontal, "candela values", &mut next)?;
    let ascending = |a: &[f64]| a.windows(2).all(|w| w[0] < w[1]);
    if !ascending(&vertical) || vertical[0] < 0.0 || vertical[n_vertical - 1] > 180.0 {
        return Err(format!(
            "the vertical angles must rise within 0 to 180°, got {} to {}",
            vertical[0],
            vertical[n_vertical - 1]
        ));
    }
    if n_vertical < 2 {
        return Err("a table needs at least two vertical angles".into());
    }
    if !ascending(&horizontal) {
        return Err("the horizontal angles must rise".into());
    }
    let scale = multiplier * ballast;
    if scale < 0.0 || candela.iter().any(|&c| c < 0.0) {
        return Err("candela values, the multiplier and the ballast factor must be ≥ 0".into());
    }
    // Each horizontal plane's column, then the planes over a full turn.
    let column = |i: usize| candela[i * n_vertical..(i + 1) * n_vertical].to_vec();
    let (first, last) = (horizontal[0], horizontal[n_horizontal - 1]);
    let planes: Vec<(f64, Vec<f64>)> = match (first, last) {
        (0.0, 0.0) => vec![(0.0, column(0))],
        (0.0, 360.0) => (0..n_horizontal - 1).map(|i| (horizontal[i], column(i))).collect(),
        // A full turn that leaves out 360° (it is 0°).
        (0.0, l) if l > 270.0 && l < 360.0 => {
            (0..n_horizontal).map(|i| (horizontal[i], column(i))).collect()
        }
        // Mirrored about the plane C = 0–180 (0–180 given) or C = 90–270 (90–270 given).
        (0.0, 180.0) | (90.0, 270.0) => {
            let axis = first;
            let mut p: Vec<(f64, Vec<f64>)> = (0..n_horizontal).map(|i| (horizontal[i], column(i))).collect();
            p.extend((1..n_horizontal - 1).rev().map(|i| (2.0 * axis + 360.0 - horizontal[i], column(i))));
            p.iter_mut().for_each(|(c, _)| *c = c.rem_euclid(360.0));
            p.sort_by(|a, b| a.0.total_cmp(&b.0));
            p
        }
        // Quadrants: 0–90 mirrored into the other three.
        (0.0, 90.0) => {
            let mut p = Vec::new();
            for q in 0..4 {
                for k in 0..n_horizontal - 1 {
                    let (c, i) = match q % 2 {
                        0 => (q as f64 * 90.0 + horizontal[k], k),
                        _ => (q as f64 * 90.0 + 90.0 - horizontal[n_horizontal - 1 - k], n_horizontal - 1 - k),
                    };
                    p.push((c, column(i)));
                }
            }
            p
        }
        _ => {
            return Err(format!(
                "horizontal angles from {first} to {last}: expected 0 (one plane), 0–90, 0–180, 90–270 or 0–360"
            ))
        }
    };
    let gammas = vertical.iter().map(|v| v.to_radians()).collect();
    let cs = planes.iter().map(|(c, _)| c.to_radians()).collect();
    let values = planes
        .into_iter()
        .flat_map(|(_, v)| v)
        .map(|v| v * scale)
        .collect();
    Ok(Goniogram::new(gammas, cs, values))
}
