//! Nothing crashes, hangs or is lost on hostile input, and properties that hold for any input.

#[path = "../common/mod.rs"]
mod common;

mod crashes;
mod hostile;
mod hostile_inputs;
mod ldtk_values;
mod located;
mod memory;
mod properties;
mod proportional;
mod streamed;
mod streamed_runs;
mod tiled_xml;
mod worded;
