//! The curved-segment engine shared by every pass: the exact arc
//! ([`CurvedSegment`]), the steppers, step control and the march with its termination reasons;
//! and the rays of the constant-curvature media in closed form ([`GeodesicRay`]: the
//! transformation method where it is exact).

mod bounds;
mod hermite;
mod linearize;
mod march;
mod segment;
mod state;
mod stepper;

pub use bounds::Bounds;
pub use hermite::{HermitePath, Path};
pub use linearize::{
    CircleArc, CircleCrossings, GeodesicPoint, GeodesicRay, Hyperplane, RoundSurface, FAR,
};
pub use march::{
    march, march_replay, march_replay_with, march_with, round_off_floor, MarchLimits, MarchOutcome,
    StepControl, Termination,
};
pub use segment::{accurate_cross, ArcHull, ArcPoint, CurvedSegment};
pub use state::RayState;
pub use stepper::{
    ArcChain, ArcPath, EstimatedStep, ExactPath, Linearize, Rk4Sharma, Rkn64, RknTableau,
    SnellSteps, Step, Stepper, StepperKind, RKN64,
};
