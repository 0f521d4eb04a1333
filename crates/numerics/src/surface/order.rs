//! Heights in descending order through the order-preserving integer image of `f64`.
//!
//! `f64::total_cmp` orders floats as their bit patterns do once negative values have every bit
//! inverted and non-negative ones their sign bit set (IEEE 754-2008 §5.10 `totalOrder`); the
//! inverted image orders them descending. Sorting the integer keys (one integer comparison
//! each, instead of two conversions per comparison) gives exactly the order of
//! `sort_unstable_by(|a, b| b.total_cmp(a))`: distinct bit patterns have distinct keys, so
//! the result is the same bit for bit.

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
