//! The dense side of the iteration: the rows the FFTs read and write, and the pass over the
//! points out of contact.
//!
//! * The forward transforms of `p` and of the conjugate direction `t` read their rows from the
//!   contact lists ([`contact_rows`]), not from the dense arrays.
//! * The displacement rows an inverse transform produces go through a sink that, while each row
//!   is still in cache, writes `u` (`u ← K p`, or the linear update `u ← u − τ K t`) and takes the
//!   row's smallest out-of-contact gap `min_{p = 0} (g₀ + u − offset)`
//!   ([`out_of_contact_min`]). The pass over the points out of contact then needs no dense
//!   sweep: the smallest gap is the smallest row minimum, and only the blocks whose rows reach
//!   below `δ` are scanned for entering points.
//! * When `u` changed otherwise (a pending update `u ← u − τ w` with a `w` kept for the step),
//!   the pass sweeps the whole grid.
//! * Both read which points are in contact from `in_contact` (kept current by the pressure
//!   update and the rebuild of the lists), one byte per point beside `g₀` instead of `p`.

use rayon::prelude::*;

use super::{contact_points, Block, Workspace, BLOCK};
use crate::contact::influence::InfluenceOperator;
use crate::fft2::{FftFailure, RowSource};

/// Independent running minima of [`out_of_contact_min`]: a single one is a serial chain of
/// dependent comparisons; eight break it and let the loop vectorise.
const LANES: usize = 8;

/// The rows of `g₀` and `in_contact` of a stretch of the grid.
#[derive(Clone, Copy)]
struct Initial<'a> {
    g0: &'a [f64],
    in_contact: &'a [bool],
}

impl<'a> Initial<'a> {
    fn at(g0: &'a [f64], in_contact: &'a [bool], start: usize, len: usize) -> Self {
        Self {
            g0: &g0[start..][..len],
            in_contact: &in_contact[start..][..len],
        }
    }

    /// `g₀ + u − offset` at a point out of contact, `+∞` at a contact point.
    fn gap(g0: f64, in_contact: bool, u: f64, offset: f64) -> f64 {
        let v = g0 + u - offset;
        if in_contact {
            f64::INFINITY
        } else {
            v
        }
    }
}

/// `min_{p = 0} (g₀ + u − offset)` over a stretch of the grid (`+∞` if every point is in
/// contact). The gaps are finite (the inputs are checked), so the branch-free `if v < m`
/// selection is the minimum.
fn out_of_contact_min(u: &[f64], initial: Initial<'_>, offset: f64) -> f64 {
    let mut lanes = [f64::INFINITY; LANES];
    let fold = |m: &mut f64, ((&ui, &g0i), &c): ((&f64, &f64), &bool)| {
        let v = Initial::gap(g0i, c, ui, offset);
        *m = if v < *m { v } else { *m };
    };
    let body = u.len() - u.len() % LANES;
    let (u_body, u_tail) = u.split_at(body);
    let (g0_body, g0_tail) = initial.g0.split_at(body);
    let (c_body, c_tail) = initial.in_contact.split_at(body);
    for ((u, g0), c) in (u_body.chunks_exact(LANES))
        .zip(g0_body.chunks_exact(LANES))
        .zip(c_body.chunks_exact(LANES))
    {
        for (m, x) in lanes.iter_mut().zip(u.iter().zip(g0).zip(c)) {
            fold(m, x);
        }
    }
    let mut tail = f64::INFINITY;
    for x in u_tail.iter().zip(g0_tail).zip(c_tail) {
        fold(&mut tail, x);
    }
    lanes.iter().fold(tail, |a, &b| a.min(b))
}

/// The rows of `values`, which vanish off the contact set, filled from the contact lists: the
/// FFT of a pressure or a direction reads its few contact points instead of the dense array.
/// The transform is bit-identical to that of the dense array.
fn contact_rows<'a>(blocks: &'a [Block], values: &'a [f64]) -> impl RowSource + 'a {
    let rows = list_rows(blocks, |i| values[i]);
    move |r: usize, row: &mut [f64]| {
        let nonzero = rows(r, row);
        debug_assert_eq!(
            row,
            &values[r * row.len()..][..row.len()],
            "row {r} has values off the contact lists"
        );
        nonzero
    }
}

/// Rows holding `value(i)` at the contact points `i` and 0 elsewhere: row `r` of
/// `nx = row.len()` points holds the points `r·nx .. (r + 1)·nx`; a row whose values are all
/// zero reports `false`, as the dense rows do.
pub(super) fn list_rows<'a>(
    blocks: &'a [Block],
    value: impl Fn(usize) -> f64 + Sync + 'a,
) -> impl RowSource + 'a {
    move |r: usize, row: &mut [f64]| {
        let start = r * row.len();
        row.fill(0.0);
        let mut nonzero = false;
        for i in row_contact_points(blocks, r, row.len()) {
            let v = value(i);
            row[i - start] = v;
            nonzero |= v != 0.0;
        }
        nonzero
    }
}

/// The contact points of row `r` of a grid of rows of `nx` points (the points
/// `r·nx .. (r + 1)·nx`, which may span two blocks), ascending.
pub(super) fn row_contact_points(
    blocks: &[Block],
    r: usize,
    nx: usize,
) -> impl Iterator<Item = usize> + '_ {
    let (start, end) = (r * nx, (r + 1) * nx);
    blocks
        .iter()
        .enumerate()
        .take(end.div_ceil(BLOCK))
        .skip(start / BLOCK)
        .flat_map(move |(b, block)| {
            let base = b * BLOCK;
            let first = block
                .contact
                .partition_point(|&l| base + (l as usize) < start);
            contact_points(base, &block.contact[first..]).take_while(move |&i| i < end)
        })
}

impl Workspace {
    /// `u ← K p` (one FFT pair; `p` is read from the contact lists, which must be current), with
    /// the row minima of the out-of-contact gap `g₀ + u − offset`.
    pub(in crate::contact) fn displace(
        &mut self,
        op: &mut InfluenceOperator,
        offset: f64,
    ) -> Result<(), FftFailure> {
        let (g0, in_contact, p, nx) = (&self.g0, &self.in_contact, &self.p, self.nx);
        let sink = |r: usize, kp: &[f64], u: &mut [f64]| {
            debug_assert!(
                (in_contact[r * nx..][..nx].iter())
                    .zip(&p[r * nx..][..nx])
                    .all(|(&c, &pi)| (pi > 0.0) == c),
                "row {r}: in_contact does not mark the contact points"
            );
            u.copy_from_slice(kp);
            out_of_contact_min(u, Initial::at(g0, in_contact, r * nx, nx), offset)
        };
        let minima = op.apply_rows_into(&contact_rows(&self.blocks, p), &mut self.u, &sink)?;
        self.row_min.copy_from_slice(minima);
        self.row_min_current = true;
        Ok(())
    }

    /// Forward transform of the conjugate direction `t` (kept for `finish_apply`); returns
    /// `tᵀ K t`. `t` must vanish off the contact lists, as [`Self::direction`] leaves it.
    pub(in crate::contact) fn start_direction_transform(
        &self,
        op: &mut InfluenceOperator,
    ) -> Result<f64, FftFailure> {
        op.start_apply_rows(&contact_rows(&self.blocks, &self.t))
    }

    /// The linear displacement update `u ← u − τ K t` from the direction transformed last
    /// (one inverse FFT; `K t` is not kept), with the row minima of the out-of-contact gap
    /// `g₀ + u − offset` for the pressures as they are now.
    pub(in crate::contact) fn advance_displacement(
        &mut self,
        op: &mut InfluenceOperator,
        tau: f64,
        offset: f64,
    ) -> Result<(), FftFailure> {
        let (g0, in_contact, nx) = (&self.g0, &self.in_contact, self.nx);
        let sink = |r: usize, kt: &[f64], u: &mut [f64]| {
            u.iter_mut().zip(kt).for_each(|(ui, &wi)| *ui -= tau * wi);
            out_of_contact_min(u, Initial::at(g0, in_contact, r * nx, nx), offset)
        };
        let minima = op.finish_apply_into(&mut self.u, &sink)?;
        self.row_min.copy_from_slice(minima);
        self.row_min_current = true;
        Ok(())
    }

    /// The pass over the points out of contact. Applies the pending displacement update
    /// `u ← u − τ w` (everywhere) if `pending_step = Some(τ)`; returns the smallest gap
    /// `min_{p = 0} (g₀ + u − offset)` and records the points with `g₀ + u − offset − δ < 0`
    /// (none for `δ = −∞`). If the row minima of the last transform are current, each block's
    /// smallest gap is that of its rows, and only the blocks that reach below `δ` are read (when
    /// none does, the pass starts no parallel work; on rough surfaces some point enters in
    /// almost every step); otherwise every block is swept for its minimum and, if that is below
    /// `δ`, scanned.
    pub(in crate::contact) fn out_of_contact_pass(
        &mut self,
        pending_step: Option<f64>,
        offset: f64,
        delta: f64,
    ) -> f64 {
        let row_minima = pending_step.is_none() && self.row_min_current;
        self.row_min_current &= pending_step.is_none();
        let (w, nx, n) = (&self.w, self.nx, self.g0.len());
        let record_entering = |u: &[f64], initial: Initial<'_>, block: &mut Block| {
            block.entering.clear();
            if block.zero_min - delta < 0.0 {
                let points = u.iter().zip(initial.g0).zip(initial.in_contact);
                for (l, ((&ui, &g0i), &c)) in points.enumerate() {
                    let v = Initial::gap(g0i, c, ui, offset);
                    if v - delta < 0.0 {
                        block.entering.push((l as u32, v - delta));
                    }
                }
            }
        };
        let (g0, in_contact) = (&self.g0, &self.in_contact);
        let blocks = self.u.par_chunks_mut(BLOCK).enumerate().map(|(b, u)| {
            let initial = Initial::at(g0, in_contact, b * BLOCK, u.len());
            (u, initial)
        });
        if row_minima {
            let mut below = false;
            for (b, block) in self.blocks.iter_mut().enumerate() {
                let rows = b * BLOCK / nx..((b + 1) * BLOCK).min(n).div_ceil(nx);
                block.zero_min = self.row_min[rows]
                    .iter()
                    .fold(f64::INFINITY, |a, &m| a.min(m));
                block.entering.clear();
                below |= block.zero_min - delta < 0.0;
            }
            if below {
                blocks
                    .zip(self.blocks.par_iter_mut())
                    .filter(|(_, block)| block.zero_min - delta < 0.0)
                    .for_each(|((u, initial), block)| record_entering(u, initial, block));
            }
        } else {
            blocks.zip(self.blocks.par_iter_mut()).enumerate().for_each(
                |(b, ((u, initial), block))| {
                    if let Some(tau) = pending_step {
                        let w = &w[b * BLOCK..][..u.len()];
                        u.iter_mut().zip(w).for_each(|(ui, &wi)| *ui -= tau * wi);
                    }
                    block.zero_min = out_of_contact_min(u, initial, offset);
                    record_entering(u, initial, block);
                },
            );
        }
        self.blocks
            .iter()
            .map(|b| b.zero_min)
            .fold(f64::INFINITY, f64::min)
    }

    /// `g ← g₀ + u` at the points out of contact and `+∞` at the contact points (`g` as scratch
    /// during a solve: the load restoration ranks the points out of contact by it).
    pub(in crate::contact) fn write_out_of_contact_gap(&mut self) {
        let (g0, in_contact, u) = (&self.g0, &self.in_contact, &self.u);
        self.g.par_chunks_mut(BLOCK).enumerate().for_each(|(b, g)| {
            let initial = Initial::at(g0, in_contact, b * BLOCK, g.len());
            let points = (initial.g0.iter())
                .zip(initial.in_contact)
                .zip(&u[b * BLOCK..]);
            for (gi, ((&g0i, &c), &ui)) in g.iter_mut().zip(points) {
                *gi = Initial::gap(g0i, c, ui, 0.0);
            }
        });
    }

    /// `g ← g₀ + u − approach` everywhere (the gap returned with a solve).
    pub(in crate::contact) fn write_gap(&mut self, approach: f64) {
        sum_into(&mut self.g, &self.g0, &self.u, approach);
    }
}

/// `g ← base + u − offset`, in parallel.
fn sum_into(g: &mut [f64], base: &[f64], u: &[f64], offset: f64) {
    g.par_chunks_mut(BLOCK)
        .zip(base.par_chunks(BLOCK))
        .zip(u.par_chunks(BLOCK))
        .for_each(|((g, base), u)| {
            for ((gi, &bi), &ui) in g.iter_mut().zip(base).zip(u) {
                *gi = bi + ui - offset;
            }
        });
}
