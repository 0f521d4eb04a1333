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
    /// The free set could not carry the load: it was saturated and the rest went to points out
    /// of contact (a fall-back of the iteration, watched for cycles).
    pub spread: bool,
}

impl Workspace {
    /// The rigid–perfectly-plastic start for mean pressure `nominal`: the k = ⌊N·p̄/p_lim⌋ points
    /// of smallest initial gap carry p_lim, the next one the remainder, all others nothing. This
    /// is the exact solution in the limit E* → ∞ and close to it when most of the contact area
    /// is saturated, where a uniform start costs the iteration hundreds of steps. Elastic
    /// problems (p_lim = ∞) start from the uniform p̄.
    pub(crate) fn start_rigid_plastic(&mut self, nominal: f64) {
        let plim = self.plim;
        let n = self.p.len();
        let share = nominal * n as f64 / plim;
        if !(plim.is_finite() && share.is_finite() && share < n as f64) || n == 0 {
            self.p.fill(nominal);
            return;
        }
        let k = share.floor() as usize;
        let remainder = (share - k as f64) * plim;
        if let Some(lowest) = lowest_ranks(&self.g0, k, &mut self.ranks) {
            self.p.par_chunks_mut(BLOCK).for_each(|p| p.fill(0.0));
            place_ranked(&mut self.p, lowest, plim, remainder);
            return;
        }
        // k < n here.
        match kth_smallest(&self.g0, k) {
            Some(kth) => place_smallest(&mut self.p, &self.g0, (k, kth), plim, remainder, |_| 0.0),
            None => self.p.fill(nominal),
        }
    }

    /// Restores `Σ p = total` from pressures set outside the iteration (a warm start).
    pub(crate) fn rebalance(&mut self, total: f64) {
        self.rebuild_contact();
        let stats = self.free_stats();
        self.rebalance_with(total, stats);
    }

    /// Restores `Σ p = total` (`0 < total < N p_lim`): scales the free pressures, saturating at
    /// `p_lim` (Newton on the concave, piecewise-linear `s ↦ Σ_F min(s p, p_lim)`, started left
    /// of the root at `s₀ = need / Σ_F p`, so it increases monotonically). If the free set cannot
    /// carry the load, it is saturated and the rest goes to the points out of contact of smallest
    /// gap (see [`Self::spread_by_gap`]). Otherwise (and when too few points are out of contact,
    /// or nothing caps the pressure) all pressures are shifted, `p ← clamp(p + c, 0, p_lim)`, with `c` by bisection, and the
    /// contact lists rebuilt. `stats` are the free-set statistics of the current pressures.
    pub(super) fn rebalance_with(&mut self, total: f64, stats: FreeStats) -> Rebalanced {
        let plim = self.plim;
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
                    let (f, slope) = self.scaled_free_sum(s);
                    if (need - f).abs() <= 1e-14 * need || slope <= 0.0 {
                        break;
                    }
                    s += (need - f) / slope;
                }
            }
            return Rebalanced {
                pressure_sum: sat_sum + self.scale_free(s),
                spread: false,
            };
        }
        if need > 0.0 && need >= capacity {
            if let Some(r) = self.spread_by_gap(need - capacity) {
                return r;
            }
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
            if self.shifted_sum(mid) < total {
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
            pressure_sum: self.free_stats().total(),
            spread: c > 0.0,
        }
    }

    /// Saturates the free set and gives the load `rest` it cannot carry to the points out of
    /// contact of smallest gap `g₀ + u`, `p_lim` each and the last one the remainder: the
    /// rigid-plastic rule of [`Self::start_rigid_plastic`] on the deformed gap, where contact
    /// would form next. The sampled ranking (`selection::lowest_ranks`) is tried first, the
    /// exact radix selection when it declines (more than `N/16` points, or a sample that misled:
    /// strided samples of a surface with a lay along a grid axis see few independent heights).
    /// `None` (nothing changed) when too few points are out of contact.
    ///
    /// Ranking by gap matters: a uniform upward shift gives every point out of contact the same
    /// pressure whatever its gap, the free set becomes most of the grid and the load-controlled
    /// iteration cycles between such fall-backs. The branch runs about twice per load step on
    /// saturated contacts, so the ranking's buffers are kept in the workspace (measurements:
    /// `docs/contact-solver-design.md`).
    fn spread_by_gap(&mut self, rest: f64) -> Option<Rebalanced> {
        let plim = self.plim;
        if !plim.is_finite() {
            return None;
        }
        let share = rest / plim;
        let m = share.floor() as usize;
        let remainder = (share - m as f64) * plim;
        self.write_out_of_contact_gap();
        let saturate = |p: &mut [f64]| {
            p.par_iter_mut().for_each(|p| {
                if *p > 0.0 {
                    *p = plim;
                }
            })
        };
        if let Some(lowest) = lowest_ranks(&self.g, m, &mut self.ranks) {
            if lowest.last()?.0.is_infinite() {
                return None;
            }
            saturate(&mut self.p);
            place_ranked(&mut self.p, lowest, plim, remainder);
        } else {
            let kth = kth_smallest(&self.g, m)?;
            if kth.is_infinite() {
                return None;
            }
            saturate(&mut self.p);
            place_smallest(&mut self.p, &self.g, (m, kth), plim, remainder, |p| p);
        }
        self.rebuild_contact();
        Some(Rebalanced {
            pressure_sum: self.free_stats().total(),
            spread: true,
        })
    }
}

/// `p_lim` at the ranked points but the last, `remainder` at the last (see
/// `selection::lowest_ranks`).
fn place_ranked(p: &mut [f64], lowest: &[(f64, usize)], plim: f64, remainder: f64) {
    if let Some((&(_, last), full)) = lowest.split_last() {
        full.iter().for_each(|&(_, i)| p[i] = plim);
        p[last] = remainder;
    }
}

/// Sets `p_lim` at the `k` smallest of `values` in the order of `(value, index)` (ties broken
/// by index, as in a stable order), `remainder` at the next one and `other(p)` everywhere else,
/// given `kth`, the `k`-th smallest value (0-based; `selection::kth_smallest`).
fn place_smallest(
    p: &mut [f64],
    values: &[f64],
    (k, kth): (usize, f64),
    plim: f64,
    remainder: f64,
    other: impl Fn(f64) -> f64 + Sync,
) {
    // Per block: points below the k-th value and points tied with it.
    let counts: Vec<(usize, usize)> = values
        .par_chunks(BLOCK)
        .map(|block| {
            block
                .iter()
                .fold((0, 0), |(below, tied), v| match v.total_cmp(&kth) {
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
    p.par_chunks_mut(BLOCK)
        .zip(values.par_chunks(BLOCK))
        .zip(ties_before.collect::<Vec<_>>())
        .for_each(|((p, block), mut tie)| {
            for (pi, v) in p.iter_mut().zip(block) {
                *pi = match v.total_cmp(&kth) {
                    Ordering::Less => plim,
                    Ordering::Equal => {
                        tie += 1;
                        match (tie - 1).cmp(&full_ties) {
                            Ordering::Less => plim,
                            Ordering::Equal => remainder,
                            Ordering::Greater => other(*pi),
                        }
                    }
                    Ordering::Greater => other(*pi),
                };
            }
        });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rigid_plastic_start_fills_the_smallest_gaps_in_index_order_of_ties() {
        // Order by (gap, index): 6, 1, 3, 4, 2, 7, 0, 5. N p̄ / p_lim = 3.5: the first three carry
        // p_lim, the fourth (index 4, the last of the tied gaps 1) half of it.
        let mut ws = Workspace::new(vec![3.0, 1.0, 2.0, 1.0, 1.0, 5.0, 0.0, 2.0], 4, 10.0);
        ws.start_rigid_plastic(3.5 * 10.0 / 8.0);
        assert_eq!(ws.p, vec![0.0, 10.0, 0.0, 10.0, 5.0, 0.0, 10.0, 0.0]);
    }

    #[test]
    fn load_the_free_set_cannot_carry_goes_to_the_smallest_deformed_gaps() {
        // Gaps 63 … 0 µm; the two smallest (points 63, 62) are in contact at 4 Pa each, p_lim
        // 10 Pa: they carry at most 20 of the 25 Pa asked.
        let n = 64;
        let plim = 10.0;
        let start = |u0: f64| {
            let mut ws = Workspace::new(
                (0..n)
                    .map(|i| (n - 1 - i) as f64 * 1e-6)
                    .collect::<Vec<_>>(),
                8,
                plim,
            );
            ws.p[62] = 4.0;
            ws.p[63] = 4.0;
            ws.u[0] = u0;
            ws
        };
        // The rest (half of p_lim) goes to the next smallest gap g₀ + u: point 61, or point 0
        // once its displacement brings it closest.
        for (u0, receiver) in [(0.0, 61), (-1e-4, 0)] {
            let mut ws = start(u0);
            ws.rebalance(25.0);
            let mut expected = vec![0.0; n];
            expected[62] = plim;
            expected[63] = plim;
            expected[receiver] = 5.0;
            assert_eq!(ws.p, expected, "u₀ = {u0}");
        }
        // More points than the sampled ranking takes (N/16): the exact selection, same rule.
        let mut ws = start(0.0);
        ws.rebalance(60.0);
        let mut expected = vec![0.0; n];
        expected[58..].fill(plim);
        assert_eq!(ws.p, expected);
    }

    #[test]
    fn load_spreads_by_gap_also_where_the_strided_sample_misleads() {
        // 512² points, gap 1 µm but 0.5 µm at every point with i % 64 = 1, which the strided
        // sample (every 64th point from 0) never sees: its bound ties with almost every gap and
        // the sampled ranking declines. Two points carry 4 Pa of p_lim = 10 Pa; the load asks
        // 10.5 p_lim more than they can carry: the ten smallest gaps in index order take p_lim,
        // the eleventh the half, as the exact selection finds them (not a shift of every point).
        let (nx, plim) = (512, 10.0);
        let n = nx * nx;
        let g0: Vec<f64> = (0..n)
            .map(|i| if i % 64 == 1 { 0.5e-6 } else { 1e-6 })
            .collect();
        let mut ws = Workspace::new(g0, nx, plim);
        ws.p[0] = 4.0;
        ws.p[2] = 4.0;
        ws.rebalance(2.0 * plim + 10.5 * plim);
        let mut expected = vec![0.0; n];
        expected[0] = plim;
        expected[2] = plim;
        (0..10).for_each(|j| expected[64 * j + 1] = plim);
        expected[64 * 10 + 1] = 0.5 * plim;
        assert!(ws.p == expected, "not the smallest gaps in index order");
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
            let mut ws = Workspace::new(g0.clone(), 128, plim);
            ws.start_rigid_plastic(share * plim / n as f64);
            let k = share as usize;
            let mut expected = vec![0.0; n];
            order[..k].iter().for_each(|&i| expected[i] = plim);
            expected[order[k]] = (share - k as f64) * plim;
            assert_eq!(ws.p, expected, "share {share}");
        }
    }
}
