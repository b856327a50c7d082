//! One-way platforms, the seed's special case: "don't collide x axis step; collide y only if
//! previously *entirely* above platform".
//!
//! The seed also warns against the simpler rule: "collide only if falling" does not work,
//! because a character can start falling mid-jump while inside the platform and would then be
//! snapped onto its top. Here a one-way box (a one-way tile, a ladder's top, or a one-way moving
//! platform) is skipped by the x move, and by the y move unless the move goes down and the feet
//! were at or above its top before it (within the storage's tolerance: the epsilon in float,
//! nothing on the grid), the rule every controller shares ([`crate::oneway::OneWayCheck`]). A
//! character dropping through (down + jump) or on a ladder passes.

use super::broadphase::BoxKind;

/// Whether `kind` blocks only from above.
pub(super) fn is_one_way(kind: BoxKind) -> bool {
    matches!(
        kind,
        BoxKind::OneWay | BoxKind::Platform { one_way: true, .. }
    )
}
