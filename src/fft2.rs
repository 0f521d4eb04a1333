//! Two-dimensional real FFT shared by the numerics (`surface` spectra, `contact` convolutions).
//!
//! [`RealFft2d`] transforms an `ny × nx` grid (row-major, `x` fastest): real-to-complex FFTs of
//! the rows (`realfft`), then complex FFTs (`rustfft`) of the `nx/2 + 1` columns of the half
//! spectrum. Transforms are unnormalised (`Z(k) = Σ z(r) e^{−i k·r}`; the inverse omits `1/N`),
//! as in FFTW/rustfft, except [`RealFft2d::round_trip`] and [`RealFft2d::convolve`] which
//! normalise. [`forward_real_2d`] and [`inverse_real_2d`] wrap it for `ndarray` grids with the
//! half spectrum in the natural layout `[ky][kx]`.
//!
//! Rows and columns are transformed in parallel with rayon; every 1-D transform is computed by
//! the same code whatever the chunking, so results are bit-identical for any thread count.

use std::sync::Arc;

use ndarray::Array2;
use rayon::prelude::*;
use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::{Fft, FftPlanner};

/// Columns transformed together: a tile of `TILE` columns of `ny` complex values is transposed,
/// transformed forward, multiplied and transformed back while it is in cache.
const TILE: usize = 16;

/// Row spectra gathered together from the column buffer before their inverse row transforms.
const TILE_ROWS: usize = 16;

/// Work chunks per rayon thread (more chunks than threads balance a shared, loaded machine).
const CHUNKS_PER_THREAD: usize = 4;

/// A 2-D FFT failed: a buffer length does not match the planned grid.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("FFT failed: {message}")]
pub struct FftFailure {
    message: String,
}

impl FftFailure {
    pub(crate) fn new(message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
        }
    }
}

impl From<realfft::FftError> for FftFailure {
    fn from(e: realfft::FftError) -> Self {
        Self::new(e.to_string())
    }
}

/// Cache-sized working memory of one parallel work chunk.
struct ChunkBuffers {
    /// Scratch of the 1-D transforms.
    fft: Vec<Complex<f64>>,
    /// One real row of `nx` values (a zero-padded input row or an inverse-transformed row).
    row: Vec<f64>,
    /// `TILE_ROWS` row spectra of `nx/2 + 1` values gathered for the inverse row transforms.
    spectra: Vec<Complex<f64>>,
}

/// Real 2-D FFT of an `ny × nx` grid with plans, buffers and scratch allocated once.
///
/// The spectrum is kept in transposed layout `[kx][ky]` (index `kx · ny + ky`, `kx ≤ nx/2`,
/// `ky` in FFT order: `ky = j` for `j ≤ ny/2`, `j − ny` above), where a convolution kernel is
/// applied column by column. Each pass streams once through the grid: input rows are copied
/// into a per-chunk row buffer and transformed into the row spectra; tiles of columns are
/// gathered, transformed (and multiplied and transformed back) in cache; tiles of row spectra
/// are gathered and transformed back into the output. Rows that are all zero (the padding of a
/// [`RealFft2d::convolve`] block, or rows without load) are not transformed: their spectrum is
/// zero. A transform allocates nothing.
pub struct RealFft2d {
    nx: usize,
    ny: usize,
    nxc: usize,
    r2c: Arc<dyn RealToComplex<f64>>,
    c2r: Arc<dyn ComplexToReal<f64>>,
    col_forward: Arc<dyn Fft<f64>>,
    col_inverse: Arc<dyn Fft<f64>>,
    rows: Vec<Complex<f64>>,
    cols: Vec<Complex<f64>>,
    chunks: Vec<ChunkBuffers>,
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

/// What the column pass does.
#[derive(Clone, Copy)]
enum ColumnPass<'a> {
    /// Transpose the row spectra in and transform forward.
    Forward,
    /// Forward, multiply by `factor`, inverse.
    Scale(f64),
    /// Forward, multiply by the real kernel (layout `[kx][ky]`), inverse.
    Kernel(&'a [f64]),
    /// Inverse only, of the spectrum already in the column buffer.
    Inverse,
}

impl RealFft2d {
    /// Plans the transforms of an `ny × nx` grid (sizes below 1 are taken as 1).
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
        let chunks = (CHUNKS_PER_THREAD * rayon::current_num_threads()).max(1);
        let cols_per_chunk = nxc.div_ceil(chunks).max(1);
        let zero = Complex::new(0.0, 0.0);
        let chunks = (0..chunks)
            .map(|_| ChunkBuffers {
                fft: vec![zero; scratch_len],
                row: vec![0.0; nx],
                spectra: vec![zero; TILE_ROWS * nxc],
            })
            .collect();
        Self {
            nx,
            ny,
            nxc,
            r2c,
            c2r,
            col_forward,
            col_inverse,
            rows: vec![zero; nxc * ny],
            cols: vec![zero; nxc * ny],
            chunks,
            cols_per_chunk,
        }
    }

    /// Grid size `(nx, ny)`.
    pub fn shape(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// Number of complex spectrum values `(nx/2 + 1) · ny`; a kernel has this length, in the
    /// transposed layout `[kx][ky]`.
    pub fn spectrum_len(&self) -> usize {
        self.nxc * self.ny
    }

    /// Forward transform of a full `ny × nx` grid; returns the spectrum in layout `[kx][ky]`.
    pub fn forward(&mut self, input: &[f64]) -> Result<&[Complex<f64>], FftFailure> {
        self.check_len("input", input.len(), self.nx * self.ny)?;
        self.rows_forward(input, self.nx, self.ny)?;
        self.columns(ColumnPass::Forward, self.ny);
        Ok(&self.cols)
    }

    /// Unnormalised inverse transform of a spectrum in layout `[kx][ky]` to a full `ny × nx`
    /// grid. The imaginary parts a real signal's row spectrum cannot carry (`kx = 0` and, for
    /// even `nx`, `kx = nx/2` after the column transform) are dropped.
    pub fn inverse(
        &mut self,
        spectrum: &[Complex<f64>],
        output: &mut [f64],
    ) -> Result<(), FftFailure> {
        self.check_len("spectrum", spectrum.len(), self.spectrum_len())?;
        self.check_len("output", output.len(), self.nx * self.ny)?;
        self.cols.copy_from_slice(spectrum);
        self.columns(ColumnPass::Inverse, self.ny);
        self.rows_inverse(output, self.nx, self.ny)
    }

    /// Forward transform, inverse transform and normalisation `1/(nx·ny)` in place: one FFT pair.
    pub fn round_trip(&mut self, data: &mut [f64]) -> Result<(), FftFailure> {
        self.check_len("data", data.len(), self.nx * self.ny)?;
        self.rows_forward(data, self.nx, self.ny)?;
        let factor = 1.0 / (self.nx as f64 * self.ny as f64);
        self.columns(ColumnPass::Scale(factor), self.ny);
        self.rows_inverse(data, self.nx, self.ny)
    }

    /// Circular convolution of the block `input` (`rows × cols`, row-major, placed in the top-left
    /// corner of the zero-padded grid) with the spectral kernel `kernel` (real, layout
    /// `[kx][ky]`, normalisation included); the top-left `rows × cols` block of the result is
    /// written to `output`. One FFT pair; the padding rows are not transformed and only the
    /// `rows` output rows are transformed back.
    pub fn convolve(
        &mut self,
        input: &[f64],
        kernel: &[f64],
        output: &mut [f64],
        cols: usize,
        rows: usize,
    ) -> Result<(), FftFailure> {
        if cols > self.nx || rows > self.ny {
            return Err(FftFailure::new(format!(
                "block {cols} × {rows} exceeds the grid {} × {}",
                self.nx, self.ny
            )));
        }
        self.check_len("input", input.len(), cols * rows)?;
        self.check_len("output", output.len(), cols * rows)?;
        self.check_len("kernel", kernel.len(), self.spectrum_len())?;
        if cols == 0 || rows == 0 {
            return Ok(());
        }
        self.rows_forward(input, cols, rows)?;
        self.columns(ColumnPass::Kernel(kernel), rows);
        self.rows_inverse(output, cols, rows)
    }

    fn check_len(&self, what: &str, got: usize, expected: usize) -> Result<(), FftFailure> {
        if got == expected {
            Ok(())
        } else {
            Err(FftFailure::new(format!(
                "{what} has {got} values, expected {expected} for the {} × {} grid",
                self.nx, self.ny
            )))
        }
    }

    /// Row spectra of the `rows × cols` block `input` (`cols, rows ≥ 1`), zero-padded to `nx`,
    /// into the first `rows` rows of the row buffer.
    fn rows_forward(&mut self, input: &[f64], cols: usize, rows: usize) -> Result<(), FftFailure> {
        let nxc = self.nxc;
        let rpc = rows.div_ceil(self.chunks.len()).max(1);
        let r2c = &self.r2c;
        let len = r2c.get_scratch_len();
        self.rows[..rows * nxc]
            .par_chunks_mut(nxc * rpc)
            .zip(input.par_chunks(cols * rpc))
            .zip(self.chunks.par_iter_mut())
            .try_for_each(|((spectra, block), buffers)| {
                for (spectrum, values) in spectra.chunks_mut(nxc).zip(block.chunks(cols)) {
                    if values.iter().all(|&v| v == 0.0) {
                        spectrum.fill(Complex::new(0.0, 0.0));
                        continue;
                    }
                    let row = &mut buffers.row;
                    row[..cols].copy_from_slice(values);
                    row[cols..].fill(0.0);
                    r2c.process_with_scratch(row, spectrum, &mut buffers.fft[..len])?;
                }
                Ok::<(), realfft::FftError>(())
            })?;
        Ok(())
    }

    /// Column pass over the column buffer; a forward transform reads the first `rows` row
    /// spectra of the row buffer (the rows below are zero).
    fn columns(&mut self, pass: ColumnPass<'_>, rows: usize) {
        let (ny, nxc, cpc) = (self.ny, self.nxc, self.cols_per_chunk);
        let spectra = &self.rows;
        let (fwd, inv) = (&self.col_forward, &self.col_inverse);
        self.cols
            .par_chunks_mut(ny * cpc)
            .zip(self.chunks.par_iter_mut())
            .enumerate()
            .for_each(|(chunk, (cols, buffers))| {
                let first_col = chunk * cpc;
                let scratch = &mut buffers.fft;
                let fwd_len = fwd.get_inplace_scratch_len();
                let inv_len = inv.get_inplace_scratch_len();
                for (t, tile) in cols.chunks_mut(ny * TILE).enumerate() {
                    let tile_col = first_col + t * TILE;
                    let width = tile.len() / ny;
                    if !matches!(pass, ColumnPass::Inverse) {
                        transpose(spectra, nxc, rows, tile_col, width, tile, ny);
                        for column in tile.chunks_mut(ny) {
                            column[rows..].fill(Complex::new(0.0, 0.0));
                        }
                        fwd.process_with_scratch(tile, &mut scratch[..fwd_len]);
                    }
                    match pass {
                        ColumnPass::Forward => continue,
                        ColumnPass::Scale(factor) => tile.iter_mut().for_each(|c| *c *= factor),
                        ColumnPass::Kernel(kernel) => {
                            let weights = &kernel[tile_col * ny..][..width * ny];
                            tile.iter_mut().zip(weights).for_each(|(c, &w)| *c *= w);
                        }
                        ColumnPass::Inverse => {}
                    }
                    inv.process_with_scratch(tile, &mut scratch[..inv_len]);
                }
            });
    }

    /// Inverse row transforms of the first `rows` rows (`cols, rows ≥ 1`) of the spectrum in the
    /// column buffer; the first `cols` values of each are written to `output` (`rows × cols`).
    fn rows_inverse(
        &mut self,
        output: &mut [f64],
        cols: usize,
        rows: usize,
    ) -> Result<(), FftFailure> {
        let (nx, ny, nxc) = (self.nx, self.ny, self.nxc);
        let rpc = rows.div_ceil(self.chunks.len()).max(1);
        let spectrum = &self.cols;
        let c2r = &self.c2r;
        let len = c2r.get_scratch_len();
        let even = nx % 2 == 0;
        output
            .par_chunks_mut(cols * rpc)
            .zip(self.chunks.par_iter_mut())
            .enumerate()
            .try_for_each(|(chunk, (out, buffers))| {
                let ChunkBuffers { fft, row, spectra } = buffers;
                for (t, out_tile) in out.chunks_mut(cols * TILE_ROWS).enumerate() {
                    let tile_row = chunk * rpc + t * TILE_ROWS;
                    let height = out_tile.len() / cols;
                    transpose(spectrum, ny, nxc, tile_row, height, spectra, nxc);
                    for (spec_row, out_row) in
                        spectra.chunks_mut(nxc).zip(out_tile.chunks_mut(cols))
                    {
                        // The inverse of a real signal's spectrum: DC and Nyquist are real up to
                        // round-off.
                        spec_row[0].im = 0.0;
                        if even {
                            spec_row[nxc - 1].im = 0.0;
                        }
                        if cols == nx {
                            c2r.process_with_scratch(spec_row, out_row, &mut fft[..len])?;
                        } else {
                            c2r.process_with_scratch(spec_row, row, &mut fft[..len])?;
                            out_row.copy_from_slice(&row[..cols]);
                        }
                    }
                }
                Ok::<(), realfft::FftError>(())
            })?;
        Ok(())
    }
}

/// Complex values per 64-byte cache line.
const LINE: usize = 4;

/// `dst[k · dst_stride + i] = src[i · src_stride + first_col + k]` for `i < rows`, `k < width`:
/// the columns `first_col..first_col + width` of the first `rows` rows of the row-major `src`
/// become rows of `dst`. Rows are taken `LINE` at a time so that each destination cache line is
/// written whole (with power-of-two strides the `width` destination lines share a cache set).
fn transpose(
    src: &[Complex<f64>],
    src_stride: usize,
    rows: usize,
    first_col: usize,
    width: usize,
    dst: &mut [Complex<f64>],
    dst_stride: usize,
) {
    for first_row in (0..rows).step_by(LINE) {
        let height = LINE.min(rows - first_row);
        let block = &src[first_row * src_stride + first_col..];
        for k in 0..width {
            let line = &mut dst[k * dst_stride + first_row..][..height];
            for (i, value) in line.iter_mut().enumerate() {
                *value = block[i * src_stride + k];
            }
        }
    }
}

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
    Ok(Array2::from_shape_fn((ny, nxh), |(j, i)| {
        spectrum[i * ny + j]
    }))
}

/// Inverse of a `[ny, nx/2 + 1]` half spectrum to a real `[ny, nx]` grid, unnormalised (divide
/// by `nx·ny` to invert [`forward_real_2d`]). The imaginary parts a real signal's row spectrum
/// cannot carry (the `kx = 0` and, for even `nx`, `kx = nx/2` columns after the y transform) are
/// dropped; callers that build Hermitian spectra make them zero up to round-off.
pub(crate) fn inverse_real_2d(
    half: &Array2<Complex<f64>>,
    nx: usize,
) -> Result<Array2<f64>, FftFailure> {
    let (ny, nxh) = half.dim();
    if nxh != nx / 2 + 1 || nx == 0 || ny == 0 {
        return Err(FftFailure::new(format!(
            "half spectrum is {ny} × {nxh}, expected {} columns for nx = {nx}",
            nx / 2 + 1
        )));
    }
    let transposed: Vec<Complex<f64>> = half.t().iter().copied().collect();
    let mut fft = RealFft2d::new(nx, ny);
    let mut out = vec![0.0; nx * ny];
    fft.inverse(&transposed, &mut out)?;
    Array2::from_shape_vec((ny, nx), out).map_err(|e| FftFailure::new(e.to_string()))
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
        for (nx, ny) in [(8, 8), (9, 6), (16, 5), (1, 4), (40, 70)] {
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
    fn wrong_lengths_are_errors() {
        let mut fft = RealFft2d::new(4, 3);
        assert!(fft.forward(&[0.0; 11]).is_err());
        assert!(fft.round_trip(&mut [0.0; 13]).is_err());
        let mut out = [0.0; 6];
        assert!(fft.convolve(&[0.0; 6], &[0.0; 9], &mut out, 3, 2).is_ok());
        assert!(fft.convolve(&[0.0; 6], &[0.0; 8], &mut out, 3, 2).is_err());
        assert!(fft
            .convolve(&[0.0; 10], &[0.0; 9], &mut [0.0; 10], 5, 2)
            .is_err());
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
        let kernel = spectral_kernel(&mut fft, &stencil);
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

    /// The normalised real spectrum of an even stencil: the kernel `convolve` takes.
    fn spectral_kernel(fft: &mut RealFft2d, stencil: &[f64]) -> Vec<f64> {
        let (nx, ny) = fft.shape();
        let norm = 1.0 / (nx * ny) as f64;
        fft.forward(stencil)
            .unwrap()
            .iter()
            .map(|c| c.re * norm)
            .collect()
    }

    /// Even stencil on an `nx × ny` grid (`s(x, y) = s(−x, y) = s(x, −y)`, real spectrum).
    fn even_stencil(nx: usize, ny: usize) -> Vec<f64> {
        (0..nx * ny)
            .map(|i| {
                let (x, y) = (i % nx, i / nx);
                let (x, y) = (x.min(nx - x), y.min(ny - y));
                1.0 / (1.0 + (x * x + 3 * y * y) as f64)
            })
            .collect()
    }

    #[test]
    fn zero_rows_match_direct_circular_sum() {
        // Block rows 1 and 3 are zero (skipped by the row pass) and the block is padded in both
        // directions; the result must still be the circular convolution with the stencil.
        let (cols, rows, nx, ny) = (6, 5, 12, 10);
        let mut input = signal(cols, rows);
        for iy in [1, 3] {
            input[iy * cols..(iy + 1) * cols].fill(0.0);
        }
        let stencil = even_stencil(nx, ny);
        let mut fft = RealFft2d::new(nx, ny);
        let kernel = spectral_kernel(&mut fft, &stencil);
        let mut out = vec![0.0; cols * rows];
        fft.convolve(&input, &kernel, &mut out, cols, rows).unwrap();
        for iy in 0..rows {
            for ix in 0..cols {
                let mut direct = 0.0;
                for jy in 0..rows {
                    for jx in 0..cols {
                        let (dx, dy) = ((ix + nx - jx) % nx, (iy + ny - jy) % ny);
                        direct += input[jy * cols + jx] * stencil[dy * nx + dx];
                    }
                }
                let got = out[iy * cols + ix];
                // Round-off of an FFT pair on O(1) data summed over 30 terms.
                assert!(
                    (direct - got).abs() < 1e-13,
                    "({ix}, {iy}): {direct} vs {got}"
                );
            }
        }
    }

    #[test]
    fn results_are_bit_identical_for_any_thread_count() {
        // The chunking follows the rayon thread count; every 1-D transform must not.
        let (cols, rows, nx, ny) = (21, 35, 42, 70);
        let mut input = signal(cols, rows);
        input[5 * cols..7 * cols].fill(0.0);
        let kernel: Vec<f64> = signal(nx / 2 + 1, ny);
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                let mut fft = RealFft2d::new(nx, ny);
                let mut out = vec![0.0; cols * rows];
                fft.convolve(&input, &kernel, &mut out, cols, rows).unwrap();
                let mut grid = signal(nx, ny);
                fft.round_trip(&mut grid).unwrap();
                out.extend(grid);
                out.extend(
                    fft.forward(&signal(nx, ny))
                        .unwrap()
                        .iter()
                        .map(|c| c.re + c.im),
                );
                out.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
            })
        };
        let one = run(1);
        for threads in [2, 3] {
            assert!(one == run(threads), "{threads} threads differ from 1");
        }
    }

    #[test]
    fn empty_block_convolves_to_nothing() {
        let mut fft = RealFft2d::new(8, 6);
        let kernel = vec![1.0; fft.spectrum_len()];
        assert!(fft.convolve(&[], &kernel, &mut [], 0, 3).is_ok());
        assert!(fft.convolve(&[], &kernel, &mut [], 4, 0).is_ok());
    }

    #[test]
    fn grid_round_trip_recovers_the_grid() {
        for (ny, nx) in [(6, 8), (5, 7), (4, 9), (2, 2), (37, 20)] {
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
        assert!(inverse_real_2d(&Array2::zeros((3, 4)), 8).is_err());
    }

    #[test]
    fn forward_matches_direct_dft() {
        let (ny, nx) = (3, 4);
        let z = Array2::from_shape_fn((ny, nx), |(j, i)| (i as f64).sin() + (j * j) as f64);
        let half = forward_real_2d(&z).unwrap();
        for ((j, i), value) in half.indexed_iter() {
            let mut direct = Complex::new(0.0, 0.0);
            for ((y, x), zz) in z.indexed_iter() {
                let phase = -2.0
                    * std::f64::consts::PI
                    * ((i * x) as f64 / nx as f64 + (j * y) as f64 / ny as f64);
                direct += Complex::from_polar(*zz, phase);
            }
            // Direct O(N²) sum vs FFT: round-off only.
            assert!((direct - value).norm() < 1e-12);
        }
    }
}
