//! Transform lengths the FFT handles quickly.

/// The smallest even length `≥ min` whose prime factors are all in `{2, 3, 5, 7}`.
///
/// `rustfft` has specialised butterflies for these radices; a length with a large prime factor
/// (3512 = 8 · 439, say) is transformed by Bluestein's algorithm through a longer FFT and costs
/// several times as much. Zero-padding to such a length is free wherever the padding only has to
/// be long enough (a linear convolution of `n` points needs `≥ 2n − 1`). Powers of two are
/// returned unchanged. Even, so that the real transform of a row packs into a half-length
/// complex one.
pub fn fast_even_length(min: usize) -> usize {
    let mut length = min.max(2);
    length += length % 2;
    while !is_7_smooth(length) {
        length += 2;
    }
    length
}

/// The largest radix `rustfft` has a butterfly of its own for.
const LARGEST_BUTTERFLY: usize = 31;

/// Whether `n` has a prime factor above 31: `rustfft` then transforms that factor by Rader's or
/// Bluestein's algorithm, several times slower per point than a 7-smooth length of twice the
/// size (`docs/contact-solver-design.md`).
pub(super) fn has_slow_factor(mut n: usize) -> bool {
    for p in 2..=LARGEST_BUTTERFLY {
        while n.is_multiple_of(p) {
            n /= p;
        }
    }
    n > 1
}

fn is_7_smooth(mut n: usize) -> bool {
    for p in [2, 3, 5, 7] {
        while n.is_multiple_of(p) {
            n /= p;
        }
    }
    n == 1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fast_lengths_are_the_smallest_even_7_smooth_ones() {
        for (min, expected) in [
            (0, 2),
            (1, 2),
            (3, 4),
            (512, 512),
            (1024, 1024),
            (1023, 1024),
            (2 * 439, 882),
            (7024, 7056),
            (3512, 3528),
            (2 * 1250, 2500),
        ] {
            assert_eq!(fast_even_length(min), expected, "min {min}");
        }
        for min in 1..2000 {
            let length = fast_even_length(min);
            assert!(length >= min && length.is_multiple_of(2) && is_7_smooth(length));
            assert!((min..length).all(|l| !l.is_multiple_of(2) || !is_7_smooth(l)));
        }
    }

    #[test]
    fn slow_factors_are_primes_above_31() {
        for n in [37, 74, 3512, 439, 37 * 37, 2 * 41 * 3] {
            assert!(has_slow_factor(n), "{n}");
        }
        for n in [1, 2, 31, 62, 29 * 31, 1024, 7056, 3584, 11 * 13 * 256] {
            assert!(!has_slow_factor(n), "{n}");
        }
    }
}
