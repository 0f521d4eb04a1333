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
//! Extrapolation, clamping and the fit's quality are reported as columns
//! ([`super::twin_self_affine`]).
//!
//! With `spectrum: measured` the twin reproduces the files' measured 2-D power spectrum instead
//! of a fitted model ([`super::twin_spectrum`]).
//!
//! This file holds the spec, its resolution, the key and the dispatch to either kind.

use serde::Deserialize;

use crate::engine::node::NodeError;
use crate::engine::study::{Param, ResolveContext, SpecError};
use crate::engine::value::Field;

use crate::surface::synthetic::MIN_SQ;
use crate::surface::twins::{format_micrometres, Extrapolation, TwinGrid};
use crate::surface::HeightMap;
use crate::units::{Dimension, Length, Quantity};
use crate::vocabulary::surface_parameters::{
    twin_of_blake3, EXTRAPOLATION, HURST_BAND_LONG, HURST_BAND_SHORT, LX, LY, NX, NY, SEED,
    SHORT_WAVELENGTH_CUTOFF, SOURCE, SPECTRUM, SQ_TARGET, TWIN_GRID,
};

use super::measured::MeasuredFile;
use super::preprocess::{PreprocessDefaults, PreprocessSpec};
use super::synthetic::{positive_length, MAX_GRID_SIDE};
use super::twin_band::HurstBand;
use super::twin_self_affine;
use super::twin_source::{TwinSize, TwinSource, TwinSq};
use super::twin_spectrum::{self, ExtrapolationChoice, TwinSpectrum};
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
    /// Which spectrum the twin reproduces: `self_affine` (default), the self-affine model fitted
    /// to the files, or `measured`, the files' measured 2-D power spectrum itself (averaged over
    /// the files, random phases from `seed`), for surfaces that are not self-affine.
    #[serde(default)]
    pub spectrum: Option<Param<TwinSpectrum>>,
    /// `spectrum: measured` only: the spectrum at wavelengths shorter than the files' sampling,
    /// `zero` (default) or `power_law` (each file's power law fitted over its Hurst band).
    #[serde(default)]
    pub extrapolation: Option<Param<ExtrapolationChoice>>,
    /// Target Sq of the twin (length > 0), or `measured`: the geometric mean Sq of the
    /// preprocessed files (the twin of one file at that file's Sq); for `spectrum: measured`
    /// their quadratic mean, the Sq of their averaged spectrum.
    pub sq: Param<TwinSq>,
    /// Grid points `[nx, ny]` of the twin. Required for a self-affine twin; a spectrum twin
    /// without `grid` and `size` has the first file's grid and size after preprocessing.
    #[serde(default)]
    pub grid: Option<[Param<usize>; 2]>,
    /// Physical size `[Lx, Ly]` of the twin (with `grid`).
    #[serde(default)]
    pub size: Option<[Param<Quantity<Length>>; 2]>,
    /// Optional short-wavelength cutoff of the twin's spectrum.
    #[serde(default)]
    pub short_wavelength_cutoff: Option<Param<Quantity<Length>>>,
    /// Seed of the twin's random phases.
    pub seed: Param<u64>,
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
        let spectrum = self.spectrum(ctx)?;
        let sq = ctx.resolve(&self.sq, "twin.sq")?;
        let size = self.size(ctx, spectrum.is_none())?;
        if let (TwinSq::Given(v), Some(size)) = (sq, size) {
            let max_sq = size.lx.min(size.ly);
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
        let hurst_band = self.hurst_band(ctx)?;
        if let (Some(Extrapolation::Zero), Some(param)) = (spectrum, &self.hurst_band) {
            if hurst_band.is_some() {
                return Err(SpecError {
                    location: param.location(),
                    field: String::from("twin.hurst_band"),
                    message: String::from(
                        "a spectrum twin fits no Hurst exponent unless `extrapolation:                          power_law` (the band of its tail): remove it or set that",
                    ),
                });
            }
        }
        Ok(SurfaceTask {
            source: SurfaceSource::Twin(TwinSource {
                measured,
                preprocessing,
                hurst_band,
                spectrum,
                sq,
                size,
                short_wavelength_cutoff: self
                    .short_wavelength_cutoff
                    .as_ref()
                    .map(|p| {
                        Ok(ctx
                            .resolve_checked(p, "twin.short_wavelength_cutoff", positive_length)?
                            .si())
                    })
                    .transpose()?,
                seed: ctx.resolve(&self.seed, "twin.seed")?,
            }),
        })
    }

    /// `None` for the self-affine twin, else the measured spectrum's extrapolation (`zero` by
    /// default); `extrapolation` on a self-affine twin is an error.
    fn spectrum(&self, ctx: &ResolveContext<'_>) -> Result<Option<Extrapolation>, SpecError> {
        let kind = match &self.spectrum {
            Some(p) => ctx.resolve(p, "twin.spectrum")?,
            None => TwinSpectrum::SelfAffine,
        };
        let extrapolation = self
            .extrapolation
            .as_ref()
            .map(|p| Ok((p.location(), ctx.resolve(p, "twin.extrapolation")?.0)))
            .transpose()?;
        match (kind, extrapolation) {
            (TwinSpectrum::Measured, e) => Ok(Some(e.map_or(Extrapolation::Zero, |e| e.1))),
            (TwinSpectrum::SelfAffine, None) => Ok(None),
            (TwinSpectrum::SelfAffine, Some((location, _))) => Err(SpecError {
                location,
                field: String::from("twin.extrapolation"),
                message: String::from(
                    "applies to a spectrum twin only (`spectrum: measured`); a self-affine twin \
                     extends its fitted model to every wavelength",
                ),
            }),
        }
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

    /// `grid` and `size`: both, or neither when not `required` (the first file's).
    fn size(
        &self,
        ctx: &ResolveContext<'_>,
        required: bool,
    ) -> Result<Option<TwinSize>, SpecError> {
        let (grid, size) = match (&self.grid, &self.size) {
            (Some(grid), Some(size)) => (grid, size),
            (None, None) if !required => return Ok(None),
            (grid, _) => {
                let missing = if grid.is_none() { "grid" } else { "size" };
                return Err(SpecError {
                    location: self.sq.location(),
                    field: format!("twin.{missing}"),
                    message: if required {
                        String::from(
                            "is required: a self-affine twin needs `grid: [nx, ny]` and `size: \
                             [Lx, Ly]` (a spectrum twin, `spectrum: measured`, defaults to the \
                             first file's)",
                        )
                    } else {
                        String::from(
                            "give both `grid` and `size`, or neither (the first file's grid and \
                             size)",
                        )
                    },
                });
            }
        };
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
        Ok(Some(TwinSize {
            nx: ctx.resolve_checked(&grid[0], "twin.grid[0]", side)?,
            ny: ctx.resolve_checked(&grid[1], "twin.grid[1]", side)?,
            lx: length(&size[0], "twin.size[0]")?,
            ly: length(&size[1], "twin.size[1]")?,
        }))
    }
}

impl TwinSource {
    /// The key fields of a twin: the measured files by content, their preprocessing, the target
    /// Sq and the twin's grid and seed, in SI.
    /// A self-affine twin has no `spectrum` field (its key is the one it had before spectrum
    /// twins existed); a spectrum twin adds `spectrum` and `extrapolation`, and `twin_grid:
    /// measured` instead of the grid and size when it takes the first file's.
    pub(super) fn key_fields(&self) -> Vec<Field> {
        let Self {
            measured,
            preprocessing,
            hurst_band,
            spectrum,
            sq,
            size,
            short_wavelength_cutoff,
            seed,
        } = self;
        let mut fields = vec![Field::text(SOURCE, "twin")];
        if let Some(extrapolation) = spectrum {
            fields.push(Field::text(SPECTRUM, "measured"));
            fields.push(Field::text(EXTRAPOLATION, extrapolation.name()));
        }
        fields.extend(preprocessing.key_fields());
        for (i, m) in measured.iter().enumerate() {
            fields.push(Field::text(twin_of_blake3(i), m.content_hash()));
        }
        if let Some([short, long]) = hurst_band {
            fields.push(Field::float(HURST_BAND_SHORT, *short, Dimension::Length));
            fields.push(Field::float(HURST_BAND_LONG, *long, Dimension::Length));
        }
        fields.push(match sq {
            TwinSq::Given(v) => Field::float(SQ_TARGET, *v, Dimension::Length),
            TwinSq::Measured => Field::text(SQ_TARGET, "measured"),
        });
        match size {
            Some(TwinSize { nx, ny, lx, ly }) => fields.extend([
                Field::int(NX, *nx as i64),
                Field::int(NY, *ny as i64),
                Field::float(LX, *lx, Dimension::Length),
                Field::float(LY, *ly, Dimension::Length),
            ]),
            None => fields.push(Field::text(TWIN_GRID, "measured")),
        }
        fields.push(Field::int(SEED, *seed as i64));
        if let Some(c) = short_wavelength_cutoff {
            fields.push(Field::float(SHORT_WAVELENGTH_CUTOFF, *c, Dimension::Length));
        }
        fields
    }

    /// Generates the twin; returns it, its extra metrics and the sentences that flag its row (a
    /// file's height unit assumed, a spectrum scaled to its Sq).
    pub(super) fn generate(&self) -> Result<(HeightMap, Vec<Field>, Vec<String>), NodeError> {
        match (self.spectrum, self.size) {
            (Some(extrapolation), _) => twin_spectrum::generate(self, extrapolation),
            (None, Some(size)) => twin_self_affine::generate(
                self,
                TwinGrid {
                    nx: size.nx,
                    ny: size.ny,
                    lx: size.lx,
                    ly: size.ly,
                    short_wavelength_cutoff: self.short_wavelength_cutoff,
                    seed: self.seed,
                },
            ),
            (None, None) => Err(NodeError::new(
                "twin: a self-affine twin needs `grid` and `size`",
            )),
        }
    }

    /// The points of the twin's grid: `grid`, or the first file's when not given.
    pub(super) fn points(&self) -> u64 {
        match self.size {
            Some(s) => (s.nx as u64) * (s.ny as u64),
            None => self.measured.first().map_or(0, MeasuredFile::points),
        }
    }

    /// Memory of the largest step: measured files are read one at a time, but a spectrum twin
    /// keeps each file's half periodogram (4 bytes per point) until the twin is made, a synthetic
    /// surface on the twin's grid ([`super::SYNTHETIC_BYTES_PER_POINT`]).
    pub(super) fn memory_estimate(&self) -> u64 {
        let largest = self
            .measured
            .iter()
            .map(MeasuredFile::memory_estimate)
            .max()
            .unwrap_or(0);
        let twin = self
            .points()
            .saturating_mul(super::SYNTHETIC_BYTES_PER_POINT);
        match self.spectrum {
            None => largest.max(twin),
            Some(_) => {
                let periodograms: u64 = self.measured.iter().map(|f| f.points() * 4).sum();
                largest.max(twin) + periodograms
            }
        }
    }
}
