//! The preconditioned direction of elastic contacts (`constrained_cg.rs`, module docs): the
//! free-set residual `r = g₀ + u − offset − δ` transformed by `M`, the convolution with the
//! reciprocal of the elastic kernel's spectrum (`InfluenceOperator::precondition_rows_into`),
//! and the conjugate direction built from it. `w` holds `M r` in between: it is free then (a
//! pending update `u ← u − τ w` was applied by the measurement before the step).

use super::dense::list_rows;
use super::{contact_points, each_block, three_sums, Block, Workspace};
use crate::contact::influence::InfluenceOperator;
use crate::fft2::{FftFailure, RowSource};

/// Rows of the free-set residual `r = g₀ + u − offset − δ` (0 at saturated points and off the
/// contact set), filled from the contact lists.
fn residual_rows<'a>(
    blocks: &'a [Block],
    g0: &'a [f64],
    u: &'a [f64],
    p: &'a [f64],
    plim: f64,
    offset: f64,
    delta: f64,
) -> impl RowSource + 'a {
    list_rows(blocks, move |i| {
        if p[i] < plim {
            g0[i] + u[i] - offset - delta
        } else {
            0.0
        }
    })
}

impl Workspace {
    /// `w ← M r` for the free-set residual `r = g₀ + u − offset − δ` (one FFT pair).
    pub(in crate::contact) fn precondition(
        &mut self,
        op: &mut InfluenceOperator,
        offset: f64,
        delta: f64,
    ) -> Result<(), FftFailure> {
        let sink = |_: usize, mr: &[f64], out: &mut [f64]| {
            out.copy_from_slice(mr);
            0.0
        };
        let Workspace {
            blocks,
            g0,
            u,
            p,
            plim,
            w,
            ..
        } = self;
        let fill = residual_rows(blocks, g0, u, p, *plim, offset, delta);
        op.precondition_rows_into(&fill, w, &sink)?;
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
        three_sums(&self.blocks)
    }

    /// [`Self::direction`] along the preconditioned residual: `t = (z − z̄) + β t` on the free
    /// set, `z = w`.
    pub(in crate::contact) fn preconditioned_direction(
        &mut self,
        beta: f64,
        z_mean: f64,
        offset: f64,
        delta: f64,
    ) -> [f64; 3] {
        // `w` is moved out for the pass: the descent reads it while `conjugate` borrows `self`.
        let w = std::mem::take(&mut self.w);
        let sums = self.conjugate(beta, offset, delta, |i, _| w[i] - z_mean);
        self.w = w;
        sums
    }
}
