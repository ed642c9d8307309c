//! Typed reading of one TOML table with every key's position kept, so that a wrong type, a
//! bad value, a missing or an unknown key is reported at file:line:col naming the key.

use super::source::Source;
use crate::color::Rgb;
use crate::error::{Error, Result};
use crate::media::MonotoneCubic;
use crate::spectrum::emission::Shape;
use crate::spectrum::{Dispersion, Spectrum, LAMBDA_MAX, LAMBDA_MIN};
use glam::DVec3;
use std::collections::BTreeMap;
use std::ops::Range;
use toml::{Spanned, Value};

pub use crate::error::MAX_MAGNITUDE;

/// A TOML table as parsed, with the span of every key and value.
pub type SpannedTable = BTreeMap<Spanned<String>, Spanned<Value>>;

/// Reads the keys of one table, each at most once; [`TableReader::finish`] rejects the rest.
pub struct TableReader<'a> {
    source: &'a Source,
    span: Range<usize>,
    /// What the table is, for messages ("medium 'rod'").
    what: String,
    entries: Vec<(Spanned<String>, Spanned<Value>, bool)>,
    /// Every key asked for, present or not: the keys this table accepts.
    asked: Vec<String>,
}

/// The most terms a Cauchy law takes (published fits use two to four).
const MAX_CAUCHY_TERMS: usize = 16;

impl<'a> TableReader<'a> {
    /// A reader of `table`, which spans `span` in `source`.
    pub fn new(
        source: &'a Source,
        span: Range<usize>,
        what: impl Into<String>,
        table: SpannedTable,
    ) -> Self {
        Self {
            source,
            span,
            what: what.into(),
            entries: table.into_iter().map(|(k, v)| (k, v, false)).collect(),
            asked: Vec::new(),
        }
    }

    /// Renames the table in later messages.
    pub fn describe(&mut self, what: impl Into<String>) {
        self.what = what.into();
    }

    /// Notes `message` at `key` as a warning of the scene (the scene still loads).
    pub fn warn(&self, key: &str, message: impl std::fmt::Display) {
        let text = self.error(key, message).to_string();
        self.source.warnings.borrow_mut().push(text);
    }

    /// An error at `key`'s value (or at the table when the key is absent).
    pub fn error(&self, key: &str, message: impl std::fmt::Display) -> Error {
        let at = self
            .entries
            .iter()
            .find(|(k, _, _)| k.get_ref() == key)
            .map_or(self.span.start, |(k, _, _)| k.span().start);
        self.source
            .error_at(at, format!("{}: key `{key}`: {message}", self.what))
    }

    fn take(&mut self, key: &str) -> Option<Value> {
        if !self.asked.iter().any(|k| k == key) {
            self.asked.push(key.to_string());
        }
        let entry = self
            .entries
            .iter_mut()
            .find(|(k, _, _)| k.get_ref() == key)?;
        entry.2 = true;
        Some(entry.1.get_ref().clone())
    }

    fn required(&mut self, key: &str) -> Result<Value> {
        self.take(key).ok_or_else(|| self.error(key, "is missing"))
    }

    fn number(&self, key: &str, v: &Value) -> Result<f64> {
        let x = match v {
            Value::Float(f) => *f,
            Value::Integer(i) => *i as f64,
            other => {
                return Err(self.error(key, format!("expected a number, got {}", other.type_str())))
            }
        };
        if !x.is_finite() {
            Err(self.error(key, format!("must be finite, got {x:?}")))
        } else if x.abs() > MAX_MAGNITUDE {
            Err(self.error(
                key,
                format!(
                    "{} is out of range: scene numbers must be within ±{MAX_MAGNITUDE:e} \
                     (beyond, the renderer's products overflow)",
                    crate::error::number(x)
                ),
            ))
        } else {
            Ok(x)
        }
    }

    /// A required finite number.
    pub fn f64(&mut self, key: &str) -> Result<f64> {
        let v = self.required(key)?;
        self.number(key, &v)
    }

    /// An optional finite number.
    pub fn f64_or(&mut self, key: &str, default: f64) -> Result<f64> {
        Ok(self.f64_opt(key)?.unwrap_or(default))
    }

    /// An optional finite number (None: absent).
    pub fn f64_opt(&mut self, key: &str) -> Result<Option<f64>> {
        self.take(key).map(|v| self.number(key, &v)).transpose()
    }

    /// An optional angle in degrees, any number of turns within ±10⁶°, as radians (None:
    /// absent).
    pub fn turn_opt(&mut self, key: &str) -> Result<Option<f64>> {
        let Some(degrees) = self.f64_opt(key)? else {
            return Ok(None);
        };
        self.check(
            key,
            degrees.abs() <= 1e6,
            format!("must be a number of degrees within ±1e6, got {degrees:?}"),
        )?;
        Ok(Some(degrees.to_radians()))
    }

    /// A required number > 0.
    pub fn positive(&mut self, key: &str) -> Result<f64> {
        let x = self.f64(key)?;
        self.check(key, x > 0.0, format!("must be > 0, got {x:?}"))?;
        Ok(x)
    }

    /// An optional number > 0.
    pub fn positive_or(&mut self, key: &str, default: f64) -> Result<f64> {
        let x = self.f64_or(key, default)?;
        self.check(key, x > 0.0, format!("must be > 0, got {x:?}"))?;
        Ok(x)
    }

    /// Fails at `key` with `message` unless `ok`.
    pub fn check(&self, key: &str, ok: bool, message: impl std::fmt::Display) -> Result<()> {
        if ok {
            Ok(())
        } else {
            Err(self.error(key, message))
        }
    }

    /// A required string.
    pub fn string(&mut self, key: &str) -> Result<String> {
        match self.required(key)? {
            Value::String(s) => Ok(s),
            other => Err(self.error(key, format!("expected a string, got {}", other.type_str()))),
        }
    }

    /// One of the named `options` at `key` (its value where the key is absent: the first);
    /// another name is refused, listing them.
    pub fn choice<T: Copy>(&mut self, key: &str, options: &[(&str, T)]) -> Result<T> {
        let Some(given) = self.string_opt(key)? else {
            return Ok(options[0].1);
        };
        options
            .iter()
            .find(|(name, _)| *name == given)
            .map(|&(_, value)| value)
            .ok_or_else(|| {
                let names: Vec<&str> = options.iter().map(|(name, _)| *name).collect();
                self.error(
                    key,
                    format!("unknown value '{given}' ({})", names.join(", ")),
                )
            })
    }

    /// A required path, relative to the scene file's directory, of a file the scene reads
    /// (remembered as an input of the scene).
    pub fn input_file(&mut self, key: &str) -> Result<std::path::PathBuf> {
        let name = self.string(key)?;
        let path = self.source.input(&name);
        match crate::input::not_regular(&path) {
            Some(why) => Err(self.error(key, format!("{}: {why}", path.display()))),
            None => Ok(path),
        }
    }

    /// An optional path relative to the scene file's directory (of a file the run writes).
    pub fn output_file(&mut self, key: &str) -> Result<Option<std::path::PathBuf>> {
        Ok(self.string_opt(key)?.map(|p| self.source.dir().join(p)))
    }

    /// An optional string.
    pub fn string_opt(&mut self, key: &str) -> Result<Option<String>> {
        match self.take(key) {
            None => Ok(None),
            Some(Value::String(s)) => Ok(Some(s)),
            Some(other) => {
                Err(self.error(key, format!("expected a string, got {}", other.type_str())))
            }
        }
    }

    fn numbers(&self, key: &str, v: &Value) -> Result<Vec<f64>> {
        match v {
            Value::Array(a) => a.iter().map(|x| self.number(key, x)).collect(),
            other => Err(self.error(
                key,
                format!("expected an array of numbers, got {}", other.type_str()),
            )),
        }
    }

    fn vec3_of(&self, key: &str, v: &Value) -> Result<DVec3> {
        let n = self.numbers(key, v)?;
        match n.as_slice() {
            [x, y, z] => Ok(DVec3::new(*x, *y, *z)),
            _ => Err(self.error(
                key,
                format!("expected 3 numbers [x, y, z], got {}", n.len()),
            )),
        }
    }

    /// A required 3-vector.
    pub fn vec3(&mut self, key: &str) -> Result<DVec3> {
        let v = self.required(key)?;
        self.vec3_of(key, &v)
    }

    /// An optional 3-vector.
    pub fn vec3_or(&mut self, key: &str, default: DVec3) -> Result<DVec3> {
        match self.take(key) {
            Some(v) => self.vec3_of(key, &v),
            None => Ok(default),
        }
    }

    /// A required non-zero 3-vector, normalised.
    pub fn direction(&mut self, key: &str) -> Result<DVec3> {
        let v = self.vec3(key)?;
        v.try_normalize()
            .ok_or_else(|| self.error(key, "must be a non-zero vector"))
    }

    /// An optional non-zero 3-vector, normalised.
    pub fn direction_or(&mut self, key: &str, default: DVec3) -> Result<DVec3> {
        let v = self.vec3_or(key, default)?;
        v.try_normalize()
            .ok_or_else(|| self.error(key, "must be a non-zero vector"))
    }

    /// A required list of 3-vectors.
    pub fn vec3_list(&mut self, key: &str) -> Result<Vec<DVec3>> {
        match self.required(key)? {
            Value::Array(a) => a.iter().map(|v| self.vec3_of(key, v)).collect(),
            other => Err(self.error(
                key,
                format!("expected an array of [x, y, z], got {}", other.type_str()),
            )),
        }
    }

    /// An optional list of number pairs `[[a, b], ...]`.
    pub fn vec2_list_opt(&mut self, key: &str) -> Result<Option<Vec<(f64, f64)>>> {
        match self.take(key) {
            Some(v) => self.pairs(key, &v).map(Some),
            None => Ok(None),
        }
    }

    /// The value `[[a, b], ...]` of `key` as pairs of finite numbers.
    fn pairs(&self, key: &str, v: &Value) -> Result<Vec<(f64, f64)>> {
        let Value::Array(rows) = v else {
            return Err(self.error(key, format!("expected [[a, b], ...], got {}", v.type_str())));
        };
        rows.iter()
            .map(|r| match self.numbers(key, r)?[..] {
                [a, b] => Ok((a, b)),
                _ => Err(self.error(key, "expected pairs [a, b]")),
            })
            .collect()
    }

    /// The numbers of a value taken with [`TableReader::value_opt`]: one number, or an array
    /// of numbers, each finite and within range.
    pub fn numbers_in(&self, key: &str, v: &Value) -> Result<Vec<f64>> {
        match v {
            Value::Array(_) => self.numbers(key, v),
            _ => Ok(vec![self.number(key, v)?]),
        }
    }

    /// A key's raw value, for a reader of its own (None when absent).
    pub fn value_opt(&mut self, key: &str) -> Option<Value> {
        self.take(key)
    }

    /// A required list of numbers.
    pub fn f64_list(&mut self, key: &str) -> Result<Vec<f64>> {
        let v = self.required(key)?;
        self.numbers(key, &v)
    }

    /// An optional list of numbers.
    pub fn f64_list_opt(&mut self, key: &str) -> Result<Option<Vec<f64>>> {
        match self.take(key) {
            Some(v) => self.numbers(key, &v).map(Some),
            None => Ok(None),
        }
    }

    /// A required list of exactly `N` non-negative integers.
    pub fn counts<const N: usize>(&mut self, key: &str) -> Result<[usize; N]> {
        let v = self.required(key)?;
        let Value::Array(a) = &v else {
            return Err(self.error(key, format!("expected {N} integers, got {}", v.type_str())));
        };
        let ints: Vec<usize> = a
            .iter()
            .map(|x| match x {
                Value::Integer(i) if *i >= 0 => Ok(*i as usize),
                other => {
                    Err(self.error(key, format!("expected non-negative integers, got {other}")))
                }
            })
            .collect::<Result<_>>()?;
        ints.try_into().map_err(|v: Vec<usize>| {
            self.error(key, format!("expected {N} integers, got {}", v.len()))
        })
    }

    /// An optional positive integer (≥ 1).
    pub fn count_or(&mut self, key: &str, default: u64) -> Result<u64> {
        match self.take(key) {
            None => Ok(default),
            Some(Value::Integer(i)) if i >= 1 => Ok(i as u64),
            Some(other) => Err(self.error(key, format!("expected an integer ≥ 1, got {other}"))),
        }
    }

    /// The render setting `key` (see [`crate::settings::keys`]), read as every front end reads
    /// it (None: absent).
    pub fn setting(
        &mut self,
        key: &'static crate::settings::Key,
    ) -> Result<Option<crate::settings::Assignment>> {
        match self.take(key.name) {
            None => Ok(None),
            Some(v) => key
                .read(&crate::settings::Given::from_toml(&v))
                .map(Some)
                .map_err(|why| self.error(key.name, why)),
        }
    }

    /// An optional non-negative integer.
    pub fn natural_or(&mut self, key: &str, default: u64) -> Result<u64> {
        match self.take(key) {
            None => Ok(default),
            Some(Value::Integer(i)) if i >= 0 => Ok(i as u64),
            Some(other) => Err(self.error(key, format!("expected an integer ≥ 0, got {other}"))),
        }
    }

    /// An optional boolean.
    pub fn bool_or(&mut self, key: &str, default: bool) -> Result<bool> {
        match self.take(key) {
            None => Ok(default),
            Some(Value::Boolean(b)) => Ok(b),
            Some(other) => Err(self.error(
                key,
                format!("expected true or false, got {}", other.type_str()),
            )),
        }
    }

    /// Whether the table has `key` (without reading it).
    pub fn has(&self, key: &str) -> bool {
        self.entries.iter().any(|(k, _, _)| k.get_ref() == key)
    }

    /// Whether `key` holds a form over wavelength — a named material or a one-entry table
    /// (`{ table = ... }`, `{ sellmeier = ... }`, ...) — rather than a number or an RGB triple.
    pub fn is_over_wavelength(&self, key: &str) -> bool {
        self.entries.iter().any(|(k, v, _)| {
            k.get_ref() == key && matches!(v.get_ref(), Value::String(_) | Value::Table(_))
        })
    }

    /// An RGB triple of non-negative numbers; a single number means grey.
    pub fn rgb_or(&mut self, key: &str, default: Option<Rgb>) -> Result<Rgb> {
        let v = match (self.take(key), default) {
            (Some(v), _) => v,
            (None, Some(d)) => return Ok(d),
            (None, None) => return Err(self.error(key, "is missing")),
        };
        let c = match &v {
            Value::Float(_) | Value::Integer(_) => DVec3::splat(self.number(key, &v)?),
            _ => self.vec3_of(key, &v)?,
        };
        self.check(
            key,
            c.min_element() >= 0.0,
            format!("must not be negative, got {}", Rgb(c)),
        )?;
        Ok(Rgb(c))
    }

    /// An optional quantity over wavelength: a number (the same at every
    /// wavelength), a named material (`"BK7"`, see [`Dispersion::names`]), or a table of one
    /// model: `{ sellmeier = [B1, B2, B3, C1, C2, C3] }` (λ in µm), `{ cauchy = [A, B, ...] }`
    /// (λ in µm), `{ abbe = [n_d, V_d] }`, `{ table = [[nm, value], ...] }` or
    /// `{ angstrom = [value, nm, exponent] }` (value at nm, times (nm/λ)^exponent).
    pub fn over_wavelength_opt(&mut self, key: &str) -> Result<Option<Dispersion>> {
        let Some(v) = self.take(key) else {
            return Ok(None);
        };
        Ok(Some(match &v {
            Value::Float(_) | Value::Integer(_) => Dispersion::Constant(self.number(key, &v)?),
            Value::String(name) => Dispersion::named(name).ok_or_else(|| {
                let known: Vec<_> = Dispersion::names().collect();
                self.error(key, format!("unknown material '{name}' (known: {})", known.join(", ")))
            })?,
            Value::Table(t) if t.len() == 1 => {
                let (model, value) = t.iter().next().expect("one entry");
                self.dispersion_model(key, model, value)?
            }
            other => {
                return Err(self.error(
                    key,
                    format!("expected a number, a material name or a table {{ sellmeier | cauchy | abbe | table | angstrom = [...] }}, got {}", other.type_str()),
                ))
            }
        }))
    }

    /// An optional spectrum, the shape of an emission over wavelength: `"D65"`, `"E"` (equal
    /// energy), `{ blackbody = kelvin }`, `{ gaussian = [peak_nm, fwhm_nm] }` (an LED, a
    /// dye's line) or `{ table = [[nm, power], ...] }` (a measured spectrum: linear between
    /// its rows, 0 beyond them); refused where it has no power from 360 to 830 nm.
    pub fn spectrum_opt(&mut self, key: &str) -> Result<Option<Spectrum>> {
        let Some(value) = self.take(key) else {
            return Ok(None);
        };
        let bad = |why: &str| {
            self.error(
                key,
                format!("{why} (expected \"D65\", \"E\", {{ blackbody = kelvin }}, {{ gaussian = [peak_nm, fwhm_nm] }} or {{ table = [[nm, power], ...] }})"),
            )
        };
        let shape = match &value {
            Value::String(s) if s == "D65" => Shape::D65,
            Value::String(s) if s == "E" => Shape::Equal,
            Value::Table(table) if table.len() == 1 && table.contains_key("table") => {
                let nodes = self.pairs(key, &table["table"])?;
                let rising = nodes.windows(2).all(|w| w[0].0 < w[1].0);
                let valid =
                    nodes.len() >= 2 && rising && nodes.iter().all(|&(nm, p)| nm > 0.0 && p >= 0.0);
                if !valid {
                    return Err(bad(
                        "a table needs two or more [nm, power] rows, the wavelengths rising and > 0, the powers ≥ 0",
                    ));
                }
                Shape::Table(nodes.into())
            }
            Value::Table(table) if table.len() == 1 => {
                let (model, v) = table.iter().next().expect("one entry");
                let numbers = self.numbers_in(key, v)?;
                match (model.as_str(), &numbers[..]) {
                    ("blackbody", &[k]) if k > 0.0 && k.is_finite() => {
                        Shape::Blackbody { kelvin: k }
                    }
                    ("gaussian", &[peak, fwhm])
                        if fwhm > 0.0 && peak.is_finite() && fwhm.is_finite() =>
                    {
                        Shape::Gaussian { peak, fwhm }
                    }
                    _ => return Err(bad(&format!("bad `{model}` spectrum"))),
                }
            }
            Value::String(s) => return Err(bad(&format!("unknown spectrum '{s}'"))),
            _ => return Err(bad("not a spectrum")),
        };
        Spectrum::new(shape)
            .map(Some)
            .map_err(|e| self.error(key, e))
    }

    /// The table at `key` (`key = { ... }`) as a reader of its own, called `what key` in
    /// messages, which point at `key` for each of its keys; None where `key` is absent.
    pub fn nested(&mut self, key: &str) -> Result<Option<TableReader<'a>>> {
        let Some(at) = self.entries.iter().position(|(k, _, _)| k.get_ref() == key) else {
            self.take(key);
            return Ok(None);
        };
        let (name, value) = (self.entries[at].0.span(), self.entries[at].1.span());
        let Some(Value::Table(table)) = self.take(key) else {
            return Err(self.error(key, "expected a table { ... }"));
        };
        Ok(Some(TableReader {
            source: self.source,
            span: value.clone(),
            what: format!("{} `{key}`", self.what),
            entries: table
                .into_iter()
                .map(|(k, v)| {
                    (
                        Spanned::new(name.clone(), k),
                        Spanned::new(value.clone(), v),
                        false,
                    )
                })
                .collect(),
            asked: Vec::new(),
        }))
    }

    /// A required quantity over wavelength (see [`TableReader::over_wavelength_opt`]).
    pub fn over_wavelength(&mut self, key: &str) -> Result<Dispersion> {
        self.over_wavelength_opt(key)?
            .ok_or_else(|| self.error(key, "is missing"))
    }

    /// A required quantity over wavelength that is positive over the whole visible range (an
    /// index, a gradient constant g).
    pub fn dispersion(&mut self, key: &str) -> Result<Dispersion> {
        let d = self.over_wavelength(key)?;
        let least = d.min_visible();
        self.check(
            key,
            least > 0.0,
            format!("must be > 0 from 360 to 830 nm, got {least:?} there"),
        )?;
        Ok(d)
    }

    fn dispersion_model(&self, key: &str, model: &str, value: &Value) -> Result<Dispersion> {
        let coefficients = || self.numbers(key, value);
        Ok(match model {
            "sellmeier" => {
                let c = coefficients()?;
                self.check(
                    key,
                    !c.is_empty() && c.len() % 2 == 0,
                    "sellmeier takes [B1, ..., Bk, C1, ..., Ck] (C in µm²)",
                )?;
                let (b, c) = c.split_at(c.len() / 2);
                // A resonance Cᵢ = λ² inside 360–830 nm is a pole of n there, which sampling
                // the range every nm may step over.
                let visible = (LAMBDA_MIN * 1e-3).powi(2)..=(LAMBDA_MAX * 1e-3).powi(2);
                self.check(
                    key,
                    !c.iter().any(|ci| visible.contains(ci)),
                    "a sellmeier C (µm²) puts a pole of n between 360 and 830 nm",
                )?;
                Dispersion::Sellmeier(b.iter().copied().zip(c.iter().copied()).collect())
            }
            "cauchy" => {
                let c = coefficients()?;
                self.check(
                    key,
                    (1..=MAX_CAUCHY_TERMS).contains(&c.len()),
                    format!("cauchy takes [A, B, ...] (λ in µm), 1 to {MAX_CAUCHY_TERMS} terms"),
                )?;
                Dispersion::Cauchy(c)
            }
            "abbe" => match coefficients()?[..] {
                [n_d, v_d] if n_d > 1.0 && v_d > 0.0 => Dispersion::abbe(n_d, v_d),
                _ => return Err(self.error(key, "abbe takes [n_d > 1, V_d > 0]")),
            },
            "table" => {
                let rows = self.pairs(key, value)?;
                let (nm, n) = rows.into_iter().unzip();
                let curve = MonotoneCubic::new(nm, n, false, ("nm", "n"))
                    .map_err(|(_, e)| self.error(key, format!("table: {e}")))?;
                Dispersion::Table(curve)
            }
            "angstrom" => match coefficients()?[..] {
                [value, nm, exponent] if value >= 0.0 && nm > 0.0 && exponent.is_finite() => {
                    Dispersion::PowerLaw {
                        value,
                        nm,
                        exponent,
                    }
                }
                _ => {
                    return Err(self.error(
                        key,
                        "angstrom takes [value ≥ 0 at nm, nm > 0, exponent] (value · (nm/λ)^exponent)",
                    ))
                }
            },
            other => {
                return Err(self.error(
                    key,
                    format!("unknown dispersion model '{other}' (expected sellmeier, cauchy, abbe, table or angstrom)"),
                ))
            }
        })
    }

    /// Fails at the first key that was never read, naming the keys this table accepts.
    pub fn finish(self) -> Result<()> {
        match self.entries.iter().find(|(_, _, used)| !used) {
            None => Ok(()),
            Some((k, _, _)) => Err(self.source.error_at(
                k.span().start,
                format!(
                    "{}: unknown key `{}` (expected one of: {})",
                    self.what,
                    k.get_ref(),
                    self.asked.join(", ")
                ),
            )),
        }
    }
}
