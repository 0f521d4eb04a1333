//! The influence operator restricted to a set of grid points, kept from one use to the next.
//!
//! `K_ab = K(r_a − r_b)` for the points `a, b` of a set (`InfluenceOperator::coefficient_between`),
//! an `m × m` matrix, symmetric bit for bit (the coefficient is read by the offset's magnitude), so
//! it is stored as its packed lower triangle, `m(m+1)/2` values (`packed_symmetric.rs`), and its
//! product is bit-identical to the dense row-major one. Each coefficient is a read at an
//! offset-dependent place of a table of the grid's size, so building the matrix from scratch
//! costs about one cache miss per entry (`docs/contact-solver-design.md`). Consecutive sets of one
//! solve share most of their points, so the matrix of the last set is kept and its entries
//! between points of both sets are copied; only the rows and columns of new points are read
//! from the table. The values do not depend on what was kept: each entry is the same
//! coefficient either way. The last matrix and the buffer of the next are both kept: at most
//! `m(m+1)` values in all.

use super::influence::InfluenceOperator;
use super::packed_symmetric::PackedSymmetric;

/// The last restricted matrix and the buffer of the next.
#[derive(Debug, Default)]
pub(crate) struct RestrictedMatrix {
    /// Flat grid indices, ascending.
    points: Vec<usize>,
    /// `K_ab` in m/Pa, `a` and `b` positions in `points`.
    values: PackedSymmetric,
    spare: PackedSymmetric,
}

impl RestrictedMatrix {
    /// Makes this the matrix of `points` (flat indices, ascending) under `op`, rows in parallel.
    pub(crate) fn update(&mut self, op: &InfluenceOperator, points: Vec<usize>) {
        let nx = op.nx();
        let kept = positions_in(&points, &self.points);
        let coords: Vec<(usize, usize)> = points.iter().map(|&i| (i % nx, i / nx)).collect();
        let mut values = std::mem::take(&mut self.spare);
        let old = &self.values;
        // Kept points keep their order, so `j ≤ i` gives old positions `kept_j ≤ kept_i`: the
        // old entry is in the old row `kept_i`.
        values.rebuild(points.len(), |i, row| {
            let (a, kept_a) = (coords[i], kept[i]);
            let old_row = kept_a.map(|k| old.row(k));
            for ((value, &b), &kept_b) in row.iter_mut().zip(&coords).zip(&kept) {
                *value = match (old_row, kept_b) {
                    (Some(old_row), Some(j)) => old_row[j],
                    _ => op.coefficient_between(a, b),
                };
            }
        });
        self.spare = std::mem::replace(&mut self.values, values);
        self.points = points;
    }

    /// The points of the matrix.
    pub(crate) fn points(&self) -> &[usize] {
        &self.points
    }

    /// `w = K t` for `t` on the points, each `w_i` bit-identical to the dense row-major product
    /// `Σ_j K_ij t_j` in ascending `j` (`PackedSymmetric::multiply`), so the result does not
    /// depend on the thread count.
    pub(crate) fn multiply(&self, t: &[f64], w: &mut [f64]) {
        self.values.multiply(t, w);
    }
}

/// For each of `points`, its position in `old` if it is there (both ascending).
fn positions_in(points: &[usize], old: &[usize]) -> Vec<Option<usize>> {
    let mut j = 0;
    points
        .iter()
        .map(|&i| {
            while j < old.len() && old[j] < i {
                j += 1;
            }
            (j < old.len() && old[j] == i).then_some(j)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::influence::Boundary;

    #[test]
    fn kept_entries_equal_fresh_ones() {
        // Sets that overlap, grow, shrink and are disjoint: the matrix built from the last one
        // is the matrix built from scratch, bit for bit.
        let op =
            InfluenceOperator::new(16, 10, 1e-6, 1e-6, 1e11, Boundary::Periodic, false).unwrap();
        let sets: [&[usize]; 5] = [
            &[3, 17, 40, 41, 99, 150],
            &[3, 18, 40, 41, 120, 150, 159],
            &[40, 41],
            &[0, 1, 2, 40, 41, 42, 159],
            &[5, 6],
        ];
        let mut kept = RestrictedMatrix::default();
        for set in sets {
            kept.update(&op, set.to_vec());
            let mut fresh = RestrictedMatrix::default();
            fresh.update(&op, set.to_vec());
            assert_eq!(kept.points(), set);
            let m = set.len();
            assert_eq!(kept.values.order(), m);
            for i in 0..m {
                assert_eq!(bits(kept.values.row(i)), bits(fresh.values.row(i)));
                for j in 0..m {
                    let (a, b) = ((set[i] % 16, set[i] / 16), (set[j] % 16, set[j] / 16));
                    assert_eq!(
                        kept.values.get(i, j).to_bits(),
                        op.coefficient_between(a, b).to_bits()
                    );
                }
            }
            let t: Vec<f64> = (0..set.len()).map(|k| k as f64 - 1.5).collect();
            let (mut w_kept, mut w_fresh) = (vec![0.0; set.len()], vec![0.0; set.len()]);
            kept.multiply(&t, &mut w_kept);
            fresh.multiply(&t, &mut w_fresh);
            assert_eq!(bits(&w_kept), bits(&w_fresh));
        }
    }

    fn bits(values: &[f64]) -> Vec<u64> {
        values.iter().map(|x| x.to_bits()).collect()
    }

    #[test]
    fn both_buffers_hold_a_triangle() {
        let op =
            InfluenceOperator::new(16, 10, 1e-6, 1e-6, 1e11, Boundary::Periodic, false).unwrap();
        let mut matrix = RestrictedMatrix::default();
        matrix.update(&op, (0..40).collect());
        matrix.update(&op, (20..120).collect());
        assert_eq!(matrix.values.stored_len(), 100 * 101 / 2);
        assert_eq!(matrix.values.capacity(), 100 * 101 / 2);
        assert_eq!(matrix.spare.stored_len(), 40 * 41 / 2);
        matrix.update(&op, (30..130).collect());
        assert_eq!(matrix.values.stored_len(), 100 * 101 / 2);
        assert_eq!(matrix.values.capacity(), 100 * 101 / 2);
        assert_eq!(matrix.spare.stored_len(), 100 * 101 / 2);
    }

    #[test]
    fn positions_of_kept_points() {
        assert_eq!(
            positions_in(&[1, 4, 5, 9], &[0, 4, 9, 12]),
            vec![None, Some(1), None, Some(2)]
        );
        assert_eq!(positions_in(&[2], &[]), vec![None]);
    }
}
