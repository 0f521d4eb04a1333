//! The work of a solve: counted where it is done (iterations by the iteration, transforms by
//! the influence operator that runs them) and added up across load steps, grid levels and the
//! inner solves of the approach search.

use std::ops::{Add, AddAssign};

/// Iterations and transforms of one solve, or of several added up.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Work {
    /// Constrained-CG iterations on the grid.
    pub iterations: usize,
    /// CG iterations of the moving points alone, with the operator restricted to them
    /// (`free_set.rs`); not counted in `iterations`.
    pub free_set_iterations: usize,
    /// Real 2-D FFTs, forward or inverse (a full convolution is two), as counted by the
    /// influence operator that ran them.
    pub fft_transforms: usize,
}

impl AddAssign for Work {
    fn add_assign(&mut self, other: Work) {
        self.iterations += other.iterations;
        self.free_set_iterations += other.free_set_iterations;
        self.fft_transforms += other.fft_transforms;
    }
}

impl Add for Work {
    type Output = Work;

    fn add(mut self, other: Work) -> Work {
        self += other;
        self
    }
}
