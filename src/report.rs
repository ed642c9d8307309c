//! What a render or a measurement did: passes, counts and timings, and whether it was cut
//! short.

use crate::transport::Stats;

/// Photons stored in each photon map.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stored {
    /// In the caustic map.
    pub caustic: u64,
    /// In the global map.
    pub global: u64,
    /// In the volume caustic map.
    pub volume: u64,
}

/// Seconds a render spent, by stage.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Seconds {
    /// Tracing photons (the maps' or the receivers').
    pub photons: f64,
    /// Building the photon maps (kd-trees and the global map's precomputed irradiance).
    pub maps: f64,
    /// The camera pass (which includes the photon queries).
    pub camera: f64,
}

impl Seconds {
    /// All of it.
    pub fn total(&self) -> f64 {
        self.photons + self.maps + self.camera
    }
}

/// Timings and photon counts of a render.
#[derive(Clone, Debug, Default)]
pub struct Report {
    /// Passes run.
    pub passes: u32,
    /// Transport counts, summed over both passes of every pass.
    pub stats: Stats,
    /// Photons stored in the maps, summed over passes.
    pub stored: Stored,
    /// Where the time went.
    pub seconds: Seconds,
    /// Set when the render was stopped before its end (see [`crate::render::Observer::stop_requested`]):
    /// what it holds.
    pub partial: Option<String>,
    /// Lines an integrator adds about how it worked (e.g. a deflection table's size, build
    /// time and checked error).
    pub notes: Vec<String>,
}

impl Report {
    /// A multi-line summary.
    pub fn summary(&self) -> String {
        let Seconds {
            photons: trace,
            maps: build,
            camera,
        } = self.seconds;
        let rate = if trace > 0.0 {
            self.stats.photons_emitted as f64 / trace
        } else {
            0.0
        };
        let partial = self
            .partial
            .as_ref()
            .map_or(String::new(), |p| format!("PARTIAL (interrupted): {p}\n"));
        let notes: String = self.notes.iter().map(|n| format!("{n}\n")).collect();
        let volume = match self.stored.volume {
            0 => String::new(),
            n => format!(", volume caustic map {n} stored"),
        };
        format!(
            "{partial}{notes}{} pass(es); photons: {} emitted ({rate:.0}/s), caustic map {} stored, global map {} stored{volume}; \
             photon tracing {trace:.2} s, map build {build:.3} s, camera pass {camera:.2} s\n{}",
            self.passes,
            self.stats.photons_emitted,
            self.stored.caustic,
            self.stored.global,
            self.stats.summary()
        )
    }
}
