//! Two-dimensional real-to-complex FFT convolution with plans and buffers allocated once.

use std::sync::Arc;

use rayon::prelude::*;
use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::{Fft, FftPlanner};

/// Columns transposed together (a tile of `TILE` complex values per column read).
const TILE: usize = 16;

/// A real 2-D FFT failed (internal error: buffer lengths are fixed at construction).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("internal FFT error: {message}")]
pub struct FftFailure {
    message: String,
}

impl From<realfft::FftError> for FftFailure {
    fn from(e: realfft::FftError) -> Self {
        Self {
            message: e.to_string(),
        }
    }
}

/// Real 2-D FFT on an `ny × nx` grid (row-major, `x` fastest) used as a convolution engine:
/// `output = IFFT2(K̂ · FFT2(input))` with a real spectral kernel `K̂`.
///
/// Rows are transformed with real-to-complex FFTs (`realfft`), columns of the half spectrum
/// (`nx/2 + 1` of them) with complex FFTs (`rustfft`) after a tiled transpose; the spectrum is
/// kept in transposed layout `[kx][ky]`, where the kernel is applied. Plans, work buffers and FFT
/// scratch are allocated once in [`RealFft2d::new`]; a transform allocates nothing. Rows and
/// columns are split into a fixed number of chunks processed with rayon; every row and column is
/// transformed by the same code whatever the chunking, so results are bit-identical for any
/// thread count.
pub struct RealFft2d {
    nx: usize,
    ny: usize,
    nxc: usize,
    r2c: Arc<dyn RealToComplex<f64>>,
    c2r: Arc<dyn ComplexToReal<f64>>,
    col_forward: Arc<dyn Fft<f64>>,
    col_inverse: Arc<dyn Fft<f64>>,
    real: Vec<f64>,
    rows: Vec<Complex<f64>>,
    cols: Vec<Complex<f64>>,
    scratch: Vec<Vec<Complex<f64>>>,
    rows_per_chunk: usize,
    cols_per_chunk: usize,
}

impl std::fmt::Debug for RealFft2d {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RealFft2d")
            .field("nx", &self.nx)
            .field("ny", &self.ny)
            .finish_non_exhaustive()
    }
}

/// What the column pass does after the forward column FFT.
#[derive(Clone, Copy)]
enum ColumnPass<'a> {
    ForwardOnly,
    Convolve(Option<&'a [f64]>),
}

impl RealFft2d {
    /// Plans the transforms of an `ny × nx` grid (`nx, ny ≥ 1`).
    pub fn new(nx: usize, ny: usize) -> Self {
        let nx = nx.max(1);
        let ny = ny.max(1);
        let nxc = nx / 2 + 1;
        let mut real_planner = RealFftPlanner::<f64>::new();
        let r2c = real_planner.plan_fft_forward(nx);
        let c2r = real_planner.plan_fft_inverse(nx);
        let mut planner = FftPlanner::<f64>::new();
        let col_forward = planner.plan_fft_forward(ny);
        let col_inverse = planner.plan_fft_inverse(ny);
        let scratch_len = r2c
            .get_scratch_len()
            .max(c2r.get_scratch_len())
            .max(col_forward.get_inplace_scratch_len())
            .max(col_inverse.get_inplace_scratch_len());
        let chunks = rayon::current_num_threads().max(1);
        let rows_per_chunk = ny.div_ceil(chunks).max(1);
        let cols_per_chunk = nxc.div_ceil(chunks).max(1);
        let zero = Complex::new(0.0, 0.0);
        Self {
            nx,
            ny,
            nxc,
            r2c,
            c2r,
            col_forward,
            col_inverse,
            real: vec![0.0; nx * ny],
            rows: vec![zero; nxc * ny],
            cols: vec![zero; nxc * ny],
            scratch: vec![vec![zero; scratch_len]; chunks],
            rows_per_chunk,
            cols_per_chunk,
        }
    }

    /// Grid size `(nx, ny)`.
    pub fn shape(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// Number of complex spectrum values `(nx/2 + 1) · ny`; a kernel has this length, in the
    /// transposed layout `[kx][ky]` (index `kx · ny + ky`).
    pub fn spectrum_len(&self) -> usize {
        self.nxc * self.ny
    }

    /// Forward transform of a full `ny × nx` grid; returns the spectrum in layout `[kx][ky]`.
    pub fn forward(&mut self, input: &[f64]) -> Result<&[Complex<f64>], FftFailure> {
        self.rows_forward(input, self.nx, self.ny)?;
        self.columns(ColumnPass::ForwardOnly);
        Ok(&self.cols)
    }

    /// Forward transform, inverse transform and normalisation `1/(nx·ny)` in place: one FFT pair.
    pub fn round_trip(&mut self, data: &mut [f64]) -> Result<(), FftFailure> {
        self.rows_forward(data, self.nx, self.ny)?;
        self.columns(ColumnPass::Convolve(None));
        self.rows_inverse(data, self.nx, self.ny)
    }

    /// Circular convolution of the block `input` (`rows × cols`, row-major, placed in the top-left
    /// corner of the zero-padded grid) with the spectral kernel `kernel` (real, layout
    /// `[kx][ky]`, normalisation included); the top-left `rows × cols` block of the result is
    /// written to `output`.
    pub fn convolve(
        &mut self,
        input: &[f64],
        kernel: &[f64],
        output: &mut [f64],
        cols: usize,
        rows: usize,
    ) -> Result<(), FftFailure> {
        self.rows_forward(input, cols, rows)?;
        self.columns(ColumnPass::Convolve(Some(kernel)));
        self.rows_inverse(output, cols, rows)
    }

    fn rows_forward(&mut self, input: &[f64], cols: usize, rows: usize) -> Result<(), FftFailure> {
        let (nx, nxc, rpc) = (self.nx, self.nxc, self.rows_per_chunk);
        let r2c = &self.r2c;
        self.real
            .par_chunks_mut(nx * rpc)
            .zip(self.rows.par_chunks_mut(nxc * rpc))
            .zip(self.scratch.par_iter_mut())
            .enumerate()
            .try_for_each(|(chunk, ((real, spec), scratch))| {
                let first_row = chunk * rpc;
                for (k, (real_row, spec_row)) in
                    real.chunks_mut(nx).zip(spec.chunks_mut(nxc)).enumerate()
                {
                    let iy = first_row + k;
                    if iy >= rows {
                        spec_row.fill(Complex::new(0.0, 0.0));
                        continue;
                    }
                    real_row[..cols].copy_from_slice(&input[iy * cols..(iy + 1) * cols]);
                    real_row[cols..].fill(0.0);
                    let len = r2c.get_scratch_len();
                    r2c.process_with_scratch(real_row, spec_row, &mut scratch[..len])?;
                }
                Ok::<(), realfft::FftError>(())
            })?;
        Ok(())
    }

    fn columns(&mut self, pass: ColumnPass<'_>) {
        let (ny, nxc, cpc) = (self.ny, self.nxc, self.cols_per_chunk);
        let norm = 1.0 / (self.nx as f64 * ny as f64);
        let rows = &self.rows;
        let (fwd, inv) = (&self.col_forward, &self.col_inverse);
        self.cols
            .par_chunks_mut(ny * cpc)
            .zip(self.scratch.par_iter_mut())
            .enumerate()
            .for_each(|(chunk, (cols, scratch))| {
                let first_col = chunk * cpc;
                let ncols = cols.len() / ny;
                for tile_start in (0..ncols).step_by(TILE) {
                    let tile_end = (tile_start + TILE).min(ncols);
                    for iy in 0..ny {
                        let src =
                            &rows[iy * nxc + first_col + tile_start..][..tile_end - tile_start];
                        for (k, v) in src.iter().enumerate() {
                            cols[(tile_start + k) * ny + iy] = *v;
                        }
                    }
                }
                let fwd_len = fwd.get_inplace_scratch_len();
                let inv_len = inv.get_inplace_scratch_len();
                for (k, col) in cols.chunks_mut(ny).enumerate() {
                    fwd.process_with_scratch(col, &mut scratch[..fwd_len]);
                    let kernel_col = match pass {
                        ColumnPass::ForwardOnly => continue,
                        ColumnPass::Convolve(kernel) => {
                            kernel.map(|kern| &kern[(first_col + k) * ny..][..ny])
                        }
                    };
                    match kernel_col {
                        Some(kern) => col.iter_mut().zip(kern).for_each(|(c, &w)| *c *= w),
                        None => col.iter_mut().for_each(|c| *c *= norm),
                    }
                    inv.process_with_scratch(col, &mut scratch[..inv_len]);
                }
            });
    }

    fn rows_inverse(
        &mut self,
        output: &mut [f64],
        cols: usize,
        rows: usize,
    ) -> Result<(), FftFailure> {
        let (nx, ny, nxc, rpc) = (self.nx, self.ny, self.nxc, self.rows_per_chunk);
        let spectrum = &self.cols;
        let c2r = &self.c2r;
        let even = nx % 2 == 0;
        self.real
            .par_chunks_mut(nx * rpc)
            .zip(self.rows.par_chunks_mut(nxc * rpc))
            .zip(output.par_chunks_mut(cols * rpc))
            .zip(self.scratch.par_iter_mut())
            .enumerate()
            .try_for_each(|(chunk, (((real, spec), out), scratch))| {
                let first_row = chunk * rpc;
                let needed = rows.saturating_sub(first_row).min(rpc);
                for tile_start in (0..needed).step_by(TILE) {
                    let tile_end = (tile_start + TILE).min(needed);
                    for kx in 0..nxc {
                        let src =
                            &spectrum[kx * ny + first_row + tile_start..][..tile_end - tile_start];
                        for (k, v) in src.iter().enumerate() {
                            spec[(tile_start + k) * nxc + kx] = *v;
                        }
                    }
                }
                let len = c2r.get_scratch_len();
                for k in 0..needed {
                    let spec_row = &mut spec[k * nxc..(k + 1) * nxc];
                    // The inverse of a real signal's spectrum: DC and Nyquist are real up to round-off.
                    spec_row[0].im = 0.0;
                    if even {
                        spec_row[nxc - 1].im = 0.0;
                    }
                    let real_row = &mut real[k * nx..(k + 1) * nx];
                    c2r.process_with_scratch(spec_row, real_row, &mut scratch[..len])?;
                    out[k * cols..(k + 1) * cols].copy_from_slice(&real_row[..cols]);
                }
                Ok::<(), realfft::FftError>(())
            })?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn signal(nx: usize, ny: usize) -> Vec<f64> {
        (0..nx * ny)
            .map(|i| ((i * 7919) % 101) as f64 / 101.0 - 0.5)
            .collect()
    }

    #[test]
    fn round_trip_is_identity() {
        for (nx, ny) in [(8, 8), (9, 6), (16, 5), (1, 4)] {
            let x = signal(nx, ny);
            let mut y = x.clone();
            let mut fft = RealFft2d::new(nx, ny);
            fft.round_trip(&mut y).unwrap();
            for (a, b) in x.iter().zip(&y) {
                // Round-off of two O(n log n) transforms on O(1) data.
                assert!((a - b).abs() < 1e-13, "{nx}×{ny}: {a} vs {b}");
            }
        }
    }

    #[test]
    fn padded_convolution_matches_direct_sum() {
        // Linear convolution of a 5 × 3 block with an even 3 × 3 stencil through a 10 × 6 padded
        // grid: the padding leaves room for the stencil, so nothing wraps around.
        let (cols, rows, nx, ny) = (5, 3, 10, 6);
        let input = signal(cols, rows);
        let mut stencil = vec![0.0; nx * ny];
        stencil[0] = 2.0;
        stencil[1] = -1.0;
        stencil[nx - 1] = -1.0;
        stencil[nx] = 0.5;
        stencil[(ny - 1) * nx] = 0.5;
        let mut fft = RealFft2d::new(nx, ny);
        let norm = 1.0 / (nx * ny) as f64;
        let kernel: Vec<f64> = fft
            .forward(&stencil)
            .unwrap()
            .iter()
            .map(|c| c.re * norm)
            .collect();
        let mut out = vec![0.0; cols * rows];
        fft.convolve(&input, &kernel, &mut out, cols, rows).unwrap();
        let at = |ix: isize, iy: isize| {
            if ix < 0 || iy < 0 || ix >= cols as isize || iy >= rows as isize {
                0.0
            } else {
                input[iy as usize * cols + ix as usize]
            }
        };
        for iy in 0..rows as isize {
            for ix in 0..cols as isize {
                let direct = 2.0 * at(ix, iy) - at(ix - 1, iy) - at(ix + 1, iy)
                    + 0.5 * at(ix, iy - 1)
                    + 0.5 * at(ix, iy + 1);
                let got = out[iy as usize * cols + ix as usize];
                // Round-off of an FFT pair on O(1) data.
                assert!(
                    (direct - got).abs() < 1e-13,
                    "({ix}, {iy}): {direct} vs {got}"
                );
            }
        }
    }
}
