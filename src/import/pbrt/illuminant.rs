//! pbrt-v4's named illuminant spectra beyond D65 and A (`src/pbrt/util/spectrum.cpp`: the CIE
//! 15:2004 tables of D50 and the fluorescent lamps F1–F12, and the ACES D60 white), every 5 nm,
//! kept as data in `illuminants.txt` (one per line: its name, its first wavelength, its
//! samples), and read as pbrt-v4 reads them: linear between the samples and, where the table
//! begins above 360 nm or ends below 830 nm, held at its end value one nanometre beyond the
//! visible range (`PiecewiseLinearSpectrum::FromInterleaved`), then scaled to unit luminance.

/// The table: one illuminant a line (`#` lines are comments).
const TABLE: &str = include_str!("illuminants.txt");

/// The samples' spacing, nm.
const STEP_NM: f64 = 5.0;

/// The names of the illuminants in the table, in order.
pub fn names() -> impl Iterator<Item = &'static str> {
    entries().filter_map(|line| line.split_whitespace().next())
}

/// The table's lines that hold an illuminant.
fn entries() -> impl Iterator<Item = &'static str> {
    TABLE
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
}

/// The (nm, value) rows of the illuminant called `name` as pbrt-v4 reads them — its samples,
/// and where they begin above 360 nm or end below 830 nm a row at 359 nm or 831 nm holding
/// the end value — or None where no illuminant is called so.
pub fn rows(name: &str) -> Option<Vec<(f64, f64)>> {
    let line = entries().find(|l| l.split_whitespace().next() == Some(name))?;
    let numbers: Vec<f64> = line
        .split_whitespace()
        .skip(1)
        .map(|w| w.parse().expect("the table's numbers"))
        .collect();
    let (first_nm, values) = numbers.split_first().expect("a first wavelength");
    let samples = values
        .iter()
        .enumerate()
        .map(|(k, &v)| (first_nm + STEP_NM * k as f64, v));
    let end_nm = first_nm + STEP_NM * (values.len() - 1) as f64;
    let before = (*first_nm > 360.0).then_some((359.0, values[0]));
    let after = (end_nm < 830.0).then_some((831.0, values[values.len() - 1]));
    Some(before.into_iter().chain(samples).chain(after).collect())
}

#[cfg(test)]
mod tests {
    /// Every line of the table parses: 14 illuminants, each of 81 samples (380–780 nm) or 107
    /// (300–830 nm).
    #[test]
    fn the_table_of_illuminants_parses() {
        let names: Vec<&str> = super::names().collect();
        assert_eq!(names.len(), 14);
        for name in names {
            let rows = super::rows(name).expect("listed");
            assert!(
                rows.len() == 83 || rows.len() == 107,
                "{name}: {}",
                rows.len()
            );
            assert!(rows.windows(2).all(|w| w[0].0 < w[1].0), "{name}");
        }
    }
}
