//! The transforms of an [`super::influence::InfluenceOperator`] in one precision (`f64` or
//! `f32`, see [`crate::fft2::Real`]) and when the single-precision ones can be used.

use crate::fft2::{FftFailure, Real, RealFft2d, RowSink, RowSource};

/// The precision of the transforms of an [`super::influence::InfluenceOperator`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Precision {
    /// `f32` transforms (and kernels): half the memory traffic, relative round-off of the
    /// displacement about `1e-7` of its largest value.
    Single,
    /// `f64` transforms: round-off about `1e-16`.
    Double,
}

/// The transforms and kernels of one precision.
#[derive(Debug)]
pub(super) struct Transforms<T: Real> {
    pub(super) fft: RealFft2d<T>,
    pub(super) kernel: Vec<T>,
    /// The kernel of the preconditioner `M`
    /// ([`super::influence::InfluenceOperator::precondition_rows_into`]), if it was built.
    pub(super) inverse_kernel: Option<Vec<T>>,
}

impl<T: Real> Transforms<T> {
    /// `out = M r` in this precision for the `ny × nx` block `r` (see
    /// [`super::influence::InfluenceOperator::precondition_rows_into`]).
    pub(super) fn precondition_rows_into<F: RowSource, S: RowSink>(
        &mut self,
        fill: &F,
        out: &mut [f64],
        (nx, ny): (usize, usize),
        sink: &S,
    ) -> Result<&[f64], FftFailure> {
        let inverse = self.inverse_kernel.as_deref().ok_or_else(|| {
            FftFailure::new("the influence operator was built without its preconditioner")
        })?;
        self.fft
            .convolve_rows_into(fill, inverse, out, nx, ny, sink)
    }
}

/// Smallest and largest magnitude of a kernel value that the single-precision transforms take:
/// `2^∓100`, far inside `f32`'s normal range (`2^∓126 … 2^128`), so that the products of the
/// kernels with the spectra of pressures (Pa) and gaps (m) neither overflow nor lose digits to
/// subnormal numbers. Kernels outside (absurd units) are transformed in double precision only.
const SINGLE_RANGE: (f64, f64) = (7.888609052210118e-31, 1.2676506002282294e30);

/// The single-precision transforms of the convolutions `fft` plans, with its kernels rounded to
/// `f32`, or `None` if a kernel value lies outside [`SINGLE_RANGE`].
pub(super) fn single_transforms(
    fft: &RealFft2d,
    kernel: &[f64],
    inverse_kernel: Option<&[f64]>,
) -> Option<Transforms<f32>> {
    let representable = |k: &[f64]| {
        k.iter()
            .all(|&v| v == 0.0 || (SINGLE_RANGE.0..=SINGLE_RANGE.1).contains(&v.abs()))
    };
    if !representable(kernel) || !inverse_kernel.is_none_or(representable) {
        return None;
    }
    let round = |k: &[f64]| k.iter().map(|&v| v as f32).collect::<Vec<_>>();
    let (nx, ny) = fft.shape();
    Some(Transforms {
        fft: RealFft2d::in_precision(nx, ny, true),
        kernel: round(kernel),
        inverse_kernel: inverse_kernel.map(round),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Kernels inside the range get single-precision transforms, rounded to `f32`; a value
    /// outside it (either side), in either kernel, leaves the operator in double precision.
    #[test]
    fn single_transforms_only_for_kernels_inside_the_range() {
        let fft = RealFft2d::for_convolution(4, 4);
        let kernel = vec![0.0, 1e-17, 3.5e-12, 2.0];
        let single = single_transforms(&fft, &kernel, Some(&[1e20, 0.5])).unwrap();
        assert_eq!(single.kernel, vec![0.0, 1e-17_f32, 3.5e-12_f32, 2.0]);
        assert_eq!(single.inverse_kernel, Some(vec![1e20_f32, 0.5]));
        assert_eq!(single.fft.shape(), (4, 4));
        for bad in [1e-31, -1e31] {
            let mut outside = kernel.clone();
            outside[1] = bad;
            assert!(single_transforms(&fft, &outside, None).is_none(), "{bad:e}");
            assert!(
                single_transforms(&fft, &kernel, Some(&[bad])).is_none(),
                "{bad:e}"
            );
        }
    }
}
