//! What a surface node measures on its heights (columns of `surfaces` beyond
//! [`super::metrics`]' shared ones).

/// Points without a height.
pub const MISSING_POINTS: &str = "missing_points";
/// Arithmetic mean height Sa (m).
pub const SA: &str = "sa";
/// Maximum peak height Sp (m).
pub const SP: &str = "sp";
/// Maximum pit depth Sv (m).
pub const SV: &str = "sv";
/// Maximum height Sz (m).
pub const SZ: &str = "sz";
/// Skewness Ssk.
pub const SSK: &str = "ssk";
/// Kurtosis Sku.
pub const SKU: &str = "sku";
/// Root-mean-square gradient Sdq.
pub const SDQ: &str = "sdq";
/// Developed interfacial area ratio Sdr (%).
pub const SDR_PERCENT: &str = "sdr_percent";
/// Texture direction Std (rad).
pub const STD: &str = "std";
/// Isotropic profile spectral moment m0 (m²); with [`X_SUFFIX`] or [`Y_SUFFIX`] along one
/// axis.
pub const M0: &str = "m0";
/// Isotropic profile spectral moment m2 (mean square slope).
pub const M2: &str = "m2";
/// Isotropic profile spectral moment m4 (1/m²).
pub const M4: &str = "m4";
/// Suffix of a moment along x.
pub const X_SUFFIX: &str = "_x";
/// Suffix of a moment along y.
pub const Y_SUFFIX: &str = "_y";
/// GW mean summit height above the mean plane y_s (m).
pub const GW_Y_S: &str = "gw_y_s";
/// Nayak's bandwidth parameter α = m0·m4/m2².
pub const GW_ALPHA: &str = "gw_alpha";
/// Autocorrelation length Sal (m).
pub const SAL: &str = "sal";
/// Texture aspect ratio Str.
pub const STR: &str = "str";
/// Correlation length along x (m).
pub const CORRELATION_LENGTH_X: &str = "correlation_length_x";
/// Correlation length along y (m).
pub const CORRELATION_LENGTH_Y: &str = "correlation_length_y";
/// Hurst exponent fitted to the radial PSD.
pub const HURST_FIT: &str = "hurst_fit";
/// Lowest wavenumber of the Hurst fit (rad/m).
pub const HURST_FIT_Q_MIN: &str = "hurst_fit_q_min_rad_per_m";
/// Highest wavenumber of the Hurst fit (rad/m).
pub const HURST_FIT_Q_MAX: &str = "hurst_fit_q_max_rad_per_m";
/// Coefficient of determination of the Hurst fit.
pub const HURST_FIT_R_SQUARED: &str = "hurst_fit_r_squared";
/// Core height Sk (m).
pub const SK: &str = "sk";
/// Reduced peak height Spk (m).
pub const SPK: &str = "spk";
/// Reduced valley depth Svk (m).
pub const SVK: &str = "svk";
/// Material ratio Smr1 (%).
pub const SMR1_PERCENT: &str = "smr1_percent";
/// Material ratio Smr2 (%).
pub const SMR2_PERCENT: &str = "smr2_percent";
/// Extreme peak height Sxp (m).
pub const SXP: &str = "sxp";
/// Peak material volume Vmp (m³/m²).
pub const VMP: &str = "vmp_m3_per_m2";
/// Core material volume Vmc (m³/m²).
pub const VMC: &str = "vmc_m3_per_m2";
/// Core void volume Vvc (m³/m²).
pub const VVC: &str = "vvc_m3_per_m2";
/// Valley void volume Vvv (m³/m²).
pub const VVV: &str = "vvv_m3_per_m2";
/// Standard deviation of the identified summits' heights (m).
pub const SUMMIT_HEIGHT_STD: &str = "summit_height_std";
/// A measured surface's sentence when its lateral scale looks wrong (empty otherwise).
pub const LATERAL_SCALE_WARNING: &str = "lateral_scale_warning";
