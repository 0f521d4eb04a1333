//! The passes of [`RealFft2d`]: the forward row transforms into the row buffer, the column
//! pass (plain, or zero-padded for convolutions, `padded.rs`) and the inverse row transforms
//! out of the column buffer.

use rayon::prelude::*;
use realfft::num_complex::Complex;

use realfft::{ComplexToReal, RealToComplex};
use rustfft::Fft;

use super::padded::PaddedPass;
use super::real::weighted_norm;
use super::rows_pass::{forward_pair, inverse_pair, RowPlan};
use super::transpose::transpose;
use super::{
    ChunkBuffers, ColumnPass, FftFailure, Real, RealFft2d, RowSink, RowSource, TILE, TILE_ROWS,
};

/// `true` when every value of `values` is zero.
fn is_zero<T: Real>(values: &[Complex<T>]) -> bool {
    values
        .iter()
        .all(|c| c.re == T::zero() && c.im == T::zero())
}

impl<T: Real> RealFft2d<T> {
    /// Rows per parallel work chunk for a block of `rows` rows: a multiple of the rows
    /// transformed together, so that every row is paired with the same row whatever the
    /// chunking.
    fn rows_per_chunk(&self, rows: usize) -> usize {
        let step = self.rows_plan.rows_per_transform();
        rows.div_ceil(self.chunks.len()).max(1).div_ceil(step) * step
    }

    /// Row spectra of a `rows × cols` block (`cols, rows ≥ 1`), zero-padded to `nx`, into the
    /// first `rows` rows of the row buffer; `fill` supplies the rows (see [`RowSource`]).
    pub(super) fn rows_forward<F: RowSource>(
        &mut self,
        fill: &F,
        cols: usize,
        rows: usize,
    ) -> Result<(), FftFailure> {
        let nxc = self.nxc;
        if self.rows.is_empty() {
            self.rows = vec![Complex::new(T::zero(), T::zero()); nxc * self.ny];
        }
        let rpc = self.rows_per_chunk(rows);
        let plan = &self.rows_plan;
        self.rows[..rows * nxc]
            .par_chunks_mut(nxc * rpc)
            .zip(self.chunks.par_iter_mut())
            .enumerate()
            .try_for_each(|(chunk, (spectra, buffers))| {
                let first = chunk * rpc;
                match plan {
                    RowPlan::Separate { r2c, .. } => {
                        separate_forward(r2c.as_ref(), fill, first, cols, spectra, buffers)
                    }
                    RowPlan::Packed { forward, .. } => {
                        packed_forward(forward.as_ref(), fill, first, cols, spectra, buffers);
                        Ok(())
                    }
                }
            })?;
        Ok(())
    }

    /// Column pass over the column buffer; a forward transform reads the first `rows` row
    /// spectra of the row buffer (the rows below are zero).
    pub(super) fn columns(&mut self, pass: ColumnPass<'_, T>, rows: usize) {
        self.column_buffer();
        let (kernel, energy_only) = match pass {
            ColumnPass::Kernel(kernel) => (kernel, false),
            ColumnPass::Energy(kernel) => (kernel, true),
            _ => return self.spectral_columns(pass, rows),
        };
        let Some(padded) = &self.padded else {
            return self.spectral_columns(pass, rows);
        };
        let job = PaddedPass {
            spectra: &self.rows,
            nxc: self.nxc,
            ny: self.ny,
            rows,
            cols_per_chunk: self.cols_per_chunk,
            kernel,
            energy_only,
        };
        padded.run(
            job,
            &mut self.cols,
            &mut self.column_energy,
            &mut self.chunks,
        );
    }

    /// [`RealFft2d::columns`] through the column DFTs of length `ny`.
    pub(super) fn spectral_columns(&mut self, pass: ColumnPass<'_, T>, rows: usize) {
        let (ny, nxc, cpc) = (self.ny, self.nxc, self.cols_per_chunk);
        let spectra = &self.rows;
        let (fwd, inv) = (&self.col_forward, &self.col_inverse);
        self.cols
            .par_chunks_mut(ny * cpc)
            .zip(self.column_energy.par_chunks_mut(cpc))
            .zip(self.chunks.par_iter_mut())
            .enumerate()
            .for_each(|(chunk, ((cols, energy), buffers))| {
                let first_col = chunk * cpc;
                let ChunkBuffers {
                    fft: scratch,
                    tile: own_tile,
                    ..
                } = buffers;
                let fwd_len = fwd.get_inplace_scratch_len();
                let inv_len = inv.get_inplace_scratch_len();
                for (t, column_tile) in cols.chunks_mut(ny * TILE).enumerate() {
                    let tile_col = first_col + t * TILE;
                    let width = column_tile.len() / ny;
                    let tile = match pass {
                        ColumnPass::Energy(_) => &mut own_tile[..width * ny],
                        _ => column_tile,
                    };
                    if !matches!(pass, ColumnPass::Inverse) {
                        transpose(spectra, nxc, rows, tile_col, width, tile, ny);
                        for column in tile.chunks_mut(ny) {
                            column[rows..].fill(Complex::new(T::zero(), T::zero()));
                        }
                        fwd.process_with_scratch(tile, &mut scratch[..fwd_len]);
                    }
                    match pass {
                        ColumnPass::Forward => continue,
                        ColumnPass::Energy(kernel) => {
                            let weights = &kernel[tile_col * ny..][..width * ny];
                            let energies = &mut energy[t * TILE..][..width];
                            for ((e, column), weights) in energies
                                .iter_mut()
                                .zip(tile.chunks(ny))
                                .zip(weights.chunks(ny))
                            {
                                *e = column
                                    .iter()
                                    .zip(weights)
                                    .map(|(&c, &w)| weighted_norm(c, w))
                                    .sum();
                            }
                            continue;
                        }
                        ColumnPass::Scale(factor) => {
                            let factor = T::of(factor);
                            tile.iter_mut().for_each(|c| *c *= factor);
                        }
                        ColumnPass::Kernel(kernel) => {
                            let weights = &kernel[tile_col * ny..][..width * ny];
                            tile.iter_mut().zip(weights).for_each(|(c, &w)| *c *= w);
                        }
                        // The inverse of an all-zero tile (a spectrum cut off above some
                        // kx) is zero: nothing to transform.
                        ColumnPass::Inverse if is_zero(tile) => continue,
                        ColumnPass::Inverse => {}
                    }
                    inv.process_with_scratch(tile, &mut scratch[..inv_len]);
                }
            });
    }

    /// Inverse row transforms of the first `rows` rows (`cols, rows ≥ 1`) of the spectrum in the
    /// column buffer; the first `cols` values of each are written to `output` (`rows × cols`),
    /// or handed to `sink` with the output row (its values go to `row_values`).
    pub(super) fn rows_inverse<S: RowSink>(
        &mut self,
        output: &mut [f64],
        cols: usize,
        rows: usize,
        sink: Option<&S>,
    ) -> Result<(), FftFailure> {
        let (nx, ny, nxc) = (self.nx, self.ny, self.nxc);
        let rpc = self.rows_per_chunk(rows);
        let spectrum = &self.cols;
        let plan = &self.rows_plan;
        let even = nx % 2 == 0;
        output
            .par_chunks_mut(cols * rpc)
            .zip(self.row_values.par_chunks_mut(rpc))
            .zip(self.chunks.par_iter_mut())
            .enumerate()
            .try_for_each(|(chunk, ((out, values), buffers))| {
                for (t, (out_tile, tile_values)) in out
                    .chunks_mut(cols * TILE_ROWS)
                    .zip(values.chunks_mut(TILE_ROWS))
                    .enumerate()
                {
                    let tile = OutputTile {
                        first_row: chunk * rpc + t * TILE_ROWS,
                        out: out_tile,
                        values: tile_values,
                        cols,
                    };
                    let spectra = &mut buffers.spectra;
                    transpose(
                        spectrum,
                        ny,
                        nxc,
                        tile.first_row,
                        tile.height(),
                        spectra,
                        nxc,
                    );
                    for spec_row in spectra.chunks_mut(nxc).take(tile.height()) {
                        // The inverse of a real signal's spectrum: DC and Nyquist are real up to
                        // round-off.
                        spec_row[0].im = T::zero();
                        if even {
                            spec_row[nxc - 1].im = T::zero();
                        }
                    }
                    match plan {
                        RowPlan::Separate { c2r, .. } => {
                            separate_inverse(c2r.as_ref(), tile, nx, sink, buffers)?;
                        }
                        RowPlan::Packed { inverse, .. } => {
                            packed_inverse(inverse.as_ref(), tile, nx, nxc, sink, buffers);
                        }
                    }
                }
                Ok::<(), realfft::FftError>(())
            })?;
        Ok(())
    }
}

/// The rows of one tile of an inverse transform's output.
struct OutputTile<'a> {
    /// The block row of the tile's first row.
    first_row: usize,
    /// The tile's output rows, `cols` values each.
    out: &'a mut [f64],
    /// The sink's value of each row.
    values: &'a mut [f64],
    cols: usize,
}

impl OutputTile<'_> {
    fn height(&self) -> usize {
        self.out.len() / self.cols
    }

    /// Row `k` of the tile is `row` (its first `cols` values): copied to the output, or handed
    /// to `sink`.
    fn emit<S: RowSink>(&mut self, k: usize, row: &[f64], sink: Option<&S>) {
        let cols = self.cols;
        let out_row = &mut self.out[k * cols..][..cols];
        match sink {
            None => out_row.copy_from_slice(&row[..cols]),
            Some(sink) => self.values[k] = sink(self.first_row + k, &row[..cols], out_row),
        }
    }
}

/// The row spectra of the block rows `first..` (one per `nxc` values of `spectra`), each row by
/// `realfft` ([`RowPlan::Separate`]).
fn separate_forward<T: Real, F: RowSource>(
    r2c: &dyn RealToComplex<T>,
    fill: &F,
    first: usize,
    cols: usize,
    spectra: &mut [Complex<T>],
    buffers: &mut ChunkBuffers<T>,
) -> Result<(), realfft::FftError> {
    let nxc = r2c.complex_len();
    let scratch = &mut buffers.fft[..r2c.get_scratch_len()];
    for (r, spectrum) in spectra.chunks_mut(nxc).enumerate() {
        let row = &mut buffers.row;
        if !T::fill_row(fill, first + r, &mut row[..cols], &mut buffers.io[..cols]) {
            spectrum.fill(Complex::new(T::zero(), T::zero()));
            continue;
        }
        row[cols..].fill(T::zero());
        r2c.process_with_scratch(row, spectrum, scratch)?;
    }
    Ok(())
}

/// [`separate_forward`] by pairs of rows ([`RowPlan::Packed`]; `first` even). A pair of zero
/// rows is not transformed; the partner of a last odd row is zero, its spectrum not kept.
fn packed_forward<T: Real, F: RowSource>(
    fft: &dyn Fft<T>,
    fill: &F,
    first: usize,
    cols: usize,
    spectra: &mut [Complex<T>],
    buffers: &mut ChunkBuffers<T>,
) {
    let nx = buffers.pair.len();
    let nxc = nx / 2 + 1;
    let ChunkBuffers {
        fft: scratch,
        io,
        pair,
        spectra: spare,
        ..
    } = buffers;
    let scratch = &mut scratch[..fft.get_inplace_scratch_len()];
    let (io_a, io_b) = io.split_at_mut(nx);
    for (j, two) in spectra.chunks_mut(2 * nxc).enumerate() {
        let r = first + 2 * j;
        let (sa, rest) = two.split_at_mut(nxc);
        let has_b = !rest.is_empty();
        let sb = if has_b { rest } else { &mut spare[..nxc] };
        let a = fill(r, &mut io_a[..cols]);
        let b = has_b && fill(r + 1, &mut io_b[..cols]);
        if !a && !b {
            sa.fill(Complex::new(T::zero(), T::zero()));
            sb.fill(Complex::new(T::zero(), T::zero()));
            continue;
        }
        if !a {
            io_a[..cols].fill(0.0);
        }
        if !b {
            io_b[..cols].fill(0.0);
        }
        forward_pair(fft, (&io_a[..cols], &io_b[..cols]), (sa, sb), pair, scratch);
    }
}

/// The inverse row transforms of one output tile, each row by `realfft` ([`RowPlan::Separate`]);
/// the row spectra are in the chunk's `spectra` buffer.
fn separate_inverse<T: Real, S: RowSink>(
    c2r: &dyn ComplexToReal<T>,
    mut tile: OutputTile<'_>,
    nx: usize,
    sink: Option<&S>,
    buffers: &mut ChunkBuffers<T>,
) -> Result<(), realfft::FftError> {
    let nxc = c2r.complex_len();
    let ChunkBuffers {
        fft,
        row,
        io,
        spectra,
        ..
    } = buffers;
    let scratch = &mut fft[..c2r.get_scratch_len()];
    let io = &mut io[..nx];
    let cols = tile.cols;
    for (k, spec_row) in spectra.chunks_mut(nxc).take(tile.height()).enumerate() {
        if sink.is_none() && cols == nx {
            let out_row = &mut tile.out[k * cols..][..cols];
            T::inverse_row(c2r, spec_row, out_row, row, scratch)?;
        } else {
            T::inverse_row(c2r, spec_row, io, row, scratch)?;
            tile.emit(k, io, sink);
        }
    }
    Ok(())
}

/// [`separate_inverse`] by pairs of rows ([`RowPlan::Packed`]; the tile starts at an even row;
/// the partner of a last odd row is zero).
fn packed_inverse<T: Real, S: RowSink>(
    fft: &dyn Fft<T>,
    mut tile: OutputTile<'_>,
    nx: usize,
    nxc: usize,
    sink: Option<&S>,
    buffers: &mut ChunkBuffers<T>,
) {
    let height = tile.height();
    let ChunkBuffers {
        fft: scratch,
        io,
        pair,
        spectra,
        ..
    } = buffers;
    let scratch = &mut scratch[..fft.get_inplace_scratch_len()];
    if height % 2 == 1 {
        spectra[height * nxc..][..nxc].fill(Complex::new(T::zero(), T::zero()));
    }
    let (io_a, io_b) = io.split_at_mut(nx);
    for (j, two) in spectra.chunks(2 * nxc).take(height.div_ceil(2)).enumerate() {
        let (sa, sb) = two.split_at(nxc);
        inverse_pair(fft, (sa, sb), (&mut *io_a, &mut *io_b), pair, scratch);
        tile.emit(2 * j, io_a, sink);
        if 2 * j + 1 < height {
            tile.emit(2 * j + 1, io_b, sink);
        }
    }
}
