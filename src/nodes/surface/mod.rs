//! The `surface` node kind: a synthetic self-affine surface or a measured topography file, and
//! its statistics. Table `surfaces`; array `heights` (m, `[[iy, ix]]`) for downstream nodes.

use serde::Deserialize;

use crate::engine::artifact::Artifact;
use crate::engine::node::{NodeError, NodeTask};
use crate::engine::study::{ResolveContext, SpecError};
use crate::engine::value::Field;
use crate::surface::synthetic::{generate_synthetic_surface, SyntheticSurfaceSpec};
use crate::surface::{amplitude_statistics, Boundary, HeightMap};
use crate::units::Dimension;

mod measured;
mod synthetic;

pub use measured::FileSpec;
pub use synthetic::{AnisotropySpec, SyntheticSpec};

use measured::MeasuredSource;

pub(crate) const KIND: &str = "surface";
pub(crate) const TABLE: &str = "surfaces";
/// Name of the height array (m, `[[iy, ix]]`) in the artifact.
pub(crate) const HEIGHTS: &str = "heights";

/// Implementation version of the `surface` kind. Bump whenever the generated heights or the
/// computed statistics change, so stale cache entries are never reused.
pub const SURFACE_KIND_VERSION: u32 = 1;

/// `surface:` — where the heights come from.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum SurfaceSpec {
    /// A periodic self-affine Gaussian random surface by spectral synthesis.
    Synthetic(SyntheticSpec),
    /// A measured topography file, optionally cropped, levelled and filtered.
    File(FileSpec),
}

impl SurfaceSpec {
    pub(crate) fn instantiate(&self, ctx: &ResolveContext<'_>) -> Result<SurfaceTask, SpecError> {
        match self {
            SurfaceSpec::Synthetic(s) => s.instantiate(ctx),
            SurfaceSpec::File(f) => f.instantiate(ctx),
        }
    }
}

/// A resolved surface node.
#[derive(Debug, Clone)]
pub struct SurfaceTask {
    pub(crate) params: Vec<Field>,
    pub(crate) source: SurfaceSource,
}

#[derive(Debug, Clone)]
pub(crate) enum SurfaceSource {
    Synthetic(SyntheticSurfaceSpec),
    Measured(MeasuredSource),
}

impl SurfaceTask {
    /// Generates or reads the heights, and says whether the map is periodic.
    fn heights(&self) -> Result<(HeightMap, Boundary), NodeError> {
        match &self.source {
            SurfaceSource::Synthetic(spec) => generate_synthetic_surface(spec)
                .map(|m| (m, Boundary::Periodic))
                .map_err(|e| NodeError::new(e.to_string())),
            SurfaceSource::Measured(m) => m.load().map(|map| (map, Boundary::Open)),
        }
    }
}

/// The `surfaces` table metrics of a height map (ISO 25178-2 amplitude and hybrid parameters).
fn surface_metrics(map: &HeightMap, boundary: Boundary) -> Result<Vec<Field>, NodeError> {
    let a = amplitude_statistics(map, boundary)
        .map_err(|e| NodeError::new(format!("statistics: {e}")))?;
    let len = |name: &str, v: f64| Field::float(name, v, Dimension::Length);
    let mut metrics = vec![
        Field::int("grid_nx", map.nx() as i64),
        Field::int("grid_ny", map.ny() as i64),
        len("dx", map.dx()),
        len("dy", map.dy()),
        Field::int("missing_points", a.missing_count as i64),
        len("sq", a.sq),
        len("sa", a.sa),
        len("sp", a.sp),
        len("sv", a.sv),
        len("sz", a.sz),
    ];
    // Undefined statistics (a flat map has no skewness) are left out: the cell is null.
    let optional = [
        ("ssk", a.ssk),
        ("sku", a.sku),
        ("sdq", a.sdq),
        ("sdr_percent", a.sdr_percent),
    ];
    metrics.extend(
        optional
            .into_iter()
            .filter_map(|(name, v)| v.map(|v| Field::float(name, v, Dimension::Dimensionless))),
    );
    Ok(metrics)
}

impl NodeTask for SurfaceTask {
    fn kind(&self) -> &'static str {
        KIND
    }

    fn version(&self) -> u32 {
        SURFACE_KIND_VERSION
    }

    fn table(&self) -> &'static str {
        TABLE
    }

    fn params(&self) -> &[Field] {
        &self.params
    }

    fn memory_estimate(&self) -> u64 {
        match &self.source {
            // heights + complex half spectrum + statistics work arrays ≈ 6 f64 per point.
            SurfaceSource::Synthetic(s) => (s.nx as u64) * (s.ny as u64) * 8 * 6,
            SurfaceSource::Measured(m) => m.memory_estimate(),
        }
    }

    fn compute(&self, _inputs: &[&Artifact]) -> Result<Artifact, NodeError> {
        let (map, boundary) = self.heights()?;
        let metrics = surface_metrics(&map, boundary)?;
        let heights = map.into_heights().into_dyn();
        Ok(Artifact {
            metrics,
            arrays: [(String::from(HEIGHTS), heights)].into_iter().collect(),
            tables: Default::default(),
        })
    }
}
