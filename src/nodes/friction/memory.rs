//! The memory estimate of a friction node, from its method and the grid of its upstream contact.

use crate::engine::study::ResolveContext;
use crate::nodes::contact::ContactTask;

use super::MethodSetup;

/// Peak bytes per point of the contact's grid for a method that reads its maps (per summit, per
/// spot): the maps are read in place; spot labels, summit lists and per-point work arrays are
/// held beside them, ≤ 3 f64 per point (measured at 1024²: 4–12 MiB, i.e. ≤ 1.5 f64 per point;
/// docs/robustness.md, "Memory").
const BYTES_PER_MAP_POINT: u64 = 3 * 8;

/// The result rows and the law's tables, whatever the grid (a statistical node at 1024² peaks
/// at 0.2 MiB).
const FIXED_BYTES: u64 = 1 << 20;

/// The peak memory of a friction node with `setup` whose upstream nodes are in `ctx`, bytes.
pub(super) fn estimate(setup: &MethodSetup, ctx: &ResolveContext<'_>) -> u64 {
    let contact = match setup {
        MethodSetup::Statistical { .. } => return FIXED_BYTES,
        MethodSetup::PerSummit { contact, .. } | MethodSetup::PerSpot { contact, .. } => *contact,
    };
    let points = ctx
        .upstream(contact)
        .and_then(|t| t.as_any().downcast_ref::<ContactTask>())
        .map_or(0, ContactTask::points);
    FIXED_BYTES.saturating_add(points.saturating_mul(BYTES_PER_MAP_POINT))
}
