//! Which pieces of a numbered list of work (passes, photons) a partial result holds.

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};
use std::ops::Range;

/// A set of indices as sorted, disjoint, non-adjacent ranges.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Coverage(Vec<Range<u64>>);

impl Coverage {
    /// The ranges, in order.
    pub fn ranges(&self) -> &[Range<u64>] {
        &self.0
    }

    /// Whether it holds nothing.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// How many indices it holds.
    pub fn len(&self) -> u64 {
        self.0.iter().map(|r| r.end - r.start).sum()
    }

    /// Whether it is well formed (sorted, non-empty, disjoint and non-adjacent ranges, as
    /// [`Coverage::insert`] keeps them) and holds only indices of `whole`.
    pub fn is_within(&self, whole: Range<u64>) -> bool {
        self.0.iter().all(|r| r.start < r.end)
            && self.0.windows(2).all(|w| w[0].end < w[1].start)
            && self
                .0
                .first()
                .zip(self.0.last())
                .is_none_or(|(a, b)| a.start >= whole.start && b.end <= whole.end)
    }

    /// Adds `r`; an error if any of it is already held (work done twice).
    pub fn insert(&mut self, r: Range<u64>) -> Result<()> {
        if r.is_empty() {
            return Ok(());
        }
        if self.0.iter().any(|h| h.start < r.end && r.start < h.end) {
            return Err(Error::Usage(format!(
                "{}..{} is already held (in {self})",
                r.start, r.end
            )));
        }
        let at = self.0.partition_point(|h| h.start < r.start);
        self.0.insert(at, r);
        // Join neighbours that touch.
        let mut joined: Vec<Range<u64>> = Vec::with_capacity(self.0.len());
        for h in self.0.drain(..) {
            match joined.last_mut() {
                Some(last) if last.end == h.start => last.end = h.end,
                _ => joined.push(h),
            }
        }
        self.0 = joined;
        Ok(())
    }

    /// The indices of `whole` it does not hold.
    pub fn missing(&self, whole: Range<u64>) -> Coverage {
        let mut out = Vec::new();
        let mut at = whole.start;
        for h in &self.0 {
            if h.start > at {
                out.push(at..h.start.min(whole.end));
            }
            at = at.max(h.end);
        }
        if at < whole.end {
            out.push(at..whole.end);
        }
        Coverage(out.into_iter().filter(|r| !r.is_empty()).collect())
    }
}

impl std::fmt::Display for Coverage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let parts: Vec<String> = self
            .0
            .iter()
            .map(|r| format!("{}..{}", r.start, r.end))
            .collect();
        match parts.is_empty() {
            true => write!(f, "none"),
            false => write!(f, "{}", parts.join(", ")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn joins_refuses_overlaps_and_names_the_gaps() {
        let mut c = Coverage::default();
        c.insert(10..20).unwrap();
        c.insert(0..5).unwrap();
        c.insert(5..10).unwrap();
        assert_eq!(c.to_string(), "0..20");
        assert!(c.insert(19..21).is_err());
        c.insert(30..40).unwrap();
        assert_eq!(c.len(), 30);
        assert_eq!(c.missing(0..50).ranges(), &[20..30, 40..50]);
        assert_eq!(c.missing(12..35).to_string(), "20..30");
        assert!(c.missing(0..20).is_empty());
        assert_eq!(c.to_string(), "0..20, 30..40");
    }
}
