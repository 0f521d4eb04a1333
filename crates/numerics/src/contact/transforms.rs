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

/// A kernel value below [`SINGLE_RANGE`] is taken as 0 in single precision when it is at most
/// this fraction, `2^−27`, of the kernel's largest magnitude: an eighth of `f32`'s unit round-off
/// (`2^−24`), so dropping it changes a convolved value by less than the single-precision
/// transforms' own round-off, and every convergence is judged in double precision anyway. Such
/// values are round-off of a kernel's own transforms, as a padded kernel has (docs/contact-solver-
/// design.md, "Mixed precision").
const NEGLIGIBLE_SHARE: f64 = 7.450580596923828e-9;

/// `kernel` rounded to `f32` (values below [`SINGLE_RANGE`] that are negligible, see
/// [`NEGLIGIBLE_SHARE`], as 0), or `None` when a value lies outside the range otherwise.
fn single_kernel(kernel: &[f64]) -> Option<Vec<f32>> {
    let largest = kernel.iter().fold(0.0f64, |m, &v| m.max(v.abs()));
    let (low, high) = SINGLE_RANGE;
    kernel
        .iter()
        .map(|&v| match v.abs() {
            0.0 => Some(0.0),
            a if (low..=high).contains(&a) => Some(v as f32),
            a if a < low && a <= largest * NEGLIGIBLE_SHARE => Some(0.0),
            _ => None,
        })
        .collect()
}

/// The single-precision transforms of the convolutions `fft` plans, with its kernels rounded to
/// `f32` ([`single_kernel`]), or `None` if a kernel has a value outside [`SINGLE_RANGE`] that is
/// not negligible.
pub(super) fn single_transforms(
    fft: &RealFft2d,
    kernel: &[f64],
    inverse_kernel: Option<&[f64]>,
) -> Option<Transforms<f32>> {
    let kernel = single_kernel(kernel)?;
    let inverse_kernel = match inverse_kernel {
        Some(k) => Some(single_kernel(k)?),
        None => None,
    };
    let (nx, ny) = fft.shape();
    Some(Transforms {
        fft: RealFft2d::in_precision(nx, ny, true),
        kernel,
        inverse_kernel,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Kernels inside the range get single-precision transforms, rounded to `f32`; a value
    /// outside it (either side), in either kernel, leaves the operator in double precision,
    /// unless it is below the range and negligible beside the kernel's largest value (then 0).
    #[test]
    fn single_transforms_only_for_kernels_inside_the_range() {
        let fft = RealFft2d::for_convolution(4, 4);
        let kernel = vec![0.0, 1e-17, 3.5e-12, 2.0];
        let single = single_transforms(&fft, &kernel, Some(&[1e20, 0.5])).unwrap();
        assert_eq!(single.kernel, vec![0.0, 1e-17_f32, 3.5e-12_f32, 2.0]);
        assert_eq!(single.inverse_kernel, Some(vec![1e20_f32, 0.5]));
        assert_eq!(single.fft.shape(), (4, 4));
        // Round-off far below the largest value: 0 in single precision.
        let mut noisy = kernel.clone();
        noisy[0] = -1e-31;
        let single = single_transforms(&fft, &noisy, None).unwrap();
        assert_eq!(single.kernel, vec![0.0, 1e-17_f32, 3.5e-12_f32, 2.0]);
        // Below the range and not negligible (the whole kernel tiny), or above it.
        let tiny = [1e-31, -2e-31, 0.0];
        assert!(single_transforms(&fft, &tiny, None).is_none());
        assert!(single_transforms(&fft, &kernel, Some(&tiny)).is_none());
        let mut huge = kernel.clone();
        huge[1] = -1e31;
        assert!(single_transforms(&fft, &huge, None).is_none());
        assert!(single_transforms(&fft, &kernel, Some(&[-1e31, 1.0])).is_none());
    }

    /// The bound of a negligible value is a share of the largest: just above it, a value below
    /// the range leaves the operator in double precision.
    #[test]
    fn a_value_below_the_range_is_dropped_only_when_negligible() {
        let largest = 1e-23;
        let at = largest * NEGLIGIBLE_SHARE;
        assert!(at < SINGLE_RANGE.0);
        assert_eq!(
            single_kernel(&[largest, at]),
            Some(vec![largest as f32, 0.0])
        );
        assert_eq!(single_kernel(&[largest, at * 1.5]), None);
    }
}
