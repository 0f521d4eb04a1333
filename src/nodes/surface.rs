//! The `surface` node kind: a synthetic self-affine surface (or, later, a measured file) and its
//! statistics. Table `surfaces`; array `heights` (m, `[[iy, ix]]`) for downstream nodes.

use ndarray::Ix2;
use serde::Deserialize;

use crate::engine::artifact::Artifact;
use crate::engine::node::{NodeError, NodeTask};
use crate::engine::study::{Param, ResolveContext, SpecError};
use crate::engine::value::Field;
use crate::surface::HeightMap;
use crate::units::{Angle, Dimension, Length, Quantity};

pub(crate) const KIND: &str = "surface";
pub(crate) const TABLE: &str = "surfaces";

/// Implementation version of the `surface` kind. Bump whenever the generated heights or the
/// computed statistics change, so stale cache entries are never reused.
pub const SURFACE_KIND_VERSION: u32 = 1;

/// Largest grid side accepted (a 16384² f64 map is 2 GiB).
const MAX_GRID_SIDE: usize = 16384;

/// `surface:` — where the heights come from.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum SurfaceSpec {
    /// A periodic self-affine Gaussian random surface by spectral synthesis.
    Synthetic(SyntheticSpec),
}

/// `surface: {synthetic: {...}}`.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SyntheticSpec {
    /// Grid points `[nx, ny]`, each ≥ 2.
    pub grid: [Param<usize>; 2],
    /// Physical size `[Lx, Ly]` (lengths, e.g. `[1 mm, 1 mm]`).
    pub size: [Param<Quantity<Length>>; 2],
    /// Target RMS height Sq (length > 0); exact after normalisation.
    pub sq: Param<Quantity<Length>>,
    /// Hurst exponent H in (0, 1]: PSD ∝ q^-(2+2H) above the roll-off.
    pub hurst: Param<f64>,
    /// Roll-off wavelength λ_r (length > 0): the PSD is flat for wavelengths longer than this.
    pub correlation_length: Param<Quantity<Length>>,
    /// Optional short-wavelength cutoff λ_s: no content at wavelengths shorter than this.
    #[serde(default)]
    pub short_wavelength_cutoff: Option<Param<Quantity<Length>>>,
    /// Optional directionality: `{ratio: r, angle: a}` — the correlation length along the
    /// direction at angle `a` from x is `r` times that across it (ground surfaces: r ≫ 1).
    #[serde(default)]
    pub anisotropy: Option<AnisotropySpec>,
    /// Seed of the portable ChaCha generator: the same seed gives the same surface everywhere.
    pub seed: Param<u64>,
}

/// Directionality of a synthetic surface.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AnisotropySpec {
    /// Ratio of the correlation lengths along and across the lay direction (≥ 1).
    pub ratio: Param<f64>,
    /// Angle of the lay direction from the x axis (e.g. `0 deg`).
    #[serde(default)]
    pub angle: Option<Param<Quantity<Angle>>>,
}

fn positive<T: Copy + Into<f64>>(unit: &'static str) -> impl Fn(&T) -> Result<(), String> {
    move |v: &T| {
        let x: f64 = (*v).into();
        if x > 0.0 && x.is_finite() {
            Ok(())
        } else {
            Err(format!("is out of range: must be > 0 {unit}"))
        }
    }
}

impl From<Quantity<Length>> for f64 {
    fn from(q: Quantity<Length>) -> f64 {
        q.si()
    }
}

impl SurfaceSpec {
    pub(crate) fn instantiate(&self, ctx: &ResolveContext<'_>) -> Result<SurfaceTask, SpecError> {
        match self {
            SurfaceSpec::Synthetic(s) => s.instantiate(ctx),
        }
    }
}

impl SyntheticSpec {
    fn instantiate(&self, ctx: &ResolveContext<'_>) -> Result<SurfaceTask, SpecError> {
        let grid_check = |n: &usize| {
            if (2..=MAX_GRID_SIDE).contains(n) {
                Ok(())
            } else {
                Err(format!("is out of range: grid sides must be between 2 and {MAX_GRID_SIDE}"))
            }
        };
        let nx = ctx.resolve_checked(&self.grid[0], "grid[0]", grid_check)?;
        let ny = ctx.resolve_checked(&self.grid[1], "grid[1]", grid_check)?;
        let lx = ctx.resolve_checked(&self.size[0], "size[0]", positive("m"))?.si();
        let ly = ctx.resolve_checked(&self.size[1], "size[1]", positive("m"))?.si();
        let sq = ctx.resolve_checked(&self.sq, "sq", positive("m"))?.si();
        let hurst = ctx.resolve_checked(&self.hurst, "hurst", |h: &f64| {
            if *h > 0.0 && *h <= 1.0 {
                Ok(())
            } else {
                Err(String::from("is out of range: the Hurst exponent must be in (0, 1]"))
            }
        })?;
        let correlation_length = ctx
            .resolve_checked(&self.correlation_length, "correlation_length", positive("m"))?
            .si();
        let mut params = vec![
            Field::int("nx", nx as i64),
            Field::int("ny", ny as i64),
            Field::float("lx", lx, Dimension::Length),
            Field::float("ly", ly, Dimension::Length),
            Field::float("sq_target", sq, Dimension::Length),
            Field::float("hurst", hurst, Dimension::Dimensionless),
            Field::float("correlation_length", correlation_length, Dimension::Length),
        ];
        let cutoff = match &self.short_wavelength_cutoff {
            Some(p) => {
                let c = ctx
                    .resolve_checked(p, "short_wavelength_cutoff", positive("m"))?
                    .si();
                params.push(Field::float("short_wavelength_cutoff", c, Dimension::Length));
                Some(c)
            }
            None => None,
        };
        let anisotropy = match &self.anisotropy {
            Some(a) => {
                let ratio = ctx.resolve_checked(&a.ratio, "anisotropy.ratio", |r: &f64| {
                    if *r >= 1.0 && r.is_finite() {
                        Ok(())
                    } else {
                        Err(String::from("is out of range: the ratio must be ≥ 1 (swap the angle by 90 deg instead)"))
                    }
                })?;
                let angle = match &a.angle {
                    Some(p) => ctx.resolve(p, "anisotropy.angle")?.si(),
                    None => 0.0,
                };
                params.push(Field::float("anisotropy_ratio", ratio, Dimension::Dimensionless));
                params.push(Field::float("anisotropy_angle", angle, Dimension::Angle));
                Some((ratio, angle))
            }
            None => None,
        };
        let seed = ctx.resolve(&self.seed, "seed")?;
        params.push(Field::int("seed", seed as i64));
        params.push(Field::text("source", "synthetic"));
        Ok(SurfaceTask {
            params,
            source: SurfaceSource::Synthetic {
                nx,
                ny,
                lx,
                ly,
                sq,
                hurst,
                correlation_length,
                cutoff,
                anisotropy,
                seed,
            },
        })
    }
}

/// A resolved surface node.
#[derive(Debug, Clone)]
pub struct SurfaceTask {
    params: Vec<Field>,
    source: SurfaceSource,
}

#[derive(Debug, Clone)]
enum SurfaceSource {
    Synthetic {
        nx: usize,
        ny: usize,
        lx: f64,
        ly: f64,
        sq: f64,
        hurst: f64,
        correlation_length: f64,
        cutoff: Option<f64>,
        anisotropy: Option<(f64, f64)>,
        seed: u64,
    },
}

impl SurfaceTask {
    fn heights(&self) -> Result<HeightMap, NodeError> {
        match &self.source {
            SurfaceSource::Synthetic { .. } => Err(NodeError::new("synthetic surfaces are not wired yet")),
        }
    }
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
            SurfaceSource::Synthetic { nx, ny, .. } => (*nx as u64) * (*ny as u64) * 8 * 6,
        }
    }

    fn compute(&self, _inputs: &[&Artifact]) -> Result<Artifact, NodeError> {
        let map = self.heights()?;
        let mut artifact = Artifact::default();
        artifact.metrics.push(Field::float("dx", map.dx(), Dimension::Length));
        artifact.metrics.push(Field::float("dy", map.dy(), Dimension::Length));
        artifact.arrays.insert(
            String::from("heights"),
            map.into_heights().into_dimensionality::<ndarray::IxDyn>().map_err(|e| NodeError::new(e.to_string()))?,
        );
        let _ = Ix2(0, 0);
        Ok(artifact)
    }
}
