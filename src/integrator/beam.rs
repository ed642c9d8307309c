//! The beam radiance estimate (Jarosz, Zwicker and Jensen 2008) along a camera path's way
//! through scattering media, curved or straight: the volume caustic scattered toward the
//! camera all along each stretch, read from every photon ball of the volume caustic map the
//! stretch passes through (each photon's 3D kernel integrated along its chord,
//! [`crate::photon::VolumeMap::along_path`]), rather than at the one point a free flight drew.
//!
//! **The estimator.** A stretch in a medium ends where its free flight ends (or at a
//! surface); it reaches arclength t with probability P(t), the flight's survival. Light
//! in-scattered at t reaches the stretch's start attenuated by the scattering transmittance
//! T_s(t) and absorption T_a(t), and σs ∫ p L dω there is what the volume map estimates (Σ Φ p
//! K); so Σ Φ p(ωi → ωo) T_a(t) (T_s(t)/P(t)) ∫K ds over the photons whose balls the stretch
//! meets up to its end is an unbiased estimate of the light in-scattered along the whole
//! stretch (over where it ends, each t is counted with probability P(t)). T_s/P is 1 for a
//! grey σs and [`crate::volume::Flights::weigh`]'s factor for a coloured one; T_a, T_s/P and
//! the index are taken at the middle of each photon's chord (within a ball of radius r they
//! change by O(σ r)). A curved stretch is walked as the chords between its accepted points.
//!
//! **Radiance across indices.** Radiance in-scattered at a point of index n is seen at the
//! chain's start as (n_start/n)² of it, as at any other event ([`crate::volume`]).

use crate::color::Rgb;
use crate::ids::MediumId;
use crate::math::Segment;
use crate::photon::VolumeMap;
use crate::polarization::{Polarization, Recorded};
use crate::transport::chain::{ChainEvents, Stretch};
use crate::transport::Tracer;
use crate::volume::{Flights, Scattering};
use glam::DVec3;
use std::borrow::Cow;

/// A chain's stretches in scattering media, recorded as it is followed.
#[derive(Default)]
pub struct Beams {
    /// Where the chain starts (its first stretch's origin and medium).
    start: Option<Start>,
    /// n at the chain's start, looked up at its first stretch in a scattering medium (a chain
    /// through none costs no lookup).
    n_start: Option<f64>,
    stretches: Vec<RecordedStretch>,
    /// Where the transport is polarized, each recorded stretch's camera measurement at its
    /// start, per unit of its weight ([`Polarization::close`]); else empty.
    measures: Vec<Polarization>,
    /// Every recorded stretch's points after its origin, in order.
    points: Vec<DVec3>,
    /// The light media emitted along the chain as the camera records it, where the chain
    /// carries a measurement ([`ChainEvents::emitted`]; its S1–S3 are read).
    emitted: Recorded,
    /// Whether the stretch under way is recorded.
    recording: bool,
}

/// Where a recorded chain starts: all of its first stretch that the estimate reads (a whole
/// [`Stretch`] copied at every chain's start was a tenth of a path-traced sample's moves in a
/// scene without fog).
#[derive(Clone, Copy)]
struct Start {
    origin: DVec3,
    medium: Option<MediumId>,
}

/// A stretch in a scattering medium and where its points start in [`Beams::points`].
struct RecordedStretch {
    stretch: Stretch,
    medium: MediumId,
    first: usize,
}

/// A recorded stretch as the chain walked it.
pub struct Walked<'a> {
    /// The stretch.
    pub stretch: &'a Stretch,
    /// Its medium.
    pub medium: MediumId,
    /// Its points after its origin, in order, its end last: the accepted points of a curved
    /// stretch, the end alone of a straight one.
    pub points: &'a [DVec3],
    /// n at the chain's start.
    pub n_start: f64,
    /// Where the transport is polarized, the camera's measurement at its start, per unit of
    /// the chain's weight there.
    pub measure: Option<&'a Polarization>,
}

/// A recorded stretch through a medium of uniform index: one straight segment.
pub struct Straight<'a> {
    /// The segment, to where it ends (a surface, the world's edge or its free flight's end).
    pub segment: Segment,
    /// The medium.
    pub medium: MediumId,
    /// How the medium scatters.
    pub scattering: Cow<'a, Scattering>,
    /// The chain's weight at its start.
    pub weight: Rgb,
    /// The path's free flights with this stretch's drawn.
    pub flights: Flights,
    /// (n at the chain's start / n here)²: radiance in-scattered here, seen at the start.
    pub radiance_scale: f64,
    /// Where the transport is polarized, the camera's measurement at its start, per unit of
    /// `weight`.
    pub measure: Option<&'a Polarization>,
}

/// A straight piece of a recorded stretch where the index is defined.
struct Chord {
    segment: Segment,
    /// Absorption's optical depth per channel from the stretch's start to the segment's origin.
    depth: Rgb,
    /// The scattering column ∫d ds from the stretch's start to the segment's origin
    /// (`travelled` in a homogeneous medium).
    column: f64,
    /// The index along it.
    index: IndexAlong,
}

impl AsRef<Segment> for Chord {
    fn as_ref(&self) -> &Segment {
        &self.segment
    }
}

/// The index along a chord, looked up at its start, middle and end (once for a chord in a
/// medium of uniform index) and read between them on the parabola through the three: along
/// a chord of length L it errs by O(L³ n‴) — for the chords of curved stretches (a few
/// hundredths of a radian of their circles) far below the chord's own distance from the
/// path — where looking it up at every photon the chord meets cost a tenth of a GRIN scene's
/// render.
#[derive(Clone, Copy, Debug, PartialEq)]
struct IndexAlong {
    start: f64,
    middle: f64,
    end: f64,
}

impl IndexAlong {
    /// The same index all along.
    fn uniform(n: f64) -> Self {
        Self {
            start: n,
            middle: n,
            end: n,
        }
    }

    /// n at the fraction `f` ∈ [0, 1] of the chord's length from its start.
    fn at(&self, f: f64) -> f64 {
        let Self { start, middle, end } = *self;
        start + f * (4.0 * middle - 3.0 * start - end) + f * f * 2.0 * (start + end - 2.0 * middle)
    }
}

impl Beams {
    /// A recorder for chains on `tracer`'s scene; what it recorded before is forgotten. It
    /// keeps nothing of a chain through no scattering medium.
    pub fn record<'b>(&'b mut self, tracer: &'b Tracer<'b>) -> Recording<'b> {
        self.start = None;
        self.n_start = None;
        self.stretches.clear();
        self.measures.clear();
        self.points.clear();
        self.emitted = Recorded::default();
        self.recording = false;
        Recording {
            beams: self,
            tracer,
        }
    }

    /// The light media emitted along the recorded chain as the camera records it, `s0` its
    /// S0 (the chain's [`crate::transport::chain::Chain::emitted`]).
    pub fn emission(&self, s0: Rgb) -> Recorded {
        Recorded {
            s0,
            stokes: self.emitted.stokes,
        }
    }

    /// Whether the chain crossed a stretch that is recorded (through a medium that scatters or
    /// holds a dye).
    pub fn recorded_any(&self) -> bool {
        !self.stretches.is_empty()
    }

    /// The radiance `volume`'s photons scatter into the recorded chain along its stretches,
    /// as seen at its start per unit of the path's throughput there; `tracer` is the one the
    /// chain ended on (it reads indices and absorption).
    pub fn radiance(&self, volume: &VolumeMap, tracer: &Tracer) -> Recorded {
        let Some(n_start) = self.n_start.filter(|_| !volume.is_empty()) else {
            return Recorded::default();
        };
        let mut sum = Recorded::default();
        let mut read = Vec::new();
        for (r, points, measure) in self.recorded() {
            let radiometry = tracer.participating(r.medium);
            let Some(scattering) = tracer.scattering(r.medium) else {
                continue;
            };
            let mut light = Rgb::ZERO;
            // Where the camera measures through a phase function that polarizes, each photon's
            // light as the camera records it, through the scattering's matrix.
            let mut polarized = Recorded::default();
            let through = measure.filter(|_| scattering.phase.polarizes());
            read.clear();
            read.extend(chords(tracer, &scattering, r, points));
            volume.along_path(&read, |k, photon, stokes, along| {
                let c: &Chord = &read[k];
                let Segment {
                    origin,
                    dir,
                    length,
                } = c.segment;
                let n = c.index.at(along.distance / length);
                let depth = c.depth + radiometry.optical_depth(origin, dir, along.distance);
                let mut flights = r.stretch.flights;
                let column = c.column + scattering.column(origin, dir, along.distance);
                let kept = flights.weigh(&scattering, column, false);
                // Light arrives travelling along −from and leaves toward the camera, −dir.
                let before = -photon.from_direction();
                let phase = scattering.phase.between(before, -dir);
                let scale = (n_start / n) * (n_start / n);
                let amount = kept * photon.flux() * ((-depth).exp() * phase * scale * along.kernel);
                match through {
                    Some(rows) => {
                        let element = scattering.phase.mueller(before, -dir);
                        polarized +=
                            rows.recorded_through(element.as_ref(), dir, stokes, before) * amount
                    }
                    None => light += amount,
                }
            });
            sum += Recorded::of(measure, r.stretch.weight * light);
            if through.is_some() {
                sum += polarized * r.stretch.weight;
            }
        }
        sum * tracer.photon_irradiance(Rgb::ONE)
    }

    /// The recorded stretches through media of uniform index (straight, whole: from their
    /// origin to their last point), on `tracer`, the one the chain ended on.
    pub fn straight<'a>(&'a self, tracer: &'a Tracer) -> impl Iterator<Item = Straight<'a>> + 'a {
        let n_start = self.n_start.unwrap_or(1.0);
        self.recorded().filter_map(move |(r, points, measure)| {
            let scattering = tracer.scattering(r.medium)?;
            if !tracer.medium(r.medium).is_uniform() {
                return None;
            }
            let end = *points.last()?;
            let length = (end - r.stretch.origin).length();
            if length.is_nan() || length <= 0.0 {
                return None;
            }
            let n = tracer.index(Some(r.medium), r.stretch.origin)?;
            Some(Straight {
                segment: Segment {
                    origin: r.stretch.origin,
                    dir: (end - r.stretch.origin) / length,
                    length,
                },
                medium: r.medium,
                scattering,
                weight: r.stretch.weight,
                flights: r.stretch.flights,
                radiance_scale: (n_start / n) * (n_start / n),
                measure,
            })
        })
    }

    /// The recorded stretches, each with its medium and its points, and n at the chain's start.
    pub fn walked(&self) -> impl Iterator<Item = Walked<'_>> {
        let n_start = self.n_start.unwrap_or(1.0);
        self.recorded().map(move |(r, points, measure)| Walked {
            stretch: &r.stretch,
            medium: r.medium,
            points,
            n_start,
            measure,
        })
    }

    /// The recorded stretches with their points after their origins, and the camera's
    /// measurement at each where the transport is polarized.
    fn recorded(
        &self,
    ) -> impl Iterator<Item = (&RecordedStretch, &[DVec3], Option<&Polarization>)> {
        self.stretches.iter().enumerate().map(|(k, r)| {
            let end = self
                .stretches
                .get(k + 1)
                .map_or(self.points.len(), |s| s.first);
            (r, &self.points[r.first..end], self.measures.get(k))
        })
    }
}

/// The chords of stretch `r` (in a medium that scatters as `scattering`) from its origin
/// through `points`, with the absorption depth and scattering column before each; a chord
/// where the index is not defined (at its ends or middle) is left out: it reads no light.
fn chords<'a>(
    tracer: &'a Tracer,
    scattering: &'a Scattering,
    r: &'a RecordedStretch,
    points: &'a [DVec3],
) -> impl Iterator<Item = Chord> + 'a {
    let medium = tracer.medium(r.medium);
    let n = |p| tracer.index(Some(r.medium), p);
    // A uniform medium's index is looked up once; a graded one's at each point once.
    let uniform = medium.is_uniform().then(|| n(r.stretch.origin));
    let radiometry = tracer.participating(r.medium);
    let (mut from, mut depth, mut column) = (r.stretch.origin, Rgb::ZERO, 0.0);
    let mut n_from = uniform.unwrap_or_else(|| n(from));
    points.iter().filter_map(move |&to| {
        let length = (to - from).length();
        if length.is_nan() || length <= 0.0 {
            return None;
        }
        let dir = (to - from) / length;
        let index = match uniform {
            Some(u) => u.map(IndexAlong::uniform),
            None => {
                let (n_mid, n_to) = (n(0.5 * (from + to)), n(to));
                let along = n_from
                    .zip(n_mid)
                    .zip(n_to)
                    .map(|((start, middle), end)| IndexAlong { start, middle, end });
                n_from = n_to;
                along
            }
        };
        let chord = index.map(|index| Chord {
            segment: Segment {
                origin: from,
                dir,
                length,
            },
            depth,
            column,
            index,
        });
        depth += radiometry.optical_depth(from, dir, length);
        column += scattering.column(from, dir, length);
        from = to;
        chord
    })
}

/// A chain being recorded into [`Beams`].
pub struct Recording<'b> {
    beams: &'b mut Beams,
    tracer: &'b Tracer<'b>,
}

impl ChainEvents for Recording<'_> {
    fn stretch(&mut self, stretch: &Stretch, polarization: Option<&Polarization>) {
        let beams = &mut *self.beams;
        let start = *beams.start.get_or_insert(Start {
            origin: stretch.origin,
            medium: stretch.medium,
        });
        // A medium holding a dye is recorded whether or not its collisions' rate is 0 at the
        // recording tracer's wavelength: the dye may emit toward the chain all the same.
        let media = self.tracer.scene.media();
        let scatters = (stretch.medium).filter(|&m| {
            stretch.may_scatter
                && (self.tracer.scattering(m).is_some() || media.fluorescence(m).is_some())
        });
        beams.recording = scatters.is_some();
        if let Some(medium) = scatters {
            if beams.stretches.is_empty() {
                beams.n_start = self.tracer.index(start.medium, start.origin);
            }
            beams.stretches.push(RecordedStretch {
                stretch: *stretch,
                medium,
                first: beams.points.len(),
            });
            if let Some(p) = polarization {
                let mut measure = *p;
                measure.close();
                beams.measures.push(measure);
            }
        }
    }

    fn emitted(&mut self, light: Recorded) {
        self.beams.emitted += light;
    }

    fn point(&mut self, p: DVec3) {
        if self.beams.recording {
            self.beams.points.push(p);
        }
    }

    fn wants_points(&self) -> bool {
        self.beams.recording
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The parabola through a chord's three indices is exact for an index quadratic along
    /// the chord, and for the fish-eye's n = 2/(1 + (r/R)²), R = 0.5, along a chord of 0.015
    /// (a 0.03-rad piece of a circle of radius 0.5) errs by 8e-7 (bound 2e-6: the O(L³ n‴)
    /// term), a relative error of the radiance scale 1/n² of ~1e-6 — against the chord's own
    /// distance from its circle, 6e-5.
    #[test]
    fn the_index_along_a_chord_is_read_on_its_parabola() {
        let quadratic = |f: f64| 1.3 - 0.4 * f + 0.25 * f * f;
        let along = IndexAlong {
            start: quadratic(0.0),
            middle: quadratic(0.5),
            end: quadratic(1.0),
        };
        for k in 0..=20 {
            let f = k as f64 / 20.0;
            assert!((along.at(f) - quadratic(f)).abs() < 1e-15);
        }
        let (from, dir, length) = (
            DVec3::new(0.1, 0.3, -0.2),
            DVec3::new(0.6, -0.8, 0.0),
            0.015,
        );
        let fish_eye = |s: f64| 2.0 / (1.0 + (from + dir * s).length_squared() / 0.25);
        let along = IndexAlong {
            start: fish_eye(0.0),
            middle: fish_eye(0.5 * length),
            end: fish_eye(length),
        };
        let worst = (0..=100)
            .map(|k| k as f64 / 100.0)
            .map(|f| (along.at(f) - fish_eye(f * length)).abs())
            .fold(0.0, f64::max);
        assert!(worst < 2e-6, "{worst}");
        assert_eq!(IndexAlong::uniform(1.33).at(0.37), 1.33);
    }
}
