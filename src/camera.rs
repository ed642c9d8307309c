//! The pinhole / thin-lens camera, in the conventions of `refs/README.md`:
//! f = normalize(look_at − position), r = normalize(f × up), u′ = r × f; for pixel (px, py),
//! py = 0 the top row, and a sample (u, v) ∈ [0,1)²:
//! x = (2(px+u)/W − 1)·tan(fov_y/2)·W/H, y = (1 − 2(py+v)/H)·tan(fov_y/2),
//! dir = normalize(f + x r + y u′).

use crate::pixel_filter::PixelFilter;
use glam::{DVec2, DVec3};

/// The point of the film and of the lens a camera ray is drawn through.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FilmPoint {
    /// Pixel column, from the left.
    pub px: u32,
    /// Pixel row, from the top.
    pub py: u32,
    /// Sub-pixel position across, in pixels from the pixel's left edge (outside [0, 1): a
    /// point of a neighbouring pixel).
    pub u: f64,
    /// Sub-pixel position down, in pixels from the pixel's top edge.
    pub v: f64,
    /// The point of the lens, in [0, 1)² ([`Camera::ray`]).
    pub lens: DVec2,
}

impl FilmPoint {
    /// The centre of pixel (`px`, `py`), through the lens's centre.
    pub fn pixel_centre(px: u32, py: u32) -> Self {
        Self {
            px,
            py,
            u: 0.5,
            v: 0.5,
            lens: DVec2::splat(0.5),
        }
    }

    /// The point `du` pixels to the right and `dv` pixels down, through the same point of the
    /// lens.
    pub fn moved(self, du: f64, dv: f64) -> Self {
        Self {
            u: self.u + du,
            v: self.v + dv,
            ..self
        }
    }
}

/// A thin lens: the aperture a camera ray leaves from, and the depth it focuses at.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThinLens {
    /// Aperture radius (scene units, > 0).
    pub radius: f64,
    /// Distance along the view axis of the plane in focus (scene units, > 0).
    pub focus: f64,
}

/// A primary ray: where it leaves the camera and its unit direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimaryRay {
    /// Where it starts (the eye, or a point of the lens).
    pub origin: DVec3,
    /// Unit direction.
    pub direction: DVec3,
}

/// How the film's points become rays.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// Through a pinhole at the eye (or a thin lens about it): rays spread from it, the film
    /// spanning tan(fov_y/2) = `tan_half_fov_y` up and down at unit distance.
    Perspective {
        /// tan of half the vertical field of view.
        tan_half_fov_y: f64,
    },
    /// Parallel rays along the view direction, from the points of a film square to it about
    /// the eye, `half_height` up and down (scene units) and as far across as the image's
    /// aspect makes it.
    Orthographic {
        /// Half the film's height, scene units.
        half_height: f64,
    },
}

/// A camera producing primary rays.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    /// Eye position (an orthographic camera's film centre).
    pub position: DVec3,
    forward: DVec3,
    right: DVec3,
    up: DVec3,
    /// How its film's points become rays.
    pub projection: Projection,
    /// Image width in pixels (the whole image's, cropped or not).
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// The thin lens; `None` for a pinhole.
    pub lens: Option<ThinLens>,
    /// The transmission axis of an ideal linear polarizer in front of the lens, radians from
    /// the image's right toward its up (`polarizer_deg`); `None` for none.
    pub polarizer: Option<f64>,
    /// How a pixel weighs the film around it (where its samples' film points fall).
    pub filter: PixelFilter,
    /// The part of the image a render makes; `None` for all of it.
    pub crop: Option<Crop>,
    /// Whether emitting surfaces and the sky seen directly are left out of the image
    /// (`hide_emitters`): what the camera's first chain finds before any reflection or bending
    /// refraction ([`crate::transport::chain::Chain::specular`]). Light they cast is seen as
    /// ever, and so is light a medium emits.
    pub hide_emitters: bool,
}

/// A window of a camera's image: `width` × `height` pixels from pixel (`x`, `y`), counted from
/// the image's top-left. A render makes the window alone, each of its pixels as the whole
/// image's render makes it — but that a pixel filter's support ends at the window's edges as
/// at the image's (Mitsuba's crop).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Crop {
    /// The window's left column.
    pub x: u32,
    /// The window's top row.
    pub y: u32,
    /// Its width in pixels.
    pub width: u32,
    /// Its height in pixels.
    pub height: u32,
}

impl Crop {
    /// Whether the window lies within a `width` × `height` image.
    pub fn fits(&self, width: u32, height: u32) -> bool {
        u64::from(self.x) + u64::from(self.width) <= u64::from(width)
            && u64::from(self.y) + u64::from(self.height) <= u64::from(height)
    }
}

impl Camera {
    /// Image width in pixels where a scene gives none.
    pub const DEFAULT_WIDTH: u32 = 640;
    /// Image height in pixels where a scene gives none.
    pub const DEFAULT_HEIGHT: u32 = 480;

    /// A camera looking from `position` at `look_at` with full vertical field of view
    /// `fov_y_deg`. Fails (with the reason) when the view direction is zero or parallel to `up`.
    pub fn new(
        position: DVec3,
        look_at: DVec3,
        up: DVec3,
        fov_y_deg: f64,
        width: u32,
        height: u32,
    ) -> Result<Self, &'static str> {
        let tan_half_fov_y = (0.5 * fov_y_deg.to_radians()).tan();
        let projection = Projection::Perspective { tan_half_fov_y };
        Self::projecting(projection, position, look_at, up, width, height)
    }

    /// An orthographic camera looking from `position` toward `look_at`, its film
    /// `view_height` high (scene units) about `position`. Fails as [`Camera::new`] does.
    pub fn orthographic(
        position: DVec3,
        look_at: DVec3,
        up: DVec3,
        view_height: f64,
        width: u32,
        height: u32,
    ) -> Result<Self, &'static str> {
        let projection = Projection::Orthographic {
            half_height: 0.5 * view_height,
        };
        Self::projecting(projection, position, look_at, up, width, height)
    }

    fn projecting(
        projection: Projection,
        position: DVec3,
        look_at: DVec3,
        up: DVec3,
        width: u32,
        height: u32,
    ) -> Result<Self, &'static str> {
        let forward = (look_at - position)
            .try_normalize()
            .ok_or("look_at equals position")?;
        let right = forward
            .cross(up)
            .try_normalize()
            .ok_or("up is parallel to the view direction")?;
        Ok(Self {
            position,
            forward,
            right,
            up: right.cross(forward),
            projection,
            width,
            height,
            lens: None,
            polarizer: None,
            filter: PixelFilter::Box,
            crop: None,
            hide_emitters: false,
        })
    }

    /// The window of the image a render makes: the crop, or the whole image.
    pub fn window(&self) -> Crop {
        self.crop.unwrap_or(Crop {
            x: 0,
            y: 0,
            width: self.width,
            height: self.height,
        })
    }

    /// The transmission axis of the polarizer in front of the lens, if any: a unit vector in
    /// the image plane at [`Camera::polarizer`].
    pub fn polarizer_axis(&self) -> Option<DVec3> {
        self.polarizer
            .map(|angle| angle.cos() * self.right + angle.sin() * self.up)
    }

    /// The unit direction it looks along (its polarizer's normal).
    pub fn forward(&self) -> DVec3 {
        self.forward
    }

    /// The first axis of the basis the camera's Stokes vector of light arriving along the ray
    /// of unit direction `d` is given in: d × up normalised, up the camera's (the image's
    /// right on the image's vertical axis; Mitsuba 3's `stokes` integrator's basis). The
    /// second is the light's direction −d × it (the image's up on its horizontal axis).
    pub fn stokes_axis(&self, d: DVec3) -> DVec3 {
        d.cross(self.up).try_normalize().unwrap_or(self.right)
    }

    /// The full vertical field of view (degrees) that gives a horizontal one of `fov_x_deg`.
    pub fn fov_y_from_x(fov_x_deg: f64, width: u32, height: u32) -> f64 {
        2.0 * ((0.5 * fov_x_deg.to_radians()).tan() * height as f64 / width as f64)
            .atan()
            .to_degrees()
    }

    /// The point (x, y) of the film at pixel (px, py), sub-pixel (u, v), `scale` times the
    /// image's own: x across from −scale·w/h (the left edge) to scale·w/h, y up from −scale
    /// (the bottom edge) to scale.
    fn film_xy(&self, px: u32, py: u32, u: f64, v: f64, scale: f64) -> (f64, f64) {
        let (w, h) = (self.width as f64, self.height as f64);
        let x = (2.0 * (px as f64 + u) / w - 1.0) * scale * w / h;
        let y = (1.0 - 2.0 * (py as f64 + v) / h) * scale;
        (x, y)
    }

    /// Unit direction of the ray through pixel (px, py) at sub-pixel (u, v): the pinhole's
    /// (the view direction for an orthographic camera).
    pub fn direction(&self, px: u32, py: u32, u: f64, v: f64) -> DVec3 {
        match self.projection {
            Projection::Perspective { tan_half_fov_y } => {
                let (x, y) = self.film_xy(px, py, u, v, tan_half_fov_y);
                (self.forward + x * self.right + y * self.up).normalize()
            }
            Projection::Orthographic { .. } => self.forward,
        }
    }

    /// The primary ray through `film` (its lens point samples the aperture uniformly).
    pub fn ray(&self, film: FilmPoint) -> PrimaryRay {
        let d = self.direction(film.px, film.py, film.u, film.v);
        match (self.projection, self.lens) {
            (Projection::Orthographic { half_height }, _) => {
                let (x, y) = self.film_xy(film.px, film.py, film.u, film.v, half_height);
                PrimaryRay {
                    origin: self.position + x * self.right + y * self.up,
                    direction: d,
                }
            }
            (Projection::Perspective { .. }, None) => PrimaryRay {
                origin: self.position,
                direction: d,
            },
            (Projection::Perspective { .. }, Some(ThinLens { radius, focus })) => {
                // The pinhole ray's point at depth `focus` along the view axis stays sharp.
                let focal_point = self.position + d * (focus / d.dot(self.forward));
                let r = radius * film.lens.x.sqrt();
                let phi = std::f64::consts::TAU * film.lens.y;
                let origin = self.position + r * (phi.cos() * self.right + phi.sin() * self.up);
                PrimaryRay {
                    origin,
                    direction: (focal_point - origin).normalize(),
                }
            }
        }
    }

    /// The angle (rad) between the pinhole rays through the centre pixel and its right-hand
    /// neighbour: the angular size of a pixel at the film's centre (0 for an orthographic
    /// camera, whose rays are parallel).
    pub fn pixel_angle(&self) -> f64 {
        let (cx, cy) = (self.width / 2, self.height / 2);
        crate::math::angle_between(
            self.direction(cx, cy, 0.5, 0.5),
            self.direction(cx + 1, cy, 0.5, 0.5),
        )
    }

    /// The width (scene units) a pixel at the film's centre spans at the point `x` seen
    /// straight on, given its [`Camera::pixel_angle`] `angle` (computed once by the caller):
    /// the angle times the distance from the eye, or an orthographic pixel's own width.
    pub fn pixel_width_at(&self, angle: f64, x: DVec3) -> f64 {
        match self.projection {
            Projection::Perspective { .. } => angle * self.position.distance(x),
            Projection::Orthographic { half_height } => 2.0 * half_height / self.height as f64,
        }
    }

    /// Whether the unit direction `dir` from the eye falls on the film: for a perspective
    /// camera, its pinhole view; for an orthographic one, whether it is the view direction.
    pub fn sees(&self, dir: DVec3) -> bool {
        let depth = dir.dot(self.forward);
        if depth <= 0.0 {
            return false;
        }
        match self.projection {
            Projection::Perspective { tan_half_fov_y } => {
                let aspect = self.width as f64 / self.height as f64;
                let (x, y) = (dir.dot(self.right) / depth, dir.dot(self.up) / depth);
                x.abs() <= tan_half_fov_y * aspect && y.abs() <= tan_half_fov_y
            }
            Projection::Orthographic { .. } => depth >= 1.0 - 1e-12,
        }
    }

    /// The range [lo, hi] of angles (rad) between `axis` (unit) and the pinhole rays of the
    /// film: 0 when the view holds `axis`, π when it holds −`axis`, else the extremes over the
    /// film's border, sampled at every pixel edge (so within half a pixel).
    pub fn angles_to(&self, axis: DVec3) -> (f64, f64) {
        let (w, h) = (self.width, self.height);
        let border = (0..=w)
            .flat_map(|x| [(x, 0), (x, h)])
            .chain((0..=h).flat_map(|y| [(0, y), (w, y)]))
            .map(|(x, y)| crate::math::angle_between(self.direction(x, y, 0.0, 0.0), axis));
        let (mut lo, mut hi) = border.fold((f64::INFINITY, 0.0f64), |(lo, hi), a| {
            (lo.min(a), hi.max(a))
        });
        if self.sees(axis) {
            lo = 0.0;
        }
        if self.sees(-axis) {
            hi = std::f64::consts::PI;
        }
        (lo, hi)
    }
}
