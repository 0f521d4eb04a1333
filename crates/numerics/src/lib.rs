//! asperity-numerics: the rough-surface numerics of asperity, as plain functions and types on
//! arrays (no YAML, cache, tables or command line):
//! * [`surface`] — height maps, topography readers, ISO 25178 statistics, spectra, synthetic
//!   surfaces and twins, summits;
//! * [`contact`] — elastic–perfectly-plastic FFT boundary-element contact;
//! * [`friction`] — Kogut–Etsion, full-stick and per-summit / per-spot static friction;
//! * [`materials`] — the body and pair material description and the built-in materials;
//! * [`fft2`] — the real-to-complex 2-D FFT they share.
//!
//! See `ARCHITECTURE.md` at the repository root for the code map and invariants.

#![deny(unsafe_code)]

pub mod contact;
pub mod fft2;
pub mod friction;
pub mod materials;
pub mod surface;
