//! IES LM-63 photometric files (the 1986, 1991, 1995, 2002 and 2019 editions): the header lines
//! (keywords ignored), `TILT=NONE` or `TILT=INCLUDE` (its lamp-tilt table read past: a tilt
//! changes the lamp's output with the luminaire's tilt, which a scene does not have), the
//! numbers that follow, and the candela table. Type C photometry (architectural and roadway
//! luminaires) has its horizontal symmetry expanded to a full turn: one plane (rotationally
//! symmetric), 0–90° (quadrants), 0–180° or 90–270° (bilateral), 0–360° (or a full turn short
//! of 360°). Types B (floodlights) and A (automotive) have horizontal angles from −90° to 90°,
//! or from 0° to 90° for a laterally symmetric luminaire (mirrored), and vertical angles within
//! ±90°; their web lies on the luminaire as [`Web`] says. Outside the measured vertical angles
//! the intensity is 0, as the file gives nothing there. Intensities are the file's candelas
//! times its multiplier and ballast factor. External tilt files are refused by name.

use super::{Goniogram, Web};

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
    let web = match next("photometric type")? {
        1.0 => Web::C,
        2.0 => Web::B,
        3.0 => Web::A,
        other => {
            return Err(format!(
                "photometric type {other}: expected 1 (type C), 2 (type B) or 3 (type A)"
            ))
        }
    };
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
    let (lowest, highest) = match web {
        Web::C => (0.0, 180.0),
        Web::B | Web::A => (-90.0, 90.0),
    };
    if !ascending(&vertical) || vertical[0] < lowest || vertical[n_vertical - 1] > highest {
        return Err(format!(
            "the vertical angles must rise within {lowest} to {highest}°, got {} to {}",
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
    let table = Table {
        vertical,
        horizontal,
        candela: candela.into_iter().map(|c| c * scale).collect(),
    };
    match web {
        Web::C => table.type_c(),
        Web::B => table.type_b(),
        Web::A => table.type_a(),
    }
}

/// A file's candela table: per horizontal angle (degrees), the candelas (times the file's
/// multiplier and ballast factor) at every vertical angle (degrees).
struct Table {
    vertical: Vec<f64>,
    horizontal: Vec<f64>,
    candela: Vec<f64>,
}

impl Table {
    /// The candelas at horizontal angle `i`, over the vertical angles.
    fn column(&self, i: usize) -> Vec<f64> {
        let n = self.vertical.len();
        self.candela[i * n..(i + 1) * n].to_vec()
    }

    /// Type C: γ is the vertical angle, C the horizontal one, the horizontal symmetry expanded
    /// to a full turn.
    fn type_c(&self) -> Result<Goniogram, String> {
        let horizontal = &self.horizontal;
        let n_horizontal = horizontal.len();
        let column = |i: usize| self.column(i);
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
        let thetas = self.vertical.iter().map(|v| v.to_radians()).collect();
        let phis = planes.iter().map(|(c, _)| c.to_radians()).collect();
        let values = planes.into_iter().flat_map(|(_, v)| v).collect();
        Ok(Goniogram::new(Web::C, thetas, phis, values))
    }

    /// Types A and B's horizontal angles H with the file's index of each one's column, H
    /// ascending: from −90° to 90°, or from 0° to 90° for a luminaire laterally symmetric about
    /// its vertical reference plane (mirrored, H as −H).
    fn lateral(&self) -> Result<Vec<(f64, usize)>, String> {
        let h = &self.horizontal;
        let given = 0..h.len();
        match (h[0], h[h.len() - 1]) {
            (-90.0, 90.0) => Ok(given.map(|i| (h[i], i)).collect()),
            (0.0, 90.0) => Ok(given
                .clone()
                .rev()
                .filter(|&i| h[i] > 0.0)
                .map(|i| (-h[i], i))
                .chain(given.map(|i| (h[i], i)))
                .collect()),
            (first, last) => Err(format!(
                "horizontal angles from {first} to {last}: types A and B expect −90 to 90, or 0 to 90 (laterally symmetric)"
            )),
        }
    }

    /// The candela at the file's horizontal angle `h` and vertical angle `v` (indices).
    fn at(&self, h: usize, v: usize) -> f64 {
        self.candela[h * self.vertical.len() + v]
    }

    /// Type A: the web's longitude is H, its polar angle 90° − V (so the vertical angles run
    /// backwards).
    fn type_a(&self) -> Result<Goniogram, String> {
        let columns = self.lateral()?;
        let n = self.vertical.len();
        let thetas = self.vertical.iter().rev().map(|v| polar(*v)).collect();
        let phis = columns.iter().map(|(h, _)| h.to_radians()).collect();
        let values = columns
            .iter()
            .flat_map(|&(_, h)| (0..n).rev().map(move |v| self.at(h, v)))
            .collect();
        Ok(Goniogram::new(Web::A, thetas, phis, values))
    }

    /// Type B: the web's longitude is V, its polar angle 90° − H (so the horizontal angles
    /// run backwards).
    fn type_b(&self) -> Result<Goniogram, String> {
        let columns = self.lateral()?;
        let thetas = columns.iter().rev().map(|(h, _)| polar(*h)).collect();
        let phis = self.vertical.iter().map(|v| v.to_radians()).collect();
        let values = (0..self.vertical.len())
            .flat_map(|v| columns.iter().rev().map(move |&(_, h)| self.at(h, v)))
            .collect();
        Ok(Goniogram::new(Web::B, thetas, phis, values))
    }
}

/// The polar angle (radians) of an angle `degrees` above a web's equator.
fn polar(degrees: f64) -> f64 {
    (90.0 - degrees).to_radians()
}
