//! Robust path: outer search on the rigid-body approach with an inner approach-controlled solve.
//!
//! The mean pressure `P(δ)` of the approach-controlled problem is continuous and non-decreasing
//! in `δ`, so `P(δ) = p̄` is solved by bracketing and the Illinois variant of regula falsi
//! (Dowell & Jarratt 1971). Each inner solve is warm-started from the previous pressures and
//! converged on the complementarity residuals; the outer search stops when
//! `|P(δ) − p̄| / p̄ ≤ ε`. This path does not rely on the free set carrying the load, so it
//! remains usable when almost all contact points are saturated, where the load-controlled
//! iteration can stall.

use super::constrained_cg::{self, CgOutcome, CgSettings, Control};
use super::influence::InfluenceOperator;
use super::options::{Termination, INNER_TOLERANCE_FLOOR};
use super::work::Work;
use super::workspace::Workspace;
use crate::fft2::FftFailure;

/// Maximum number of inner solves (bracketing plus regula falsi).
const MAX_OUTER: usize = 200;

/// Solves for the approach giving mean pressure `nominal_pressure` (Pa), starting at
/// `start_approach` (m).
pub(crate) fn solve(
    ws: &mut Workspace,
    op: &mut InfluenceOperator,
    nominal_pressure: f64,
    start_approach: f64,
    settings: &CgSettings,
) -> Result<CgOutcome, FftFailure> {
    let mut search = ApproachSearch::new(nominal_pressure, start_approach, settings);
    let Some((first, f_first)) = search.inner(ws, op, start_approach)? else {
        return Ok(search.fail(Termination::Stalled, None));
    };
    if f_first.abs() <= search.tolerance {
        return Ok(search.finish(first));
    }
    match search.bracket(ws, op, first, f_first)? {
        Bracketing::Ended(outcome) => Ok(outcome),
        Bracketing::Found(bracket) => search.regula_falsi(ws, op, bracket),
    }
}

/// The outer search: its fixed settings and the work counted over its inner solves.
struct ApproachSearch<'a> {
    nominal_pressure: f64,
    start_approach: f64,
    settings: &'a CgSettings,
    /// Complementarity tolerance of the inner solves.
    inner_tolerance: f64,
    /// `|P(δ) − p̄|` (Pa) accepted.
    tolerance: f64,
    /// The work of the inner solves so far.
    work: Work,
    /// Inner solves so far.
    outer: usize,
}

/// A sign change of `P(δ) − p̄` between `a` and `b`, with the last inner solution.
struct Bracket {
    a: f64,
    fa: f64,
    b: f64,
    fb: f64,
    last: CgOutcome,
}

enum Bracketing {
    Found(Bracket),
    /// Converged while bracketing, or failed.
    Ended(CgOutcome),
}

impl<'a> ApproachSearch<'a> {
    fn new(nominal_pressure: f64, start_approach: f64, settings: &'a CgSettings) -> Self {
        // The mean pressure of an approach-controlled solve is exact only to the precision of its
        // gaps: a gap error e moves a free point's pressure by ~E*·e/dx, i.e. the mean by up to
        // p_lim·(e/h)-ish relative to p_lim, not to p̄. To resolve P(δ) = p̄ to ε·p̄ the inner
        // solves are converged to ε·p̄/p_lim, never looser than ε and never tighter than the
        // residual floor of f64 gaps (nor than ε itself, should ε be below that floor).
        let inner_tolerance = (settings.tolerance * nominal_pressure / settings.flow_pressure)
            .max(INNER_TOLERANCE_FLOOR.min(settings.tolerance))
            .min(settings.tolerance);
        Self {
            nominal_pressure,
            start_approach,
            settings,
            inner_tolerance,
            tolerance: settings.tolerance * nominal_pressure,
            work: Work::default(),
            outer: 0,
        }
    }

    /// The approach-controlled solve at `approach` within the remaining iteration budget, and
    /// `P(δ) − p̄`; `None` when it did not converge.
    fn inner(
        &mut self,
        ws: &mut Workspace,
        op: &mut InfluenceOperator,
        approach: f64,
    ) -> Result<Option<(CgOutcome, f64)>, FftFailure> {
        self.outer += 1;
        let budget = CgSettings {
            max_iterations: self
                .settings
                .max_iterations
                .saturating_sub(self.work.iterations),
            tolerance: self.inner_tolerance,
            ..*self.settings
        };
        let out = constrained_cg::solve(ws, op, Control::Approach { approach }, &budget)?;
        self.work += out.work;
        Ok(match out.termination {
            Termination::Converged => Some((out, out.mean_pressure - self.nominal_pressure)),
            _ => None,
        })
    }

    /// Steps away from the start in the direction that reduces `|P − p̄|`, doubling the step,
    /// until the sign changes.
    fn bracket(
        &mut self,
        ws: &mut Workspace,
        op: &mut InfluenceOperator,
        first: CgOutcome,
        f_first: f64,
    ) -> Result<Bracketing, FftFailure> {
        let direction = if f_first < 0.0 { 1.0 } else { -1.0 };
        let mut step = 0.1 * self.settings.gap_scale;
        let (mut a, mut fa) = (self.start_approach, f_first);
        let mut last = first;
        loop {
            let trial = a + direction * step;
            let Some((out, f)) = self.inner(ws, op, trial)? else {
                return Ok(Bracketing::Ended(
                    self.fail(Termination::Stalled, Some(last)),
                ));
            };
            if f.abs() <= self.tolerance {
                return Ok(Bracketing::Ended(self.finish(out)));
            }
            if f.signum() != fa.signum() {
                return Ok(Bracketing::Found(Bracket {
                    a,
                    fa,
                    b: trial,
                    fb: f,
                    last: out,
                }));
            }
            (a, fa) = (trial, f);
            last = out;
            step *= 2.0;
            if self.outer >= MAX_OUTER {
                return Ok(Bracketing::Ended(
                    self.fail(Termination::ApproachSearchFailed, Some(out)),
                ));
            }
        }
    }

    /// Illinois regula falsi on the bracket.
    fn regula_falsi(
        &mut self,
        ws: &mut Workspace,
        op: &mut InfluenceOperator,
        bracket: Bracket,
    ) -> Result<CgOutcome, FftFailure> {
        let Bracket {
            mut a,
            mut fa,
            b: mut bx,
            mut fb,
            mut last,
        } = bracket;
        while self.outer < MAX_OUTER {
            let x = (a * fb - bx * fa) / (fb - fa);
            let Some((out, f)) = self.inner(ws, op, x)? else {
                return Ok(self.fail(Termination::Stalled, Some(last)));
            };
            last = out;
            if f.abs() <= self.tolerance {
                return Ok(self.finish(out));
            }
            if f.signum() != fb.signum() {
                (a, fa) = (bx, fb);
            } else {
                fa *= 0.5;
            }
            (bx, fb) = (x, f);
            if (bx - a).abs() <= f64::EPSILON * bx.abs().max(a.abs()) {
                break;
            }
        }
        Ok(self.fail(Termination::ApproachSearchFailed, Some(last)))
    }

    /// A converged inner solution with the outer work and force residual.
    fn finish(&self, mut out: CgOutcome) -> CgOutcome {
        out.residuals.force =
            (out.mean_pressure - self.nominal_pressure).abs() / self.nominal_pressure;
        out.work = self.work;
        out
    }

    /// The search ended without meeting the load: the last inner solution (if any) and why.
    fn fail(&self, termination: Termination, last: Option<CgOutcome>) -> CgOutcome {
        let mean_pressure = last.map_or(0.0, |o| o.mean_pressure);
        let mut residuals = last.map(|o| o.residuals).unwrap_or_default();
        residuals.force = (mean_pressure - self.nominal_pressure).abs() / self.nominal_pressure;
        CgOutcome {
            termination,
            work: self.work,
            residuals,
            approach: last.map_or(self.start_approach, |o| o.approach),
            mean_pressure,
        }
    }
}
