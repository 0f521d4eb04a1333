//! The column pass of a periodic convolution as a zero-padded cyclic convolution of a fast
//! length.
//!
//! A periodic convolution along a column of length `n`,
//! `u(y) = Σ_{y' < n} k((y − y') mod n) c(y')` for `y < n`,
//! equals the cyclic convolution of length `m ≥ 2n − 1` of the column zero-padded to `m` with
//! the kernel extended to
//! `e(j) = k(j)` for `j < n`, `e(j) = k(j − m + n)` for `j > m − n`, `e(j) = 0` between,
//! restricted to `y < n`: the differences `y − y'` lie in `(−n, n)` and are distinct modulo `m`
//! (the standard reduction of a cyclic convolution to a linear one, e.g. Press et al.,
//! *Numerical Recipes*, 3rd ed., §13.1). With `m` 7-smooth that is two FFTs of length `m` per
//! column where the column's own DFT pair costs two transforms of length `n`; when `n` has a
//! prime factor `rustfft` computes by Rader's or Bluestein's algorithm, the padded pair is about
//! twice as fast (measured in `docs/contact-solver-design.md`).
//!
//! The kernel `k` of column `kx` is the inverse DFT of that column of the spectral kernel; for
//! an even spectral kernel (`K(kx, −ky) = K(kx, ky)`), `k` and `e` are real and even, so the
//! spectrum `E = DFT_m(e) / m` is real and even too and only `E(0..=m/2)` is kept. The quadratic
//! form of a column follows from Parseval on the padded circle, whose extra points carry no
//! input: `Σ_{y<n} c̄(y) u(y) = Σ_j E(j) |C(j)|²` with `C = DFT_m(c)`.

use std::sync::Arc;

use rayon::prelude::*;
use realfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

use super::fast_length::{fast_even_length, has_slow_factor};
use super::real::weighted_norm;
use super::transpose::transpose;
use super::{ChunkBuffers, FftFailure, Real};

/// Padded columns transformed together, as many as the spectral pass (`TILE`); narrower tiles,
/// which fit a 512 kB L2 cache, measured slower (`docs/contact-solver-design.md`).
pub(super) const PADDED_TILE: usize = 16;

/// One padded column pass: what it reads from the [`super::RealFft2d`].
pub(super) struct PaddedPass<'a, T> {
    /// Row spectra, `nxc` values per row; the first `rows` rows are read.
    pub(super) spectra: &'a [Complex<T>],
    pub(super) nxc: usize,
    /// Column length `n`.
    pub(super) ny: usize,
    pub(super) rows: usize,
    pub(super) cols_per_chunk: usize,
    /// Padded kernel, `m/2 + 1` values per column.
    pub(super) kernel: &'a [T],
    /// Only the quadratic form of each column: the column buffer is not written.
    pub(super) energy_only: bool,
}

/// Plans of the padded column pass.
pub(super) struct PaddedColumns<T> {
    /// Padded length `m ≥ 2n − 1`, even and 7-smooth.
    len: usize,
    forward: Arc<dyn Fft<T>>,
    inverse: Arc<dyn Fft<T>>,
}

impl<T: Real> PaddedColumns<T> {
    /// The padded pass for columns of length `n`, or `None` when `n` has no prime factor above
    /// 31 and its own transforms are the faster way.
    pub(super) fn for_columns(n: usize) -> Option<Self> {
        if !has_slow_factor(n) {
            return None;
        }
        let len = fast_even_length(2 * n);
        let mut planner = FftPlanner::<T>::new();
        Some(Self {
            len,
            forward: planner.plan_fft_forward(len),
            inverse: planner.plan_fft_inverse(len),
        })
    }

    /// The padded length `m`.
    pub(super) fn len(&self) -> usize {
        self.len
    }

    /// Kernel values kept per column, `m/2 + 1`.
    pub(super) fn half_len(&self) -> usize {
        self.len / 2 + 1
    }

    /// Scratch the padded transforms need.
    pub(super) fn scratch_len(&self) -> usize {
        self.forward
            .get_inplace_scratch_len()
            .max(self.inverse.get_inplace_scratch_len())
    }

    /// The column pass of a convolution (or of its quadratic form, `job.energy_only`) through
    /// padded columns: the output columns (`n` values each) go to `cols`, the quadratic forms of
    /// the columns to `energy`. Chunked as the spectral pass, in tiles of [`PADDED_TILE`]
    /// columns; every column is computed by the same code whatever the chunking.
    pub(super) fn run(
        &self,
        job: PaddedPass<'_, T>,
        cols: &mut [Complex<T>],
        energy: &mut [f64],
        chunks: &mut [ChunkBuffers<T>],
    ) {
        let (n, cpc, half, m) = (job.ny, job.cols_per_chunk, self.half_len(), self.len);
        cols.par_chunks_mut(n * cpc)
            .zip(energy.par_chunks_mut(cpc))
            .zip(chunks.par_iter_mut())
            .enumerate()
            .for_each(|(chunk, ((cols, energy), buffers))| {
                for (t, (out, energies)) in cols
                    .chunks_mut(n * PADDED_TILE)
                    .zip(energy.chunks_mut(PADDED_TILE))
                    .enumerate()
                {
                    let first_col = chunk * cpc + t * PADDED_TILE;
                    let width = energies.len();
                    let tile = &mut buffers.tile[..width * m];
                    let kernel = &job.kernel[first_col * half..][..width * half];
                    transpose(job.spectra, job.nxc, job.rows, first_col, width, tile, m);
                    self.forward(tile, job.rows, &mut buffers.fft);
                    if job.energy_only {
                        for ((e, column), weights) in energies
                            .iter_mut()
                            .zip(tile.chunks(m))
                            .zip(kernel.chunks(half))
                        {
                            *e = self.energy(column, weights);
                        }
                    } else {
                        self.finish(tile, kernel, out, &mut buffers.fft);
                    }
                }
            });
    }

    /// Forward transforms of the padded columns of `tile` (`m` values each, the first `rows`
    /// set, the rest zeroed here).
    fn forward(&self, tile: &mut [Complex<T>], rows: usize, scratch: &mut [Complex<T>]) {
        for column in tile.chunks_mut(self.len) {
            column[rows..].fill(Complex::new(T::zero(), T::zero()));
        }
        self.forward
            .process_with_scratch(tile, &mut scratch[..self.forward.get_inplace_scratch_len()]);
    }

    /// Multiplies the forward-transformed columns of `tile` by their kernels `kernel`
    /// (`m/2 + 1` values per column), transforms them back and writes the first `n` values of
    /// each to the columns of `out` (`n` values each).
    fn finish(
        &self,
        tile: &mut [Complex<T>],
        kernel: &[T],
        out: &mut [Complex<T>],
        scratch: &mut [Complex<T>],
    ) {
        let m = self.len;
        for (column, weights) in tile.chunks_mut(m).zip(kernel.chunks(self.half_len())) {
            for (j, c) in column.iter_mut().enumerate() {
                *c *= weights[j.min(m - j)];
            }
        }
        self.inverse
            .process_with_scratch(tile, &mut scratch[..self.inverse.get_inplace_scratch_len()]);
        let n = out.len() / (tile.len() / m);
        for (column, out) in tile.chunks(m).zip(out.chunks_mut(n)) {
            out.copy_from_slice(&column[..n]);
        }
    }

    /// `Σ_j E(j) |C(j)|²` of one forward-transformed column `column` with its kernel `weights`.
    fn energy(&self, column: &[Complex<T>], weights: &[T]) -> f64 {
        let m = self.len;
        column
            .iter()
            .enumerate()
            .map(|(j, &c)| weighted_norm(c, weights[j.min(m - j)]))
            .sum()
    }
}

impl PaddedColumns<f64> {
    /// The padded kernel `E(kx, 0..=m/2)` (layout `[kx][j]`) of the spectral kernel `spectral`
    /// (layout `[kx][ky]`, `n` values per column, normalisation included), whose columns are
    /// inverse-transformed by `column_inverse` (length `n`). The spectral kernel must be even
    /// in `ky` up to round-off; its even part is used.
    pub(super) fn kernel(
        &self,
        spectral: &[f64],
        n: usize,
        column_inverse: &dyn Fft<f64>,
    ) -> Result<Vec<f64>, FftFailure> {
        let spectral = even_part(spectral, n)?;
        let (m, half) = (self.len, self.half_len());
        let columns = spectral.len() / n;
        let mut padded = vec![0.0; columns * half];
        let zero = Complex::new(0.0, 0.0);
        let scratch_len = column_inverse
            .get_inplace_scratch_len()
            .max(self.scratch_len());
        padded
            .par_chunks_mut(half)
            .zip(spectral.par_chunks(n))
            .for_each_init(
                || (vec![zero; n], vec![zero; m], vec![zero; scratch_len]),
                |(column, extended, scratch), (out, weights)| {
                    column
                        .iter_mut()
                        .zip(weights)
                        .for_each(|(c, &w)| *c = Complex::new(w, 0.0));
                    column_inverse.process_with_scratch(column, scratch);
                    extended.fill(zero);
                    extended[..n].copy_from_slice(column);
                    for d in 1..n {
                        extended[m - d] = column[n - d];
                    }
                    self.forward.process_with_scratch(extended, scratch);
                    let norm = 1.0 / m as f64;
                    out.iter_mut()
                        .zip(extended.iter())
                        .for_each(|(o, e)| *o = e.re * norm);
                },
            );
        Ok(padded)
    }
}

/// Relative asymmetry `|K(ky) − K(n − ky)| / max |K|` a spectral kernel may have: the
/// round-off of the FFT that computed it from an even stencil (about 1e-16 per operation).
const EVEN_TOLERANCE: f64 = 1e-9;

/// The even part `(K(ky) + K(n − ky)) / 2` of the spectral kernel `spectral` (columns of `n`
/// values), which must be even in `ky` up to [`EVEN_TOLERANCE`].
fn even_part(spectral: &[f64], n: usize) -> Result<Vec<f64>, FftFailure> {
    let largest = spectral.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let mut even = spectral.to_vec();
    for (kx, (column, out)) in spectral.chunks(n).zip(even.chunks_mut(n)).enumerate() {
        for ky in 1..n {
            let (value, mirror) = (column[ky], column[n - ky]);
            if (value - mirror).abs() > EVEN_TOLERANCE * largest {
                return Err(FftFailure::new(format!(
                    "the convolution kernel is not even in ky (column {kx}: K({ky}) = {value} \
                     but K({}) = {mirror}); a periodic convolution through padded columns needs \
                     an even kernel, as every symmetric stencil has",
                    n - ky
                )));
            }
            out[ky] = 0.5 * (value + mirror);
        }
    }
    Ok(even)
}
