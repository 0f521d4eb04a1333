//! Spectral analysis of height maps: FFT helpers, PSD, autocorrelation, Hurst exponent, moments.

pub(crate) mod fft2;

pub use fft2::FftFailure;
