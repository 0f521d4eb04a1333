//! `twin: {spectrum: measured}`: a twin whose 2-D power spectrum is the measured one
//! (`surface::twins::spectrum_twin`, where the estimate, the resampling onto the twin's grid, the
//! extrapolation and the phases are defined).
//!
//! Each file is read and preprocessed exactly as for the self-affine twin (the fields of
//! `preprocess`, defaults `form_degree: 1` and `fill_missing: true`), then its Hann-window
//! periodogram is taken. With `extrapolation: power_law` each file's spectrum is continued
//! beyond its sampling by the power law fitted to its radial PSD over its Hurst band (found as
//! for the self-affine twin, or `hurst_band`). Without `grid` and `size` the twin has the first
//! file's grid and size after preprocessing. Line scans are refused: a profile has no 2-D
//! spectrum.

use std::f64::consts::PI;

use crate::engine::node::NodeError;
use crate::engine::study::FromParamValue;
use crate::engine::value::{Field, ParamValue};
use crate::surface::spectral::{fit_power_law, radial_psd, SpectralError, Window};
use crate::surface::twins::{
    format_micrometres, spectrum_twin, Extrapolation, MeasuredSpectrum, SpectrumTwin,
    SpectrumTwinError, SpectrumTwinSpec,
};
use crate::surface::HeightMap;
use crate::units::Dimension;
use crate::vocabulary::twin_metrics::{
    TWIN_EXTRAPOLATED_POWER_SHARE, TWIN_EXTRAPOLATION, TWIN_GRID_POWER_SHARE, TWIN_MEASURED_BANDS,
    TWIN_MEASURED_FILES, TWIN_MEASURED_SPECTRUM_SQ, TWIN_MEASURED_SQ, TWIN_MODES_CUT,
    TWIN_MODES_EXTRAPOLATED, TWIN_MODES_LONGER_THAN_MEASURED, TWIN_MODES_MEASURED, TWIN_SPECTRUM,
    TWIN_SPECTRUM_SCALE, TWIN_SPECTRUM_SQ, TWIN_SQ,
};

use super::measured::{MeasuredFile, MeasuredSource};
use super::twin_band::{band_fields, band_of, FileBand};
use super::twin_source::{TwinSource, TwinSq};

/// A share of the measured spectrum's power the twin's grid may miss (or its tail add) before its
/// row is flagged.
pub(crate) const GRID_POWER_TOLERANCE: f64 = 0.1;

/// `spectrum` as written: which spectrum the twin reproduces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TwinSpectrum {
    /// The self-affine model fitted to the files (correlation lengths, Hurst exponent).
    #[default]
    SelfAffine,
    /// The files' measured 2-D power spectrum itself.
    Measured,
}

impl FromParamValue for TwinSpectrum {
    fn from_param(value: &ParamValue) -> Result<Self, String> {
        match value {
            ParamValue::Text(t) if t == "self_affine" => Ok(Self::SelfAffine),
            ParamValue::Text(t) if t == "measured" => Ok(Self::Measured),
            other => Err(format!(
                "expected `self_affine` (the fitted self-affine model) or `measured` (the files' \
                 2-D power spectrum), got {other}"
            )),
        }
    }
}

impl schemars::JsonSchema for TwinSpectrum {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "TwinSpectrum".into()
    }

    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        schemars::json_schema!({
            "description": "`self_affine` (fitted model) or `measured` (the files' 2-D spectrum).",
            "enum": ["self_affine", "measured"]
        })
    }
}

/// `extrapolation` as written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ExtrapolationChoice(pub Extrapolation);

impl FromParamValue for ExtrapolationChoice {
    fn from_param(value: &ParamValue) -> Result<Self, String> {
        match value {
            ParamValue::Text(t) if t == "zero" => Ok(Self(Extrapolation::Zero)),
            ParamValue::Text(t) if t == "power_law" => Ok(Self(Extrapolation::PowerLaw)),
            other => Err(format!(
                "expected `zero` (nothing beyond the measured wavelengths) or `power_law` (the \
                 fitted self-affine tail), got {other}"
            )),
        }
    }
}

impl schemars::JsonSchema for ExtrapolationChoice {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "TwinExtrapolation".into()
    }

    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        schemars::json_schema!({
            "description": "`zero` or `power_law`: the spectrum beyond the measured sampling.",
            "enum": ["zero", "power_law"]
        })
    }
}

/// A preprocessed file, its name, (with a power-law tail) its band, and the sentence that flags
/// it (a height unit assumed).
struct LoadedFile {
    map: HeightMap,
    name: String,
    band: Option<FileBand>,
    flag: Option<String>,
}

/// Reads the files, takes their spectra and generates the twin; returns it, its metrics and the
/// sentences that flag its row.
pub(super) fn generate(
    source: &TwinSource,
    extrapolation: Extrapolation,
) -> Result<(HeightMap, Vec<Field>, Vec<String>), NodeError> {
    let mut spectra = Vec::with_capacity(source.measured.len());
    let mut files = Vec::with_capacity(source.measured.len());
    let mut flags = Vec::new();
    for (i, file) in source.measured.iter().enumerate() {
        let mut loaded = load(source, file, i, extrapolation)?;
        let mut spectrum = MeasuredSpectrum::of_map(&loaded.map).map_err(|e| {
            let fill = match e {
                SpectrumTwinError::Spectral(SpectralError::MissingPoints { .. }) => {
                    " (`preprocess: {fill_missing: true}` fills them)"
                }
                _ => "",
            };
            NodeError::new(format!("measuring {}: {e}{fill}", file.path().display()))
        })?;
        if let Some(band) = &loaded.band {
            let [short, long] = band.band;
            let psd = radial_psd(&loaded.map, Window::Hann)
                .map_err(|e| NodeError::new(format!("{}: {e}", file.path().display())))?;
            let fit = fit_power_law(&psd, 2.0 * PI / long, 2.0 * PI / short)
                .map_err(|e| NodeError::new(format!("{}: tail: {e}", file.path().display())))?;
            spectrum = spectrum.with_tail(fit);
        }
        flags.extend(loaded.flag.take());
        spectra.push(spectrum);
        files.push(loaded);
    }
    let first = files
        .first()
        .ok_or_else(|| NodeError::new("twin: needs at least one measured file"))?;
    let spec = twin_spec(source, extrapolation, &first.map);
    let twin = spectrum_twin(&spectra, &spec).map_err(|e| twin_error(&e, source))?;
    let names: Vec<String> = files.iter().map(|f| f.name.clone()).collect();
    let mut metrics = spectrum_metrics(&twin, &spectra, extrapolation, &names);
    if extrapolation == Extrapolation::PowerLaw {
        let bands: Vec<FileBand> = files.iter().filter_map(|f| f.band).collect();
        metrics.extend(band_fields(&bands, source.hurst_band.is_some(), &names));
    }
    flags.extend(power_flag(&twin));
    Ok((twin.surface, metrics, flags))
}

/// Reads and preprocesses file `index` of the twin and, for a power-law tail, finds its band.
fn load(
    source: &TwinSource,
    file: &MeasuredFile,
    index: usize,
    extrapolation: Extrapolation,
) -> Result<LoadedFile, NodeError> {
    let measured = MeasuredSource::new(file.clone(), source.preprocessing);
    let loaded = measured.load().map_err(|e| {
        NodeError::new(format!(
            "twin.of[{index}]: {}{}",
            e.message,
            if e.message.contains("line scan") {
                " (a spectrum twin averages 2-D power spectra, which a profile does not have)"
            } else {
                ""
            }
        ))
    })?;
    let path = file.path();
    let band = match extrapolation {
        Extrapolation::Zero => None,
        Extrapolation::PowerLaw => Some(
            band_of(&loaded.map, source.hurst_band, &source.preprocessing, path).map_err(|e| {
                NodeError::new(format!(
                    "{} (`extrapolation: power_law` needs it; `extrapolation: zero` does \
                         not)",
                    e.message
                ))
            })?,
        ),
    };
    let name = path
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    Ok(LoadedFile {
        map: loaded.map,
        name,
        band,
        flag: loaded.flag,
    })
}

/// The twin's grid: `grid` and `size` when given, else the first file's.
fn twin_spec(
    source: &TwinSource,
    extrapolation: Extrapolation,
    first: &HeightMap,
) -> SpectrumTwinSpec {
    let (nx, ny, lx, ly) = match source.size {
        Some(s) => (s.nx, s.ny, s.lx, s.ly),
        None => {
            let (lx, ly) = first.size();
            (first.nx(), first.ny(), lx, ly)
        }
    };
    SpectrumTwinSpec {
        nx,
        ny,
        lx,
        ly,
        sq: match source.sq {
            TwinSq::Given(v) => Some(v),
            TwinSq::Measured => None,
        },
        short_wavelength_cutoff: source.short_wavelength_cutoff,
        extrapolation,
        seed: source.seed,
    }
}

/// The numerics' error, with the files named where it names map indices.
fn twin_error(e: &SpectrumTwinError, source: &TwinSource) -> NodeError {
    let name = |i: usize| {
        source
            .measured
            .get(i)
            .map_or_else(String::new, |f| f.path().display().to_string())
    };
    let files = match e {
        SpectrumTwinError::NoCommonBand { first, second, .. }
        | SpectrumTwinError::SpectraDisagree { first, second, .. } => format!(
            " (map {first}: {}; map {second}: {})",
            name(*first),
            name(*second)
        ),
        _ => String::new(),
    };
    NodeError::new(format!("twin (spectrum: measured): {e}{files}"))
}

/// The twin's columns: the spectrum kind, Sq of the measured maps, of their spectra, of the
/// spectrum on the twin's grid and of the twin, the share of the measured spectrum's power the
/// grid holds and the scale applied to it, the modes by origin and each file's wavelengths.
fn spectrum_metrics(
    twin: &SpectrumTwin,
    spectra: &[MeasuredSpectrum],
    extrapolation: Extrapolation,
    names: &[String],
) -> Vec<Field> {
    let length = |name: &'static str, v: f64| Field::float(name, v, Dimension::Length);
    let count = |name: &'static str, n: usize| Field::int(name, n as i64);
    let bands = spectra
        .iter()
        .zip(names)
        .map(|(s, name)| {
            let [short, long] = s.band();
            format!(
                "{name}: {} to {}",
                format_micrometres(short),
                format_micrometres(long)
            )
        })
        .collect();
    vec![
        Field::text(TWIN_SPECTRUM, "measured"),
        Field::text(TWIN_EXTRAPOLATION, extrapolation.name()),
        length(TWIN_SQ, twin.sq),
        length(TWIN_MEASURED_SQ, twin.measured_sq),
        length(TWIN_MEASURED_SPECTRUM_SQ, twin.measured_spectrum_sq),
        length(TWIN_SPECTRUM_SQ, twin.spectrum_sq),
        Field::float(
            TWIN_GRID_POWER_SHARE,
            grid_power_share(twin),
            Dimension::Dimensionless,
        ),
        Field::float(
            TWIN_SPECTRUM_SCALE,
            twin.sq / twin.spectrum_sq,
            Dimension::Dimensionless,
        ),
        count(TWIN_MEASURED_FILES, spectra.len()),
        Field::texts(TWIN_MEASURED_BANDS, bands),
        count(TWIN_MODES_MEASURED, twin.modes.measured),
        count(TWIN_MODES_EXTRAPOLATED, twin.modes.shorter),
        count(TWIN_MODES_LONGER_THAN_MEASURED, twin.modes.longer),
        count(TWIN_MODES_CUT, twin.modes.cut),
        Field::float(
            TWIN_EXTRAPOLATED_POWER_SHARE,
            twin.modes.extrapolated_power_share,
            Dimension::Dimensionless,
        ),
    ]
}

/// `(Sq of the spectrum on the twin's grid / Sq of the measured spectra)²`.
fn grid_power_share(twin: &SpectrumTwin) -> f64 {
    (twin.spectrum_sq / twin.measured_spectrum_sq).powi(2)
}

/// The sentence that flags a twin whose grid holds a different power than the measured spectra.
fn power_flag(twin: &SpectrumTwin) -> Option<String> {
    let share = grid_power_share(twin);
    if (share - 1.0).abs() <= GRID_POWER_TOLERANCE {
        return None;
    }
    Some(format!(
        "the twin's grid holds {:.0} % of the measured spectrum's power (Sq {} of {}): the \
         measured wavelengths longer than its size or shorter than 2 of its pixels are lost, \
         an extrapolated tail adds some; the rest was scaled by {:.3} to reach Sq = {}, so its \
         spectrum is not the measured one; a size and spacing closer to the measurement's keep \
         it",
        100.0 * share,
        format_micrometres(twin.spectrum_sq),
        format_micrometres(twin.measured_spectrum_sq),
        twin.sq / twin.spectrum_sq,
        format_micrometres(twin.sq)
    ))
}
