//! The light a scattering ambient medium scatters outside the scene ball, as a source of map
//! photons.
//!
//! In open fog the medium fills space out to the world sphere, and much of the light that
//! reaches the scene has scattered far outside it: under a uniform sky in conservative fog of
//! optical depth 1 to the world sphere, most of it. A photon traced from a light or from
//! beyond the world reaches the scene after such a scattering about (ball radius / 2 ×
//! distance)² of the time, and when it does it carries a weight that the few others do not: the
//! maps would be right on average and useless in any one render. So map photons are split by
//! where their path first scatters:
//! - paths whose first event is a surface or a scattering inside the scene ball, or that never
//!   scatter, are traced from the lights as ever (parallel and environment light from upstream
//!   of the scene, carrying what the medium lets through from the world sphere to there); a
//!   photon whose first event is a scattering outside the ball ends there;
//! - paths whose first event is a scattering outside the ball are this source's: a point of
//!   the shell between the ball and the world sphere, drawn with density ∝ 1/ρ² about the
//!   ball's centre (uniform in ρ, the distance from it), sends the light it scatters — σs times
//!   the direct light there ([`direct_light`]: every light, the environment and parallel
//!   light, through the medium) — half the time toward the ball's cone, half the time in any
//!   direction (so that light scattered away and back is not missed).
//!
//! Light scattered at distance ρ reaches the ball in proportion to its solid angle there,
//! ∝ 1/ρ², so a photon's power hardly depends on where it started. Where a map photon
//! scatters again outside the ball, a branch is split off toward it ([`super::split_toward`]).
//! Receiver photons, which book each photon's own power, are traced from the world sphere
//! instead ([`crate::lights::Entry::World`]).

use crate::color::Rgb;
use crate::ids::MediumId;
use crate::lights::{Cone, Emission};
use crate::math::Ball;
use crate::sampling::{uniform_sphere, UNIFORM_SPHERE_PDF};
use crate::spectrum::Spectrum;
use crate::transport::chain::Carried;
use crate::transport::lighting::{direct_light, Radiance};
use crate::transport::{MediumVertex, Stats, Tracer, Vertex};
use rand::Rng;
use std::f64::consts::PI;

/// Photons of the shell traced to weigh it against the lights.
const PILOT: u32 = 1024;

/// The scattering ambient medium between the scene ball and the world sphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shell {
    /// The ambient medium (index).
    pub medium: MediumId,
    /// The scene ball: the shell's inside.
    pub ball: Ball,
    /// The world sphere's radius: the shell's outside.
    pub world: f64,
}

/// A photon of the shell: where, which way, with what power; and its power at its hero
/// wavelength where the medium's scattering depends on wavelength.
pub struct ShellPhoton {
    /// Where, which way, and with what power (RGB).
    pub emission: Emission,
    /// In a medium whose σs depends on wavelength: the vacuum wavelength (nm) the photon
    /// was sent at, drawn from D65, and its power there (W, over the wavelength's density).
    pub hero: Option<(f64, f64)>,
}

impl Shell {
    /// The shell of the tracer's scene: where the ambient medium scatters and the world is a
    /// sphere larger than the scene ball.
    pub fn of(tracer: &Tracer) -> Option<Shell> {
        let medium = tracer.scene.ambient()?;
        tracer.scene.media().scattering(medium)?;
        let radius = tracer.ball.radius;
        match tracer.world {
            crate::curve::Bounds::Ball { radius: world, .. } if world > radius => Some(Shell {
                medium,
                ball: tracer.ball,
                world,
            }),
            crate::curve::Bounds::Ball { .. }
            | crate::curve::Bounds::Box { .. }
            | crate::curve::Bounds::HalfSpace { .. }
            | crate::curve::Bounds::Unbounded => None,
        }
    }

    /// A weight for choosing the shell among the lights: the power it sends toward the ball
    /// (W, the channels' mean), estimated from [`PILOT`] photons of a fixed stream — the
    /// lights are weighed by the power they send into the scene.
    pub fn selection_power(&self, tracer: &Tracer, dispersive: bool) -> f64 {
        let mut rng = crate::sampling::stream(0, crate::sampling::Purpose::Pilot, 0, 0);
        let mut stats = Stats::default();
        let mut sum = 0.0;
        for _ in 0..PILOT {
            let u = [rng.gen(), rng.gen(), rng.gen(), rng.gen()];
            if let Some(p) = self.emit(tracer, u, dispersive, &mut rng, &mut stats) {
                let e = p.emission;
                if Cone::toward(self.ball, e.origin).is_some_and(|c| c.density(e.direction) > 0.0) {
                    sum += e.power.mean();
                }
            }
        }
        sum / PILOT as f64
    }

    /// A photon for uniform numbers `u` and more from `rng` (the direct light's samples), or
    /// None where it carries nothing. `dispersive`: whether the medium's σs depends on
    /// wavelength (the photon is then one wavelength's, drawn from D65 by `rng`).
    pub fn emit(
        &self,
        tracer: &Tracer,
        u: [f64; 4],
        dispersive: bool,
        rng: &mut impl Rng,
        stats: &mut Stats,
    ) -> Option<ShellPhoton> {
        let Ball {
            center,
            radius: inner,
        } = self.ball;
        let rho = inner + (self.world - inner) * u[0];
        let position = center + uniform_sphere((u[1], u[2])) * rho;
        let point_density = 1.0 / (4.0 * PI * rho * rho * (self.world - inner));
        let cone = Cone::toward(self.ball, position)?;
        let uv = (rng.gen(), rng.gen());
        let direction = match u[3] < 0.5 {
            true => cone.sample(uv),
            false => uniform_sphere(uv),
        };
        let direction_density = 0.5 * cone.density(direction) + 0.5 * UNIFORM_SPHERE_PDF;
        let at = |tracer: &Tracer, rng: &mut _, stats: &mut _| -> Option<Rgb> {
            let sc = tracer.scattering(self.medium)?;
            let d = sc.density.as_ref().map_or(1.0, |d| d.at(position));
            let vertex = Vertex::Medium(MediumVertex {
                position,
                wo: direction,
                medium: Some(self.medium),
                phase: sc.phase,
            });
            let light = direct_light(Carried::on(tracer), &vertex, &Radiance, rng, stats);
            Some(sc.sigma_s * d * light / (point_density * direction_density))
        };
        let (power, hero) = match dispersive {
            false => (at(tracer, rng, stats)?, None),
            true => {
                let white = Spectrum::white();
                let nm = white.sample(rng.gen());
                let spectral = at(&tracer.at_wavelength(nm), rng, stats)?.mean();
                let power = spectral / white.pdf(nm);
                (Rgb::splat(power), Some((nm, power)))
            }
        };
        (power != Rgb::ZERO && power.0.is_finite()).then_some(ShellPhoton {
            emission: Emission {
                origin: position,
                direction,
                power,
            },
            hero,
        })
    }
}
