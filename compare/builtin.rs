//! The built-in level set, embedded in the binary so that `platbench` runs with no files.

/// `(file name, TOML text)` of every built-in level, in run order.
pub const LEVELS: &[(&str, &str)] = &[
    ("flat_seams.toml", include_str!("levels/flat_seams.toml")),
    ("drops.toml", include_str!("levels/drops.toml")),
    ("jumps.toml", include_str!("levels/jumps.toml")),
    ("corridor.toml", include_str!("levels/corridor.toml")),
    ("thin_wall.toml", include_str!("levels/thin_wall.toml")),
    ("slope_22_5.toml", include_str!("levels/slope_22_5.toml")),
    ("slope_26_6.toml", include_str!("levels/slope_26_6.toml")),
    ("slope_45.toml", include_str!("levels/slope_45.toml")),
    ("slope_63_4.toml", include_str!("levels/slope_63_4.toml")),
    ("seed_tile.toml", include_str!("levels/seed_tile.toml")),
    ("oneway.toml", include_str!("levels/oneway.toml")),
    ("ladders.toml", include_str!("levels/ladders.toml")),
    ("platforms.toml", include_str!("levels/platforms.toml")),
    ("moving_wall.toml", include_str!("levels/moving_wall.toml")),
    ("elevator.toml", include_str!("levels/elevator.toml")),
    ("long_floor.toml", include_str!("levels/long_floor.toml")),
    (
        "very_long_floor.toml",
        include_str!("levels/very_long_floor.toml"),
    ),
];
