//! Arrays and passes of the constrained conjugate-gradient iteration, organised around the
//! contact set.
//!
//! At the loads of interest the true contact area is a few per cent of the grid (A/A₀ ≈ 0.7 % for
//! the 20 MPa rough benchmark), so every quantity that lives on the contact set — the free-set
//! statistics, the conjugate direction, the step sums, the pressure update and the load
//! rebalancing — is computed over an explicit list of contact points (`p > 0`). The dense side
//! lives in [`dense`]: the transforms (which read `p` and `t` from the lists and, while writing
//! `u`, take each row's smallest gap out of contact) and the check of `g ≥ 0` out of contact
//! (the separation residual and the points that re-enter the contact), which scans only the
//! blocks that reach below `δ`.
//!
//! The grid is cut into blocks of [`BLOCK`] points; each block keeps its own ascending list of
//! contact points, so every pass runs in parallel over blocks with safe disjoint writes, and every
//! reduction is combined block by block in a fixed order: results do not depend on the number of
//! threads. The lists are reused from iteration to iteration (no allocation once they reached
//! their size).

use std::sync::Arc;

use rayon::prelude::*;

use super::restricted_matrix::RestrictedMatrix;
use super::selection::RankBuffers;

mod dense;
mod moving;
mod preconditioned;
mod stats;

pub(crate) use stats::{ContactStats, FreeStats};

/// Points per block (independent of the thread count).
pub(crate) const BLOCK: usize = 1 << 13;

/// What one pressure update did.
#[derive(Debug, Clone, Copy)]
pub(crate) struct UpdateOutcome {
    /// `Σ p` after the update.
    pub pressure_sum: f64,
    /// Points at a bound with a wrong-signed gap that re-entered the free set.
    pub entered: f64,
    /// Free-set statistics of the new pressures.
    pub free: FreeStats,
    /// Points whose new pressure differs from the linear CG step `p − τ t` (projections and
    /// re-entries): the displacement update `u ← u − τ w` does not account for them.
    pub corrected: f64,
}

/// One block of the grid: its contact list and the partial results of the last pass.
#[derive(Debug, Clone)]
struct Block {
    /// Local indices of the points with `p > 0`, ascending.
    contact: Vec<u32>,
    /// Points out of contact whose gap is negative at the current `δ`: local index and `g − δ`.
    entering: Vec<(u32, f64)>,
    /// Scratch list for rebuilding `contact`.
    merged: Vec<u32>,
    /// Points out of contact whose direction is not yet cleared (it is kept until the next
    /// conjugation, as a point that is back in contact by then continues its direction).
    dropped: Vec<u32>,
    stats: ContactStats,
    free: FreeStats,
    sums: [f64; 4],
    zero_min: f64,
}

impl Block {
    fn new() -> Self {
        Self {
            contact: Vec::new(),
            entering: Vec::new(),
            merged: Vec::new(),
            dropped: Vec::new(),
            stats: ContactStats::EMPTY,
            free: FreeStats::EMPTY,
            sums: [0.0; 4],
            zero_min: f64::INFINITY,
        }
    }
}

/// The per-block output of a pressure update: new pressures and contact list, statistics.
struct Settled<'a> {
    p: &'a mut [f64],
    t: &'a [f64],
    in_contact: &'a mut [bool],
    merged: &'a mut Vec<u32>,
    dropped: &'a mut Vec<u32>,
    free: FreeStats,
    corrected: f64,
}

impl Settled<'_> {
    /// Sets `p[l] = clamp(new, 0, p_lim)` where the linear CG step predicted `linear`; a point
    /// left with `p > 0` joins the new contact list, one at 0 is recorded as dropped.
    fn set(&mut self, l: usize, new: f64, linear: f64, plim: f64) {
        let clamped = new.clamp(0.0, plim);
        self.in_contact[l] = clamped > 0.0;
        self.p[l] = clamped;
        if clamped != linear {
            self.corrected += 1.0;
        }
        if clamped > 0.0 {
            self.merged.push(l as u32);
            self.free.add(clamped, plim);
        } else if self.t[l] != 0.0 {
            self.dropped.push(l as u32);
        }
    }
}

/// Runs `visit(base, block)` for every block in parallel; `base` is the global index of the
/// block's first point.
fn each_block(blocks: &mut [Block], visit: impl Fn(usize, &mut Block) + Sync + Send) {
    blocks
        .par_iter_mut()
        .enumerate()
        .for_each(|(b, block)| visit(b * BLOCK, block));
}

/// Runs `visit(base, t, block)` for every block in parallel, with the block's slice of the
/// direction `t`, after clearing the direction of the block's recorded points that are still
/// out of contact (a point back in contact keeps it) and emptying the record: the start of
/// every pass that builds a new direction.
fn each_direction_block(
    t: &mut [f64],
    p: &[f64],
    blocks: &mut [Block],
    visit: impl Fn(usize, &mut [f64], &mut Block) + Sync + Send,
) {
    t.par_chunks_mut(BLOCK)
        .zip(blocks.par_iter_mut())
        .enumerate()
        .for_each(|(b, (t, block))| {
            let base = b * BLOCK;
            for &l in &block.dropped {
                if p[base + l as usize] <= 0.0 {
                    t[l as usize] = 0.0;
                }
            }
            block.dropped.clear();
            visit(base, t, block);
        });
}

/// The first three partial sums of every block, combined in block order.
fn three_sums(blocks: &[Block]) -> [f64; 3] {
    blocks.iter().fold([0.0; 3], |mut s, b| {
        s.iter_mut().zip(b.sums).for_each(|(o, v)| *o += v);
        s
    })
}

/// Global indices of a block's contact points.
fn contact_points(base: usize, contact: &[u32]) -> impl Iterator<Item = usize> + '_ {
    contact.iter().map(move |&l| base + l as usize)
}

fn is_free(p: f64, flow_pressure: f64) -> bool {
    p > 0.0 && p < flow_pressure
}

/// Pressures, displacements, gaps and CG vectors of one grid, allocated once.
#[derive(Debug)]
pub(crate) struct Workspace {
    /// Initial gap `g₀` in m, shared with the problem's gap (read only: not a copy of it).
    pub g0: Arc<Vec<f64>>,
    /// `p > 0`, one byte per point: the dense passes over the points out of contact read it
    /// beside `g₀` instead of `p`.
    in_contact: Vec<bool>,
    /// Pressure in Pa.
    pub p: Vec<f64>,
    /// Composite elastic displacement `u = K p` in m.
    pub u: Vec<f64>,
    /// Gap `g₀ + u − δ` in m of the last iterate (written when a solve returns; scratch during a
    /// solve).
    pub g: Vec<f64>,
    /// Conjugate direction: zero at saturated points and, whenever it is convolved, off the
    /// contact set.
    pub(super) t: Vec<f64>,
    /// `w = K t` (and `M r` while a preconditioned direction is built, `preconditioned.rs`).
    pub(super) w: Vec<f64>,
    blocks: Vec<Block>,
    /// Buffers of the ranking of gaps (rigid-plastic start, load restoration).
    pub(super) ranks: RankBuffers,
    /// The operator restricted to the points last iterated alone (`free_set.rs`).
    pub(in crate::contact) restricted: RestrictedMatrix,
    /// Points per grid row.
    nx: usize,
    /// Per grid row, `min_{p = 0} (g₀ + u − offset)` as the last inverse transform left it.
    row_min: Vec<f64>,
    /// `row_min` holds for the current `u` and `p` (cleared whenever either changes otherwise).
    row_min_current: bool,
    /// The flow pressure p_lim (Pa; +∞ for a purely elastic contact): the cap on every point's
    /// pressure, constant for the workspace's problem.
    pub(super) plim: f64,
}

impl Workspace {
    /// The pressure, gap and displacement of the last iterate, `[p, g, u]`, the rest released.
    pub(crate) fn into_solution(self) -> [Vec<f64>; 3] {
        let Self { p, g, u, .. } = self;
        [p, g, u]
    }

    /// The workspace of a grid of `g0.len()` points in rows of `nx`, pressures capped at `plim`.
    pub(crate) fn new(g0: impl Into<Arc<Vec<f64>>>, nx: usize, plim: f64) -> Self {
        let g0 = g0.into();
        let n = g0.len();
        let nx = nx.max(1);
        let blocks = n.div_ceil(BLOCK).max(1);
        Self {
            in_contact: vec![false; n],
            g0,
            p: vec![0.0; n],
            u: vec![0.0; n],
            g: vec![0.0; n],
            t: vec![0.0; n],
            w: vec![0.0; n],
            blocks: vec![Block::new(); blocks],
            ranks: RankBuffers::default(),
            restricted: RestrictedMatrix::default(),
            nx,
            row_min: vec![f64::INFINITY; n.div_ceil(nx)],
            row_min_current: false,
            plim,
        }
    }

    pub(super) fn len(&self) -> usize {
        self.p.len()
    }

    /// Rebuilds the contact lists and `in_contact` from `p` (after `p` was set or shifted outside the
    /// CG step); points out of contact with a direction left are recorded to be cleared at the
    /// next conjugation.
    pub(super) fn rebuild_contact(&mut self) {
        self.row_min_current = false;
        self.blocks
            .par_iter_mut()
            .zip(self.in_contact.par_chunks_mut(BLOCK))
            .zip(self.p.par_chunks(BLOCK))
            .zip(self.t.par_chunks(BLOCK))
            .for_each(|(((block, in_contact), p), t)| {
                block.contact.clear();
                block.dropped.clear();
                for (l, (c, (&pi, &ti))) in in_contact.iter_mut().zip(p.iter().zip(t)).enumerate() {
                    *c = pi > 0.0;
                    if pi > 0.0 {
                        block.contact.push(l as u32);
                    } else {
                        if ti != 0.0 {
                            block.dropped.push(l as u32);
                        }
                    }
                }
            });
    }

    /// [`ContactStats`] of `v = g₀ + u − τ w − offset` with `y = v − δ_prev`, where
    /// `pending_step = Some(τ)` is a displacement update not yet applied (`τ = 0` otherwise).
    pub(super) fn contact_stats(
        &mut self,
        pending_step: Option<f64>,
        offset: f64,
        delta_prev: f64,
    ) -> ContactStats {
        let plim = self.plim;
        let (g0, u, p, w) = (&self.g0, &self.u, &self.p, &self.w);
        let tau = pending_step.unwrap_or(0.0);
        each_block(&mut self.blocks, |base, block| {
            let mut s = ContactStats::EMPTY;
            for i in contact_points(base, &block.contact) {
                let v = g0[i] + (u[i] - tau * w[i]) - offset;
                s.add(v, v - delta_prev, p[i], plim);
            }
            block.stats = s;
        });
        self.blocks.iter().fold(ContactStats::EMPTY, |a, b| {
            ContactStats::combine(a, &b.stats)
        })
    }

    /// `t ← (v − δ) + β t` on the free set, 0 at saturated points and off the contact set;
    /// returns `[Σ_F (v − δ) t, Σ_F t, Σ_F |t|]` of the new direction.
    pub(super) fn direction(&mut self, beta: f64, offset: f64, delta: f64) -> [f64; 3] {
        self.conjugate(beta, offset, delta, |_, r| r)
    }

    /// `t ← d + β t` on the free set with `d = descent(i, r)` for the residual
    /// `r = g₀ + u − offset − δ` at point `i`, 0 at saturated points and off the contact set;
    /// returns `[Σ_F r t, Σ_F t, Σ_F |t|]` of the new direction.
    fn conjugate(
        &mut self,
        beta: f64,
        offset: f64,
        delta: f64,
        descent: impl Fn(usize, f64) -> f64 + Sync + Send,
    ) -> [f64; 3] {
        let plim = self.plim;
        let (g0, u, p) = (&self.g0, &self.u, &self.p);
        each_direction_block(&mut self.t, p, &mut self.blocks, |base, t, block| {
            let mut sums = [0.0; 4];
            for &l in &block.contact {
                let (i, l) = (base + l as usize, l as usize);
                t[l] = if p[i] < plim {
                    let r = g0[i] + u[i] - offset - delta;
                    let ti = descent(i, r) + beta * t[l];
                    sums[0] += r * ti;
                    sums[1] += ti;
                    sums[2] += ti.abs();
                    ti
                } else {
                    0.0
                };
            }
            block.sums = sums;
        });
        three_sums(&self.blocks)
    }

    /// The projected-gradient direction of a step the CG cannot take (see
    /// `constrained_cg::solve`): `t ← v − δ` on the free set, at saturated points with an open
    /// gap and at the recorded out-of-contact points with a negative gap, 0 elsewhere on the
    /// contact set; returns `Σ t²`.
    pub(super) fn entry_direction(&mut self, offset: f64, delta: f64) -> f64 {
        let plim = self.plim;
        let (g0, u, p) = (&self.g0, &self.u, &self.p);
        each_direction_block(&mut self.t, p, &mut self.blocks, |base, t, block| {
            let mut sum = 0.0;
            for &l in &block.contact {
                let (i, l) = (base + l as usize, l as usize);
                let r = g0[i] + u[i] - offset - delta;
                t[l] = if p[i] < plim || r > 0.0 { r } else { 0.0 };
                sum += t[l] * t[l];
            }
            for &(l, gap) in &block.entering {
                t[l as usize] = gap;
                sum += gap * gap;
            }
            block.sums[0] = sum;
        });
        self.blocks.iter().map(|b| b.sums[0]).sum()
    }

    /// `Σ_F w` with `w = K t`.
    pub(super) fn free_w_sum(&mut self) -> f64 {
        let plim = self.plim;
        let (p, w) = (&self.p, &self.w);
        each_block(&mut self.blocks, |base, block| {
            block.sums[0] = contact_points(base, &block.contact)
                .filter(|&i| p[i] < plim)
                .map(|i| w[i])
                .sum();
        });
        self.blocks.iter().map(|b| b.sums[0]).sum()
    }

    /// CG update of the contact points `p ← p − τ t` (free) and re-entry `p ← p − τ (v − δ)` at
    /// saturated points with an open gap and at the recorded out-of-contact points with a
    /// negative gap; projection on `[0, p_lim]`. Points that drop to 0 leave the contact list,
    /// re-entered points join it. `u` is not changed.
    pub(super) fn update(
        &mut self,
        tau: f64,
        tau_entry: f64,
        offset: f64,
        delta: f64,
    ) -> UpdateOutcome {
        let plim = self.plim;
        self.row_min_current = false;
        let (g0, u) = (&self.g0, &self.u);
        self.p
            .par_chunks_mut(BLOCK)
            .zip(self.t.par_chunks(BLOCK))
            .zip(self.in_contact.par_chunks_mut(BLOCK))
            .zip(self.blocks.par_iter_mut())
            .enumerate()
            .for_each(|(b, (((p, t), in_contact), block))| {
                let base = b * BLOCK;
                let Block {
                    contact,
                    entering,
                    merged,
                    dropped,
                    ..
                } = block;
                merged.clear();
                let mut settled = Settled {
                    p,
                    t,
                    in_contact,
                    merged,
                    dropped,
                    free: FreeStats::EMPTY,
                    corrected: 0.0,
                };
                let mut entered = 0.0;
                let mut next_entering = entering.iter().peekable();
                for &l in contact.iter() {
                    while let Some(&&(e, gap)) = next_entering.peek() {
                        if e >= l {
                            break;
                        }
                        entered += 1.0;
                        settled.set(e as usize, -tau_entry * gap, 0.0, plim);
                        next_entering.next();
                    }
                    let (l, i) = (l as usize, base + l as usize);
                    let old = settled.p[l];
                    let (new, linear) = if old < plim {
                        let v = old - tau * settled.t[l];
                        (v, v)
                    } else {
                        let gap = g0[i] + u[i] - offset - delta;
                        if gap > 0.0 {
                            entered += 1.0;
                            (old - tau_entry * gap, old)
                        } else {
                            (old, old)
                        }
                    };
                    settled.set(l, new, linear, plim);
                }
                for &(e, gap) in next_entering {
                    entered += 1.0;
                    settled.set(e as usize, -tau_entry * gap, 0.0, plim);
                }
                let (free, corrected) = (settled.free, settled.corrected);
                std::mem::swap(contact, merged);
                block.free = free;
                block.sums = [entered, corrected, 0.0, 0.0];
            });
        self.update_outcome()
    }

    /// The blocks' counts and free-set statistics of the last [`Self::update`], added up in
    /// block order.
    fn update_outcome(&self) -> UpdateOutcome {
        let mut out = UpdateOutcome {
            pressure_sum: 0.0,
            entered: 0.0,
            free: FreeStats::EMPTY,
            corrected: 0.0,
        };
        for b in &self.blocks {
            out.entered += b.sums[0];
            out.corrected += b.sums[1];
            out.free = FreeStats::combine(out.free, &b.free);
        }
        out.pressure_sum = out.free.total();
        out
    }

    /// Free-set statistics of the current pressures (contact lists must be current).
    pub(super) fn free_stats(&mut self) -> FreeStats {
        let plim = self.plim;
        let p = &self.p;
        each_block(&mut self.blocks, |base, block| {
            let mut free = FreeStats::EMPTY;
            for i in contact_points(base, &block.contact) {
                free.add(p[i], plim);
            }
            block.free = free;
        });
        self.blocks
            .iter()
            .fold(FreeStats::EMPTY, |a, b| FreeStats::combine(a, &b.free))
    }

    /// `(Σ_F min(s p, p_lim), Σ_{F, s p < p_lim} p)`.
    pub(super) fn scaled_free_sum(&mut self, s: f64) -> (f64, f64) {
        let plim = self.plim;
        let p = &self.p;
        each_block(&mut self.blocks, |base, block| {
            let mut a = [0.0; 4];
            for i in contact_points(base, &block.contact) {
                let pi = p[i];
                if is_free(pi, plim) {
                    if s * pi < plim {
                        a[0] += s * pi;
                        a[1] += pi;
                    } else {
                        a[0] += plim;
                    }
                }
            }
            block.sums = a;
        });
        self.blocks
            .iter()
            .fold((0.0, 0.0), |(f, d), b| (f + b.sums[0], d + b.sums[1]))
    }

    /// `p ← min(s p, p_lim)` on the free set; returns the new `Σ_F p`.
    pub(super) fn scale_free(&mut self, s: f64) -> f64 {
        let plim = self.plim;
        self.row_min_current = false;
        self.p
            .par_chunks_mut(BLOCK)
            .zip(self.blocks.par_iter_mut())
            .for_each(|(p, block)| {
                let mut sum = 0.0;
                for &l in &block.contact {
                    let pi = &mut p[l as usize];
                    if is_free(*pi, plim) {
                        *pi = (s * *pi).min(plim);
                        sum += *pi;
                    }
                }
                block.sums[0] = sum;
            });
        self.blocks.iter().map(|b| b.sums[0]).sum()
    }

    /// `Σ clamp(p + c, 0, p_lim)` over all points: the contact points one by one, the points
    /// out of contact (`p = 0`) together as `n₀ · clamp(c, 0, p_lim)` (contact lists must be
    /// current).
    pub(super) fn shifted_sum(&mut self, c: f64) -> f64 {
        let plim = self.plim;
        let p = &self.p;
        each_block(&mut self.blocks, |base, block| {
            block.sums[0] = contact_points(base, &block.contact)
                .map(|i| (p[i] + c).clamp(0.0, plim))
                .sum();
        });
        let in_contact: usize = self.blocks.iter().map(|b| b.contact.len()).sum();
        let out_of_contact = (self.len() - in_contact) as f64;
        let contact_sum: f64 = self.blocks.iter().map(|b| b.sums[0]).sum();
        contact_sum + out_of_contact * c.clamp(0.0, plim)
    }
}
