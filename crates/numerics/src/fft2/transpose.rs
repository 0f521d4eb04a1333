//! Transposition of tiles between the row and column layouts of [`super::RealFft2d`].

use rayon::prelude::*;
use realfft::num_complex::Complex;

use super::TILE;

/// Complex values per 64-byte cache line.
const LINE: usize = 4;

/// `dst[k · dst_stride + i] = src[i · src_stride + first_col + k]` for `i < rows`, `k < width`:
/// the columns `first_col..first_col + width` of the first `rows` rows of the row-major `src`
/// become rows of `dst`. Rows are taken `LINE` at a time so that each destination cache line is
/// written whole (with power-of-two strides the `width` destination lines share a cache set).
pub(super) fn transpose(
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

/// The whole row-major `rows × cols` matrix `src` transposed into `dst` (`cols × rows`), in
/// parallel tiles of `TILE` destination rows.
pub(super) fn transpose_all(
    src: &[Complex<f64>],
    rows: usize,
    cols: usize,
    dst: &mut [Complex<f64>],
) {
    dst.par_chunks_mut(rows * TILE)
        .enumerate()
        .for_each(|(t, tile)| transpose(src, cols, rows, t * TILE, tile.len() / rows, tile, rows));
}
