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
//! `G = Σ_F g²`, reset to 0 when points entered `F`); step `τ = Σ_F g t / Σ_F (K t − mean_F K t) t`;
//! `p ← p − τ t`, then projection on the box; points at a bound whose gap has the wrong sign
//! (`p = 0, g < 0` or `p = p_lim, g > 0`) re-enter with `p ← p − τ g`. Under load control the
//! load is restored by scaling the free pressures (saturating at `p_lim`).
//!
//! Convolutions: one FFT pair `w = K t` per iteration; the displacement is updated by linearity,
//! `u ← u − τ w`, which is exact for the CG step itself. After a nonlinear correction
//! (projection, re-entry, load rebalancing) `u = K p` is recomputed with a second FFT pair at the
//! start of the next iteration, and convergence is only accepted on a displacement recomputed
//! from the pressures, so every residual is judged on an exact `u`. (Deferring the
//! recomputation over several iterations saves FFT pairs but, measured on rough elastic–plastic
//! contact, costs more iterations than it saves, and can stall the iteration.)
//!
//! Convergence: all four [`Residuals`] `≤ ε`.

use rayon::prelude::*;

use super::influence::InfluenceOperator;
use super::options::{Residuals, Termination};
use crate::fft2::FftFailure;

/// Block length of the deterministic parallel reductions (independent of the thread count).
const BLOCK: usize = 1 << 13;

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
    /// Fallback step `1/K₀₀` in Pa/m when the CG step is undefined.
    pub default_step: f64,
}

/// Result of one solve.
#[derive(Debug, Clone, Copy)]
pub(crate) struct CgOutcome {
    pub termination: Termination,
    pub iterations: usize,
    /// Convolutions (one forward and one inverse real 2-D FFT each) of this solve.
    pub fft_pairs: usize,
    pub residuals: Residuals,
    pub approach: f64,
    pub mean_pressure: f64,
}

/// Statistics of the gap pass; `y = g − δ_prev` on the free set `F`.
#[derive(Debug, Clone, Copy)]
struct GapAcc {
    free_y: f64,
    free_y2: f64,
    free_count: f64,
    free_max: f64,
    free_min: f64,
    zero_min: f64,
    sat_max: f64,
}

impl GapAcc {
    const EMPTY: Self = Self {
        free_y: 0.0,
        free_y2: 0.0,
        free_count: 0.0,
        free_max: f64::NEG_INFINITY,
        free_min: f64::INFINITY,
        zero_min: f64::INFINITY,
        sat_max: f64::NEG_INFINITY,
    };
    fn combine(a: Self, b: &Self) -> Self {
        Self {
            free_y: a.free_y + b.free_y,
            free_y2: a.free_y2 + b.free_y2,
            free_count: a.free_count + b.free_count,
            free_max: a.free_max.max(b.free_max),
            free_min: a.free_min.min(b.free_min),
            zero_min: a.zero_min.min(b.zero_min),
            sat_max: a.sat_max.max(b.sat_max),
        }
    }
}

/// Sums of one pass, combined block by block in a fixed order.
#[derive(Debug, Clone, Copy, Default)]
struct Sums([f64; 8]);

impl Sums {
    fn combine(a: Self, b: &Self) -> Self {
        let mut out = a;
        for (o, v) in out.0.iter_mut().zip(b.0) {
            *o += v;
        }
        out
    }
}

/// Free-set statistics after an update: `Σ_F p`, `max_F p`, `Σ_{p = p_lim} p`, `|F|`.
#[derive(Debug, Clone, Copy)]
struct FreeStats {
    free_sum: f64,
    free_max: f64,
    sat_sum: f64,
    free_count: f64,
}

/// Pressures, displacements, gaps and CG vectors of one grid, allocated once.
#[derive(Debug)]
pub(crate) struct Workspace {
    pub g0: Vec<f64>,
    pub p: Vec<f64>,
    pub u: Vec<f64>,
    pub g: Vec<f64>,
    t: Vec<f64>,
    w: Vec<f64>,
    gap_partials: Vec<GapAcc>,
    partials: Vec<Sums>,
}

fn is_free(p: f64, flow_pressure: f64) -> bool {
    p > 0.0 && p < flow_pressure
}

impl Workspace {
    pub(crate) fn new(g0: Vec<f64>) -> Self {
        let n = g0.len();
        let blocks = n.div_ceil(BLOCK).max(1);
        Self {
            g0,
            p: vec![0.0; n],
            u: vec![0.0; n],
            g: vec![0.0; n],
            t: vec![0.0; n],
            w: vec![0.0; n],
            gap_partials: vec![GapAcc::EMPTY; blocks],
            partials: vec![Sums::default(); blocks],
        }
    }

    fn len(&self) -> usize {
        self.p.len()
    }

    /// `g = g₀ + u − offset`; statistics of `y = g − δ_prev` on the free set and of `g` at the
    /// bounds.
    fn gap_pass(&mut self, offset: f64, delta_prev: f64, plim: f64) -> GapAcc {
        self.g
            .par_chunks_mut(BLOCK)
            .zip(self.g0.par_chunks(BLOCK))
            .zip(self.u.par_chunks(BLOCK))
            .zip(self.p.par_chunks(BLOCK))
            .zip(self.gap_partials.par_iter_mut())
            .for_each(|((((g, g0), u), p), acc)| {
                let mut a = GapAcc::EMPTY;
                for (((gi, &g0i), &ui), &pi) in g.iter_mut().zip(g0).zip(u).zip(p) {
                    let v = g0i + ui - offset;
                    *gi = v;
                    if pi <= 0.0 {
                        a.zero_min = a.zero_min.min(v);
                    } else if pi >= plim {
                        a.sat_max = a.sat_max.max(v);
                    } else {
                        let y = v - delta_prev;
                        a.free_y += y;
                        a.free_y2 += y * y;
                        a.free_count += 1.0;
                        a.free_max = a.free_max.max(v);
                        a.free_min = a.free_min.min(v);
                    }
                }
                *acc = a;
            });
        self.gap_partials
            .iter()
            .fold(GapAcc::EMPTY, GapAcc::combine)
    }

    /// `g ← g − δ`.
    fn shift_gap(&mut self, delta: f64) {
        if delta != 0.0 {
            self.g
                .par_chunks_mut(BLOCK)
                .for_each(|g| g.iter_mut().for_each(|gi| *gi -= delta));
        }
    }

    /// `t ← (g − δ) + β t` on the free set, 0 elsewhere.
    fn direction_pass(&mut self, beta: f64, delta: f64, plim: f64) {
        self.t
            .par_chunks_mut(BLOCK)
            .zip(self.g.par_chunks(BLOCK))
            .zip(self.p.par_chunks(BLOCK))
            .for_each(|((t, g), p)| {
                for ((ti, &gi), &pi) in t.iter_mut().zip(g).zip(p) {
                    *ti = if is_free(pi, plim) {
                        (gi - delta) + beta * *ti
                    } else {
                        0.0
                    };
                }
            });
    }

    /// `[Σ_F w, Σ_F w t, Σ_F t, Σ_F (g − δ) t]` with `w = K t`.
    fn step_pass(&mut self, delta: f64, plim: f64) -> [f64; 4] {
        self.partials
            .par_iter_mut()
            .zip(self.w.par_chunks(BLOCK))
            .zip(self.t.par_chunks(BLOCK))
            .zip(self.g.par_chunks(BLOCK))
            .zip(self.p.par_chunks(BLOCK))
            .for_each(|((((acc, w), t), g), p)| {
                let mut a = [0.0; 8];
                for (((&wi, &ti), &gi), &pi) in w.iter().zip(t).zip(g).zip(p) {
                    if is_free(pi, plim) {
                        a[0] += wi;
                        a[1] += wi * ti;
                        a[2] += ti;
                        a[3] += (gi - delta) * ti;
                    }
                }
                *acc = Sums(a);
            });
        let s = self.partials.iter().fold(Sums::default(), Sums::combine).0;
        [s[0], s[1], s[2], s[3]]
    }

    /// CG update `p ← p − τ t`, projection on the box, re-entry `p ← p − τ (g − δ)` at bounds
    /// with a wrong-signed gap, and `u ← u − τ w` (exact when nothing was projected or re-entered).
    /// Returns `(Σ p, points re-entered, points projected, free-set statistics)`.
    fn update_pass(&mut self, tau: f64, delta: f64, plim: f64) -> (f64, f64, f64, FreeStats) {
        self.p
            .par_chunks_mut(BLOCK)
            .zip(self.u.par_chunks_mut(BLOCK))
            .zip(self.w.par_chunks(BLOCK))
            .zip(self.t.par_chunks(BLOCK))
            .zip(self.g.par_chunks(BLOCK))
            .zip(self.partials.par_iter_mut())
            .for_each(|(((((p, u), w), t), g), acc)| {
                let mut a = [0.0; 8];
                for ((((pi, ui), &wi), &ti), &gi) in p.iter_mut().zip(u).zip(w).zip(t).zip(g) {
                    *ui -= tau * wi;
                    let old = *pi;
                    let gap = gi - delta;
                    let new = if is_free(old, plim) {
                        let v = old - tau * ti;
                        if v <= 0.0 || v >= plim {
                            a[2] += 1.0;
                        }
                        v
                    } else if (old <= 0.0 && gap < 0.0) || (old >= plim && gap > 0.0) {
                        a[1] += 1.0;
                        old - tau * gap
                    } else {
                        old
                    };
                    let clamped = new.clamp(0.0, plim);
                    *pi = clamped;
                    a[0] += clamped;
                    if is_free(clamped, plim) {
                        a[3] += clamped;
                        a[4] = f64::max(a[4], clamped);
                        a[6] += 1.0;
                    } else if clamped >= plim {
                        a[5] += clamped;
                    }
                }
                *acc = Sums(a);
            });
        let mut free_max: f64 = 0.0;
        let mut s = [0.0; 8];
        for part in &self.partials {
            free_max = free_max.max(part.0[4]);
            s = Sums::combine(Sums(s), part).0;
        }
        let stats = FreeStats {
            free_sum: s[3],
            free_max,
            sat_sum: s[5],
            free_count: s[6],
        };
        (s[0], s[1], s[2], stats)
    }

    /// Free-set statistics of the current pressures.
    fn free_pass(&mut self, plim: f64) -> FreeStats {
        self.partials
            .par_iter_mut()
            .zip(self.p.par_chunks(BLOCK))
            .for_each(|(acc, p)| {
                let mut a = [0.0; 8];
                for &pi in p {
                    if is_free(pi, plim) {
                        a[0] += pi;
                        a[1] = f64::max(a[1], pi);
                        a[3] += 1.0;
                    } else if pi >= plim {
                        a[2] += pi;
                    }
                }
                *acc = Sums(a);
            });
        let mut free_max: f64 = 0.0;
        let mut s = [0.0; 8];
        for part in &self.partials {
            free_max = free_max.max(part.0[1]);
            s = Sums::combine(Sums(s), part).0;
        }
        FreeStats {
            free_sum: s[0],
            free_max,
            sat_sum: s[2],
            free_count: s[3],
        }
    }

    /// `Σ_F min(s p, p_lim)` and `Σ_{F, s p < p_lim} p`.
    fn scaled_free_sum(&mut self, s: f64, plim: f64) -> (f64, f64) {
        self.partials
            .par_iter_mut()
            .zip(self.p.par_chunks(BLOCK))
            .for_each(|(acc, p)| {
                let mut a = [0.0; 8];
                for &pi in p.iter().filter(|&&pi| is_free(pi, plim)) {
                    if s * pi < plim {
                        a[0] += s * pi;
                        a[1] += pi;
                    } else {
                        a[0] += plim;
                    }
                }
                *acc = Sums(a);
            });
        let sums = self.partials.iter().fold(Sums::default(), Sums::combine);
        (sums.0[0], sums.0[1])
    }

    /// `Σ clamp(p + c, 0, p_lim)` over all points.
    fn shifted_sum(&mut self, c: f64, plim: f64) -> f64 {
        self.partials
            .par_iter_mut()
            .zip(self.p.par_chunks(BLOCK))
            .for_each(|(acc, p)| {
                acc.0[0] = p.iter().map(|&pi| (pi + c).clamp(0.0, plim)).sum();
            });
        self.partials.iter().map(|s| s.0[0]).sum()
    }

    /// Restores `Σ p = total` (`0 < total < N p_lim`): scales the free pressures, saturating at
    /// `p_lim` (Newton on the concave, piecewise-linear `s ↦ Σ_F min(s p, p_lim)`, started left
    /// of the root at `s₀ = need / Σ_F p`, so it increases monotonically); if the free set cannot
    /// carry the load, shifts all pressures, `p ← clamp(p + c, 0, p_lim)`, with `c` by bisection.
    /// `stats` are the free-set statistics of the current pressures if known. Returns `Σ p`.
    /// The rigid–perfectly-plastic start for mean pressure `nominal`: the k = ⌊N·p̄/p_lim⌋ points
    /// of smallest initial gap carry p_lim, the next one the remainder, all others nothing. This
    /// is the exact solution in the limit E* → ∞ and close to it when most of the contact area
    /// is saturated, where a uniform start costs the iteration hundreds of steps. Elastic
    /// problems (p_lim = ∞) start from the uniform p̄.
    pub(crate) fn start_rigid_plastic(&mut self, nominal: f64, plim: f64) {
        let n = self.p.len();
        let share = nominal * n as f64 / plim;
        if !(plim.is_finite() && share.is_finite() && share < n as f64) || n == 0 {
            self.p.fill(nominal);
            return;
        }
        let k = share.floor() as usize;
        let mut order: Vec<usize> = (0..n).collect();
        let by_gap = |a: &usize, b: &usize| self.g0[*a].total_cmp(&self.g0[*b]).then(a.cmp(b));
        if k < n {
            order.select_nth_unstable_by(k, by_gap);
        }
        self.p.fill(0.0);
        for &i in &order[..k] {
            self.p[i] = plim;
        }
        if k < n {
            self.p[order[k]] = (share - k as f64) * plim;
        }
    }

    pub(crate) fn rebalance(&mut self, total: f64, plim: f64) -> f64 {
        let stats = self.free_pass(plim);
        self.rebalance_with(total, plim, stats)
    }

    fn rebalance_with(&mut self, total: f64, plim: f64, stats: FreeStats) -> f64 {
        let FreeStats {
            free_sum,
            free_max,
            sat_sum,
            free_count,
        } = stats;
        let need = total - sat_sum;
        let capacity = free_count * plim;
        if free_sum > 0.0 && need > 0.0 && need < capacity {
            let mut s = need / free_sum;
            if s * free_max >= plim {
                for _ in 0..100 {
                    let (f, slope) = self.scaled_free_sum(s, plim);
                    if (need - f).abs() <= 1e-14 * need || slope <= 0.0 {
                        break;
                    }
                    s += (need - f) / slope;
                }
            }
            self.p
                .par_chunks_mut(BLOCK)
                .zip(self.partials.par_iter_mut())
                .for_each(|(p, acc)| {
                    let mut sum = 0.0;
                    for pi in p.iter_mut().filter(|pi| is_free(**pi, plim)) {
                        *pi = (s * *pi).min(plim);
                        sum += *pi;
                    }
                    acc.0[0] = sum;
                });
            let new_free: f64 = self.partials.iter().map(|a| a.0[0]).sum();
            return sat_sum + new_free;
        }
        let n = self.len() as f64;
        let pmax = self.p.iter().copied().fold(0.0, f64::max);
        let (mut lo, mut hi) = (-pmax, if plim.is_finite() { plim } else { total / n });
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if self.shifted_sum(mid, plim) < total {
                lo = mid;
            } else {
                hi = mid;
            }
            if hi - lo <= 1e-15 * hi.abs().max(lo.abs()) {
                break;
            }
        }
        let c = 0.5 * (lo + hi);
        self.p
            .par_chunks_mut(BLOCK)
            .for_each(|p| p.iter_mut().for_each(|pi| *pi = (*pi + c).clamp(0.0, plim)));
        self.p.iter().sum()
    }
}

/// Runs the constrained CG from the pressures in `ws.p` (which must satisfy the bounds, and under
/// load control the load). On return `ws.p`, `ws.u = K p` (recomputed exactly) and `ws.g` hold
/// the last iterate.
pub(crate) fn solve(
    ws: &mut Workspace,
    op: &mut InfluenceOperator,
    control: Control,
    settings: &CgSettings,
) -> Result<CgOutcome, FftFailure> {
    let plim = settings.flow_pressure;
    let n = ws.len() as f64;
    let h = settings.gap_scale;
    let mut fft_pairs = 0;
    // `u` was recomputed from `p` at this iterate (not only updated incrementally).
    let mut u_fresh = false;
    // `u = K p` must be recomputed before the next gap pass: at the start, after a change of `p`
    // that `u ← u − τ w` does not account for, and to confirm convergence.
    let mut recompute = true;
    let mut p_sum: f64 = ws.p.iter().sum();
    let mut g_old = 0.0;
    let mut reset = true;
    let mut progress_mark = f64::INFINITY;
    let mut last_progress = 0;
    let mut iterations = 0;
    let mut delta_prev = 0.0;
    loop {
        if recompute {
            op.apply(&ws.p, &mut ws.u)?;
            fft_pairs += 1;
            u_fresh = true;
        }
        let (offset, load_control) = match control {
            Control::Approach { approach } => (approach, false),
            Control::Load { .. } => (0.0, true),
        };
        let stats = ws.gap_pass(offset, delta_prev, plim);
        let has_free = stats.free_count > 0.0;
        // Mean of y = g − δ_prev on F: the correction of δ (load control).
        let shift = if load_control && has_free {
            stats.free_y / stats.free_count
        } else {
            0.0
        };
        let delta = match (load_control, has_free) {
            (false, _) => 0.0,
            (true, true) => delta_prev + shift,
            (true, false) => match (stats.sat_max.is_finite(), stats.zero_min.is_finite()) {
                (true, true) => 0.5 * (stats.sat_max + stats.zero_min),
                (true, false) => stats.sat_max,
                (false, _) => stats.zero_min,
            },
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
            separation: (delta - stats.zero_min).max(0.0) / h,
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
            // Confirm (or correct) on the exact displacement of the current pressures.
            recompute = true;
            delta_prev = delta;
            continue;
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
                op.apply(&ws.p, &mut ws.u)?;
                fft_pairs += 1;
                ws.gap_pass(offset, delta, plim);
            }
            ws.shift_gap(delta);
            return Ok(CgOutcome {
                termination,
                iterations,
                fft_pairs,
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
        ws.direction_pass(beta, delta, plim);
        op.apply(&ws.t, &mut ws.w)?;
        fft_pairs += 1;
        let [w_sum, wt, t_sum, gt] = ws.step_pass(delta, plim);
        let rt = match control {
            Control::Load { .. } if has_free => wt - w_sum / stats.free_count * t_sum,
            Control::Load { .. } => 0.0,
            Control::Approach { .. } => wt,
        };
        let breakdown = !(rt > 0.0 && gt > 0.0 && (gt / rt).is_finite());
        let tau = if breakdown {
            settings.default_step
        } else {
            gt / rt
        };
        let (new_sum, entered, projected, free_stats) = ws.update_pass(tau, delta, plim);
        iterations += 1;
        u_fresh = false;
        reset = breakdown || entered > 0.0;
        p_sum = new_sum;
        delta_prev = delta;
        let mut nonlinear = entered > 0.0 || projected > 0.0 || breakdown;
        if let Control::Load { nominal_pressure } = control {
            let total = nominal_pressure * n;
            // Round-off drift of the load in linear steps is repaired once it reaches a tenth of
            // the force tolerance.
            if nonlinear || (p_sum - total).abs() > 0.1 * settings.tolerance * total {
                p_sum = ws.rebalance_with(total, plim, free_stats);
                nonlinear = true;
            }
        }
        recompute = nonlinear;
    }
}
