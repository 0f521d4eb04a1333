//! The static friction coefficient of the statistical models (Kogut–Etsion 2004):
//! solve **F = P(d*) − F_s(d*)** for the separation d*, then **μ_s = Q_max(d*) / F**.
//!
//! F(d*) → 0⁻ as d* → ∞ (adhesion outlasts contact) and has a minimum, the pull-off load. The net
//! load P − F_s is known on a grid of d* (default [−3, 12 σ_s/σ], step 0.5; the lower end is
//! extended in steps of 3 down to −30 when the load needs it; the points are evaluated only as far
//! as the sign of P − F_s − F needs, see [`super::net_load_grid`]), every sign change of
//! P − F_s − F between grid points is counted as a root ([`SolveStatus::roots_found`]). **The
//! root with the smallest d\* is taken** and refined with Brent, run on ln((P − F_s)/F) when the
//! bracket is compressive at both ends and on P − F_s − F otherwise; it stops at an x tolerance
//! of 1e-11 in d* (~1e-17 m for σ = 1 µm) or a relative load residual ≤ 1e-11. There
//! dF/dd* < 0, the stable equilibrium under load control (for a
//! tensile load between pull-off and 0 the other root lies on the unstable, receding branch).
//! Two roots closer than one grid step are not resolved (a limitation). A tensile load below the
//! pull-off load returns [`FrictionError::LoadBelowPullOff`] (pull-off = grid minimum of P − F_s
//! refined by golden section; a minimum beyond the top of the grid is not searched); μ_s is
//! reported only for a compressive load F > 0 (it is `None` for a tensile load). With the
//! literal KE 2004 Q_max at high ψ, Q_max and μ_s can come out negative; the library reports them
//! as computed (see [`super::laws::kogut_etsion`]) and the callers decide how to present them.
//!
//! μ(F) curves reuse one table for all loads: every net-load evaluation made by Brent is inserted
//! into it, so later loads start from narrower brackets (each extra load costs a few iterations).
//! The table only ever holds exact evaluations, so root counting stays valid (refinement can only
//! reveal sign changes, never invent them).

use super::error::FrictionError;
use super::net_load_grid::NetLoadGrid;
use super::root_finding::{brent, BrentTolerances};
use super::solve_settings::SolveSettings;
use super::statistical_integrals::{AdhesionForce, IntegralValue, StatisticalModel};

/// Brent also stops once the relative load residual |P − F_s − F|/|F| (or |ln((P − F_s)/F)|) is
/// ≤ 1e-11, below the 1e-10 accuracy of the integrals, where further steps only chase noise.
const RESIDUAL_TOLERANCE: f64 = 1e-11;

/// Diagnostics of one solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolveStatus {
    /// Number of sign changes of P − F_s − F found on the grid.
    pub roots_found: usize,
    /// Index (0 = smallest d*) of the root taken; always 0 (see module docs).
    pub root_taken: usize,
    /// Brent iterations of the refinement.
    pub brent_iterations: usize,
    /// |P − F_s − F| / |F| at the solution.
    pub relative_residual: f64,
    /// Largest relative error estimate among the integrals reported.
    pub max_integral_relative_error: f64,
}

/// Static friction of a statistical model at one external load.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticFrictionResult {
    /// External load F (N, compressive positive).
    pub external_load: f64,
    /// μ_s = Q_max / F (None for F ≤ 0).
    pub mu_s: Option<f64>,
    /// Contact load P (N).
    pub contact_load: f64,
    /// Total adhesion force F_s (N).
    pub adhesion_force: f64,
    /// Adhesion of contacting summits (N).
    pub adhesion_contacting: f64,
    /// Adhesion of non-contacting summits (N).
    pub adhesion_non_contacting: f64,
    /// Static friction force Q_max (N).
    pub static_friction_force: f64,
    /// Dimensionless separation d* = d/σ from the summit mean plane.
    pub d_star: f64,
    /// Separation d from the summit mean plane (m).
    pub separation_from_summits: f64,
    /// Separation h = d + y_s from the mean plane of surface heights (m).
    pub separation_from_heights: f64,
    /// Plasticity index ψ (with σ_s).
    pub plasticity_index: f64,
    /// Expected number of contacting summits.
    pub contacting_summits: f64,
    /// Real contact area (m²).
    pub real_contact_area: f64,
    /// The part of the contact load carried by summits beyond the validated range of the
    /// model's friction law (N; see [`super::AsperityLaws::fit_limit`]).
    pub load_beyond_fit: f64,
    /// Solver diagnostics.
    pub status: SolveStatus,
}

/// Solve for one external load `load` (N) using (and extending) a precomputed grid.
pub fn static_friction_on_grid(
    model: &StatisticalModel,
    grid: &mut NetLoadGrid,
    load: f64,
    settings: &SolveSettings,
) -> Result<StaticFrictionResult, FrictionError> {
    if !load.is_finite() || load == 0.0 {
        return Err(FrictionError::InvalidParameter {
            name: "external_load",
            value: load,
            expected: "a finite, non-zero load (N)",
        });
    }
    if load > 0.0 {
        grid.cover_load(model, load, settings)?;
    }
    let brackets = grid.brackets(model, load)?;
    let (first, a, b) = first_bracket(model, grid, &brackets, load, settings)?;
    let fa = grid.net_load_at(model, first)?;
    let fb = grid.net_load_at(model, first + 1)?;
    // Brent runs on ln(net/F) when the whole bracket carries a compressive net load (F > 0): the
    // net load falls off like a Gaussian tail, so its logarithm is nearly linear in d* and Brent's
    // interpolation converges in fewer steps. Otherwise it runs on net − F.
    let logarithmic = load > 0.0 && fa > 0.0 && fb > 0.0;
    let residual = |net: f64| {
        if logarithmic {
            (net / load).ln()
        } else {
            net - load
        }
    };
    let mut evaluated = Vec::new();
    let mut last: Option<(f64, IntegralValue, AdhesionForce)> = None;
    let root = brent(
        &mut |d| {
            let p = model.contact_load(d)?;
            let fs = model.adhesion_force(d)?;
            let net = p.value - fs.total();
            evaluated.push((d, p.value, net));
            last = Some((d, p, fs));
            if logarithmic && net <= 0.0 {
                // Not expected inside a bracket positive at both ends (P − F_s is monotone there);
                // a non-positive value is mapped to the residual of the smallest positive net
                // load, finite and below every other value, so the sign logic stays correct.
                return Ok::<f64, FrictionError>(residual(f64::MIN_POSITIVE));
            }
            Ok::<f64, FrictionError>(residual(net))
        },
        a,
        b,
        residual(fa),
        residual(fb),
        BrentTolerances {
            x_tol: settings.d_star_tolerance,
            f_tol: if logarithmic {
                RESIDUAL_TOLERANCE
            } else {
                RESIDUAL_TOLERANCE * load.abs()
            },
            max_iterations: 100,
        },
    )?;
    grid.insert(&evaluated);
    let cached = last
        .filter(|(d, _, _)| *d == root.x)
        .map(|(_, p, fs)| (p, fs));
    let roots_found = grid.count_roots(&brackets);
    evaluate_at(model, load, root.x, cached, roots_found, root.iterations)
}

/// The first bracket of a sign change of `P − F_s − F` on the grid: its index and the d* at
/// its ends; without one, why (below the pull-off load, or above the grid's range).
fn first_bracket(
    model: &StatisticalModel,
    grid: &mut NetLoadGrid,
    brackets: &[usize],
    load: f64,
    settings: &SolveSettings,
) -> Result<(usize, f64, f64), FrictionError> {
    let Some(&first) = brackets.first() else {
        return Err(if load < 0.0 {
            let pull_off = grid.pull_off_load(model)?;
            FrictionError::LoadBelowPullOff { load, pull_off }
        } else {
            FrictionError::LoadAboveSearchRange {
                load,
                max_load: grid.net_load_at(model, 0)?,
                d_star_min: grid.d_star(0).unwrap_or(settings.d_star_min),
            }
        });
    };
    let (Some(a), Some(b)) = (grid.d_star(first), grid.d_star(first + 1)) else {
        return Err(FrictionError::InvalidParameter {
            name: "grid",
            value: first as f64,
            expected: "a bracket inside the grid",
        });
    };
    Ok((first, a, b))
}

/// Solve for one external load `load` (N > pull-off load).
pub fn static_friction(
    model: &StatisticalModel,
    load: f64,
    settings: &SolveSettings,
) -> Result<StaticFrictionResult, FrictionError> {
    let mut grid = NetLoadGrid::new(model, settings)?;
    static_friction_on_grid(model, &mut grid, load, settings)
}

/// Solve for a nominal pressure `pressure` (Pa): F = pressure × A_n.
pub fn static_friction_at_pressure(
    model: &StatisticalModel,
    pressure: f64,
    settings: &SolveSettings,
) -> Result<StaticFrictionResult, FrictionError> {
    static_friction(model, pressure * model.nominal_area, settings)
}

/// μ(F) curve: one result per load, sharing one net-load grid (each load may fail on its own).
pub fn static_friction_curve(
    model: &StatisticalModel,
    loads: &[f64],
    settings: &SolveSettings,
) -> Result<Vec<Result<StaticFrictionResult, FrictionError>>, FrictionError> {
    let mut grid = NetLoadGrid::new(model, settings)?;
    Ok(loads
        .iter()
        .map(|&load| static_friction_on_grid(model, &mut grid, load, settings))
        .collect())
}

fn evaluate_at(
    model: &StatisticalModel,
    load: f64,
    d_star: f64,
    cached: Option<(IntegralValue, AdhesionForce)>,
    roots_found: usize,
    brent_iterations: usize,
) -> Result<StaticFrictionResult, FrictionError> {
    let (p, fs) = match cached {
        Some(values) => values,
        None => (model.contact_load(d_star)?, model.adhesion_force(d_star)?),
    };
    let q = model.static_friction_force(d_star)?;
    let area = model.contact_area(d_star)?;
    let beyond = model.load_beyond_fit(d_star)?;
    let rel = |v: f64, e: f64| if v == 0.0 { 0.0 } else { (e / v).abs() };
    let max_integral_relative_error = [
        rel(p.value, p.error),
        rel(fs.contacting.value, fs.contacting.error),
        rel(fs.non_contacting.value, fs.non_contacting.error),
        rel(q.value, q.error),
        rel(area.value, area.error),
    ]
    .into_iter()
    .fold(0.0, f64::max);
    let net = p.value - fs.total();
    let sigma = model.summits.sigma;
    Ok(StaticFrictionResult {
        external_load: load,
        mu_s: (load > 0.0).then(|| q.value / load),
        contact_load: p.value,
        adhesion_force: fs.total(),
        adhesion_contacting: fs.contacting.value,
        adhesion_non_contacting: fs.non_contacting.value,
        static_friction_force: q.value,
        d_star,
        separation_from_summits: d_star * sigma,
        separation_from_heights: d_star * sigma + model.summits.y_s,
        plasticity_index: model.plasticity_index,
        contacting_summits: model.contacting_summits(d_star),
        real_contact_area: area.value,
        load_beyond_fit: beyond.value,
        status: SolveStatus {
            roots_found,
            root_taken: 0,
            brent_iterations,
            relative_residual: ((net - load) / load).abs(),
            max_integral_relative_error,
        },
    })
}
