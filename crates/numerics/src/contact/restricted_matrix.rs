//! The influence operator restricted to a set of grid points, kept from one use to the next.
//!
//! `K_ab = K(r_a − r_b)` for the points `a, b` of a set (`InfluenceOperator::coefficient_between`),
//! a dense `m × m` matrix. Each coefficient is a read at an offset-dependent place of a table of
//! the grid's size, so building the matrix from scratch costs about one cache miss per entry
//! (`docs/contact-solver-design.md`). Consecutive sets of one
//! solve share most of their points, so the matrix of the last set is kept and its entries
//! between points of both sets are copied; only the rows and columns of new points are read
//! from the table. The values do not depend on what was kept: each entry is the same
//! coefficient either way.

use rayon::prelude::*;

use super::influence::InfluenceOperator;

/// The last restricted matrix and the buffer of the next.
#[derive(Debug, Default)]
pub(crate) struct RestrictedMatrix {
    /// Flat grid indices, ascending.
    points: Vec<usize>,
    /// Row-major `points.len()²` values in m/Pa.
    values: Vec<f64>,
    spare: Vec<f64>,
}

impl RestrictedMatrix {
    /// Makes this the matrix of `points` (flat indices, ascending) under `op`.
    pub(crate) fn update(&mut self, op: &InfluenceOperator, points: Vec<usize>) {
        let nx = op.nx();
        let kept = positions_in(&points, &self.points);
        let coords: Vec<(usize, usize)> = points.iter().map(|&i| (i % nx, i / nx)).collect();
        let (m, m_old) = (points.len(), self.points.len());
        // Every value is written below: the spare's old values are not cleared first, only a
        // grown tail is zero-filled by `resize`.
        let mut values = std::mem::take(&mut self.spare);
        values.resize(m * m, 0.0);
        let old = &self.values;
        values
            .par_chunks_mut(m.max(1))
            .zip(coords.par_iter().zip(&kept))
            .for_each(|(row, (&a, &kept_a))| {
                let old_row = kept_a.map(|i| &old[i * m_old..][..m_old]);
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

    /// `w = K t` for `t` on the points, rows in parallel (each row's sum in a fixed order, so
    /// the result does not depend on the thread count).
    pub(crate) fn multiply(&self, t: &[f64], w: &mut [f64]) {
        let m = t.len();
        w.par_iter_mut()
            .zip(self.values.par_chunks(m.max(1)))
            .for_each(|(wi, row)| *wi = row.iter().zip(t).map(|(a, b)| a * b).sum());
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
            assert_eq!(kept.values, fresh.values);
            let t: Vec<f64> = (0..set.len()).map(|k| k as f64 - 1.5).collect();
            let (mut w_kept, mut w_fresh) = (vec![0.0; set.len()], vec![0.0; set.len()]);
            kept.multiply(&t, &mut w_kept);
            fresh.multiply(&t, &mut w_fresh);
            assert_eq!(w_kept, w_fresh);
        }
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
