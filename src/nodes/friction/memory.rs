//! The memory estimate of a friction node, from its method and the grid of its upstream contact.

use super::MethodSetup;

/// Peak bytes per point of the contact's grid for a method that reads its maps (per summit, per
/// spot): the maps are read in place; spot labels, summit lists and per-point work arrays are
/// held beside them, ≤ 3 f64 per point.
const BYTES_PER_MAP_POINT: u64 = 3 * 8;

/// The result rows and the law's tables, whatever the grid.
const FIXED_BYTES: u64 = 1 << 20;

/// Peak bytes per point for the maps of the earlier load steps (`ContactTask::step_maps`): the
/// pressure, gap, both deformations and the plastic penetration, 5 f64, allocated once and
/// overwritten at every step. The convolution each step needs is the contact's, done once for
/// all its consumers and charged to the contact's artifact.
const BYTES_PER_STEP_MAP_POINT: u64 = 5 * 8;

/// The peak memory of a friction node with `setup`, bytes; an upper bound of the process's peak
/// less its base and the contact's maps (figures: docs/robustness.md, "Memory").
pub(super) fn estimate(setup: &MethodSetup) -> u64 {
    let contact = match setup {
        MethodSetup::Statistical { .. } => return FIXED_BYTES,
        MethodSetup::PerSummit { contact, .. } | MethodSetup::PerSpot { contact, .. } => contact,
    };
    let points = contact.task.points();
    let per_point = if contact.task.step_count() > 1 {
        BYTES_PER_MAP_POINT + BYTES_PER_STEP_MAP_POINT
    } else {
        BYTES_PER_MAP_POINT
    };
    FIXED_BYTES.saturating_add(points.saturating_mul(per_point))
}
