//! The volume caustic map: photons stored where they scatter in a medium (Jensen and
//! Christensen 1998; a [`Photon`] there has no surface: its normal is zero), in a kiddo
//! kd-tree, and the in-scattered radiance they give.
//!
//! Photons are stored at scattering events, whose density per unit volume is σs times the
//! fluence; so at a point x, Σ p(ωi → ωo) Φ K(|x − x_p|) over the photons near x — K a kernel
//! normalised over the ball — estimates σs ∫ p L dω, the radiance the medium scatters into ωo
//! per unit length.

use super::Photon;
use crate::color::Rgb;
use glam::DVec3;
use kiddo::immutable::float::kdtree::ImmutableKdTree;
use kiddo::SquaredEuclidean;
use std::num::NonZero;

/// Volume photons with a kd-tree over their positions.
pub struct VolumeMap {
    photons: Vec<Photon>,
    tree: Option<ImmutableKdTree<f64, u32, 3, 32>>,
}

impl VolumeMap {
    /// Builds the tree over `photons` (at most u32::MAX of them are indexed).
    pub fn new(mut photons: Vec<Photon>) -> Self {
        photons.truncate(u32::MAX as usize);
        let tree = (!photons.is_empty()).then(|| {
            let points: Vec<[f64; 3]> = photons.iter().map(|p| p.position.to_array()).collect();
            ImmutableKdTree::new_from_slice(&points)
        });
        Self { photons, tree }
    }

    /// Number of photons.
    pub fn len(&self) -> usize {
        self.photons.len()
    }

    /// True when the map holds no photon.
    pub fn is_empty(&self) -> bool {
        self.photons.is_empty()
    }

    /// The squared distance from `p` to its k-th nearest photon, or `max_r2` when fewer than
    /// k lie within that.
    pub fn knn_radius2(&self, p: DVec3, k: usize, max_r2: f64) -> f64 {
        let Some(tree) = &self.tree else {
            return max_r2;
        };
        let k = NonZero::new(k.max(1)).expect("k ≥ 1");
        let found = tree.nearest_n::<SquaredEuclidean>(&p.to_array(), k);
        match found.last() {
            Some(nn) if found.len() == k.get() => nn.distance.min(max_r2),
            _ => max_r2,
        }
    }

    /// Σ weight(photon)·K(d) over the photons within squared radius `r2` of `p`, with the
    /// Epanechnikov kernel of the ball, K(d) = 15 (1 − d²/r²) / (8π r³).
    pub fn weighted(&self, p: DVec3, r2: f64, weight: impl Fn(&Photon) -> Rgb) -> Rgb {
        let Some(tree) = &self.tree else {
            return Rgb::ZERO;
        };
        if r2 <= 0.0 {
            return Rgb::ZERO;
        }
        let mut sum = Rgb::ZERO;
        for nn in tree.within_unsorted::<SquaredEuclidean>(&p.to_array(), r2) {
            sum += weight(&self.photons[nn.item as usize]) * (1.0 - nn.distance / r2);
        }
        sum * (15.0 / (8.0 * std::f64::consts::PI * r2 * r2.sqrt()))
    }
}
