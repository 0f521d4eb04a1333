//! What a twin surface reports of its model and calibration (columns of `surfaces`).

/// Sq the twin was generated with (m).
pub const TWIN_SQ: &str = "twin_sq";
/// Predicted correlation length along x (m).
pub const TWIN_CORRELATION_LENGTH_X: &str = "twin_correlation_length_x";
/// Predicted correlation length along y (m).
pub const TWIN_CORRELATION_LENGTH_Y: &str = "twin_correlation_length_y";
/// Hurst exponent the twin was generated with.
pub const TWIN_HURST: &str = "twin_hurst";
/// Hurst exponent the model predicts before clamping.
pub const TWIN_HURST_PREDICTED: &str = "twin_hurst_predicted";
/// Whether the twin's parameters lie outside the measured files' range.
pub const TWIN_EXTRAPOLATED: &str = "twin_extrapolated";
/// Whether the predicted Hurst exponent was clamped into (0, 1].
pub const TWIN_HURST_CLAMPED: &str = "twin_hurst_clamped";
/// The twin's warnings, a list of sentences (empty when there is none).
pub const TWIN_WARNINGS: &str = "twin_warnings";
/// Smallest Sq of the measured files (m).
pub const TWIN_MEASURED_SQ_MIN: &str = "twin_measured_sq_min";
/// Largest Sq of the measured files (m).
pub const TWIN_MEASURED_SQ_MAX: &str = "twin_measured_sq_max";
/// Number of measured files the twin is made from.
pub const TWIN_MEASURED_FILES: &str = "twin_measured_files";
/// How the files' correlation lengths along x were obtained, a list: one entry per method.
pub const TWIN_CORRELATION_X_METHODS: &str = "twin_correlation_x_methods";
/// How the files' correlation lengths along y were obtained, a list: one entry per method.
pub const TWIN_CORRELATION_Y_METHODS: &str = "twin_correlation_y_methods";
/// Lowest r² of the files' Hurst fits.
pub const TWIN_MIN_HURST_FIT_R2: &str = "twin_min_hurst_fit_r2";
/// Iterations of the twin's Sq calibration.
pub const TWIN_CALIBRATION_ITERATIONS: &str = "twin_calibration_iterations";
/// Relative residual of the twin's Sq calibration.
pub const TWIN_CALIBRATION_RESIDUAL: &str = "twin_calibration_residual";
/// Where the Hurst band came from: `study` or `found`.
pub const TWIN_HURST_BAND_SOURCE: &str = "twin_hurst_band_source";
/// Each file's Hurst band, a list: one text per file.
pub const TWIN_HURST_BANDS: &str = "twin_hurst_bands";
/// Shortest wavelength of the common Hurst band (m).
pub const TWIN_HURST_BAND_SHORT: &str = "twin_hurst_band_short";
/// Longest wavelength of the common Hurst band (m).
pub const TWIN_HURST_BAND_LONG: &str = "twin_hurst_band_long";
/// A spectrum twin's spectrum: `measured`.
pub const TWIN_SPECTRUM: &str = "twin_spectrum";
/// A spectrum twin's extrapolation.
pub const TWIN_EXTRAPOLATION: &str = "twin_extrapolation";
/// Geometric mean Sq of the measured files (m).
pub const TWIN_MEASURED_SQ: &str = "twin_measured_sq";
/// Sq of the mean measured spectrum (m).
pub const TWIN_MEASURED_SPECTRUM_SQ: &str = "twin_measured_spectrum_sq";
/// Sq of the spectrum on the twin's grid before scaling (m).
pub const TWIN_SPECTRUM_SQ: &str = "twin_spectrum_sq";
/// (Sq of the spectrum on the twin's grid / Sq of the measured spectra)².
pub const TWIN_GRID_POWER_SHARE: &str = "twin_grid_power_share";
/// Factor the spectrum was scaled by to reach the target Sq.
pub const TWIN_SPECTRUM_SCALE: &str = "twin_spectrum_scale";
/// Each file's measured band, a list: one text per file.
pub const TWIN_MEASURED_BANDS: &str = "twin_measured_bands";
/// Modes taken from the measured spectrum.
pub const TWIN_MODES_MEASURED: &str = "twin_modes_measured";
/// Modes extrapolated beyond the measured sampling.
pub const TWIN_MODES_EXTRAPOLATED: &str = "twin_modes_extrapolated";
/// Modes longer than the measured field of view.
pub const TWIN_MODES_LONGER_THAN_MEASURED: &str = "twin_modes_longer_than_measured";
/// Modes cut (set to zero).
pub const TWIN_MODES_CUT: &str = "twin_modes_cut";
/// Share of the twin's power in extrapolated modes.
pub const TWIN_EXTRAPOLATED_POWER_SHARE: &str = "twin_extrapolated_power_share";

/// The rms residual of the model's fit of `quantity` (`twin_fit_rms_hurst`).
pub fn twin_fit_rms(quantity: &str) -> String {
    format!("twin_fit_rms_{quantity}")
}

/// The r² of the model's fit of `quantity` (`twin_fit_r2_hurst`).
pub fn twin_fit_r2(quantity: &str) -> String {
    format!("twin_fit_r2_{quantity}")
}
