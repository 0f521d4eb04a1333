//! Spectral analysis of complete height maps (no missing points): PSD, autocorrelation, Sal/Str,
//! texture direction Std, Hurst exponent and spectral moments. All inputs and outputs in SI
//! units; wavenumbers `q = 2π/λ` in rad/m.

pub mod autocorrelation;
pub mod direction;
pub mod error;
pub mod hurst;
pub mod inverse;
pub mod moments;
pub mod power_law_band;
pub mod psd;

pub use crate::fft2::FftFailure;
pub use autocorrelation::{
    autocorrelation, periodic_autocorrelation_of, periodic_autocorrelation_with, AcfBoundary,
    AcfTexture, Autocorrelation, CorrelationLengths, RadialAcf, ISO_ACF_THRESHOLD,
};
pub use direction::{texture_direction, texture_direction_of, TextureDirection};
pub use error::SpectralError;
pub use hurst::{fit_power_law, hurst_exponent, hurst_exponent_of, HurstFit, HurstFitOptions};
pub use inverse::InverseTransform;
pub use moments::{
    spectral_moments, spectral_moments_of, MomentMethod, ProfileMoments, SpectralMoments,
};
pub use power_law_band::{
    find_power_law_band, BandCriteria, BandFit, BandSearchError, BINS_PER_DECADE, MIN_BINS,
};
pub use psd::{
    periodogram, profile_psd, radial_psd, radial_psd_of, Axis, Periodogram, PsdTable, Window,
};
