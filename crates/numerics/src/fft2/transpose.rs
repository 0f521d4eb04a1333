//! Transposition of tiles between the row and column layouts of [`super::RealFft2d`].

use rayon::prelude::*;

use super::TILE;

/// Rows of the source moved together: a whole 64-byte cache line of each destination row in
/// single precision (8 complex values), two in double precision.
const BLOCK_ROWS: usize = 8;

/// `dst[k · dst_stride + i] = src[i · src_stride + first_col + k]` for `i < rows`, `k < width`:
/// the columns `first_col..first_col + width` of the first `rows` rows of the row-major `src`
/// become rows of `dst`. Rows are taken [`BLOCK_ROWS`] at a time so that each destination cache
/// line is written whole (with power-of-two strides the `width` destination lines share a cache
/// set); a full block of `TILE` columns goes through a fixed-size array, which the compiler
/// unrolls without index checks.
pub(super) fn transpose<C: Copy + Default>(
    src: &[C],
    src_stride: usize,
    rows: usize,
    first_col: usize,
    width: usize,
    dst: &mut [C],
    dst_stride: usize,
) {
    let full = if width == TILE {
        rows - rows % BLOCK_ROWS
    } else {
        0
    };
    for first_row in (0..full).step_by(BLOCK_ROWS) {
        let mut block = [[C::default(); TILE]; BLOCK_ROWS];
        for (i, row) in block.iter_mut().enumerate() {
            row.copy_from_slice(&src[(first_row + i) * src_stride + first_col..][..TILE]);
        }
        for k in 0..TILE {
            let line = &mut dst[k * dst_stride + first_row..][..BLOCK_ROWS];
            for (value, row) in line.iter_mut().zip(&block) {
                *value = row[k];
            }
        }
    }
    for first_row in (full..rows).step_by(BLOCK_ROWS) {
        let height = BLOCK_ROWS.min(rows - first_row);
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
pub(super) fn transpose_all<C: Copy + Default + Send + Sync>(
    src: &[C],
    rows: usize,
    cols: usize,
    dst: &mut [C],
) {
    dst.par_chunks_mut(rows * TILE)
        .enumerate()
        .for_each(|(t, tile)| transpose(src, cols, rows, t * TILE, tile.len() / rows, tile, rows));
}
