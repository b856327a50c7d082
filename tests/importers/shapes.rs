//! Tile collision shapes other than one full-tile rectangle or one ramp (src/level/tiled/approx.rs):
//! each approximated by the nearest solid tile, flat box, ramp or empty tile, with a warning
//! naming the tile and the approximation. The shapes are written for these tests.
#![cfg(all(feature = "tiled", feature = "ldtk"))]

use platbench::level::{Slope, Tile};

use super::tiled::{row0, MapText};

/// Tile 0 of the tileset with `objects` as its collision shape, drawn at cell (1, 0).
fn read(objects: &str) -> (Tile, Vec<String>) {
    let tiles =
        format!(r#"<tile id="0"><objectgroup draworder="index">{objects}</objectgroup></tile>"#);
    let i = MapText {
        tiles: &tiles,
        rows: &["0,0,0", "0,1,0"],
        ..MapText::default()
    }
    .import()
    .unwrap();
    let notes = i
        .warnings
        .iter()
        .filter(|w| w.subject.contains("tile 0"))
        .map(|w| w.message.clone())
        .collect();
    (row0(&i.level)[1], notes)
}

fn flat(h: f32) -> Tile {
    Tile::Slope(Slope::Line { left: h, right: h })
}

#[test]
fn a_box_over_part_of_the_tile_is_a_flat_box_or_a_solid_tile() {
    // The bottom half (y 8 to 16 px of a 16 px tile): a box half a tile high.
    let (t, notes) = read(r#"<object id="1" x="0" y="8" width="16" height="8"/>"#);
    assert_eq!(t, flat(0.5));
    assert!(notes[0].contains("flat box 0.5 tile high"), "{notes:?}");
    // Its top 2 px below the tile's top (within the quarter tile TOP_SNAP allows): solid.
    let (t, notes) = read(r#"<object id="1" x="1" y="2" width="14" height="14"/>"#);
    assert_eq!(t, Tile::Solid);
    assert!(
        notes[0].contains("approximated as a solid tile"),
        "{notes:?}"
    );
    // A post 4 px wide: less than half the tile's width (MIN_WIDTH), nothing rests on it.
    let (t, notes) = read(r#"<object id="1" x="0" y="0" width="4" height="16"/>"#);
    assert_eq!(t, Tile::Empty);
    assert!(notes[0].contains("approximated as empty"), "{notes:?}");
}

#[test]
fn several_shapes_an_ellipse_and_a_polyline_are_read_by_their_extent() {
    // Two half-tile rectangles side by side make the whole tile.
    let (t, notes) = read(
        r#"<object id="1" x="0" y="0" width="8" height="16"/><object id="2" x="8" y="0" width="8" height="16"/>"#,
    );
    assert_eq!(t, Tile::Solid);
    assert!(notes[0].contains("2 objects"), "{notes:?}");
    let (t, _) = read(r#"<object id="1" x="0" y="0" width="16" height="16"><ellipse/></object>"#);
    assert_eq!(t, Tile::Solid);
    // A polyline across the tile 6 px below its top: a surface, read as a box under it.
    let (t, notes) = read(r#"<object id="1" x="0" y="6"><polyline points="0,0 16,0"/></object>"#);
    assert_eq!(t, flat(0.625));
    assert!(notes[0].contains("a polyline"), "{notes:?}");
}

#[test]
fn a_polygon_that_is_almost_a_ramp_is_the_ramp_through_its_ends() {
    // A ramp rising to the right with a notch in its top: not a ramp, read as the line from its
    // left end's top (0) to its right end's top (1 tile).
    let (t, notes) =
        read(r#"<object id="1" x="0" y="0"><polygon points="0,16 16,16 16,0 8,10"/></object>"#);
    assert_eq!(
        t,
        Tile::Slope(Slope::Line {
            left: 0.0,
            right: 1.0
        })
    );
    assert!(notes[0].contains("approximated as a ramp"), "{notes:?}");
}
