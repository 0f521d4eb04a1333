//! Hurst exponent from the slope of the radially averaged PSD.
//!
//! For a self-affine surface `C(q) ∝ q^−(2+2H)` (Persson et al., *J. Phys.: Condens. Matter* 17
//! (2005) R1; Jacobs et al., *Surf. Topogr.* 5 (2017) 013001), so a least-squares line
//! `log C = a + s·log q` over a band of wavenumbers gives `H = −s/2 − 1`. The band must lie
//! above the roll-off (or the largest measured wavelengths) and below the instrument's
//! resolution limit or S-filter; the default is the two octaves `[q_N/8, q_N/2]` with
//! `q_N = min(π/dx, π/dy)`, i.e. wavelengths from 4 to 16 pixels. The band used is returned.
//!
//! Only PSD points with power are fitted: `C > ROUND_OFF_FLOOR · max C` (the largest value of
//! the table). A double-precision FFT leaves round-off of relative power ~1e-32 in modes the
//! surface has none in (beyond a synthetic surface's short-wavelength cutoff), and a log–log
//! fit through them would report that round-off's slope; a surface without such modes (the
//! exact spectrum of a synthetic surface, or any measured one) has none so far below its peak.

use super::error::SpectralError;
use super::psd::{radial_psd, PsdTable, Window};
use crate::surface::HeightMap;

/// Least-squares fits need at least this many PSD points in the band.
pub const MIN_FIT_POINTS: usize = 3;

/// PSD points at or below this share of the table's largest value are round-off, not power
/// (module docs): 10 orders of magnitude above the round-off of a double-precision FFT, 20
/// below the peak — a self-affine spectrum spans fewer decades on any grid up to the largest
/// synthetic one (`C ∝ q⁻⁴` over 8192 wavenumbers: 16 decades).
pub const ROUND_OFF_FLOOR: f64 = 1e-20;

/// Band and window of a Hurst fit.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct HurstFitOptions {
    /// Lower end of the band, rad/m; default `q_N/8`.
    pub q_min: Option<f64>,
    /// Upper end of the band, rad/m; default `q_N/2`.
    pub q_max: Option<f64>,
    /// Window of the periodogram (default Hann; use `Window::None` for periodic surfaces).
    pub window: Window,
}

/// Result of a power-law fit `C(q) = prefactor · q^slope` over `[q_min, q_max]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HurstFit {
    /// Hurst exponent `H = −slope/2 − 1` (not clamped: values outside (0, 1] mean the band is
    /// not self-affine in the model's sense).
    pub hurst: f64,
    /// Fitted log–log slope of the radial PSD.
    pub slope: f64,
    /// Fitted `C` at `q = 1 rad/m`, m⁴ (the exponentiated intercept).
    pub prefactor: f64,
    /// Band used, rad/m.
    pub q_min: f64,
    /// Band used, rad/m.
    pub q_max: f64,
    /// Number of PSD points fitted.
    pub points: usize,
    /// Coefficient of determination of the log–log fit.
    pub r_squared: f64,
}

/// Fits the Hurst exponent of a complete height map over a band (defaults in module docs).
pub fn hurst_exponent(
    map: &HeightMap,
    options: HurstFitOptions,
) -> Result<HurstFit, SpectralError> {
    hurst_exponent_of(&radial_psd(map, options.window)?, map, options)
}

/// [`hurst_exponent`] from the radial PSD of `map` (computed with `options.window`; one FFT
/// shared by several statistics).
pub fn hurst_exponent_of(
    psd: &PsdTable,
    map: &HeightMap,
    options: HurstFitOptions,
) -> Result<HurstFit, SpectralError> {
    let q_nyquist = (std::f64::consts::PI / map.dx()).min(std::f64::consts::PI / map.dy());
    let q_min = options.q_min.unwrap_or(q_nyquist / 8.0);
    let q_max = options.q_max.unwrap_or(q_nyquist / 2.0);
    fit_power_law(psd, q_min, q_max)
}

/// Fits `log C = a + s log q` to the rows of `psd` with `q_min ≤ q ≤ q_max` (rad/m) that have
/// power (`C > ROUND_OFF_FLOOR · max C`, module docs).
pub fn fit_power_law(psd: &PsdTable, q_min: f64, q_max: f64) -> Result<HurstFit, SpectralError> {
    if !(q_min.is_finite() && q_min > 0.0) {
        return Err(SpectralError::InvalidOption {
            name: "q_min",
            value: q_min.to_string(),
            expected: "a finite wavenumber > 0 rad/m".into(),
        });
    }
    if !(q_max.is_finite() && q_max > q_min) {
        return Err(SpectralError::InvalidOption {
            name: "q_max",
            value: q_max.to_string(),
            expected: format!("a finite wavenumber > q_min = {q_min} rad/m"),
        });
    }
    let floor = ROUND_OFF_FLOOR * psd.c.iter().copied().fold(0.0, f64::max);
    let points: Vec<(f64, f64)> = psd
        .q
        .iter()
        .zip(&psd.c)
        .filter(|(q, c)| **q >= q_min && **q <= q_max && **c > floor)
        .map(|(q, c)| (q.ln(), c.ln()))
        .collect();
    let n = points.len();
    if n < MIN_FIT_POINTS {
        return Err(SpectralError::TooFewPoints {
            q_min,
            q_max,
            points: n,
            needed: MIN_FIT_POINTS,
        });
    }
    let nf = n as f64;
    let mean_x = points.iter().map(|p| p.0).sum::<f64>() / nf;
    let mean_y = points.iter().map(|p| p.1).sum::<f64>() / nf;
    let sxx: f64 = points.iter().map(|p| (p.0 - mean_x).powi(2)).sum();
    let sxy: f64 = points.iter().map(|p| (p.0 - mean_x) * (p.1 - mean_y)).sum();
    let syy: f64 = points.iter().map(|p| (p.1 - mean_y).powi(2)).sum();
    if sxx.is_nan() || sxx <= 0.0 {
        return Err(SpectralError::TooFewPoints {
            q_min,
            q_max,
            points: 1,
            needed: MIN_FIT_POINTS,
        });
    }
    let slope = sxy / sxx;
    let intercept = mean_y - slope * mean_x;
    let r_squared = if syy > 0.0 {
        sxy * sxy / (sxx * syy)
    } else {
        1.0
    };
    Ok(HurstFit {
        hurst: -slope / 2.0 - 1.0,
        slope,
        prefactor: intercept.exp(),
        q_min,
        q_max,
        points: n,
        r_squared,
    })
}
