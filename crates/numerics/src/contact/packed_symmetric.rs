//! A symmetric matrix stored as its packed lower triangle, with a product whose every entry is
//! bit-identical to the dense row-major product's.
//!
//! Row `i` holds `A_i0 … A_ii` contiguously from index `i(i+1)/2`: `n(n+1)/2` values instead of
//! `n²`. The product `w = A t` computes each `w_i` as the dense product's row `i` does —
//! `Σ_j A_ij t_j` added in ascending `j` to Rust's `f64` sum start `−0.0` — so it equals
//! `row.iter().zip(t).map(|(a, b)| a * b).sum()` bit for bit whatever the thread count.
//!
//! Order of the product: the rows are split into contiguous ranges `[a, b)`, one task each. A task
//! walks the rows `p` from `a` to the last row `n − 1` once:
//! * `p < b`: `w_p` is started and summed along row `p` (`j ≤ p`, ascending), and each entry
//!   `A_pq` with `a ≤ q < p` is also added, as `A_qp t_p`, to `w_q`, whose terms `j < p` are all in;
//! * `p ≥ b`: the segment `A_p,a … A_p,b−1` is added, times `t_p`, to `w_a … w_b−1` (their terms
//!   `j = p` in ascending `p`, a vectorisable update).
//!
//! A task of `k` rows reads `k(n − k/2)` values, the same for equal ranges wherever they lie, and
//! the whole product reads the triangle once plus the blocks below the diagonal between ranges
//! (with two ranges, `¾ n²` values against the dense product's `n²`).

use rayon::prelude::*;

/// A symmetric `n × n` matrix as its packed lower triangle.
#[derive(Debug, Default, Clone)]
pub struct PackedSymmetric {
    order: usize,
    /// Row `i` of the lower triangle at `i(i+1)/2 .. i(i+1)/2 + i + 1`.
    values: Vec<f64>,
}

impl PackedSymmetric {
    /// The matrix of order `order` with entries `entry(i, j)` for `j ≤ i` (the lower triangle).
    pub fn from_lower(order: usize, entry: impl Fn(usize, usize) -> f64 + Sync) -> Self {
        let mut matrix = Self::default();
        matrix.rebuild(order, |i, row| {
            row.iter_mut()
                .enumerate()
                .for_each(|(j, value)| *value = entry(i, j))
        });
        matrix
    }

    /// Makes this a matrix of order `order` whose row `i` (`i + 1` values, `A_i0 … A_ii`) is
    /// written by `fill(i, row)`, rows in parallel. The buffer is reused: `fill` must write every
    /// value of its row (old values are not cleared first).
    pub fn rebuild(&mut self, order: usize, fill: impl Fn(usize, &mut [f64]) + Sync) {
        let len = packed_len(order);
        self.values
            .reserve_exact(len.saturating_sub(self.values.len()));
        self.values.resize(len, 0.0);
        self.order = order;
        let mut rows = Vec::with_capacity(order);
        let mut rest = self.values.as_mut_slice();
        for i in 0..order {
            let (row, tail) = rest.split_at_mut(i + 1);
            rows.push(row);
            rest = tail;
        }
        rows.into_par_iter()
            .enumerate()
            .for_each(|(i, row)| fill(i, row));
    }

    /// The order `n`.
    pub fn order(&self) -> usize {
        self.order
    }

    /// Row `i` of the lower triangle, `A_i0 … A_ii`.
    pub fn row(&self, i: usize) -> &[f64] {
        &self.values[packed_len(i)..packed_len(i + 1)]
    }

    /// `A_ij = A_ji`.
    pub fn get(&self, i: usize, j: usize) -> f64 {
        let (i, j) = (i.max(j), i.min(j));
        self.row(i)[j]
    }

    /// Values stored: `n(n+1)/2`.
    pub fn stored_len(&self) -> usize {
        self.values.len()
    }

    /// Values the buffer can hold without reallocating.
    pub fn capacity(&self) -> usize {
        self.values.capacity()
    }

    /// `w = A t`, each `w_i` bit-identical to the dense row-major product's (module docs), one
    /// range of rows per thread of rayon's pool.
    ///
    /// # Panics
    /// If `t` or `w` does not have `n` values.
    pub fn multiply(&self, t: &[f64], w: &mut [f64]) {
        let n = self.order;
        assert!(
            t.len() == n && w.len() == n,
            "vectors of the matrix's order"
        );
        let ranges = rayon::current_num_threads().clamp(1, n.max(1));
        let width = n.div_ceil(ranges).max(1);
        w.par_chunks_mut(width)
            .enumerate()
            .for_each(|(k, w_range)| self.multiply_range(k * width, t, w_range));
    }

    /// `w_a … w_b−1` (`w` holds `b − a` values) in the order of the module docs.
    fn multiply_range(&self, a: usize, t: &[f64], w: &mut [f64]) {
        let b = a + w.len();
        for p in a..b {
            let row = self.row(p);
            let tp = t[p];
            let mut sum = -0.0;
            for (v, tq) in row[..a].iter().zip(&t[..a]) {
                sum += v * tq;
            }
            for ((v, tq), wq) in row[a..p].iter().zip(&t[a..p]).zip(&mut w[..p - a]) {
                sum += v * tq;
                *wq += v * tp;
            }
            w[p - a] = sum + row[p] * tp;
        }
        for (p, &tp) in t.iter().enumerate().skip(b) {
            for (wq, v) in w.iter_mut().zip(&self.row(p)[a..b]) {
                *wq += v * tp;
            }
        }
    }
}

/// Values of the rows `0 … order − 1` of a packed triangle: `order(order+1)/2`.
fn packed_len(order: usize) -> usize {
    order * (order + 1) / 2
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The dense row-major product the packed one replaces.
    fn dense_product(matrix: &PackedSymmetric, t: &[f64]) -> Vec<f64> {
        let n = matrix.order();
        let dense: Vec<f64> = (0..n * n).map(|k| matrix.get(k / n, k % n)).collect();
        dense
            .chunks(n.max(1))
            .take(n)
            .map(|row| row.iter().zip(t).map(|(a, b)| a * b).sum())
            .collect()
    }

    /// Seeded values of mixed signs and magnitudes, with zeros of both signs.
    fn values(n: usize, seed: u64) -> Vec<f64> {
        let mut state = seed;
        (0..n)
            .map(|_| {
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                match (state >> 60) % 8 {
                    0 => 0.0,
                    1 => -0.0,
                    _ => {
                        ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.5)
                            * 10f64.powi((state >> 56) as i32 % 7 - 3)
                    }
                }
            })
            .collect()
    }

    fn assert_bit_identical(n: usize, threads: usize, t: &[f64], entries: &[f64]) {
        let matrix = PackedSymmetric::from_lower(n, |i, j| entries[packed_len(i) + j]);
        let mut w = vec![f64::NAN; n];
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| matrix.multiply(t, &mut w));
        let dense = dense_product(&matrix, t);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&w), bits(&dense), "order {n}, {threads} threads");
    }

    #[test]
    fn product_is_bit_identical_to_the_dense_one() {
        for n in [0, 1, 2, 3, 7, 31, 32, 33, 64, 65, 200, 257] {
            for threads in [1, 2, 3, 5] {
                let t = values(n, 7 + n as u64);
                let entries = values(packed_len(n), 11 + n as u64);
                assert_bit_identical(n, threads, &t, &entries);
            }
        }
    }

    #[test]
    fn signed_zero_products_sum_as_the_dense_product_does() {
        // Every product is ±0: the sign of each w_i follows from the −0.0 start of the sum and
        // the order of the terms.
        for n in [1, 2, 5, 40] {
            for threads in [1, 2, 4] {
                let t: Vec<f64> = (0..n)
                    .map(|k| if k % 3 == 0 { -0.0 } else { 0.0 })
                    .collect();
                let entries: Vec<f64> = (0..packed_len(n))
                    .map(|k| if k % 2 == 0 { -1.5 } else { 2.0 })
                    .collect();
                assert_bit_identical(n, threads, &t, &entries);
                let all_negative = vec![-0.0; n];
                assert_bit_identical(n, threads, &all_negative, &entries);
            }
        }
    }

    #[test]
    fn stores_the_triangle_only() {
        let mut matrix = PackedSymmetric::from_lower(100, |i, j| (i * 1000 + j) as f64);
        assert_eq!(matrix.stored_len(), 5050);
        assert_eq!(matrix.capacity(), 5050);
        assert_eq!(matrix.get(3, 70), 70_003.0);
        assert_eq!(matrix.get(70, 3), 70_003.0);
        matrix.rebuild(120, |i, row| row.fill(i as f64));
        assert_eq!((matrix.stored_len(), matrix.capacity()), (7260, 7260));
        assert_eq!(matrix.row(119), &[119.0; 120][..]);
    }
}
