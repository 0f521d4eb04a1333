//! The memory estimate of a friction node, from its method and the grid of its upstream contact.

use super::MethodSetup;

/// Peak bytes per point of the contact's grid for a method that reads its maps (per summit, per
/// spot): the maps are read in place; spot labels, summit lists and per-point work arrays are
/// held beside them, ≤ 3 f64 per point.
const BYTES_PER_MAP_POINT: u64 = 3 * 8;

/// The result rows and the law's tables, whatever the grid.
const FIXED_BYTES: u64 = 1 << 20;

/// Peak bytes per point for the earlier load steps: 12 f64 per point, a measured upper bound
/// that also covers an influence operator and its transform buffers. A node holds one pressure
/// array of them (`ContactTask::step_pressure`; the other maps are read point by point,
/// `StepPressure::view`), so the bound is loose (docs/robustness.md, "Memory").
const BYTES_PER_STEP_MAP_POINT: u64 = 12 * 8;

/// Peak bytes of the earlier load steps' maps whatever the grid (measured with the bound above).
const STEP_MAP_FIXED_BYTES: u64 = 12 << 20;

/// The peak memory of a friction node with `setup`, bytes, where the earlier load steps' maps add
/// the worker threads' `scratch` (bytes per point, `nodes::thread_scratch_bytes_per_point`); an
/// upper bound of the process's peak less its base and the contact's maps (figures:
/// docs/robustness.md, "Memory").
pub(super) fn estimate(setup: &MethodSetup, scratch: u64) -> u64 {
    let contact = match setup {
        MethodSetup::Statistical { .. } => return FIXED_BYTES,
        MethodSetup::PerSummit { contact, .. } | MethodSetup::PerSpot { contact, .. } => contact,
    };
    let points = contact.task.points();
    let (fixed, per_point) = if contact.task.step_count() > 1 {
        (
            FIXED_BYTES + STEP_MAP_FIXED_BYTES,
            BYTES_PER_MAP_POINT + BYTES_PER_STEP_MAP_POINT + scratch,
        )
    } else {
        (FIXED_BYTES, BYTES_PER_MAP_POINT)
    };
    fixed.saturating_add(points.saturating_mul(per_point))
}
