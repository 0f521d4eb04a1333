//! Texture statistics of one measured surface ([`measure_texture`]): Sq, the correlation
//! lengths along x and y and the Hurst exponent, each with how it was obtained.
//!
//! # Correlation length along an axis
//! The lag at which the ACF along the axis first drops to the threshold `s` (default 0.2, as
//! Sal), linearly interpolated between lags ([`CorrelationMethod::AcfCrossing`]).
//!
//! When the ACF stays above `s` within half the map (a long lay, or waviness left in the map) but
//! has fallen to at most [`EXTRAPOLATION_MAX_ACF`], the crossing is extrapolated with the
//! stretched exponential of a self-affine surface's ACF, `ACF(τ) = exp(−(τ/τc)^α)` (Sinha et al.,
//! Phys. Rev. B 38 (1988) 2297; α = 2H for an ideal self-affine surface), fitted by least
//! squares of `ln(−ln ACF)` against `ln τ` over the lags with `s < ACF ≤ 0.95`:
//! `ξ = τc · (ln 1/s)^(1/α)` ([`CorrelationMethod::StretchedExponential`]). It needs at least
//! [`MIN_FIT_LAGS`] such lags and a fitted α in (0, 4]. An ACF that decays less is an error
//! ([`TwinError::NoDecay`]): the map does not show the texture's correlation along that axis, and
//! an L-filter (high-pass) or a larger measured area is needed.

use super::fit::least_squares;
use super::{CorrelationMethod, MeasuredTexture, TextureOptions, TwinError};
use crate::surface::spectral::{autocorrelation, hurst_exponent, Autocorrelation};
use crate::surface::HeightMap;

/// The ACF must fall at least to this value within half the map for its threshold crossing to be
/// extrapolated (a factor ln 5 / ln 2 ≈ 2.3 in `−ln ACF` beyond the data at the ISO threshold).
pub const EXTRAPOLATION_MAX_ACF: f64 = 0.5;

/// Fewest lags the stretched-exponential fit uses.
pub const MIN_FIT_LAGS: usize = 3;

/// ACF values above this are left out of the fit (the curvature at the origin, set by the
/// shortest wavelengths and the instrument, is not part of the decay).
const FIT_MAX_ACF: f64 = 0.95;

/// A principal axis of the map.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    X,
    Y,
}

/// Measures Sq, correlation lengths along x and y, and the Hurst exponent of a complete map.
pub fn measure_texture(
    map: &HeightMap,
    options: &TextureOptions,
) -> Result<MeasuredTexture, TwinError> {
    let acf = autocorrelation(map, options.boundary)?;
    let (correlation_length_x, method_x) =
        correlation_length_along(&acf, Axis::X, options.threshold)?;
    let (correlation_length_y, method_y) =
        correlation_length_along(&acf, Axis::Y, options.threshold)?;
    let fit = hurst_exponent(map, options.hurst)?;
    Ok(MeasuredTexture {
        sq: rms_about_mean(map.heights()),
        correlation_length_x,
        correlation_length_y,
        hurst: fit.hurst,
        method_x,
        method_y,
        hurst_r_squared: fit.r_squared,
    })
}

fn rms_about_mean(z: &ndarray::Array2<f64>) -> f64 {
    let n = z.len() as f64;
    let mean = z.sum() / n;
    (z.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt()
}

/// The ACF along `axis` at lags 1, 2, … up to half the map, with the lag in metres.
fn axis_profile(acf: &Autocorrelation, axis: Axis) -> Vec<(f64, f64)> {
    let (dx, dy) = acf.spacing();
    (1..)
        .map_while(|k: isize| match axis {
            Axis::X => acf.at(k, 0).map(|v| (k as f64 * dx, v)),
            Axis::Y => acf.at(0, k).map(|v| (k as f64 * dy, v)),
        })
        .collect()
}

/// The correlation length (m) along `axis` at the ACF `threshold`, and how it was obtained
/// (module docs).
pub fn correlation_length_along(
    acf: &Autocorrelation,
    axis: Axis,
    threshold: f64,
) -> Result<(f64, CorrelationMethod), TwinError> {
    let profile = axis_profile(acf, axis);
    let mut previous = (0.0, 1.0);
    for &(lag, value) in &profile {
        if value <= threshold {
            let fraction = (previous.1 - threshold) / (previous.1 - value);
            return Ok((
                previous.0 + fraction * (lag - previous.0),
                CorrelationMethod::AcfCrossing,
            ));
        }
        previous = (lag, value);
    }
    let no_decay = |acf_reached: f64| TwinError::NoDecay {
        axis: match axis {
            Axis::X => "x",
            Axis::Y => "y",
        },
        threshold,
        acf_reached,
        half_map: profile.last().map_or(0.0, |p| p.0),
    };
    let acf_reached = profile.iter().map(|p| p.1).fold(1.0, f64::min);
    if acf_reached > EXTRAPOLATION_MAX_ACF {
        return Err(no_decay(acf_reached));
    }
    let (tau_c, exponent) =
        stretched_exponential_fit(&profile, threshold).ok_or_else(|| no_decay(acf_reached))?;
    let length = tau_c * (1.0 / threshold).ln().powf(1.0 / exponent);
    Ok((
        length,
        CorrelationMethod::StretchedExponential {
            acf_reached,
            exponent,
        },
    ))
}

/// `(τc, α)` of `ACF = exp(−(τ/τc)^α)` fitted to the lags with `threshold < ACF ≤ 0.95`;
/// `None` with fewer than [`MIN_FIT_LAGS`] of them or α outside (0, 4].
fn stretched_exponential_fit(profile: &[(f64, f64)], threshold: f64) -> Option<(f64, f64)> {
    let (ln_lag, ln_decay): (Vec<f64>, Vec<f64>) = profile
        .iter()
        .filter(|(_, a)| *a > threshold && *a <= FIT_MAX_ACF)
        .map(|&(lag, a)| (lag.ln(), (-a.ln()).ln()))
        .unzip();
    if ln_lag.len() < MIN_FIT_LAGS {
        return None;
    }
    // ln(−ln ACF) = α ln τ − α ln τc.
    let (intercept, alpha, _) = least_squares(&ln_lag, &ln_decay);
    if !(alpha > 0.0 && alpha <= 4.0) {
        return None;
    }
    let tau_c = (-intercept / alpha).exp();
    tau_c.is_finite().then_some((tau_c, alpha))
}
