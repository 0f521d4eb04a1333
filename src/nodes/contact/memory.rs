//! The memory estimate of a contact node, from its grid, boundary, fields and load steps.

/// Peak bytes per grid point of the solver on periodic surfaces and on non-periodic ones (its
/// FFTs run on the grid padded to twice each side): its maps, spectra and the solver's
/// single-precision copies, beside the threads' scratch.
const SOLVER_BYTES_PER_POINT: [u64; 2] = [11 * 8, 25 * 8];
/// Peak bytes per grid point of the final step's maps kept for consumers (`fields: true`): the
/// pressure, gap, both deformations, plastic penetration, composite height and upper heights.
const FIELDS_BYTES_PER_POINT: u64 = 7 * 8;
/// Bytes per grid point and earlier load step kept for consumers (`fields: true`): the step's
/// displacement (array `step_displacements`), derived after the solver is dropped with an operator
/// and a pressure map smaller than the solver's arrays.
const STEP_BYTES_PER_POINT: u64 = 8;
/// The node's bytes whatever the grid: the solver's plans and options, the load curve and
/// storing the result in the cache.
const SOLVER_FIXED_BYTES: u64 = 20 << 20;

/// The peak memory of a contact on `points` grid points with `steps` load steps, bytes: the
/// solver's arrays, the worker threads' `scratch` (bytes per point,
/// `nodes::thread_scratch_bytes_per_point`) and the fields when kept (the final step's maps and
/// the earlier steps' displacements); an upper bound of the process's peak less its base
/// (figures: docs/robustness.md, "Memory").
pub(super) fn memory_estimate(
    points: u64,
    periodic: bool,
    fields: bool,
    steps: usize,
    scratch: u64,
) -> u64 {
    let solver = SOLVER_BYTES_PER_POINT[usize::from(!periodic)];
    let earlier = steps.saturating_sub(1) as u64;
    let kept = if fields {
        FIELDS_BYTES_PER_POINT + earlier * STEP_BYTES_PER_POINT
    } else {
        0
    };
    SOLVER_FIXED_BYTES.saturating_add(points.saturating_mul(solver + scratch + kept))
}
