//! Starting pressures and the restoration of the load `Σ p = N p̄` between CG steps.

use super::workspace::{FreeStats, Workspace};

/// Result of a load restoration.
#[derive(Debug, Clone, Copy)]
pub(super) struct Rebalanced {
    /// `Σ p` after it.
    pub pressure_sum: f64,
    /// The shift was upwards: every point out of contact received pressure, i.e. the iterate
    /// fell back to contact everywhere.
    pub spread: bool,
}

impl Workspace {
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

    /// Restores `Σ p = total` from pressures set outside the iteration (a warm start).
    pub(crate) fn rebalance(&mut self, total: f64, plim: f64) {
        self.rebuild_contact();
        let stats = self.free_stats(plim);
        self.rebalance_with(total, plim, stats);
    }

    /// Restores `Σ p = total` (`0 < total < N p_lim`): scales the free pressures, saturating at
    /// `p_lim` (Newton on the concave, piecewise-linear `s ↦ Σ_F min(s p, p_lim)`, started left
    /// of the root at `s₀ = need / Σ_F p`, so it increases monotonically); if the free set cannot
    /// carry the load, shifts all pressures, `p ← clamp(p + c, 0, p_lim)`, with `c` by bisection,
    /// and rebuilds the contact lists. `stats` are the free-set statistics of the current
    /// pressures.
    pub(super) fn rebalance_with(&mut self, total: f64, plim: f64, stats: FreeStats) -> Rebalanced {
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
            return Rebalanced {
                pressure_sum: sat_sum + self.scale_free(s, plim),
                spread: false,
            };
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
            .iter_mut()
            .for_each(|pi| *pi = (*pi + c).clamp(0.0, plim));
        self.rebuild_contact();
        Rebalanced {
            pressure_sum: self.p.iter().sum(),
            spread: c > 0.0,
        }
    }
}
