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
use super::options::Termination;
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
    // (CG iterations, FFT pairs) summed over the inner solves.
    let mut iterations = (0, 0);
    // The mean pressure of an approach-controlled solve is exact only to the precision of its
    // gaps: a gap error e moves a free point's pressure by ~E*·e/dx, i.e. the mean by up to
    // p_lim·(e/h)-ish relative to p_lim, not to p̄. To resolve P(δ) = p̄ to ε·p̄ the inner solves
    // are converged to ε·p̄/p_lim (and never looser than ε).
    let inner_tolerance = (settings.tolerance * nominal_pressure / settings.flow_pressure)
        .clamp(1e-13, settings.tolerance);
    let inner = |ws: &mut Workspace,
                 op: &mut InfluenceOperator,
                 approach: f64,
                 iterations: &mut (usize, usize)|
     -> Result<Option<(CgOutcome, f64)>, FftFailure> {
        let budget = CgSettings {
            max_iterations: settings.max_iterations.saturating_sub(iterations.0),
            tolerance: inner_tolerance,
            ..*settings
        };
        let out = constrained_cg::solve(ws, op, Control::Approach { approach }, &budget)?;
        iterations.0 += out.iterations;
        iterations.1 += out.fft_transforms;
        Ok(match out.termination {
            Termination::Converged => Some((out, out.mean_pressure - nominal_pressure)),
            _ => None,
        })
    };
    let fail =
        |termination, (iterations, fft_transforms): (usize, usize), last: Option<CgOutcome>| {
            let mean_pressure = last.map_or(0.0, |o| o.mean_pressure);
            let mut residuals = last.map(|o| o.residuals).unwrap_or_default();
            residuals.force = (mean_pressure - nominal_pressure).abs() / nominal_pressure;
            CgOutcome {
                termination,
                iterations,
                fft_transforms,
                residuals,
                approach: last.map_or(start_approach, |o| o.approach),
                mean_pressure,
            }
        };
    let finish = |mut out: CgOutcome, (iterations, fft_transforms): (usize, usize)| {
        out.residuals.force = (out.mean_pressure - nominal_pressure).abs() / nominal_pressure;
        out.iterations = iterations;
        out.fft_transforms = fft_transforms;
        out
    };
    let tolerance = settings.tolerance * nominal_pressure;
    let Some((first, f_first)) = inner(ws, op, start_approach, &mut iterations)? else {
        return Ok(fail(Termination::Stalled, iterations, None));
    };
    if f_first.abs() <= tolerance {
        return Ok(finish(first, iterations));
    }
    // Bracket: step away from the start in the direction that reduces |P − p̄|, doubling.
    let direction = if f_first < 0.0 { 1.0 } else { -1.0 };
    let mut step = 0.1 * settings.gap_scale;
    let (mut a, mut fa) = (start_approach, f_first);
    let mut b = (start_approach, f_first, first);
    let mut outer = 1;
    loop {
        outer += 1;
        let trial = a + direction * step;
        let Some((out, f)) = inner(ws, op, trial, &mut iterations)? else {
            return Ok(fail(Termination::Stalled, iterations, Some(b.2)));
        };
        if f.abs() <= tolerance {
            return Ok(finish(out, iterations));
        }
        if f.signum() != fa.signum() {
            b = (trial, f, out);
            break;
        }
        (a, fa) = (trial, f);
        b = (trial, f, out);
        step *= 2.0;
        if outer >= MAX_OUTER {
            return Ok(fail(
                Termination::ApproachSearchFailed,
                iterations,
                Some(out),
            ));
        }
    }
    // Illinois regula falsi on [a, b].
    let (mut bx, mut fb, mut last) = b;
    while outer < MAX_OUTER {
        outer += 1;
        let x = (a * fb - bx * fa) / (fb - fa);
        let Some((out, f)) = inner(ws, op, x, &mut iterations)? else {
            return Ok(fail(Termination::Stalled, iterations, Some(last)));
        };
        last = out;
        if f.abs() <= tolerance {
            return Ok(finish(out, iterations));
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
    Ok(fail(
        Termination::ApproachSearchFailed,
        iterations,
        Some(last),
    ))
}
