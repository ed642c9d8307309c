//! Merging the partials of one render, one at a time: each is checked against the first,
//! added and dropped, so a merge holds one merged result and one partial whatever the number
//! of shards.

use super::{Header, Partial, Shard};
use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

/// Partials of one render merged so far.
#[derive(Default)]
pub struct Merge {
    /// The merged result, and the first partial's file and header (what every other must
    /// agree with).
    merged: Option<(Partial, PathBuf, Header)>,
    /// Each shard index added, with its file.
    seen: Vec<(u32, PathBuf)>,
}

impl Merge {
    /// Nothing merged yet.
    pub fn new() -> Merge {
        Merge::default()
    }

    /// Adds the partial read from `path`: refused (naming both files and the difference) if it
    /// is of another scene, other inputs, other settings, another shard count or program, a
    /// shard already added, or work already added.
    pub fn add(&mut self, path: &Path, part: Partial) -> Result<()> {
        let Some((merged, first_path, first)) = &mut self.merged else {
            self.seen
                .push((part.header.shard.index, path.to_path_buf()));
            let header = part.header.clone();
            let whole = Partial {
                header: Header {
                    shard: Shard::WHOLE,
                    ..part.header.clone()
                },
                ..part
            };
            self.merged = Some((whole, path.to_path_buf(), header));
            return Ok(());
        };
        if let Some(d) = first.difference(&part.header) {
            return Err(Error::Usage(format!(
                "{} and {} are not parts of one render: {d}",
                first_path.display(),
                path.display()
            )));
        }
        let shard = part.header.shard;
        if let Some((_, other)) = self.seen.iter().find(|(k, _)| *k == shard.index) {
            return Err(Error::Usage(format!(
                "{} and {} are both shard {shard}: each shard once",
                other.display(),
                path.display(),
            )));
        }
        self.seen.push((shard.index, path.to_path_buf()));
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
        let Some((merged, _, first)) = self.merged else {
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
            self.seen.len()
        )))
    }
}
