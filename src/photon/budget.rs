//! The energy budget of a photon batch: where each photon's power went when its path ended.
//! Every emitted photon is booked exactly once, so the entries add up to the power emitted;
//! what they measure is how it divides (out through which face, reflected, absorbed, lost).
//! Photons that carry a wavelength are also booked in every receiver band holding it.

use crate::exact::ExactSum;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// How a photon's path ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fate {
    /// It escaped the scene after last leaving a dielectric into the ambient medium through
    /// this primitive.
    OutThrough(usize),
    /// It escaped without ever leaving a dielectric (so without entering one), after a
    /// specular reflection.
    Reflected,
    /// It escaped without a specular interaction.
    Missed,
    /// It ended on a diffuse or emissive surface, or a lossy mirror's Russian roulette.
    Absorbed,
    /// It was captured by a singular medium, ran out of steps, was cut at `max_depth`, or left
    /// the world from inside a dielectric (the world sphere cuts the object).
    Lost,
}

/// Power per fate, in the lights' power unit (W), as the mean over the RGB channels; each
/// entry a `T`: an [`ExactSum`] while photons are booked (a [`Ledger`], so that ledgers of
/// photons traced apart add exactly), an f64 once read ([`Ledger::statement`]).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Budget<T = f64> {
    /// Power of the photons emitted.
    pub emitted: T,
    /// Escaped after last leaving a dielectric through a primitive, by primitive index.
    pub out_through: BTreeMap<usize, T>,
    /// See [`Fate::Reflected`].
    pub reflected: T,
    /// See [`Fate::Missed`].
    pub missed: T,
    /// See [`Fate::Absorbed`].
    pub absorbed: T,
    /// See [`Fate::Lost`].
    pub lost: T,
    /// The same for the photons in each wavelength band [lo, hi) nm (in
    /// [`Ledger::with_bands`] order; empty: no bands).
    pub bands: Vec<((f64, f64), Budget<T>)>,
}

/// The books a batch keeps as its photons end: exact sums.
pub type Ledger = Budget<ExactSum>;

impl<T> Budget<T> {
    /// Every entry mapped by `f`.
    fn map<U>(&self, f: &impl Fn(&T) -> U) -> Budget<U> {
        Budget {
            emitted: f(&self.emitted),
            out_through: self.out_through.iter().map(|(&p, w)| (p, f(w))).collect(),
            reflected: f(&self.reflected),
            missed: f(&self.missed),
            absorbed: f(&self.absorbed),
            lost: f(&self.lost),
            bands: self.bands.iter().map(|(b, x)| (*b, x.map(f))).collect(),
        }
    }
}

impl Ledger {
    /// An empty ledger that also books photons by wavelength `bands` [lo, hi) nm.
    pub fn with_bands(bands: &[(f64, f64)]) -> Ledger {
        Budget {
            bands: bands.iter().map(|&b| (b, Budget::default())).collect(),
            ..Budget::default()
        }
    }

    /// The ledgers of the bands holding wavelength `nm` (none without one).
    fn bands_at(&mut self, nm: Option<f64>) -> impl Iterator<Item = &mut Ledger> {
        self.bands
            .iter_mut()
            .filter(move |((lo, hi), _)| nm.is_some_and(|nm| (*lo..*hi).contains(&nm)))
            .map(|(_, b)| b)
    }

    /// Books the emission of a photon of `power` at wavelength `nm` (None: it carries all).
    pub fn emit(&mut self, power: f64, nm: Option<f64>) {
        self.emitted.add(power);
        self.bands_at(nm).for_each(|b| b.emitted.add(power));
    }

    /// Books a photon of `power` at wavelength `nm` that ended as `fate`.
    pub fn book(&mut self, fate: Fate, power: f64, nm: Option<f64>) {
        self.book_here(fate, power);
        self.bands_at(nm).for_each(|b| b.book_here(fate, power));
    }

    fn book_here(&mut self, fate: Fate, power: f64) {
        match fate {
            Fate::OutThrough(p) => self.out_through.entry(p).or_default().add(power),
            Fate::Reflected => self.reflected.add(power),
            Fate::Missed => self.missed.add(power),
            Fate::Absorbed => self.absorbed.add(power),
            Fate::Lost => self.lost.add(power),
        }
    }

    /// Adds another ledger's entries to this one, exactly (band by band: both have the same
    /// bands, or this one none yet).
    pub fn add(&mut self, other: &Ledger) {
        if self.bands.is_empty() {
            self.bands = other
                .bands
                .iter()
                .map(|(b, _)| (*b, Budget::default()))
                .collect();
        }
        for ((_, mine), (_, theirs)) in self.bands.iter_mut().zip(&other.bands) {
            mine.add(theirs);
        }
        self.emitted.merge(&other.emitted);
        for (&p, w) in &other.out_through {
            self.out_through.entry(p).or_default().merge(w);
        }
        self.reflected.merge(&other.reflected);
        self.missed.merge(&other.missed);
        self.absorbed.merge(&other.absorbed);
        self.lost.merge(&other.lost);
    }

    /// Whether a ledger read from a file fits a scene of `primitives` primitives and `bands`
    /// wavelength bands (every sum well formed, every primitive booked one of the scene's):
    /// the reason when not.
    pub fn fits(&self, primitives: usize, bands: usize) -> Result<(), String> {
        let sums = [
            &self.emitted,
            &self.reflected,
            &self.missed,
            &self.absorbed,
            &self.lost,
        ];
        if !sums
            .into_iter()
            .chain(self.out_through.values())
            .all(ExactSum::is_well_formed)
        {
            return Err("a malformed sum in its energy budget".into());
        }
        if let Some(p) = self.out_through.keys().find(|&&p| p >= primitives) {
            return Err(format!(
                "an energy budget through primitive {p} of a scene of {primitives}"
            ));
        }
        if !self.bands.is_empty() && self.bands.len() != bands {
            return Err(format!(
                "an energy budget of {} wavelength bands where the scene has {bands}",
                self.bands.len()
            ));
        }
        self.bands
            .iter()
            .try_for_each(|(_, b)| b.fits(primitives, 0))
    }

    /// The budget these books hold, every entry times `factor` (1, or a batch's share traced
    /// to its full power).
    pub fn statement(&self, factor: f64) -> Budget {
        self.map(&|w: &ExactSum| w.value() * factor)
    }
}

impl Budget {
    /// The sum of all fates (equal to `emitted` up to rounding).
    pub fn booked(&self) -> f64 {
        self.out_through.values().sum::<f64>()
            + self.reflected
            + self.missed
            + self.absorbed
            + self.lost
    }

    /// Where the power went, one line per fate with its share; `primitives` name the faces
    /// of [`Fate::OutThrough`].
    pub fn table(&self, primitives: &[crate::shapes::Primitive]) -> String {
        let share = |w: f64| 100.0 * w / self.emitted.max(f64::MIN_POSITIVE);
        let mut lines = vec![format!(
            "energy budget: emitted {:.6e} W, booked {:.6e} W",
            self.emitted,
            self.booked()
        )];
        for (&p, &w) in &self.out_through {
            lines.push(format!(
                "  {w:.6e} W ({:6.3} %) left through {}",
                share(w),
                primitives[p]
            ));
        }
        for (name, w) in [
            ("reflected without entering a dielectric", self.reflected),
            ("missed every specular surface", self.missed),
            ("absorbed", self.absorbed),
            (
                "lost (captured, out of steps or cut at max_depth)",
                self.lost,
            ),
        ] {
            lines.push(format!("  {w:.6e} W ({:6.3} %) {name}", share(w)));
        }
        for ((lo, hi), b) in &self.bands {
            let share = |w: f64| 100.0 * w / b.emitted.max(f64::MIN_POSITIVE);
            let mut fates: Vec<String> = b
                .out_through
                .iter()
                .map(|(&p, &w)| format!("{:.3} % out through {}", share(w), primitives[p]))
                .collect();
            for (name, w) in [
                ("reflected", b.reflected),
                ("missed", b.missed),
                ("absorbed", b.absorbed),
                ("lost", b.lost),
            ] {
                fates.push(format!("{:.3} % {name}", share(w)));
            }
            lines.push(format!(
                "  band {lo}–{hi} nm: emitted {:.6e} W: {}",
                b.emitted,
                fates.join(", ")
            ));
        }
        lines.join("\n")
    }
}
