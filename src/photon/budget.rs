//! The energy budget of a photon batch: where each photon's power went when its path ended.
//! Every emitted photon is booked exactly once, so the entries add up to the power emitted;
//! what they measure is how it divides (out through which face, reflected, absorbed by
//! surfaces or in which medium, lost). The photons a medium scattered are also booked apart
//! (where scattered light went), so are the photons a dye emitted (where fluorescence went),
//! and photons that carry a wavelength in every receiver band holding it (the band of the
//! wavelength they left their light at).
//!
//! **Fluorophores.** A dye's or a fluorescent layer's absorption ends nothing by itself: what
//! it turns into heat — all of a photon it does not emit again, and the Stokes shift's energy
//! of one it does — is booked as absorbed in its medium (or by surfaces) where it happens, and
//! the photon it emits goes on to a fate of its own, so the fates still add up to the power
//! emitted. What each absorbed, what of that a fluorophore had emitted before (re-absorption)
//! and what it emitted are booked beside ([`Dye`]).

use crate::exact::ExactSum;
use crate::ids::{MediumId, PrimId};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// How a photon's path ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fate {
    /// It escaped the scene after last leaving a dielectric into the ambient medium through
    /// this primitive.
    OutThrough(PrimId),
    /// It escaped without ever leaving a dielectric (so without entering one), after a
    /// specular reflection.
    Reflected,
    /// It escaped without a specular interaction.
    Missed,
    /// It ended on a diffuse or emissive surface, or a lossy mirror's Russian roulette.
    Absorbed,
    /// It was absorbed in this medium (by index): on the way through it, or where it
    /// scattered in it.
    AbsorbedIn(MediumId),
    /// It was captured by a singular medium, ran out of steps, was cut at `max_depth`, or left
    /// the world from inside a dielectric (the world sphere cuts the object).
    Lost,
}

/// One photon as its batch books it when its path ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ended {
    /// Its power when it left the light (W, the mean over the RGB channels).
    pub emitted: f64,
    /// Its power when its path ended (W, the mean over the RGB channels).
    pub power: f64,
    /// How its path ended.
    pub fate: Fate,
    /// Its vacuum wavelength, nm (None: it carries all).
    pub nm: Option<f64>,
    /// Whether a medium scattered it on the way.
    pub scattered: bool,
    /// Whether a dye emitted it on the way: Some(power the dye first emitted it with, W;
    /// booked once, 0 in later bookings of the same photon), else None.
    pub fluoresced: Option<f64>,
}

/// Where a fluorophore sits: dissolved in a medium (a dye), or a layer on a primitive's
/// surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DyeSite {
    /// A dye in this medium.
    Medium(MediumId),
    /// A fluorescent layer on this primitive.
    Surface(PrimId),
}

/// What a fluorophore did to a photon at one absorption, as its site's [`Dye`] books it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DyeEvent {
    /// Where the fluorophore sits.
    pub site: DyeSite,
    /// The power it absorbed (W, the mean over the RGB channels).
    pub absorbed: f64,
    /// The power it emitted again (0: none).
    pub emitted: f64,
    /// Whether the photon was light a dye had emitted (re-absorption).
    pub again: bool,
    /// The photon's vacuum wavelength when it left its light, nm (the band it is booked in).
    pub nm: Option<f64>,
}

/// What a fluorophore absorbed and emitted, W: its heat is `absorbed − emitted`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Dye<T = f64> {
    /// Power it absorbed.
    pub absorbed: T,
    /// Of that, power a dye had emitted before (re-absorbed).
    pub reabsorbed: T,
    /// Power it emitted again.
    pub emitted: T,
}

impl<T> Dye<T> {
    fn map<U>(&self, f: &impl Fn(&T) -> U) -> Dye<U> {
        Dye {
            absorbed: f(&self.absorbed),
            reabsorbed: f(&self.reabsorbed),
            emitted: f(&self.emitted),
        }
    }
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
    /// See [`Fate::Absorbed`]: by surfaces.
    pub absorbed: T,
    /// See [`Fate::AbsorbedIn`]: by media, by medium index.
    pub absorbed_in: BTreeMap<usize, T>,
    /// See [`Fate::Lost`].
    pub lost: T,
    /// The same for the photons a medium scattered on the way (None: none did): where the
    /// light a scattering medium redirected went in the end.
    pub scattered: Option<Box<Budget<T>>>,
    /// The same for the light dyes emitted (None: none did), its `emitted` the power they
    /// emitted first (light a dye absorbs again is booked there as heat and what it emits
    /// again goes on): where fluorescence went in the end.
    #[serde(default)]
    pub fluoresced: Option<Box<Budget<T>>>,
    /// What each dye absorbed and emitted, by medium index.
    #[serde(default)]
    pub dyes: BTreeMap<usize, Dye<T>>,
    /// What each fluorescent layer absorbed and emitted, by primitive index.
    #[serde(default)]
    pub layers: BTreeMap<usize, Dye<T>>,
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
            absorbed_in: self.absorbed_in.iter().map(|(&m, w)| (m, f(w))).collect(),
            lost: f(&self.lost),
            scattered: self.scattered.as_ref().map(|b| Box::new(b.map(f))),
            fluoresced: self.fluoresced.as_ref().map(|b| Box::new(b.map(f))),
            dyes: self.dyes.iter().map(|(&m, d)| (m, d.map(f))).collect(),
            layers: self.layers.iter().map(|(&p, d)| (p, d.map(f))).collect(),
            bands: self.bands.iter().map(|(b, x)| (*b, x.map(f))).collect(),
        }
    }

    /// Each fate's sum (its own, not its parts').
    fn fate_sums(&self) -> impl Iterator<Item = &T> {
        [&self.reflected, &self.missed, &self.absorbed, &self.lost]
            .into_iter()
            .chain(self.out_through.values())
            .chain(self.absorbed_in.values())
    }

    /// Every sum of its own: emitted and each fate's.
    fn sums(&self) -> impl Iterator<Item = &T> {
        std::iter::once(&self.emitted).chain(self.fate_sums())
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

    /// Books a photon: its emission and its fate, here, in the part of the photons a medium
    /// scattered if one did, and in every band holding its wavelength.
    pub fn book(&mut self, photon: &Ended) {
        self.book_here(photon);
        self.in_bands(photon.nm, |band| band.book_here(photon));
    }

    /// Runs `book` on the band holding wavelength `nm` (none for a photon without one).
    fn in_bands(&mut self, nm: Option<f64>, mut book: impl FnMut(&mut Ledger)) {
        for (_, band) in self
            .bands
            .iter_mut()
            .filter(|((lo, hi), _)| nm.is_some_and(|nm| (*lo..*hi).contains(&nm)))
        {
            book(band);
        }
    }

    fn book_here(&mut self, photon: &Ended) {
        self.emitted.add(photon.emitted);
        let power = photon.power;
        match photon.fate {
            Fate::OutThrough(p) => self.out_through.entry(p.index()).or_default().add(power),
            Fate::Reflected => self.reflected.add(power),
            Fate::Missed => self.missed.add(power),
            Fate::Absorbed => self.absorbed.add(power),
            Fate::AbsorbedIn(m) => self.absorbed_in.entry(m.index()).or_default().add(power),
            Fate::Lost => self.lost.add(power),
        }
        let plain = Ended {
            scattered: false,
            fluoresced: None,
            ..*photon
        };
        if photon.scattered {
            let part = self.scattered.get_or_insert_with(Box::default);
            part.book_here(&plain);
        }
        if let Some(emitted) = photon.fluoresced {
            let part = self.fluoresced.get_or_insert_with(Box::default);
            part.book_here(&Ended { emitted, ..plain });
        }
    }

    /// Books what a dye did at one absorption, in the whole and in the band holding the
    /// photon's wavelength.
    pub fn book_dye(&mut self, event: &DyeEvent) {
        self.book_dye_here(event);
        self.in_bands(event.nm, |band| band.book_dye_here(event));
    }

    fn book_dye_here(&mut self, event: &DyeEvent) {
        let dye = match event.site {
            DyeSite::Medium(m) => self.dyes.entry(m.index()),
            DyeSite::Surface(p) => self.layers.entry(p.index()),
        }
        .or_default();
        dye.absorbed.add(event.absorbed);
        dye.emitted.add(event.emitted);
        if event.again {
            dye.reabsorbed.add(event.absorbed);
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
        if let Some(theirs) = &other.scattered {
            self.scattered.get_or_insert_with(Box::default).add(theirs);
        }
        if let Some(theirs) = &other.fluoresced {
            self.fluoresced.get_or_insert_with(Box::default).add(theirs);
        }
        for (mine, theirs) in [
            (&mut self.dyes, &other.dyes),
            (&mut self.layers, &other.layers),
        ] {
            for (&site, theirs) in theirs {
                let mine = mine.entry(site).or_default();
                mine.absorbed.merge(&theirs.absorbed);
                mine.reabsorbed.merge(&theirs.reabsorbed);
                mine.emitted.merge(&theirs.emitted);
            }
        }
        self.emitted.merge(&other.emitted);
        for (&p, w) in &other.out_through {
            self.out_through.entry(p).or_default().merge(w);
        }
        for (&m, w) in &other.absorbed_in {
            self.absorbed_in.entry(m).or_default().merge(w);
        }
        self.reflected.merge(&other.reflected);
        self.missed.merge(&other.missed);
        self.absorbed.merge(&other.absorbed);
        self.lost.merge(&other.lost);
    }

    /// Whether a ledger read from a file fits a scene of `primitives` primitives, `media`
    /// media and `bands` wavelength bands (every sum well formed, every primitive and medium
    /// booked one of the scene's): the reason when not.
    pub fn fits(&self, primitives: usize, media: usize, bands: usize) -> Result<(), String> {
        if !self.sums().all(ExactSum::is_well_formed) {
            return Err("a malformed sum in its energy budget".into());
        }
        // Each map's keys must name one of the scene's primitives or media.
        fn beyond<'k>(
            mut keys: impl Iterator<Item = &'k usize>,
            limit: usize,
            what: &str,
        ) -> Result<(), String> {
            match keys.find(|&&k| k >= limit) {
                Some(k) => Err(format!("an energy budget {what} {k} of a scene of {limit}")),
                None => Ok(()),
            }
        }
        beyond(self.out_through.keys(), primitives, "through primitive")?;
        beyond(self.absorbed_in.keys(), media, "absorbed in medium")?;
        beyond(self.dyes.keys(), media, "of a dye in medium")?;
        beyond(
            self.layers.keys(),
            primitives,
            "of a fluorescent layer on primitive",
        )?;
        if !self.bands.is_empty() && self.bands.len() != bands {
            return Err(format!(
                "an energy budget of {} wavelength bands where the scene has {bands}",
                self.bands.len()
            ));
        }
        let dye_sums = self
            .dyes
            .values()
            .chain(self.layers.values())
            .flat_map(|d| [&d.absorbed, &d.reabsorbed, &d.emitted]);
        if !dye_sums.into_iter().all(ExactSum::is_well_formed) {
            return Err("a malformed sum in its energy budget".into());
        }
        for part in [&self.scattered, &self.fluoresced].into_iter().flatten() {
            let nested = part.scattered.is_some() || part.fluoresced.is_some();
            let dyed = !part.dyes.is_empty() || !part.layers.is_empty();
            if nested || !part.bands.is_empty() || dyed {
                return Err(
                    "a malformed part (scattered or fluoresced) in its energy budget".into(),
                );
            }
            part.fits(primitives, media, 0)?;
        }
        self.bands
            .iter()
            .try_for_each(|(_, b)| b.fits(primitives, media, 0))
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
        self.fate_sums().sum()
    }

    /// Each fate with power, named: the faces of [`Fate::OutThrough`] by `primitives`, the
    /// media of [`Fate::AbsorbedIn`] by `media` (names in index order).
    fn fates(&self, primitives: &[crate::shapes::Primitive], media: &[&str]) -> Vec<(String, f64)> {
        let through = self
            .out_through
            .iter()
            .map(|(&p, &w)| (format!("left through {}", primitives[p]), w));
        let named = [
            ("reflected without entering a dielectric", self.reflected),
            ("missed every specular surface", self.missed),
            ("absorbed by surfaces", self.absorbed),
        ]
        .map(|(name, w)| (name.to_string(), w));
        let media = self
            .absorbed_in
            .iter()
            .map(|(&m, &w)| (format!("absorbed in medium '{}'", media[m]), w));
        let lost = (
            "lost (captured, out of steps or cut at max_depth)".to_string(),
            self.lost,
        );
        through.chain(named).chain(media).chain([lost]).collect()
    }

    /// Where the power went, one line per fate with its share; `primitives` name the faces
    /// of [`Fate::OutThrough`], `media` (names in index order) the media of
    /// [`Fate::AbsorbedIn`].
    pub fn table(&self, primitives: &[crate::shapes::Primitive], media: &[&str]) -> String {
        let share = |w: f64, of: f64| 100.0 * w / of.max(f64::MIN_POSITIVE);
        let mut lines = vec![format!(
            "energy budget: emitted {:.6e} W, booked {:.6e} W",
            self.emitted,
            self.booked()
        )];
        for (name, w) in self.fates(primitives, media) {
            lines.push(format!(
                "  {w:.6e} W ({:6.3} %) {name}",
                share(w, self.emitted)
            ));
        }
        // A part's shares are of its own emitted power.
        let part = |b: &Budget| {
            b.fates(primitives, media)
                .into_iter()
                .filter(|(_, w)| *w > 0.0)
                .map(|(name, w)| format!("{:.3} % {name}", share(w, b.emitted)))
                .collect::<Vec<_>>()
                .join(", ")
        };
        if let Some(b) = &self.scattered {
            lines.push(format!(
                "  scattered in a medium: {:.6e} W ({:.3} %): {}",
                b.emitted,
                share(b.emitted, self.emitted),
                part(b)
            ));
        }
        let dyes = self
            .dyes
            .iter()
            .map(|(&m, d)| (format!("dye in medium '{}'", media[m]), d));
        let layers = self
            .layers
            .iter()
            .map(|(&p, d)| (format!("fluorescent layer on {}", primitives[p]), d));
        for (site, d) in dyes.chain(layers) {
            lines.push(format!(
                "  {site}: absorbed {:.6e} W ({:.3} % of it emitted by a fluorophore before), \
                 emitted {:.6e} W, heat {:.6e} W",
                d.absorbed,
                share(d.reabsorbed, d.absorbed),
                d.emitted,
                d.absorbed - d.emitted
            ));
        }
        if let Some(b) = &self.fluoresced {
            lines.push(format!(
                "  emitted by dyes: {:.6e} W: {}",
                b.emitted,
                part(b)
            ));
        }
        for ((lo, hi), b) in &self.bands {
            lines.push(format!(
                "  band {lo}–{hi} nm: emitted {:.6e} W: {}",
                b.emitted,
                part(b)
            ));
        }
        lines.join("\n")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ended(fate: Fate, scattered: bool) -> Ended {
        Ended {
            emitted: 1.0,
            power: 0.5,
            fate,
            nm: Some(550.0),
            scattered,
            fluoresced: None,
        }
    }

    /// A photon is booked once in the whole, once more in the scattered part if a medium
    /// scattered it, and in each band holding its wavelength; ledgers booked apart add up to
    /// the ledger booked at once, exactly.
    #[test]
    fn photons_are_booked_in_their_parts_and_ledgers_add() {
        let photons = [
            ended(Fate::AbsorbedIn(MediumId::new(1)), true),
            ended(Fate::OutThrough(PrimId::new(3)), false),
            ended(Fate::Absorbed, true),
            ended(Fate::Lost, false),
        ];
        let mut whole = Ledger::with_bands(&[(500.0, 600.0), (600.0, 700.0)]);
        let (mut a, mut b) = (whole.clone(), whole.clone());
        for (i, p) in photons.iter().enumerate() {
            whole.book(p);
            if i % 2 == 0 { &mut a } else { &mut b }.book(p);
        }
        a.add(&b);
        assert_eq!(a, whole);
        let s = whole.statement(1.0);
        assert_eq!((s.emitted, s.booked()), (4.0, 2.0));
        assert_eq!(s.absorbed_in[&1], 0.5);
        let part = s.scattered.as_deref().unwrap();
        assert_eq!(
            (part.emitted, part.absorbed_in[&1], part.absorbed),
            (2.0, 0.5, 0.5)
        );
        assert_eq!(s.bands[0].1.emitted, 4.0);
        assert_eq!(s.bands[1].1.emitted, 0.0);
        assert!(whole.fits(4, 2, 2).is_ok());
    }

    /// A dye's absorption is booked with its medium, in the whole and the photon's band; a
    /// photon a dye emitted is booked in the fluoresced part with the power it was emitted with
    /// once, and the part's fates add up to it.
    #[test]
    fn a_dyes_events_and_light_are_booked_apart() {
        let mut ledger = Ledger::with_bands(&[(500.0, 600.0)]);
        let medium = MediumId::new(1);
        // A photon of 1 W absorbed by the dye, 0.6 W emitted again: 0.4 W of heat at once,
        // then the emitted light absorbed again (0.6 W, none emitted), all heat.
        ledger.book(&Ended {
            emitted: 1.0,
            power: 0.4,
            fate: Fate::AbsorbedIn(medium),
            nm: Some(550.0),
            scattered: false,
            fluoresced: None,
        });
        for (absorbed, emitted, again) in [(1.0, 0.6, false), (0.6, 0.0, true)] {
            ledger.book_dye(&DyeEvent {
                site: DyeSite::Medium(medium),
                absorbed,
                emitted,
                again,
                nm: Some(550.0),
            });
        }
        ledger.book(&Ended {
            emitted: 0.0,
            power: 0.6,
            fate: Fate::AbsorbedIn(medium),
            nm: Some(550.0),
            scattered: false,
            fluoresced: Some(0.6),
        });
        let s = ledger.statement(1.0);
        assert_eq!((s.emitted, s.booked()), (1.0, 1.0));
        let dye = &s.dyes[&1];
        assert_eq!((dye.absorbed, dye.reabsorbed, dye.emitted), (1.6, 0.6, 0.6));
        let part = s.fluoresced.as_deref().unwrap();
        assert_eq!((part.emitted, part.booked()), (0.6, 0.6));
        assert_eq!(s.bands[0].1.dyes[&1].absorbed, 1.6);
        assert!(ledger.fits(1, 2, 1).is_ok());
    }

    /// Books read from a file are refused when they name a medium or a face the scene does not
    /// have (a dye's medium too), or hold a scattered or fluoresced part that is not a plain
    /// budget.
    #[test]
    fn books_that_do_not_fit_the_scene_are_refused() {
        let mut ledger = Ledger::default();
        ledger.book(&ended(Fate::AbsorbedIn(MediumId::new(2)), true));
        assert!(ledger.fits(1, 3, 0).is_ok());
        let why = ledger.fits(1, 2, 0).unwrap_err();
        assert!(why.contains("medium 2 of a scene of 2"), "{why}");
        let mut nested = ledger.clone();
        nested.scattered.as_mut().unwrap().scattered = Some(Box::default());
        assert!(nested.fits(1, 3, 0).unwrap_err().contains("malformed part"));
        let mut dyed = ledger.clone();
        dyed.fluoresced = Some(Box::new(Ledger::with_bands(&[(500.0, 600.0)])));
        assert!(dyed.fits(1, 3, 0).unwrap_err().contains("malformed part"));
        let mut dyed = ledger.clone();
        dyed.book_dye(&DyeEvent {
            site: DyeSite::Medium(MediumId::new(3)),
            absorbed: 1.0,
            emitted: 0.5,
            again: false,
            nm: None,
        });
        assert!(dyed.fits(1, 3, 0).unwrap_err().contains("dye in medium 3"));
        ledger.book(&ended(Fate::OutThrough(PrimId::new(5)), false));
        assert!(ledger.fits(5, 3, 0).unwrap_err().contains("primitive 5"));
    }
}
