//! Multilevel start of a cold load step: the same problem solved on grids coarsened by two in
//! each direction, the coarsest first, each coarse pressure prolongated as the start of the next
//! finer grid (nested iteration, the coarse-to-fine phase of full multigrid; Brandt 1977, Math.
//! Comp. 31; for dry contact Lubrecht & Ioannides 1991, J. Tribol. 113).
//!
//! The coarsest grid is solved first, from its rigid-plastic start. When more than
//! [`MAX_COARSE_PLASTIC_SHARE`] of its contact area is saturated, the multilevel start is
//! abandoned and the fine grid starts rigid-plastic: that start is then already close to the
//! solution (most of the load sits at `p_lim` on the points of smallest gap), and a prolongated
//! coarse pressure, blurred over 2 × 2 blocks, is a worse one.
//!
//! Restriction: each coarse gap is the mean of its 2 × 2 fine block, on pixels of twice the
//! spacing, with the fine problem's material and boundary (a non-periodic problem stays
//! non-periodic). Prolongation: each fine point takes the pressure of its coarse block, which
//! keeps the mean pressure, hence the load; the fine solver then restores the load of its own
//! free set exactly (`Workspace::rebalance`) as after a warm start.
//!
//! Why it pays: from a uniform or rigid-plastic start the load-controlled iteration spends most
//! of its steps moving load between distant parts of the surface, which the elastic operator
//! couples only through its long wavelengths; those wavelengths are resolved on a coarse grid at
//! a quarter of the cost per level. What is left on the fine grid is the local redistribution
//! within and around each contact spot. The converged result is the fine grid's: only the start
//! differs, and every reported residual is the fine solve's. Measurements in
//! `docs/contact-solver-design.md`.

use ndarray::Array2;

use super::gap::CompositeGap;
use super::problem::ContactProblem;

/// A grid is coarsened only while the coarse grid keeps at least this many points along each
/// side: on smaller grids the fine solve from the rigid-plastic start takes few iterations and
/// the coarse ones did not pay for themselves (the shipped 256² and 512² studies).
pub(super) const MIN_COARSE_POINTS: usize = 256;

/// Above this share of the coarsest contact area at `p_lim` the fine grid starts rigid-plastic.
pub(super) const MAX_COARSE_PLASTIC_SHARE: f64 = 0.5;

/// Relative tolerance of the coarse solves (or the fine tolerance, if looser). A coarse solution
/// only places the start; a tighter coarse tolerance did not reduce the fine iterations.
pub(super) const COARSE_TOLERANCE: f64 = 1e-3;

/// Whether an `nx × ny` grid can be coarsened: both sides even, and the coarse grid keeps at
/// least [`MIN_COARSE_POINTS`] points along each side.
pub(super) fn coarsenable(nx: usize, ny: usize) -> bool {
    nx.is_multiple_of(2)
        && ny.is_multiple_of(2)
        && nx / 2 >= MIN_COARSE_POINTS
        && ny / 2 >= MIN_COARSE_POINTS
}

/// The problem on the grid coarsened by two in each direction, or `None` when the grid is not
/// [`coarsenable`].
pub(super) fn coarsened(problem: &ContactProblem) -> Option<ContactProblem> {
    let gap = problem.gap();
    let (nx, ny) = (gap.nx(), gap.ny());
    if !coarsenable(nx, ny) {
        return None;
    }
    let fine = gap.gap();
    let coarse = Array2::from_shape_fn((ny / 2, nx / 2), |(iy, ix)| {
        let (y, x) = (2 * iy, 2 * ix);
        0.25 * (fine[[y, x]] + fine[[y, x + 1]] + fine[[y + 1, x]] + fine[[y + 1, x + 1]])
    });
    let coarse_gap =
        CompositeGap::from_gap_array(coarse.view(), 2.0 * gap.dx(), 2.0 * gap.dy()).ok()?;
    Some(ContactProblem::new(
        coarse_gap,
        *problem.material(),
        problem.boundary(),
    ))
}

/// The coarser problems of `problem`, finest first (empty when it cannot be coarsened).
pub(super) fn coarse_levels(problem: &ContactProblem) -> Vec<ContactProblem> {
    let mut levels: Vec<ContactProblem> = Vec::new();
    while let Some(next) = coarsened(levels.last().unwrap_or(problem)) {
        levels.push(next);
    }
    levels
}

/// `fine[iy·nx + ix] = coarse[(iy/2)·(nx/2) + ix/2]` on a fine grid of rows of `nx` points.
pub(super) fn prolongate(coarse: &[f64], fine: &mut [f64], nx: usize) {
    let nxc = nx / 2;
    for (iy, row) in fine.chunks_mut(nx).enumerate() {
        let coarse_row = &coarse[(iy / 2) * nxc..][..nxc];
        for (ix, p) in row.iter_mut().enumerate() {
            *p = coarse_row[ix / 2];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::{Boundary, ContactMaterial};

    #[test]
    fn prolongation_keeps_the_mean_pressure() {
        let (nx, ny) = (8, 6);
        let coarse: Vec<f64> = (0..nx * ny / 4).map(|i| (i * 7 % 5) as f64).collect();
        let mut fine = vec![0.0; nx * ny];
        prolongate(&coarse, &mut fine, nx);
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
        assert_eq!(mean(&coarse), mean(&fine));
        assert_eq!(fine[nx + 3], coarse[1]);
    }

    #[test]
    fn coarsening_averages_blocks_and_stops_at_the_minimum() {
        let n = 2 * MIN_COARSE_POINTS;
        let gap = Array2::from_shape_fn((n, n), |(iy, ix)| (iy * n + ix) as f64 * 1e-9);
        let material = ContactMaterial::from_young_poisson(210e9, 0.3, 210e9, 0.3, 1e9).unwrap();
        let problem =
            ContactProblem::from_gap_array(gap.view(), 1e-6, 2e-6, material, Boundary::NonPeriodic)
                .unwrap();
        let coarse = coarsened(&problem).unwrap();
        assert_eq!(coarse.boundary(), Boundary::NonPeriodic);
        assert_eq!((coarse.gap().dx(), coarse.gap().dy()), (2e-6, 4e-6));
        let block = 0.25 * (gap[[2, 4]] + gap[[2, 5]] + gap[[3, 4]] + gap[[3, 5]]);
        let shift = coarse.gap().gap()[[1, 2]] - block;
        assert!(
            (coarse.gap().gap()[[0, 0]]
                - shift
                - 0.25 * (gap[[0, 0]] + gap[[0, 1]] + gap[[1, 0]] + gap[[1, 1]]))
            .abs()
                < 1e-18
        );
        assert!(coarsened(&coarse).is_none());
    }
}
