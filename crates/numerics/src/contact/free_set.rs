//! The linear tail of a load step, iterated on the free set alone.
//!
//! Once a step of the constrained CG (`constrained_cg.rs`) has changed no point's state — no
//! projection, no re-entry, no load restoration — and every residual but the contact residual
//! is within the tolerance, what is left of the step is a linear system on the free set
//! `F = {0 < p < p_lim}`: `g_F = g₀_F + u_F − offset − δ = 0` with `Σ_F p` fixed under load
//! control (`δ` its multiplier) or `δ = 0` under approach control. The pressures off `F` stay
//! as they are, so their displacement on `F` is a constant of the system, and the CG of
//! Polonsky & Keer (1999, Wear 231) continues on it with the restricted operator
//! `K_FF` (`InfluenceOperator::restricted_matrix`, `|F| × |F|`) in place of the FFT pair:
//! `t = r + β t_old`, `β = Σ r² / Σ r_old²`, `τ = Σ r t / (tᵀ K_FF t − Σ K_FF t Σ t / |F|)`
//! (the last term under load control), `p_F ← p_F − τ t`, `u_F ← u_F − τ K_FF t`, with
//! `r = g_F` and `δ = mean_F(g₀ + u − offset)` under load control.
//!
//! It pays where the free set is small: on rough contacts near saturation (ground steel at
//! stress ratios near 1) `|F|` is a few thousand points of a grid of millions, and a product with
//! `K_FF` costs `|F|²` multiplications against two transforms of the whole grid. It is used only
//! while `|F|² ≤` [`MAX_MATRIX_SHARE`] `· N`.
//!
//! The iteration stops at a contact residual of [`TARGET_SHARE`] of the tolerance, before a step
//! that would take a point of `F` to a bound (the constrained CG handles that step), when the
//! residual has stopped falling (its round-off floor), or after [`MAX_ITERATIONS`]. The caller then
//! recomputes `u = K p` with an FFT pair and judges convergence on it, as on every step: the
//! iteration only moves the pressures of `F`, it never decides that a step has converged.

use rayon::prelude::*;

use super::influence::InfluenceOperator;
use super::workspace::Workspace;

/// The restricted matrix holds at most this many values per grid point (`|F|² ≤ 2 N`: at
/// 3512² up to 4967 free points, a 197 MB matrix, as much as two grid arrays).
pub(super) const MAX_MATRIX_SHARE: f64 = 0.125;

/// The iteration aims at a contact residual of this share of the tolerance, so that the
/// displacement recomputed by FFT (equal to `K_FF`'s up to round-off) confirms it.
const TARGET_SHARE: f64 = 0.5;

/// Iteration cap (each iteration costs one product with `K_FF`).
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
    /// CG iterations taken (products with `K_FF`); 0 leaves the pressures unchanged.
    pub iterations: usize,
    /// `δ` of the last iterate (0 under approach control).
    pub delta: f64,
}

/// Whether a free set of `free_count` points on a grid of `points` points is iterated alone.
pub(super) fn applies(free_count: f64, points: f64) -> bool {
    free_count >= 2.0 && free_count * free_count <= MAX_MATRIX_SHARE * points
}

/// Iterates the free set of `ws` from its pressures and displacement (`u` exact on `F`) and
/// writes the new free pressures into `ws.p`; `ws.u` is left as it was (stale on the whole grid
/// when any iteration was taken).
pub(super) fn iterate(
    ws: &mut Workspace,
    op: &InfluenceOperator,
    task: FreeSetTask,
    delta: f64,
) -> FreeSetOutcome {
    let points = ws.moving_points(task.offset, delta);
    if !applies(points.len() as f64, ws.len() as f64) {
        return FreeSetOutcome {
            iterations: 0,
            delta,
        };
    }
    let mut matrix = Vec::new();
    op.restricted_matrix(&points, &mut matrix);
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
            let sum: f64 = v
                .iter()
                .zip(&free)
                .filter(|(_, &f)| f)
                .map(|(x, _)| x)
                .sum();
            sum / free_count as f64
        } else {
            0.0
        };
        for ((ri, &vi), &fi) in r.iter_mut().zip(&v).zip(&free) {
            *ri = if fi { vi - delta } else { 0.0 };
        }
        let residual = r.iter().fold(0.0f64, |a, &x| a.max(x.abs()));
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
        multiply(&matrix, &t, &mut w);
        let tw: f64 = t.iter().zip(&w).map(|(a, b)| a * b).sum();
        let rt: f64 = r.iter().zip(&t).map(|(a, b)| a * b).sum();
        let load_term = if task.load_control {
            let free_w: f64 = w
                .iter()
                .zip(&free)
                .filter(|(_, &f)| f)
                .map(|(x, _)| x)
                .sum();
            free_w * t.iter().sum::<f64>() / free_count as f64
        } else {
            0.0
        };
        let tau = rt / (tw - load_term);
        if !(tau.is_finite() && tau > 0.0) {
            break delta;
        }
        let (step, hit) = feasible_step(&p, &t, tau, task.flow_pressure);
        p.iter_mut().zip(&t).for_each(|(pi, &ti)| *pi -= step * ti);
        v.iter_mut().zip(&w).for_each(|(vi, &wi)| *vi -= step * wi);
        if let Some(a) = hit {
            p[a] = if t[a] > 0.0 { 0.0 } else { task.flow_pressure };
            free[a] = false;
            free_count -= 1;
            restart = true;
        }
        iterations += 1;
    };
    if iterations > 0 {
        ws.set_pressures(&points, &p);
    }
    FreeSetOutcome { iterations, delta }
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

/// `w = A t` for the row-major square matrix `A`, rows in parallel (each row's sum in a fixed
/// order, so the result does not depend on the thread count).
fn multiply(matrix: &[f64], t: &[f64], w: &mut [f64]) {
    let m = t.len();
    w.par_iter_mut()
        .zip(matrix.par_chunks(m))
        .for_each(|(wi, row)| *wi = row.iter().zip(t).map(|(a, b)| a * b).sum());
}
