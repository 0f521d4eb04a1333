//! `surface: {twin: {...}}`: a synthetic twin of measured surfaces at a new Sq (the workflow's
//! method for parameter studies).
//!
//! Each measured file is preprocessed as a `surface: {file: ...}` would be, with the fields of
//! `preprocess` ([`super::preprocess`]; a twin's files are by default levelled by a plane and
//! filled, since the texture is measured on complete maps); its texture is measured (correlation
//! lengths along x and y at the ISO ACF threshold 0.2, extrapolated when the map is too short to
//! show the crossing; Hurst exponent from the PSD slope); correlation lengths are fitted as power
//! laws of Sq and the Hurst exponent as linear in ln Sq across the files
//! (`surface::twins::fit_twin_model`); a periodic synthetic surface is generated at the requested
//! Sq — or at the files' (geometric mean) Sq with `sq: measured` — with the predicted statistics.
//! Extrapolation, clamping and the fit's quality are reported as columns ([`twin_metrics`]).

use serde::Deserialize;

use crate::engine::node::NodeError;
use crate::engine::study::{FromParamValue, Param, ResolveContext, SpecError};
use crate::engine::value::{Field, ParamValue};
use std::f64::consts::PI;

use crate::surface::spectral::{HurstFitOptions, ISO_ACF_THRESHOLD};
use crate::surface::synthetic::MIN_SQ;
use crate::surface::twins::{
    fit_twin_model, format_micrometres, measure_texture, synthetic_twin, CorrelationMethod,
    MeasuredTexture, SyntheticTwin, TextureOptions, TwinError, TwinGrid, TwinModel, TwinWarning,
};
use crate::surface::HeightMap;
use crate::units::{Dimension, Length, Quantity};

use super::measured::{MeasuredFile, MeasuredSource};
use super::preprocess::{PreprocessDefaults, PreprocessSpec, Preprocessing};
use super::synthetic::{positive_length, MAX_GRID_SIDE};
use super::twin_band::{band_fields, band_of, HurstBand};
use super::{SurfaceSource, SurfaceTask};

/// `surface: {twin: {...}}`.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TwinSpec {
    /// Measured topography files the twin's statistics are fitted to (relative to the study file).
    pub of: Vec<Param<String>>,
    /// Preprocessing of every measured file, the fields of `surface: {file: ...}` (lateral
    /// calibration, crop, decimate, form removal, S- and L-filter, filling). Defaults here:
    /// `form_degree: 1` (a plane) and `fill_missing: true`.
    #[serde(default)]
    pub preprocess: Option<Box<PreprocessSpec>>,
    /// Wavelength band `[λ_short, λ_long]` of the Hurst fit to the files' PSD. Default: found per
    /// file, the widest band between the S-filter (or 2 pixels) and the L-filter (or half the
    /// map) over which the PSD is a power law (R² ≥ 0.95, every log bin within max(0.1 decade,
    /// 3 standard errors) of the line, at least 0.5 decade, falling faster than noise: H > 0).
    /// Give it to
    /// override the search (`auto`: search, e.g. in a parameter axis beside given bands); a
    /// given band must give 0 < H ≤ 1.5.
    #[serde(default)]
    pub hurst_band: Option<Param<HurstBand>>,
    /// Target Sq of the twin (length > 0), or `measured`: the geometric mean Sq of the
    /// preprocessed files (the twin of one file at that file's Sq).
    pub sq: Param<TwinSq>,
    /// Grid points `[nx, ny]` of the twin.
    pub grid: [Param<usize>; 2],
    /// Physical size `[Lx, Ly]` of the twin.
    pub size: [Param<Quantity<Length>>; 2],
    /// Optional short-wavelength cutoff of the twin's spectrum.
    #[serde(default)]
    pub short_wavelength_cutoff: Option<Param<Quantity<Length>>>,
    /// Seed of the twin's random phases.
    pub seed: Param<u64>,
}

/// The Sq a twin is generated at.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TwinSq {
    /// m
    Given(f64),
    /// The geometric mean Sq of the measured files.
    Measured,
}

impl FromParamValue for TwinSq {
    fn from_param(value: &ParamValue) -> Result<Self, String> {
        if let ParamValue::Text(t) = value {
            if t == "measured" {
                return Ok(Self::Measured);
            }
        }
        let q = Quantity::<Length>::from_param(value)
            .map_err(|e| format!("{e} (or `measured`: the files' Sq)"))?;
        positive_length(&q)?;
        Ok(Self::Given(q.si()))
    }
}

impl schemars::JsonSchema for TwinSq {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "TwinSq".into()
    }

    fn json_schema(generator: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let length = generator.subschema_for::<Quantity<Length>>();
        schemars::json_schema!({
            "description": "A length, e.g. '1.19 um', or 'measured' (the files' geometric mean Sq).",
            "anyOf": [length, {"const": "measured"}]
        })
    }
}

/// A resolved twin.
#[derive(Debug, Clone)]
pub(crate) struct TwinSource {
    measured: Vec<MeasuredFile>,
    preprocessing: Preprocessing,
    /// `[λ_short, λ_long]` of the Hurst fit (m); `None`: found per file ([`band_of`]).
    hurst_band: Option<[f64; 2]>,
    sq: TwinSq,
    grid: TwinGrid,
}

impl TwinSpec {
    pub(super) fn instantiate(&self, ctx: &ResolveContext<'_>) -> Result<SurfaceTask, SpecError> {
        if self.of.is_empty() {
            return Err(SpecError {
                location: self.sq.location(),
                field: String::from("twin.of"),
                message: String::from("needs at least one measured file"),
            });
        }
        let measured = self
            .of
            .iter()
            .enumerate()
            .map(|(i, p)| MeasuredFile::resolve(ctx, p, &format!("twin.of[{i}]")))
            .collect::<Result<Vec<_>, _>>()?;
        let none = PreprocessSpec::default();
        let preprocessing = self
            .preprocess
            .as_ref()
            .map_or(&none, |p| p.as_ref())
            .preprocess_fields()
            .resolve(
                ctx,
                self.sq.location(),
                "twin.preprocess",
                PreprocessDefaults::TWIN,
            )?;
        let sq = ctx.resolve(&self.sq, "twin.sq")?;
        let grid = self.grid(ctx)?;
        if let TwinSq::Given(v) = sq {
            let max_sq = grid.lx.min(grid.ly);
            if !(MIN_SQ..=max_sq).contains(&v) {
                return Err(SpecError {
                    location: self.sq.location(),
                    field: String::from("twin.sq"),
                    message: format!(
                        "{v:e} m is out of range: expected {MIN_SQ:e} m ≤ Sq ≤ the shorter side \
                         of the twin, {max_sq:e} m (see synthetic.sq in docs/study-format.md)"
                    ),
                });
            }
        }
        Ok(SurfaceTask {
            source: SurfaceSource::Twin(TwinSource {
                measured,
                preprocessing,
                hurst_band: self.hurst_band(ctx)?,
                sq,
                grid,
            }),
        })
    }

    /// `[λ_short, λ_long]`, both > 0, ascending; `None` for `auto` or no field.
    fn hurst_band(&self, ctx: &ResolveContext<'_>) -> Result<Option<[f64; 2]>, SpecError> {
        let Some(param) = &self.hurst_band else {
            return Ok(None);
        };
        let HurstBand::Given([short, long]) = ctx.resolve(param, "twin.hurst_band")? else {
            return Ok(None);
        };
        if short >= long {
            return Err(SpecError {
                location: param.location(),
                field: String::from("twin.hurst_band"),
                message: format!(
                    "[{}, {}] must ascend: [shortest, longest wavelength]",
                    format_micrometres(short),
                    format_micrometres(long)
                ),
            });
        }
        Ok(Some([short, long]))
    }

    fn grid(&self, ctx: &ResolveContext<'_>) -> Result<TwinGrid, SpecError> {
        let side = |n: &usize| {
            if (2..=MAX_GRID_SIDE).contains(n) {
                Ok(())
            } else {
                Err(format!(
                    "is out of range: grid sides must be between 2 and {MAX_GRID_SIDE}"
                ))
            }
        };
        let length = |p: &Param<Quantity<Length>>, field: &str| {
            Ok(ctx.resolve_checked(p, field, positive_length)?.si())
        };
        Ok(TwinGrid {
            nx: ctx.resolve_checked(&self.grid[0], "twin.grid[0]", side)?,
            ny: ctx.resolve_checked(&self.grid[1], "twin.grid[1]", side)?,
            lx: length(&self.size[0], "twin.size[0]")?,
            ly: length(&self.size[1], "twin.size[1]")?,
            short_wavelength_cutoff: self
                .short_wavelength_cutoff
                .as_ref()
                .map(|p| length(p, "twin.short_wavelength_cutoff"))
                .transpose()?,
            seed: ctx.resolve(&self.seed, "twin.seed")?,
        })
    }
}

impl TwinSource {
    /// The key fields of a twin: the measured files by content, their preprocessing, the target
    /// Sq and the twin's grid and seed, in SI.
    pub(super) fn key_fields(&self) -> Vec<Field> {
        let Self {
            measured,
            preprocessing,
            hurst_band,
            sq,
            grid,
        } = self;
        let TwinGrid {
            nx,
            ny,
            lx,
            ly,
            short_wavelength_cutoff,
            seed,
        } = *grid;
        let mut fields = vec![Field::text("source", "twin")];
        fields.extend(preprocessing.key_fields());
        for (i, m) in measured.iter().enumerate() {
            fields.push(Field::text(format!("twin_of_{i}_blake3"), m.content_hash()));
        }
        if let Some([short, long]) = hurst_band {
            fields.push(Field::float("hurst_band_short", *short, Dimension::Length));
            fields.push(Field::float("hurst_band_long", *long, Dimension::Length));
        }
        fields.push(match sq {
            TwinSq::Given(v) => Field::float("sq_target", *v, Dimension::Length),
            TwinSq::Measured => Field::text("sq_target", "measured"),
        });
        fields.extend([
            Field::int("nx", nx as i64),
            Field::int("ny", ny as i64),
            Field::float("lx", lx, Dimension::Length),
            Field::float("ly", ly, Dimension::Length),
            Field::int("seed", seed as i64),
        ]);
        if let Some(c) = short_wavelength_cutoff {
            fields.push(Field::float(
                "short_wavelength_cutoff",
                c,
                Dimension::Length,
            ));
        }
        fields
    }

    /// Measures, fits and generates; returns the twin, its extra metrics and the sentences that
    /// flag its row (a file's height unit assumed).
    pub(super) fn generate(&self) -> Result<(HeightMap, Vec<Field>, Vec<String>), NodeError> {
        let mut textures = Vec::with_capacity(self.measured.len());
        let mut bands = Vec::with_capacity(self.measured.len());
        let mut flags = Vec::new();
        for file in &self.measured {
            let source = MeasuredSource::new(file.clone(), self.preprocessing);
            let loaded = source.load()?;
            flags.extend(loaded.flag);
            let map = loaded.map;
            // An ACF that does not decay is the more basic fault (and names its fix): report
            // it rather than the band search's failure.
            let band = band_of(&map, self.hurst_band, &self.preprocessing, file.path()).map_err(
                |band_error| match measure_texture(&map, &TextureOptions::default()) {
                    Err(e @ TwinError::NoDecay { .. }) => texture_error(&e, file),
                    _ => band_error,
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
        let model =
            fit_twin_model(&textures).map_err(|e| NodeError::new(format!("twin fit: {e}")))?;
        let sq = match self.sq {
            TwinSq::Given(v) => v,
            TwinSq::Measured => model.sq_reference,
        };
        let twin = synthetic_twin(&model, sq, &self.grid, ISO_ACF_THRESHOLD)
            .map_err(|e| generation_error(&e))?;
        let mut metrics = twin_metrics(&textures, &model, &twin);
        let names: Vec<String> = self
            .measured
            .iter()
            .map(|f| {
                f.path()
                    .file_name()
                    .map_or_else(String::new, |n| n.to_string_lossy().into_owned())
            })
            .collect();
        metrics.extend(band_fields(&bands, self.hurst_band.is_some(), &names));
        Ok((twin.surface, metrics, flags))
    }

    /// Memory of the largest step (measured files are read one at a time).
    pub(super) fn memory_estimate(&self) -> u64 {
        let synthetic = (self.grid.nx as u64) * (self.grid.ny as u64) * 8 * 6;
        self.measured
            .iter()
            .map(MeasuredFile::memory_estimate)
            .max()
            .unwrap_or(0)
            .max(synthetic)
    }
}

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
             measure a larger area",
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
         and the instrument's noise, below the L-filter)",
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
        length("twin_sq", p.sq),
        length("twin_correlation_length_x", p.correlation_length_x),
        length("twin_correlation_length_y", p.correlation_length_y),
        n("twin_hurst", p.hurst),
        n("twin_hurst_predicted", p.hurst_predicted),
        Field::bool("twin_extrapolated", extrapolated),
        Field::bool("twin_hurst_clamped", clamped),
        Field::text("twin_warnings", sentences.join("; ")),
        length("twin_measured_sq_min", model.sq_range.0),
        length("twin_measured_sq_max", model.sq_range.1),
        Field::int("twin_measured_files", model.surfaces as i64),
        Field::text(
            "twin_correlation_x_methods",
            methods(textures, |t| t.method_x),
        ),
        Field::text(
            "twin_correlation_y_methods",
            methods(textures, |t| t.method_y),
        ),
        n(
            "twin_min_hurst_fit_r2",
            textures
                .iter()
                .map(|t| t.hurst_r_squared)
                .fold(f64::INFINITY, f64::min),
        ),
    ];
    for (name, fit) in [
        ("correlation_length_x", model.correlation_length_x.fit),
        ("correlation_length_y", model.correlation_length_y.fit),
        ("hurst", model.hurst.fit),
    ] {
        fields.push(Field::float(
            format!("twin_fit_rms_{name}"),
            fit.rms_residual,
            Dimension::Dimensionless,
        ));
        // R² needs three or more files: the column is empty otherwise.
        if let Some(r2) = fit.r_squared {
            fields.push(Field::float(
                format!("twin_fit_r2_{name}"),
                r2,
                Dimension::Dimensionless,
            ));
        }
    }
    fields.push(Field::int(
        "twin_calibration_iterations",
        twin.iterations as i64,
    ));
    fields.push(n("twin_calibration_residual", twin.residual));
    fields
}

/// How the files' correlation lengths along one axis were obtained, e.g.
/// `acf_crossing: 2; stretched_exponential_fit: 1 (ACF down to 0.31)`.
fn methods(
    textures: &[MeasuredTexture],
    axis: fn(&MeasuredTexture) -> CorrelationMethod,
) -> String {
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
    let mut text = format!("acf_crossing: {crossing}");
    if !reached.is_empty() {
        let highest = reached.iter().copied().fold(0.0, f64::max);
        text.push_str(&format!(
            "; stretched_exponential_fit: {} (ACF down to {highest:.2} at most)",
            reached.len()
        ));
    }
    text
}
