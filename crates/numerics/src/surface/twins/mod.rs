//! Synthetic twins of measured surfaces: texture statistics measured on a set of surfaces, fitted
//! as functions of Sq, and synthetic surfaces generated at new Sq values from the fit (the
//! workflow's stage 1: correlation length and Hurst exponent fitted across ground grades and
//! extrapolated to other Sq).
//!
//! * [`measure_texture`] (`texture.rs`): Sq, the correlation lengths `ξx`, `ξy` at the ACF
//!   threshold `s` (default 0.2, as Sal) — the ACF crossing, or its extrapolation by a fitted
//!   stretched exponential when the map is too short to show it — and the Hurst exponent from
//!   the radial PSD slope ([`super::spectral::hurst`]), each with how it was obtained. The
//!   surfaces' principal texture axes are assumed to be x and y (align the lay with x or y).
//! * [`fit_twin_model`] (`fit.rs`): power laws `ξ(Sq)` and `H` linear in `ln Sq`, with the
//!   quality of each fit; [`TwinModel::predict`] at a new Sq, flagging extrapolation
//!   ([`TwinWarning::Extrapolated`]) and clamping a predicted H outside [`HURST_RANGE`]
//!   ([`TwinWarning::HurstClamped`]).
//! * [`synthetic_twin`] (`generate.rs`): a periodic synthetic surface whose model ACF decays to
//!   `s` at the predicted `ξx`, `ξy`, or an error naming the size and grid that would hold them.
//!
//! The other kind of twin needs no model of the texture: [`spectrum_twin`]
//! (`spectrum_twin.rs`) reproduces the measured 2-D power spectrum itself
//! ([`MeasuredSpectrum`], `spectrum.rs`), averaged over the files and resampled onto the twin's
//! grid, with random phases — for surfaces that are not self-affine over any useful band.

mod fit;
mod generate;
mod spectrum;
mod spectrum_twin;
mod texture;

pub use fit::fit_twin_model;
pub use generate::{synthetic_twin, POINTS_PER_CORRELATION_LENGTH, SIZE_PER_CORRELATION_LENGTH};
pub use spectrum::{
    check_compatible, MeasuredSpectrum, SpectrumTwinError, SpectrumValue, MAX_BAND_RMS_RATIO,
};
pub use spectrum_twin::{spectrum_twin, Extrapolation, ModeTally, SpectrumTwin, SpectrumTwinSpec};
pub use texture::{
    correlation_length_along, measure_texture, Axis, EXTRAPOLATION_MAX_ACF, MIN_FIT_LAGS,
};

use std::fmt;

use super::spectral::{AcfBoundary, HurstFitOptions, SpectralError, ISO_ACF_THRESHOLD};
use super::synthetic::{SyntheticError, SyntheticSurfaceSpec};
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
    /// How `correlation_length_x` was obtained.
    pub method_x: CorrelationMethod,
    /// How `correlation_length_y` was obtained.
    pub method_y: CorrelationMethod,
    /// R² of the log–log PSD fit behind `hurst`.
    pub hurst_r_squared: f64,
}

/// How a correlation length was obtained ([`measure_texture`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CorrelationMethod {
    /// The ACF crosses the threshold within half the map.
    AcfCrossing,
    /// Extrapolated by the stretched exponential `exp(−(τ/τc)^α)` fitted to the ACF, which fell
    /// only to `acf_reached` within half the map.
    StretchedExponential { acf_reached: f64, exponent: f64 },
}

impl CorrelationMethod {
    /// The name written to tables.
    pub fn name(&self) -> &'static str {
        match self {
            Self::AcfCrossing => "acf_crossing",
            Self::StretchedExponential { .. } => "stretched_exponential_fit",
        }
    }
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
    /// Quality of the fit of `ln value` against `ln Sq`.
    pub fit: LineFit,
}

/// `value(Sq) = at_reference + slope · ln(Sq/Sq_ref)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LogLinear {
    pub at_reference: f64,
    pub slope: f64,
    /// Quality of the fit.
    pub fit: LineFit,
}

/// Quality of a least-squares line across the measured surfaces.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineFit {
    /// Root-mean-square residual, in the fitted variable (`ln ξ`: a relative scatter; `H`).
    pub rms_residual: f64,
    /// Coefficient of determination; `None` with fewer than three surfaces or no spread.
    pub r_squared: Option<f64>,
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
    /// The Hurst exponent used (clamped to [`HURST_RANGE`]).
    pub hurst: f64,
    /// The fit's value before clamping.
    pub hurst_predicted: f64,
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
    #[error(
        "the autocorrelation along {axis} does not decay to {threshold} within half the map \
         ({half_map:e} m): it only falls to {acf_reached:.2}, too little to extrapolate (≤ {limit}); \
         the map does not show the texture's correlation along {axis} — remove waviness and form \
         with an L-filter (high-pass, e.g. a cutoff of a fifth of the map side) or measure a \
         larger area",
        limit = EXTRAPOLATION_MAX_ACF
    )]
    NoDecay {
        axis: &'static str,
        threshold: f64,
        /// Lowest ACF value within half the map.
        acf_reached: f64,
        /// Half the map along the axis, m.
        half_map: f64,
    },
    #[error("requested Sq = {0} m is not a finite value > 0")]
    InvalidSq(f64),
    #[error(
        "the predicted correlation lengths {correlation_length_x:e} m × {correlation_length_y:e} m \
         do not fit the twin's periodic grid (roll-off calibration: {iterations} iterations, \
         residual {residual:.2e}); a size of {} m × {} m on {} × {} points holds {} correlation \
         lengths per axis",
        suggested_size[0], suggested_size[1], suggested_grid[0], suggested_grid[1],
        SIZE_PER_CORRELATION_LENGTH
    )]
    GridTooSmall {
        correlation_length_x: f64,
        correlation_length_y: f64,
        iterations: usize,
        residual: f64,
        /// `[Lx, Ly]`, m.
        suggested_size: [f64; 2],
        /// `[nx, ny]` at the given spacing.
        suggested_grid: [usize; 2],
    },
    #[error(transparent)]
    Spectral(#[from] SpectralError),
    #[error(transparent)]
    Synthetic(#[from] SyntheticError),
}

/// A length in micrometres with three significant digits, as a message or a study writes it
/// (`105 µm`, `2.00 µm`).
pub fn format_micrometres(metres: f64) -> String {
    let um = metres * 1e6;
    if um == 0.0 || !um.is_finite() {
        return format!("{um} µm");
    }
    let digits = (2 - um.abs().log10().floor() as i32).max(0) as usize;
    format!("{um:.digits$} µm")
}

impl fmt::Display for TwinWarning {
    /// A sentence with units.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::Extrapolated { sq, min, max } => write!(
                f,
                "Sq = {} lies outside the measured range {} to {}: the texture statistics are \
                 extrapolated",
                format_micrometres(sq),
                format_micrometres(min),
                format_micrometres(max)
            ),
            Self::HurstClamped { predicted, used } => write!(
                f,
                "the fitted Hurst exponent at this Sq is {predicted:.3}, outside [{}, {}]; {used} \
                 is used",
                HURST_RANGE.0, HURST_RANGE.1
            ),
            Self::ConstantFit { surfaces } => write!(
                f,
                "the {surfaces} measured surface(s) share one Sq: the texture statistics are \
                 taken as constant in Sq"
            ),
        }
    }
}
