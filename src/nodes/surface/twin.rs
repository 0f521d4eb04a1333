//! `surface: {twin: {...}}`: a synthetic twin of measured surfaces at a new Sq (the workflow's
//! method for parameter studies).
//!
//! Each measured file is levelled (polynomial form of `form_degree`, default 1 = plane) and its
//! missing points filled; its texture is measured (correlation lengths along x and y at the ISO
//! ACF threshold 0.2, Hurst exponent from the PSD slope); correlation lengths are fitted as power
//! laws of Sq and the Hurst exponent as linear in ln Sq across the files
//! (`surface::twins::fit_twin_model`); a periodic synthetic surface is generated at the requested
//! Sq with the predicted statistics. A requested Sq outside the measured range is extrapolated and
//! reported in the `twin_warnings` column.

use serde::Deserialize;

use crate::engine::node::NodeError;
use crate::engine::study::{Param, ResolveContext, SpecError};
use crate::engine::value::Field;
use crate::surface::spectral::ISO_ACF_THRESHOLD;
use crate::surface::twins::{
    fit_twin_model, measure_texture, synthetic_twin, TextureOptions, TwinGrid,
};
use crate::surface::HeightMap;
use crate::units::{Dimension, Length, Quantity};

use super::measured::MeasuredSource;
use super::synthetic::positive_length;
use super::{SurfaceSource, SurfaceTask};

/// `surface: {twin: {...}}`.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TwinSpec {
    /// Measured topography files the twin's statistics are fitted to (relative to the study file).
    pub of: Vec<Param<String>>,
    /// Polynomial form removed from each measured file before its texture is measured (default 1).
    #[serde(default)]
    pub form_degree: Option<Param<usize>>,
    /// Target Sq of the twin (length > 0).
    pub sq: Param<Quantity<Length>>,
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

/// A resolved twin.
#[derive(Debug, Clone)]
pub(crate) struct TwinSource {
    /// The measured files, levelled by `form_degree` and filled.
    measured: Vec<MeasuredSource>,
    form_degree: usize,
    sq: f64,
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
        let form_degree = match &self.form_degree {
            Some(p) => ctx.resolve(p, "twin.form_degree")?,
            None => 1,
        };
        let mut measured = Vec::with_capacity(self.of.len());
        for (i, p) in self.of.iter().enumerate() {
            let field = format!("twin.of[{i}]");
            let written: String = ctx.resolve(p, &field)?;
            let path = ctx.study_dir().join(&written);
            let hash = ctx.file_content_hash(&path).map_err(|m| SpecError {
                location: p.location(),
                field: field.clone(),
                message: format!("{m}; paths are relative to the study file"),
            })?;
            measured.push(MeasuredSource::levelled_and_filled(path, hash, form_degree));
        }
        let sq = ctx
            .resolve_checked(&self.sq, "twin.sq", positive_length)?
            .si();
        let side = |n: &usize| {
            if *n >= 2 {
                Ok(())
            } else {
                Err(String::from("is out of range: grid sides must be ≥ 2"))
            }
        };
        let nx = ctx.resolve_checked(&self.grid[0], "twin.grid[0]", side)?;
        let ny = ctx.resolve_checked(&self.grid[1], "twin.grid[1]", side)?;
        let lx = ctx
            .resolve_checked(&self.size[0], "twin.size[0]", positive_length)?
            .si();
        let ly = ctx
            .resolve_checked(&self.size[1], "twin.size[1]", positive_length)?
            .si();
        let cutoff = match &self.short_wavelength_cutoff {
            Some(p) => Some(
                ctx.resolve_checked(p, "twin.short_wavelength_cutoff", positive_length)?
                    .si(),
            ),
            None => None,
        };
        let seed = ctx.resolve(&self.seed, "twin.seed")?;
        Ok(SurfaceTask {
            source: SurfaceSource::Twin(TwinSource {
                measured,
                form_degree,
                sq,
                grid: TwinGrid {
                    nx,
                    ny,
                    lx,
                    ly,
                    short_wavelength_cutoff: cutoff,
                    seed,
                },
            }),
        })
    }
}

impl TwinSource {
    /// The key fields of a twin: the measured files by content, their levelling, the target Sq
    /// and the twin's grid and seed, in SI.
    pub(super) fn key_fields(&self) -> Vec<Field> {
        let Self {
            measured,
            form_degree,
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
        let mut fields = vec![
            Field::text("source", "twin"),
            Field::int("form_degree", *form_degree as i64),
        ];
        for (i, m) in measured.iter().enumerate() {
            fields.push(Field::text(format!("twin_of_{i}_blake3"), m.content_hash()));
        }
        fields.extend([
            Field::float("sq_target", *sq, Dimension::Length),
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

    /// Measures, fits and generates; returns the twin and its extra metrics.
    pub(super) fn generate(&self) -> Result<(HeightMap, Vec<Field>), NodeError> {
        let mut textures = Vec::with_capacity(self.measured.len());
        for m in &self.measured {
            let map = m.load()?;
            let texture = measure_texture(&map, &TextureOptions::default())
                .map_err(|e| NodeError::new(format!("measuring {}: {e}", m.path().display())))?;
            textures.push(texture);
        }
        let model =
            fit_twin_model(&textures).map_err(|e| NodeError::new(format!("twin fit: {e}")))?;
        let twin = synthetic_twin(&model, self.sq, &self.grid, ISO_ACF_THRESHOLD)
            .map_err(|e| NodeError::new(format!("twin: {e}")))?;
        let p = &twin.prediction;
        let warnings: Vec<String> = p.warnings.iter().map(|w| format!("{w:?}")).collect();
        let metrics = vec![
            Field::float(
                "twin_correlation_length_x",
                p.correlation_length_x,
                Dimension::Length,
            ),
            Field::float(
                "twin_correlation_length_y",
                p.correlation_length_y,
                Dimension::Length,
            ),
            Field::float("twin_hurst", p.hurst, Dimension::Dimensionless),
            Field::text("twin_warnings", warnings.join("; ")),
        ];
        Ok((twin.surface, metrics))
    }

    /// Memory of the largest step (measured files are read one at a time).
    pub(super) fn memory_estimate(&self) -> u64 {
        let synthetic = (self.grid.nx as u64) * (self.grid.ny as u64) * 8 * 6;
        self.measured
            .iter()
            .map(MeasuredSource::memory_estimate)
            .max()
            .unwrap_or(0)
            .max(synthetic)
    }
}
