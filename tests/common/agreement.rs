//! Two renders of one view compared by their films' own error estimates.

use grinlight::film::Film;

/// Two renders of one view, each film with its `error` layer: the second's image over the
/// first's (the sum of every pixel and channel), that difference in standard errors, and the
/// largest difference of a `block` × `block` block's channel in standard errors (the films
/// `width` pixels wide).
pub struct Agreement {
    /// The second's image over the first's.
    pub ratio: f64,
    /// That difference in standard errors.
    pub z: f64,
    /// The largest block's difference in standard errors.
    pub worst: f64,
}

pub fn agreement(first: &Film, second: &Film, width: usize, block: usize) -> Agreement {
    let layer = |film: &Film, name: &str| film.layer(name).unwrap();
    let (a, b) = (layer(first, "beauty"), layer(second, "beauty"));
    let (ea, eb) = (layer(first, "error"), layer(second, "error"));
    let mut worst: f64 = 0.0;
    for by in 0..a.len() / width / block {
        for bx in 0..width / block {
            let pixels: Vec<usize> = (0..block * block)
                .map(|k| (by * block + k / block) * width + bx * block + k % block)
                .collect();
            for c in 0..3 {
                let sum = |img: &[[f32; 3]]| pixels.iter().map(|&i| img[i][c] as f64).sum::<f64>();
                let var = |err: &[[f32; 3]]| {
                    pixels
                        .iter()
                        .map(|&i| (err[i][c] as f64).powi(2))
                        .sum::<f64>()
                };
                let sigma = (var(&ea) + var(&eb)).sqrt();
                if sigma > 0.0 {
                    worst = worst.max((sum(&a) - sum(&b)).abs() / sigma);
                }
            }
        }
    }
    let total = |img: &[[f32; 3]]| img.iter().flatten().map(|&v| v as f64).sum::<f64>();
    let spread = |err: &[[f32; 3]]| {
        err.iter()
            .flatten()
            .map(|&v| (v as f64).powi(2))
            .sum::<f64>()
    };
    Agreement {
        ratio: total(&b) / total(&a),
        z: (total(&b) - total(&a)).abs() / (spread(&ea) + spread(&eb)).sqrt(),
        worst,
    }
}
