//! Merging the partials of one render: every partial's header is checked first (read alone,
//! before any payload), then each partial is read, added and dropped, so a merge refuses a
//! mismatch before it reads the sums and holds one merged result and one partial whatever the
//! number of shards.

use super::{Header, Partial, Shard};
use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

/// Partials of one render merged so far.
#[derive(Default)]
pub struct Merge {
    /// The first header admitted, and its file: what every other must agree with.
    first: Option<(PathBuf, Header)>,
    /// Each shard admitted, with its file and header.
    admitted: Vec<(PathBuf, Header)>,
    /// The merged result (None: nothing added yet).
    merged: Option<Partial>,
}

impl Merge {
    /// Nothing merged yet.
    pub fn new() -> Merge {
        Merge::default()
    }

    /// Admits the partial at `path` with `header` (its file's header, read alone): refused
    /// (naming both files and the difference) if it is of another scene, other inputs, other
    /// settings, another shard count or program, or a shard already admitted.
    pub fn admit(&mut self, path: &Path, header: &Header) -> Result<()> {
        if let Some((first_path, first)) = &self.first {
            if let Some(d) = first.difference(header) {
                return Err(Error::Usage(format!(
                    "{} and {} are not parts of one render: {d}",
                    first_path.display(),
                    path.display()
                )));
            }
        }
        let shard = header.shard;
        if let Some((other, _)) = self
            .admitted
            .iter()
            .find(|(_, h)| h.shard.index == shard.index)
        {
            return Err(Error::Usage(format!(
                "{} and {} are both shard {shard}: each shard once",
                other.display(),
                path.display(),
            )));
        }
        self.first
            .get_or_insert_with(|| (path.to_path_buf(), header.clone()));
        self.admitted.push((path.to_path_buf(), header.clone()));
        Ok(())
    }

    /// Adds `part`, read from `path` after it was admitted with the same header: refused when
    /// it holds work already added.
    pub fn add(&mut self, path: &Path, part: Partial) -> Result<()> {
        if !self
            .admitted
            .iter()
            .any(|(p, h)| p == path && *h == part.header)
        {
            return Err(Error::Usage(format!(
                "{}: changed while it was being merged",
                path.display()
            )));
        }
        let Some(merged) = &mut self.merged else {
            self.merged = Some(Partial {
                header: Header {
                    shard: Shard::WHOLE,
                    ..part.header.clone()
                },
                ..part
            });
            return Ok(());
        };
        let shard = part.header.shard;
        let overlap = |what: &str| {
            Error::Usage(format!(
                "{}: its {what} overlap another partial's (shard {shard}): each piece of work once",
                path.display(),
            ))
        };
        for r in part.passes.ranges() {
            merged
                .passes
                .insert(r.clone())
                .map_err(|_| overlap("passes"))?;
        }
        for r in part.photons.ranges() {
            merged
                .photons
                .insert(r.clone())
                .map_err(|_| overlap("receiver photons"))?;
        }
        match (&mut merged.film, part.film) {
            (Some(f), Some(film)) => f.merge(&film)?,
            (f @ None, film) => *f = film,
            (Some(_), None) => {}
        }
        merged.books.add(&part.books);
        Ok(())
    }

    /// The merged result; unless `allow_missing`, refused when it lacks any of the render's
    /// passes or receiver photons.
    pub fn finish(self, allow_missing: bool) -> Result<Partial> {
        let (Some(merged), Some((_, first))) = (self.merged, self.first) else {
            return Err(Error::Usage(
                "nothing to merge: name the partial files".into(),
            ));
        };
        let (passes, photons) = merged.remaining();
        if allow_missing || (passes.is_empty() && photons.is_empty()) {
            return Ok(merged);
        }
        let mut lacks = Vec::new();
        if !passes.is_empty() {
            lacks.push(format!("passes {passes} of {}", merged.header.passes));
        }
        if !photons.is_empty() {
            lacks.push(format!(
                "receiver photons {photons} of {}",
                merged.header.photons
            ));
        }
        Err(Error::Usage(format!(
            "the partials lack {} (of {} shards, {} given): render the missing shards, or \
             merge with --allow-missing for an estimate from what is there",
            lacks.join(" and "),
            first.shard.count,
            self.admitted.len()
        )))
    }
}
