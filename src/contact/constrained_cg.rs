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
//! load is restored by scaling the free pressures (saturating at `p_lim`). The displacement is
//! updated as `u ← u − τ K t` when no projection occurred, otherwise recomputed with one FFT pair;
//! convergence is always confirmed on an exactly recomputed displacement.
//!
//! Convergence: all four [`Residuals`] `≤ ε`.

use rayon::prelude::*;

use super::fft2d::FftFailure;
use super::influence::InfluenceOperator;
use super::options::{Residuals, Termination};

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
    pub residuals: Residuals,
    pub approach: f64,
    pub mean_pressure: f64,
}

#[derive(Debug, Clone, Copy)]
struct GapAcc {
    free_sum: f64,
    free_count: f64,
    zero_min: f64,
    sat_max: f64,
}

impl GapAcc {
    const EMPTY: Self = Self {
        free_sum: 0.0,
        free_count: 0.0,
        zero_min: f64::INFINITY,
        sat_max: f64::NEG_INFINITY,
    };
    fn combine(a: Self, b: &Self) -> Self {
        Self {
            free_sum: a.free_sum + b.free_sum,
            free_count: a.free_count + b.free_count,
            zero_min: a.zero_min.min(b.zero_min),
            sat_max: a.sat_max.max(b.sat_max),
        }
    }
}

/// Sums of one pass, combined block by block in a fixed order.
#[derive(Debug, Clone, Copy, Default)]
struct Sums([f64; 4]);

impl Sums {
    fn combine(a: Self, b: &Self) -> Self {
        Self([
            a.0[0] + b.0[0],
            a.0[1] + b.0[1],
            a.0[2] + b.0[2],
            a.0[3] + b.0[3],
        ])
    }
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

    /// `g = g₀ + u − offset`; statistics of `g` on the free set and at the bounds.
    fn gap_pass(&mut self, offset: f64, plim: f64) -> GapAcc {
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
                        a.free_sum += v;
                        a.free_count += 1.0;
                    }
                }
                *acc = a;
            });
        self.gap_partials
            .iter()
            .fold(GapAcc::EMPTY, GapAcc::combine)
    }

    /// `g ← g − δ`; returns `[Σ_F g², max sep. violation, max |g| on F, max plastic violation]`.
    fn residual_pass(&mut self, delta: f64, plim: f64) -> [f64; 4] {
        self.g
            .par_chunks_mut(BLOCK)
            .zip(self.p.par_chunks(BLOCK))
            .zip(self.partials.par_iter_mut())
            .for_each(|((g, p), acc)| {
                let mut a = [0.0; 4];
                for (gi, &pi) in g.iter_mut().zip(p) {
                    let v = *gi - delta;
                    *gi = v;
                    if pi <= 0.0 {
                        a[1] = f64::max(a[1], -v);
                    } else if pi >= plim {
                        a[3] = f64::max(a[3], v);
                    } else {
                        a[0] += v * v;
                        a[2] = f64::max(a[2], v.abs());
                    }
                }
                *acc = Sums(a);
            });
        self.partials.iter().fold([0.0; 4], |a, b| {
            [
                a[0] + b.0[0],
                a[1].max(b.0[1]),
                a[2].max(b.0[2]),
                a[3].max(b.0[3]),
            ]
        })
    }

    /// `t ← g + β t` on the free set, 0 elsewhere.
    fn direction_pass(&mut self, beta: f64, plim: f64) {
        self.t
            .par_chunks_mut(BLOCK)
            .zip(self.g.par_chunks(BLOCK))
            .zip(self.p.par_chunks(BLOCK))
            .for_each(|((t, g), p)| {
                for ((ti, &gi), &pi) in t.iter_mut().zip(g).zip(p) {
                    *ti = if is_free(pi, plim) {
                        gi + beta * *ti
                    } else {
                        0.0
                    };
                }
            });
    }

    /// `[Σ_F w, Σ_F w t, Σ_F t, Σ_F g t]` with `w = K t`.
    fn step_pass(&mut self, plim: f64) -> Sums {
        self.partials
            .par_iter_mut()
            .zip(self.w.par_chunks(BLOCK))
            .zip(self.t.par_chunks(BLOCK))
            .zip(self.g.par_chunks(BLOCK))
            .zip(self.p.par_chunks(BLOCK))
            .for_each(|((((acc, w), t), g), p)| {
                let mut a = [0.0; 4];
                for (((&wi, &ti), &gi), &pi) in w.iter().zip(t).zip(g).zip(p) {
                    if is_free(pi, plim) {
                        a[0] += wi;
                        a[1] += wi * ti;
                        a[2] += ti;
                        a[3] += gi * ti;
                    }
                }
                *acc = Sums(a);
            });
        self.partials.iter().fold(Sums::default(), Sums::combine)
    }

    /// CG update, projection and re-entry; returns `[Σ p, points re-entered, points projected, 0]`.
    fn update_pass(&mut self, tau: f64, plim: f64) -> Sums {
        self.p
            .par_chunks_mut(BLOCK)
            .zip(self.t.par_chunks(BLOCK))
            .zip(self.g.par_chunks(BLOCK))
            .zip(self.partials.par_iter_mut())
            .for_each(|(((p, t), g), acc)| {
                let mut a = [0.0; 4];
                for ((pi, &ti), &gi) in p.iter_mut().zip(t).zip(g) {
                    let old = *pi;
                    let new = if is_free(old, plim) {
                        let v = old - tau * ti;
                        if v <= 0.0 || v >= plim {
                            a[2] += 1.0;
                        }
                        v
                    } else if (old <= 0.0 && gi < 0.0) || (old >= plim && gi > 0.0) {
                        a[1] += 1.0;
                        old - tau * gi
                    } else {
                        old
                    };
                    let clamped = new.clamp(0.0, plim);
                    *pi = clamped;
                    a[0] += clamped;
                }
                *acc = Sums(a);
            });
        self.partials.iter().fold(Sums::default(), Sums::combine)
    }

    /// `u ← u − τ w`.
    fn displacement_pass(&mut self, tau: f64) {
        self.u
            .par_chunks_mut(BLOCK)
            .zip(self.w.par_chunks(BLOCK))
            .for_each(|(u, w)| u.iter_mut().zip(w).for_each(|(ui, &wi)| *ui -= tau * wi));
    }

    /// `[Σ_F p, max_F p, Σ_{p ≥ p_lim} p, |F|]`.
    fn free_pass(&mut self, plim: f64) -> Sums {
        self.partials
            .par_iter_mut()
            .zip(self.p.par_chunks(BLOCK))
            .for_each(|(acc, p)| {
                let mut a = [0.0; 4];
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
        self.partials.iter().fold(Sums::default(), |a, b| {
            Sums([
                a.0[0] + b.0[0],
                a.0[1].max(b.0[1]),
                a.0[2] + b.0[2],
                a.0[3] + b.0[3],
            ])
        })
    }

    /// `Σ_F min(s p, p_lim)` and `Σ_{F, s p < p_lim} p`.
    fn scaled_free_sum(&mut self, s: f64, plim: f64) -> (f64, f64) {
        self.partials
            .par_iter_mut()
            .zip(self.p.par_chunks(BLOCK))
            .for_each(|(acc, p)| {
                let mut a = [0.0; 4];
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
    /// `p_lim` (Newton on the concave, piecewise-linear `s ↦ Σ_F min(s p, p_lim)`); if the free set
    /// cannot carry the load, shifts all pressures, `p ← clamp(p + c, 0, p_lim)`, with `c` by
    /// bisection. Returns the new `Σ p`.
    pub(crate) fn rebalance(&mut self, total: f64, plim: f64) -> f64 {
        let stats = self.free_pass(plim);
        let [free_sum, free_max, sat_sum, free_count] = stats.0;
        let need = total - sat_sum;
        let capacity = free_count * plim;
        if free_sum > 0.0 && need > 0.0 && need < capacity {
            let mut s = need / free_sum;
            if s * free_max >= plim {
                s = 0.0;
                for _ in 0..100 {
                    let (f, slope) = self.scaled_free_sum(s, plim);
                    if (need - f).abs() <= 1e-14 * need || slope <= 0.0 {
                        break;
                    }
                    s += (need - f) / slope;
                }
            }
            self.p.par_chunks_mut(BLOCK).for_each(|p| {
                for pi in p.iter_mut().filter(|pi| is_free(**pi, plim)) {
                    *pi = (s * *pi).min(plim);
                }
            });
            return sat_sum + self.scaled_free_sum(1.0, plim).0;
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
/// load control the load). On return `ws.p`, `ws.u = K p` and `ws.g` hold the last iterate.
pub(crate) fn solve(
    ws: &mut Workspace,
    op: &mut InfluenceOperator,
    control: Control,
    settings: &CgSettings,
) -> Result<CgOutcome, FftFailure> {
    let plim = settings.flow_pressure;
    let n = ws.len() as f64;
    op.apply(&ws.p, &mut ws.u)?;
    let mut u_exact = true;
    let mut p_sum: f64 = ws.p.iter().sum();
    let mut g_old = 0.0;
    let mut reset = true;
    let mut progress_mark = f64::INFINITY;
    let mut last_progress = 0;
    let mut iterations = 0;
    loop {
        let offset = match control {
            Control::Approach { approach } => approach,
            Control::Load { .. } => 0.0,
        };
        let stats = ws.gap_pass(offset, plim);
        let delta = match control {
            Control::Approach { .. } => 0.0,
            Control::Load { .. } if stats.free_count > 0.0 => stats.free_sum / stats.free_count,
            Control::Load { .. } => match (stats.sat_max.is_finite(), stats.zero_min.is_finite()) {
                (true, true) => 0.5 * (stats.sat_max + stats.zero_min),
                (true, false) => stats.sat_max,
                (false, _) => stats.zero_min,
            },
        };
        let [free_g2, separation, contact, plastic] = ws.residual_pass(delta, plim);
        let force = match control {
            Control::Load { nominal_pressure } => {
                (p_sum / n - nominal_pressure).abs() / nominal_pressure
            }
            Control::Approach { .. } => 0.0,
        };
        let h = settings.gap_scale;
        let residuals = Residuals {
            separation: separation / h,
            contact: contact / h,
            plastic: plastic / h,
            force,
        };
        let outcome = |termination| CgOutcome {
            termination,
            iterations,
            residuals,
            approach: offset + delta,
            mean_pressure: p_sum / n,
        };
        let r = residuals.max();
        if !r.is_finite() {
            return Ok(outcome(Termination::Stalled));
        }
        if r <= settings.tolerance {
            if u_exact {
                return Ok(outcome(Termination::Converged));
            }
            op.apply(&ws.p, &mut ws.u)?;
            u_exact = true;
            continue;
        }
        if iterations >= settings.max_iterations {
            return Ok(outcome(Termination::MaxIterations));
        }
        if r < 0.9 * progress_mark {
            progress_mark = r;
            last_progress = iterations;
        } else if iterations - last_progress > settings.stall_iterations {
            return Ok(outcome(Termination::Stalled));
        }

        let beta = if reset || g_old <= 0.0 {
            0.0
        } else {
            free_g2 / g_old
        };
        g_old = free_g2;
        ws.direction_pass(beta, plim);
        op.apply(&ws.t, &mut ws.w)?;
        let Sums([w_sum, wt, t_sum, gt]) = ws.step_pass(plim);
        let rt = match control {
            Control::Load { .. } if stats.free_count > 0.0 => wt - w_sum / stats.free_count * t_sum,
            Control::Load { .. } => 0.0,
            Control::Approach { .. } => wt,
        };
        let breakdown = !(rt > 0.0 && gt > 0.0 && (gt / rt).is_finite());
        let tau = if breakdown {
            settings.default_step
        } else {
            gt / rt
        };
        let Sums([new_sum, entered, projected, _]) = ws.update_pass(tau, plim);
        iterations += 1;
        reset = breakdown || entered > 0.0;
        p_sum = new_sum;
        let mut nonlinear = entered > 0.0 || projected > 0.0 || breakdown;
        if let Control::Load { nominal_pressure } = control {
            let total = nominal_pressure * n;
            if nonlinear || (p_sum - total).abs() > 1e-13 * total {
                p_sum = ws.rebalance(total, plim);
                nonlinear = true;
            }
        }
        if nonlinear {
            op.apply(&ws.p, &mut ws.u)?;
            u_exact = true;
        } else {
            ws.displacement_pass(tau);
            u_exact = false;
        }
    }
}
