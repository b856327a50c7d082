//! The collision grid of an LDtk project: the cell size of the IntGrid layer that most surely
//! holds the collision (given a collision role, else named for collision, else not named like
//! art, else any), of those the one painting the largest area, as a game reads its collision
//! layer at its own size. Layers with cells a whole multiple as large are read onto it.

use super::json::LayerInstance;
use crate::level::import::names::role_from_name;
use crate::level::import::{ImportOptions, LayerRole};

/// How surely a layer holds the collision: 0 (a collision role given) to 4 (another role
/// given).
fn tier(l: &LayerInstance, opts: &ImportOptions) -> u8 {
    match opts.role_of(&l.identifier) {
        Some(r) if r.collides() => 0,
        Some(_) => 4,
        None => match role_from_name(&l.identifier) {
            Some((LayerRole::Collision, _)) => 1,
            Some((LayerRole::Decoration, _)) => 3,
            _ => 2,
        },
    }
}

/// The area a layer paints, in square pixels.
fn painted(l: &LayerInstance) -> u128 {
    let n = l.int_grid_csv.iter().flatten().filter(|&&v| v != 0).count()
        + l.int_grid.as_ref().map_or(0, |c| c.len());
    (n as u128) * (l.grid_size.unsigned_abs() as u128).pow(2)
}

/// The IntGrid layer whose cell size is the grid (the first of equals), if there is one.
pub(super) fn collision_layer<'a>(
    layers: impl Iterator<Item = &'a LayerInstance> + Clone,
    opts: &ImportOptions,
) -> Option<&'a LayerInstance> {
    let int_grids = layers.filter(|l| l.kind == "IntGrid");
    let best = int_grids.clone().map(|l| tier(l, opts)).min()?;
    int_grids
        .filter(|l| tier(l, opts) == best)
        .fold(None, |acc: Option<(&LayerInstance, u128)>, l| {
            let area = painted(l);
            match acc {
                Some((_, a)) if a >= area => acc,
                _ => Some((l, area)),
            }
        })
        .map(|(l, _)| l)
}
