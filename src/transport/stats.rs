//! Render statistics, summed over tiles in a fixed order.

use crate::curve::Termination;

/// Counts of what the render did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Stats {
    /// Camera rays (samples).
    pub camera_rays: u64,
    /// Straight ray traversals.
    pub straight_rays: u64,
    /// Curved marches.
    pub curved_marches: u64,
    /// Accepted curved steps.
    pub curved_steps: u64,
    /// Curved march endings, by [`Termination`] (in `ENDS` order).
    pub ends: [u64; 6],
    /// Paths that ended at the depth limit.
    pub depth_limited: u64,
    /// What camera paths ended at the depth limit carried: their weight there (a camera
    /// sample's is 1 where it starts; the mean over channels), summed.
    pub camera_weight_cut: f64,
    /// The power map photons left their sources with (W, the mean over channels), summed.
    pub photon_power_emitted: f64,
    /// The power map photons ended at the depth limit carried there (W), summed.
    pub photon_power_cut: f64,
    /// Paths lost at a surface because a medium's index is undefined there (inside a medium's
    /// capture region: a black hole's horizon, the hyperbolic medium's rim).
    pub undefined_index: u64,
    /// Paths lost inside a crystal at a surface that is none of its faces (a diffuse surface
    /// or a light in it), or that set off inside one: what such a vertex reads of the light
    /// is not defined for a crystal's two waves.
    pub lost_in_crystal: u64,
    /// Photons emitted.
    pub photons_emitted: u64,
    /// Gather rays of the final gather.
    pub gather_rays: u64,
    /// Photon-map queries of the camera pass (caustic radius and estimate, gather lookups).
    pub photon_queries: u64,
    /// The queries among them that were timed: one in [`TIMED_QUERY_EVERY`].
    pub timed_queries: u64,
    /// CPU time spent in the timed queries, ns (summed over threads).
    pub query_nanos: u64,
    /// Curved connections to lights solved (see [`super::connect`]), and those that failed
    /// (no converged direction: the light is not reached from there, or the solver gave up).
    pub connections: (u64, u64),
}

const ENDS: [Termination; 6] = [
    Termination::LengthReached,
    Termination::LeftBounds,
    Termination::Captured,
    Termination::StepUnderflow,
    Termination::MaxSteps,
    Termination::Stopped,
];

/// Photon-map queries are timed one in this many: reading the clock twice costs about a tenth
/// of a query (a Cornell caustic's camera pass spent 4 % of its time in the clock when every
/// query was timed), and the mean of a sample of queries is what the report prints.
pub const TIMED_QUERY_EVERY: u64 = 32;

impl Stats {
    /// Runs a photon-map query, counting it, and timing it if it is the first of a run of
    /// [`TIMED_QUERY_EVERY`] (so that a render of a few queries has one timed: it would
    /// report 0 µs each).
    pub fn time_query<T>(&mut self, query: impl FnOnce() -> T) -> T {
        let timed = self.photon_queries.is_multiple_of(TIMED_QUERY_EVERY);
        self.photon_queries += 1;
        if !timed {
            return query();
        }
        let t = std::time::Instant::now();
        let out = query();
        self.query_nanos += t.elapsed().as_nanos() as u64;
        self.timed_queries += 1;
        out
    }

    /// Counts one march ending.
    pub fn record_end(&mut self, reason: Termination) {
        if let Some(i) = ENDS.iter().position(|r| *r == reason) {
            self.ends[i] += 1;
        }
    }

    /// Adds another tile's counts.
    pub fn add(&mut self, o: &Stats) {
        self.camera_rays += o.camera_rays;
        self.straight_rays += o.straight_rays;
        self.curved_marches += o.curved_marches;
        self.curved_steps += o.curved_steps;
        self.depth_limited += o.depth_limited;
        self.camera_weight_cut += o.camera_weight_cut;
        self.photon_power_emitted += o.photon_power_emitted;
        self.photon_power_cut += o.photon_power_cut;
        self.undefined_index += o.undefined_index;
        self.lost_in_crystal += o.lost_in_crystal;
        self.photons_emitted += o.photons_emitted;
        self.gather_rays += o.gather_rays;
        self.photon_queries += o.photon_queries;
        self.timed_queries += o.timed_queries;
        self.query_nanos += o.query_nanos;
        self.connections.0 += o.connections.0;
        self.connections.1 += o.connections.1;
        for (a, b) in self.ends.iter_mut().zip(o.ends) {
            *a += b;
        }
    }

    /// What paths ended at the depth limit took away, where it is more than a thousandth: of
    /// the camera paths' weight (the light they would have gathered on, as a share of what
    /// they gathered if the light they found beyond is like the rest), and of the map photons'
    /// power; None where the cut took less.
    pub fn cut_warning(&self, max_depth: u32) -> Option<String> {
        let camera = self.camera_weight_cut / self.camera_rays.max(1) as f64;
        let photons = self.photon_power_cut / self.photon_power_emitted.max(f64::MIN_POSITIVE);
        let mut parts = Vec::new();
        if camera > 1e-3 {
            parts.push(format!(
                "{:.2} % of the camera paths' weight",
                100.0 * camera
            ));
        }
        if photons > 1e-3 {
            parts.push(format!("{:.2} % of the photons' power", 100.0 * photons));
        }
        (!parts.is_empty()).then(|| {
            format!(
                "paths cut at max_depth {max_depth} carried {}: the image is that much too dark \
                 where they went; raise [render] max_depth (or leave it out: paths then end \
                 by Russian roulette)",
                parts.join(" and ")
            )
        })
    }

    /// A multi-line summary.
    pub fn summary(&self) -> String {
        let ends: Vec<String> = ENDS
            .iter()
            .zip(self.ends)
            .filter(|(_, n)| *n > 0)
            .map(|(r, n)| {
                format!(
                    "{} {n}",
                    if *r == Termination::Stopped {
                        "surface hit"
                    } else {
                        r.name()
                    }
                )
            })
            .collect();
        let undefined = match self.undefined_index {
            0 => String::new(),
            n => format!(
                ", paths lost at a surface where a medium's index is undefined {n} (a shape \
                 reaching into a medium's capture region)"
            ),
        };
        let crystal = match self.lost_in_crystal {
            0 => String::new(),
            n => format!(
                ", paths lost in a crystal {n} (at a surface in it that is none of its faces, \
                 or setting off in it)"
            ),
        };
        let connections = match self.connections {
            (0, 0) => String::new(),
            (ok, failed) => format!(", curved light connections {ok} ({failed} unsolved)"),
        };
        format!(
            "camera rays {}, photons {}, gather rays {}, photon queries {} ({:.2} µs each), straight traversals {}, curved marches {} ({} steps; ends: {}), paths cut at max_depth {}{undefined}{crystal}{connections}",
            self.camera_rays,
            self.photons_emitted,
            self.gather_rays,
            self.photon_queries,
            self.query_nanos as f64 * 1e-3 / self.timed_queries.max(1) as f64,
            self.straight_rays,
            self.curved_marches,
            self.curved_steps,
            if ends.is_empty() { "none".into() } else { ends.join(", ") },
            self.depth_limited
        )
    }
}
