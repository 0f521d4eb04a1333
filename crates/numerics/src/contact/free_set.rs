//! The moving points of a load step, iterated alone with the operator restricted to them.
//!
//! On a rough contact near saturation (ground steel at stress ratios near 1) almost all the
//! contact is at `p_lim` and the free set `F = {0 < p < p_lim}` is a few thousand points of a grid
//! of millions, yet every step of the constrained CG (`constrained_cg.rs`) costs transforms of the
//! whole grid. The points whose pressure the next steps move are the moving set
//! `M = F ∪ {p = 0, g < 0} ∪ {p = p_lim, g > 0}` (`Workspace::moving_points`). With every other
//! pressure held, their displacement on `M` is a constant of the problem, so the QP restricted to
//! `M` — `min ½ p_Mᵀ K_MM p_M + p_Mᵀ (g₀ + u_rest − offset)_M` over `0 ≤ p ≤ p_lim`, with `Σ_M p`
//! fixed under load control — is solved with the matrix `K_MM` (`restricted_matrix.rs`, a packed
//! triangle), whose product costs `|M|²` multiplications instead of an FFT pair.
//!
//! Iteration (the CG of Polonsky & Keer 1999, Wear 231, on a face of the box, restarted whenever
//! a point reaches a bound — an active-set CG): on the points of `M` not held at a bound,
//! `r = g₀ + u − offset − δ` with `δ` their mean under load control (0 otherwise),
//! `t = r + β t_old` (`β = Σ r² / Σ r_old²`, 0 at a restart), `w = K_MM t`,
//! `τ = Σ r t / (tᵀ w − Σ w Σ t / n)` (the last term under load control), and the step
//! `p ← p − τ' t`, `u_M ← u_M − τ' w` with `τ'` the smaller of `τ` and the step at which the
//! first point reaches 0 or `p_lim`; that point is then held there and the conjugation restarts.
//! `Σ t = 0` under load control, so the load is kept. The points of `M` out of `F` start free:
//! their gap has the sign that moves them in.
//!
//! It stops at a contact residual of [`TARGET_SHARE`] of the tolerance, when fewer than two points
//! are left free, when the residual has stopped falling, or after [`MAX_ITERATIONS`]. The
//! constrained CG then recomputes `u = K p` with an FFT pair and judges convergence on it, as on
//! every step: this iteration moves pressures, it never decides that a step has converged, and
//! points outside `M` that the new pressures open or close are caught by that recomputation.
//!
//! It is used while the matrix is small (`|M|² ≤` [`MAX_MATRIX_SHARE`] `· N`) and the step is
//! near its final contact (at most [`MAX_CHANGING_SHARE`] of `M` not free). Measurements in
//! `docs/contact-solver-design.md`.

use super::influence::InfluenceOperator;
use super::workspace::Workspace;

/// The restricted matrix has at most this many entries per grid point (`|M|² ≤ 2 N`: at 3512²
/// up to 4967 moving points). It is stored as a packed triangle of `|M|(|M|+1)/2` values, at the
/// cap 99 MB, as much as one grid array, and the buffer of the next matrix as much again.
pub(super) const MAX_MATRIX_SHARE: f64 = 2.0;

/// The moving points are iterated alone only when at most this share of them is not free (points
/// out of contact with a negative gap, saturated points with an open gap): while many points
/// still enter or leave, the iteration soon stops at a bound, and its matrix, whose new rows are
/// the costly part, would be built for a few steps only.
const MAX_CHANGING_SHARE: f64 = 0.05;

/// The iteration aims at a contact residual of this share of the tolerance, so that the
/// displacement recomputed by FFT (equal to `K_MM`'s up to round-off) confirms it.
const TARGET_SHARE: f64 = 0.5;

/// Iteration cap (each iteration costs one product with `K_MM`).
const MAX_ITERATIONS: usize = 50;

/// Iterations without a 0.9-fold fall of the residual after which the iteration stops.
const STALL_ITERATIONS: usize = 5;

/// What the caller's step fixes.
#[derive(Debug, Clone, Copy)]
pub(super) struct FreeSetTask {
    /// Load control (`Σ_F p` fixed, `δ` solved for) or approach control (`δ = 0`).
    pub load_control: bool,
    /// The prescribed approach under approach control, else 0.
    pub offset: f64,
    /// The pressure cap `p_lim`.
    pub flow_pressure: f64,
    /// Aimed-at contact residual `max_F |g − δ|` in m.
    pub target: f64,
}

impl FreeSetTask {
    /// The task aiming at [`TARGET_SHARE`] of the relative tolerance `tolerance` of gaps
    /// scaled by `gap_scale`.
    pub(super) fn new(
        load_control: bool,
        offset: f64,
        flow_pressure: f64,
        tolerance: f64,
        gap_scale: f64,
    ) -> Self {
        Self {
            load_control,
            offset,
            flow_pressure,
            target: TARGET_SHARE * tolerance * gap_scale,
        }
    }
}

/// The result of [`iterate`].
#[derive(Debug, Clone, Copy)]
pub(super) struct FreeSetOutcome {
    /// CG iterations taken (products with `K_MM`); 0 leaves the pressures unchanged.
    pub iterations: usize,
    /// `δ` of the last iterate (0 under approach control).
    pub delta: f64,
}

/// Whether `moving` points of a grid of `points` points are few enough to be iterated alone.
pub(super) fn applies(moving: f64, points: f64) -> bool {
    moving >= 2.0 && moving * moving <= MAX_MATRIX_SHARE * points
}

/// Iterates the moving points of `ws` (`u` exact, `δ` = `delta` of the last measurement, where
/// `free_in_step` points are free) and writes their new pressures into `ws.p`; `ws.u` is left as
/// it was (stale on the whole grid when any iteration was taken).
pub(super) fn iterate(
    ws: &mut Workspace,
    op: &InfluenceOperator,
    task: FreeSetTask,
    delta: f64,
    free_in_step: f64,
) -> FreeSetOutcome {
    let points = ws.moving_points(task.offset, delta);
    let moving = points.len() as f64;
    if !applies(moving, ws.len() as f64) || moving > (1.0 + MAX_CHANGING_SHARE) * free_in_step {
        return FreeSetOutcome {
            iterations: 0,
            delta,
        };
    }
    let mut matrix = std::mem::take(&mut ws.restricted);
    matrix.update(op, points);
    let points = matrix.points();
    let mut p: Vec<f64> = points.iter().map(|&i| ws.p[i]).collect();
    let mut v: Vec<f64> = points
        .iter()
        .map(|&i| ws.g0[i] + ws.u[i] - task.offset)
        .collect();
    let m = points.len();
    let (mut t, mut w, mut r) = (vec![0.0; m], vec![0.0; m], vec![0.0; m]);
    let mut free = vec![true; m];
    let (mut free_count, mut restart) = (m, true);
    let (mut iterations, mut r2_old) = (0, 0.0);
    let (mut best, mut last_progress) = (f64::INFINITY, 0);
    let delta = loop {
        let delta = if task.load_control {
            free_sum(&v, &free) / free_count as f64
        } else {
            0.0
        };
        let residual = free_residual(&mut r, &v, &free, delta);
        if residual < 0.9 * best {
            best = residual;
            last_progress = iterations;
        }
        if residual <= task.target
            || free_count < 2
            || iterations >= MAX_ITERATIONS
            || iterations - last_progress > STALL_ITERATIONS
        {
            break delta;
        }
        let r2: f64 = r.iter().map(|x| x * x).sum();
        let beta = if restart { 0.0 } else { r2 / r2_old };
        (r2_old, restart) = (r2, false);
        t.iter_mut()
            .zip(&r)
            .for_each(|(ti, &ri)| *ti = ri + beta * *ti);
        matrix.multiply(&t, &mut w);
        let free_w = if task.load_control {
            free_sum(&w, &free)
        } else {
            0.0
        };
        let tau = step_length(&r, &t, &w, free_w, free_count);
        if !(tau.is_finite() && tau > 0.0) {
            break delta;
        }
        if let Some(a) = advance(&mut p, &mut v, (&t, &w), tau, task.flow_pressure) {
            free[a] = false;
            free_count -= 1;
            restart = true;
        }
        iterations += 1;
    };
    if iterations > 0 {
        ws.set_pressures(points, &p);
    }
    ws.restricted = matrix;
    FreeSetOutcome { iterations, delta }
}

/// `r = v − δ` on the free points (0 on those at a bound); returns `max |r|`.
fn free_residual(r: &mut [f64], v: &[f64], free: &[bool], delta: f64) -> f64 {
    for ((ri, &vi), &fi) in r.iter_mut().zip(v).zip(free) {
        *ri = if fi { vi - delta } else { 0.0 };
    }
    r.iter().fold(0.0f64, |a, &x| a.max(x.abs()))
}

/// Moves the pressures `p` by `−τ t` (at most to the first bound reached) and their gaps `v` by
/// `−τ w` (`w = A t`); returns the point that reached a bound, set exactly to it.
fn advance(
    p: &mut [f64],
    v: &mut [f64],
    (t, w): (&[f64], &[f64]),
    tau: f64,
    flow_pressure: f64,
) -> Option<usize> {
    let (step, hit) = feasible_step(p, t, tau, flow_pressure);
    p.iter_mut().zip(t).for_each(|(pi, &ti)| *pi -= step * ti);
    v.iter_mut().zip(w).for_each(|(vi, &wi)| *vi -= step * wi);
    if let Some(a) = hit {
        p[a] = if t[a] > 0.0 { 0.0 } else { flow_pressure };
    }
    hit
}

/// `Σ values` over the points not held at a bound.
fn free_sum(values: &[f64], free: &[bool]) -> f64 {
    values
        .iter()
        .zip(free)
        .filter(|(_, &f)| f)
        .map(|(x, _)| x)
        .sum()
}

/// The CG step `τ = Σ r t / (tᵀ w − free_w Σ t / free_count)` along `t` with `w = K t`, where
/// `free_w = Σ_free w` under load control and 0 otherwise (`t` vanishes at the points held at a
/// bound).
fn step_length(r: &[f64], t: &[f64], w: &[f64], free_w: f64, free_count: usize) -> f64 {
    let tw: f64 = t.iter().zip(w).map(|(a, b)| a * b).sum();
    let rt: f64 = r.iter().zip(t).map(|(a, b)| a * b).sum();
    let load_term = free_w * t.iter().sum::<f64>() / free_count as f64;
    rt / (tw - load_term)
}

/// The step along `−t` from `p`: `tau`, or the shorter step at which the first free point
/// reaches 0 or `p_lim`, with that point.
fn feasible_step(p: &[f64], t: &[f64], tau: f64, flow_pressure: f64) -> (f64, Option<usize>) {
    let mut step = (tau, None);
    for (a, (&pa, &ta)) in p.iter().zip(t).enumerate() {
        let to_bound = if ta > 0.0 {
            pa / ta
        } else if ta < 0.0 {
            (pa - flow_pressure) / ta
        } else {
            continue;
        };
        if to_bound < step.0 {
            step = (to_bound, Some(a));
        }
    }
    step
}
