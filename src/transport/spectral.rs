//! The tracer at a wavelength: the scene's dispersive media (and scattering over wavelength)
//! at a path's hero wavelength, and how the colours a scene gives (reflectances, emitted
//! radiance, photon irradiance) read there. A tracer from [`Tracer::new`] sees every medium
//! at [`LAMBDA_D`] and every colour as RGB.

use super::Tracer;
use crate::color::Rgb;
use crate::ids::MediumId;
use crate::media::{Medium, Parametric};
use crate::scene::Surface;
use crate::spectrum::{colour, Hero, LAMBDA_D};
use crate::volume::{Fluorescence, Participating, Scattering};
use glam::DVec3;
use std::borrow::Cow;

/// A medium as a tracer's rays see it: the scene's own, or a dispersive one evaluated at
/// their wavelength (made where it is asked for, on the stack).
pub enum MediumAt<'a> {
    /// The scene's medium, the same at the rays' wavelength as at every other.
    Scene(&'a (dyn Medium + 'static)),
    /// The scene's medium given by a formula, the same at the rays' wavelength as at every
    /// other.
    SceneParametric(&'a Parametric),
    /// A dispersive medium at the rays' wavelength.
    Dispersed(Parametric),
}

impl MediumAt<'_> {
    /// The medium as its own type, where it is given by a formula ([`Parametric::apply`]).
    pub fn parametric(&self) -> Option<&Parametric> {
        match self {
            Self::Scene(_) => None,
            Self::SceneParametric(p) => Some(p),
            Self::Dispersed(p) => Some(p),
        }
    }
}

impl std::ops::Deref for MediumAt<'_> {
    type Target = dyn Medium;

    fn deref(&self) -> &Self::Target {
        match self {
            Self::Scene(m) => *m,
            Self::SceneParametric(p) => p.as_medium(),
            Self::Dispersed(p) => p.as_medium(),
        }
    }
}

/// A hero wavelength ready for the paths of one camera sample or one photon to take on where
/// they meet dispersion ([`Hero`]; [`chain::Walker`] does it): the tracer at that wavelength,
/// built the first time a path needs it (most paths of a scene never meet its dispersive
/// part), and the sRGB weight r̄(λ)/p(λ) a camera path's throughput takes on there.
pub struct HeroTracer<'a> {
    /// The tracer the paths start on.
    base: &'a Tracer<'a>,
    /// The hero wavelength, nm.
    nm: f64,
    /// The tracer at `nm`, once built.
    at: std::cell::OnceCell<Tracer<'a>>,
    /// [`Hero::sensor_weight`] (one for a photon, whose power changes at dispersion as its
    /// source's spectrum says).
    pub weight: Rgb,
}

impl<'a> HeroTracer<'a> {
    /// `tracer`'s hero `hero`, for camera paths.
    pub fn new(tracer: &'a Tracer<'a>, hero: Hero) -> Self {
        Self {
            base: tracer,
            nm: hero.nm,
            at: std::cell::OnceCell::new(),
            weight: hero.sensor_weight(),
        }
    }

    /// `tracer`'s hero at vacuum wavelength `nm`, for a photon.
    pub fn for_photon(tracer: &'a Tracer<'a>, nm: f64) -> Self {
        Self {
            base: tracer,
            nm,
            at: std::cell::OnceCell::new(),
            weight: Rgb::ONE,
        }
    }

    /// The tracer with rays at the hero wavelength.
    pub fn tracer(&self) -> &Tracer<'a> {
        self.at.get_or_init(|| self.base.at_wavelength(self.nm))
    }
}

impl<'a> Tracer<'a> {
    /// The same tracer with rays at vacuum wavelength `nm`: each dispersive medium is the
    /// one at that wavelength, and so is each scattering coefficient over wavelength. Rays of
    /// a tracer from [`Tracer::new`] see every medium at [`LAMBDA_D`].
    pub fn at_wavelength<'b>(&'b self, nm: f64) -> Tracer<'b> {
        Tracer {
            scene: self.scene,
            settings: self.settings,
            ball: self.ball,
            world: self.world,
            camera_medium: self.camera_medium,
            light_sampler: Cow::Borrowed(&self.light_sampler),
            light_samples: self.light_samples,
            wavelength: Some(nm),
            may_match_indices: self.may_match_indices,
            has_crystals: self.has_crystals,
            emission_on_lines: self.emission_on_lines,
        }
    }

    /// The one vacuum wavelength rays travel at, nm, when the tracer was made at one
    /// ([`Tracer::at_wavelength`]; None: RGB rays, every medium at [`LAMBDA_D`]).
    pub fn single_wavelength(&self) -> Option<f64> {
        self.wavelength
    }

    /// The vacuum wavelength rays travel at, nm.
    pub fn wavelength(&self) -> f64 {
        self.wavelength.unwrap_or(LAMBDA_D)
    }

    /// Whether a ray in `medium` travels a path that depends on its wavelength.
    pub fn disperses_in(&self, medium: Option<MediumId>) -> bool {
        medium.is_some_and(|i| self.scene.media().is_dispersive(i))
    }

    /// Whether a dielectric `surface` bends rays by their wavelength (a dispersive medium on
    /// either side).
    pub fn disperses_at(&self, surface: Surface) -> bool {
        self.disperses_in(surface.interior) || self.disperses_in(surface.exterior)
    }

    /// A reflectance (an albedo, a mirror's reflectance) as this tracer's rays see it: the
    /// RGB itself, or — rays at one wavelength — its reflectance spectrum there
    /// ([`colour::reflectance`]), the same in every channel.
    pub fn reflectance(&self, rgb: Rgb) -> Rgb {
        crate::material::reflectance(rgb, self.single_wavelength())
    }

    /// A radiance, irradiance or intensity of emitted light likewise: the RGB itself, or its
    /// spectral value (per nm) at the tracer's wavelength ([`colour::illuminant`]).
    pub fn radiance(&self, rgb: Rgb) -> Rgb {
        match self.wavelength {
            None => rgb,
            Some(nm) => Rgb::splat(colour::illuminant(rgb, nm)),
        }
    }

    /// The radiance, irradiance or intensity `rgb` of light `light`'s emission as this
    /// tracer's rays see it: [`Tracer::radiance`] for a light without a spectrum; for one with
    /// a spectrum S, the RGB itself, or at one wavelength S's density there times its power
    /// (the light's RGB is its power times S's colour, [`crate::scene::read::light`]), so
    /// that a line's light is found at the line's wavelengths alone.
    pub fn emitted_by(&self, light: usize, rgb: Rgb) -> Rgb {
        let (Some(nm), Some(spectrum)) = (self.wavelength, self.scene.light_spectrum(light)) else {
            return self.radiance(rgb);
        };
        let colour = spectrum.colour().0.max(glam::DVec3::ZERO);
        let k = colour.max_position();
        Rgb::splat(rgb.0[k] / colour[k] * spectrum.pdf(nm))
    }

    /// An irradiance estimated from stored photons (an RGB sum of a few photons' colours,
    /// whose channels may be negative: [`colour::sensor`]) as this tracer's rays see it: the
    /// RGB itself, or — rays at one wavelength — each channel times D65 there, joined to the
    /// path's sRGB weight channel by channel (as pbrt-v4's SPPM joins camera and photon). The
    /// reading is linear, so the estimate's noise averages out (an upsampled spectrum of a
    /// noisy colour would be biased: its negative channels clip), and its expectation over
    /// wavelengths is the RGB itself wherever the rest of the path is grey.
    pub fn photon_irradiance(&self, rgb: Rgb) -> Rgb {
        match self.wavelength {
            None => rgb,
            Some(nm) => rgb * colour::d65(nm),
        }
    }

    /// Medium `i` at the tracer's wavelength.
    pub fn medium(&self, i: MediumId) -> MediumAt<'a> {
        let media = self.scene.media();
        match self.wavelength.and_then(|nm| media.at_wavelength(i, nm)) {
            Some(p) => MediumAt::Dispersed(p),
            None => match media.parametric(i) {
                Some(p) => MediumAt::SceneParametric(p),
                None => MediumAt::Scene(media.at(i)),
            },
        }
    }

    /// How medium `i` scatters at the tracer's wavelength (None: it does not), a dye it holds
    /// counted in: the dye's absorption stops a path as a collision at the rate σf (a path
    /// through a dye is always at one wavelength: the medium is dispersive), and which of the
    /// two a collision was is [`Tracer::dye_share`]'s to tell.
    pub fn scattering(&self, i: MediumId) -> Option<Cow<'a, Scattering>> {
        let media = self.scene.media();
        if let Some(dye) = media.fluorescence(i) {
            let nm = self.wavelength();
            return Scattering::with_dye(media.scattering(i), dye.sigma(nm), nm).map(Cow::Owned);
        }
        let scattering = media.scattering(i)?;
        Some(match self.wavelength {
            Some(nm) if scattering.is_spectral() => Cow::Owned(scattering.at_wavelength(nm)),
            _ => Cow::Borrowed(scattering),
        })
    }

    /// The dye medium `i` holds, and the share of the collisions there at the tracer's
    /// wavelength that are the dye's absorption ([`Fluorescence::share`]); None without a dye.
    pub fn dye_share(&self, i: MediumId) -> Option<(&'a Fluorescence, f64)> {
        let media = self.scene.media();
        let dye = media.fluorescence(i)?;
        let nm = self.wavelength();
        let sigma_s = media.scattering(i).map_or(0.0, |s| s.sigma_at(nm));
        Some((dye, dye.share(nm, sigma_s)))
    }

    /// What medium `i` does to light's power: its absorption and emission (its scattering at
    /// the tracer's wavelength is [`Tracer::scattering`]).
    pub fn participating(&self, i: MediumId) -> &Participating {
        self.scene.media().participating(i)
    }

    /// The optical depth of absorption per channel along the straight piece from `from` along
    /// unit `dir` over `length` in `medium` (0 in vacuum and in a medium that does not absorb).
    pub fn optical_depth(
        &self,
        medium: Option<MediumId>,
        from: DVec3,
        dir: DVec3,
        length: f64,
    ) -> Rgb {
        medium.map_or(Rgb::ZERO, |i| {
            self.participating(i).optical_depth(from, dir, length)
        })
    }

    /// The fraction of light per channel that `medium` lets through along the straight piece
    /// from `from` along unit `dir` over `length`, at the tracer's wavelength: what it neither
    /// absorbs nor scatters out of the line, exp(−∫σa ds)·exp(−σs C) with C the scattering
    /// column (1 in vacuum). Surfaces on the way are the caller's ([`super::visibility`]).
    pub fn transmittance(
        &self,
        medium: Option<MediumId>,
        from: DVec3,
        dir: DVec3,
        length: f64,
    ) -> Rgb {
        let Some(i) = medium else {
            return Rgb::ONE;
        };
        let absorbed = (-self.participating(i).optical_depth(from, dir, length)).exp();
        let unscattered = self.scattering(i).map_or(Rgb::ONE, |sc| {
            sc.transmittance(sc.column(from, dir, length))
        });
        unscattered * absorbed
    }

    /// The refractive index at `p` in `medium` (None: vacuum, n = 1); None where the medium
    /// captures rays (a horizon).
    pub fn index(&self, medium: Option<MediumId>, p: DVec3) -> Option<f64> {
        match medium {
            None => Some(1.0),
            Some(m) => self.medium(m).sample(p).map(|s| s.n),
        }
    }
}
