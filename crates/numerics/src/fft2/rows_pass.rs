//! The row transforms of [`super::RealFft2d`]: each real row by `realfft`'s real-to-complex
//! transform ([`RowPlan::Separate`]), or two real rows at once as one complex FFT
//! ([`RowPlan::Packed`]).
//!
//! Packed rows ("two real FFTs for the price of one"; e.g. Press et al., *Numerical Recipes*,
//! 3rd ed., §12.3.2): with `z = a + i b` for the real rows `a` and `b` of length `n` and
//! `Z = DFT(z)`,
//! `A(k) = ½ (Z(k) + conj Z(n − k))`, `B(k) = (Z(k) − conj Z(n − k)) / (2i)`
//! for `k ≤ n/2` (indices modulo `n`), and back, `Z(k) = A(k) + i B(k)` with
//! `Z(n − k) = conj A(k) + i conj B(k)`, `a = Re z`, `b = Im z`. Where `realfft` transforms each
//! row as a complex FFT of half the length followed by a pass with a twiddle factor per
//! frequency, the packed pair needs only additions around the one FFT, which `rustfft`
//! vectorises; the separation loops vectorise too. Its round-off differs from `realfft`'s
//! (the two rows share their butterflies), so the precision chooses the plan once
//! ([`super::Real::PACKED_ROWS`]) and a row's result depends only on its pair, rows `2j` and
//! `2j + 1`, never on the chunking.

use std::sync::Arc;

use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::{Fft, FftPlanner};

use super::Real;

/// How the rows are transformed.
pub(super) enum RowPlan<T: Real> {
    /// Each row by `realfft`.
    Separate {
        r2c: Arc<dyn RealToComplex<T>>,
        c2r: Arc<dyn ComplexToReal<T>>,
    },
    /// Rows `2j` and `2j + 1` together by one complex FFT of the row length.
    Packed {
        forward: Arc<dyn Fft<T>>,
        inverse: Arc<dyn Fft<T>>,
    },
}

impl<T: Real> RowPlan<T> {
    /// The plan of rows of `nx` values in the precision's way ([`Real::PACKED_ROWS`]).
    pub(super) fn new(nx: usize) -> Self {
        if T::PACKED_ROWS {
            let mut planner = FftPlanner::<T>::new();
            Self::Packed {
                forward: planner.plan_fft_forward(nx),
                inverse: planner.plan_fft_inverse(nx),
            }
        } else {
            let mut planner = RealFftPlanner::<T>::new();
            Self::Separate {
                r2c: planner.plan_fft_forward(nx),
                c2r: planner.plan_fft_inverse(nx),
            }
        }
    }

    /// Scratch the row transforms need.
    pub(super) fn scratch_len(&self) -> usize {
        match self {
            Self::Separate { r2c, c2r } => r2c.get_scratch_len().max(c2r.get_scratch_len()),
            Self::Packed { forward, inverse } => forward
                .get_inplace_scratch_len()
                .max(inverse.get_inplace_scratch_len()),
        }
    }

    /// Rows transformed together: 2 when packed (chunks of rows start at even rows).
    pub(super) fn rows_per_transform(&self) -> usize {
        match self {
            Self::Separate { .. } => 1,
            Self::Packed { .. } => 2,
        }
    }
}

/// Frequencies combined together: fixed-size blocks, which the compiler unrolls, the mirrored
/// frequencies reversed within the block (measured faster than a plain loop; for the
/// separation the plain loop was faster).
const LANES: usize = 8;

/// `(A(k), B(k))` from `Z(k)` and its mirror `Z(n − k)` (module docs).
#[inline]
fn separate<T: Real>(zk: Complex<T>, zm: Complex<T>) -> (Complex<T>, Complex<T>) {
    let half = T::of(0.5);
    (
        Complex::new(half * (zk.re + zm.re), half * (zk.im - zm.im)),
        Complex::new(half * (zk.im + zm.im), half * (zm.re - zk.re)),
    )
}

/// `(Z(k), Z(n − k))` from `A(k)` and `B(k)` (module docs).
#[inline]
fn combine<T: Real>(a: Complex<T>, b: Complex<T>) -> (Complex<T>, Complex<T>) {
    (
        Complex::new(a.re - b.im, a.im + b.re),
        Complex::new(a.re + b.im, b.re - a.im),
    )
}

/// The spectra `sa` and `sb` (`n/2 + 1` values each) of the real rows `a` and `b` (`cols`
/// values each, zero beyond up to `n = pair.len()`), by one complex FFT of `pair`.
pub(super) fn forward_pair<T: Real>(
    fft: &dyn Fft<T>,
    (a, b): (&[f64], &[f64]),
    (sa, sb): (&mut [Complex<T>], &mut [Complex<T>]),
    pair: &mut [Complex<T>],
    scratch: &mut [Complex<T>],
) {
    let (n, nxc, cols) = (pair.len(), sa.len(), a.len());
    let zero = T::zero();
    let (packed, padding) = pair.split_at_mut(cols);
    for ((z, &x), &y) in packed.iter_mut().zip(a).zip(b) {
        *z = Complex::new(T::of(x), T::of(y));
    }
    padding.fill(Complex::new(zero, zero));
    fft.process_with_scratch(pair, scratch);
    let z0 = pair[0];
    sa[0] = Complex::new(z0.re, zero);
    sb[0] = Complex::new(z0.im, zero);
    // `Z(k)` for `1 ≤ k < nxc` in `low`; its mirror `Z(n − k)` is `high[count − 1 − k]`.
    let count = nxc - 1;
    let (low, high) = (&pair[1..nxc], &pair[n - count..]);
    let (sa, sb) = (&mut sa[1..][..count], &mut sb[1..][..count]);
    for k in 0..count {
        (sa[k], sb[k]) = separate(low[k], high[count - 1 - k]);
    }
}

/// The real rows `a` and `b` (`n = pair.len()` values each, unnormalised) of the half spectra
/// `sa` and `sb` (`n/2 + 1` values each, Hermitian: the imaginary parts at `k = 0` and, for
/// even `n`, `k = n/2` must be zero), by one complex inverse FFT of `pair`.
pub(super) fn inverse_pair<T: Real>(
    fft: &dyn Fft<T>,
    (sa, sb): (&[Complex<T>], &[Complex<T>]),
    (a, b): (&mut [f64], &mut [f64]),
    pair: &mut [Complex<T>],
    scratch: &mut [Complex<T>],
) {
    let (n, nxc) = (pair.len(), sa.len());
    // `Z(k)` for `k < nxc` in `low`; `Z(n − k)` for `1 ≤ k ≤ count` is `high[count − k]`.
    let (low, high) = pair.split_at_mut(nxc);
    let count = n - nxc;
    let (z0, _) = combine(sa[0], sb[0]);
    low[0] = z0;
    let (low, sa, sb) = (&mut low[1..], &sa[1..], &sb[1..]);
    let whole = count - count % LANES;
    for (((lo, hi), ca), cb) in (low[..whole].chunks_exact_mut(LANES))
        .zip(high[count - whole..].rchunks_exact_mut(LANES))
        .zip(sa[..whole].chunks_exact(LANES))
        .zip(sb[..whole].chunks_exact(LANES))
    {
        for i in 0..LANES {
            (lo[i], hi[LANES - 1 - i]) = combine(ca[i], cb[i]);
        }
    }
    for k in whole..count {
        (low[k], high[count - 1 - k]) = combine(sa[k], sb[k]);
    }
    // For even `n` the last frequency `n/2` is its own mirror.
    for ((z, &za), &zb) in low.iter_mut().zip(sa).zip(sb).skip(count) {
        *z = combine(za, zb).0;
    }
    fft.process_with_scratch(pair, scratch);
    for ((z, a), b) in pair.iter().zip(a.iter_mut()).zip(b.iter_mut()) {
        *a = z.re.into();
        *b = z.im.into();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Both plans give the same spectra and rows, to round-off, for even and odd lengths.
    #[test]
    fn packed_pairs_match_separate_rows() {
        for n in [1, 2, 5, 8, 12, 15] {
            let nxc = n / 2 + 1;
            let a: Vec<f64> = (0..n).map(|i| ((i * 37) % 11) as f64 - 4.0).collect();
            let b: Vec<f64> = (0..n).map(|i| ((i * 13) % 7) as f64 * 0.5).collect();
            let mut planner = RealFftPlanner::<f64>::new();
            let r2c = planner.plan_fft_forward(n);
            let mut scratch = vec![Complex::new(0.0, 0.0); 4 * n + 8];
            let separate = |row: &[f64]| {
                let mut input = row.to_vec();
                let mut out = vec![Complex::new(0.0, 0.0); nxc];
                r2c.process_with_scratch(&mut input, &mut out, &mut scratch.clone())
                    .unwrap();
                out
            };
            let (ea, eb) = (separate(&a), separate(&b));
            let mut planner = FftPlanner::<f64>::new();
            let (forward, inverse) = (planner.plan_fft_forward(n), planner.plan_fft_inverse(n));
            let mut pair = vec![Complex::new(0.0, 0.0); n];
            let mut sa = vec![Complex::new(0.0, 0.0); nxc];
            let mut sb = sa.clone();
            forward_pair(
                forward.as_ref(),
                (&a[..], &b[..]),
                (&mut sa, &mut sb),
                &mut pair,
                &mut scratch,
            );
            for (got, want) in sa.iter().chain(&sb).zip(ea.iter().chain(&eb)) {
                assert!((got - want).norm() < 1e-12, "n = {n}: {got} vs {want}");
            }
            let (mut ra, mut rb) = (vec![0.0; n], vec![0.0; n]);
            inverse_pair(
                inverse.as_ref(),
                (&sa, &sb),
                (&mut ra, &mut rb),
                &mut pair,
                &mut scratch,
            );
            for (got, want) in ra.iter().chain(&rb).zip(a.iter().chain(&b)) {
                assert!((got / n as f64 - want).abs() < 1e-12, "n = {n}");
            }
        }
    }
}
