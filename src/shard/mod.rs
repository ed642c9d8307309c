//! Scaling out: a render as independent slices of work, each kept as an exact
//! partial result, merged into the result one run would have produced.
//!
//! A render's work is its passes (pass p draws from streams keyed by p) and its receiver
//! photons (photon i from streams keyed by i). A [`Shard`] K/N takes the K-th of N contiguous
//! slices of both. Its [`Partial`] keeps sums, never means — the film's fixed-point sums, the
//! receivers' exact tallies, the energy ledger — with which passes and photons it holds, and a
//! [`Header`] saying what it is a part of (the program, the scene and its inputs' contents,
//! every setting that shapes the result). Partials of the same header merge by adding
//! ([`Merge`]), exactly and in any order, so N shards merged are bit for bit the
//! single run. [`run`] does a partial's remaining work, saving it as it goes (a checkpoint
//! that `--resume` continues).
//!
//! grinlight provides the shard and the merge, not a scheduler: a cluster's own (a Slurm job
//! array, a Ray driver; `cluster/` in the repository) runs the shards.

mod coverage;
pub mod file;
mod merge;
mod run;

pub use coverage::Coverage;
pub use merge::Merge;
pub use run::{run, Ran, Saving, BLOCK};

use crate::error::{Error, Result};
use crate::film::Film;
use crate::render::Books;
use crate::scene::Scene;
use crate::settings::{IntegratorKind, PhotonSettings, SamplerKind, Settings, TraceSettings};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The K-th of N slices of a render's work (1 ≤ K ≤ N).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    /// K, from 1.
    pub index: u32,
    /// N.
    pub count: u32,
}

impl Shard {
    /// All the work: 1/1.
    pub const WHOLE: Shard = Shard { index: 1, count: 1 };

    /// Parses "K/N" (as a command line writes it), naming what is wrong.
    pub fn parse(text: &str) -> Result<Shard> {
        let bad = |why: &str| Error::Usage(format!("--shard {text}: {why} (write K/N, 1 ≤ K ≤ N)"));
        let (k, n) = text.split_once('/').ok_or_else(|| bad("no '/'"))?;
        let number = |s: &str| {
            let s = s.trim();
            s.parse::<u32>().map_err(|_| match s.parse::<u128>() {
                Ok(_) => bad(&format!("{s} is more than {} shards", u32::MAX)),
                Err(_) => bad(&format!("`{s}` is not a whole number")),
            })
        };
        let (index, count) = (number(k)?, number(n)?);
        if index == 0 || index > count {
            return Err(bad("K out of range"));
        }
        Ok(Shard { index, count })
    }

    /// This shard's slice of `0..total`: [⌊(K−1)·total/N⌋, ⌊K·total/N⌋), so the N slices
    /// tile it and differ in size by at most one.
    pub fn slice(&self, total: u64) -> std::ops::Range<u64> {
        let at = |k: u32| (total as u128 * k as u128 / self.count as u128) as u64;
        at(self.index - 1)..at(self.index)
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// What a partial file is for, and so who may replace or remove it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Role {
    /// A shard's result (`render --shard`), for `grinlight merge`: a render resumes or keeps
    /// it, never replaces or removes it.
    Shard,
    /// A whole render's saved state beside its EXR, for `--resume`: the render that owns it
    /// replaces it as it goes and removes it when it finishes.
    Checkpoint,
}

/// The settings that shape a render's result, as its partials record them: two partials
/// merge only where these are equal.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Shaping {
    /// Seed of every random stream.
    pub seed: u64,
    /// Camera samples per pixel per pass.
    pub spp: u32,
    /// The integrator.
    pub integrator: IntegratorKind,
    /// Where camera samples' numbers come from.
    pub sampler: SamplerKind,
    /// Whether a deflection table may stand in for traced camera rays.
    pub deflection_table: bool,
    /// How rays travel.
    pub trace: TraceSettings,
    /// The photon maps.
    pub photons: PhotonSettings,
    /// The rendered image's (the camera's window's) width and height (None: no camera).
    pub image: Option<[u32; 2]>,
}

impl Shaping {
    /// The first setting in which `other` differs: its name and both values, in words.
    pub fn difference(&self, other: &Shaping) -> Option<(&'static str, String, String)> {
        fn differ<T: PartialEq + std::fmt::Debug>(
            name: &'static str,
            a: &T,
            b: &T,
        ) -> Option<(&'static str, String, String)> {
            (a != b).then(|| (name, format!("{a:?}"), format!("{b:?}")))
        }
        differ("seed", &self.seed, &other.seed)
            .or_else(|| differ("spp", &self.spp, &other.spp))
            .or_else(|| differ("integrator", &self.integrator, &other.integrator))
            .or_else(|| differ("sampler", &self.sampler, &other.sampler))
            .or_else(|| {
                differ(
                    "deflection_table",
                    &self.deflection_table,
                    &other.deflection_table,
                )
            })
            .or_else(|| differ("trace", &self.trace, &other.trace))
            .or_else(|| differ("photons", &self.photons, &other.photons))
            .or_else(|| differ("image", &self.image, &other.image))
    }
}

/// What a partial result is a part of. Two partials merge only when their headers agree in
/// everything but the shard's index (and role).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Header {
    /// The program and version that rendered it.
    pub program: String,
    /// A shard's result or a whole render's saved state.
    pub role: Role,
    /// The scene file, absolute.
    pub scene: PathBuf,
    /// FNV-1a hash of the contents of the scene file and every file it reads, in order.
    pub inputs: u64,
    /// Every setting that shapes the result.
    pub settings: Shaping,
    /// Which slice.
    pub shard: Shard,
    /// Passes of the whole render (0: no camera).
    pub passes: u32,
    /// Receiver photons of the whole render (0: no receivers).
    pub photons: u64,
}

impl Header {
    /// The header of shard `shard` of the render of `scene` with `settings`, in `role`: reads
    /// the scene's input files to hash them.
    pub fn new(scene: &Scene, settings: &Settings, shard: Shard, role: Role) -> Result<Header> {
        let camera = scene.camera.as_ref();
        Ok(Header {
            program: format!("grinlight {}", env!("CARGO_PKG_VERSION")),
            role,
            scene: std::path::absolute(scene.path()).map_err(|e| Error::io(scene.path(), e))?,
            inputs: hash_files(&scene.inputs)?,
            settings: Shaping {
                seed: settings.seed,
                spp: settings.spp,
                sampler: settings.sampler,
                integrator: settings.integrator,
                deflection_table: settings.deflection_table,
                trace: settings.trace,
                photons: settings.photons,
                image: camera.map(|c| [c.window().width, c.window().height]),
            },
            shard,
            passes: if camera.is_some() { settings.passes } else { 0 },
            photons: if scene.receivers.is_empty() {
                0
            } else {
                settings.receiver_photons
            },
        })
    }

    /// The first way `other` differs from this header apart from the shard's index, said in
    /// words; None when they agree.
    pub fn difference(&self, other: &Header) -> Option<String> {
        let differ = |what: &str, a: &dyn std::fmt::Debug, b: &dyn std::fmt::Debug| {
            Some(format!("{what}: {a:?} against {b:?}"))
        };
        if self.program != other.program {
            return differ("program", &self.program, &other.program);
        }
        // The scene is its contents (the render's directory may have moved or been copied).
        if self.inputs != other.inputs {
            return Some(
                "the scene's files (the scene or a file it reads) changed between them".into(),
            );
        }
        if let Some((name, a, b)) = self.settings.difference(&other.settings) {
            return Some(format!("{name}: {a} against {b}"));
        }
        if self.shard.count != other.shard.count {
            return differ("shard count", &self.shard.count, &other.shard.count);
        }
        if self.passes != other.passes {
            let passes = |p: u32| match p {
                u32::MAX => "as many as it takes (a time_budget or target_error)".to_string(),
                p => p.to_string(),
            };
            return Some(format!(
                "passes: {} against {} — give the passes, time_budget or target_error it was \
                 started with",
                passes(self.passes),
                passes(other.passes)
            ));
        }
        if self.photons != other.photons {
            return differ("receiver photons", &self.photons, &other.photons);
        }
        None
    }
}

/// FNV-1a (64-bit) over the files' contents, each followed by its length.
fn hash_files(paths: &[PathBuf]) -> Result<u64> {
    let mut h = file::FNV_START;
    for p in paths {
        let bytes = std::fs::read(p).map_err(|e| Error::io(p, e))?;
        h = file::fnv1a(h, &bytes);
        h = file::fnv1a(h, &(bytes.len() as u64).to_le_bytes());
    }
    Ok(h)
}

/// A partial result: what a slice of a render's work added up to, in sums.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Partial {
    /// What it is a part of.
    pub header: Header,
    /// The passes its film holds.
    pub passes: Coverage,
    /// The film of those passes (None: none yet, or no camera).
    pub film: Option<Film>,
    /// The receiver photons its books hold.
    pub photons: Coverage,
    /// The receivers' books of those photons.
    pub books: Books,
}

impl Partial {
    /// A partial holding nothing yet.
    pub fn empty(header: Header) -> Partial {
        Partial {
            header,
            passes: Coverage::default(),
            film: None,
            photons: Coverage::default(),
            books: Books::default(),
        }
    }

    /// The work of its shard this partial does not hold yet: (passes, receiver photons).
    pub fn remaining(&self) -> (Coverage, Coverage) {
        let shard = self.header.shard;
        (
            self.passes.missing(shard.slice(self.header.passes as u64)),
            self.photons.missing(shard.slice(self.header.photons)),
        )
    }

    /// Whether it holds all of its shard's work.
    pub fn is_complete(&self) -> bool {
        let (p, r) = self.remaining();
        p.is_empty() && r.is_empty()
    }

    /// Adds the film of `passes` (none of which it holds).
    pub fn add_passes(&mut self, passes: std::ops::Range<u64>, film: Film) -> Result<()> {
        self.passes.insert(passes)?;
        match &mut self.film {
            Some(f) => f.merge(&film),
            None => {
                self.film = Some(film);
                Ok(())
            }
        }
    }

    /// Adds the books of receiver photons `photons` (none of which it holds).
    pub fn add_photons(&mut self, photons: std::ops::Range<u64>, books: &Books) -> Result<()> {
        self.photons.insert(photons)?;
        self.books.add(books);
        Ok(())
    }

    /// Whether it is whole and consistent: the shard within its count, the work it holds
    /// within its shard's slices, a film whose buffers match its size and the header's camera,
    /// receivers' books of the photons it holds. The reason when not.
    pub fn check(&self) -> std::result::Result<(), String> {
        let h = &self.header;
        if h.shard.index == 0 || h.shard.index > h.shard.count {
            return Err(format!("shard {} does not exist", h.shard));
        }
        let within = |c: &Coverage, total: u64, what: &str| {
            let slice = h.shard.slice(total);
            match c.is_within(slice.clone()) {
                true => Ok(()),
                false => Err(format!(
                    "its {what} {c} are not a part of its shard's {}..{}",
                    slice.start, slice.end
                )),
            }
        };
        within(&self.passes, h.passes as u64, "passes")?;
        within(&self.photons, h.photons, "receiver photons")?;
        if self.books.traced != self.photons.len() {
            return Err(format!(
                "books of {} photons for {} receiver photons",
                self.books.traced,
                self.photons.len()
            ));
        }
        if let Some(film) = &self.film {
            film.check()?;
            let image = h.settings.image.map(|[w, h]| [w as usize, h as usize]);
            if image != Some([film.width, film.height]) {
                return Err(format!(
                    "a {}×{} film of another camera",
                    film.width, film.height
                ));
            }
        }
        Ok(())
    }

    /// Refuses it, as a damaged file at `path`, unless its books fit `scene` (a tally per
    /// receiver of its bins and bands, budget entries of its primitives and media).
    pub fn fits(&self, scene: &Scene, path: &Path) -> Result<()> {
        self.books
            .fits(
                &scene.receivers,
                scene.accel.primitives().len(),
                scene.medium_names().count(),
            )
            .map_err(|why| file::damaged(path, why))
    }

    /// Reads a partial file: its header and payload checked (see [`file`]), and the result
    /// ([`Partial::check`]); every error names the file.
    pub fn read(path: &Path) -> Result<Partial> {
        file::Opened::open(path)?.payload()
    }

    /// Writes it to `path` atomically.
    pub fn write(&self, path: &Path) -> Result<()> {
        let bytes = file::encode(self).map_err(|e| Error::Image {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        crate::output::write_atomic(path, |tmp| {
            std::fs::write(tmp, &bytes).map_err(|e| Error::io(path, e))
        })
    }
}
