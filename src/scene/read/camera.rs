//! `[camera]`: the view. Every key's unit and default is in `docs/scene-format.md`.

use crate::camera::{Camera, Crop, ThinLens};
use crate::error::Result;
use crate::pixel_filter::{PixelFilter, Reach};
use crate::scene::table::TableReader;
use crate::settings;
use glam::DVec3;

/// `[camera]`.
pub fn read_camera(t: &mut TableReader) -> Result<Camera> {
    let position = t.vec3("position")?;
    let look_at = t.vec3("look_at")?;
    let up = t.vec3_or("up", DVec3::Y)?;
    let mut side = |key, default: u32| -> Result<u32> {
        let n = t.setting(key)?.and_then(|a| a.count());
        Ok(n.map_or(default, |n| u32::try_from(n).unwrap_or(u32::MAX)))
    };
    let width = side(&settings::WIDTH, Camera::DEFAULT_WIDTH)?;
    let height = side(&settings::HEIGHT, Camera::DEFAULT_HEIGHT)?;
    let orthographic = t.choice(
        "projection",
        &[("perspective", false), ("orthographic", true)],
    )?;
    let frame = Frame {
        position,
        look_at,
        up,
        width,
        height,
    };
    let mut camera = match orthographic {
        true => read_orthographic(t, frame)?,
        false => read_perspective(t, frame)?,
    };
    camera.polarizer = t.turn_opt("polarizer_deg")?;
    camera.filter = read_filter(t)?;
    camera.crop = read_crop(t, width, height)?;
    camera.hide_emitters = t.bool_or("hide_emitters", false)?;
    Ok(camera)
}

/// `crop`: `[x, y, width, height]`, the window of the `width` × `height` image a render makes
/// (pixels, from the top-left), non-empty and within the image.
fn read_crop(t: &mut TableReader, width: u32, height: u32) -> Result<Option<Crop>> {
    if !t.has("crop") {
        return Ok(None);
    }
    let [x, y, w, h] = t.counts::<4>("crop")?;
    let side = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
    let crop = Crop {
        x: side(x),
        y: side(y),
        width: side(w),
        height: side(h),
    };
    t.check(
        "crop",
        crop.width > 0 && crop.height > 0 && crop.fits(width, height),
        format!(
            "a window of {w}×{h} pixels at ({x}, {y}) must be non-empty and lie within the \
             {width}×{height} image"
        ),
    )?;
    Ok(Some(crop))
}

/// `filter` (`"box"`, the default, or `"gaussian"`) and a Gaussian's `filter_stddev` (pixels,
/// in (0, 8]; 0.5, Mitsuba's default), `filter_radius` (pixels, in (0, 32]; 4σ, Mitsuba's) and
/// `filter_beyond_image` (false: a pixel at the image's edge weighs the film inside it only,
/// as Mitsuba's; true: the film beyond it too, as pbrt's).
fn read_filter(t: &mut TableReader) -> Result<PixelFilter> {
    let gaussian = t.choice("filter", &[("box", false), ("gaussian", true)])?;
    if !gaussian {
        for key in ["filter_stddev", "filter_radius", "filter_beyond_image"] {
            t.check(
                key,
                !t.has(key),
                "is a Gaussian filter's: give filter = \"gaussian\"",
            )?;
        }
        return Ok(PixelFilter::Box);
    }
    let stddev = t.positive_or("filter_stddev", 0.5)?;
    t.check(
        "filter_stddev",
        stddev <= 8.0,
        format!("must be at most 8 pixels, got {stddev}"),
    )?;
    let radius = t.positive_or("filter_radius", 4.0 * stddev)?;
    t.check(
        "filter_radius",
        radius <= 32.0,
        format!("must be at most 32 pixels, got {radius}"),
    )?;
    let reach = match t.bool_or("filter_beyond_image", false)? {
        true => Reach::Beyond,
        false => Reach::Image,
    };
    Ok(PixelFilter::Gaussian {
        stddev,
        radius,
        reach,
    })
}

/// Where a camera stands and looks, and its image's size in pixels.
struct Frame {
    position: DVec3,
    look_at: DVec3,
    up: DVec3,
    width: u32,
    height: u32,
}

/// An orthographic camera's keys: `view_height`, and no field of view or lens.
fn read_orthographic(t: &mut TableReader, f: Frame) -> Result<Camera> {
    for key in [
        "fov_y_deg",
        "fov_x_deg",
        "aperture_radius",
        "focus_distance",
    ] {
        t.check(
            key,
            !t.has(key),
            "an orthographic camera has no field of view or lens (its film is `view_height` high)",
        )?;
    }
    let view_height = t.positive("view_height")?;
    Camera::orthographic(f.position, f.look_at, f.up, view_height, f.width, f.height)
        .map_err(|e| t.error("look_at", e))
}

/// A perspective camera's keys: its field of view, and its lens if it has one.
fn read_perspective(t: &mut TableReader, f: Frame) -> Result<Camera> {
    let (width, height) = (f.width, f.height);
    let fov_y = match (t.has("fov_y_deg"), t.has("fov_x_deg")) {
        (true, false) => t.f64("fov_y_deg")?,
        (false, true) => Camera::fov_y_from_x(t.f64("fov_x_deg")?, width, height),
        _ => {
            return Err(t.error(
                "fov_y_deg",
                "give exactly one of `fov_y_deg` and `fov_x_deg`",
            ))
        }
    };
    let key = if t.has("fov_y_deg") {
        "fov_y_deg"
    } else {
        "fov_x_deg"
    };
    t.check(
        key,
        fov_y > 0.0 && fov_y < 179.0,
        "the field of view must be in (0°, 179°)",
    )?;
    let mut camera = Camera::new(f.position, f.look_at, f.up, fov_y, width, height)
        .map_err(|e| t.error("look_at", e))?;
    let aperture = t.f64_or("aperture_radius", 0.0)?;
    t.check("aperture_radius", aperture >= 0.0, "must be ≥ 0")?;
    if aperture > 0.0 {
        let focus = t.positive("focus_distance")?;
        camera.lens = Some(ThinLens {
            radius: aperture,
            focus,
        });
    }
    Ok(camera)
}
