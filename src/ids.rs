//! The typed indices by which the parts of a built scene are known: a medium, a material, a
//! light, a receiver, a primitive. Each is its own type, so a light's index cannot be taken
//! for a material's, and `Option<MediumId>` means one thing everywhere: `None` is vacuum
//! (n = 1), never "the ambient medium", which the scene resolves once when it is built.

/// Declares an index type: a `usize` that only its own table reads.
macro_rules! index_type {
    ($(#[$doc:meta])* $name:ident) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub struct $name(usize);

        impl $name {
            /// The id of the `index`-th entry of its table.
            pub const fn new(index: usize) -> Self {
                Self(index)
            }

            /// Its position in its table.
            pub const fn index(self) -> usize {
                self.0
            }
        }
    };
}

index_type!(
    /// A medium of the scene (`scene::Media`): an index field with what it does to light's
    /// power.
    MediumId
);
index_type!(
    /// A material of the scene (`Scene::materials`).
    MaterialId
);
index_type!(
    /// A light of the scene (`Scene::lights`), the environment apart.
    LightId
);
index_type!(
    /// A receiver of the scene (`Scene::receivers`).
    ReceiverId
);
index_type!(
    /// A primitive of the scene's acceleration structure (`Accel::primitives`), and so of its
    /// surface (`Scene::surfaces`).
    PrimId
);
