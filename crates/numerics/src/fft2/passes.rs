//! The passes of [`RealFft2d`]: the forward row transforms into the row buffer, the column
//! pass (plain, or zero-padded for convolutions, `padded.rs`) and the inverse row transforms
//! out of the column buffer.

use rayon::prelude::*;
use realfft::num_complex::Complex;

use super::padded::PaddedPass;
use super::transpose::transpose;
use super::{ChunkBuffers, ColumnPass, FftFailure, RealFft2d, RowSink, RowSource, TILE, TILE_ROWS};

impl RealFft2d {
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
            self.rows = vec![Complex::new(0.0, 0.0); nxc * self.ny];
        }
        let rpc = rows.div_ceil(self.chunks.len()).max(1);
        let r2c = &self.r2c;
        let len = r2c.get_scratch_len();
        self.rows[..rows * nxc]
            .par_chunks_mut(nxc * rpc)
            .zip(self.chunks.par_iter_mut())
            .enumerate()
            .try_for_each(|(chunk, (spectra, buffers))| {
                for (r, spectrum) in spectra.chunks_mut(nxc).enumerate() {
                    let row = &mut buffers.row;
                    if !fill(chunk * rpc + r, &mut row[..cols]) {
                        spectrum.fill(Complex::new(0.0, 0.0));
                        continue;
                    }
                    row[cols..].fill(0.0);
                    r2c.process_with_scratch(row, spectrum, &mut buffers.fft[..len])?;
                }
                Ok::<(), realfft::FftError>(())
            })?;
        Ok(())
    }

    /// Column pass over the column buffer; a forward transform reads the first `rows` row
    /// spectra of the row buffer (the rows below are zero).
    pub(super) fn columns(&mut self, pass: ColumnPass<'_>, rows: usize) {
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
    pub(super) fn spectral_columns(&mut self, pass: ColumnPass<'_>, rows: usize) {
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
                            column[rows..].fill(Complex::new(0.0, 0.0));
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
                                    .map(|(c, &w)| w * c.norm_sqr())
                                    .sum();
                            }
                            continue;
                        }
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
        let rpc = rows.div_ceil(self.chunks.len()).max(1);
        let spectrum = &self.cols;
        let c2r = &self.c2r;
        let len = c2r.get_scratch_len();
        let even = nx % 2 == 0;
        output
            .par_chunks_mut(cols * rpc)
            .zip(self.row_values.par_chunks_mut(rpc))
            .zip(self.chunks.par_iter_mut())
            .enumerate()
            .try_for_each(|(chunk, ((out, values), buffers))| {
                let ChunkBuffers {
                    fft, row, spectra, ..
                } = buffers;
                for (t, (out_tile, tile_values)) in out
                    .chunks_mut(cols * TILE_ROWS)
                    .zip(values.chunks_mut(TILE_ROWS))
                    .enumerate()
                {
                    let tile_row = chunk * rpc + t * TILE_ROWS;
                    let height = out_tile.len() / cols;
                    transpose(spectrum, ny, nxc, tile_row, height, spectra, nxc);
                    for (k, ((spec_row, out_row), value)) in spectra
                        .chunks_mut(nxc)
                        .zip(out_tile.chunks_mut(cols))
                        .zip(tile_values.iter_mut())
                        .enumerate()
                    {
                        // The inverse of a real signal's spectrum: DC and Nyquist are real up to
                        // round-off.
                        spec_row[0].im = 0.0;
                        if even {
                            spec_row[nxc - 1].im = 0.0;
                        }
                        match sink {
                            None if cols == nx => {
                                c2r.process_with_scratch(spec_row, out_row, &mut fft[..len])?;
                            }
                            None => {
                                c2r.process_with_scratch(spec_row, row, &mut fft[..len])?;
                                out_row.copy_from_slice(&row[..cols]);
                            }
                            Some(sink) => {
                                c2r.process_with_scratch(spec_row, row, &mut fft[..len])?;
                                *value = sink(tile_row + k, &row[..cols], out_row);
                            }
                        }
                    }
                }
                Ok::<(), realfft::FftError>(())
            })?;
        Ok(())
    }
}
