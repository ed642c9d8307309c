//! Writes `scenes/heat_haze_temperature.txt`, the air temperature (K) over a sunlit road for
//! `scenes/heat_haze.toml`, and `scenes/heat_haze_board.png`, the texture of the board beside
//! the road (concentric yellow and black rings on blue, so its mirror image shows). The air: 300 K air, a road surface at 345 K whose heat reaches a few
//! centimetres up (an exponential boundary layer, scale height 4 cm), broken into warm and
//! cool cells across and along the road (convective plumes) that widen and rise with height.
//! The grid is 11 × 33 × 31 nodes over x ∈ [−4, 4], y ∈ [0, 0.4], z ∈ [−40, 0] m (1.25 cm
//! apart in height, where the layer is), x fastest, as the `grid` profile reads it.
//! Deterministic: the file in the repository is its output.
//!
//! `cargo run --release --example heat_haze_field`

use std::io::Write;

fn main() -> std::io::Result<()> {
    let (nx, ny, nz) = (11usize, 33usize, 31usize);
    let (x0, x1, y1, z0, z1) = (-4.0f64, 4.0f64, 0.4f64, -40.0f64, 0.0f64);
    let (air, road, height) = (300.0f64, 345.0f64, 0.04f64);
    let mut out =
        std::io::BufWriter::new(std::fs::File::create("scenes/heat_haze_temperature.txt")?);
    writeln!(
        out,
        "# Air temperature (K) for scenes/heat_haze.toml, written by examples/heat_haze_field.rs"
    )?;
    for k in 0..nz {
        let z = z0 + (z1 - z0) * k as f64 / (nz - 1) as f64;
        for j in 0..ny {
            let y = y1 * j as f64 / (ny - 1) as f64;
            let line: Vec<String> = (0..nx)
                .map(|i| {
                    let x = x0 + (x1 - x0) * i as f64 / (nx - 1) as f64;
                    // Plumes: a product of slow waves, wider higher up.
                    let w = 1.0 + 4.0 * y;
                    let plume = 0.25 * (1.3 * x / w + 0.7).sin() * (0.45 * z / w + 0.4 * x).sin();
                    let t = air + (road - air) * (-y / height).exp() * (1.0 + plume);
                    format!("{t:.3}")
                })
                .collect();
            writeln!(out, "{}", line.join(" "))?;
        }
    }
    out.flush()?;
    // The board: 96 × 64 sRGB pixels, rings around its centre.
    let board = image::RgbImage::from_fn(96, 64, |x, y| {
        let (dx, dy) = (x as f64 - 47.5, y as f64 - 31.5);
        let r = (dx * dx + dy * dy).sqrt();
        match r {
            r if r < 28.0 && ((r / 7.0) as u32).is_multiple_of(2) => image::Rgb([250, 200, 20]),
            r if r < 28.0 => image::Rgb([20, 20, 20]),
            _ => image::Rgb([30, 60, 170]),
        }
    });
    board
        .save("scenes/heat_haze_board.png")
        .map_err(std::io::Error::other)
}
