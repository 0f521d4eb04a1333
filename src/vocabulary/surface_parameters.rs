//! The resolved parameters of a surface node (its key fields; columns of `surfaces`).

/// Where the heights come from: `synthetic`, `file` or `twin`.
pub const SOURCE: &str = "source";
/// Grid points along x of a generated surface.
pub const NX: &str = "nx";
/// Grid points along y of a generated surface.
pub const NY: &str = "ny";
/// Size along x of a generated surface (m).
pub const LX: &str = "lx";
/// Size along y of a generated surface (m).
pub const LY: &str = "ly";
/// Target Sq (m), or `measured` for a twin taking its files' geometric mean.
pub const SQ_TARGET: &str = "sq_target";
/// Correlation length of a synthetic surface (m).
pub const CORRELATION_LENGTH: &str = "correlation_length";
/// Shortest wavelength generated (m).
pub const SHORT_WAVELENGTH_CUTOFF: &str = "short_wavelength_cutoff";
/// Aspect ratio of an anisotropic synthetic surface.
pub const ANISOTROPY_RATIO: &str = "anisotropy_ratio";
/// Angle of the long axis of an anisotropic synthetic surface (rad).
pub const ANISOTROPY_ANGLE: &str = "anisotropy_angle";
/// Seed of the random phases.
pub const SEED: &str = "seed";
/// blake3 hash of a measured file's content (hex).
pub const FILE_BLAKE3: &str = "file_blake3";
/// Channel read from a multi-channel file.
pub const CHANNEL: &str = "channel";
/// Whether the study's lateral calibration replaces the file's spacing.
pub const OVERRIDE_FILE_SPACING: &str = "override_file_spacing";
/// The study's height unit (m per file unit).
pub const HEIGHT_UNIT: &str = "height_unit";
/// Where a file surface's height unit came from (`file`, `study`, `assumed`).
pub const HEIGHT_UNIT_SOURCE: &str = "height_unit_source";
/// Pixel size along x stated by the study (m).
pub const PIXEL_SIZE_X: &str = "pixel_size_x";
/// Pixel size along y stated by the study (m).
pub const PIXEL_SIZE_Y: &str = "pixel_size_y";
/// Field of view along x stated by the study (m).
pub const SIZE_X: &str = "size_x";
/// Field of view along y stated by the study (m).
pub const SIZE_Y: &str = "size_y";
/// Crop window: first column, first row, columns, rows.
pub const CROP: [&str; 4] = ["crop_ix0", "crop_iy0", "crop_nx", "crop_ny"];
/// Decimation factor along x.
pub const DECIMATE_X: &str = "decimate_x";
/// Decimation factor along y.
pub const DECIMATE_Y: &str = "decimate_y";
/// Degree of the polynomial form removed.
pub const FORM_DEGREE: &str = "form_degree";
/// S-filter nesting index (m).
pub const S_FILTER: &str = "s_filter";
/// L-filter nesting index (m).
pub const L_FILTER: &str = "l_filter";
/// Whether missing points are filled.
pub const FILL_MISSING: &str = "fill_missing";
/// A twin's spectrum: `measured` (absent: the fitted self-affine model).
pub const SPECTRUM: &str = "spectrum";
/// A spectrum twin's extrapolation beyond the measured sampling (`zero`, `power_law`).
pub const EXTRAPOLATION: &str = "extrapolation";
/// Shortest wavelength of the Hurst band a twin fits (m).
pub const HURST_BAND_SHORT: &str = "hurst_band_short";
/// Longest wavelength of the Hurst band a twin fits (m).
pub const HURST_BAND_LONG: &str = "hurst_band_long";
/// A twin's grid when it is the measured one: `measured`.
pub const TWIN_GRID: &str = "twin_grid";

/// The blake3 hash of a twin's `i`-th measured file (`twin_of_0_blake3`).
pub fn twin_of_blake3(i: usize) -> String {
    format!("twin_of_{i}_blake3")
}
