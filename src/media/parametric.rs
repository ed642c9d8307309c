//! The index profiles fixed by a few constants (an index n or n0, a fiber's shape constant, a
//! lens's or a black hole's centre and radius), as one value type: a dispersive medium is one
//! of these evaluated at a path's wavelength, made on the stack where the path needs it, never
//! allocated; a march is compiled for each ([`Parametric::apply`]).

use super::{
    BlackHole, ExactBlackHole, ExponentialMedium, FishEye, HyperbolicMedium, LinearMedium,
    Luneburg, Medium, ParabolicFiber, SechFiber, UniformMedium,
};

/// Work done with a medium as its own type, compiled for it (its samples inlined where the work
/// calls them), rather than through `dyn Medium`'s vtable: [`Parametric::apply`].
pub trait WithMedium {
    /// What the work gives.
    type Output;
    /// Does the work with `medium`.
    fn with<M: Medium + ?Sized>(self, medium: &M) -> Self::Output;
}

/// Declares [`Parametric`] with one variant per profile, and its views.
macro_rules! parametric {
    ($($(#[$doc:meta])* $variant:ident($profile:ty),)+) => {
        /// An index profile given by a formula and its constants.
        #[derive(Clone, Debug)]
        pub enum Parametric {
            $($(#[$doc])* $variant($profile),)+
        }

        impl Parametric {
            /// The profile as the index-field interface.
            pub fn as_medium(&self) -> &(dyn Medium + 'static) {
                match self {
                    $(Self::$variant(m) => m,)+
                }
            }

            /// Does `work` with the profile as its own type.
            pub fn apply<W: WithMedium>(&self, work: W) -> W::Output {
                match self {
                    $(Self::$variant(m) => work.with(m),)+
                }
            }
        }
    };
}

parametric! {
    /// n constant.
    Uniform(UniformMedium),
    /// n linear in position.
    Linear(LinearMedium),
    /// ln n linear in position.
    Exponential(ExponentialMedium),
    /// A parabolic GRIN rod.
    Parabolic(ParabolicFiber),
    /// A sech fiber.
    Sech(SechFiber),
    /// Maxwell's fish-eye.
    FishEye(FishEye),
    /// The Poincaré ball.
    Hyperbolic(HyperbolicMedium),
    /// The Luneburg lens.
    Luneburg(Luneburg),
    /// A Reissner–Nordström black hole's weak-field index.
    BlackHole(BlackHole),
    /// A Reissner–Nordström (or Schwarzschild) black hole as the exact index medium.
    ExactBlackHole(ExactBlackHole),
}
