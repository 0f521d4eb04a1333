//! Heights in descending order through the order-preserving integer image of `f64`, and the
//! mean-removed heights of a map in that order by a bucket sort.
//!
//! `f64::total_cmp` orders floats as their bit patterns do once negative values have every bit
//! inverted and non-negative ones their sign bit set (IEEE 754-2008 §5.10 `totalOrder`); the
//! inverted image orders them descending. Sorting the integer keys (one integer comparison
//! each, instead of two conversions per comparison) gives exactly the order of
//! `sort_unstable_by(|a, b| b.total_cmp(a))`: distinct bit patterns have distinct keys, so
//! the result is the same bit for bit.

use rayon::prelude::*;

/// Buckets of the first pass of [`deviations_descending`]: few enough that the lines being
/// written to stay in the L1 cache while the heights are scattered.
const FIRST_BUCKETS: usize = 256;

/// Points per parallel chunk of the first pass's histogram.
const HISTOGRAM_CHUNK: usize = 1 << 16;

/// Points per bucket of the second pass, within one first-pass bucket (in the L2 cache).
const SECOND_BUCKET_POINTS: usize = 32;

/// The non-`NaN` `values` less their mean `m = (Σ v)/N` (summed in order, as `Iterator::sum`),
/// in descending `total_cmp` order: the same bits as collecting `v − m` and calling
/// [`sort_descending`].
///
/// Bucket sort by value: `d` goes to bucket `⌊(d_max − d)·B/(d_max − d_min)⌋` (at most
/// `B − 1`). Subtraction, multiplication by a positive factor and truncation are monotone under
/// rounding, so a larger `d` never lands in a later bucket, and the buckets in order, each
/// sorted on its own, are the sorted sequence. The heights are scattered into
/// [`FIRST_BUCKETS`] buckets, chunk by chunk in parallel (each chunk of [`HISTOGRAM_CHUNK`]
/// values into its own slots of each bucket, [`scatter_into_buckets`]); each bucket is then
/// sorted in cache, in parallel, by the same rule with buckets of about
/// [`SECOND_BUCKET_POINTS`] points ([`sort_bucket`]). A sorted bucket depends only on the values
/// it holds, not on the order they arrived in, so the result is unique and does not depend on
/// the thread count. The in-order sum of the mean runs beside the parallel count, minimum and
/// maximum. Small inputs, equal values and ranges that overflow take the plain sort.
pub(crate) fn deviations_descending(values: &[f64]) -> Vec<f64> {
    let valid = || values.iter().copied().filter(|v| !v.is_nan());
    let (sum, (count, min, max)) = rayon::join(
        || valid().sum::<f64>(),
        || {
            values
                .par_iter()
                .filter(|v| !v.is_nan())
                .fold(
                    || (0usize, f64::INFINITY, f64::NEG_INFINITY),
                    |(n, lo, hi), &v| (n + 1, lo.min(v), hi.max(v)),
                )
                .reduce(
                    || (0, f64::INFINITY, f64::NEG_INFINITY),
                    |a, b| (a.0 + b.0, a.1.min(b.1), a.2.max(b.2)),
                )
        },
    );
    if count == 0 {
        return Vec::new();
    }
    let mean = sum / count as f64;
    let Some(bucket) = Buckets::spanning(max - mean, min - mean, FIRST_BUCKETS, count) else {
        let mut z: Vec<f64> = valid().map(|v| v - mean).collect();
        sort_descending(&mut z);
        return z;
    };
    let mut sorted = vec![0.0; count];
    let sizes = scatter_into_buckets(values, mean, &bucket, &mut sorted);
    split(&mut sorted, &sizes)
        .into_par_iter()
        .for_each_init(Scratch::default, |scratch, part| sort_bucket(part, scratch));
    sorted
}

/// Writes the deviations `v − mean` of the non-`NaN` `values` into `sorted` (as many values),
/// bucket after bucket (each bucket's values in an order of no consequence), and returns the
/// size of each bucket. Each chunk of [`HISTOGRAM_CHUNK`] values counts its values per bucket;
/// bucket `b` of `sorted` is then cut into one part per chunk, of that chunk's count, and every
/// chunk writes its values into its own parts, all chunks in parallel.
fn scatter_into_buckets(
    values: &[f64],
    mean: f64,
    bucket: &Buckets,
    sorted: &mut [f64],
) -> Vec<usize> {
    let histograms: Vec<Vec<usize>> = values
        .par_chunks(HISTOGRAM_CHUNK)
        .map(|chunk| {
            let mut sizes = vec![0usize; bucket.count];
            for &v in chunk.iter().filter(|v| !v.is_nan()) {
                sizes[bucket.of(v - mean)] += 1;
            }
            sizes
        })
        .collect();
    let mut sizes = vec![0usize; bucket.count];
    for histogram in &histograms {
        sizes.iter_mut().zip(histogram).for_each(|(s, h)| *s += h);
    }
    let mut parts: Vec<Vec<&mut [f64]>> = histograms
        .iter()
        .map(|_| Vec::with_capacity(bucket.count))
        .collect();
    for (b, mut rest) in split(sorted, &sizes).into_iter().enumerate() {
        for (chunk_parts, histogram) in parts.iter_mut().zip(&histograms) {
            let (part, tail) = std::mem::take(&mut rest).split_at_mut(histogram[b]);
            chunk_parts.push(part);
            rest = tail;
        }
    }
    values
        .par_chunks(HISTOGRAM_CHUNK)
        .zip(parts)
        .for_each(|(chunk, mut parts)| {
            let mut next = vec![0usize; bucket.count];
            for &v in chunk.iter().filter(|v| !v.is_nan()) {
                let d = v - mean;
                let b = bucket.of(d);
                parts[b][next[b]] = d;
                next[b] += 1;
            }
        });
    sizes
}

/// Working memory of [`sort_bucket`], kept by each parallel task.
#[derive(Default)]
struct Scratch {
    values: Vec<f64>,
    keys: Vec<u64>,
}

/// Sorts `part` in descending `total_cmp` order (as [`sort_descending`]): its values scattered
/// into buckets of about [`SECOND_BUCKET_POINTS`] by value, each sorted by its keys.
fn sort_bucket(part: &mut [f64], scratch: &mut Scratch) {
    let (lo, hi) = part
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    let buckets = part.len() / SECOND_BUCKET_POINTS;
    let Some(bucket) = Buckets::spanning(hi, lo, buckets, part.len()) else {
        return sort_through(&mut scratch.keys, part);
    };
    let mut sizes = vec![0usize; bucket.count];
    for &d in part.iter() {
        sizes[bucket.of(d)] += 1;
    }
    let mut next = starts(&sizes);
    scratch.values.clear();
    scratch.values.resize(part.len(), 0.0);
    for &d in part.iter() {
        let slot = &mut next[bucket.of(d)];
        scratch.values[*slot] = d;
        *slot += 1;
    }
    for small in split(&mut scratch.values, &sizes) {
        sort_through(&mut scratch.keys, small);
    }
    part.copy_from_slice(&scratch.values);
}

/// Buckets by value between `top` and `bottom` (see [`deviations_descending`]).
struct Buckets {
    top: f64,
    scale: f64,
    count: usize,
}

impl Buckets {
    /// `count` buckets over `[bottom, top]`, or `None` where buckets do not pay (fewer than
    /// two, or fewer than 64 points) or cannot be formed (all values equal, a range that
    /// overflows).
    fn spanning(top: f64, bottom: f64, count: usize, points: usize) -> Option<Self> {
        let range = top - bottom;
        (count >= 2 && points >= 64 && range.is_finite() && range > 0.0).then(|| Self {
            top,
            scale: count as f64 / range,
            count,
        })
    }

    /// The bucket of `d`: `⌊(top − d)·scale⌋`, at most `count − 1`.
    fn of(&self, d: f64) -> usize {
        (((self.top - d) * self.scale) as usize).min(self.count - 1)
    }
}

/// The first index of each bucket of `sizes` values.
fn starts(sizes: &[usize]) -> Vec<usize> {
    sizes
        .iter()
        .scan(0, |start, &size| {
            let first = *start;
            *start += size;
            Some(first)
        })
        .collect()
}

/// `values` cut into consecutive parts of `sizes` values.
fn split<'a>(mut values: &'a mut [f64], sizes: &[usize]) -> Vec<&'a mut [f64]> {
    let mut parts = Vec::with_capacity(sizes.len());
    for &size in sizes {
        let (part, rest) = values.split_at_mut(size);
        parts.push(part);
        values = rest;
    }
    parts
}

/// Sorts `part` as [`sort_descending`] does, with `keys` as the buffer of its keys.
fn sort_through(keys: &mut Vec<u64>, part: &mut [f64]) {
    keys.clear();
    keys.extend(part.iter().map(|&v| descending_key(v)));
    keys.sort_unstable();
    for (value, &key) in part.iter_mut().zip(keys.iter()) {
        *value = from_descending_key(key);
    }
}

/// The key of `h` in descending `total_cmp` order: `a.total_cmp(&b)` is `Greater` exactly when
/// `descending_key(a) < descending_key(b)`.
pub(crate) fn descending_key(h: f64) -> u64 {
    let bits = h.to_bits();
    let ascending = if bits >> 63 == 1 {
        !bits
    } else {
        bits | 1 << 63
    };
    !ascending
}

/// The float of a [`descending_key`].
fn from_descending_key(key: u64) -> f64 {
    let ascending = !key;
    let bits = if ascending >> 63 == 1 {
        ascending & !(1 << 63)
    } else {
        !ascending
    };
    f64::from_bits(bits)
}

/// Sorts `values` in descending `total_cmp` order (module docs): the same result as
/// `values.sort_unstable_by(|a, b| b.total_cmp(a))`.
pub(crate) fn sort_descending(values: &mut [f64]) {
    let mut keys: Vec<u64> = values.iter().map(|&v| descending_key(v)).collect();
    keys.sort_unstable();
    for (value, &key) in values.iter_mut().zip(&keys) {
        *value = from_descending_key(key);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reference(values: &[f64]) -> Vec<u64> {
        let mut sorted = values.to_vec();
        sorted.sort_unstable_by(|a, b| b.total_cmp(a));
        sorted.iter().map(|v| v.to_bits()).collect()
    }

    fn radix(values: &[f64]) -> Vec<u64> {
        let mut sorted = values.to_vec();
        sort_descending(&mut sorted);
        sorted.iter().map(|v| v.to_bits()).collect()
    }

    /// Signed zeros, infinities, subnormals, NaNs of both signs, duplicates and the extremes
    /// sort bit for bit as `total_cmp` sorts them.
    #[test]
    fn special_values_sort_as_total_cmp() {
        let values = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            -f64::NAN,
            f64::MIN_POSITIVE / 4.0,
            -f64::MIN_POSITIVE / 4.0,
            f64::MAX,
            f64::MIN,
            1.0,
            2.5e-7,
            -2.5e-7,
            2.5e-7,
        ];
        assert_eq!(radix(&values), reference(&values));
        for v in values {
            assert_eq!(
                from_descending_key(descending_key(v)).to_bits(),
                v.to_bits()
            );
        }
    }

    /// The reference of [`deviations_descending`]: collect, subtract the mean, sort.
    fn deviations_reference(values: &[f64]) -> Vec<u64> {
        let valid: Vec<f64> = values.iter().copied().filter(|v| !v.is_nan()).collect();
        let mean = valid.iter().sum::<f64>() / valid.len() as f64;
        let shifted: Vec<f64> = valid.iter().map(|v| v - mean).collect();
        reference(&shifted)
    }

    fn bits(values: &[f64]) -> Vec<u64> {
        values.iter().map(|v| v.to_bits()).collect()
    }

    /// The bucket sort gives the bits of the plain sort: Gaussian-like heights with missing
    /// points, repeats and signed zeros, a spike far above the rest (one crowded bucket), equal
    /// values, too few points for buckets, and a range that overflows.
    #[test]
    fn bucket_sorted_deviations_equal_the_plain_sort() {
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        let mut uniform = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut heights: Vec<f64> = (0..200_000)
            .map(|i| match i % 97 {
                0 => f64::NAN,
                1 => 0.0,
                2 => -0.0,
                3 => 1.5e-6,
                _ => 1e-6 * ((uniform() + uniform() + uniform()) - 1.5),
            })
            .collect();
        assert_eq!(
            bits(&deviations_descending(&heights)),
            deviations_reference(&heights)
        );
        heights[12_345] = 1.0;
        assert_eq!(
            bits(&deviations_descending(&heights)),
            deviations_reference(&heights)
        );
        let equal = vec![2.5e-7; 50_000];
        assert_eq!(
            bits(&deviations_descending(&equal)),
            deviations_reference(&equal)
        );
        let few = [3.0, f64::NAN, -1.0, 2.0];
        assert_eq!(
            bits(&deviations_descending(&few)),
            deviations_reference(&few)
        );
        let mut huge = vec![1.0; 10_000];
        huge[0] = f64::MAX;
        huge[1] = f64::MIN;
        assert_eq!(
            bits(&deviations_descending(&huge)),
            deviations_reference(&huge)
        );
        assert!(deviations_descending(&[f64::NAN]).is_empty());
    }

    /// Many chunks of the parallel scatter, one of them all missing and the last one short,
    /// give the bits of the plain sort.
    #[test]
    fn chunks_scattered_in_parallel_equal_the_plain_sort() {
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let mut heights: Vec<f64> = (0..5 * HISTOGRAM_CHUNK + 123)
            .map(|_| {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 2e-6
            })
            .collect();
        heights[2 * HISTOGRAM_CHUNK..3 * HISTOGRAM_CHUNK].fill(f64::NAN);
        heights[7] = 5e-6;
        assert_eq!(
            bits(&deviations_descending(&heights)),
            deviations_reference(&heights)
        );
    }

    /// Pseudo-random heights over many binades, with repeats, and values one ulp apart sort as
    /// `total_cmp` sorts them.
    #[test]
    fn random_heights_sort_as_total_cmp() {
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let spread: Vec<f64> = (0..50_000)
            .map(|_| {
                let u = next();
                let magnitude = (u >> 11) as f64 / (1u64 << 53) as f64;
                let sign = if u & 1 == 0 { 1.0 } else { -1.0 };
                sign * magnitude * 10f64.powi((u >> 3 & 15) as i32 - 9)
            })
            .collect();
        assert_eq!(radix(&spread), reference(&spread));
        let narrow: Vec<f64> = (0..20_000)
            .map(|_| 1.0 + (next() % 64) as f64 * f64::EPSILON)
            .collect();
        assert_eq!(radix(&narrow), reference(&narrow));
        assert_eq!(radix(&[]), reference(&[]));
        assert_eq!(radix(&[3.0]), reference(&[3.0]));
    }
}
