//! The memory estimate of a contact node, from its grid, boundary, fields and load steps.

/// Peak bytes per grid point of the solver on periodic surfaces and on non-periodic ones (its
/// FFTs run on the grid padded to twice each side), beside the threads' scratch: on a periodic
/// grid six maps (the initial gap, pressure, displacement, gap, direction and its product), the
/// row and column spectra of one precision's transforms at a time (two), the kernels and
/// influence coefficients (about one) and the restricted matrix of the moving points (about one
/// where it is used).
const SOLVER_BYTES_PER_POINT: [u64; 2] = [10 * 8, 25 * 8];
/// Bytes per grid point the node holds after the solver is released (`fields: true`): the
/// solver's pressure, gap and displacement while the earlier steps are convolved (with the
/// operator's transforms and a pressure map, about four more), then the final step's pressure
/// and displacement, the composite height and the upper heights.
const FIELDS_BYTES_PER_POINT: u64 = 7 * 8;
/// Bytes per grid point and earlier load step kept for consumers (`fields: true`): the step's
/// displacement (array `step_displacements`), convolved after the solver is released, with an
/// operator and a pressure map no larger than the two maps made after it.
const STEP_BYTES_PER_POINT: u64 = 8;
/// The node's bytes whatever the grid: the solver's plans and options, the load curve and
/// storing the result in the cache.
const SOLVER_FIXED_BYTES: u64 = 20 << 20;

/// The peak memory of a contact on `points` grid points with `steps` load steps, bytes: the
/// larger of the solver's arrays with the worker threads' `scratch` (bytes per point,
/// `nodes::thread_scratch_bytes_per_point`) and, when the fields are kept, what the node holds
/// after the solver is released (the final step's maps and the earlier steps'
/// displacements); an upper bound of the process's peak less its base and the input surfaces
/// (figures: docs/robustness.md, "Memory").
pub(super) fn memory_estimate(
    points: u64,
    periodic: bool,
    fields: bool,
    steps: usize,
    scratch: u64,
) -> u64 {
    let solver = SOLVER_BYTES_PER_POINT[usize::from(!periodic)] + scratch;
    let earlier = steps.saturating_sub(1) as u64;
    let kept = if fields {
        FIELDS_BYTES_PER_POINT + earlier * STEP_BYTES_PER_POINT
    } else {
        0
    };
    SOLVER_FIXED_BYTES.saturating_add(points.saturating_mul(solver.max(kept)))
}

#[cfg(test)]
mod tests {
    use super::*;

    const MIB: u64 = 1 << 20;

    /// The process peaks of a contact measured at the full size (release and debug binaries
    /// alike hold the same arrays), less the base and the two input surfaces, lie below the
    /// estimate by a modest margin (docs/robustness.md, "Memory"): 3512² and 2048², fields and
    /// four load steps, two threads (one precision's transforms at a time, the packed
    /// restricted matrix).
    #[test]
    fn the_estimate_bounds_the_measured_full_size_peaks_by_a_modest_margin() {
        for (n, measured_mib) in [(3512_u64, 980), (2048, 328)] {
            let estimate = memory_estimate(n * n, true, true, 4, 16) / MIB;
            assert!(
                estimate >= measured_mib && estimate <= measured_mib * 5 / 4,
                "{n}²: {estimate} MiB against {measured_mib} measured"
            );
        }
    }

    /// Many load steps: the displacements kept after the solve outgrow the solver's arrays.
    #[test]
    fn the_kept_displacements_count_once_they_outgrow_the_solver() {
        let points = 1 << 20;
        let few = memory_estimate(points, true, true, 4, 16);
        let many = memory_estimate(points, true, true, 20, 16);
        assert_eq!(few, SOLVER_FIXED_BYTES + points * (80 + 16));
        assert_eq!(many, SOLVER_FIXED_BYTES + points * (56 + 19 * 8));
        assert_eq!(
            memory_estimate(points, true, false, 20, 16),
            SOLVER_FIXED_BYTES + points * (80 + 16)
        );
    }
}
