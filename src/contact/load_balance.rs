//! Starting pressures and the restoration of the load `Σ p = N p̄` between CG steps.

use std::cmp::Ordering;

use rayon::prelude::*;

use super::selection::{kth_smallest, lowest_ranks};
use super::workspace::{FreeStats, Workspace, BLOCK};

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
        let remainder = (share - k as f64) * plim;
        if let Some(lowest) = lowest_ranks(&self.g0, k) {
            self.p.par_chunks_mut(BLOCK).for_each(|p| p.fill(0.0));
            if let Some((&kth, full)) = lowest.split_last() {
                full.iter().for_each(|&i| self.p[i] = plim);
                self.p[kth] = remainder;
            }
            return;
        }
        // k < n here. The k-th smallest gap (0-based), ties broken by index as in a stable order
        // of (gap, index): the first `k` points of that order carry p_lim, the next one the rest.
        let Some(kth) = kth_smallest(&self.g0, k) else {
            self.p.fill(nominal);
            return;
        };
        // Per block: points below the k-th gap and points tied with it.
        let counts: Vec<(usize, usize)> = self
            .g0
            .par_chunks(BLOCK)
            .map(|g0| {
                g0.iter()
                    .fold((0, 0), |(below, tied), g| match g.total_cmp(&kth) {
                        Ordering::Less => (below + 1, tied),
                        Ordering::Equal => (below, tied + 1),
                        Ordering::Greater => (below, tied),
                    })
            })
            .collect();
        // The tied points carrying p_lim, then the one with the remainder, in index order.
        let full_ties = k - counts.iter().map(|&(below, _)| below).sum::<usize>();
        let ties_before = counts.iter().scan(0, |before, &(_, tied)| {
            let first = *before;
            *before += tied;
            Some(first)
        });
        self.p
            .par_chunks_mut(BLOCK)
            .zip(self.g0.par_chunks(BLOCK))
            .zip(ties_before.collect::<Vec<_>>())
            .for_each(|((p, g0), mut tie)| {
                for (pi, g) in p.iter_mut().zip(g0) {
                    *pi = match g.total_cmp(&kth) {
                        Ordering::Less => plim,
                        Ordering::Equal => {
                            tie += 1;
                            match (tie - 1).cmp(&full_ties) {
                                Ordering::Less => plim,
                                Ordering::Equal => remainder,
                                Ordering::Greater => 0.0,
                            }
                        }
                        Ordering::Greater => 0.0,
                    };
                }
            });
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
        let pmax = self
            .p
            .par_chunks(BLOCK)
            .map(|p| p.iter().copied().fold(0.0, f64::max))
            .reduce(|| 0.0, f64::max);
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
            .par_iter_mut()
            .for_each(|pi| *pi = (*pi + c).clamp(0.0, plim));
        self.rebuild_contact();
        Rebalanced {
            pressure_sum: self.free_stats(plim).total(),
            spread: c > 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rigid_plastic_start_fills_the_smallest_gaps_in_index_order_of_ties() {
        // Order by (gap, index): 6, 1, 3, 4, 2, 7, 0, 5. N p̄ / p_lim = 3.5: the first three carry
        // p_lim, the fourth (index 4, the last of the tied gaps 1) half of it.
        let mut ws = Workspace::new(vec![3.0, 1.0, 2.0, 1.0, 1.0, 5.0, 0.0, 2.0], 4);
        ws.start_rigid_plastic(3.5 * 10.0 / 8.0, 10.0);
        assert_eq!(ws.p, vec![0.0, 10.0, 0.0, 10.0, 5.0, 0.0, 10.0, 0.0]);
    }

    #[test]
    fn rigid_plastic_start_is_the_same_by_either_selection() {
        // 2¹⁴ gaps with many ties: small shares take the sampled selection, large ones the radix
        // selection; both must give the order of (gap, index).
        let n = 1 << 14;
        let g0: Vec<f64> = (0..n).map(|i| ((i * 7919) % 211) as f64 * 1e-7).collect();
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&a, &b| g0[a].total_cmp(&g0[b]).then(a.cmp(&b)));
        let plim = 4e9;
        for share in [0.3, 7.5, 100.25, 1000.5, 5000.75] {
            let mut ws = Workspace::new(g0.clone(), 128);
            ws.start_rigid_plastic(share * plim / n as f64, plim);
            let k = share as usize;
            let mut expected = vec![0.0; n];
            order[..k].iter().for_each(|&i| expected[i] = plim);
            expected[order[k]] = (share - k as f64) * plim;
            assert_eq!(ws.p, expected, "share {share}");
        }
    }
}
