//! The self-affine twin (`spectrum: self_affine`, the default): each file's texture measured
//! (correlation lengths at the ACF threshold, Hurst exponent over its band), fitted against Sq
//! across the files and generated at the requested Sq (`surface::twins`); its columns and the
//! failures that name their fix.

use std::f64::consts::PI;

use crate::engine::node::NodeError;
use crate::engine::value::Field;
use crate::surface::spectral::{HurstFitOptions, ISO_ACF_THRESHOLD};
use crate::surface::twins::{
    fit_twin_model, format_micrometres, measure_texture, synthetic_twin, CorrelationMethod,
    MeasuredTexture, SyntheticTwin, TextureOptions, TwinError, TwinGrid, TwinModel, TwinWarning,
};
use crate::surface::HeightMap;
use crate::units::Dimension;
use crate::vocabulary::metrics::HURST;
use crate::vocabulary::surface_metrics::{CORRELATION_LENGTH_X, CORRELATION_LENGTH_Y};
use crate::vocabulary::twin_metrics::{
    twin_fit_r2, twin_fit_rms, TWIN_CALIBRATION_ITERATIONS, TWIN_CALIBRATION_RESIDUAL,
    TWIN_CORRELATION_LENGTH_X, TWIN_CORRELATION_LENGTH_Y, TWIN_CORRELATION_X_METHODS,
    TWIN_CORRELATION_Y_METHODS, TWIN_EXTRAPOLATED, TWIN_HURST, TWIN_HURST_CLAMPED,
    TWIN_HURST_PREDICTED, TWIN_MEASURED_FILES, TWIN_MEASURED_SQ_MAX, TWIN_MEASURED_SQ_MIN,
    TWIN_MIN_HURST_FIT_R2, TWIN_SQ, TWIN_WARNINGS,
};

use super::measured::{MeasuredFile, MeasuredSource};
use super::twin_band::{band_fields, band_of};
use super::twin_source::{TwinSource, TwinSq};

/// Measures, fits and generates a self-affine twin on `grid`.
pub(super) fn generate(
    source: &TwinSource,
    grid: TwinGrid,
) -> Result<(HeightMap, Vec<Field>, Vec<String>), NodeError> {
    let mut textures = Vec::with_capacity(source.measured.len());
    let mut bands = Vec::with_capacity(source.measured.len());
    let mut flags = Vec::new();
    for file in &source.measured {
        let loaded = MeasuredSource::new(file.clone(), source.preprocessing).load()?;
        flags.extend(loaded.flag);
        let map = loaded.map;
        // An ACF that does not decay is the more basic fault (and names its fix): report
        // it rather than the band search's failure.
        let band = band_of(&map, source.hurst_band, &source.preprocessing, file.path()).map_err(
            |band_error| match measure_texture(&map, &TextureOptions::default()) {
                Err(e @ TwinError::NoDecay { .. }) => texture_error(&e, file),
                _ => NodeError::new(format!("{}{SPECTRUM_TWIN_HINT}", band_error.message)),
            },
        )?;
        let [short, long] = band.band;
        let options = TextureOptions {
            hurst: HurstFitOptions {
                q_min: Some(2.0 * PI / long),
                q_max: Some(2.0 * PI / short),
                ..HurstFitOptions::default()
            },
            ..TextureOptions::default()
        };
        let texture = measure_texture(&map, &options).map_err(|e| texture_error(&e, file))?;
        if band.found.is_none() {
            check_hurst(&texture, band.band, file)?;
        }
        textures.push(texture);
        bands.push(band);
    }
    let model = fit_twin_model(&textures).map_err(|e| NodeError::new(format!("twin fit: {e}")))?;
    let sq = match source.sq {
        TwinSq::Given(v) => v,
        TwinSq::Measured => model.sq_reference,
    };
    let twin =
        synthetic_twin(&model, sq, &grid, ISO_ACF_THRESHOLD).map_err(|e| generation_error(&e))?;
    let mut metrics = twin_metrics(&textures, &model, &twin);
    let names: Vec<String> = source
        .measured
        .iter()
        .map(|f| {
            f.path()
                .file_name()
                .map_or_else(String::new, |n| n.to_string_lossy().into_owned())
        })
        .collect();
    metrics.extend(band_fields(&bands, source.hurst_band.is_some(), &names));
    Ok((twin.surface, metrics, flags))
}

/// The alternative a self-affine twin's failure to see a self-affine surface names.
const SPECTRUM_TWIN_HINT: &str = "; or twin the measured spectrum itself, which needs neither a \
     power law nor a correlation length: `spectrum: measured`";

/// A texture measurement failed: the message names the file and, for an ACF that does not decay,
/// the study field that fixes it.
fn texture_error(e: &TwinError, file: &MeasuredFile) -> NodeError {
    let path = file.path().display();
    match e {
        TwinError::NoDecay {
            axis,
            acf_reached,
            half_map,
            ..
        } => NodeError::new(format!(
            "measuring {path}: the autocorrelation along {axis} stays above {:.2} over half the \
             map ({}), so the map does not show the texture's correlation along {axis}; remove \
             waviness and form with `preprocess: {{l_filter: {}}}` (a fifth of the map side) or \
             measure a larger area{SPECTRUM_TWIN_HINT}",
            acf_reached,
            format_micrometres(*half_map),
            format_micrometres(0.4 * half_map)
        )),
        other => NodeError::new(format!("measuring {path}: {other}")),
    }
}

/// A measured Hurst exponent outside (0, 1.5] over a band the study gave means that band is not
/// self-affine (noise flattens the spectrum, or a filter steepens it): the node fails naming the
/// band and the fix. (A found band has passed the search's own criterion instead.)
fn check_hurst(
    texture: &MeasuredTexture,
    [short, long]: [f64; 2],
    file: &MeasuredFile,
) -> Result<(), NodeError> {
    if texture.hurst > 0.0 && texture.hurst <= 1.5 {
        return Ok(());
    }
    Err(NodeError::new(format!(
        "measuring {}: the PSD between the wavelengths {} and {} falls with a Hurst exponent of \
         {:.2} (R² {:.2}), outside (0, 1.5]: the surface is not self-affine in that band; set \
         `hurst_band: [short, long]` where its spectrum falls as a power law (above the S-filter \
         and the instrument's noise, below the L-filter){SPECTRUM_TWIN_HINT}",
        file.path().display(),
        format_micrometres(short),
        format_micrometres(long),
        texture.hurst,
        texture.hurst_r_squared
    )))
}

/// A twin that does not fit its grid names the `size` and `grid` that would hold it.
fn generation_error(e: &TwinError) -> NodeError {
    match e {
        TwinError::GridTooSmall {
            correlation_length_x,
            correlation_length_y,
            suggested_size,
            suggested_grid,
            ..
        } => NodeError::new(format!(
            "twin: the predicted correlation lengths {} (x) and {} (y) do not fit the twin's \
             periodic grid; use `size: [{}, {}]` with `grid: [{}, {}]` ({} correlation lengths per \
             side, at least {} points per correlation length)",
            format_micrometres(*correlation_length_x),
            format_micrometres(*correlation_length_y),
            format_micrometres(suggested_size[0]),
            format_micrometres(suggested_size[1]),
            suggested_grid[0],
            suggested_grid[1],
            crate::surface::twins::SIZE_PER_CORRELATION_LENGTH,
            crate::surface::twins::POINTS_PER_CORRELATION_LENGTH
        )),
        other => NodeError::new(format!("twin: {other}")),
    }
}

/// The twin's columns: the predicted statistics, typed warnings and sentences, how the measured
/// statistics were obtained, the fit's quality and the calibration.
fn twin_metrics(
    textures: &[MeasuredTexture],
    model: &TwinModel,
    twin: &SyntheticTwin,
) -> Vec<Field> {
    let p = &twin.prediction;
    let n = |name: &'static str, v: f64| Field::float(name, v, Dimension::Dimensionless);
    let length = |name: &'static str, v: f64| Field::float(name, v, Dimension::Length);
    let extrapolated = p
        .warnings
        .iter()
        .any(|w| matches!(w, TwinWarning::Extrapolated { .. }));
    let clamped = p
        .warnings
        .iter()
        .any(|w| matches!(w, TwinWarning::HurstClamped { .. }));
    let sentences: Vec<String> = p.warnings.iter().map(ToString::to_string).collect();
    let mut fields = vec![
        length(TWIN_SQ, p.sq),
        length(TWIN_CORRELATION_LENGTH_X, p.correlation_length_x),
        length(TWIN_CORRELATION_LENGTH_Y, p.correlation_length_y),
        n(TWIN_HURST, p.hurst),
        n(TWIN_HURST_PREDICTED, p.hurst_predicted),
        Field::bool(TWIN_EXTRAPOLATED, extrapolated),
        Field::bool(TWIN_HURST_CLAMPED, clamped),
        Field::texts(TWIN_WARNINGS, sentences),
        length(TWIN_MEASURED_SQ_MIN, model.sq_range.0),
        length(TWIN_MEASURED_SQ_MAX, model.sq_range.1),
        Field::int(TWIN_MEASURED_FILES, model.surfaces as i64),
        Field::texts(
            TWIN_CORRELATION_X_METHODS,
            methods(textures, |t| t.method_x),
        ),
        Field::texts(
            TWIN_CORRELATION_Y_METHODS,
            methods(textures, |t| t.method_y),
        ),
        n(
            TWIN_MIN_HURST_FIT_R2,
            textures
                .iter()
                .map(|t| t.hurst_r_squared)
                .fold(f64::INFINITY, f64::min),
        ),
    ];
    for (name, fit) in [
        (CORRELATION_LENGTH_X, model.correlation_length_x.fit),
        (CORRELATION_LENGTH_Y, model.correlation_length_y.fit),
        (HURST, model.hurst.fit),
    ] {
        fields.push(Field::float(
            twin_fit_rms(name),
            fit.rms_residual,
            Dimension::Dimensionless,
        ));
        // R² needs three or more files: the column is empty otherwise.
        if let Some(r2) = fit.r_squared {
            fields.push(Field::float(
                twin_fit_r2(name),
                r2,
                Dimension::Dimensionless,
            ));
        }
    }
    fields.push(Field::int(
        TWIN_CALIBRATION_ITERATIONS,
        twin.iterations as i64,
    ));
    fields.push(n(TWIN_CALIBRATION_RESIDUAL, twin.residual));
    fields
}

/// How the files' correlation lengths along one axis were obtained, one entry per method used,
/// e.g. `["acf_crossing: 2", "stretched_exponential_fit: 1 (ACF down to 0.31 at most)"]`.
fn methods(
    textures: &[MeasuredTexture],
    axis: fn(&MeasuredTexture) -> CorrelationMethod,
) -> Vec<String> {
    let crossing = textures
        .iter()
        .filter(|t| axis(t) == CorrelationMethod::AcfCrossing)
        .count();
    let reached: Vec<f64> = textures
        .iter()
        .filter_map(|t| match axis(t) {
            CorrelationMethod::StretchedExponential { acf_reached, .. } => Some(acf_reached),
            CorrelationMethod::AcfCrossing => None,
        })
        .collect();
    let mut methods = vec![format!("acf_crossing: {crossing}")];
    if !reached.is_empty() {
        let highest = reached.iter().copied().fold(0.0, f64::max);
        methods.push(format!(
            "stretched_exponential_fit: {} (ACF down to {highest:.2} at most)",
            reached.len()
        ));
    }
    methods
}
