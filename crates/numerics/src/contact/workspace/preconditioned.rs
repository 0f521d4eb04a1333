//! The preconditioned direction of elastic contacts (`constrained_cg.rs`, module docs): the
//! free-set residual `r = g₀ + u − offset − δ` transformed by `M`, the convolution with the
//! reciprocal of the elastic kernel's spectrum (`InfluenceOperator::precondition_rows_into`),
//! and the conjugate direction built from it. `w` holds `M r` in between: it is free then (a
//! pending update `u ← u − τ w` was applied by the measurement before the step). The direction
//! reads `M r` on the free set only, so the transform writes it at the contact points alone and
//! leaves the rest of `w` as it was (one grid array less written per preconditioned iteration;
//! every dense read of `w` follows a `w ← K t`, which overwrites it whole).

use super::dense::{list_rows, row_contact_points};
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
    /// `w ← M r` at the contact points (module docs) for the free-set residual
    /// `r = g₀ + u − offset − δ` (one FFT pair).
    pub(in crate::contact) fn precondition(
        &mut self,
        op: &mut InfluenceOperator,
        offset: f64,
        delta: f64,
    ) -> Result<(), FftFailure> {
        let Workspace {
            blocks,
            g0,
            u,
            p,
            plim,
            w,
            nx,
            ..
        } = self;
        let (nx, blocks): (usize, &[Block]) = (*nx, blocks);
        let sink = |r: usize, mr: &[f64], out: &mut [f64]| {
            for i in row_contact_points(blocks, r, nx) {
                out[i - r * nx] = mr[i - r * nx];
            }
            0.0
        };
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::Boundary;

    /// `w` holds `M r` at the contact points, bit for bit the dense convolution's, and keeps its
    /// old values elsewhere; the grid spans three blocks, one of its rows two of them.
    #[test]
    fn preconditioned_residual_is_written_at_the_contact_points_only() {
        let (nx, ny) = (96, 200);
        let n = nx * ny;
        let g0: Vec<f64> = (0..n).map(|i| ((i * 7919) % 1013) as f64 * 1e-9).collect();
        let mut ws = Workspace::new(g0, nx, 5.0);
        for i in (0..n).filter(|i| i % 7 == 3 || (2000..2300).contains(i)) {
            ws.p[i] = if i % 5 == 0 {
                5.0
            } else {
                1.0 + (i % 3) as f64
            };
        }
        ws.u.iter_mut()
            .enumerate()
            .for_each(|(i, u)| *u = ((i * 31) % 17) as f64 * 1e-10);
        ws.rebuild_contact();
        ws.w.fill(f64::NAN);
        let mut op =
            InfluenceOperator::new(nx, ny, 1e-6, 1e-6, 1e11, Boundary::Periodic, true).unwrap();
        let (offset, delta) = (2e-9, 3e-8);
        ws.precondition(&mut op, offset, delta).unwrap();

        let r: Vec<f64> = (0..n)
            .map(|i| match ws.p[i] {
                p if p > 0.0 && p < ws.plim => ws.g0[i] + ws.u[i] - offset - delta,
                _ => 0.0,
            })
            .collect();
        let fill = |row: usize, values: &mut [f64]| {
            values.copy_from_slice(&r[row * nx..][..nx]);
            true
        };
        let copy = |_: usize, values: &[f64], out: &mut [f64]| {
            out.copy_from_slice(values);
            0.0
        };
        let mut dense = vec![0.0; n];
        op.precondition_rows_into(&fill, &mut dense, &copy).unwrap();
        for (i, ((&p, &w), &d)) in ws.p.iter().zip(&ws.w).zip(&dense).enumerate() {
            if p > 0.0 {
                assert_eq!(w.to_bits(), d.to_bits(), "point {i}");
            } else {
                assert!(w.is_nan(), "point {i} out of contact was written");
            }
        }
    }
}
