//! # lambert-light
//!
//! The physics of a scene: radiometric quantities and solid angles
//! ([`radiometry`]), emitters ([`emitter`]), the receiver ([`receiver`]) and
//! the closed-form irradiance every emitter gives it ([`analytic`]), scenes
//! ([`scene`]) and the built-in scenes used by the suites and studies
//! ([`builtin`]). TOML scene files are behind the `scene-file` feature, so a
//! renderer that only needs emitters and closed forms pulls in no parser.

pub mod analytic;
pub mod builtin;
pub mod emitter;
pub mod radiometry;
pub mod receiver;
pub mod scene;

pub use emitter::{Emitter, EmitterError};
pub use receiver::Receiver;
pub use scene::Scene;
#[cfg(feature = "scene-file")]
pub use scene::SceneError;
