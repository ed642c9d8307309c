//! OpenVDB volumes for `grid` media: one scalar grid of a `.vdb` file (read with vdb-rs, the
//! pure-format reader; Blosc and zip compression), densified over its active voxels' bounding
//! box. Voxel (i, j, k) lies at the grid's transform of (i, j, k) — OpenVDB's voxel-centred
//! convention — so the box's nodes are the voxels themselves and no value is resampled.
//!
//! The reader is guarded: it may panic on files it does not support (other transforms than
//! scale and translate, multi-buffer trees) and those panics become errors naming the file.
//! It does not read a grid's background value, so the inactive voxels inside the box take the
//! scene's `background`, and a grid that has some needs one.

use glam::{DVec3, I64Vec3, IVec3};
use std::fs::File;
use std::io::BufReader;
use std::path::Path;
use vdb_rs::{Grid, Map, Node3, Node4, Node5, VdbReader};

/// A VDB grid densified: node (i, j, k) of `dims` at `min` + (i, j, k)·(max − min)/(dims − 1),
/// values x fastest.
#[derive(Clone, Debug, PartialEq)]
pub struct Dense {
    /// The first voxel's world position.
    pub min: DVec3,
    /// The last voxel's world position.
    pub max: DVec3,
    /// Voxels along each axis.
    pub dims: [usize; 3],
    /// Values, x fastest.
    pub values: Vec<f64>,
}

/// The most voxels a densified grid may hold (4 GiB of f64).
const MAX_VOXELS: u64 = 1 << 29;

/// A box of more voxels than this is made dense only where its active voxels fill at least
/// 1 % of it (two voxels 800 apart made a 3.9 GB grid of background).
const SPARSE_BOX: u64 = 1 << 24;

/// Reads grid `name` (None: the file's only scalar grid) of the VDB file at `path`, its
/// inactive voxels inside the active box taking `background`. Errors say what is wrong, not
/// where (the caller names the file and the scene key).
pub fn read(path: &Path, name: Option<&str>, background: Option<f64>) -> Result<Dense, String> {
    let file = File::open(path).map_err(|e| format!("cannot read: {e}"))?;
    guarded(|| {
        let mut reader =
            VdbReader::new(BufReader::new(file)).map_err(|e| format!("not a VDB file: {e:?}"))?;
        let mut grids: Vec<(String, String)> = reader
            .grid_descriptors
            .iter()
            .map(|(n, d)| (n.clone(), d.grid_type.clone()))
            .collect();
        grids.sort();
        let scalar =
            |t: &str| t.starts_with("Tree_float_5_4_3") || t.starts_with("Tree_double_5_4_3");
        let listing = || {
            grids
                .iter()
                .map(|(n, t)| format!("'{n}' ({t})"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let (name, kind) = match name {
            Some(n) => grids
                .iter()
                .find(|(g, _)| g == n)
                .cloned()
                .ok_or_else(|| format!("has no grid '{n}' (it has {})", listing()))?,
            None => {
                let mut found = grids.iter().filter(|(_, t)| scalar(t));
                match (found.next(), found.next()) {
                    (Some(g), None) => g.clone(),
                    _ => {
                        return Err(format!(
                            "name the grid to read with `grid` (it has {})",
                            listing()
                        ))
                    }
                }
            }
        };
        if !scalar(&kind) {
            return Err(format!(
                "grid '{name}' is a {kind}: a grid medium reads a scalar (float or double) grid"
            ));
        }
        let read_err = |e| format!("grid '{name}' cannot be read: {e:?}");
        if kind.starts_with("Tree_double") {
            densify(
                &reader.read_grid::<f64>(&name).map_err(read_err)?,
                background,
                |v| v,
            )
        } else {
            densify(
                &reader.read_grid::<f32>(&name).map_err(read_err)?,
                background,
                |v| v as f64,
            )
        }
        .map_err(|e| format!("grid '{name}': {e}"))
    })
}

/// Runs `f`, turning a panic of the VDB reader into an error (without its message on the
/// terminal). The panic hook is process-wide: reads are serialised, so that two at once cannot
/// leave the silent hook in place of the previous one.
fn guarded<T>(f: impl FnOnce() -> Result<T, String> + std::panic::UnwindSafe) -> Result<T, String> {
    static HOOK: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let _one_at_a_time = HOOK.lock().unwrap_or_else(|e| e.into_inner());
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let result = std::panic::catch_unwind(f);
    std::panic::set_hook(hook);
    result.unwrap_or_else(|p| {
        let why = p
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default();
        Err(format!("a VDB file this reader does not support ({why})"))
    })
}

/// The grid's active voxels' bounding box, densified.
fn densify<T: Copy>(
    grid: &Grid<T>,
    background: Option<f64>,
    value: impl Fn(T) -> f64,
) -> Result<Dense, String> {
    // (vdb-rs speaks an older glam: its vectors cross over as arrays.)
    let (translation, voxel) = match &grid.transform {
        Map::UniformScaleMap { voxel_size, .. } => (DVec3::ZERO, voxel_size.to_array()),
        Map::ScaleTranslateMap {
            translation,
            voxel_size,
            ..
        } => (
            DVec3::from_array(translation.to_array()),
            voxel_size.to_array(),
        ),
    };
    let voxel = DVec3::from_array(voxel);
    // The active box: voxels, and tiles of 8³ or 128³ voxels.
    // In 64 bits: a voxel's coordinates may lie near ±2³¹, where their box overflows i32.
    let (mut lo, mut hi) = (I64Vec3::MAX, I64Vec3::MIN);
    let mut active = 0u64;
    for (at, _, level) in grid.iter() {
        let at = I64Vec3::from_array(at.as_ivec3().to_array().map(i64::from));
        let size = level.scale() as i64;
        lo = lo.min(at);
        hi = hi.max(at + I64Vec3::splat(size - 1));
        active = active.saturating_add((size * size * size) as u64);
    }
    if lo.cmpgt(hi).any() {
        return Err("has no active voxel".into());
    }
    let extent = hi - lo + I64Vec3::ONE;
    if extent.cmplt(I64Vec3::splat(2)).any() {
        return Err(format!(
            "its active voxels span {extent} voxels: a grid medium needs at least 2 along every axis"
        ));
    }
    let count = extent
        .to_array()
        .iter()
        .try_fold(1u64, |a, &d| a.checked_mul(d as u64))
        .unwrap_or(u64::MAX);
    if count > MAX_VOXELS {
        return Err(format!(
            "its active box, from voxel {lo} to {hi}, holds {count} voxels, more than the \
             {MAX_VOXELS} a grid medium takes (a grid whose few voxels lie far apart is mostly \
             background: crop it)"
        ));
    }
    if count > SPARSE_BOX && active.saturating_mul(100) < count {
        return Err(format!(
            "its {active} active voxels fill {:.2} % of their box, from voxel {lo} to {hi}, of \
             {count} voxels, which a grid medium holds whole ({} of memory, mostly background): \
             crop the grid to where its voxels are",
            100.0 * active as f64 / count as f64,
            crate::resources::human(count.saturating_mul(8))
        ));
    }
    // The dense values, and as much again for the medium built from them: refused at once
    // where the machine has not the room.
    crate::resources::check_memory(
        count.saturating_mul(3 * 8),
        &format!("the VDB grid's active box of {count} voxels, made dense"),
    )
    .map_err(|e| e.to_string())?;
    let reach = I64Vec3::splat(i64::from(i32::MAX));
    if hi.cmpgt(reach).any() || lo.cmplt(-reach).any() {
        return Err(format!(
            "its active box, from voxel {lo} to {hi}, reaches beyond voxel ±2³¹"
        ));
    }
    let (lo, hi) = (lo.as_ivec3(), hi.as_ivec3());
    let mut values = Vec::with_capacity(count as usize);
    let mut missing = 0u64;
    for k in lo.z..=hi.z {
        for j in lo.y..=hi.y {
            for i in lo.x..=hi.x {
                match (lookup(grid, IVec3::new(i, j, k)), background) {
                    (Some(v), _) => values.push(value(v)),
                    (None, Some(b)) => values.push(b),
                    (None, None) => {
                        missing += 1;
                        values.push(f64::NAN);
                    }
                }
            }
        }
    }
    if missing > 0 {
        return Err(format!(
            "{missing} of the {count} voxels in its active box are inactive: give `background`, \
             the value there (the VDB reader does not read the grid's own)"
        ));
    }
    let world = |c: IVec3| translation + voxel * c.as_dvec3();
    Ok(Dense {
        min: world(lo),
        max: world(hi),
        dims: extent.to_array().map(|d| d as usize),
        values,
    })
}

/// The value of voxel `c` where it is active (a voxel or a tile of the tree), None where it is
/// inactive or outside the tree.
fn lookup<T: Copy>(grid: &Grid<T>, c: IVec3) -> Option<T> {
    let inside = |origin: IVec3, size: i32| {
        let d = c - origin;
        d.cmpge(IVec3::ZERO).all() && d.cmplt(IVec3::splat(size)).all()
    };
    // Offset of `c` in a node at `origin` of 2^log2 children each 2^child voxels wide, x slowest.
    let offset = |origin: IVec3, log2: u32, child: u32| {
        let d = (c - origin).as_uvec3() >> child;
        ((d.x << (2 * log2)) + (d.y << log2) + d.z) as usize
    };
    let n5: &Node5<T> = grid
        .tree
        .root_nodes
        .iter()
        .find(|n| inside(IVec3::from_array(n.origin.to_array()), 4096))?;
    let i5 = offset(IVec3::from_array(n5.origin.to_array()), 5, 7);
    if !n5.child_mask[i5] {
        return n5.value_mask[i5].then(|| n5.data[i5]);
    }
    let n4: &Node4<T> = n5.nodes.get(&(i5 as u32))?;
    let i4 = offset(IVec3::from_array(n4.origin.to_array()), 4, 3);
    if !n4.child_mask[i4] {
        return n4.value_mask[i4].then(|| n4.data[i4]);
    }
    let n3: &Node3<T> = n4.nodes.get(&(i4 as u32))?;
    let i3 = offset(IVec3::from_array(n3.origin.to_array()), 3, 0);
    n3.value_mask[i3].then(|| n3.buffer[i3])
}
