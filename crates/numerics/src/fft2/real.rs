//! The floating-point types [`super::RealFft2d`] transforms in: `f64`, and `f32` for half the
//! bytes per value and twice the values per SIMD register.
//!
//! Callers always see `f64`: the rows a [`RowSource`] fills and a [`super::RowSink`] receives,
//! the quadratic forms, the real input and output blocks. In single precision each row is
//! converted on its way into and out of the transform, while it is in cache; in double precision
//! the row is transformed where it is, with no copy.

use realfft::num_complex::Complex;
use realfft::num_traits::NumAssign;
use realfft::{ComplexToReal, FftError, FftNum};

use super::RowSource;

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
}

/// A transform precision of [`super::RealFft2d`]: `f64` or `f32`.
pub trait Real: FftNum + NumAssign + Default + Into<f64> + sealed::Sealed {
    /// The rows are transformed two at a time as one complex FFT (`rows_pass.rs`) rather than
    /// one at a time by `realfft`: in `f32`, where that is faster; not in `f64`, whose results
    /// stay bit-identical with those of earlier versions (surface statistics, contact solutions).
    const PACKED_ROWS: bool;

    /// The value of `x` in this type (rounded to nearest for `f32`).
    fn of(x: f64) -> Self;

    /// Fills the transform row `row` with the `row.len()` values of input row `r` from `fill`
    /// (through the `f64` buffer `io`, of the same length, when this is not `f64`); returns
    /// `fill`'s answer (`false`: the row is zero and `row` was not written).
    fn fill_row<F: RowSource>(fill: &F, r: usize, row: &mut [Self], io: &mut [f64]) -> bool;

    /// Inverse real transform of the row spectrum `spectrum` into the `f64` row `out`
    /// (through `row`, of the same length, when this is not `f64`).
    fn inverse_row(
        c2r: &dyn ComplexToReal<Self>,
        spectrum: &mut [Complex<Self>],
        out: &mut [f64],
        row: &mut [Self],
        scratch: &mut [Complex<Self>],
    ) -> Result<(), FftError>;
}

impl Real for f64 {
    const PACKED_ROWS: bool = false;

    fn of(x: f64) -> Self {
        x
    }

    fn fill_row<F: RowSource>(fill: &F, r: usize, row: &mut [f64], _: &mut [f64]) -> bool {
        fill(r, row)
    }

    fn inverse_row(
        c2r: &dyn ComplexToReal<f64>,
        spectrum: &mut [Complex<f64>],
        out: &mut [f64],
        _: &mut [f64],
        scratch: &mut [Complex<f64>],
    ) -> Result<(), FftError> {
        c2r.process_with_scratch(spectrum, out, scratch)
    }
}

impl Real for f32 {
    const PACKED_ROWS: bool = true;

    fn of(x: f64) -> Self {
        x as f32
    }

    fn fill_row<F: RowSource>(fill: &F, r: usize, row: &mut [f32], io: &mut [f64]) -> bool {
        if !fill(r, io) {
            return false;
        }
        row.iter_mut()
            .zip(io.iter())
            .for_each(|(d, &s)| *d = s as f32);
        true
    }

    fn inverse_row(
        c2r: &dyn ComplexToReal<f32>,
        spectrum: &mut [Complex<f32>],
        out: &mut [f64],
        row: &mut [f32],
        scratch: &mut [Complex<f32>],
    ) -> Result<(), FftError> {
        c2r.process_with_scratch(spectrum, row, scratch)?;
        out.iter_mut()
            .zip(row.iter())
            .for_each(|(d, &s)| *d = f64::from(s));
        Ok(())
    }
}

/// `w |c|²` in `f64` (a single-precision square can overflow where the quadratic form does not),
/// with the operations of `w * c.norm_sqr()` in double precision.
pub(super) fn weighted_norm<T: Real>(c: Complex<T>, w: T) -> f64 {
    let (re, im): (f64, f64) = (c.re.into(), c.im.into());
    w.into() * (re * re + im * im)
}
