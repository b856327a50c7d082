//! The names a controller of your own needs, in one `use`:
//!
//! ```
//! use platbench::prelude::*;
//!
//! let registry = Registry::builtin();
//! assert!(registry.names().contains(&"sweep"));
//! let params = MotionParams::default();
//! assert!(params.validate().is_ok());
//! ```
//!
//! The controller API ([`Controller`], what it is built over, what it returns), the shared game
//! rules it may reuse ([`MotionParams`], [`MotionState`], [`Input`], [`Contacts`]), the level it
//! reads ([`Level`], [`Features`]) and the [`Registry`] that adds it beside the built-in
//! controllers; the command line is [`crate::cli::main_with`].

pub use crate::backend::{
    BackendError, Capabilities, CharacterId, CharacterSpec, CharacterState, DeclaredContact,
    Precision, ShownByDefault,
};
pub use crate::config::RunConfig;
pub use crate::controller::{Controller, Setup};
pub use crate::level::{Features, Level};
pub use crate::motion::{Contacts, Input, MotionParams, MotionState};
pub use crate::registry::Registry;
pub use crate::shape::CharacterShape;
