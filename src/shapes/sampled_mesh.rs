//! Points drawn uniformly over a triangle mesh's surface: a triangle in proportion to its area,
//! then a point uniformly over it (the square-root warp of Pharr et al. 2023, §6.5.4), so
//! that the density over the whole
//! surface is 1/A. An emitting mesh's light samples and photons start here.

use super::TriangleMesh;
use crate::math::Ball;
use crate::sampling::Discrete;
use glam::DVec3;
use std::sync::Arc;

/// A point drawn on a surface and the surface's unit normal there (for an emitting surface: on
/// the side it emits to).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceSample {
    /// The point.
    pub position: DVec3,
    /// Unit normal.
    pub normal: DVec3,
}

/// A triangle mesh with the distribution of its triangles by area. Each triangle's normal is
/// its winding's, (b − a) × (c − a) for corners a, b, c: the geometric normal of its hits.
#[derive(Debug, PartialEq)]
pub struct SampledMesh {
    mesh: Arc<TriangleMesh>,
    /// Triangles by area (zero-area ones are never drawn).
    triangles: Discrete,
    /// Total area (length²).
    area: f64,
    /// A ball around the vertices' bounds' centre holding every vertex.
    ball: Ball,
}

impl SampledMesh {
    /// The mesh's surface; None where all its triangles have zero area or the areas do not sum
    /// to a finite number.
    pub fn new(mesh: Arc<TriangleMesh>) -> Option<Self> {
        let areas: Vec<f64> = (0..mesh.len())
            .map(|i| {
                let [a, b, c] = mesh.corners(i);
                0.5 * (b - a).cross(c - a).length()
            })
            .collect();
        let triangles = Discrete::new(&areas)?;
        let center = mesh.bounds().center();
        let radius = (0..mesh.len())
            .flat_map(|i| mesh.corners(i))
            .map(|v| v.distance(center))
            .fold(0.0, f64::max);
        Some(Self {
            triangles,
            area: areas.iter().sum(),
            ball: Ball { center, radius },
            mesh,
        })
    }

    /// The mesh.
    pub fn mesh(&self) -> &Arc<TriangleMesh> {
        &self.mesh
    }

    /// Total area (length²).
    pub fn area(&self) -> f64 {
        self.area
    }

    /// A ball holding the whole surface.
    pub fn ball(&self) -> Ball {
        self.ball
    }

    /// A point distributed uniformly over the surface for `uv` uniform in [0, 1)² (density
    /// 1/area), with its triangle's normal.
    pub fn sample(&self, (u, v): (f64, f64)) -> SurfaceSample {
        let pick = self.triangles.pick(u);
        let [a, b, c] = self.mesh.corners(pick.index);
        let s = self.triangles.within(u, pick).sqrt();
        SurfaceSample {
            position: a * (1.0 - s) + b * (s * (1.0 - v)) + c * (s * v),
            normal: (b - a).cross(c - a).normalize(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two triangles of areas 1 and 3 side by side: a quarter of the points land on the first,
    /// and points spread evenly within each (their mean is the triangle's centroid), each with
    /// its triangle's winding normal.
    #[test]
    fn points_fall_uniformly_by_area() {
        // Triangle 0: (0,0,0) (1,0,0) (0,2,0), area 1, normal +z; triangle 1: (2,0,0) (2,3,0)
        // (4,0,0), area 3, normal −z.
        let vertices = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 2.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 3.0, 0.0],
            [4.0, 0.0, 0.0],
        ];
        let mesh = TriangleMesh::new(vertices, vec![[0, 1, 2], [3, 4, 5]], None, None).unwrap();
        let surface = SampledMesh::new(Arc::new(mesh)).unwrap();
        assert_eq!(surface.area(), 4.0);
        let n = 400;
        let (mut first, mut sums) = (0, [DVec3::ZERO; 2]);
        for i in 0..n {
            for j in 0..n {
                let uv = ((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
                let p = surface.sample(uv);
                let k = usize::from(p.position.x >= 2.0);
                first += usize::from(k == 0);
                sums[k] += p.position;
                let want = [DVec3::Z, -DVec3::Z][k];
                assert_eq!(p.normal, want, "{uv:?}");
            }
        }
        // A midpoint grid: the share is exact to one row of the grid (1/n).
        let share = first as f64 / (n * n) as f64;
        assert!((share - 0.25).abs() <= 1.0 / n as f64, "{share}");
        // The grid's means: the centroids to the grid's resolution.
        let centroid = [
            DVec3::new(1.0, 2.0, 0.0) / 3.0,
            DVec3::new(8.0, 3.0, 0.0) / 3.0,
        ];
        for k in 0..2 {
            let count = [first, n * n - first][k] as f64;
            let mean = sums[k] / count;
            assert!(
                (mean - centroid[k]).length() < 4.0 / n as f64,
                "{k}: {mean}"
            );
        }
    }
}
