//! What the repository says stays true: README and docs/ numbers produced by the tests and commands they name, and the library's layers (ARCHITECTURE.md).

#[path = "../common/mod.rs"]
mod common;

mod architecture;
mod ci_recipe;
mod readme;
