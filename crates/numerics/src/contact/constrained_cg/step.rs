//! The length of one step of the constrained CG: along the conjugate direction, or the
//! projected-gradient step where the CG step is undefined (the module docs of `constrained_cg`).

use super::{ConstrainedCg, Measurement, MEAN_FREE_DIRECTION};
use crate::fft2::FftFailure;

/// The step chosen by [`ConstrainedCg::step_length`].
pub(super) struct Step {
    pub(super) tau: f64,
    /// The CG step was undefined and the projected-gradient step was taken.
    pub(super) breakdown: bool,
    /// `w = K t` is in real space (the load-control term needed it), so `u` can be updated
    /// without another inverse transform.
    pub(super) w_ready: bool,
}

impl ConstrainedCg<'_> {
    /// The CG step `τ` along the conjugate direction, or the projected-gradient step when the CG
    /// step is undefined (module docs).
    pub(super) fn step_length(
        &mut self,
        m: &Measurement,
        beta: f64,
        z_mean: Option<f64>,
    ) -> Result<Step, FftFailure> {
        let load_control = self.load_control();
        let mut w_ready = false;
        let cg_step = if load_control && m.free_count <= 1.0 {
            // Under load control `δ` is the mean of `g` on the free set, so on a free set of one
            // point (the rigid-plastic start) `t = g − δ` vanishes: no direction to transform.
            None
        } else {
            let [gt, t_sum, t_abs] = match z_mean {
                Some(z_mean) => {
                    self.ws
                        .preconditioned_direction(beta, z_mean, self.offset, m.delta)
                }
                None => self.ws.direction(beta, self.offset, m.delta),
            };
            // `tᵀ K t = Σ_F t (K t)`: `t` vanishes off the free set.
            let mut rt = self.ws.start_direction_transform(self.op)?;
            if load_control
                && m.free_count > 0.0
                && t_sum.abs() > MEAN_FREE_DIRECTION * t_abs
                && !self.heavily_corrected
            {
                self.op.finish_apply(&mut self.ws.w)?;
                w_ready = true;
                rt -= self.ws.free_w_sum() * t_sum / m.free_count;
            }
            (rt > 0.0 && gt > 0.0 && (gt / rt).is_finite()).then_some(gt / rt)
        };
        let tau = match cg_step {
            Some(tau) => tau,
            None => {
                // The projected-gradient step replaces `t`; `reset` restarts the conjugation.
                let e2 = self.ws.entry_direction(self.offset, m.delta);
                let ek = self.op.start_apply(&self.ws.t)?;
                if ek > 0.0 && e2 > 0.0 && (e2 / ek).is_finite() {
                    e2 / ek
                } else {
                    self.settings.default_step
                }
            }
        };
        Ok(Step {
            tau,
            breakdown: cg_step.is_none(),
            w_ready,
        })
    }
}
