//! The commands of the `grinlight` program as library calls: what a user can do from the
//! command line, a library user does with one call ([`render()`], [`merge()`], [`validate()`], [`trace()`]; [`render_in_memory()`] renders without files). Each takes a job (the scene file and the command line's choices) and an
//! [`Observer`] that is told of progress, shown the report line by line and asked whether to
//! stop; each checks every file it will write before any work (see [`crate::output`]) and
//! what it asks of the machine (see [`crate::resources`]).

mod convert;
mod merge;
mod render;
mod trace;
mod validate;

pub use convert::{convert, ConvertJob};
pub use merge::{merge, MergeJob};
pub use render::{
    render, render_in_memory, shard_partial, Overrides, RenderJob, RenderOutcome, Rendered,
};
pub use trace::{
    trace, trace_ray, FieldAtEnd, PathPoint, RayTrace, TraceControl, TraceJob, Traced,
};
pub use validate::{validate, ValidateJob};

pub use crate::render::{Observer, Progress};

pub(crate) use crate::error::positive;
