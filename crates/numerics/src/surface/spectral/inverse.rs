//! One inverse 2-D real FFT of a grid kept for several transforms: a surface's synthesis and its
//! periodic autocorrelation are both inverse transforms of `ny × (nx/2 + 1)` half spectra, and
//! at 3512² each fresh plan costs a 99 MB column buffer (new pages, each zeroed by the kernel on
//! first touch) beside its planning. The output grid may come from the caller too (a buffer a
//! statistic no longer needs). Every transform is the one of [`RealFft2d`] in its natural-layout
//! form, so the values are those of a plan made for it alone.

use ndarray::Array2;
use realfft::num_complex::Complex64;

use crate::fft2::{FftFailure, RealFft2d};

/// A planned inverse transform of `[ny, nx/2 + 1]` half spectra (rows `ky` in FFT order,
/// columns `kx`) to real `[ny, nx]` grids, unnormalised.
#[derive(Debug)]
pub struct InverseTransform {
    fft: RealFft2d,
    nx: usize,
    ny: usize,
}

impl InverseTransform {
    /// Plans the transforms of an `ny × nx` grid.
    pub fn new(nx: usize, ny: usize) -> Self {
        Self {
            fft: RealFft2d::new(nx, ny),
            nx,
            ny,
        }
    }

    /// Grid size `(nx, ny)`.
    pub fn shape(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// The inverse of the half spectrum `half` (the imaginary parts a real signal's row spectrum
    /// cannot carry dropped, as `RealFft2d::inverse`), written into `buffer`'s memory where it
    /// holds `nx·ny` values (else a new grid).
    pub fn complex(
        &mut self,
        half: &Array2<Complex64>,
        buffer: Vec<f64>,
    ) -> Result<Array2<f64>, FftFailure> {
        let standard = half.as_standard_layout();
        let values = self.spectrum(standard.dim(), standard.as_slice())?;
        let mut out = self.output(buffer);
        self.fft.inverse_natural(values, &mut out)?;
        self.grid(out)
    }

    /// [`InverseTransform::complex`] of a real half spectrum (a power spectrum), without
    /// building its complex image: the same bits.
    pub fn real(
        &mut self,
        half: &Array2<f64>,
        buffer: Vec<f64>,
    ) -> Result<Array2<f64>, FftFailure> {
        let standard = half.as_standard_layout();
        let values = self.spectrum(standard.dim(), standard.as_slice())?;
        let mut out = self.output(buffer);
        self.fft.inverse_natural_real(values, &mut out)?;
        self.grid(out)
    }

    /// The values of a half spectrum of shape `dim`, checked against the plan.
    fn spectrum<'a, T>(
        &self,
        dim: (usize, usize),
        values: Option<&'a [T]>,
    ) -> Result<&'a [T], FftFailure> {
        let expected = (self.ny, self.nx / 2 + 1);
        if dim != expected {
            return Err(FftFailure::new(format!(
                "half spectrum is {} × {}, expected {} × {} for the {} × {} grid",
                dim.0, dim.1, expected.0, expected.1, self.nx, self.ny
            )));
        }
        values.ok_or_else(|| FftFailure::new("half spectrum is not contiguous"))
    }

    /// `buffer` holding `nx·ny` values (its old values are overwritten by the transform), or,
    /// where it cannot without growing, a new zeroed grid (fresh pages, zeroed on first touch).
    fn output(&self, mut buffer: Vec<f64>) -> Vec<f64> {
        let n = self.nx * self.ny;
        if buffer.capacity() < n {
            return vec![0.0; n];
        }
        buffer.truncate(n);
        buffer.resize(n, 0.0);
        buffer
    }

    fn grid(&self, out: Vec<f64>) -> Result<Array2<f64>, FftFailure> {
        Array2::from_shape_vec((self.ny, self.nx), out).map_err(|e| FftFailure::new(e.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fft2::{inverse_real_2d, inverse_real_spectrum_2d};

    fn bits(a: &Array2<f64>) -> Vec<u64> {
        a.iter().map(|v| v.to_bits()).collect()
    }

    /// One plan used for several transforms, into new grids or into reused buffers (longer,
    /// shorter or of the right size, holding other values), gives the bits of a plan made for
    /// each; a spectrum of another shape is an error.
    #[test]
    fn a_kept_plan_and_reused_buffers_give_the_bits_of_fresh_ones() {
        for (nx, ny) in [(16, 12), (15, 9), (2, 1)] {
            let nxh = nx / 2 + 1;
            let complex = Array2::from_shape_fn((ny, nxh), |(j, i)| {
                Complex64::new(
                    (j * 7 + i) as f64 * 0.25 - 3.0,
                    (i * 3 + j) as f64 * 0.1 - 1.0,
                )
            });
            let power = Array2::from_shape_fn((ny, nxh), |(j, i)| ((j * 5 + i * 11) % 13) as f64);
            let mut plan = InverseTransform::new(nx, ny);
            let expected_complex = bits(&inverse_real_2d(&complex, nx).unwrap());
            let expected_real = bits(&inverse_real_spectrum_2d(&power, nx).unwrap());
            for buffer in [Vec::new(), vec![7.5; nx * ny], vec![-1.0; 3 * nx * ny], {
                let mut short = Vec::with_capacity(2 * nx * ny);
                short.push(4.0);
                short
            }] {
                let z = plan.complex(&complex, buffer.clone()).unwrap();
                assert_eq!(bits(&z), expected_complex, "{nx} × {ny}");
                let acf = plan.real(&power, buffer).unwrap();
                assert_eq!(bits(&acf), expected_real, "{nx} × {ny}");
            }
            let wrong = Array2::<f64>::zeros((ny + 1, nxh));
            assert!(plan.real(&wrong, Vec::new()).is_err());
        }
    }
}
