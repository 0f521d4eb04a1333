//! `surface: {synthetic: {...}}`: periodic self-affine Gaussian surfaces.

use serde::Deserialize;

use crate::engine::study::{Param, ResolveContext, SpecError};
use crate::engine::value::Field;
use crate::surface::synthetic::{Anisotropy, SyntheticError, SyntheticSurfaceSpec};
use crate::units::{Angle, Dimension, Length, Quantity};
use crate::vocabulary::metrics::HURST;
use crate::vocabulary::surface_parameters::{
    ANISOTROPY_ANGLE, ANISOTROPY_RATIO, CORRELATION_LENGTH, LX, LY, NX, NY, SEED,
    SHORT_WAVELENGTH_CUTOFF, SOURCE, SQ_TARGET,
};

use super::{SurfaceSource, SurfaceTask};

/// Largest grid side accepted (a 16384² f64 map is 2 GiB).
pub(super) const MAX_GRID_SIDE: usize = 16384;

/// `surface: {synthetic: {...}}`.
#[derive(Debug, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SyntheticSpec {
    /// Grid points `[nx, ny]`, each ≥ 2.
    pub grid: [Param<usize>; 2],
    /// Physical size `[Lx, Ly]` (lengths, each 1 nm to 1 km, e.g. `[1 mm, 1 mm]`).
    pub size: [Param<Quantity<Length>>; 2],
    /// Target RMS height Sq (length from 1 pm to the shorter side); exact after normalisation.
    pub sq: Param<Quantity<Length>>,
    /// Hurst exponent H in (0, 1]: PSD ∝ q^-(2+2H) above the roll-off.
    pub hurst: Param<f64>,
    /// Roll-off wavelength λ_r (length > 0, ≤ 1 km): the PSD is flat for wavelengths longer than this.
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

/// Range check: a length > 0.
pub(super) fn positive_length(v: &Quantity<Length>) -> Result<(), String> {
    if v.si() > 0.0 {
        Ok(())
    } else {
        Err(String::from("is out of range: must be > 0 m"))
    }
}

impl SyntheticSpec {
    pub(super) fn instantiate(&self, ctx: &ResolveContext<'_>) -> Result<SurfaceTask, SpecError> {
        let grid_check = |n: &usize| {
            if (2..=MAX_GRID_SIDE).contains(n) {
                Ok(())
            } else {
                Err(format!(
                    "is out of range: grid sides must be between 2 and {MAX_GRID_SIDE}"
                ))
            }
        };
        let nx = ctx.resolve_checked(&self.grid[0], "synthetic.grid[0]", grid_check)?;
        let ny = ctx.resolve_checked(&self.grid[1], "synthetic.grid[1]", grid_check)?;
        let lx = ctx
            .resolve_checked(&self.size[0], "synthetic.size[0]", positive_length)?
            .si();
        let ly = ctx
            .resolve_checked(&self.size[1], "synthetic.size[1]", positive_length)?
            .si();
        let sq = ctx
            .resolve_checked(&self.sq, "synthetic.sq", positive_length)?
            .si();
        let hurst = ctx.resolve_checked(&self.hurst, "synthetic.hurst", |h: &f64| {
            if *h > 0.0 && *h <= 1.0 {
                Ok(())
            } else {
                Err(String::from(
                    "is out of range: the Hurst exponent must be in (0, 1]",
                ))
            }
        })?;
        let correlation_length = ctx
            .resolve_checked(
                &self.correlation_length,
                "synthetic.correlation_length",
                positive_length,
            )?
            .si();
        let short_wavelength_cutoff = match &self.short_wavelength_cutoff {
            Some(p) => Some(
                ctx.resolve_checked(p, "synthetic.short_wavelength_cutoff", positive_length)?
                    .si(),
            ),
            None => None,
        };
        let anisotropy = self.anisotropy(ctx)?;
        let seed = ctx.resolve(&self.seed, "synthetic.seed")?;
        let spec = SyntheticSurfaceSpec {
            nx,
            ny,
            lx,
            ly,
            sq,
            hurst,
            correlation_length,
            short_wavelength_cutoff,
            anisotropy,
            seed,
        };
        self.check_together(&spec)?;
        Ok(SurfaceTask {
            source: SurfaceSource::Synthetic(spec),
        })
    }
}

impl SyntheticSpec {
    /// `anisotropy: {ratio, angle}`: ratio ≥ 1, angle (default 0) in radians.
    fn anisotropy(&self, ctx: &ResolveContext<'_>) -> Result<Option<Anisotropy>, SpecError> {
        let Some(a) = &self.anisotropy else {
            return Ok(None);
        };
        let aspect_ratio =
            ctx.resolve_checked(&a.ratio, "synthetic.anisotropy.ratio", |r: &f64| {
                if *r >= 1.0 && r.is_finite() {
                    Ok(())
                } else {
                    Err(String::from(
                        "is out of range: the ratio must be ≥ 1 (swap the angle by 90 deg instead)",
                    ))
                }
            })?;
        let angle = match &a.angle {
            Some(p) => ctx.resolve(p, "synthetic.anisotropy.angle")?.si(),
            None => 0.0,
        };
        Ok(Some(Anisotropy {
            aspect_ratio,
            angle,
        }))
    }

    /// Checks that involve several fields (e.g. the cutoff against the grid spacing), made when
    /// the study is resolved so `validate` reports them, not the run; located at the field named.
    fn check_together(&self, spec: &SyntheticSurfaceSpec) -> Result<(), SpecError> {
        let Err(SyntheticError::InvalidParameter {
            name,
            value,
            expected,
            unit,
        }) = spec.validate()
        else {
            return Ok(());
        };
        let location = match name {
            "short_wavelength_cutoff" => self.short_wavelength_cutoff.as_ref().map(Param::location),
            "correlation_length" => Some(self.correlation_length.location()),
            "hurst" => Some(self.hurst.location()),
            "sq" => Some(self.sq.location()),
            "lx" => Some(self.size[0].location()),
            "ly" => Some(self.size[1].location()),
            _ => None,
        }
        .unwrap_or_else(|| self.grid[0].location());
        let field = match name {
            "lx" => "size[0]",
            "ly" => "size[1]",
            other => other,
        };
        Err(SpecError {
            location,
            field: format!("synthetic.{field}"),
            message: format!("{value} {unit} is out of range: expected {expected} ({unit})"),
        })
    }
}

/// The key fields of a synthetic surface: every field of its spec, in SI.
pub(super) fn key_fields(spec: &SyntheticSurfaceSpec) -> Vec<Field> {
    let SyntheticSurfaceSpec {
        nx,
        ny,
        lx,
        ly,
        sq,
        hurst,
        correlation_length,
        short_wavelength_cutoff,
        anisotropy,
        seed,
    } = *spec;
    let mut fields = vec![
        Field::int(NX, nx as i64),
        Field::int(NY, ny as i64),
        Field::float(LX, lx, Dimension::Length),
        Field::float(LY, ly, Dimension::Length),
        Field::float(SQ_TARGET, sq, Dimension::Length),
        Field::float(HURST, hurst, Dimension::Dimensionless),
        Field::float(CORRELATION_LENGTH, correlation_length, Dimension::Length),
    ];
    if let Some(c) = short_wavelength_cutoff {
        fields.push(Field::float(SHORT_WAVELENGTH_CUTOFF, c, Dimension::Length));
    }
    if let Some(Anisotropy {
        aspect_ratio,
        angle,
    }) = anisotropy
    {
        fields.push(Field::float(
            ANISOTROPY_RATIO,
            aspect_ratio,
            Dimension::Dimensionless,
        ));
        fields.push(Field::float(ANISOTROPY_ANGLE, angle, Dimension::Angle));
    }
    fields.push(Field::int(SEED, seed as i64));
    fields.push(Field::text(SOURCE, "synthetic"));
    fields
}
