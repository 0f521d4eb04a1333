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
//! Preconditioning (elastic contacts whose start is a coarser grid's solution, the multilevel
//! start; [`CgSettings::precondition`]): the direction is built
//! from `z = M r` instead of the residual `r = g − δ` on `F`, where `M` is the convolution whose
//! spectrum is the reciprocal of the elastic kernel's, `M̂(q) = 1/K̂(q)` (0 at `q = 0`): the
//! inverse of the elastic operator on the whole grid, applied to `r` extended by zero and read
//! back on `F` (the FFT-based approximate inverse of Zhao, Vollebregt & Oosterlee 2014, Numer.
//! Linear Algebra Appl. 21, used here as the preconditioner of the constrained CG). Only
//! load-controlled solves are preconditioned; `z` is shifted to zero mean on `F`, so that `Σ_F t`
//! stays 0 as it does for `r`;
//! `β = ρ/ρ_old` with `ρ = Σ_F r z`, and `τ` as above. `K` damps the short wavelengths of a
//! pressure error by `1/|q|`, so the plain iteration removes them slowly and leaves spurious
//! small pressures at the spot edges; `M` weighs all wavelengths alike. It costs one more FFT pair
//! per iteration and saves more than that on rough elastic contacts (`docs/contact-solver-design.md`).
//! Along a preconditioned direction `τ` is dimensionless, so a point entering the contact takes
//! `−τ g / K₀₀`. From the rigid-plastic start, whose free set is far from the solution's, the
//! preconditioned steps change the free set more and save fewer iterations than the extra pair
//! costs. With a flow pressure it is not used: re-entries from saturation with that step stalled
//! the iteration.
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
//! exact `u`. (Deferring the recomputation after small corrections does not pay, and deferring it
//! longer can stall the iteration: `docs/contact-solver-design.md`.)
//!
//! Convergence: all four [`Residuals`] `≤ ε`. The solve ends `Stalled` when its largest residual
//! has not fallen below 0.9 × its best value for `stall_iterations`, or at once when the load
//! restoration has twice found the free set unable to carry the load from the same state —
//! free-set size and largest residual within [`CYCLE_MATCH`] (a cycle of the load-controlled
//! iteration, seen when almost all contact is saturated).
//!
//! Structure: [`solve`] drives a small state machine, argmin style — [`ConstrainedCg::init`],
//! then per iteration [`ConstrainedCg::measure`] (the gap statistics, δ and the residuals of the
//! iterate), [`ConstrainedCg::decide`] (converged, confirm, stop, or step) and
//! [`ConstrainedCg::next_iter`] (the step, the pressure update, the load restoration), or, where
//! few points are still moving, [`ConstrainedCg::free_set_tail`] (those points iterated alone
//! with the operator restricted to them, `free_set.rs`, between two recomputations of `u`).
//!
//! Everything but the transforms (whose inputs are read from the lists) and, after a pending
//! update, one dense pass over the points out of contact runs over explicit contact lists (see
//! [`super::workspace`]).
//!
//! Mixed precision ([`CgSettings::mixed_precision`], `precision.rs`): the iteration may run on
//! single-precision transforms first and ends in double precision, where every convergence is
//! judged.

use super::free_set::{self, FreeSetTask};
use super::influence::InfluenceOperator;
use super::options::{Residuals, Termination};
use super::work::Work;
use super::workspace::{ContactStats, FreeStats, Workspace};
use crate::fft2::FftFailure;

mod precision;
mod step;

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
    /// The conjugate directions are built from the preconditioned residual `M r` (module docs).
    pub precondition: bool,
    /// Iterate on single-precision transforms first (`precision.rs`).
    pub mixed_precision: bool,
}

/// Result of one solve.
#[derive(Debug, Clone, Copy)]
pub(crate) struct CgOutcome {
    pub termination: Termination,
    pub work: Work,
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
    let mut cg = ConstrainedCg::init(ws, op, control, settings);
    loop {
        let m = cg.measure()?;
        match cg.decide(&m) {
            Decision::Stop(termination) => return cg.finish(termination, &m),
            Decision::Confirm => cg.confirm(&m),
            Decision::Double => cg.end_single_phase(&m),
            Decision::Step if cg.free_set_applies(&m) => cg.free_set_tail(&m)?,
            Decision::Step => cg.next_iter(&m)?,
        }
    }
}

/// One measured iterate.
struct Measurement {
    /// `|F|`, the free-set size.
    free_count: f64,
    /// δ of this iterate (solved for under load control, 0 under approach control).
    delta: f64,
    /// `Σ_F (g − δ)²`.
    free_g2: f64,
    residuals: Residuals,
}

/// What follows a measurement.
enum Decision {
    Stop(Termination),
    /// The residuals meet the tolerance on an incrementally updated `u`: recompute `u = K p` and
    /// measure again.
    Confirm,
    /// The single-precision phase ends: recompute `u = K p` in double precision and measure
    /// again.
    Double,
    Step,
}

/// The iteration between two measurements: the problem (held once) and the state the next
/// iteration needs.
struct ConstrainedCg<'a> {
    ws: &'a mut Workspace,
    op: &'a mut InfluenceOperator,
    control: Control,
    settings: &'a CgSettings,
    /// The prescribed approach under approach control, else 0 (δ is then solved for).
    offset: f64,
    /// Grid points.
    n: f64,
    /// The operator's transform count when this solve started.
    start_transforms: usize,
    iterations: usize,
    free_set_iterations: usize,
    /// The largest residual when the free set was last iterated alone: it is iterated alone
    /// again only once the residual has halved since (no alternation with the confirmation).
    free_set_mark: f64,
    /// `u` was recomputed from `p` at this iterate (not only updated incrementally).
    u_fresh: bool,
    /// The transforms are in single precision (`precision.rs`).
    single: bool,
    displacement: Displacement,
    /// Σ p over the contact lists (`p` vanishes off them).
    p_sum: f64,
    /// δ of the last measured iterate.
    delta_prev: f64,
    /// `Σ_F g²` of the last step, the denominator of β.
    g_old: f64,
    /// The next direction restarts the conjugation (β = 0).
    reset: bool,
    /// The last step corrected many points of a free set without saturated points (see
    /// [`CORRECTED_SHARE`]).
    heavily_corrected: bool,
    /// The largest residual last improved on by a factor 0.9, and at which iteration.
    progress_mark: f64,
    last_progress: usize,
    /// The free-set size and largest residual of the last iteration whose load restoration
    /// spread pressure over every point (see `Rebalanced::spread`).
    last_spread: Option<(f64, f64)>,
    /// Two such fall-backs came from the same state.
    cycling: bool,
}

impl<'a> ConstrainedCg<'a> {
    fn init(
        ws: &'a mut Workspace,
        op: &'a mut InfluenceOperator,
        control: Control,
        settings: &'a CgSettings,
    ) -> Self {
        let offset = match control {
            Control::Approach { approach } => approach,
            Control::Load { .. } => 0.0,
        };
        ws.rebuild_contact();
        let p_sum = ws.free_stats().total();
        let n = ws.len() as f64;
        let start_transforms = op.transforms();
        let single = precision::start(settings, op);
        Self {
            ws,
            op,
            control,
            settings,
            offset,
            n,
            start_transforms,
            iterations: 0,
            free_set_iterations: 0,
            free_set_mark: f64::INFINITY,
            u_fresh: false,
            single,
            displacement: Displacement::Stale,
            p_sum,
            delta_prev: 0.0,
            g_old: 0.0,
            reset: true,
            heavily_corrected: false,
            progress_mark: f64::INFINITY,
            last_progress: 0,
            last_spread: None,
            cycling: false,
        }
    }

    fn load_control(&self) -> bool {
        matches!(self.control, Control::Load { .. })
    }

    /// Brings `u` up to date (or leaves a pending linear update to the passes below), then
    /// measures the gap: δ, the out-of-contact minimum and the four residuals.
    fn measure(&mut self) -> Result<Measurement, FftFailure> {
        let pending_step = match std::mem::replace(&mut self.displacement, Displacement::Stale) {
            Displacement::Stale => {
                self.ws.displace(self.op, self.offset)?;
                self.u_fresh = true;
                None
            }
            Displacement::Pending(tau) => Some(tau),
            Displacement::Current => None,
        };
        let stats = self
            .ws
            .contact_stats(pending_step, self.offset, self.delta_prev);
        let has_free = stats.free_count > 0.0;
        // Mean of y = g − δ_prev on F: the correction of δ (load control).
        let shift = if self.load_control() && has_free {
            stats.free_y / stats.free_count
        } else {
            0.0
        };
        let (delta, zero_min) = self.approach_and_separation(&stats, pending_step, shift);
        // Σ_F (g − δ)² from the shifted sums: no cancellation once δ changes little.
        let free_g2 = (stats.free_y2 - stats.free_count * shift * shift).max(0.0);
        Ok(Measurement {
            free_count: stats.free_count,
            delta,
            free_g2,
            residuals: self.residuals(&stats, delta, zero_min),
        })
    }

    /// δ (under load control: shifted by the free set's mean gap, or between the saturated
    /// and the out-of-contact gaps when the free set is empty) and the smallest gap out of
    /// contact, from the pass over the points out of contact.
    fn approach_and_separation(
        &mut self,
        stats: &ContactStats,
        pending_step: Option<f64>,
        shift: f64,
    ) -> (f64, f64) {
        let load_control = self.load_control();
        let (ws, offset) = (&mut *self.ws, self.offset);
        match (load_control, stats.free_count > 0.0) {
            (false, _) => (0.0, ws.out_of_contact_pass(pending_step, offset, 0.0)),
            (true, true) => {
                let delta = self.delta_prev + shift;
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
        }
    }

    /// The residuals of the complementarity conditions (scaled by the gap scale) and of the load.
    fn residuals(&self, stats: &ContactStats, delta: f64, zero_min: f64) -> Residuals {
        let h = self.settings.gap_scale;
        let contact = if stats.free_count > 0.0 {
            (stats.free_max - delta).max(delta - stats.free_min)
        } else {
            0.0
        };
        let force = match self.control {
            Control::Load { nominal_pressure } => {
                (self.p_sum / self.n - nominal_pressure).abs() / nominal_pressure
            }
            Control::Approach { .. } => 0.0,
        };
        Residuals {
            separation: (delta - zero_min).max(0.0) / h,
            contact: contact / h,
            plastic: (stats.sat_max - delta).max(0.0) / h,
            force,
        }
    }

    /// The convergence criterion (every residual ≤ the tolerance on a recomputed `u`) and the
    /// stopping rules of the module docs.
    fn decide(&mut self, m: &Measurement) -> Decision {
        if self.single {
            return self.decide_single(m);
        }
        let r = m.residuals.max();
        let settings = self.settings;
        if !r.is_finite() {
            Decision::Stop(Termination::NonFinite)
        } else if r <= settings.tolerance && self.u_fresh {
            Decision::Stop(Termination::Converged)
        } else if r <= settings.tolerance {
            Decision::Confirm
        } else if self.cycling {
            Decision::Stop(Termination::Stalled)
        } else if self.iterations >= settings.max_iterations {
            Decision::Stop(Termination::MaxIterations)
        } else if r < 0.9 * self.progress_mark {
            self.progress_mark = r;
            self.last_progress = self.iterations;
            Decision::Step
        } else if self.iterations - self.last_progress > settings.stall_iterations {
            Decision::Stop(Termination::Stalled)
        } else {
            Decision::Step
        }
    }

    /// Confirms (or corrects) on the exact displacement of the current pressures, restarting the
    /// conjugation there: the directions were built on the drifted displacement. (`measure` left
    /// the displacement stale, so the next measurement recomputes it.)
    fn confirm(&mut self, m: &Measurement) {
        self.delta_prev = m.delta;
        self.reset = true;
    }

    /// The outcome, with `u = K p` recomputed exactly and the gap written.
    fn finish(self, termination: Termination, m: &Measurement) -> Result<CgOutcome, FftFailure> {
        if !self.u_fresh {
            self.ws.displace(self.op, self.offset)?;
        }
        self.ws.write_gap(self.offset + m.delta);
        Ok(CgOutcome {
            termination,
            work: Work {
                iterations: self.iterations,
                free_set_iterations: self.free_set_iterations,
                fft_transforms: self.op.transforms() - self.start_transforms,
            },
            residuals: m.residuals,
            approach: self.offset + m.delta,
            mean_pressure: self.p_sum / self.n,
        })
    }

    /// One step: direction and length, the projected pressure update, the load restoration,
    /// and how `u` follows.
    fn next_iter(&mut self, m: &Measurement) -> Result<(), FftFailure> {
        let load_control = self.load_control();
        let precondition = self.settings.precondition && load_control && m.free_count > 1.0;
        let (rho, z_mean) = if precondition {
            self.ws.precondition(self.op, self.offset, m.delta)?;
            let [z_sum, rz, r_sum] = self.ws.preconditioned_sums(self.offset, m.delta);
            let z_mean = z_sum / m.free_count;
            (rz - z_mean * r_sum, Some(z_mean))
        } else {
            (m.free_g2, None)
        };
        let beta = if self.reset || self.g_old <= 0.0 {
            0.0
        } else {
            rho / self.g_old
        };
        self.g_old = rho;
        let step = self.step_length(m, beta, z_mean)?;
        // Along a preconditioned direction `τ` is dimensionless (`≈ 1` where `M ≈ K⁻¹`); a point
        // entering the contact takes the pressure that closes its own gap, `−τ g / K₀₀`.
        let tau_entry = if z_mean.is_some() && !step.breakdown {
            step.tau * self.settings.default_step
        } else {
            step.tau
        };
        let update = self.ws.update(step.tau, tau_entry, self.offset, m.delta);
        self.iterations += 1;
        self.u_fresh = false;
        self.reset = step.breakdown || update.entered > RESTART_FRACTION * update.free.free_count;
        self.heavily_corrected = update.corrected > CORRECTED_SHARE * update.free.free_count
            && update.free.sat_sum == 0.0;
        self.p_sum = update.pressure_sum;
        self.delta_prev = m.delta;
        let linear = update.corrected == 0.0 && !step.breakdown;
        let exact = self.restore_load(m, linear, update.free);
        if exact {
            self.displacement = if step.w_ready {
                Displacement::Pending(step.tau)
            } else {
                self.ws
                    .advance_displacement(self.op, step.tau, self.offset)?;
                Displacement::Current
            };
        }
        Ok(())
    }

    /// The moving points are iterated alone (`free_set.rs`) when the load is met, their set is
    /// small enough (checked again, with the points that are not free, by `free_set::iterate`)
    /// and the residual has halved since the last time.
    fn free_set_applies(&self, m: &Measurement) -> bool {
        let r = m.residuals;
        let tolerance = self.settings.tolerance;
        r.force <= tolerance
            && r.max() < 0.5 * self.free_set_mark
            && free_set::applies(m.free_count, self.n)
    }

    /// Iterates the moving points alone, then leaves `u` to be recomputed by the next
    /// measurement; takes a CG step on the grid instead if they took none.
    fn free_set_tail(&mut self, m: &Measurement) -> Result<(), FftFailure> {
        self.free_set_mark = m.residuals.max();
        let task = FreeSetTask::new(
            self.load_control(),
            self.offset,
            self.settings.flow_pressure,
            self.settings.tolerance,
            self.settings.gap_scale,
        );
        let outcome = free_set::iterate(self.ws, self.op, task, m.delta, m.free_count);
        if outcome.iterations == 0 {
            return self.next_iter(m);
        }
        self.free_set_iterations += outcome.iterations;
        self.p_sum = self.ws.free_stats().total();
        self.delta_prev = outcome.delta;
        self.u_fresh = false;
        self.reset = true;
        Ok(())
    }

    /// Under load control, restores the load after a corrected step (or once the round-off drift
    /// of linear steps reaches a tenth of the force tolerance) and watches the fall-backs for a
    /// cycle. Returns whether `p` is still the linear step's, so `u` may follow by linearity.
    fn restore_load(&mut self, m: &Measurement, linear: bool, free: FreeStats) -> bool {
        let Control::Load { nominal_pressure } = self.control else {
            return linear;
        };
        let total = nominal_pressure * self.n;
        let drift = (self.p_sum - total).abs() > 0.1 * self.settings.tolerance * total;
        if linear && !drift {
            return true;
        }
        let rebalanced = self.ws.rebalance_with(total, free);
        self.p_sum = rebalanced.pressure_sum;
        if rebalanced.spread && self.iterations > 1 {
            // A fall-back from the same state as the last one: the load-controlled iteration
            // cycles (seen when almost all contact is saturated); it stops here instead of after
            // `stall_iterations`.
            let state = (m.free_count, m.residuals.max());
            let (free_now, r) = state;
            self.cycling = self.last_spread.is_some_and(|(free_last, r_last)| {
                (free_last - free_now).abs() <= CYCLE_MATCH * free_now
                    && (r - r_last).abs() <= CYCLE_MATCH * r_last
            });
            self.last_spread = Some(state);
        }
        false
    }
}
