//! Light sources and their sampling for direct illumination at a surface point.
//! Radiometry per RGB channel: intensity W/sr, radiance W/(m²·sr), irradiance W/m².

use crate::color::Rgb;
use crate::ids::LightId;
use crate::math::Ball;
use crate::photometry::IntensityMap;
use crate::sampling::{
    cosine_hemisphere, power_cosine_hemisphere, uniform_cone, uniform_disk, uniform_sphere, Frame,
    Given, Pick,
};
use crate::shapes::{Disk, Primitive, Quad, SampledMesh, SurfaceSample};
use glam::DVec3;
use std::f64::consts::{PI, TAU};
use std::sync::Arc;

/// One photon leaving a light: where, which way, and the light's power as this sample
/// estimates it (W per channel): the emitted radiance (or intensity) over the joint pdf of the
/// position and direction. Averaged over many samples it is the light's total power, so a
/// photon emitted with probability p among N carries `power / (p N)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Emission {
    /// Start point.
    pub origin: DVec3,
    /// Unit direction of travel.
    pub direction: DVec3,
    /// Power estimate, W per channel.
    pub power: Rgb,
}

/// Where photons are sent: parallel and environment light through the `target` ball, from
/// where it enters the scene ([`Entry`]); light from points and surfaces over the target's cone
/// ([`Light::emit`]). The target is the scene ball itself (every photon as the light emits
/// it), or a ball holding what a batch of photons must meet (the specular surfaces, for
/// caustic photons): light missing it is not traced, and the photons toward it carry its power
/// only.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aim {
    /// The ball holding the scene.
    pub scene: Ball,
    /// The ball the photons are sent through.
    pub target: Ball,
    /// Where parallel and environment light sets off.
    pub entry: Entry,
}

/// Where parallel and environment light sets off toward the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Entry {
    /// From a plane upstream of the scene ball, as it arrives from beyond the world: nothing
    /// outside the scene ball changes it on its way in (the ambient medium neither absorbs
    /// nor scatters).
    Upstream,
    /// From the world sphere, where light from the environment enters an ambient medium that
    /// absorbs or scatters (what it loses and scatters between the world sphere and the
    /// scene is what the camera's direct estimate, attenuated to the world sphere, leaves
    /// out). Where the medium `scatters`, light along lines that miss the target also
    /// reaches the scene, scattered: half the photons set off through the target, half over
    /// the whole world's disk, each weighed by the mixture of both densities.
    World {
        /// The world sphere.
        ball: Ball,
        /// Whether the ambient medium scatters.
        scatters: bool,
    },
}

impl Aim {
    /// At the whole scene, light entering it as `entry` says.
    pub fn whole(scene: Ball, entry: Entry) -> Aim {
        Aim {
            scene,
            target: scene,
            entry,
        }
    }

    /// The directions from `from` that meet the target ball; None when the aim is the whole
    /// scene or `from` is inside the target (every direction may meet it).
    pub fn cone(&self, from: DVec3) -> Option<Cone> {
        (self.target != self.scene)
            .then(|| Cone::toward(self.target, from))
            .flatten()
    }
}

/// The cone of directions from a point that meet a ball: its unit axis and 1 − the cosine of
/// its half-angle (computed from the sine, so that a far, small ball's solid angle is not lost
/// to rounding).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cone {
    /// Unit axis, from the point to the ball's centre.
    pub axis: DVec3,
    /// 1 − cos of the half-angle.
    one_minus_cos: f64,
}

impl Cone {
    /// The directions from `from` that meet `ball`; None when `from` is inside it.
    pub fn toward(Ball { center, radius }: Ball, from: DVec3) -> Option<Cone> {
        let v = center - from;
        let d2 = v.length_squared();
        let sin2 = radius * radius / d2;
        (sin2 < 1.0).then(|| Cone {
            axis: v / d2.sqrt(),
            one_minus_cos: sin2 / (1.0 + (1.0 - sin2).sqrt()),
        })
    }

    /// Its solid angle, sr.
    pub fn solid_angle(&self) -> f64 {
        TAU * self.one_minus_cos
    }

    /// The density of [`Cone::sample`] at unit `dir` (1/sr): 1/solid angle inside the cone, 0
    /// outside.
    pub fn density(&self, dir: DVec3) -> f64 {
        match 1.0 - dir.dot(self.axis) <= self.one_minus_cos {
            true => 1.0 / self.solid_angle(),
            false => 0.0,
        }
    }

    /// A direction uniformly distributed over the cone (density 1/solid angle) for `uv`
    /// uniform in [0,1)².
    pub fn sample(&self, uv: (f64, f64)) -> DVec3 {
        Frame::new(self.axis).to_world(uniform_cone(1.0 - self.one_minus_cos, uv))
    }
}

/// Where a photon of parallel light travelling along unit `direction` sets off, for `uv`
/// uniform in [0,1)², and the reciprocal of the density of its line across the beam (an area,
/// length²: the photon carries the irradiance times it). As `aim.entry` says: on a disk of the
/// target's radius perpendicular to `direction` around the line through the target's centre,
/// in the plane 2 scene radii upstream of the scene's centre, sampled uniformly; or where
/// such a line — or, where the ambient medium scatters, half the time a line across the whole
/// world sphere — enters the world sphere. None for a line that misses the world sphere.
pub fn covering_disk(aim: Aim, direction: DVec3, uv: (f64, f64)) -> Option<(DVec3, f64)> {
    let Ball { center, radius } = aim.scene;
    let Ball {
        center: target,
        radius: r,
    } = aim.target;
    let frame = Frame::new(direction);
    let across = |(x, y): (f64, f64), radius: f64| frame.to_world(DVec3::new(x, y, 0.0)) * radius;
    let (world, scatters) = match aim.entry {
        Entry::Upstream => {
            let upstream = (target - center).dot(direction) + 2.0 * radius;
            let origin = target - direction * upstream + across(uniform_disk(uv), r);
            return Some((origin, PI * r * r));
        }
        Entry::World { ball, scatters } => (ball, scatters),
    };
    let Ball {
        center: c,
        radius: big,
    } = world;
    // The line's foot in the plane through the world's centre, drawn from the mixture: the
    // world's lines uniform in their distance ρ from its centre (density 1/(2πρR) across the
    // beam), for light scattered from a line reaches the scene about as 1/ρ.
    let share = if scatters { 0.5 } else { 1.0 };
    let target_foot = target - direction * (target - c).dot(direction);
    let foot = match uv.0 < share {
        true => target_foot + across(uniform_disk((uv.0 / share, uv.1)), r),
        false => {
            let rho = big * (uv.0 - share) / (1.0 - share);
            let phi = TAU * uv.1;
            c + across((rho * phi.cos(), rho * phi.sin()), 1.0)
        }
    };
    let rho = (foot - c).length();
    let in_target = (foot - target_foot).length_squared() <= r * r;
    let density = share * f64::from(u8::from(in_target)) / (PI * r * r)
        + (1.0 - share) * f64::from(u8::from(rho < big)) / (TAU * rho * big);
    let half_chord = (big * big - rho * rho).sqrt();
    // Just inside the sphere, so that the photon's first step starts within the world.
    let origin = foot - direction * (half_chord * (1.0 - 1e-9));
    (half_chord > 0.0 && density > 0.0 && density.is_finite()).then(|| (origin, 1.0 / density))
}

/// The emitting surface of an area light: a flat primitive, emitting on its normal's side, a
/// sphere, emitting outward, or a triangle mesh, each triangle emitting on its winding
/// normal's side.
#[derive(Clone, Debug, PartialEq)]
pub enum Emitter {
    /// A parallelogram, emitting on the side of e1 × e2.
    Quad(Quad),
    /// A disk (a full one: `inner` is 0), emitting on the side of its normal.
    Disk(Disk),
    /// A sphere, emitting outward.
    Sphere(Ball),
    /// A triangle mesh, each triangle emitting on the side of (b − a) × (c − a).
    Mesh(Arc<SampledMesh>),
}

impl Emitter {
    /// Whether the straight ray o + t d (d unit) meets the surface at some t > 0, either
    /// face ([`Primitive::meets_ray`], the test the scene's own primitive answers).
    pub fn meets_ray(&self, o: DVec3, d: DVec3) -> bool {
        match self {
            Emitter::Mesh(m) => m.mesh().meets_ray(o, d, 0.0, f64::INFINITY),
            Emitter::Quad(_) | Emitter::Disk(_) | Emitter::Sphere(_) => {
                self.primitive().meets_ray(o, d, 0.0, f64::INFINITY)
            }
        }
    }

    /// The largest distance of a point of the surface from its centre (length).
    pub fn extent(&self) -> f64 {
        match self {
            Emitter::Quad(q) => q.extent(),
            Emitter::Disk(d) => d.radius,
            Emitter::Sphere(b) => b.radius,
            Emitter::Mesh(m) => m.ball().radius,
        }
    }

    /// Area (length²).
    pub fn area(&self) -> f64 {
        match self {
            Emitter::Quad(q) => q.area(),
            Emitter::Disk(d) => d.area(),
            Emitter::Sphere(b) => 4.0 * PI * b.radius * b.radius,
            Emitter::Mesh(m) => m.area(),
        }
    }

    /// The largest area it shows along any direction (length²), or a bound on it: a flat
    /// surface's own, a sphere's disk πr², a mesh's whole area.
    pub fn largest_projected_area(&self) -> f64 {
        match self {
            Emitter::Quad(_) | Emitter::Disk(_) | Emitter::Mesh(_) => self.area(),
            Emitter::Sphere(b) => PI * b.radius * b.radius,
        }
    }

    /// The surface as a scene primitive.
    pub fn primitive(&self) -> Primitive {
        match self {
            Emitter::Quad(q) => Primitive::Quad(*q),
            Emitter::Disk(d) => Primitive::Disk(*d),
            Emitter::Sphere(Ball { center, radius }) => Primitive::Sphere {
                center: *center,
                radius: *radius,
            },
            Emitter::Mesh(m) => Primitive::Mesh(m.mesh().clone()),
        }
    }

    /// The centre of the surface (of a mesh: of its bounds).
    pub fn center(&self) -> DVec3 {
        match self {
            Emitter::Quad(q) => q.center(),
            Emitter::Disk(d) => d.center,
            Emitter::Sphere(b) => b.center,
            Emitter::Mesh(m) => m.ball().center,
        }
    }

    /// A point just in front of the emitting surface (in the medium it emits into).
    pub fn front(&self) -> DVec3 {
        let on = match self {
            Emitter::Quad(q) => SurfaceSample {
                position: q.center(),
                normal: q.normal(),
            },
            Emitter::Disk(d) => SurfaceSample {
                position: d.center,
                normal: d.normal,
            },
            Emitter::Sphere(b) => SurfaceSample {
                position: b.center + DVec3::Y * b.radius,
                normal: DVec3::Y,
            },
            Emitter::Mesh(m) => m.sample((0.5, 0.5)),
        };
        crate::math::offset(on.position, on.normal)
    }

    /// A direction from `p` toward the surface for `uv` uniform in [0,1)², the distance to the
    /// surface along it and its solid-angle density (1/sr): a flat surface's or a mesh's point
    /// drawn uniformly over its area (density d²/(cos θ · area), 0 from behind it); a sphere's
    /// direction uniform over the cone it fills seen from `p` (density 1/Ω). None where no
    /// direction reaches it (`p` on a flat surface, or inside a sphere).
    pub fn sample_toward(&self, p: DVec3, uv: (f64, f64)) -> Option<(DVec3, f64, f64)> {
        match self {
            Emitter::Quad(_) | Emitter::Disk(_) | Emitter::Mesh(_) => {
                let on = self.sample(uv);
                let v = on.position - p;
                let d = v.length();
                (d > 0.0).then(|| (v / d, d, self.area_density(v / d, d, on.normal)))
            }
            Emitter::Sphere(ball) => {
                let cone = Cone::toward(*ball, p)?;
                let wi = cone.sample(uv);
                // The nearer crossing of the ray with the sphere (the cone's edge grazes it).
                let v = ball.center - p;
                let along = v.dot(wi);
                let half_chord2 =
                    (ball.radius * ball.radius - (v.length_squared() - along * along)).max(0.0);
                let distance = along - half_chord2.sqrt();
                (distance > 0.0).then(|| (wi, distance, 1.0 / cone.solid_angle()))
            }
        }
    }

    /// The solid-angle density (1/sr) of a point drawn uniformly over the area, seen along
    /// unit `wi` at `distance` where the surface's normal is `normal`: d²/(cos θ · area), 0
    /// from behind.
    fn area_density(&self, wi: DVec3, distance: f64, normal: DVec3) -> f64 {
        let cos_l = -wi.dot(normal);
        match cos_l > 0.0 {
            true => distance * distance / (cos_l * self.area()),
            false => 0.0,
        }
    }

    /// The density (1/sr) with which [`Emitter::sample_toward`] at `from` draws the unit
    /// direction `wi` that meets the surface at `distance`, where its normal is `normal` (its
    /// hit's geometric normal).
    pub fn pdf_toward(&self, from: DVec3, wi: DVec3, distance: f64, normal: DVec3) -> f64 {
        match self {
            Emitter::Quad(_) | Emitter::Disk(_) | Emitter::Mesh(_) => {
                self.area_density(wi, distance, normal)
            }
            Emitter::Sphere(ball) => {
                Cone::toward(*ball, from).map_or(0.0, |cone| 1.0 / cone.solid_angle())
            }
        }
    }

    /// A point uniformly distributed over the surface for `uv` uniform in [0,1)², with the
    /// normal of its emitting side.
    pub fn sample(&self, uv: (f64, f64)) -> SurfaceSample {
        match self {
            Emitter::Quad(q) => SurfaceSample {
                position: q.point_at(uv),
                normal: q.normal(),
            },
            Emitter::Disk(d) => SurfaceSample {
                position: d.point_at(uv),
                normal: d.normal,
            },
            Emitter::Sphere(b) => {
                let position = b.center + uniform_sphere(uv) * b.radius;
                SurfaceSample {
                    position,
                    normal: (position - b.center).normalize(),
                }
            }
            Emitter::Mesh(m) => m.sample(uv),
        }
    }
}

/// A light source.
#[derive(Clone, Debug, PartialEq)]
pub enum Light {
    /// Isotropic point source.
    Point {
        /// Position.
        position: DVec3,
        /// Intensity, W/sr.
        intensity: Rgb,
    },
    /// A point source emitting inside a cone, with a smooth falloff between two angles.
    Spot {
        /// Position.
        position: DVec3,
        /// Unit axis of the cone.
        direction: DVec3,
        /// Intensity on the axis, W/sr.
        intensity: Rgb,
        /// cos of the angle where the falloff starts.
        cos_inner: f64,
        /// cos of the cone's half angle (no light beyond).
        cos_outer: f64,
        /// How the intensity falls from the inner angle to the outer.
        falloff: Falloff,
    },
    /// Constant radiance from one side of a quad or disk (also visible to the camera).
    Area {
        /// The surface.
        emitter: Emitter,
        /// Radiance, W/(m²·sr).
        radiance: Rgb,
    },
    /// A small disk LED with intensity I(θ) = I0 cos^m θ, I0 = P (m + 1)/(2π) for total power P.
    Led {
        /// The disk, emitting on its normal's side.
        disk: Disk,
        /// Peak intensity I0 per channel, W/sr.
        peak_intensity: Rgb,
        /// The exponent m.
        m: f64,
    },
    /// A point source whose intensity over direction is a luminaire's measured one
    /// ([`crate::photometry`]: an IES or EULUMDAT file's table, or an equal-area image).
    Goniometric {
        /// Position.
        position: DVec3,
        /// How the luminaire is turned.
        aim: Luminaire,
        /// The map's intensity unit in W/sr, per channel.
        colour: Rgb,
        /// The intensity over direction, in the map's unit.
        map: Arc<IntensityMap>,
    },
    /// Parallel light.
    Directional {
        /// Unit direction of propagation.
        direction: DVec3,
        /// Irradiance on a surface facing the light, W/m².
        irradiance: Rgb,
    },
}

impl Light {
    /// Whether a ray can meet it (an area light's surface): light from any other reaches a
    /// point of a camera path only by a light sample, in a straight line (through
    /// index-matched boundaries), never through a refracting or reflecting surface.
    pub fn is_met_by_rays(&self) -> bool {
        match self {
            Light::Area { .. } => true,
            Light::Point { .. }
            | Light::Spot { .. }
            | Light::Led { .. }
            | Light::Goniometric { .. }
            | Light::Directional { .. } => false,
        }
    }

    /// Its colour quantity (intensity, radiance, peak intensity or irradiance, as its type
    /// says), to be scaled.
    pub fn colour_mut(&mut self) -> &mut Rgb {
        match self {
            Light::Point { intensity, .. } | Light::Spot { intensity, .. } => intensity,
            Light::Area { radiance, .. } => radiance,
            Light::Led { peak_intensity, .. } => peak_intensity,
            Light::Goniometric { colour, .. } => colour,
            Light::Directional { irradiance, .. } => irradiance,
        }
    }

    /// The radiance leaving the front of its surface (the side its normal points to),
    /// W/(m²·sr): an area light's; a point, spot, LED or directional light is not a surface
    /// a ray can meet (zero).
    pub fn surface_radiance(&self) -> Rgb {
        match self {
            Light::Area { radiance, .. } => *radiance,
            Light::Point { .. }
            | Light::Spot { .. }
            | Light::Led { .. }
            | Light::Goniometric { .. }
            | Light::Directional { .. } => Rgb::ZERO,
        }
    }
}

/// How a measured luminaire is turned: its nadir (γ = 0) and its C = 0 and C = 90°
/// directions (unit, orthogonal; C counterclockwise seen from above, so c90 = −nadir × c0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Luminaire {
    /// The direction of γ = 0 (straight down the luminaire's axis).
    pub nadir: DVec3,
    /// The direction of C = 0, γ = 90°.
    pub c0: DVec3,
    /// The direction of C = 90°, γ = 90°.
    pub c90: DVec3,
}

impl Luminaire {
    /// The luminaire with nadir `nadir` and its C = 0 plane through `c0` (both non-zero, not
    /// parallel: `c0` is made orthogonal to the nadir).
    pub fn new(nadir: DVec3, c0: DVec3) -> Self {
        let nadir = nadir.normalize();
        let c0 = (c0 - nadir * c0.dot(nadir)).normalize();
        Self {
            nadir,
            c0,
            c90: (-nadir).cross(c0),
        }
    }

    /// Unit direction `dir` leaving the luminaire in its own frame
    /// ([`crate::photometry`]): x along C = 0, y along C = 90°, z the nadir.
    fn local(&self, dir: DVec3) -> DVec3 {
        DVec3::new(dir.dot(self.c0), dir.dot(self.c90), dir.dot(self.nadir))
    }

    /// The world direction of unit direction `d` of the luminaire's frame.
    fn world(&self, d: DVec3) -> DVec3 {
        self.c0 * d.x + self.c90 * d.y + self.nadir * d.z
    }
}

/// Light arriving at a point from one sample of a light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Incident {
    /// Unit direction from the point toward the light.
    pub wi: DVec3,
    /// Distance to the sampled light point (∞ for directional light).
    pub distance: f64,
    /// Irradiance estimate on a surface facing the light (W/m²): multiply by the BRDF and
    /// the receiving cosine.
    pub irradiance: Rgb,
    /// Solid-angle density of this sample's direction (1/sr): d²/(cos θ_light · area) for
    /// an area light, ∞ for lights no other strategy can find (point, spot, LED, directional).
    pub pdf: f64,
}

impl Light {
    /// The solid-angle density (1/sr) with which [`Light::sample_incident`] at `from` draws
    /// the unit direction `wi` that reaches the light's surface at distance `distance`, where
    /// the surface's unit normal is `normal` (its hit's geometric normal):
    /// d²/(cos θ_light · area) for a flat or mesh area light (0 from behind it), 1/Ω for a sphere
    /// seen from outside under the solid angle Ω (0 from inside); ∞ for the lights no other
    /// strategy can find (point, spot, LED, directional), which it draws with certainty.
    pub fn pdf_incident(&self, from: DVec3, wi: DVec3, distance: f64, normal: DVec3) -> f64 {
        match self {
            Light::Area { emitter, .. } => emitter.pdf_toward(from, wi, distance, normal),
            Light::Point { .. }
            | Light::Spot { .. }
            | Light::Led { .. }
            | Light::Goniometric { .. }
            | Light::Directional { .. } => f64::INFINITY,
        }
    }

    /// One sample of the light arriving at `p`; `None` when this sample sends nothing there.
    pub fn sample_incident(&self, p: DVec3, uv: (f64, f64)) -> Option<Incident> {
        let toward = |x: DVec3| {
            let v = x - p;
            let d = v.length();
            (d > 0.0).then(|| (v / d, d))
        };
        match self {
            Light::Area { emitter, radiance } => {
                let (wi, distance, pdf) = emitter.sample_toward(p, uv)?;
                (pdf > 0.0).then(|| Incident {
                    wi,
                    distance,
                    irradiance: *radiance / pdf,
                    pdf,
                })
            }
            Light::Point { .. }
            | Light::Spot { .. }
            | Light::Led { .. }
            | Light::Goniometric { .. }
            | Light::Directional { .. } => match self.anchor(uv)? {
                Anchor::Point(x) => {
                    let (wi, d) = toward(x)?;
                    let intensity = self.intensity(-wi);
                    (intensity != Rgb::ZERO).then(|| Incident {
                        wi,
                        distance: d,
                        irradiance: intensity / (d * d),
                        pdf: f64::INFINITY,
                    })
                }
                Anchor::Direction { toward, irradiance } => Some(Incident {
                    wi: toward,
                    distance: f64::INFINITY,
                    irradiance,
                    pdf: f64::INFINITY,
                }),
            },
        }
    }

    /// Where a path connects to a light no direction sample finds: a point (sampled on an
    /// LED's disk by `uv`) or, for parallel light, the direction toward it with its
    /// irradiance. None for an area light.
    pub fn anchor(&self, uv: (f64, f64)) -> Option<Anchor> {
        match self {
            Light::Point { position, .. }
            | Light::Spot { position, .. }
            | Light::Goniometric { position, .. } => Some(Anchor::Point(*position)),
            Light::Led { disk, .. } => Some(Anchor::Point(disk.point_at(uv))),
            Light::Directional {
                direction,
                irradiance,
            } => Some(Anchor::Direction {
                toward: -*direction,
                irradiance: *irradiance,
            }),
            Light::Area { .. } => None,
        }
    }

    /// Intensity (W/sr) a point-like light (point, spot, LED) sends along unit `dir` leaving
    /// it; zero for other lights.
    pub fn intensity(&self, dir: DVec3) -> Rgb {
        match self {
            Light::Point { intensity, .. } => *intensity,
            Light::Spot {
                direction,
                intensity,
                cos_inner,
                cos_outer,
                falloff,
                ..
            } => *intensity * falloff.at(*cos_outer, *cos_inner, dir.dot(*direction)),
            Light::Led {
                disk,
                peak_intensity,
                m,
            } => {
                let cos = dir.dot(disk.normal);
                if cos > 0.0 {
                    *peak_intensity * cos.powf(*m)
                } else {
                    Rgb::ZERO
                }
            }
            Light::Goniometric {
                aim, colour, map, ..
            } => *colour * map.intensity(aim.local(dir)),
            Light::Area { .. } | Light::Directional { .. } => Rgb::ZERO,
        }
    }
}

/// Where a path connects to a light it cannot hit (see [`Light::anchor`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Anchor {
    /// A point that sends [`Light::intensity`] along each direction.
    Point(DVec3),
    /// Parallel light.
    Direction {
        /// Unit direction toward the light.
        toward: DVec3,
        /// Irradiance on a surface facing it, W/m².
        irradiance: Rgb,
    },
}

impl Light {
    /// Where the light sits, to find the medium it emits into: its position, or a point just
    /// in front of its emitting surface; None for parallel light (it comes from beyond the
    /// scene).
    pub fn origin(&self) -> Option<DVec3> {
        match self {
            Light::Point { position, .. }
            | Light::Spot { position, .. }
            | Light::Goniometric { position, .. } => Some(*position),
            Light::Area { emitter, .. } => Some(emitter.front()),
            Light::Led { disk, .. } => Some(crate::math::offset(disk.center, disk.normal)),
            Light::Directional { .. } => None,
        }
    }

    /// Whether a path can find this light by sampling directions (an area light's surface is
    /// in the scene); point, spot, LED and parallel light are reached only by connecting to
    /// them.
    pub fn is_hittable(&self) -> bool {
        matches!(self, Light::Area { .. })
    }

    /// The solid angle over which the light spreads its power: its power over its peak
    /// intensity (sr) — 4π for a point, π for a Lambertian surface, 2π/(m + 1) for an LED,
    /// about 2π(1 − (cos θ_inner + cos θ_outer)/2) for a spot (its falloff taken as linear
    /// in cos θ); 0 for parallel light. A cone of solid angle Ω receives at most Ω/spread of
    /// the power.
    fn spread(&self) -> f64 {
        match self {
            Light::Point { .. } => 4.0 * PI,
            Light::Spot {
                cos_inner,
                cos_outer,
                ..
            } => TAU * (1.0 - 0.5 * (cos_inner + cos_outer)),
            // A Lambertian surface's power π A L over its peak intensity: π flat, 4π a sphere.
            Light::Area { emitter, .. } => PI * emitter.area() / emitter.largest_projected_area(),
            Light::Led { m, .. } => TAU / (m + 1.0),
            Light::Goniometric { map, .. } => match map.peak() > 0.0 {
                true => map.power() / map.peak(),
                false => 0.0,
            },
            Light::Directional { .. } => 0.0,
        }
    }

    /// The cone from `origin` toward `aim`'s target when it is narrower than the light's
    /// [`Light::spread`] (sampling it then wastes fewer photons than the light's own
    /// distribution does).
    fn narrowing_cone(&self, origin: DVec3, aim: Aim) -> Option<Cone> {
        aim.cone(origin)
            .filter(|cone| cone.solid_angle() < self.spread())
    }

    /// A photon from this light for four uniform numbers `u` (see [`Emission`]); `None` when
    /// this sample emits nothing (a spot's falloff edge, a direction behind an emitting
    /// surface). Photons are sent as `aim` says: parallel light through its target ball from
    /// upstream of the scene; light from a point or surface, where the target's cone seen from
    /// the photon's start is narrower than the light's spread, uniformly over that cone — the
    /// photon then carries the light's intensity (or radiance × area × cos θ) along its
    /// direction times the cone's solid angle, and the light's power outside the cone is not
    /// traced (Jensen's projection maps).
    pub fn emit(&self, u: [f64; 4], aim: Aim) -> Option<Emission> {
        let emission = |origin, direction, power| {
            Some(Emission {
                origin,
                direction,
                power,
            })
        };
        let aimed = |origin: DVec3, cone: Cone, power: &dyn Fn(DVec3) -> Rgb| {
            let direction = cone.sample((u[2], u[3]));
            let power = power(direction) * cone.solid_angle();
            (power != Rgb::ZERO).then_some(Emission {
                origin,
                direction,
                power,
            })
        };
        match self {
            Light::Point { position, .. }
            | Light::Spot { position, .. }
            | Light::Goniometric { position, .. } => {
                if let Some(cone) = self.narrowing_cone(*position, aim) {
                    return aimed(*position, cone, &|d| self.intensity(d));
                }
            }
            Light::Area { emitter, radiance } => {
                let SurfaceSample { position, normal } = emitter.sample((u[0], u[1]));
                let origin = crate::math::offset(position, normal);
                if let Some(cone) = self.narrowing_cone(origin, aim) {
                    let area = emitter.area();
                    return aimed(origin, cone, &|d| {
                        *radiance * (d.dot(normal).max(0.0) * area)
                    });
                }
            }
            Light::Led { disk, .. } => {
                let origin = disk.point_at((u[0], u[1]));
                if let Some(cone) = self.narrowing_cone(origin, aim) {
                    return aimed(origin, cone, &|d| self.intensity(d));
                }
            }
            Light::Directional { .. } => {}
        }
        match self {
            Light::Point {
                position,
                intensity,
            } => emission(
                *position,
                uniform_sphere((u[0], u[1])),
                *intensity * (4.0 * PI),
            ),
            Light::Spot {
                position,
                direction,
                intensity,
                cos_inner,
                cos_outer,
                falloff,
            } => {
                let local = uniform_cone(*cos_outer, (u[0], u[1]));
                let f = falloff.at(*cos_outer, *cos_inner, local.z);
                (f > 0.0).then_some(())?;
                let solid_angle = TAU * (1.0 - cos_outer);
                emission(
                    *position,
                    Frame::new(*direction).to_world(local),
                    *intensity * (f * solid_angle),
                )
            }
            // Off the emitting surface, which is a primitive of the scene: a photon started
            // on a tilted quad (its sampled point rounded to either side of the plane) hit
            // the light itself at t ≈ 1e-16 about half the time, and its power was lost.
            Light::Area { emitter, radiance } => {
                let SurfaceSample { position, normal } = emitter.sample((u[0], u[1]));
                emission(
                    crate::math::offset(position, normal),
                    Frame::new(normal).to_world(cosine_hemisphere((u[2], u[3]))),
                    *radiance * (PI * emitter.area()),
                )
            }
            Light::Led {
                disk,
                peak_intensity,
                m,
            } => emission(
                disk.point_at((u[0], u[1])),
                Frame::new(disk.normal).to_world(power_cosine_hemisphere(*m, (u[2], u[3]))),
                *peak_intensity * (TAU / (m + 1.0)),
            ),
            Light::Goniometric {
                position,
                aim: luminaire,
                map,
                ..
            } => {
                let drawn = map.draw([u[0], u[1], u[2]])?;
                let direction = luminaire.world(drawn.direction);
                let power = self.intensity(direction) / drawn.pdf;
                (power != Rgb::ZERO).then_some(())?;
                emission(*position, direction, power)
            }
            Light::Directional {
                direction,
                irradiance,
            } => {
                let (origin, area) = covering_disk(aim, *direction, (u[0], u[1]))?;
                emission(origin, *direction, *irradiance * area)
            }
        }
    }

    /// A weight for choosing among lights: the light's power (W, mean over channels) as sent
    /// by `aim` — exact for the whole scene except for a spot, where the falloff is taken as
    /// linear in cos θ; toward a target, at most the power the target's cone can receive
    /// from the light's nearest possible point (an upper bound, so that no light that can
    /// reach the target goes unchosen).
    pub fn selection_power(&self, aim: Aim) -> f64 {
        self.power(aim) * self.reach(aim)
    }

    /// An upper bound on the fraction of the light's power that reaches `aim`'s target (1 for
    /// the whole scene and for parallel light, already sent through the target): the solid
    /// angle of the target seen from the light's point nearest to it over the light's
    /// [`Light::spread`].
    fn reach(&self, aim: Aim) -> f64 {
        let (from, extent) = match self {
            Light::Point { position, .. }
            | Light::Spot { position, .. }
            | Light::Goniometric { position, .. } => (*position, 0.0),
            Light::Area { emitter, .. } => (emitter.center(), emitter.extent()),
            Light::Led { disk, .. } => (disk.center, disk.radius),
            Light::Directional { .. } => return 1.0,
        };
        // The point of the light nearest the target, in the direction of its centre.
        let toward = aim.target.center - from;
        let d = toward.length();
        let nearest = from + toward * (extent / d).min(1.0);
        aim.cone(nearest)
            .map_or(1.0, |cone| (cone.solid_angle() / self.spread()).min(1.0))
    }

    /// The light's power (W, mean over channels) as sent by `aim`: parallel light's through
    /// the target's disk, any other's its peak intensity times its [`Light::spread`].
    fn power(&self, aim: Aim) -> f64 {
        let p = match self {
            Light::Directional { irradiance, .. } => {
                *irradiance * (PI * aim.target.radius * aim.target.radius)
            }
            Light::Point { .. }
            | Light::Spot { .. }
            | Light::Led { .. }
            | Light::Area { .. }
            | Light::Goniometric { .. } => self.peak_intensity() * self.spread(),
        };
        p.element_sum() / 3.0
    }

    /// The largest intensity it sends along any direction (W/sr; a surface's radiance times
    /// its area); zero for parallel light.
    fn peak_intensity(&self) -> Rgb {
        match self {
            Light::Point { intensity, .. } | Light::Spot { intensity, .. } => *intensity,
            Light::Area { emitter, radiance } => *radiance * emitter.largest_projected_area(),
            Light::Led { peak_intensity, .. } => *peak_intensity,
            Light::Goniometric { colour, map, .. } => *colour * map.peak(),
            Light::Directional { .. } => Rgb::ZERO,
        }
    }
}

/// How a spot's intensity falls off between its inner angle (full) and its outer (none).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Falloff {
    /// A smooth step in cos θ: 3t² − 2t³, t = (cos θ − cos θ_outer)/(cos θ_inner − cos θ_outer).
    #[default]
    SmoothStep,
    /// Linear in the angle: (θ_outer − θ)/(θ_outer − θ_inner), as Mitsuba 3's `spot`.
    LinearInAngle,
}

impl Falloff {
    /// The fraction of the axis's intensity at cos θ = `cos`, between the cone's `cos_outer`
    /// and the falloff's start `cos_inner`.
    pub fn at(self, cos_outer: f64, cos_inner: f64, cos: f64) -> f64 {
        match self {
            Falloff::SmoothStep => smoothstep(cos_outer, cos_inner, cos),
            Falloff::LinearInAngle => {
                if cos >= cos_inner {
                    return 1.0;
                }
                if cos < cos_outer {
                    return 0.0;
                }
                let (outer, inner) = (cos_outer.acos(), cos_inner.acos());
                ((outer - cos.clamp(-1.0, 1.0).acos()) / (outer - inner)).clamp(0.0, 1.0)
            }
        }
    }
}

fn smoothstep(lo: f64, hi: f64, x: f64) -> f64 {
    if hi <= lo {
        return if x >= hi { 1.0 } else { 0.0 };
    }
    let t = ((x - lo) / (hi - lo)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// How many lights a scattering vertex's direct estimate samples: a choice of the integrator,
/// by where its cost lies. Measured on 64 lamps of spread intensities in a room
/// (`bench/many_lights.sh`, 10 s each): the path tracer, whose every vertex takes a light
/// sample, read a relative RMSE of 0.0729 sampling each light and 0.0316 drawing one; the
/// photon mapper, whose time goes to its photons and whose direct estimate is at the first
/// vertex only, 0.0258 sampling each and 0.0495 drawing one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightSamples {
    /// One light drawn by the [`LightSampler`].
    One,
    /// One sample of every light.
    Each,
}

/// Which light a scattering vertex's light sample goes to: one light drawn in proportion to
/// a bound on the irradiance it can send to the vertex — a located light's peak intensity
/// over its squared distance (its size added, so that a surface's own lamp does not take
/// every sample), parallel light's irradiance — its estimate divided by the probability it
/// had. No light that can reach the vertex has probability 0, so the estimate is unbiased; a
/// scene of many lights costs one shadow ray a vertex instead of one per light, and near
/// lamps get the samples that far ones do not need (a whole-scene power sampler would give
/// every point the same choice). Each draw costs one pass over the lights, no ray and no
/// allocation; a scene of one light draws no number.
#[derive(Clone, Debug, PartialEq)]
pub struct LightSampler {
    reach: Vec<Reach>,
}

/// What [`LightSampler`] knows of one light.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Reach {
    /// A light at a place: its centre, its squared extent (scene units²) and its peak
    /// intensity (W/sr, mean over channels).
    Located {
        center: DVec3,
        extent2: f64,
        intensity: f64,
    },
    /// Parallel light: its irradiance (W/m², mean over channels).
    Parallel { irradiance: f64 },
}

/// The squared distance (scene units²) below which [`LightSampler`] treats a lamp as that
/// near: a bound that keeps the weight of a point light at the vertex itself finite.
const NEAREST2: f64 = 1e-12;

impl Reach {
    fn of(light: &Light) -> Self {
        match light {
            Light::Directional { irradiance, .. } => Reach::Parallel {
                irradiance: irradiance.mean(),
            },
            Light::Point { position, .. }
            | Light::Spot { position, .. }
            | Light::Goniometric { position, .. } => Reach::Located {
                center: *position,
                extent2: 0.0,
                intensity: light.peak_intensity().mean(),
            },
            Light::Area { emitter, .. } => Reach::Located {
                center: emitter.center(),
                extent2: emitter.extent() * emitter.extent(),
                intensity: light.peak_intensity().mean(),
            },
            Light::Led { disk, .. } => Reach::Located {
                center: disk.center,
                extent2: disk.radius * disk.radius,
                intensity: light.peak_intensity().mean(),
            },
        }
    }

    /// The weight of the light at `p` (W/m²; 0 only for a light that sends nothing).
    fn at(&self, p: DVec3) -> f64 {
        let w = match *self {
            Reach::Parallel { irradiance } => irradiance,
            Reach::Located {
                center,
                extent2,
                intensity,
            } => intensity / (center.distance_squared(p) + extent2).max(NEAREST2),
        };
        match w.is_finite() && w > 0.0 {
            true => w,
            false => 0.0,
        }
    }
}

impl LightSampler {
    /// The sampler of `lights`.
    pub fn new(lights: &[Light]) -> Self {
        Self {
            reach: lights.iter().map(Reach::of).collect(),
        }
    }

    /// The choice among the lights at point `p`.
    pub fn at(&self, p: DVec3) -> LightChoice<'_> {
        LightChoice {
            sampler: self,
            point: p,
            total: self.reach.iter().map(|r| r.at(p)).sum(),
        }
    }
}

/// The lights' distribution at one point ([`LightSampler::at`]).
#[derive(Clone, Copy, Debug)]
pub struct LightChoice<'s> {
    sampler: &'s LightSampler,
    point: DVec3,
    /// The sum of the lights' weights there.
    total: f64,
}

impl LightChoice<'_> {
    /// A light and its probability, by the number `u` (drawn from `rng` where not given)
    /// unless there is one light, which takes none (None: no light sends power).
    pub fn pick(&self, u: Given<1>, rng: &mut impl rand::Rng) -> Option<Pick> {
        let reach = &self.sampler.reach;
        if !(self.total > 0.0 && self.total.is_finite()) {
            return None;
        }
        if reach.len() == 1 {
            return Some(Pick {
                index: 0,
                probability: 1.0,
            });
        }
        let [u] = u.or_draw(rng);
        let target = u * self.total;
        let mut acc = 0.0;
        let mut last = None;
        for (index, r) in reach.iter().enumerate() {
            let w = r.at(self.point);
            if w > 0.0 {
                acc += w;
                last = Some(index);
                if target < acc {
                    break;
                }
            }
        }
        // Rounding may leave the target at the very end: the last light of weight > 0.
        last.map(|index| Pick {
            index,
            probability: self.probability(index),
        })
    }

    /// The probability light `i` is drawn here.
    pub fn probability(&self, i: usize) -> f64 {
        match self.sampler.reach.len() {
            1 => 1.0,
            _ => self.sampler.reach[i].at(self.point) / self.total,
        }
    }

    /// The chance light `light` had under `samples`.
    pub fn chance(&self, samples: LightSamples, light: LightId) -> f64 {
        match samples {
            LightSamples::Each => 1.0,
            LightSamples::One => self.probability(light.index()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::TriangleMesh;
    use glam::DMat3;

    /// A Lambertian sphere of radiance L and radius a, its centre at distance d: a surface
    /// whose normal makes the angle β with the direction to the centre, all of the sphere above
    /// its horizon, receives E = π L a² cos β / d². The light's samples (directions uniform
    /// over the cone the sphere fills, each carrying L Ω) summed on a 400 × 400 midpoint grid
    /// give it to 1e-5; each sample's point lies on the sphere, and `pdf_incident` gives its
    /// density back. From inside the sphere nothing is sent.
    #[test]
    fn a_sphere_lights_irradiance_is_its_closed_form() {
        let ball = Ball {
            center: DVec3::new(0.3, -0.2, 2.0),
            radius: 0.5,
        };
        let light = Light::Area {
            emitter: Emitter::Sphere(ball),
            radiance: Rgb(DVec3::splat(2.0)),
        };
        let p = DVec3::new(0.0, 0.1, 0.0);
        let axis = ball.center - p;
        let d = axis.length();
        let n = 400;
        for beta in [0.0f64, 0.6] {
            let side = axis.cross(DVec3::X).normalize();
            let normal = DMat3::from_axis_angle(side, beta) * (axis / d);
            let mut e = 0.0;
            for i in 0..n {
                for j in 0..n {
                    let uv = ((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
                    let s = light.sample_incident(p, uv).expect("the sphere is seen");
                    let x = p + s.wi * s.distance;
                    assert!(((x - ball.center).length() - ball.radius).abs() < 1e-12);
                    let pdf =
                        light.pdf_incident(p, s.wi, s.distance, (x - ball.center) / ball.radius);
                    assert!((pdf / s.pdf - 1.0).abs() < 1e-12);
                    e += s.irradiance.0.x * s.wi.dot(normal).max(0.0);
                }
            }
            e /= (n * n) as f64;
            let exact = PI * 2.0 * ball.radius * ball.radius * beta.cos() / (d * d);
            assert!((e / exact - 1.0).abs() < 1e-5, "β {beta}: {e} vs {exact}");
        }
        assert!(light.sample_incident(ball.center, (0.3, 0.6)).is_none());
    }

    /// The irradiance a Lambertian polygon of radiance L sends to a point of unit normal m is
    /// Lambert's closed form (Arvo 1995) E = (L/2) Σᵢ Θᵢ m·(rᵢ × rᵢ₊₁)/|rᵢ × rᵢ₊₁|, rᵢ = vᵢ − p,
    /// Θᵢ the angle between rᵢ and rᵢ₊₁. A regular hexagon facing the point, a
    /// fan of six triangles, and a seventh of the same area behind it facing away (it sends
    /// nothing, and takes its share of the samples): a mesh light's samples summed on a
    /// 700 × 700 midpoint grid give it to 1e-6 (the grid's error: −3.5e-7, −8.0e-8, −1.4e-8
    /// at n = 350, 700, 1400); every sample lies on the hexagon and `pdf_incident` gives its
    /// density back.
    #[test]
    fn a_mesh_lights_irradiance_is_lamberts_polygon_formula() {
        let (centre, r) = (DVec3::new(0.2, -0.1, 2.0), 0.6);
        let corner = |k: usize| {
            let a = TAU * k as f64 / 6.0 + 0.3;
            centre + r * DVec3::new(a.cos(), a.sin(), 0.0)
        };
        // Wound clockwise seen from below: each triangle's normal is −z, toward the point.
        let mut vertices = vec![centre];
        vertices.extend((0..6).map(corner));
        let mut triangles: Vec<[u32; 3]> = (0..6u32).map(|k| [0, 1 + (k + 1) % 6, 1 + k]).collect();
        // Behind, facing +z, of the same area.
        let behind = [
            centre + DVec3::Z,
            corner(0) + DVec3::Z,
            corner(1) + DVec3::Z,
        ];
        vertices.extend(behind);
        triangles.push([7, 8, 9]);
        let vertices = vertices.iter().map(|v| v.as_vec3().to_array()).collect();
        let mesh = TriangleMesh::new(vertices, triangles, None, None).unwrap();
        let emitter = Emitter::Mesh(Arc::new(SampledMesh::new(Arc::new(mesh)).unwrap()));
        let light = Light::Area {
            emitter,
            radiance: Rgb(DVec3::splat(2.0)),
        };
        let p = DVec3::new(0.1, 0.3, 0.0);
        let m = DVec3::new(0.2, -0.3, 1.0).normalize();
        let exact = 0.5
            * 2.0
            * (0..6)
                .map(|k| {
                    let (a, b) = (corner(k) - p, corner((k + 1) % 6) - p);
                    a.angle_between(b) * m.dot(a.cross(b).normalize())
                })
                .sum::<f64>()
                .abs();
        let n = 700;
        let mut e = 0.0;
        for i in 0..n {
            for j in 0..n {
                let uv = ((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
                let Some(s) = light.sample_incident(p, uv) else {
                    continue;
                };
                let x = p + s.wi * s.distance;
                assert!(
                    (x.z - 2.0).abs() < 1e-6,
                    "{x}: only the hexagon sends light"
                );
                let pdf = light.pdf_incident(p, s.wi, s.distance, -DVec3::Z);
                assert!((pdf / s.pdf - 1.0).abs() < 1e-12);
                e += s.irradiance.0.x * s.wi.dot(m).max(0.0);
            }
        }
        e /= (n * n) as f64;
        assert!((e / exact - 1.0).abs() < 1e-6, "{e} vs {exact}");
    }
}
