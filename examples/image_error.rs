//! The error of an image against a reference made of independent halves (linear RGB EXRs of
//! the same camera, e.g. two long renders with different seeds): the relative RMSE per pixel
//! and channel over the whole image and over pixel rectangles, and the mean ratios there. The
//! reference is the halves' average; its own noise (half the RMSE between the halves, relative
//! to their mean) is printed and taken out of the image's RMSE in quadrature, so that a short
//! render is not credited with the reference's noise.
//!
//! `cargo run --release --example image_error -- IMAGE.exr HALF_A.exr HALF_B.exr [X0 Y0 X1 Y1]...`
//!
//! Each rectangle is [X0, X1) × [Y0, Y1) in pixels from the top left.

use grinlight::compare::{read_exr_layer, relative_rmse};
use std::path::Path;

/// The pixels of `plane` (`width` wide) inside [x0, x1) × [y0, y1).
fn crop(plane: &[[f32; 3]], width: usize, [x0, y0, x1, y1]: [usize; 4]) -> Vec<[f32; 3]> {
    (y0..y1)
        .flat_map(|y| (x0..x1).map(move |x| plane[y * width + x]))
        .collect()
}

/// The ratio of the means of `a` and `b` (all channels).
fn mean_ratio(a: &[[f32; 3]], b: &[[f32; 3]]) -> f64 {
    let total = |img: &[[f32; 3]]| img.iter().flatten().map(|&c| c as f64).sum::<f64>();
    total(a) / total(b)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() < 3 || !(args.len() - 3).is_multiple_of(4) {
        return Err("usage: image_error IMAGE.exr HALF_A.exr HALF_B.exr [X0 Y0 X1 Y1]...".into());
    }
    let read = |p: &str| read_exr_layer(Path::new(p), None);
    let image = read(&args[0])?;
    let (w, h, image) = (image.width, image.height, image.pixels);
    let a = read(&args[1])?.pixels;
    let b = read(&args[2])?.pixels;
    if a.len() != image.len() || b.len() != image.len() {
        return Err(format!("the images are not all {w}×{h}").into());
    }
    let reference: Vec<[f32; 3]> = a
        .iter()
        .zip(&b)
        .map(|(p, q)| [0, 1, 2].map(|c| 0.5 * (p[c] + q[c])))
        .collect();
    let numbers: Vec<usize> = args[3..]
        .iter()
        .map(|s| s.parse())
        .collect::<Result<_, _>>()?;
    let mut rects = vec![("image", [0, 0, w, h])];
    for r in numbers.chunks(4) {
        if r[0] >= r[2] || r[1] >= r[3] || r[2] > w || r[3] > h {
            return Err(format!("the rectangle {r:?} is not inside {w}×{h}").into());
        }
        rects.push(("region", [r[0], r[1], r[2], r[3]]));
    }
    for (name, rect) in rects {
        let (image, reference) = (crop(&image, w, rect), crop(&reference, w, rect));
        let (a, b) = (crop(&a, w, rect), crop(&b, w, rect));
        let noise = 0.5 * relative_rmse(&a, &b) * mean_ratio(&b, &reference);
        let rmse = relative_rmse(&image, &reference);
        let corrected = (rmse * rmse - noise * noise).max(0.0).sqrt();
        println!(
            "{name} {rect:?}: relative RMSE {corrected:.4} (raw {rmse:.4}, reference noise \
             {noise:.4}); mean ratio {:.4}; halves' ratio {:.4}",
            mean_ratio(&image, &reference),
            mean_ratio(&a, &b)
        );
    }
    Ok(())
}
