//! Each controller set up as its own docs advise and held to its own documented promises: Rapier against its reference figures and its own tests, Box2D's mover, the move-and-slide example, a user's controller through the public API, and the registry.

#[path = "../common/mod.rs"]
mod common;

mod box2d;
mod box2d_advised;
mod box2d_far;
mod box_mover;
mod move_and_slide;
mod rapier_builtin;
mod rapier_descending_carry;
mod rapier_feeds;
mod rapier_own_tests;
mod rapier_reference;
mod rapier_setup;
mod rapier_slope_polygons;
mod rapier_steep_slope_left;
mod registry;
