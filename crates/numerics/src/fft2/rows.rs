//! How the rows of a transform's input are supplied and its output rows received.

/// Supplies the rows of a transform's input block: `fill(r, row)` writes all `cols` values of
/// row `r` into `row` and returns `true`, or returns `false` if the row is zero (then `row` is
/// not read). A caller that knows where its input is nonzero fills the rows from that, without
/// reading a dense array.
pub trait RowSource: Fn(usize, &mut [f64]) -> bool + Sync {}

impl<F: Fn(usize, &mut [f64]) -> bool + Sync> RowSource for F {}

/// Receives the output rows of a convolution: `sink(r, values, out)` gets the `cols` values of
/// row `r` of the result, still in cache, and the row `out` of the output block, which it writes
/// as it likes (a copy, an update `out −= τ · values`, …); it returns one number per row (a
/// reduction over the row, say), which the transform hands back. The output block is written
/// only through the sink.
pub trait RowSink: Fn(usize, &[f64], &mut [f64]) -> f64 + Sync {}

impl<F: Fn(usize, &[f64], &mut [f64]) -> f64 + Sync> RowSink for F {}

/// The type of "no sink": the output rows are the result.
pub(super) type Copy = fn(usize, &[f64], &mut [f64]) -> f64;

/// The rows of a dense row-major block with `row.len()` columns; all-zero rows report `false`.
pub(super) fn dense_rows(input: &[f64]) -> impl RowSource + '_ {
    move |r: usize, row: &mut [f64]| {
        let values = &input[r * row.len()..][..row.len()];
        if values.iter().all(|&v| v == 0.0) {
            return false;
        }
        row.copy_from_slice(values);
        true
    }
}
