//! The widest wavenumber band over which a radial PSD is a power law ([`find_power_law_band`]):
//! where a measured surface is self-affine, so that its Hurst exponent means something.
//!
//! **Limits.** The search stays inside `[q_low, q_high]`, which the caller sets from what it
//! knows: the L-filter (wavelengths beyond λc are attenuated: `q_low ≥ 2π/λc`) or the map
//! (wavelengths of at most half its shorter side), and the S-filter or the sampling
//! (wavelengths of at least λs, and of at least 2 pixels: `q_high ≤ q_N`, the Nyquist
//! wavenumber).
//!
//! **Criterion.** The PSD rows inside the limits are averaged in logarithmic bins of
//! [`BINS_PER_DECADE`] per decade of `q` (mean `log₁₀ q`, mean `log₁₀ C` of the rows in each
//! bin), so every decade weighs alike however many modes it holds. A run of consecutive bins is
//! a **power-law band** when
//! * it spans at least [`BandCriteria::min_decades`] (default 0.5 decade, a factor 3.2 in
//!   wavelength) with at least [`MIN_BINS`] bins;
//! * the least-squares line through its bins has `R² ≥` [`BandCriteria::min_r_squared`]
//!   (default 0.95), and every bin lies within its own sampling error of the line: no further
//!   than `max(floor, k·σ)` decades, with [`BandCriteria::residual_floor_decades`] = 0.1 (a
//!   factor 1.26 in `C`: the departure from a power law tolerated where the sampling error is
//!   smaller) and [`BandCriteria::residual_sigmas`] `k` = 3. `σ = log₁₀e / √M` is the standard
//!   error of the bin's mean `log₁₀ C` for `M` independent periodogram values, each
//!   exponentially distributed (a Gaussian surface's periodogram); `M` = the bin's Fourier
//!   modes / [`BandCriteria::modes_per_independent`] (default 4.5: the modes `q` and `−q` are one
//!   value, and the Hann window's equivalent noise bandwidth of 1.5 bins per axis joins 2.25 of
//!   them). A curved spectrum (a roll-off, the noise floor of an instrument, the edge of a
//!   filter) fails this test however high its R²; a few noisy long-wavelength bins do not;
//! * the spectrum falls faster than white noise: `H = −slope/2 − 1 > 0` (a flat noise floor has
//!   `H ≤ 0`). `H > 1` is a power law too (a surface smoother than self-affine at those
//!   scales, or an instrument's optical low-pass); the caller decides what to do with it.
//!
//! The widest such band is chosen (in decades; on a tie the one with the higher R²). With none,
//! the result names the best band of the minimum width (highest R²) and its fit.

use super::psd::PsdTable;

/// Logarithmic bins per decade of wavenumber.
pub const BINS_PER_DECADE: f64 = 10.0;

/// Fewest bins in a band.
pub const MIN_BINS: usize = 4;

/// What makes a band a power law (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BandCriteria {
    /// Least width, decades of `q`.
    pub min_decades: f64,
    /// Least coefficient of determination of the log–log fit.
    pub min_r_squared: f64,
    /// Distance of a bin from the fitted line always tolerated, decades of `C`.
    pub residual_floor_decades: f64,
    /// Distance tolerated in standard errors of the bin.
    pub residual_sigmas: f64,
    /// Fourier modes per independent periodogram value.
    pub modes_per_independent: f64,
}

impl Default for BandCriteria {
    fn default() -> Self {
        Self {
            min_decades: 0.5,
            min_r_squared: 0.95,
            residual_floor_decades: 0.1,
            residual_sigmas: 3.0,
            modes_per_independent: 4.5,
        }
    }
}

/// A band and the power-law fit over it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BandFit {
    /// Lower end, rad/m: the lowest PSD row of the band's first bin.
    pub q_min: f64,
    /// Upper end, rad/m: the highest PSD row of its last bin.
    pub q_max: f64,
    /// `H = −slope/2 − 1` of the binned fit.
    pub hurst: f64,
    /// R² of the binned log–log fit.
    pub r_squared: f64,
    /// Largest distance of a bin from the line, decades.
    pub max_residual_decades: f64,
    /// Largest distance of a bin from the line in units of its tolerance (≤ 1 passes).
    pub max_residual_ratio: f64,
}

impl BandFit {
    /// Width of the band, decades.
    pub fn decades(&self) -> f64 {
        (self.q_max / self.q_min).log10()
    }

    fn qualifies(&self, c: &BandCriteria) -> bool {
        self.r_squared >= c.min_r_squared && self.max_residual_ratio <= 1.0 && self.hurst > 0.0
    }
}

/// Why no band was found.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum BandSearchError {
    #[error(
        "the limits [{q_low:e}, {q_high:e}] rad/m hold {bins} logarithmic bins of the PSD, \
         fewer than the {MIN_BINS} of a band of {min_decades} decade"
    )]
    TooNarrow {
        q_low: f64,
        q_high: f64,
        bins: usize,
        min_decades: f64,
    },
    #[error(
        "no band of {min_decades} decade or more is a power law (R² ≥ {min_r_squared}, every \
         bin within its sampling error of the line, H > 0); the best one, [{:e}, {:e}] rad/m, \
         has H = {:.2}, R² = {:.3} and a bin {:.2} decade off ({:.1} times its tolerance)",
        best.q_min, best.q_max, best.hurst, best.r_squared, best.max_residual_decades,
        best.max_residual_ratio
    )]
    NoPowerLaw {
        best: BandFit,
        min_decades: f64,
        min_r_squared: f64,
    },
}

/// The widest power-law band of `psd` within `[q_low, q_high]` rad/m (module docs).
pub fn find_power_law_band(
    psd: &PsdTable,
    q_low: f64,
    q_high: f64,
    criteria: BandCriteria,
) -> Result<BandFit, BandSearchError> {
    let bins = log_bins(psd, q_low, q_high, &criteria);
    let too_narrow = BandSearchError::TooNarrow {
        q_low,
        q_high,
        bins: bins.len(),
        min_decades: criteria.min_decades,
    };
    let mut chosen: Option<BandFit> = None;
    let mut best_failed: Option<BandFit> = None;
    for first in 0..bins.len() {
        for last in first + MIN_BINS - 1..bins.len() {
            let fit = fit_bins(&bins[first..=last], &criteria);
            if fit.decades() + 1e-9 < criteria.min_decades {
                continue;
            }
            if fit.qualifies(&criteria) {
                let better = chosen.is_none_or(|c| {
                    fit.decades() > c.decades() + 1e-9
                        || (fit.decades() > c.decades() - 1e-9 && fit.r_squared > c.r_squared)
                });
                if better {
                    chosen = Some(fit);
                }
            } else if best_failed.is_none_or(|b| fit.r_squared > b.r_squared) {
                best_failed = Some(fit);
            }
        }
    }
    match (chosen, best_failed) {
        (Some(fit), _) => Ok(fit),
        (None, Some(best)) => Err(BandSearchError::NoPowerLaw {
            best,
            min_decades: criteria.min_decades,
            min_r_squared: criteria.min_r_squared,
        }),
        (None, None) => Err(too_narrow),
    }
}

/// One logarithmic bin: mean `log₁₀ q`, mean `log₁₀ C`, the standard error `sigma` of the
/// latter (decades), and its lowest and highest `q`.
#[derive(Debug, Clone, Copy)]
struct Bin {
    x: f64,
    y: f64,
    sigma: f64,
    q_first: f64,
    q_last: f64,
}

/// The bins of the rows with `q_low ≤ q ≤ q_high` and `C > 0` (rows in ascending `q`).
fn log_bins(psd: &PsdTable, q_low: f64, q_high: f64, criteria: &BandCriteria) -> Vec<Bin> {
    if !(q_low > 0.0 && q_high > q_low) {
        return Vec::new();
    }
    let origin = q_low.log10();
    // Per bin: Σ log₁₀ q, Σ log₁₀ C, rows, modes, lowest q, highest q.
    let mut sums: Vec<(f64, f64, usize, usize, f64, f64)> = Vec::new();
    for ((&q, &c), &modes) in psd.q.iter().zip(&psd.c).zip(&psd.modes) {
        if !(q >= q_low && q <= q_high && c > 0.0) {
            continue;
        }
        let bin = ((q.log10() - origin) * BINS_PER_DECADE).floor() as usize;
        if sums.len() <= bin {
            sums.resize(bin + 1, (0.0, 0.0, 0, 0, f64::INFINITY, 0.0));
        }
        let s = &mut sums[bin];
        *s = (
            s.0 + q.log10(),
            s.1 + c.log10(),
            s.2 + 1,
            s.3 + modes,
            s.4.min(q),
            s.5.max(q),
        );
    }
    sums.into_iter()
        .filter(|s| s.2 > 0)
        .map(|(x, y, rows, modes, q_first, q_last)| {
            let independent = (modes as f64 / criteria.modes_per_independent).max(1.0);
            Bin {
                x: x / rows as f64,
                y: y / rows as f64,
                sigma: std::f64::consts::LOG10_E / independent.sqrt(),
                q_first,
                q_last,
            }
        })
        .collect()
}

/// The least-squares line through the bins and its quality.
fn fit_bins(bins: &[Bin], criteria: &BandCriteria) -> BandFit {
    let n = bins.len() as f64;
    let mean_x = bins.iter().map(|b| b.x).sum::<f64>() / n;
    let mean_y = bins.iter().map(|b| b.y).sum::<f64>() / n;
    let (sxx, sxy, syy) = bins.iter().fold((0.0, 0.0, 0.0), |(xx, xy, yy), b| {
        let (dx, dy) = (b.x - mean_x, b.y - mean_y);
        (xx + dx * dx, xy + dx * dy, yy + dy * dy)
    });
    let slope = sxy / sxx;
    let residual = |b: &Bin| (b.y - mean_y - slope * (b.x - mean_x)).abs();
    let tolerance =
        |b: &Bin| (criteria.residual_sigmas * b.sigma).max(criteria.residual_floor_decades);
    let max_residual_decades = bins.iter().map(residual).fold(0.0, f64::max);
    let max_residual_ratio = bins
        .iter()
        .map(|b| residual(b) / tolerance(b))
        .fold(0.0, f64::max);
    BandFit {
        q_min: bins[0].q_first,
        q_max: bins[bins.len() - 1].q_last,
        hurst: -slope / 2.0 - 1.0,
        r_squared: if syy > 0.0 {
            sxy * sxy / (sxx * syy)
        } else {
            1.0
        },
        max_residual_decades,
        max_residual_ratio,
    }
}
