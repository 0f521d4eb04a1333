//! Synthetic twins of measured surfaces: texture statistics measured on a set of surfaces, fitted
//! as functions of Sq, and synthetic surfaces generated at new Sq values from the fit (the
//! workflow's stage 1: correlation length and Hurst exponent fitted across ground grades and
//! extrapolated to other Sq).
//!
//! # Measured statistics
//! Per surface ([`measure_texture`]): Sq (rms about the mean); correlation lengths `ξx`, `ξy` —
//! the lags at which the ACF along the x and y axes first drops to `s` (default 0.2, as Sal);
//! the Hurst exponent from the radial PSD slope over a band (see [`super::spectral::hurst`]).
//! The surfaces' principal texture axes are assumed to be x and y (align the lay with x or y).
//!
//! # Fit across surfaces ([`fit_twin_model`])
//! With `Sq_ref` the geometric mean of the measured Sq and `u = ln(Sq / Sq_ref)`:
//! * `ξx(Sq) = ξx_ref · (Sq/Sq_ref)^bx`, `ξy` likewise (power laws: least squares of `ln ξ`
//!   against `u`);
//! * `H(Sq) = H_ref + h · u` (linear in `ln Sq`, least squares).
//!
//! A single surface, or surfaces all at the same Sq, give constant fits (exponents 0) and a
//! [`TwinWarning::ConstantFit`].
//!
//! # Generation ([`synthetic_twin`])
//! The predicted `ξx`, `ξy`, `H` at the requested Sq are turned into roll-off wavelengths of the
//! [`super::synthetic`] model (lay along x: `correlation_length = λx`,
//! `anisotropy = {aspect_ratio: λx/λy, angle: 0°}`) such that the model's ensemble ACF
//! ([`model_autocorrelation`]) on the requested grid decays to `s` exactly at `ξx` and `ξy`:
//! fixed-point iteration `λ ← λ · ξ_target / ξ_model` per axis, started at `λ = ξ/0.3`,
//! converged when both relative residuals `|ξ_model/ξ_target − 1|` are below 1e-3, at most 50
//! iterations; iterations and residual are reported. Requests outside the measured Sq range are
//! generated but flagged with [`TwinWarning::Extrapolated`]; a predicted Hurst exponent outside
//! [0.05, 1] is clamped with [`TwinWarning::HurstClamped`].

use ndarray::Array2;

use super::spectral::{
    autocorrelation, hurst_exponent, AcfBoundary, Autocorrelation, HurstFitOptions, SpectralError,
    ISO_ACF_THRESHOLD,
};
use super::synthetic::{
    generate_synthetic_surface, model_autocorrelation, Anisotropy, SyntheticError,
    SyntheticSurfaceSpec,
};
use super::HeightMap;

/// Relative residual below which the calibration of roll-off wavelengths stops.
pub const CALIBRATION_TOLERANCE: f64 = 1e-3;
/// Iteration limit of the calibration.
pub const CALIBRATION_MAX_ITERATIONS: usize = 50;
/// Hurst exponents predicted outside this range are clamped (with a warning).
pub const HURST_RANGE: (f64, f64) = (0.05, 1.0);

/// Texture statistics of one measured surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeasuredTexture {
    /// m
    pub sq: f64,
    /// ACF decay length along x, m.
    pub correlation_length_x: f64,
    /// ACF decay length along y, m.
    pub correlation_length_y: f64,
    /// Hurst exponent from the PSD slope.
    pub hurst: f64,
}

/// How [`measure_texture`] evaluates a surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TextureOptions {
    /// ACF threshold `s` of the correlation lengths (default 0.2).
    pub threshold: f64,
    /// ACF boundary (default zero-padded, for measured non-periodic maps).
    pub boundary: AcfBoundary,
    /// Band and window of the Hurst fit (defaults of [`HurstFitOptions`]).
    pub hurst: HurstFitOptions,
}

impl Default for TextureOptions {
    fn default() -> Self {
        Self {
            threshold: ISO_ACF_THRESHOLD,
            boundary: AcfBoundary::ZeroPadded,
            hurst: HurstFitOptions::default(),
        }
    }
}

/// `value(Sq) = at_reference · (Sq/Sq_ref)^exponent`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PowerLaw {
    pub at_reference: f64,
    pub exponent: f64,
}

/// `value(Sq) = at_reference + slope · ln(Sq/Sq_ref)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LogLinear {
    pub at_reference: f64,
    pub slope: f64,
}

/// Texture statistics as functions of Sq, fitted over a set of measured surfaces.
#[derive(Debug, Clone, PartialEq)]
pub struct TwinModel {
    /// Geometric mean of the measured Sq, m.
    pub sq_reference: f64,
    /// Measured Sq range `(min, max)`, m.
    pub sq_range: (f64, f64),
    /// m
    pub correlation_length_x: PowerLaw,
    /// m
    pub correlation_length_y: PowerLaw,
    pub hurst: LogLinear,
    /// Number of surfaces fitted.
    pub surfaces: usize,
    /// Warnings of the fit (e.g. [`TwinWarning::ConstantFit`]).
    pub warnings: Vec<TwinWarning>,
}

/// Something the caller should know about a twin; none of these stop the generation.
#[derive(Debug, Clone, PartialEq)]
pub enum TwinWarning {
    /// The requested Sq (m) lies outside the measured range: the fit is extrapolated.
    Extrapolated { sq: f64, min: f64, max: f64 },
    /// The predicted Hurst exponent was clamped to [`HURST_RANGE`].
    HurstClamped { predicted: f64, used: f64 },
    /// Fewer than two distinct measured Sq: statistics are constant in Sq.
    ConstantFit { surfaces: usize },
}

/// Predicted statistics at one Sq.
#[derive(Debug, Clone, PartialEq)]
pub struct TwinPrediction {
    /// m
    pub sq: f64,
    /// m
    pub correlation_length_x: f64,
    /// m
    pub correlation_length_y: f64,
    pub hurst: f64,
    pub warnings: Vec<TwinWarning>,
}

/// Grid and seed of a generated twin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwinGrid {
    pub nx: usize,
    pub ny: usize,
    /// m
    pub lx: f64,
    /// m
    pub ly: f64,
    /// Optional short-wavelength cutoff, m.
    pub short_wavelength_cutoff: Option<f64>,
    pub seed: u64,
}

/// A generated twin with its provenance.
#[derive(Debug, Clone, PartialEq)]
pub struct SyntheticTwin {
    pub surface: HeightMap,
    /// The synthetic-surface parameters actually used (calibrated roll-off wavelengths).
    pub spec: SyntheticSurfaceSpec,
    pub prediction: TwinPrediction,
    /// Calibration iterations.
    pub iterations: usize,
    /// Final max relative residual of the model correlation lengths.
    pub residual: f64,
}

/// Why a twin could not be measured, fitted or generated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TwinError {
    #[error("synthetic twins need at least one measured surface")]
    NoSurfaces,
    #[error("measured surface {index}: {what} = {value} is not a finite positive value")]
    InvalidMeasurement {
        index: usize,
        what: &'static str,
        value: f64,
    },
    #[error("the autocorrelation along {axis} does not decay to {threshold} within half the map")]
    NoDecay { axis: &'static str, threshold: f64 },
    #[error("requested Sq = {0} m is not a finite value > 0")]
    InvalidSq(f64),
    #[error(
        "roll-off calibration did not converge in {iterations} iterations (residual {residual:.2e}); \
         correlation lengths {target_x:e} m × {target_y:e} m may be unreachable on this grid"
    )]
    CalibrationFailed {
        iterations: usize,
        residual: f64,
        target_x: f64,
        target_y: f64,
    },
    #[error(transparent)]
    Spectral(#[from] SpectralError),
    #[error(transparent)]
    Synthetic(#[from] SyntheticError),
}

/// Measures Sq, correlation lengths along x and y, and the Hurst exponent of a complete map.
pub fn measure_texture(
    map: &HeightMap,
    options: &TextureOptions,
) -> Result<MeasuredTexture, TwinError> {
    let acf = autocorrelation(map, options.boundary)?;
    let lengths = acf.correlation_lengths(options.threshold)?;
    let no_decay = |axis| TwinError::NoDecay {
        axis,
        threshold: options.threshold,
    };
    let fit = hurst_exponent(map, options.hurst)?;
    Ok(MeasuredTexture {
        sq: rms_about_mean(map.heights()),
        correlation_length_x: lengths.x.ok_or_else(|| no_decay("x"))?,
        correlation_length_y: lengths.y.ok_or_else(|| no_decay("y"))?,
        hurst: fit.hurst,
    })
}

fn rms_about_mean(z: &Array2<f64>) -> f64 {
    let n = z.len() as f64;
    let mean = z.sum() / n;
    (z.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt()
}

/// Fits the statistics of `measured` as functions of Sq (see module docs).
pub fn fit_twin_model(measured: &[MeasuredTexture]) -> Result<TwinModel, TwinError> {
    if measured.is_empty() {
        return Err(TwinError::NoSurfaces);
    }
    for (index, m) in measured.iter().enumerate() {
        for (what, value) in [
            ("sq", m.sq),
            ("correlation_length_x", m.correlation_length_x),
            ("correlation_length_y", m.correlation_length_y),
            ("hurst", m.hurst),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(TwinError::InvalidMeasurement { index, what, value });
            }
        }
    }
    let n = measured.len() as f64;
    let sq_reference = (measured.iter().map(|m| m.sq.ln()).sum::<f64>() / n).exp();
    let u: Vec<f64> = measured
        .iter()
        .map(|m| (m.sq / sq_reference).ln())
        .collect();
    let line = |values: Vec<f64>| least_squares(&u, &values);
    let (ax, bx) = line(
        measured
            .iter()
            .map(|m| m.correlation_length_x.ln())
            .collect(),
    );
    let (ay, by) = line(
        measured
            .iter()
            .map(|m| m.correlation_length_y.ln())
            .collect(),
    );
    let (h0, h1) = line(measured.iter().map(|m| m.hurst).collect());
    let min = measured.iter().map(|m| m.sq).fold(f64::INFINITY, f64::min);
    let max = measured.iter().map(|m| m.sq).fold(0.0, f64::max);
    let warnings = if min == max {
        vec![TwinWarning::ConstantFit {
            surfaces: measured.len(),
        }]
    } else {
        Vec::new()
    };
    Ok(TwinModel {
        sq_reference,
        sq_range: (min, max),
        correlation_length_x: PowerLaw {
            at_reference: ax.exp(),
            exponent: bx,
        },
        correlation_length_y: PowerLaw {
            at_reference: ay.exp(),
            exponent: by,
        },
        hurst: LogLinear {
            at_reference: h0,
            slope: h1,
        },
        surfaces: measured.len(),
        warnings,
    })
}

/// Least-squares line `y = a + b x`; a constant (`b = 0`) when all `x` are equal.
fn least_squares(x: &[f64], y: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let mean_x = x.iter().sum::<f64>() / n;
    let mean_y = y.iter().sum::<f64>() / n;
    let sxx: f64 = x.iter().map(|v| (v - mean_x).powi(2)).sum();
    let sxy: f64 = x
        .iter()
        .zip(y)
        .map(|(a, b)| (a - mean_x) * (b - mean_y))
        .sum();
    let slope = if sxx > 0.0 { sxy / sxx } else { 0.0 };
    (mean_y - slope * mean_x, slope)
}

impl TwinModel {
    /// Predicted statistics at `sq` (m), with warnings when extrapolating or clamping.
    pub fn predict(&self, sq: f64) -> Result<TwinPrediction, TwinError> {
        if !(sq.is_finite() && sq > 0.0) {
            return Err(TwinError::InvalidSq(sq));
        }
        let ratio = sq / self.sq_reference;
        let mut warnings = self.warnings.clone();
        let (min, max) = self.sq_range;
        if sq < min || sq > max {
            warnings.push(TwinWarning::Extrapolated { sq, min, max });
        }
        let predicted = self.hurst.at_reference + self.hurst.slope * ratio.ln();
        let hurst = predicted.clamp(HURST_RANGE.0, HURST_RANGE.1);
        if hurst != predicted {
            warnings.push(TwinWarning::HurstClamped {
                predicted,
                used: hurst,
            });
        }
        let law = |p: PowerLaw| p.at_reference * ratio.powf(p.exponent);
        Ok(TwinPrediction {
            sq,
            correlation_length_x: law(self.correlation_length_x),
            correlation_length_y: law(self.correlation_length_y),
            hurst,
            warnings,
        })
    }
}

/// Generates a synthetic twin at `sq` (m) on `grid`, with correlation lengths measured at the
/// threshold `threshold` (use the one of [`TextureOptions`] that measured the model's inputs).
pub fn synthetic_twin(
    model: &TwinModel,
    sq: f64,
    grid: &TwinGrid,
    threshold: f64,
) -> Result<SyntheticTwin, TwinError> {
    let prediction = model.predict(sq)?;
    let (target_x, target_y) = (
        prediction.correlation_length_x,
        prediction.correlation_length_y,
    );
    let mut spec = SyntheticSurfaceSpec {
        nx: grid.nx,
        ny: grid.ny,
        lx: grid.lx,
        ly: grid.ly,
        sq,
        hurst: prediction.hurst,
        correlation_length: target_x / 0.3,
        short_wavelength_cutoff: grid.short_wavelength_cutoff,
        anisotropy: Some(Anisotropy {
            aspect_ratio: target_x / target_y,
            angle: 0.0,
        }),
        seed: grid.seed,
    };
    let (mut lambda_x, mut lambda_y) = (target_x / 0.3, target_y / 0.3);
    let mut residual = f64::INFINITY;
    let mut iterations = 0;
    for iteration in 1..=CALIBRATION_MAX_ITERATIONS {
        iterations = iteration;
        spec.correlation_length = lambda_x;
        spec.anisotropy = Some(Anisotropy {
            aspect_ratio: lambda_x / lambda_y,
            angle: 0.0,
        });
        let (dx, dy) = spec.spacing();
        let acf = Autocorrelation::from_periodic_lags(&model_autocorrelation(&spec)?, dx, dy);
        let lengths = acf.correlation_lengths(threshold)?;
        let (Some(model_x), Some(model_y)) = (lengths.x, lengths.y) else {
            break;
        };
        residual = (model_x / target_x - 1.0)
            .abs()
            .max((model_y / target_y - 1.0).abs());
        if residual < CALIBRATION_TOLERANCE {
            let surface = generate_synthetic_surface(&spec)?;
            return Ok(SyntheticTwin {
                surface,
                spec,
                prediction,
                iterations: iteration,
                residual,
            });
        }
        lambda_x *= target_x / model_x;
        lambda_y *= target_y / model_y;
    }
    Err(TwinError::CalibrationFailed {
        iterations,
        residual,
        target_x,
        target_y,
    })
}
