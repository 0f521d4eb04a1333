//! The `surface` node kind: a synthetic self-affine surface or a measured topography file, and
//! its statistics. Table `surfaces`; array `heights` (m, `[[iy, ix]]`) for downstream nodes.

use serde::Deserialize;

use crate::engine::artifact::Artifact;
use crate::engine::node::{ArrayStorage, NodeError, NodeTask};
use crate::engine::study::{ResolveContext, SpecError};
use crate::engine::value::Field;
use crate::nodes::surface_view::HEIGHTS;
use crate::nodes::validity;
use crate::surface::spectral::{InverseTransform, Periodogram};
use crate::surface::synthetic::{generate_synthetic_surface_with_spectrum, SyntheticSurfaceSpec};
use crate::surface::{amplitude_statistics, Boundary, HeightMap};
use crate::vocabulary::surface_metrics::LATERAL_SCALE_WARNING;

mod height_unit;
mod lateral_scale;
mod measured;
mod metrics;
mod preprocess;
mod synthetic;
mod twin;
mod twin_band;
mod twin_self_affine;
mod twin_source;
mod twin_spectrum;

pub use height_unit::{apply_height_unit, height_unit_rule, HeightUnitSource};
pub use measured::FileSpec;
pub use synthetic::{AnisotropySpec, SyntheticSpec};
pub use twin::TwinSpec;

use lateral_scale::lateral_scale_warning;
pub use lateral_scale::{apply_lateral_calibration, LateralCalibration};
use measured::MeasuredSource;
use twin_source::TwinSource;

pub(crate) use crate::vocabulary::kinds::SURFACE as KIND;
/// The column that says where a file surface's height unit came from (`file`, `study`,
/// `assumed`).
pub(crate) use crate::vocabulary::surface_parameters::HEIGHT_UNIT_SOURCE;
pub(crate) use crate::vocabulary::tables::SURFACES as TABLE;

/// Implementation version of the `surface` kind. Bump whenever the generated heights or the
/// computed statistics change, so stale cache entries are never reused (8: the validity rules
/// fail impossible values and flag heights beyond the field of view; 9: the ISO 25178-2
/// functional and volume parameters and the material ratio table, `height_unit_source` instead
/// of `height_unit_from_file`, a flag when a file's height unit is assumed; a twin without
/// `hurst_band` finds its band per file and reports it; 10: an MNT file's mask image, not a
/// count of 0, marks its missing points; 11: a synthetic surface's spectra come from its
/// synthesized modes, not a transform of its heights, and the Hurst fit leaves out PSD points at
/// round-off level; 12: a twin's `twin_warnings`, `twin_hurst_bands`, `twin_measured_bands` and
/// `twin_correlation_x/y_methods` are lists of texts, no longer texts joined by "; "; 13: the
/// readers refuse an rms slope above 100 from a file's scales and a binary SDF whose bytes after
/// the data are no text trailer, so a cached surface of such a file is not reused).
pub const SURFACE_KIND_VERSION: u32 = 13;

/// Synthetic surfaces with more points than this (1024², 8 MB of heights) are not stored in the
/// cache but regenerated when a dependant needs their heights.
pub const REGENERATE_ABOVE_POINTS: usize = 1 << 20;

/// `surface:` — where the heights come from.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum SurfaceSpec {
    /// A periodic self-affine Gaussian random surface by spectral synthesis.
    Synthetic(SyntheticSpec),
    /// A measured topography file, optionally cropped, levelled and filtered.
    File(FileSpec),
    /// A synthetic twin of measured surfaces at a new Sq.
    Twin(TwinSpec),
}

impl SurfaceSpec {
    pub(crate) fn instantiate(&self, ctx: &ResolveContext<'_>) -> Result<SurfaceTask, SpecError> {
        match self {
            SurfaceSpec::Synthetic(s) => s.instantiate(ctx),
            SurfaceSpec::File(f) => f.instantiate(ctx),
            SurfaceSpec::Twin(t) => t.instantiate(ctx),
        }
    }
}

/// A resolved surface node.
#[derive(Debug, Clone)]
pub struct SurfaceTask {
    pub(crate) source: SurfaceSource,
}

#[derive(Debug, Clone)]
pub(crate) enum SurfaceSource {
    Synthetic(SyntheticSurfaceSpec),
    Measured(MeasuredSource),
    Twin(TwinSource),
}

/// The heights of a surface node and what their source says of them.
struct SourceHeights {
    map: HeightMap,
    boundary: Boundary,
    /// Metrics of the source itself (a twin's fitted statistics, where a file's height unit came
    /// from).
    metrics: Vec<Field>,
    /// Sentences that flag the row (a height unit assumed).
    flags: Vec<String>,
    /// The unwindowed periodogram and the inverse transform planned for the grid, where the
    /// source has them (a synthetic surface's modes and its synthesis).
    spectrum: Option<(Periodogram, InverseTransform)>,
}

/// Peak bytes per point of a synthetic surface node (and of a twin's grid): the heights, their
/// complex half spectrum and the statistics' spectra and work arrays, beside
/// [`STATISTICS_FIXED_BYTES`]; an upper bound of the process's peak less its base (figures:
/// docs/robustness.md, "Memory").
const SYNTHETIC_BYTES_PER_POINT: u64 = 4 * 8;

/// Peak bytes of every surface node whatever its grid: the statistics' tables (PSD, ACF,
/// material ratio, summits) and storing them in the cache.
const STATISTICS_FIXED_BYTES: u64 = 24 << 20;

impl SurfaceTask {
    /// The number of points of the heights (for a measured file an upper bound, before it is
    /// read), for the memory estimates of the nodes downstream.
    pub(crate) fn points(&self) -> u64 {
        match &self.source {
            SurfaceSource::Synthetic(s) => (s.nx as u64) * (s.ny as u64),
            SurfaceSource::Measured(m) => m.points(),
            SurfaceSource::Twin(t) => t.points(),
        }
    }

    /// Generates or reads the heights; says whether the map is periodic and adds any metrics of
    /// the source itself and the sentences that flag its row.
    fn heights(&self) -> Result<SourceHeights, NodeError> {
        match &self.source {
            SurfaceSource::Synthetic(spec) => generate_synthetic_surface_with_spectrum(spec)
                .map(|(map, p, transform)| SourceHeights {
                    map,
                    boundary: Boundary::Periodic,
                    metrics: Vec::new(),
                    flags: Vec::new(),
                    spectrum: Some((p, transform)),
                })
                .map_err(|e| NodeError::new(e.to_string())),
            SurfaceSource::Measured(m) => m.load().map(|p| {
                let source = Field::text(HEIGHT_UNIT_SOURCE, p.height_unit_source.name());
                SourceHeights {
                    map: p.map,
                    boundary: Boundary::Open,
                    metrics: vec![source],
                    flags: p.flag.into_iter().collect(),
                    spectrum: None,
                }
            }),
            SurfaceSource::Twin(t) => t.generate().map(|(map, metrics, flags)| SourceHeights {
                map,
                boundary: Boundary::Periodic,
                metrics,
                flags,
                spectrum: None,
            }),
        }
    }
}

/// What a surface node computes from `map`, the one computation the node and the Python package
/// share: the `surfaces` row's metrics (amplitude, hybrid, functional, spectral and summit
/// statistics; see `metrics`), its long tables (`psd`, `acf`, `summits`, the material ratio
/// curve) and the flag of heights beyond the field of view, after the spacing is checked; and
/// the lateral-scale warning (empty when the rms slope is plausible), which the node writes to
/// the row of a measured map. `boundary` is [`Boundary::Periodic`] for a synthetic map,
/// [`Boundary::Open`] for a measured one; `spectrum`, where the source has it without a
/// transform (a synthetic surface's modes and synthesis), is `map`'s unwindowed periodogram and
/// the inverse transform planned for its grid. The caller adds its own metrics and then checks the
/// artifact with [`validity::check_artifact`].
pub fn surface_artifact(
    map: &HeightMap,
    boundary: Boundary,
    spectrum: Option<(Periodogram, InverseTransform)>,
) -> Result<(Artifact, String), NodeError> {
    validity::check_fields(KIND, &metrics::spacing_fields(map))?;
    let report = metrics::surface_report(map, boundary, spectrum)?;
    let warning = lateral_scale_warning(report.sdq, map.dx(), map.dy());
    let flags = validity::cross::surface_size(
        report.sq,
        map.nx() as f64 * map.dx(),
        map.ny() as f64 * map.dy(),
    );
    let artifact = Artifact {
        metrics: report.metrics,
        tables: report.tables,
        flags: flags.into_iter().collect(),
        ..Artifact::default()
    };
    Ok((artifact, warning))
}

/// The checks a surface node makes of a map's scale, without the rest of its statistics (for
/// callers that take a map without a surface node: the Python package's contact and friction
/// functions): the spacing (a value the node fails is `Err`), then the rms slope Sdq and the
/// sentences that would flag heights beyond the field of view or warn of an implausible lateral
/// scale — the rules [`surface_artifact`] applies.
pub fn scale_checks(
    map: &HeightMap,
    boundary: Boundary,
) -> Result<(Option<f64>, Vec<String>), NodeError> {
    validity::check_fields(KIND, &metrics::spacing_fields(map))?;
    let a = amplitude_statistics(map, boundary)
        .map_err(|e| NodeError::new(format!("statistics: {e}")))?;
    let flags =
        validity::cross::surface_size(a.sq, map.nx() as f64 * map.dx(), map.ny() as f64 * map.dy())
            .into_iter()
            .chain(Some(lateral_scale_warning(a.sdq, map.dx(), map.dy())).filter(|w| !w.is_empty()))
            .collect();
    Ok((a.sdq, flags))
}

impl NodeTask for SurfaceTask {
    fn as_any(&self) -> &dyn std::any::Any {
        self
    }

    fn kind(&self) -> &'static str {
        KIND
    }

    fn version(&self) -> u32 {
        SURFACE_KIND_VERSION
    }

    fn table(&self) -> &'static str {
        TABLE
    }

    fn params(&self) -> Vec<Field> {
        match &self.source {
            SurfaceSource::Synthetic(spec) => synthetic::key_fields(spec),
            SurfaceSource::Measured(m) => m.key_fields(),
            SurfaceSource::Twin(t) => t.key_fields(),
        }
    }

    /// Synthetic heights above `REGENERATE_ABOVE_POINTS` (1024²) are regenerated from the key (about
    /// a second at 3512², where they take ~100 MB); smaller ones cost little to keep and stay
    /// readable by the report and numpy. Measured and twin surfaces depend on files that may
    /// move, so they are stored.
    fn array_storage(&self) -> ArrayStorage {
        match &self.source {
            SurfaceSource::Synthetic(s) if s.nx * s.ny > REGENERATE_ABOVE_POINTS => {
                ArrayStorage::Regenerate
            }
            _ => ArrayStorage::Store,
        }
    }

    fn memory_estimate(&self) -> u64 {
        let source = match &self.source {
            SurfaceSource::Synthetic(_) => self.points() * SYNTHETIC_BYTES_PER_POINT,
            SurfaceSource::Measured(m) => m.memory_estimate(),
            SurfaceSource::Twin(t) => t.memory_estimate(),
        };
        STATISTICS_FIXED_BYTES.saturating_add(source)
    }

    /// The heights' statistics, checked by [`validity`]: the spacing before any statistic is
    /// computed, every value after.
    fn compute(&self, _inputs: &[&Artifact]) -> Result<Artifact, NodeError> {
        let SourceHeights {
            map,
            boundary,
            metrics: source_metrics,
            flags: source_flags,
            spectrum,
        } = self.heights()?;
        let (mut artifact, warning) = surface_artifact(&map, boundary, spectrum)?;
        artifact.metrics.extend(source_metrics);
        if let SurfaceSource::Measured(_) = self.source {
            artifact
                .metrics
                .push(Field::text(LATERAL_SCALE_WARNING, warning));
        }
        artifact.flags = source_flags.into_iter().chain(artifact.flags).collect();
        let heights = map.into_heights().into_dyn();
        artifact.arrays = [(String::from(HEIGHTS), heights)].into_iter().collect();
        validity::check_artifact(KIND, &mut artifact)?;
        Ok(artifact)
    }
}
