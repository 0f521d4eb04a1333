//! The preconditioned direction of elastic contacts (`constrained_cg.rs`, module docs): the
//! free-set residual `r = g₀ + u − offset − δ` transformed by `M`, the convolution with the
//! reciprocal of the elastic kernel's spectrum (`InfluenceOperator::precondition_rows_into`),
//! and the conjugate direction built from it. `w` holds `M r` in between: it is free then (a
//! pending update `u ← u − τ w` was applied by the measurement before the step).

use super::{contact_points, each_block, each_direction_block, Block, Workspace, BLOCK};
use crate::contact::influence::InfluenceOperator;
use crate::fft2::{FftFailure, RowSource};

/// Rows of the free-set residual `r = g₀ + u − level` (0 at saturated points and off the
/// contact set), filled from the contact lists.
fn residual_rows<'a>(
    blocks: &'a [Block],
    g0: &'a [f64],
    u: &'a [f64],
    p: &'a [f64],
    plim: f64,
    level: f64,
) -> impl RowSource + 'a {
    move |r: usize, row: &mut [f64]| {
        let nx = row.len();
        let (start, end) = (r * nx, (r + 1) * nx);
        row.fill(0.0);
        let mut nonzero = false;
        for (b, block) in blocks
            .iter()
            .enumerate()
            .take(end.div_ceil(BLOCK))
            .skip(start / BLOCK)
        {
            let base = b * BLOCK;
            let first = block
                .contact
                .partition_point(|&l| base + (l as usize) < start);
            for i in contact_points(base, &block.contact[first..]).take_while(|&i| i < end) {
                if p[i] < plim {
                    let v = g0[i] + u[i] - level;
                    row[i - start] = v;
                    nonzero |= v != 0.0;
                }
            }
        }
        nonzero
    }
}

impl Workspace {
    /// `w ← M r` for the free-set residual `r = g₀ + u − offset − δ` (one FFT pair).
    pub(in crate::contact) fn precondition(
        &mut self,
        op: &mut InfluenceOperator,
        offset: f64,
        delta: f64,
    ) -> Result<(), FftFailure> {
        let fill = residual_rows(
            &self.blocks,
            &self.g0,
            &self.u,
            &self.p,
            self.plim,
            offset + delta,
        );
        let sink = |_: usize, mr: &[f64], out: &mut [f64]| {
            out.copy_from_slice(mr);
            0.0
        };
        op.precondition_rows_into(&fill, &mut self.w, &sink)?;
        Ok(())
    }

    /// `[Σ_F z, Σ_F r z, Σ_F r]` for `z = w` (the preconditioned residual) and
    /// `r = g₀ + u − offset − δ`.
    pub(in crate::contact) fn preconditioned_sums(&mut self, offset: f64, delta: f64) -> [f64; 3] {
        let plim = self.plim;
        let (g0, u, p, w) = (&self.g0, &self.u, &self.p, &self.w);
        each_block(&mut self.blocks, |base, block| {
            let mut sums = [0.0; 4];
            for i in contact_points(base, &block.contact) {
                if p[i] < plim {
                    let r = g0[i] + u[i] - offset - delta;
                    sums[0] += w[i];
                    sums[1] += r * w[i];
                    sums[2] += r;
                }
            }
            block.sums = sums;
        });
        self.blocks.iter().fold([0.0; 3], |mut s, b| {
            s.iter_mut().zip(b.sums).for_each(|(o, v)| *o += v);
            s
        })
    }

    /// [`Self::direction`] along the preconditioned residual: `t = (z − z̄) + β t` on the free set.
    pub(in crate::contact) fn preconditioned_direction(
        &mut self,
        beta: f64,
        z_mean: f64,
        offset: f64,
        delta: f64,
    ) -> [f64; 3] {
        let plim = self.plim;
        let (g0, u, p, w) = (&self.g0, &self.u, &self.p, &self.w);
        each_direction_block(&mut self.t, p, &mut self.blocks, |base, t, block| {
            let mut sums = [0.0; 4];
            for &l in &block.contact {
                let (i, l) = (base + l as usize, l as usize);
                t[l] = if p[i] < plim {
                    let r = g0[i] + u[i] - offset - delta;
                    let ti = (w[i] - z_mean) + beta * t[l];
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
        self.blocks.iter().fold([0.0; 3], |mut s, b| {
            s.iter_mut().zip(b.sums).for_each(|(o, v)| *o += v);
            s
        })
    }
}
