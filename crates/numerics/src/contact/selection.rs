//! The k-th smallest of many values, in parallel and without copying them all: the selection
//! behind the rigid-plastic start and the load restoration (`load_balance`).
//!
//! * [`lowest_ranks`], for a small rank (the rigid-plastic start at the loads of interest,
//!   `k/N = p̄/p_lim` of a few per cent at most): a strided sample of the values gives a bound
//!   that a little more than `k + 1` values are expected to stay below; one parallel pass counts
//!   them, a serial one gathers them with their indices into buffers the caller keeps, and the
//!   `k + 1` smallest in the order of `(value, index)` are selected among those few. If the
//!   sample misled (fewer than `k + 1` values below the bound, or far more), it declines and the
//!   caller falls back on [`kth_smallest`].
//! * [`kth_smallest`], for any rank: radix selection on the order-preserving integer keys of the
//!   values (the IEEE 754 total order of `f64::total_cmp`). The leading bits shared by the
//!   smallest and the largest key are those of every key; below them each pass counts, in
//!   parallel, the next [`DIGIT_BITS`] bits of the keys that share the digits fixed so far, and
//!   fixes the digit whose bucket holds the wanted rank. Once that bucket holds at most
//!   [`GATHER`] values they are gathered and the rank is selected among them (up to [`GATHER`]
//!   values in all are copied and selected in directly). Faster than a copy and
//!   `select_nth_unstable` from 2²⁰ values on (timings: `docs/contact-solver-design.md`).
//!
//! Counts are exact integers and the results are values or indices, so neither depends on the
//! thread count.

use rayon::prelude::*;

/// Bits of the key counted per pass (a histogram of 2¹¹ counts, 16 kB, per parallel job).
const DIGIT_BITS: u32 = 11;

/// A bucket this small is gathered and selected in directly.
const GATHER: usize = 1 << 17;

/// Values per parallel job.
const CHUNK: usize = 1 << 14;

/// Values sampled (at a fixed stride) for the bound of [`lowest_ranks`].
const SAMPLE: usize = 1 << 12;

/// [`lowest_ranks`] declines ranks above this share of the values (where the radix selection
/// is as fast).
const LOW_RANK_SHARE: usize = 16;

/// The key of `x` whose unsigned order is the total order of `f64::total_cmp`.
fn key(x: f64) -> u64 {
    let bits = x.to_bits();
    if bits >> 63 == 1 {
        !bits
    } else {
        bits | 1 << 63
    }
}

/// The value of a key (the inverse of [`key`]).
fn value(key: u64) -> f64 {
    if key >> 63 == 1 {
        f64::from_bits(key & !(1 << 63))
    } else {
        f64::from_bits(!key)
    }
}

/// The buffers of [`lowest_ranks`], kept by the caller: no allocation once they reached their
/// size (the load restoration ranks inside the iteration).
#[derive(Debug, Clone, Default)]
pub(super) struct RankBuffers {
    sample: Vec<f64>,
    candidates: Vec<(f64, usize)>,
}

/// The `k + 1` smallest of `values` in the order of `(value, index)` (values by
/// `f64::total_cmp`, ties by index), as `(value, index)`: the last is the `k`-th (0-based), the
/// others the `k` before it, in no particular order. `None` when `k + 1` exceeds
/// `1/`[`LOW_RANK_SHARE`] of the values or the sampled bound misled (see the module docs); use
/// [`kth_smallest`] then. The values below the bound are counted in parallel and gathered
/// serially into `buffers` (a few times `k` of them).
pub(super) fn lowest_ranks<'a>(
    values: &[f64],
    k: usize,
    buffers: &'a mut RankBuffers,
) -> Option<&'a [(f64, usize)]> {
    let n = values.len();
    let wanted = k + 1;
    if wanted > n / LOW_RANK_SHARE {
        return None;
    }
    // The sample rank with 1.5× and three standard deviations of margin (binomial count of the
    // sample below the k-th value), so that the bound rarely falls short of it.
    let m = SAMPLE.min(n);
    let expected = wanted as f64 / n as f64 * m as f64;
    let rank = (1.5 * expected + 3.0 * expected.sqrt() + 8.0).ceil() as usize;
    if rank >= m {
        return None;
    }
    let RankBuffers { sample, candidates } = buffers;
    sample.clear();
    sample.extend((0..m).map(|j| values[j * n / m]));
    let (_, &mut bound, _) = sample.select_nth_unstable_by(rank, f64::total_cmp);
    let below = |x: &f64| x.total_cmp(&bound).is_le();
    let count: usize = values
        .par_chunks(CHUNK)
        .map(|chunk| chunk.iter().filter(|x| below(x)).count())
        .sum();
    // Far more than expected: the sample missed a cluster of small values (or many are tied),
    // and gathering them would copy a large share of the grid.
    if count < wanted || count > 4 * wanted + SAMPLE {
        return None;
    }
    candidates.clear();
    candidates.extend(
        (values.iter().enumerate())
            .filter(|(_, x)| below(x))
            .map(|(i, &x)| (x, i)),
    );
    candidates.select_nth_unstable_by(k, |a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    Some(&candidates[..wanted])
}

/// The `k`-th smallest (0-based) of `values` in the order of `f64::total_cmp`; `None` if
/// `k ≥ values.len()`.
pub(super) fn kth_smallest(values: &[f64], k: usize) -> Option<f64> {
    if k >= values.len() {
        return None;
    }
    if values.len() <= GATHER {
        let mut copy = values.to_vec();
        let (_, &mut kth, _) = copy.select_nth_unstable_by(k, f64::total_cmp);
        return Some(kth);
    }
    // The keys in the wanted bucket share their top `fixed` bits with `prefix`; `rank` counts
    // within the bucket.
    // The leading bits that the smallest and the largest key share are those of every key:
    // the passes start below them (gaps of one sign and a few binades share a dozen).
    let (lowest, highest) = values
        .par_chunks(CHUNK)
        .map(|chunk| {
            chunk.iter().fold((u64::MAX, 0), |(lo, hi), &x| {
                let k = key(x);
                (lo.min(k), hi.max(k))
            })
        })
        .reduce(|| (u64::MAX, 0), |a, b| (a.0.min(b.0), a.1.max(b.1)));
    let mut fixed = (lowest ^ highest).leading_zeros();
    let mut prefix = if fixed == 0 {
        0
    } else {
        lowest >> (64 - fixed)
    };
    let (mut rank, mut in_bucket) = (k, values.len());
    let in_prefix =
        |prefix: u64, fixed: u32, x: f64| fixed == 0 || key(x) >> (64 - fixed) == prefix;
    while fixed < 64 && in_bucket > GATHER {
        // The last digit is narrower when 64 is not a multiple of DIGIT_BITS.
        let bits = DIGIT_BITS.min(64 - fixed);
        let shift = 64 - fixed - bits;
        let counts = values
            .par_chunks(CHUNK)
            .fold(
                || vec![0usize; 1 << DIGIT_BITS],
                |mut counts, chunk| {
                    for &x in chunk.iter().filter(|&&x| in_prefix(prefix, fixed, x)) {
                        counts[(key(x) >> shift) as usize & ((1 << bits) - 1)] += 1;
                    }
                    counts
                },
            )
            .reduce_with(|mut a, b| {
                a.iter_mut().zip(&b).for_each(|(a, b)| *a += b);
                a
            })
            .unwrap_or_default();
        let mut below = 0;
        for (digit, &count) in counts.iter().enumerate() {
            if rank < below + count {
                prefix = prefix << bits | digit as u64;
                rank -= below;
                in_bucket = count;
                break;
            }
            below += count;
        }
        fixed += bits;
    }
    if fixed == 64 {
        // Every value of the bucket has the key `prefix`.
        return Some(value(prefix));
    }
    let parts: Vec<Vec<f64>> = values
        .par_chunks(CHUNK)
        .map(|chunk| {
            (chunk.iter().copied())
                .filter(|&x| in_prefix(prefix, fixed, x))
                .collect()
        })
        .collect();
    let mut bucket = parts.concat();
    let (_, &mut kth, _) = bucket.select_nth_unstable_by(rank, f64::total_cmp);
    Some(kth)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn by_sorting(values: &[f64], k: usize) -> f64 {
        let mut sorted = values.to_vec();
        sorted.sort_by(f64::total_cmp);
        sorted[k]
    }

    #[test]
    fn keys_keep_the_total_order() {
        let values = [
            f64::NEG_INFINITY,
            -1e300,
            -1.0,
            -1e-300,
            -0.0,
            0.0,
            1e-300,
            1.0,
            1e300,
        ];
        for pair in values.windows(2) {
            assert!(key(pair[0]) < key(pair[1]), "{pair:?}");
        }
        for x in values {
            assert_eq!(value(key(x)).to_bits(), x.to_bits());
        }
    }

    /// `n` values spread over many binades, of both signs.
    fn spread(n: usize) -> Vec<f64> {
        (0..n)
            .map(|i| ((i * 7919 % 1013) as f64 - 500.0) * 10f64.powi((i % 37) as i32 - 18))
            .collect()
    }

    #[test]
    fn selects_every_rank_of_spread_clustered_and_tied_values() {
        // More values than GATHER so that the radix passes run: spread over many binades,
        // clustered in one binade (the first pass cannot split them), and heavily tied.
        let n = 3 * GATHER + 17;
        let spread = spread(n);
        let clustered: Vec<f64> = (0..n)
            .map(|i| 1.0 + (i * 7919 % n) as f64 * 1e-12)
            .collect();
        let tied: Vec<f64> = (0..n).map(|i| (i % 2) as f64).collect();
        for values in [&spread, &clustered, &tied] {
            for k in [0, 1, n / 3, n / 2, n - 2, n - 1] {
                assert_eq!(
                    kth_smallest(values, k),
                    Some(by_sorting(values, k)),
                    "k = {k}"
                );
            }
        }
    }

    /// `lowest_ranks` as a set with its last index, against a stable sort of `(value, index)`.
    fn check_lowest_ranks(values: &[f64], k: usize) -> bool {
        let mut buffers = RankBuffers::default();
        let Some(lowest) = lowest_ranks(values, k, &mut buffers) else {
            return false;
        };
        let mut got: Vec<usize> = lowest.iter().map(|&(_, i)| i).collect();
        let mut order: Vec<usize> = (0..values.len()).collect();
        order.sort_by(|&a, &b| values[a].total_cmp(&values[b]).then(a.cmp(&b)));
        assert_eq!(got.last(), Some(&order[k]), "k = {k}");
        got.sort_unstable();
        let mut expected = order[..=k].to_vec();
        expected.sort_unstable();
        assert_eq!(got, expected, "k = {k}");
        true
    }

    #[test]
    fn lowest_ranks_select_the_smallest_in_index_order_of_ties() {
        let n = 5 * SAMPLE + 3;
        let spread = spread(n);
        // Few distinct values: the k-th is tied with many, which must be cut in index order.
        let tied: Vec<f64> = (0..n).map(|i| (i * 7919 % 97) as f64).collect();
        for values in [&spread, &tied] {
            for k in [0, 1, 50, n / 100, n / LOW_RANK_SHARE - 1] {
                assert!(check_lowest_ranks(values, k), "declined k = {k}");
            }
        }
        // Small inputs are sampled whole.
        assert!(check_lowest_ranks(&[3.0, 1.0, 2.0, 1.0].repeat(8), 1));
    }

    #[test]
    fn lowest_ranks_declines_when_the_sample_misleads_or_the_rank_is_large() {
        let n = 64 * SAMPLE;
        // The smallest values sit between the sampled points (stride 64): the bound is above
        // all of them and tied with every other value, so far too many fall below it.
        let between: Vec<f64> = (0..n)
            .map(|i| if i % 64 == 1 { -1.0 } else { 0.0 })
            .collect();
        assert_eq!(
            lowest_ranks(&between, 10, &mut RankBuffers::default()),
            None
        );
        // A constant grid: every value is tied with the bound.
        assert_eq!(
            lowest_ranks(&vec![2.5; n], 10, &mut RankBuffers::default()),
            None
        );
        // Large ranks go to the radix selection.
        let ramp: Vec<f64> = (0..n).map(|i| i as f64).collect();
        assert_eq!(
            lowest_ranks(&ramp, n / 2, &mut RankBuffers::default()),
            None
        );
        assert!(check_lowest_ranks(&ramp, n / LOW_RANK_SHARE - 1));
    }

    #[test]
    fn small_inputs_and_ranks_out_of_range() {
        assert_eq!(kth_smallest(&[3.0, 1.0, 2.0], 1), Some(2.0));
        assert_eq!(kth_smallest(&[3.0, 1.0, 2.0], 3), None);
        assert_eq!(kth_smallest(&[], 0), None);
    }
}
