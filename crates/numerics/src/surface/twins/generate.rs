//! Generation of a twin ([`synthetic_twin`]).
//!
//! The predicted `ξx`, `ξy`, `H` at the requested Sq are turned into roll-off wavelengths of the
//! [`crate::surface::synthetic`] model (lay along x: `correlation_length = λx`,
//! `anisotropy = {aspect_ratio: λx/λy, angle: 0}`) such that the model's ensemble ACF
//! ([`model_autocorrelation`]) on the requested grid decays to `s` exactly at `ξx` and `ξy`:
//! fixed-point iteration `λ ← λ · ξ_target / ξ_model` per axis, started at `λ = ξ/0.3`,
//! converged when both relative residuals `|ξ_model/ξ_target − 1|` are below
//! [`CALIBRATION_TOLERANCE`], at most [`CALIBRATION_MAX_ITERATIONS`] iterations; iterations and
//! residual are reported.
//!
//! A periodic twin can only hold correlation lengths well below its size. When the calibration
//! cannot reach them (the model ACF does not decay to `s` within half the period, a spacing
//! coarser than the correlation lengths, or an iteration that does not converge), the error names
//! the size that gives each axis [`SIZE_PER_CORRELATION_LENGTH`] correlation lengths and the grid
//! that samples each with [`POINTS_PER_CORRELATION_LENGTH`] points or the spacing given, if finer
//! ([`TwinError::GridTooSmall`]).

use super::{
    SyntheticTwin, TwinError, TwinGrid, TwinModel, CALIBRATION_MAX_ITERATIONS,
    CALIBRATION_TOLERANCE,
};
use crate::surface::spectral::Autocorrelation;
use crate::surface::synthetic::{
    generate_synthetic_surface, model_autocorrelation, Anisotropy, SyntheticSurfaceSpec,
};

/// The twin's size that [`TwinError::GridTooSmall`] suggests, in correlation lengths per axis: a
/// single periodic realisation then holds enough independent patches for stable statistics.
pub const SIZE_PER_CORRELATION_LENGTH: f64 = 8.0;

/// The finest sampling [`TwinError::GridTooSmall`] suggests: points per correlation length, so
/// that the ACF's decay to the threshold spans several lags.
pub const POINTS_PER_CORRELATION_LENGTH: f64 = 4.0;

/// Generates a synthetic twin at `sq` (m) on `grid`, with correlation lengths measured at the
/// threshold `threshold` (use the one of [`super::TextureOptions`] that measured the model's
/// inputs).
pub fn synthetic_twin(
    model: &TwinModel,
    sq: f64,
    grid: &TwinGrid,
    threshold: f64,
) -> Result<SyntheticTwin, TwinError> {
    let prediction = model.predict(sq)?;
    let (target_x, target_y) = (
        prediction.correlation_length_x,
        prediction.correlation_length_y,
    );
    let mut spec = SyntheticSurfaceSpec {
        nx: grid.nx,
        ny: grid.ny,
        lx: grid.lx,
        ly: grid.ly,
        sq,
        hurst: prediction.hurst,
        correlation_length: target_x / 0.3,
        short_wavelength_cutoff: grid.short_wavelength_cutoff,
        anisotropy: Some(Anisotropy {
            aspect_ratio: target_x / target_y,
            angle: 0.0,
        }),
        seed: grid.seed,
    };
    let (mut lambda_x, mut lambda_y) = (target_x / 0.3, target_y / 0.3);
    let mut residual = f64::INFINITY;
    let mut iterations = 0;
    for iteration in 1..=CALIBRATION_MAX_ITERATIONS {
        iterations = iteration;
        spec.correlation_length = lambda_x;
        spec.anisotropy = Some(Anisotropy {
            aspect_ratio: lambda_x / lambda_y,
            angle: 0.0,
        });
        let (dx, dy) = spec.spacing();
        let acf = Autocorrelation::from_periodic_lags(&model_autocorrelation(&spec)?, dx, dy);
        let lengths = acf.correlation_lengths(threshold)?;
        let (Some(model_x), Some(model_y)) = (lengths.x, lengths.y) else {
            break;
        };
        residual = (model_x / target_x - 1.0)
            .abs()
            .max((model_y / target_y - 1.0).abs());
        if residual < CALIBRATION_TOLERANCE {
            let surface = generate_synthetic_surface(&spec)?;
            return Ok(SyntheticTwin {
                surface,
                spec,
                prediction,
                iterations: iteration,
                residual,
            });
        }
        lambda_x *= target_x / model_x;
        lambda_y *= target_y / model_y;
    }
    Err(grid_too_small(
        grid, target_x, target_y, iterations, residual,
    ))
}

/// The error naming the size and grid that hold [`SIZE_PER_CORRELATION_LENGTH`] correlation
/// lengths along each axis (never smaller than the size given) at a spacing that resolves them
/// ([`POINTS_PER_CORRELATION_LENGTH`] points per correlation length, never coarser than the
/// spacing given).
fn grid_too_small(
    grid: &TwinGrid,
    target_x: f64,
    target_y: f64,
    iterations: usize,
    residual: f64,
) -> TwinError {
    let needed = |target: f64, size: f64, n: usize| {
        let length = (SIZE_PER_CORRELATION_LENGTH * target).max(size);
        let spacing = (size / n as f64).min(target / POINTS_PER_CORRELATION_LENGTH);
        // Round-off in `length / spacing` must not add a point to an exact fit.
        (length, (length / spacing * (1.0 - 1e-12)).ceil() as usize)
    };
    let (lx, nx) = needed(target_x, grid.lx, grid.nx);
    let (ly, ny) = needed(target_y, grid.ly, grid.ny);
    TwinError::GridTooSmall {
        correlation_length_x: target_x,
        correlation_length_y: target_y,
        iterations,
        residual,
        suggested_size: [lx, ly],
        suggested_grid: [nx, ny],
    }
}
