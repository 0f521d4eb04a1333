//! asperity: reproducible rough-surface contact and static-friction studies — the application
//! that joins two library crates:
//! * [`asperity_numerics`] (re-exported as [`surface`], [`contact`], [`friction`], [`materials`],
//!   [`fft2`]) — the numerics, usable as a plain library without YAML, cache or CLI;
//! * [`asperity_engine`] (re-exported as [`engine`], with [`units`]) — the study engine, which
//!   knows nothing of tribology beyond the node-kind trait.
//!
//! This crate owns the node kinds that plug tribology into the engine ([`nodes`]) and the
//! report pages ([`report`]), and the steps of a study run every front end shares
//! ([`study_run`]); the `asperity` binary is the command line, the `python/` package another. See `ARCHITECTURE.md`
//! for the code map and invariants.

#![deny(unsafe_code)]

pub use asperity_engine as engine;
pub use asperity_engine::units;
pub use asperity_numerics::{contact, fft2, friction, materials, surface};

pub mod nodes;
pub mod report;
pub mod study_run;
pub mod vocabulary;

/// The tool version recorded in cache manifests and Parquet metadata.
pub const TOOL_VERSION: &str = env!("CARGO_PKG_VERSION");
