//! Stage 1: surface statistics, spectra, summits, synthetic surfaces and twins.

#[path = "../common/mod.rs"]
mod common;
mod surface_amplitude;
mod surface_functional;
mod surface_power_law_band;
mod surface_spectral_statistics;
mod surface_spectral_synthetic;
mod surface_spectral_twins;
mod surface_spectrum_twins;
mod surface_summits;
