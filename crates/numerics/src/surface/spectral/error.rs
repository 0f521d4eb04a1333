//! Errors of the spectral statistics.

use crate::fft2::FftFailure;

/// Why a spectral statistic could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SpectralError {
    #[error("height map has {count} missing (NaN) points; fill them before spectral analysis")]
    MissingPoints { count: usize },
    #[error("height map is flat (zero variance); spectral statistics are undefined")]
    FlatSurface,
    #[error("option `{name}` = {value} is out of range, expected {expected}")]
    InvalidOption {
        name: &'static str,
        value: String,
        expected: String,
    },
    #[error(
        "fit band [{q_min:e}, {q_max:e}] rad/m holds {points} PSD points, at least {needed} needed"
    )]
    TooFewPoints {
        q_min: f64,
        q_max: f64,
        points: usize,
        needed: usize,
    },
    #[error(
        "autocorrelation does not decay to {threshold} within the largest lag {max_lag:e} m in any direction"
    )]
    NoDecay { threshold: f64, max_lag: f64 },
    #[error("{what} need the unwindowed periodogram; this one was computed with a window")]
    Windowed { what: &'static str },
    #[error(transparent)]
    Fft(#[from] FftFailure),
}

/// Checks that the map has no missing points and is not flat.
pub(crate) fn require_complete(map: &crate::surface::HeightMap) -> Result<(), SpectralError> {
    let count = map.missing_count();
    if count > 0 {
        return Err(SpectralError::MissingPoints { count });
    }
    let z = map.heights();
    let first = z.first().copied().unwrap_or(0.0);
    if z.iter().all(|v| *v == first) {
        return Err(SpectralError::FlatSurface);
    }
    Ok(())
}
