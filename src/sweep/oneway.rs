//! One-way platforms, the seed's special case: "don't collide x axis step; collide y only if
//! previously *entirely* above platform".
//!
//! The seed also warns against the simpler rule: "collide only if falling" does not work,
//! because a character can start falling mid-jump while inside the platform and would then be
//! snapped onto its top. Here a one-way box (a one-way tile, a ladder's top, or a one-way moving
//! platform) is skipped by the x move, and by the y move unless the move goes down and the feet
//! were at or above its top before it (within the storage's tolerance: the epsilon in float,
//! nothing on the grid). A character dropping through (down + jump) or on a ladder passes.

use std::ops::Sub;

use super::broadphase::BoxKind;

/// Whether `kind` blocks only from above.
pub(super) fn is_one_way(kind: BoxKind) -> bool {
    matches!(
        kind,
        BoxKind::OneWay | BoxKind::Platform { one_way: true, .. }
    )
}

/// A y move's view of one-way boxes: where its feet started and whether it may land on one.
#[derive(Clone, Copy, Debug)]
pub(super) struct Fall<C> {
    /// The feet before the y move, in the storage's coordinate.
    pub from: C,
    /// The storage's overlap tolerance.
    pub eps: C,
    /// Whether this move passes every one-way box: not falling, dropping through, or climbing.
    pub passes: bool,
}

impl<C: Copy + PartialOrd + Sub<Output = C>> Fall<C> {
    /// Step 5's one-way rule: whether the y move passes a one-way box whose top is `top`
    /// (it blocks only a fall that started entirely above it).
    pub(super) fn passes(&self, top: C) -> bool {
        self.passes || self.from < top - self.eps
    }
}
