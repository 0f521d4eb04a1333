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
//!
//! The transforms run in double precision (`RealFft2d<f64>`, [`RealFft2d::new`]) or in single
//! precision (`RealFft2d<f32>`, [`RealFft2d::in_precision`]: half the bytes per value and twice
//! the values per SIMD register, relative round-off about `1e-7` instead of `1e-16`; see
//! [`Real`]). Either way the caller's real data are `f64`.

use std::sync::Arc;

use rayon::prelude::*;
use realfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

mod fast_length;
mod grid;
mod padded;
mod passes;
mod real;
mod rows;
mod rows_pass;
mod transpose;

pub use fast_length::fast_even_length;

pub(crate) use grid::{forward_real_2d, inverse_real_2d, inverse_real_spectrum_2d};
use padded::{PaddedColumns, PADDED_TILE};
pub use real::Real;
use rows::{dense_rows, Copy};
pub use rows::{RowSink, RowSource};
use rows_pass::RowPlan;
use transpose::transpose_all;

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
struct ChunkBuffers<T> {
    /// Scratch of the 1-D transforms.
    fft: Vec<Complex<T>>,
    /// One tile of `TILE` columns of `ny` values, transformed without being kept
    /// ([`ColumnPass::Energy`]), or of `PADDED_TILE` padded columns.
    tile: Vec<Complex<T>>,
    /// One real row of `nx` values (a zero-padded input row or an inverse-transformed row).
    row: Vec<T>,
    /// Two rows of `nx` values in `f64`, as callers read and write them (see [`Real`]).
    io: Vec<f64>,
    /// Two packed rows of `nx` complex values ([`RowPlan::Packed`]; empty otherwise).
    pair: Vec<Complex<T>>,
    /// `TILE_ROWS` row spectra of `nx/2 + 1` values gathered for the inverse row transforms.
    spectra: Vec<Complex<T>>,
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
/// zero. A transform allocates nothing, but for the row buffer, which the first forward transform
/// allocates (an inverse transform alone never needs it). `T` is the precision of the
/// transforms (module docs).
pub struct RealFft2d<T: Real = f64> {
    nx: usize,
    ny: usize,
    nxc: usize,
    rows_plan: RowPlan<T>,
    col_forward: Arc<dyn Fft<T>>,
    col_inverse: Arc<dyn Fft<T>>,
    /// The column pass of convolutions as padded linear convolutions, when `ny` is slow to
    /// transform (see [`RealFft2d::for_convolution`]).
    padded: Option<PaddedColumns<T>>,
    rows: Vec<Complex<T>>,
    cols: Vec<Complex<T>>,
    /// Per-column results of an [`ColumnPass::Energy`] pass, summed in column order.
    column_energy: Vec<f64>,
    /// Per-row results of a [`RowSink`].
    row_values: Vec<f64>,
    chunks: Vec<ChunkBuffers<T>>,
    cols_per_chunk: usize,
}

impl<T: Real> std::fmt::Debug for RealFft2d<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RealFft2d")
            .field("nx", &self.nx)
            .field("ny", &self.ny)
            .field("precision", &std::any::type_name::<T>())
            .finish_non_exhaustive()
    }
}

/// What the column pass does.
#[derive(Clone, Copy)]
enum ColumnPass<'a, T> {
    /// Transpose the row spectra in and transform forward.
    Forward,
    /// Forward, multiply by `factor`, inverse.
    Scale(f64),
    /// Forward, multiply by the real kernel (layout `[kx][ky]`), inverse.
    Kernel(&'a [T]),
    /// Inverse only, of the spectrum already in the column buffer.
    Inverse,
    /// Forward, then the energy `Σ_ky kernel |X|²` of every column. The tiles are transformed
    /// in the chunk's own tile buffer: the column buffer is not written (the row spectra, which
    /// the pass only reads, still hold everything a later [`ColumnPass::Kernel`] needs).
    Energy(&'a [T]),
}

impl RealFft2d {
    /// Plans the transforms of an `ny × nx` grid (sizes below 1 are taken as 1); convolution
    /// kernels are spectral kernels, in the layout of [`RealFft2d::forward`].
    pub fn new(nx: usize, ny: usize) -> Self {
        Self::in_precision(nx, ny, false)
    }

    /// Plans the transforms of an `ny × nx` grid for convolutions. Where `ny` has a prime factor
    /// above 31 (which `rustfft` transforms by Rader's or Bluestein's algorithm), the column pass
    /// of a convolution is done as a linear convolution zero-padded to a fast length, about twice
    /// as fast (see `padded.rs`); its kernels then come from
    /// [`RealFft2d::convolution_kernel`]. Otherwise this is [`RealFft2d::new`]. Forward and
    /// inverse transforms are the same either way.
    pub fn for_convolution(nx: usize, ny: usize) -> Self {
        Self::in_precision(nx, ny, true)
    }

    /// [`RealFft2d::inverse_natural`] of a real spectrum in the natural layout (imaginary parts
    /// zero), converted while it is transposed into the column buffer in tiles of `TILE`
    /// columns.
    pub(crate) fn inverse_natural_real(
        &mut self,
        spectrum: &[f64],
        output: &mut [f64],
    ) -> Result<(), FftFailure> {
        self.check_len("spectrum", spectrum.len(), self.spectrum_len())?;
        self.check_len("output", output.len(), self.nx * self.ny)?;
        let (ny, nxc) = (self.ny, self.nxc);
        self.column_buffer()
            .par_chunks_mut(ny * TILE)
            .enumerate()
            .for_each(|(t, tile)| {
                let width = tile.len() / ny;
                for ky in 0..ny {
                    let row = &spectrum[ky * nxc + t * TILE..][..width];
                    for (k, &v) in row.iter().enumerate() {
                        tile[k * ny + ky] = Complex::new(v, 0.0);
                    }
                }
            });
        self.inverse_of_cols(output)
    }

    /// The convolution kernel of the real spectral kernel `spectral` (layout `[kx][ky]`,
    /// normalisation `1/(nx·ny)` included, even in `ky`): `spectral` itself, or with padded
    /// columns its padded form (one inverse transform of each column and one padded forward
    /// transform). A spectral kernel that is not even in `ky` is an error there. A transform of
    /// the same grid in single precision takes this kernel rounded to `f32`.
    pub fn convolution_kernel(&self, spectral: Vec<f64>) -> Result<Vec<f64>, FftFailure> {
        self.check_len("spectral kernel", spectral.len(), self.spectrum_len())?;
        match &self.padded {
            None => Ok(spectral),
            Some(padded) => padded.kernel(&spectral, self.ny, self.col_inverse.as_ref()),
        }
    }
}

impl<T: Real> RealFft2d<T> {
    /// [`RealFft2d::new`] (or with `convolution` [`RealFft2d::for_convolution`]) in the
    /// precision `T`.
    pub fn in_precision(nx: usize, ny: usize, convolution: bool) -> Self {
        let padded = if convolution {
            PaddedColumns::for_columns(ny.max(1))
        } else {
            None
        };
        let nx = nx.max(1);
        let ny = ny.max(1);
        let nxc = nx / 2 + 1;
        let rows_plan = RowPlan::new(nx);
        let mut planner = FftPlanner::<T>::new();
        let col_forward = planner.plan_fft_forward(ny);
        let col_inverse = planner.plan_fft_inverse(ny);
        let scratch_len = rows_plan
            .scratch_len()
            .max(col_forward.get_inplace_scratch_len())
            .max(col_inverse.get_inplace_scratch_len())
            .max(padded.as_ref().map_or(0, PaddedColumns::scratch_len));
        let tile_len = (TILE * ny).max(padded.as_ref().map_or(0, |p| PADDED_TILE * p.len()));
        let chunks = (CHUNKS_PER_THREAD * rayon::current_num_threads()).max(1);
        let cols_per_chunk = nxc.div_ceil(chunks).max(1);
        let zero = Complex::new(T::zero(), T::zero());
        let chunks = (0..chunks)
            .map(|_| ChunkBuffers {
                fft: vec![zero; scratch_len],
                tile: vec![zero; tile_len],
                row: vec![T::zero(); nx],
                io: vec![0.0; 2 * nx],
                pair: vec![zero; if T::PACKED_ROWS { nx } else { 0 }],
                spectra: vec![zero; TILE_ROWS * nxc],
            })
            .collect();
        Self {
            nx,
            ny,
            nxc,
            rows_plan,
            col_forward,
            col_inverse,
            padded,
            rows: Vec::new(),
            cols: Vec::new(),
            column_energy: vec![0.0; nxc],
            row_values: vec![0.0; ny],
            chunks,
            cols_per_chunk,
        }
    }

    /// Grid size `(nx, ny)`.
    pub fn shape(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// Gives back the row and column buffers (`2 · (nx/2 + 1) · ny` complex values, the bulk
    /// of a plan's memory) until the next transform allocates them again, for a plan kept idle
    /// beside another of the same grid. A forward transform kept for a `finish_*` is dropped
    /// with them: finishing it is then an error.
    pub fn release_buffers(&mut self) {
        self.rows = Vec::new();
        self.cols = Vec::new();
    }

    /// The column buffer, allocated (zeroed) where it was not.
    fn column_buffer(&mut self) -> &mut [Complex<T>] {
        if self.cols.is_empty() {
            self.cols = vec![Complex::new(T::zero(), T::zero()); self.nxc * self.ny];
        }
        &mut self.cols
    }

    /// Number of complex spectrum values `(nx/2 + 1) · ny`, in the transposed layout `[kx][ky]`;
    /// a spectral kernel has this length.
    pub fn spectrum_len(&self) -> usize {
        self.nxc * self.ny
    }

    /// Number of values of a convolution kernel: [`RealFft2d::spectrum_len`], or with padded
    /// columns `(nx/2 + 1) · (m/2 + 1)` for the padded length `m`.
    pub fn kernel_len(&self) -> usize {
        self.padded
            .as_ref()
            .map_or(self.spectrum_len(), |p| self.nxc * p.half_len())
    }

    /// Forward transform of a full `ny × nx` grid; returns the spectrum in layout `[kx][ky]`.
    pub fn forward(&mut self, input: &[f64]) -> Result<&[Complex<T>], FftFailure> {
        self.check_len("input", input.len(), self.nx * self.ny)?;
        self.rows_forward(&dense_rows(input), self.nx, self.ny)?;
        self.columns(ColumnPass::Forward, self.ny);
        Ok(&self.cols)
    }

    /// Unnormalised inverse transform of a spectrum in layout `[kx][ky]` to a full `ny × nx`
    /// grid. The imaginary parts a real signal's row spectrum cannot carry (`kx = 0` and, for
    /// even `nx`, `kx = nx/2` after the column transform) are dropped.
    pub fn inverse(
        &mut self,
        spectrum: &[Complex<T>],
        output: &mut [f64],
    ) -> Result<(), FftFailure> {
        self.check_inverse(spectrum, output)?;
        self.column_buffer().copy_from_slice(spectrum);
        self.inverse_of_cols(output)
    }

    /// [`RealFft2d::inverse`] of a spectrum in the natural layout `[ky][kx]` (`ny` rows of
    /// `nx/2 + 1` values), transposed into the column buffer in tiles.
    pub(crate) fn inverse_natural(
        &mut self,
        spectrum: &[Complex<T>],
        output: &mut [f64],
    ) -> Result<(), FftFailure> {
        self.check_inverse(spectrum, output)?;
        let (ny, nxc) = (self.ny, self.nxc);
        transpose_all(spectrum, ny, nxc, self.column_buffer());
        self.inverse_of_cols(output)
    }

    fn check_inverse(&self, spectrum: &[Complex<T>], output: &[f64]) -> Result<(), FftFailure> {
        self.check_len("spectrum", spectrum.len(), self.spectrum_len())?;
        self.check_len("output", output.len(), self.nx * self.ny)
    }

    /// The inverse transform of the spectrum in the column buffer into `output`.
    fn inverse_of_cols(&mut self, output: &mut [f64]) -> Result<(), FftFailure> {
        self.columns(ColumnPass::Inverse, self.ny);
        self.rows_inverse(output, self.nx, self.ny, None::<&Copy>)
    }

    /// Forward transform, inverse transform and normalisation `1/(nx·ny)` in place: one FFT pair.
    pub fn round_trip(&mut self, data: &mut [f64]) -> Result<(), FftFailure> {
        self.check_len("data", data.len(), self.nx * self.ny)?;
        self.rows_forward(&dense_rows(data), self.nx, self.ny)?;
        let factor = 1.0 / (self.nx as f64 * self.ny as f64);
        self.columns(ColumnPass::Scale(factor), self.ny);
        self.rows_inverse(data, self.nx, self.ny, None::<&Copy>)
    }

    /// Circular convolution of the block `input` (`rows × cols`, row-major, placed in the top-left
    /// corner of the zero-padded grid) with the spectral kernel `kernel` (real, layout
    /// `[kx][ky]`, normalisation included); the top-left `rows × cols` block of the result is
    /// written to `output`. One FFT pair; the padding rows are not transformed and only the
    /// `rows` output rows are transformed back.
    pub fn convolve(
        &mut self,
        input: &[f64],
        kernel: &[T],
        output: &mut [f64],
        cols: usize,
        rows: usize,
    ) -> Result<(), FftFailure> {
        self.check_len("input", input.len(), cols * rows)?;
        self.convolve_through(
            &dense_rows(input),
            kernel,
            output,
            cols,
            rows,
            None::<&Copy>,
        )
    }

    /// [`RealFft2d::convolve`] of the block whose rows `fill` supplies (see [`RowSource`]), its
    /// output rows going through `sink` (see [`RowSink`]); returns the sink's value of each of
    /// the `rows` rows.
    pub fn convolve_rows_into<F: RowSource, S: RowSink>(
        &mut self,
        fill: &F,
        kernel: &[T],
        output: &mut [f64],
        cols: usize,
        rows: usize,
        sink: &S,
    ) -> Result<&[f64], FftFailure> {
        self.convolve_through(fill, kernel, output, cols, rows, Some(sink))?;
        Ok(&self.row_values[..rows])
    }

    /// Both halves of a convolution, the output rows written directly or through `sink`.
    fn convolve_through<F: RowSource, S: RowSink>(
        &mut self,
        fill: &F,
        kernel: &[T],
        output: &mut [f64],
        cols: usize,
        rows: usize,
        sink: Option<&S>,
    ) -> Result<(), FftFailure> {
        self.check_back(kernel, output, cols, rows)?;
        if cols == 0 || rows == 0 {
            return Ok(());
        }
        self.rows_forward(fill, cols, rows)?;
        self.finish_through(kernel, output, cols, rows, sink)
    }

    /// First half of [`RealFft2d::convolve`]: the forward transform of the block `input`, kept
    /// for [`RealFft2d::finish_convolve`]. Returns the quadratic form
    /// `Σ_r input(r) · (K input)(r) = Σ_k kernel(k) |X(k)|²` (Parseval, with the mirrored half of
    /// the spectrum counted twice), where `K` is the convolution with `kernel`; the kernel must
    /// be even (`kernel(−k) = kernel(k)`), as every kernel of a convolution with a symmetric
    /// stencil is. The sum runs column by column in a fixed order, so it does not depend on the
    /// thread count.
    pub fn start_convolve(
        &mut self,
        input: &[f64],
        kernel: &[T],
        cols: usize,
        rows: usize,
    ) -> Result<f64, FftFailure> {
        self.check_len("input", input.len(), cols * rows)?;
        self.start_convolve_rows(&dense_rows(input), kernel, cols, rows)
    }

    /// [`RealFft2d::start_convolve`] of the block whose rows `fill` supplies (see
    /// [`RowSource`]).
    pub fn start_convolve_rows<F: RowSource>(
        &mut self,
        fill: &F,
        kernel: &[T],
        cols: usize,
        rows: usize,
    ) -> Result<f64, FftFailure> {
        self.check_block(cols, rows)?;
        self.check_len("kernel", kernel.len(), self.kernel_len())?;
        if cols == 0 || rows == 0 {
            return Ok(0.0);
        }
        self.rows_forward(fill, cols, rows)?;
        self.columns(ColumnPass::Energy(kernel), rows);
        let (nx, nxc) = (self.nx, self.nxc);
        Ok(self
            .column_energy
            .iter()
            .enumerate()
            .map(|(kx, &e)| {
                // Columns 0 and (for even nx) nx/2 are their own mirror images.
                if kx == 0 || (nx % 2 == 0 && kx == nxc - 1) {
                    e
                } else {
                    2.0 * e
                }
            })
            .sum())
    }

    /// Second half of [`RealFft2d::convolve`], from the row spectra kept by the last
    /// [`RealFft2d::start_convolve`] (no other transform may run in between): transforms the
    /// columns, multiplies by `kernel`, transforms back and writes the top-left `rows × cols`
    /// block to `output`. The two halves give the same bits as [`RealFft2d::convolve`]. (The
    /// column transforms are repeated here rather than kept by `start_convolve`: writing the
    /// column spectra out costs the first half more than redoing them costs the second, which a
    /// caller needs only sometimes.)
    pub fn finish_convolve(
        &mut self,
        kernel: &[T],
        output: &mut [f64],
        cols: usize,
        rows: usize,
    ) -> Result<(), FftFailure> {
        self.check_back(kernel, output, cols, rows)?;
        if cols == 0 || rows == 0 {
            return Ok(());
        }
        self.finish_through(kernel, output, cols, rows, None::<&Copy>)
    }

    /// [`RealFft2d::finish_convolve`] whose output rows go through `sink` (see [`RowSink`]);
    /// returns the sink's value of each of the `rows` rows.
    pub fn finish_convolve_into<S: RowSink>(
        &mut self,
        kernel: &[T],
        output: &mut [f64],
        cols: usize,
        rows: usize,
        sink: &S,
    ) -> Result<&[f64], FftFailure> {
        self.check_back(kernel, output, cols, rows)?;
        if cols == 0 || rows == 0 {
            return Ok(&[]);
        }
        self.finish_through(kernel, output, cols, rows, Some(sink))?;
        Ok(&self.row_values[..rows])
    }

    /// The way back of a convolution from the row spectra (`cols, rows ≥ 1`): column transforms,
    /// kernel, inverse transforms, output rows written directly or through `sink`.
    fn finish_through<S: RowSink>(
        &mut self,
        kernel: &[T],
        output: &mut [f64],
        cols: usize,
        rows: usize,
        sink: Option<&S>,
    ) -> Result<(), FftFailure> {
        if self.rows.is_empty() {
            return Err(FftFailure::new(
                "no forward transform to finish: the plan's buffers were released after it",
            ));
        }
        self.columns(ColumnPass::Kernel(kernel), rows);
        self.rows_inverse(output, cols, rows, sink)
    }

    /// The block, kernel and output of a convolution's way back.
    fn check_back(
        &self,
        kernel: &[T],
        output: &[f64],
        cols: usize,
        rows: usize,
    ) -> Result<(), FftFailure> {
        self.check_block(cols, rows)?;
        self.check_len("output", output.len(), cols * rows)?;
        self.check_len("kernel", kernel.len(), self.kernel_len())
    }

    fn check_block(&self, cols: usize, rows: usize) -> Result<(), FftFailure> {
        if cols > self.nx || rows > self.ny {
            return Err(FftFailure::new(format!(
                "block {cols} × {rows} exceeds the grid {} × {}",
                self.nx, self.ny
            )));
        }
        Ok(())
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
}

#[cfg(test)]
mod tests;
