//! One-way platforms: the rule every controller applies, written once. A one-way platform (a
//! one-way tile, a ladder's top, a one-way moving platform) blocks a move only for a character
//! whose feet started at or above its top, within the controller's own tolerance, that is not
//! on a ladder and not dropping through that platform. The seed states it ("collide y only if
//! previously *entirely* above platform") and warns against the simpler "collide only if
//! falling", which snaps a character that starts falling mid-jump inside the platform onto its
//! top.
//!
//! The tolerance stays each controller's, because it is where that controller rests: the
//! sweep's epsilon (nothing on the integer grid), rounding for Rapier (which keeps its offset
//! above a top it stands on), and for Box2D's pogo a margin over the spring's sag below the
//! surface.

use std::ops::Sub;

/// What the one-way rule needs to know of a character at the start of a move.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OneWayCheck<T> {
    /// The feet's height at the start of the move (tiles, in the controller's coordinates).
    pub feet: T,
    /// How far below a platform's top the feet may start and still land on it (tiles): the
    /// controller's own rest tolerance.
    pub tolerance: T,
    /// Whether this move passes every one-way platform: on a ladder, or, for a controller that
    /// knows it before the move, going up or dropping through.
    pub passes_all: bool,
    /// The top of the one-way platform the character is dropping through, which it passes
    /// until the drop is over.
    pub dropping_through: Option<T>,
}

impl<T: Copy + PartialOrd + Sub<Output = T>> OneWayCheck<T> {
    /// Whether a one-way platform whose top is at `top` blocks this move.
    ///
    /// ```
    /// use platbench::oneway::OneWayCheck;
    ///
    /// let standing = OneWayCheck { feet: 3.0, tolerance: 1e-3, passes_all: false, dropping_through: None };
    /// assert!(standing.blocks(3.0), "feet on the top: it holds");
    /// assert!(!standing.blocks(3.5), "feet below the top: jumping up through it");
    /// let dropping = OneWayCheck { dropping_through: Some(3.0), ..standing };
    /// assert!(!dropping.blocks(3.0));
    /// ```
    pub fn blocks(&self, top: T) -> bool {
        !self.passes_all && self.dropping_through != Some(top) && self.feet >= top - self.tolerance
    }
}

/// A drop through a one-way platform, the other half of the rule: the drop input on one-way
/// ground starts one through the platform stood on (`one_way_ground`, its top), which the
/// character then passes ([`OneWayCheck::dropping_through`]) until [`drop_over`].
pub fn drop_start<T: Copy>(
    drop: Option<T>,
    drop_input: bool,
    one_way_ground: Option<T>,
) -> Option<T> {
    if drop_input {
        one_way_ground
    } else {
        drop
    }
}

/// The drop after a step that left the character's head (its box's top) at `head`: over once
/// the head is below the platform's top, so the character is entirely under it.
pub fn drop_over<T: Copy + PartialOrd>(drop: Option<T>, head: T) -> Option<T> {
    drop.filter(|top| head.partial_cmp(top) != Some(std::cmp::Ordering::Less))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tolerance_reaches_below_the_top_and_no_further() {
        let c = |feet: f32| OneWayCheck {
            feet,
            tolerance: 0.1,
            passes_all: false,
            dropping_through: None,
        };
        assert!(c(2.95).blocks(3.0));
        assert!(c(2.9).blocks(3.0), "exactly at the tolerance");
        assert!(!c(2.89).blocks(3.0));
        assert!(
            !c(f32::NAN).blocks(3.0),
            "a non-finite character blocks on nothing"
        );
        let ladder = OneWayCheck {
            passes_all: true,
            ..c(3.0)
        };
        assert!(!ladder.blocks(3.0));
        // A drop passes only the platform it started on.
        let drop = OneWayCheck {
            dropping_through: Some(3.0),
            ..c(5.0)
        };
        assert!(drop.blocks(5.0));
    }

    #[test]
    fn a_drop_starts_on_one_way_ground_and_ends_below_the_top() {
        assert_eq!(drop_start(None, true, Some(3.0)), Some(3.0));
        assert_eq!(drop_start(Some(3.0), false, None), Some(3.0), "it lasts");
        assert_eq!(
            drop_start::<f32>(None, true, None),
            None,
            "not on one-way ground"
        );
        assert_eq!(
            drop_over(Some(3.0), 3.5),
            Some(3.0),
            "the head is still above"
        );
        assert_eq!(drop_over(Some(3.0), 2.9), None);
    }
}
