//! Mixed precision: the constrained CG first iterates on single-precision transforms
//! ([`super::CgSettings::mixed_precision`]; [`Precision::Single`], `f32` FFTs and kernels, half
//! the bytes per value and twice the values per SIMD register), then polishes in double
//! precision.
//!
//! The single phase runs the iteration of the module docs unchanged, with `u = K p` and every
//! product with `K` (or the preconditioner `M`) rounded to about `1e-7` of its largest value.
//! Nothing ends the solve there ([`ConstrainedCg::decide_single`]): when the largest residual
//! reaches the tolerance or [`SINGLE_FLOOR`], or a stopping rule applies (iteration budget,
//! stall, cycle), the phase ends ([`ConstrainedCg::end_single_phase`]), `u = K p` is recomputed in
//! double precision and the iteration goes on from the single phase's pressures, in double
//! precision, under the convergence test and stopping rules of the module docs. So the
//! reported residuals are always those of a double-precision `u`, and a converged solve meets
//! the tolerance as a double-precision solve does; the pressures it converges to differ from
//! those of a double-precision solve by what the tolerance allows (measured in
//! `docs/benchmarks.md`). Operators whose kernels do not fit `f32`'s range (absurd units) have
//! no single-precision transforms and iterate in double precision throughout
//! ([`InfluenceOperator::has_single`]).

use super::{CgSettings, ConstrainedCg, Decision, Measurement};
use crate::contact::influence::InfluenceOperator;
use crate::contact::transforms::Precision;

/// The largest residual down to which the iteration runs on single-precision transforms, if
/// the tolerance is below it: well above the floor their round-off sets (the displacement to
/// about `1e-7` of its largest value, relative residuals of a few `1e-6`), so that the
/// single-precision iteration still converges at full speed down to it.
const SINGLE_FLOOR: f64 = 1e-5;

/// Sets the precision `op` starts a solve with `settings` in, and returns whether it is
/// single: with `mixed_precision`, when the solve iterates at all (a solve without iterations,
/// the approach estimate, measures its start once, in double precision) and `op` has
/// single-precision transforms.
pub(super) fn start(settings: &CgSettings, op: &mut InfluenceOperator) -> bool {
    let single = settings.mixed_precision && settings.max_iterations > 0 && op.has_single();
    op.set_precision(if single {
        Precision::Single
    } else {
        Precision::Double
    });
    single
}

impl ConstrainedCg<'_> {
    /// [`Self::decide`] in single precision, where nothing ends the solve: the iteration steps
    /// on while the largest residual is finite and above the tolerance and [`SINGLE_FLOOR`]
    /// and no stopping rule applies (iteration budget, stall, cycle); otherwise the single
    /// phase ends, and the next measurement, on `u = K p` in double precision, decides.
    pub(super) fn decide_single(&mut self, m: &Measurement) -> Decision {
        let r = m.residuals.max();
        let settings = self.settings;
        let stalled = self.iterations - self.last_progress > settings.stall_iterations;
        if !r.is_finite()
            || r <= settings.tolerance.max(SINGLE_FLOOR)
            || self.cycling
            || stalled
            || self.iterations >= settings.max_iterations
        {
            return Decision::Double;
        }
        if r < 0.9 * self.progress_mark {
            self.progress_mark = r;
            self.last_progress = self.iterations;
        }
        Decision::Step
    }

    /// Ends the single-precision phase: the next measurement recomputes `u = K p` in double
    /// precision, from which the conjugation restarts; the stopping rules start afresh (a
    /// stall or cycle of the single phase may be its round-off).
    pub(super) fn end_single_phase(&mut self, m: &Measurement) {
        self.single = false;
        self.op.set_precision(Precision::Double);
        if m.residuals.max().is_finite() {
            self.delta_prev = m.delta;
        }
        self.reset = true;
        self.cycling = false;
        self.last_spread = None;
        self.last_progress = self.iterations;
    }
}
