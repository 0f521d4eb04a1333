//! asperity: reproducible rough-surface contact and static-friction studies.
//!
//! Numerics (usable as a plain library, no YAML, cache or CLI):
//! * [`surface`] — height maps, topography readers, statistics, synthetic surfaces, summits;
//! * [`contact`] — elastic–perfectly-plastic FFT boundary-element contact;
//! * [`friction`] — Greenwood–Williamson / Kogut–Etsion static friction models.
//!
//! See `ARCHITECTURE.md` for the code map and invariants.

pub mod contact;
pub mod friction;
pub mod surface;
