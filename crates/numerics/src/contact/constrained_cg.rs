//! Bound-constrained conjugate gradients for the elastic–perfectly-plastic contact problem.
//!
//! Discrete problem (Polonsky & Keer 1999, Wear 231; pressure saturation as Almqvist et al. 2007,
//! Wear 262): find pressures `0 ≤ pᵢ ≤ p_lim` and the rigid-body approach `δ` such that, with the
//! gap `g = g₀ + K p − δ`,
//! `pᵢ = 0 ⇒ gᵢ ≥ 0`, `0 < pᵢ < p_lim ⇒ gᵢ = 0`, `pᵢ = p_lim ⇒ gᵢ ≤ 0`,
//! and either the mean pressure is prescribed (load control, `δ` unknown) or `δ` is prescribed
//! (approach control). It is the optimality system of the convex quadratic programme
//! `min ½ pᵀK p + pᵀg₀` over the box, with `δ` the multiplier of the load constraint.
//!
//! Iteration (one CG step on the free set `F = {0 < p < p_lim}`): under load control
//! `δ = mean_F(g₀ + K p)`; conjugate direction `t = g + β t_old` on `F` (`β = G/G_old`,
//! `G = Σ_F g²`; reset to 0 — a steepest-descent restart — when more than [`RESTART_FRACTION`] of
//! the free set entered it in the last step, and after every recomputation of `u` that did not
//! confirm convergence); step `τ = Σ_F g t / (tᵀ K t − Σ_F (K t) Σ_F t / |F|)` (the last term
//! under load control only; it vanishes with `Σ_F t` when the free set has not changed, see
//! [`MEAN_FREE_DIRECTION`] and [`CORRECTED_SHARE`] for when it is left out);
//! `p ← p − τ t`, then projection on the box; points at a bound whose gap has the wrong sign
//! (`p = 0, g < 0` or `p = p_lim, g > 0`) re-enter with `p ← p − τ g`. Under load control the
//! load is restored by scaling the free pressures (saturating at `p_lim`); when the free set
//! cannot carry it, the rest goes to the points out of contact of smallest gap (see
//! `Workspace::rebalance_with`).
//!
//! When the CG step is undefined (`Σ_F g t ≤ 0` or `tᵀKt ≤ 0`, or under load control a free set
//! of at most one point, on which `t = g − δ` vanishes: the first step from the rigid-plastic
//! start, taken without transforming that zero direction), the step is taken along the projected
//! gradient `e = g − δ` on the free set and at the points that would re-enter, with its exact
//! length for the unconstrained quadratic, `τ = Σ e² / eᵀ K e` (one more forward FFT). (A step
//! `1/K₀₀`, exact for one isolated point, overshoots when thousands of points re-enter at once;
//! see `docs/contact-solver-design.md`.)
//!
//! Convolutions: the forward FFT of `t` gives `tᵀ K t` by Parseval, `Σ_q K̂(q) |t̂(q)|²`, so the
//! step needs no inverse transform unless the load correction term does. After a linear step the
//! displacement is updated by linearity, `u ← u − τ K t`, from one inverse FFT that recomputes
//! the column transforms of the kept row spectra (one FFT pair per iteration); its output rows
//! update `u` as they are produced (see `workspace::dense`). After a nonlinear correction
//! (projection, re-entry, load rebalancing) `u = K p` is recomputed with a full pair at the start
//! of the next iteration instead (1.5 pairs, or 2 if the step needed `w`). On the rough
//! benchmark almost every step is corrected: a few points enter or leave the contact in nearly
//! every step, so the solver runs at about 1.5 pairs per iteration. Convergence is only accepted
//! on a displacement recomputed from the pressures, so every reported residual is judged on an
//! exact `u`. (Deferring the recomputation while the corrections are small saved at most 6 % of
//! the FFTs of the 1024² benchmark and cost up to 13 % more iterations; deferring it by a fixed
//! number of iterations, or for larger corrections, can stall the iteration.)
//!
//! Convergence: all four [`Residuals`] `≤ ε`. The solve ends `Stalled` when its largest residual
//! has not fallen below 0.9 × its best value for `stall_iterations`, or at once when the load
//! restoration has twice found the free set unable to carry the load from the same state —
//! free-set size and largest residual within [`CYCLE_MATCH`] (a cycle of the load-controlled
//! iteration, seen when almost all contact is saturated).
//!
//! Everything but the transforms (whose inputs are read from the lists) and, after a pending
//! update, one dense pass over the points out of contact runs over explicit contact lists (see
//! [`super::workspace`]).

use super::influence::InfluenceOperator;
use super::options::{Residuals, Termination};
use super::workspace::Workspace;
use crate::fft2::FftFailure;

/// The conjugation restarts (`β = 0`) when the points that entered the free set in the last step
/// (from zero pressure or from saturation) exceed this fraction of it. Polonsky & Keer restart at
/// every entry; on rough surfaces a few points enter in almost every step until the very end, so
/// that rule keeps the iteration at steepest descent. A handful of new points perturbs the
/// conjugacy only slightly; many new points (saturated rough contacts) do, and a higher fraction
/// makes more load-controlled solves stall. The measurements behind 1 % are in
/// `docs/contact-solver-design.md`.
const RESTART_FRACTION: f64 = 0.01;

/// Under load control the step is `τ = Σ_F g t / (tᵀ K t − Σ_F (K t) Σ_F t / |F|)` (Polonsky &
/// Keer). The correction term needs `K t` in real space (an inverse FFT before the step); it is
/// computed only when `|Σ_F t|` exceeds this fraction of `Σ_F |t|` (after the free set changed
/// under a conjugate direction). Below it the step is taken without the term, and the load it
/// moves (`τ Σ_F t`) is restored with the corrections of the step, which a changed free set
/// brings anyway: an inverse FFT for `K t` would mostly be spent on a step whose displacement is
/// recomputed all the same. The threshold leaves iteration counts unchanged and saves FFTs;
/// leaving the term out altogether costs iterations on saturated contacts
/// (`docs/contact-solver-design.md`).
const MEAN_FREE_DIRECTION: f64 = 0.1;

/// Nor is the load-control term computed when the last step projected or re-entered more than
/// this fraction of the free set and no point is saturated: the step will most likely be
/// corrected again, and its displacement recomputed. On an elastic contact loaded from the
/// uniform start the contact area shrinks by projection over the first steps, and `Σ_F t` of
/// the conjugate direction is large in every one of them. With saturated points it is always
/// computed: skipping it there sends saturated contacts to the approach search
/// (`docs/contact-solver-design.md`).
const CORRECTED_SHARE: f64 = 0.05;

/// Two fall-backs of the load restoration are the same state when their free-set sizes and
/// largest residuals agree within this fraction: a cycle may move a point per period, so exact
/// equality of the free-set size would not recognise it.
const CYCLE_MATCH: f64 = 0.02;

/// The state of `u` at the start of an iteration.
enum Displacement {
    /// `u = K p` is recomputed (one FFT pair): at the start, after a pressure correction, and
    /// to confirm convergence.
    Stale,
    /// The linear update `u ← u − τ w` with the kept `w = K t` is still to be applied (by the
    /// pass over the points out of contact; on the contact set the statistics include it).
    Pending(f64),
    /// `u` was updated by linearity, `u ← u − τ K t`, as the inverse FFT wrote it.
    Current,
}

/// What is prescribed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Control {
    /// Prescribed mean pressure `p̄` in Pa.
    Load { nominal_pressure: f64 },
    /// Prescribed rigid-body approach `δ` in m.
    Approach { approach: f64 },
}

/// Fixed parameters of one solve.
#[derive(Debug, Clone, Copy)]
pub(crate) struct CgSettings {
    pub tolerance: f64,
    pub max_iterations: usize,
    pub stall_iterations: usize,
    pub flow_pressure: f64,
    pub gap_scale: f64,
    /// Step `1/K₀₀` in Pa/m when neither the CG step nor the projected-gradient step is defined.
    pub default_step: f64,
}

/// Result of one solve.
#[derive(Debug, Clone, Copy)]
pub(crate) struct CgOutcome {
    pub termination: Termination,
    pub iterations: usize,
    /// Real 2-D FFTs (forward or inverse; a full convolution is two) of this solve.
    pub fft_transforms: usize,
    pub residuals: Residuals,
    pub approach: f64,
    pub mean_pressure: f64,
}

/// Runs the constrained CG from the pressures in `ws.p` (which must satisfy the bounds, and under
/// load control the load). On return `ws.p`, `ws.u = K p` (recomputed exactly) and the gap
/// `ws.g = g₀ + u − δ` hold the last iterate.
pub(crate) fn solve(
    ws: &mut Workspace,
    op: &mut InfluenceOperator,
    control: Control,
    settings: &CgSettings,
) -> Result<CgOutcome, FftFailure> {
    let n = ws.len() as f64;
    let h = settings.gap_scale;
    let (offset, load_control) = match control {
        Control::Approach { approach } => (approach, false),
        Control::Load { .. } => (0.0, true),
    };
    ws.rebuild_contact();
    let mut fft_transforms = 0;
    // `u` was recomputed from `p` at this iterate (not only updated incrementally).
    let mut u_fresh = false;
    let mut displacement = Displacement::Stale;
    // The free-set size and largest residual of the last iteration whose load restoration spread
    // pressure over every point (see `Rebalanced::spread`).
    let mut last_spread: Option<(f64, f64)> = None;
    let mut cycling = false;
    // Σ p over the contact lists (`p` vanishes off them), in parallel.
    let mut p_sum = ws.free_stats().total();
    let mut g_old = 0.0;
    let mut reset = true;
    let mut progress_mark = f64::INFINITY;
    let mut last_progress = 0;
    let mut iterations = 0;
    let mut delta_prev = 0.0;
    // The last step corrected many points of a free set without saturated points (see
    // [`CORRECTED_SHARE`]).
    let mut heavily_corrected = false;
    loop {
        let pending_step = match std::mem::replace(&mut displacement, Displacement::Stale) {
            Displacement::Stale => {
                ws.displace(op, offset)?;
                fft_transforms += 2;
                u_fresh = true;
                None
            }
            Displacement::Pending(tau) => Some(tau),
            Displacement::Current => None,
        };
        let stats = ws.contact_stats(pending_step, offset, delta_prev);
        let has_free = stats.free_count > 0.0;
        // Mean of y = g − δ_prev on F: the correction of δ (load control).
        let shift = if load_control && has_free {
            stats.free_y / stats.free_count
        } else {
            0.0
        };
        let (delta, zero_min) = match (load_control, has_free) {
            (false, _) => (0.0, ws.out_of_contact_pass(pending_step, offset, 0.0)),
            (true, true) => {
                let delta = delta_prev + shift;
                (delta, ws.out_of_contact_pass(pending_step, offset, delta))
            }
            (true, false) => {
                let zero_min = ws.out_of_contact_pass(pending_step, offset, f64::NEG_INFINITY);
                let delta = match (stats.sat_max.is_finite(), zero_min.is_finite()) {
                    (true, true) => 0.5 * (stats.sat_max + zero_min),
                    (true, false) => stats.sat_max,
                    (false, _) => zero_min,
                };
                (delta, ws.out_of_contact_pass(None, offset, delta))
            }
        };
        // Σ_F (g − δ)² from the shifted sums: no cancellation once δ changes little.
        let free_g2 = (stats.free_y2 - stats.free_count * shift * shift).max(0.0);
        let contact = if has_free {
            (stats.free_max - delta).max(delta - stats.free_min)
        } else {
            0.0
        };
        let force = match control {
            Control::Load { nominal_pressure } => {
                (p_sum / n - nominal_pressure).abs() / nominal_pressure
            }
            Control::Approach { .. } => 0.0,
        };
        let residuals = Residuals {
            separation: (delta - zero_min).max(0.0) / h,
            contact: contact / h,
            plastic: (stats.sat_max - delta).max(0.0) / h,
            force,
        };
        let r = residuals.max();
        let termination = if !r.is_finite() {
            Some(Termination::Stalled)
        } else if r <= settings.tolerance && u_fresh {
            Some(Termination::Converged)
        } else if r <= settings.tolerance {
            // Confirm (or correct) on the exact displacement of the current pressures, and restart
            // the conjugation from there: the directions were built on the drifted displacement.
            delta_prev = delta;
            reset = true;
            continue;
        } else if cycling {
            Some(Termination::Stalled)
        } else if iterations >= settings.max_iterations {
            Some(Termination::MaxIterations)
        } else if r < 0.9 * progress_mark {
            progress_mark = r;
            last_progress = iterations;
            None
        } else if iterations - last_progress > settings.stall_iterations {
            Some(Termination::Stalled)
        } else {
            None
        };
        if let Some(termination) = termination {
            if !u_fresh {
                ws.displace(op, offset)?;
                fft_transforms += 2;
            }
            ws.write_gap(offset + delta);
            return Ok(CgOutcome {
                termination,
                iterations,
                fft_transforms,
                residuals,
                approach: offset + delta,
                mean_pressure: p_sum / n,
            });
        }

        let beta = if reset || g_old <= 0.0 {
            0.0
        } else {
            free_g2 / g_old
        };
        g_old = free_g2;
        // `w = K t` in real space, if it was needed for the step.
        let mut w_ready = false;
        let cg_step = if load_control && stats.free_count <= 1.0 {
            // Under load control `δ` is the mean of `g` on the free set, so on a free set of one
            // point (the rigid-plastic start) `t = g − δ` vanishes: no direction to transform.
            None
        } else {
            let [gt, t_sum, t_abs] = ws.direction(beta, offset, delta);
            // `tᵀ K t = Σ_F t (K t)`: `t` vanishes off the free set.
            let mut rt = ws.start_direction_transform(op)?;
            fft_transforms += 1;
            if load_control
                && has_free
                && t_sum.abs() > MEAN_FREE_DIRECTION * t_abs
                && !heavily_corrected
            {
                op.finish_apply(&mut ws.w)?;
                fft_transforms += 1;
                w_ready = true;
                rt -= ws.free_w_sum() * t_sum / stats.free_count;
            }
            (rt > 0.0 && gt > 0.0 && (gt / rt).is_finite()).then_some(gt / rt)
        };
        let breakdown = cg_step.is_none();
        let tau = match cg_step {
            Some(tau) => tau,
            None => {
                // The projected-gradient step (module docs); it replaces `t`, and `reset` below
                // restarts the conjugation.
                let e2 = ws.entry_direction(offset, delta);
                let ek = op.start_apply(&ws.t)?;
                fft_transforms += 1;
                if ek > 0.0 && e2 > 0.0 && (e2 / ek).is_finite() {
                    e2 / ek
                } else {
                    settings.default_step
                }
            }
        };
        let update = ws.update(tau, offset, delta);
        iterations += 1;
        u_fresh = false;
        reset = breakdown || update.entered > RESTART_FRACTION * update.free.free_count;
        heavily_corrected = update.corrected > CORRECTED_SHARE * update.free.free_count
            && update.free.sat_sum == 0.0;
        p_sum = update.pressure_sum;
        delta_prev = delta;
        let mut exact = update.corrected == 0.0 && !breakdown;
        if let Control::Load { nominal_pressure } = control {
            let total = nominal_pressure * n;
            // Round-off drift of the load in linear steps is repaired once it reaches a tenth of
            // the force tolerance.
            if !exact || (p_sum - total).abs() > 0.1 * settings.tolerance * total {
                let rebalanced = ws.rebalance_with(total, update.free);
                p_sum = rebalanced.pressure_sum;
                if rebalanced.spread && iterations > 1 {
                    // A fall-back from the same state as the last one: the load-controlled
                    // iteration cycles (seen when almost all contact is saturated); it stops here
                    // instead of after `stall_iterations`.
                    let state = (stats.free_count, r);
                    cycling = last_spread.is_some_and(|(free, r_last)| {
                        (free - state.0).abs() <= CYCLE_MATCH * state.0
                            && (r - r_last).abs() <= CYCLE_MATCH * r_last
                    });
                    last_spread = Some(state);
                }
                exact = false;
            }
        }
        if exact {
            displacement = if w_ready {
                Displacement::Pending(tau)
            } else {
                ws.advance_displacement(op, tau, offset)?;
                fft_transforms += 1;
                Displacement::Current
            };
        }
    }
}
