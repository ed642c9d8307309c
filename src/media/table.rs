//! Tabulated profiles: a function of one coordinate through nodes, joined by monotone cubic
//! Hermite pieces (Fritsch–Carlson slopes), so the value and its derivative are continuous
//! and nothing overshoots between nodes; constant beyond the last node. The radial table of
//! a fiber and the height table of a layered atmosphere are both this, along r or along h.

/// Nodes (x, y) with their Hermite slopes.
#[derive(Clone, Debug)]
pub struct MonotoneCubic {
    /// Node positions, strictly increasing.
    x: Vec<f64>,
    /// Node values.
    y: Vec<f64>,
    /// dy/dx at the nodes.
    slope: Vec<f64>,
    /// Where to start looking for the piece holding t ([`Pieces`]).
    pieces: Pieces,
}

/// The piece of a table that each of [`Pieces::PER_PIECE`]·(nodes − 1) equal stretches of
/// its span starts in: a lookup starts there and steps at most a node or two either way, where
/// a binary search over the nodes took a chain of dependent, unpredictable comparisons (a
/// third of a mirage's time went to its table).
#[derive(Clone, Debug)]
struct Pieces {
    /// Stretches per unit of x.
    per_x: f64,
    /// The piece at each stretch's start.
    start: Vec<usize>,
}

impl Pieces {
    /// Stretches per piece, on average.
    const PER_PIECE: usize = 4;

    fn new(x: &[f64]) -> Self {
        let last = x.len() - 1;
        let count = Self::PER_PIECE * last;
        let per_x = count as f64 / (x[last] - x[0]);
        let start = (0..count)
            .map(|k| {
                let t = x[0] + k as f64 / per_x;
                x.partition_point(|&xi| xi <= t).clamp(1, last) - 1
            })
            .collect();
        Self { per_x, start }
    }

    /// The piece i with x[i] ≤ t < x[i + 1], for x[0] ≤ t < x[last].
    fn holding(&self, x: &[f64], t: f64) -> usize {
        let k = (((t - x[0]) * self.per_x) as usize).min(self.start.len() - 1);
        let mut i = self.start[k];
        // The stretch's start was rounded: step to the piece itself.
        while x[i] > t {
            i -= 1;
        }
        while x[i + 1] <= t {
            i += 1;
        }
        i
    }
}

impl MonotoneCubic {
    /// [`MonotoneCubic::new`] for a table of indices: every value > 0 besides.
    pub fn indices(
        x: Vec<f64>,
        y: Vec<f64>,
        flat_start: bool,
        keys: (&'static str, &'static str),
    ) -> Result<Self, (&'static str, String)> {
        if !y.iter().all(|v| *v > 0.0) {
            return Err((keys.1, "every value must be a finite number > 0".into()));
        }
        Self::new(x, y, flat_start, keys)
    }

    /// The curve through the nodes, or why not, as (the offending key `x_key` or `y_key`,
    /// message): at least two nodes, x strictly increasing and finite, every y finite and ≥ 0
    /// (an index or a coefficient; [`MonotoneCubic::indices`] for > 0). With `flat_start`,
    /// y'(x₀) = 0 (a radial profile, smooth across the axis). Between its nodes it lies
    /// between their values, so it stays ≥ 0 — or > 0 where they are.
    pub fn new(
        x: Vec<f64>,
        y: Vec<f64>,
        flat_start: bool,
        (x_key, y_key): (&'static str, &'static str),
    ) -> Result<Self, (&'static str, String)> {
        if x.len() != y.len() || x.len() < 2 {
            return Err((
                y_key,
                format!(
                    "`{x_key}` and `{y_key}` need the same number (≥ 2) of values, got {} and {}",
                    x.len(),
                    y.len()
                ),
            ));
        }
        if !x.windows(2).all(|w| w[1] > w[0]) || !x.iter().all(|v| v.is_finite()) {
            return Err((x_key, "must increase strictly".into()));
        }
        if !y.iter().all(|v| v.is_finite() && *v >= 0.0) {
            return Err((y_key, "every value must be a finite number ≥ 0".into()));
        }
        // Fritsch–Carlson: secant slopes, averaged inside, zeroed at extrema, limited to 3×.
        let secant: Vec<f64> = (0..x.len() - 1)
            .map(|i| (y[i + 1] - y[i]) / (x[i + 1] - x[i]))
            .collect();
        let last = x.len() - 1;
        let mut slope = vec![0.0; x.len()];
        for i in 1..last {
            if secant[i - 1] * secant[i] > 0.0 {
                slope[i] = 0.5 * (secant[i - 1] + secant[i]);
            }
        }
        slope[0] = if flat_start { 0.0 } else { secant[0] };
        slope[last] = secant[last - 1];
        for (i, &d) in secant.iter().enumerate() {
            if d == 0.0 {
                slope[i] = 0.0;
                slope[i + 1] = 0.0;
            } else {
                let (a, b) = (slope[i] / d, slope[i + 1] / d);
                let s = a * a + b * b;
                if s > 9.0 {
                    let t = 3.0 / s.sqrt();
                    slope[i] = t * a * d;
                    slope[i + 1] = t * b * d;
                }
            }
        }
        if flat_start {
            slope[0] = 0.0;
        }
        let pieces = Pieces::new(&x);
        Ok(Self {
            x,
            y,
            slope,
            pieces,
        })
    }

    /// y and dy/dx at `t`: the first node's value before it, the last one's after it
    /// (derivative 0 there).
    pub fn at(&self, t: f64) -> (f64, f64) {
        let last = self.x.len() - 1;
        if t >= self.x[last] {
            return (self.y[last], 0.0);
        }
        if t < self.x[0] {
            return (self.y[0], 0.0);
        }
        let i = self.pieces.holding(&self.x, t);
        let h = self.x[i + 1] - self.x[i];
        let u = (t - self.x[i]) / h;
        let (u2, u3) = (u * u, u * u * u);
        let (y0, y1, m0, m1) = (
            self.y[i],
            self.y[i + 1],
            self.slope[i] * h,
            self.slope[i + 1] * h,
        );
        let y = (2.0 * u3 - 3.0 * u2 + 1.0) * y0
            + (u3 - 2.0 * u2 + u) * m0
            + (-2.0 * u3 + 3.0 * u2) * y1
            + (u3 - u2) * m1;
        let dy = ((6.0 * u2 - 6.0 * u) * y0
            + (3.0 * u2 - 4.0 * u + 1.0) * m0
            + (-6.0 * u2 + 6.0 * u) * y1
            + (3.0 * u2 - 2.0 * u) * m1)
            / h;
        (y, dy)
    }

    /// How far a step from `t` may reach without skipping a piece: 4 pieces' lengths inside
    /// the nodes (RK4 and its error estimate sample a step at ≥ 4 points), and outside them
    /// the distance to the nearest node plus 4 end pieces (a step can then reach the table,
    /// never cross it).
    pub fn reach(&self, t: f64) -> f64 {
        let last = self.x.len() - 1;
        if t < self.x[0] {
            return self.x[0] - t + 4.0 * (self.x[1] - self.x[0]);
        }
        if t >= self.x[last] {
            return t - self.x[last] + 4.0 * (self.x[last] - self.x[last - 1]);
        }
        let i = self.pieces.holding(&self.x, t);
        4.0 * (self.x[i + 1] - self.x[i])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A lookup finds the piece a binary search over the nodes finds: on uneven tables (a
    /// mirage's heights, a node 1e-9 from the next, cubes spreading over six decades) and on
    /// spans whose stretches per unit overflow (subnormal nodes) or vanish (a span beyond
    /// f64's range), at every node, just below each and at points between.
    #[test]
    fn a_lookup_finds_the_piece_a_binary_search_finds() {
        let tables = [
            vec![0.0, 0.1, 0.2, 0.35, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0],
            vec![-1e-3, 0.0, 1e-9, 1.0],
            (0..50).map(|i| 0.01 * f64::from(i).powi(3)).collect(),
            vec![0.0, 1e-320, 2e-320],
            vec![-1e308, 0.0, 1e308],
        ];
        for x in tables {
            let pieces = Pieces::new(&x);
            let last = x.len() - 1;
            let mut checked = 0;
            for w in x.windows(2) {
                let between = [0.0, 1e-12, 0.3, 0.5, 0.999_999].map(|f| w[0] + f * (w[1] - w[0]));
                for t in between.into_iter().chain([w[1].next_down(), w[1]]) {
                    if t < x[0] || t >= x[last] {
                        continue;
                    }
                    let searched = x.partition_point(|&xi| xi <= t) - 1;
                    assert_eq!(pieces.holding(&x, t), searched, "t = {t:e} in {x:?}");
                    checked += 1;
                }
            }
            assert!(checked >= 6 * last - 1);
        }
    }
}
