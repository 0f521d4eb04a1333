//! asperity: reproducible rough-surface contact and static-friction studies.
//!
//! Numerics (usable as a plain library, no YAML, cache or CLI):
//! * [`surface`] — height maps, topography readers, statistics, synthetic surfaces, summits;
//! * [`contact`] — elastic–perfectly-plastic FFT boundary-element contact;
//! * [`friction`] — Greenwood–Williamson / Kogut–Etsion static friction models.
//!
//! Study engine (knows nothing of tribology beyond the node-kind trait): [`engine`].
//! Built-in material data: [`materials`]. Glue between the two: [`nodes`]. Quantities with units at the boundary: [`units`].
//!
//! See `ARCHITECTURE.md` for the code map and invariants.

pub mod contact;
pub mod engine;
pub mod fft2;
pub mod friction;
pub mod materials;
pub mod nodes;
pub mod report;
pub mod surface;
pub mod units;

/// The tool version recorded in cache manifests and Parquet metadata.
pub const TOOL_VERSION: &str = env!("CARGO_PKG_VERSION");
