//! Maps as the games read them: the Tiled and LDtk importers, and the level format's validation with located errors.

#[path = "../common/mod.rs"]
mod common;

mod edges;
mod evident_roles;
mod json_limits;
mod json_values;
mod ldtk;
mod limits;
mod map_problems;
mod markings;
mod shapes;
mod side_expect;
mod side_import;
mod tiled;
mod tiled_errors;
mod tiled_json;
mod tiled_runs;
mod tiled_twins;
mod tiled_written;
mod validation;
