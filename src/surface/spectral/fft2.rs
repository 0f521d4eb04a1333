//! Two-dimensional real FFT on `[[iy, ix]]` grids: realfft along x (rows), rustfft along y.
//!
//! The half spectrum has shape `[ny, nx/2 + 1]`: row `j` holds `ky = j` for `j ≤ ny/2` and
//! `ky = j − ny` above; column `i` holds `kx = i ≥ 0`. Transforms are unnormalised
//! (`Z(k) = Σ z(r) e^{−i k·r}`, and the inverse omits the `1/N` factor), as in FFTW/rustfft.
//!
//! Rows and columns are transformed in parallel with rayon; each 1-D transform is independent, so
//! the result does not depend on the number of threads.

use ndarray::Array2;
use rayon::prelude::*;
use realfft::num_complex::Complex64;
use realfft::RealFftPlanner;
use rustfft::FftPlanner;

/// A 1-D transform failed (a length mismatch; not reachable with the grids built here).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("FFT failed: {0}")]
pub struct FftFailure(pub String);

/// Forward 2-D transform of a real `[ny, nx]` grid to its `[ny, nx/2 + 1]` half spectrum.
pub(crate) fn forward_real_2d(z: &Array2<f64>) -> Result<Array2<Complex64>, FftFailure> {
    let (ny, nx) = z.dim();
    let nxh = nx / 2 + 1;
    let r2c = RealFftPlanner::<f64>::new().plan_fft_forward(nx);
    let standard = z.as_standard_layout();
    let rows = standard
        .as_slice()
        .ok_or_else(|| FftFailure("height grid is not contiguous".into()))?;
    let mut half = vec![Complex64::new(0.0, 0.0); ny * nxh];
    half.par_chunks_mut(nxh)
        .zip(rows.par_chunks(nx))
        .try_for_each_init(
            || (r2c.make_input_vec(), r2c.make_scratch_vec()),
            |(input, scratch), (out, row)| {
                input.copy_from_slice(row);
                r2c.process_with_scratch(input, out, scratch)
                    .map_err(|e| FftFailure(e.to_string()))
            },
        )?;
    columns_in_place(&mut half, ny, nxh, false);
    Array2::from_shape_vec((ny, nxh), half).map_err(|e| FftFailure(e.to_string()))
}

/// Inverse 2-D transform of a `[ny, nx/2 + 1]` half spectrum to a real `[ny, nx]` grid
/// (unnormalised: divide by `nx·ny` to invert [`forward_real_2d`]).
///
/// The imaginary parts that a real signal's row spectrum cannot carry (the `kx = 0` and, for even
/// `nx`, the `kx = nx/2` columns after the y transform) are dropped; callers that build Hermitian
/// spectra make them zero up to round-off.
pub(crate) fn inverse_real_2d(
    half: &Array2<Complex64>,
    nx: usize,
) -> Result<Array2<f64>, FftFailure> {
    let (ny, nxh) = half.dim();
    if nxh != nx / 2 + 1 {
        return Err(FftFailure(format!(
            "half spectrum has {nxh} columns, expected {} for nx = {nx}",
            nx / 2 + 1
        )));
    }
    let mut data: Vec<Complex64> = half.iter().copied().collect();
    columns_in_place(&mut data, ny, nxh, true);
    let c2r = RealFftPlanner::<f64>::new().plan_fft_inverse(nx);
    let mut out = vec![0.0; ny * nx];
    out.par_chunks_mut(nx)
        .zip(data.par_chunks_mut(nxh))
        .try_for_each_init(
            || c2r.make_scratch_vec(),
            |scratch, (row_out, row_in)| {
                if let Some(first) = row_in.first_mut() {
                    first.im = 0.0;
                }
                if nx.is_multiple_of(2) {
                    if let Some(last) = row_in.last_mut() {
                        last.im = 0.0;
                    }
                }
                c2r.process_with_scratch(row_in, row_out, scratch)
                    .map_err(|e| FftFailure(e.to_string()))
            },
        )?;
    Array2::from_shape_vec((ny, nx), out).map_err(|e| FftFailure(e.to_string()))
}

/// Complex FFT along y of every column of a row-major `[ny, ncols]` buffer, in place.
fn columns_in_place(data: &mut [Complex64], ny: usize, ncols: usize, inverse: bool) {
    let mut planner = FftPlanner::<f64>::new();
    let fft = if inverse {
        planner.plan_fft_inverse(ny)
    } else {
        planner.plan_fft_forward(ny)
    };
    let mut columns = vec![Complex64::new(0.0, 0.0); data.len()];
    transpose_into(data, &mut columns, ny, ncols);
    columns.par_chunks_mut(ny).for_each_init(
        || vec![Complex64::new(0.0, 0.0); fft.get_inplace_scratch_len()],
        |scratch, column| fft.process_with_scratch(column, scratch),
    );
    transpose_into(&columns, data, ncols, ny);
}

/// Writes the transpose of a row-major `[rows, cols]` buffer into a row-major `[cols, rows]` one.
fn transpose_into(data: &[Complex64], out: &mut [Complex64], rows: usize, cols: usize) {
    out.par_chunks_mut(rows)
        .enumerate()
        .for_each(|(c, column)| {
            for (r, value) in column.iter_mut().enumerate() {
                *value = data[r * cols + c];
            }
        });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_recovers_the_grid() {
        for (ny, nx) in [(6, 8), (5, 7), (4, 9), (2, 2)] {
            let z = Array2::from_shape_fn((ny, nx), |(j, i)| {
                ((i * 7 + j * 3) % 11) as f64 - 0.3 * j as f64
            });
            let half = forward_real_2d(&z).unwrap();
            let back = inverse_real_2d(&half, nx).unwrap() / (nx * ny) as f64;
            // Round-off of a few FFT passes on O(10) values.
            for (a, b) in z.iter().zip(back.iter()) {
                assert!((a - b).abs() < 1e-12, "{a} vs {b}");
            }
        }
    }

    #[test]
    fn forward_matches_direct_dft() {
        let (ny, nx) = (3, 4);
        let z = Array2::from_shape_fn((ny, nx), |(j, i)| (i as f64).sin() + (j * j) as f64);
        let half = forward_real_2d(&z).unwrap();
        for ((j, i), value) in half.indexed_iter() {
            let mut direct = Complex64::new(0.0, 0.0);
            for ((y, x), zz) in z.indexed_iter() {
                let phase = -2.0
                    * std::f64::consts::PI
                    * ((i * x) as f64 / nx as f64 + (j * y) as f64 / ny as f64);
                direct += Complex64::from_polar(*zz, phase);
            }
            // Direct O(N²) sum vs FFT: round-off only.
            assert!((direct - value).norm() < 1e-12);
        }
    }
}
