//! What a reader may allocate, decided from the header before the data is decoded.
//!
//! Two bounds hold for every reader. A raw format's header must not declare more points than its
//! file holds (`points × bytes per point ≤ bytes left`, checked by each reader before it
//! allocates, and reported as a truncated file). And no header may declare more than
//! [`MAX_POINTS`] (checked before decoding): a compressed container (X3P deflate, ZON zstd) can
//! legitimately hold a thousand times its size, so a 2 MB X3P of zeros declaring 16384² float64
//! points is refused before 2 GiB are inflated, with an error naming the count; a raw file of
//! one-byte samples would otherwise take 8 times its size as `f64`.
//!
//! The limit is a fixed number rather than a parameter tied to `--memory-mib`: a reader runs in
//! `inspect`, in plan-time tools and in node computations alike, and the same file must be read,
//! or refused, the same way everywhere (a table must not depend on the budget of the run that
//! filled the cache). The scheduler's budget then serialises the large maps this limit admits.

use super::ParseError;

/// Most points a reader decodes: 2²⁷ ≈ 134 million, 1 GiB of `f64` heights (11 585² points).
/// The largest single-field instrument maps (8192², 2²⁶) fit with a factor of two to spare; a
/// larger map also cannot go through the contact solver, whose padded FFT grids need about 64
/// bytes per point.
pub const MAX_POINTS: usize = 1 << 27;

/// `nx · ny` when it is at most [`MAX_POINTS`]; `what` names the format and its header fields.
pub(crate) fn check_points(nx: usize, ny: usize, what: &str) -> Result<usize, ParseError> {
    nx.checked_mul(ny)
        .filter(|&n| n <= MAX_POINTS)
        .ok_or_else(|| too_many(&format!("{nx} × {ny}"), what))
}

/// `count` when it is at most [`MAX_POINTS`].
pub(crate) fn check_count(count: usize, what: &str) -> Result<usize, ParseError> {
    if count <= MAX_POINTS {
        Ok(count)
    } else {
        Err(too_many(&count.to_string(), what))
    }
}

fn too_many(points: &str, what: &str) -> ParseError {
    ParseError::malformed(format!(
        "{what} declares {points} points, more than the {MAX_POINTS} points a topography may \
         hold (1 GiB of heights); a damaged header, or a map to crop before reading"
    ))
}
