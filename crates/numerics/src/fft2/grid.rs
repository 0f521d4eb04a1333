//! [`RealFft2d`] for `ndarray` grids, with the half spectrum in the natural layout `[ky][kx]`.

use ndarray::{Array2, ArrayView2};
use realfft::num_complex::Complex;

use super::transpose::transpose_all;
use super::{FftFailure, RealFft2d};

/// Forward transform of a real `[ny, nx]` grid to its half spectrum `[ny, nx/2 + 1]`
/// (row `j` holds `ky = j` for `j ≤ ny/2` and `j − ny` above; column `i` holds `kx = i`).
pub(crate) fn forward_real_2d(z: &Array2<f64>) -> Result<Array2<Complex<f64>>, FftFailure> {
    let (ny, nx) = z.dim();
    let standard = z.as_standard_layout();
    let values = standard
        .as_slice()
        .ok_or_else(|| FftFailure::new("height grid is not contiguous"))?;
    let mut fft = RealFft2d::new(nx, ny);
    let spectrum = fft.forward(values)?;
    let nxh = nx / 2 + 1;
    let mut natural = vec![Complex::new(0.0, 0.0); ny * nxh];
    transpose_all(spectrum, nxh, ny, &mut natural);
    Array2::from_shape_vec((ny, nxh), natural).map_err(|e| FftFailure::new(e.to_string()))
}

/// Inverse of a `[ny, nx/2 + 1]` half spectrum to a real `[ny, nx]` grid, unnormalised (divide
/// by `nx·ny` to invert [`forward_real_2d`]). The imaginary parts a real signal's row spectrum
/// cannot carry (the `kx = 0` and, for even `nx`, `kx = nx/2` columns after the y transform) are
/// dropped; callers that build Hermitian spectra make them zero up to round-off.
pub(crate) fn inverse_real_2d(
    half: &Array2<Complex<f64>>,
    nx: usize,
) -> Result<Array2<f64>, FftFailure> {
    let standard = half.as_standard_layout();
    let values = contiguous(standard.view(), nx)?;
    inverse_into_grid(half.nrows(), nx, |fft, out| {
        fft.inverse_natural(values, out)
    })
}

/// [`inverse_real_2d`] of a real half spectrum (a power spectrum, say): the same bits as the
/// inverse of its complex image with zero imaginary parts, without building that image.
pub(crate) fn inverse_real_spectrum_2d(
    half: &Array2<f64>,
    nx: usize,
) -> Result<Array2<f64>, FftFailure> {
    let standard = half.as_standard_layout();
    let values = contiguous(standard.view(), nx)?;
    inverse_into_grid(half.nrows(), nx, |fft, out| {
        fft.inverse_natural_real(values, out)
    })
}

/// The values of a `[ny, nx/2 + 1]` half spectrum in standard layout.
fn contiguous<T>(half: ArrayView2<'_, T>, nx: usize) -> Result<&[T], FftFailure> {
    let (ny, nxh) = half.dim();
    if nxh != nx / 2 + 1 || nx == 0 || ny == 0 {
        return Err(FftFailure::new(format!(
            "half spectrum is {ny} × {nxh}, expected {} columns for nx = {nx}",
            nx / 2 + 1
        )));
    }
    half.to_slice()
        .ok_or_else(|| FftFailure::new("half spectrum is not contiguous"))
}

/// The `[ny, nx]` grid that `inverse` writes with a transform planned for it.
fn inverse_into_grid(
    ny: usize,
    nx: usize,
    inverse: impl FnOnce(&mut RealFft2d, &mut [f64]) -> Result<(), FftFailure>,
) -> Result<Array2<f64>, FftFailure> {
    let mut fft = RealFft2d::new(nx, ny);
    let mut out = vec![0.0; nx * ny];
    inverse(&mut fft, &mut out)?;
    Array2::from_shape_vec((ny, nx), out).map_err(|e| FftFailure::new(e.to_string()))
}
