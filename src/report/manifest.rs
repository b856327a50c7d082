//! A baseline's manifest (`manifest.toml` in the baseline directory): what the baseline holds
//! and how it was made — the selection it ran (so that `platbench check` runs the same one), the
//! configurations and levels it covers (each level with a hash of its text), and the versions
//! of platbench and of the key dependencies it was written with.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

/// The manifest's file name inside a baseline directory.
pub(crate) const FILE: &str = "manifest.toml";

/// The format this build writes and reads.
const FORMAT: u32 = 1;

/// The dependencies whose versions the manifest records: the physics a baseline depends on.
const KEY_DEPENDENCIES: &[&str] = &[
    "rapier2d",
    "rapier2d-f64",
    "parry2d",
    "parry2d-f64",
    "boxdd",
    "glam",
];

/// Why a manifest could not be read or written.
#[derive(Debug, thiserror::Error)]
pub(crate) enum ManifestError {
    /// The file is missing or unreadable.
    #[error("cannot read the baseline manifest {path}: {cause} (a baseline written by `platbench baseline` or `platbench run --bless` holds one; write the baseline again with this platbench)")]
    Read {
        /// The file.
        path: PathBuf,
        /// The cause (in the message, not chained, so that it is said once).
        cause: std::io::Error,
    },
    /// The baseline given is a file.
    #[error("the baseline {path} is a file, not a directory; expected a baseline directory (written by `platbench baseline` or `platbench run --bless`)")]
    NotADirectory {
        /// The file.
        path: PathBuf,
    },
    /// The file is not a manifest this build reads.
    #[error("{path} is not a baseline manifest this platbench reads: {why}")]
    Malformed {
        /// The file.
        path: PathBuf,
        /// What was wrong, with the line.
        why: String,
    },
    /// The manifest could not be written.
    #[error("cannot write {path}: {why}")]
    Write {
        /// The file.
        path: PathBuf,
        /// The cause.
        why: String,
    },
}

/// What a baseline holds and how it was made.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct Manifest {
    /// The manifest format (1).
    pub(crate) format: u32,
    /// The platbench version that wrote the baseline.
    pub(crate) platbench: String,
    /// The key dependencies' versions from the `Cargo.lock` found when the baseline was
    /// written (empty when none was found).
    #[serde(default)]
    pub(crate) dependencies: BTreeMap<String, String>,
    /// The selection the baseline ran.
    pub(crate) selection: SelectionRecord,
    /// The levels it ran, in run order.
    #[serde(default, rename = "level")]
    pub(crate) levels: Vec<LevelRecord>,
    /// The configurations it ran, in run order.
    #[serde(default, rename = "config")]
    pub(crate) configs: Vec<ConfigRecord>,
}

/// The selection options of a baseline, as given (empty: the default).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SelectionRecord {
    /// Level files, as given (relative paths from the directory platbench ran in); empty: the
    /// built-in set.
    #[serde(default)]
    pub(crate) files: Vec<String>,
    /// `--backend`.
    #[serde(default)]
    pub(crate) backends: Vec<String>,
    /// `--shape`.
    #[serde(default)]
    pub(crate) shapes: Vec<String>,
    /// `--precision`.
    #[serde(default)]
    pub(crate) precisions: Vec<String>,
    /// `--scenario`.
    #[serde(default)]
    pub(crate) scenarios: Vec<String>,
    /// `--dt`.
    #[serde(default)]
    pub(crate) dt: Option<f32>,
    /// `--epsilon`.
    #[serde(default)]
    pub(crate) epsilon: Option<f32>,
    /// `--traces`: `all`, `failing` or `none`.
    pub(crate) traces: String,
    /// `--timing`.
    #[serde(default)]
    pub(crate) timing: bool,
    /// `--layer` (map imports).
    #[serde(default)]
    pub(crate) layers: Vec<String>,
    /// `--tile-layers`.
    #[serde(default)]
    pub(crate) tile_layers: Option<String>,
    /// `--spawn`.
    #[serde(default)]
    pub(crate) spawns: Vec<String>,
    /// `--intgrid`.
    #[serde(default)]
    pub(crate) intgrid: Vec<String>,
    /// `--level` (LDtk).
    #[serde(default)]
    pub(crate) ldtk_level: Option<String>,
    /// `--edges` (map imports).
    #[serde(default)]
    pub(crate) edges: Option<String>,
    /// `--controller` (external controllers' files, as given).
    #[serde(default)]
    pub(crate) controllers: Vec<String>,
}

/// One level of a baseline.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct LevelRecord {
    /// The level's name.
    pub(crate) name: String,
    /// Where it was read from (a built-in file name or the path given).
    pub(crate) source: String,
    /// [`content_hash`] of its file's bytes.
    pub(crate) hash: String,
    /// The scenarios run on it.
    pub(crate) scenarios: Vec<String>,
}

/// One configuration of a baseline.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ConfigRecord {
    /// Backend name.
    pub(crate) backend: String,
    /// Configuration label.
    pub(crate) label: String,
}

impl Manifest {
    /// A manifest of this build's versions for `selection`, `levels` and `configs`.
    pub(crate) fn new(
        selection: SelectionRecord,
        levels: Vec<LevelRecord>,
        configs: Vec<ConfigRecord>,
    ) -> Self {
        Manifest {
            format: FORMAT,
            platbench: env!("CARGO_PKG_VERSION").to_string(),
            dependencies: current_dependencies(),
            selection,
            levels,
            configs,
        }
    }

    /// Reads `DIR/manifest.toml`.
    pub(crate) fn read(dir: &Path) -> Result<Manifest, ManifestError> {
        let path = dir.join(FILE);
        if dir.exists() && !dir.is_dir() {
            return Err(ManifestError::NotADirectory {
                path: dir.to_path_buf(),
            });
        }
        let text = crate::limits::read_text_capped(&path).map_err(|cause| ManifestError::Read {
            path: path.clone(),
            cause,
        })?;
        let m: Manifest = toml::from_str(&text).map_err(|e| ManifestError::Malformed {
            path: path.clone(),
            why: e.to_string().trim().replace('\n', " "),
        })?;
        if m.format != FORMAT {
            return Err(ManifestError::Malformed {
                path,
                why: format!(
                    "format {} (this platbench reads format {FORMAT}); write the baseline again",
                    m.format
                ),
            });
        }
        if !["all", "failing", "none"].contains(&m.selection.traces.as_str()) {
            return Err(ManifestError::Malformed {
                path,
                why: format!(
                    "selection.traces = {:?}; expected \"all\", \"failing\" or \"none\"",
                    m.selection.traces
                ),
            });
        }
        Ok(m)
    }

    /// Writes `DIR/manifest.toml`.
    pub(crate) fn write(&self, dir: &Path) -> Result<(), ManifestError> {
        let path = dir.join(FILE);
        let text = toml::to_string(self).map_err(|e| ManifestError::Write {
            path: path.clone(),
            why: e.to_string(),
        })?;
        let text = format!(
            "# What this platbench baseline holds and how it was made: written by `platbench baseline`\n# (or `run --bless`), read by `platbench check`. Do not edit: write the baseline again.\n{text}"
        );
        std::fs::write(&path, text).map_err(|e| ManifestError::Write {
            path,
            why: e.to_string(),
        })
    }

    /// How this build's versions differ from the manifest's, one line each (empty: they agree,
    /// or this build found no `Cargo.lock` to compare the dependencies with).
    pub(crate) fn version_changes(&self) -> Vec<String> {
        let mut out = Vec::new();
        let now = env!("CARGO_PKG_VERSION");
        if self.platbench != now {
            out.push(format!(
                "platbench {} wrote the baseline; this is platbench {now}",
                self.platbench
            ));
        }
        let deps = current_dependencies();
        if deps.is_empty() {
            return out;
        }
        for name in KEY_DEPENDENCIES {
            let (was, is) = (self.dependencies.get(*name), deps.get(*name));
            if was != is {
                let show = |v: Option<&String>| v.map_or("absent".to_string(), |v| v.clone());
                out.push(format!(
                    "{name}: {} in the baseline, {} now",
                    show(was),
                    show(is)
                ));
            }
        }
        out
    }
}

/// A hash of `bytes` for telling a changed file: FNV-1a, 64 bits, as `fnv1a64:<hex>`.
pub(crate) fn content_hash(bytes: &[u8]) -> String {
    format!(
        "fnv1a64:{:016x}",
        crate::input::fnv1a64(bytes.iter().copied())
    )
}

/// The `Cargo.lock` the running program was most likely built from: the nearest one at or
/// above `CARGO_MANIFEST_DIR` (which `cargo run` sets), else at or above the current directory.
fn find_lockfile() -> Option<PathBuf> {
    let starts = [
        std::env::var_os("CARGO_MANIFEST_DIR").map(PathBuf::from),
        std::env::current_dir().ok(),
    ];
    starts.into_iter().flatten().find_map(|dir| {
        dir.ancestors()
            .map(|d| d.join("Cargo.lock"))
            .find(|p| p.is_file())
    })
}

/// The key dependencies' versions in the `Cargo.lock` of [`find_lockfile`] (several versions of
/// one package joined by `, `); empty when there is none or it does not parse.
pub(crate) fn current_dependencies() -> BTreeMap<String, String> {
    #[derive(Deserialize)]
    struct Lock {
        #[serde(default)]
        package: Vec<Package>,
    }
    #[derive(Deserialize)]
    struct Package {
        name: String,
        version: String,
    }
    let mut out: BTreeMap<String, String> = BTreeMap::new();
    let Some(text) = find_lockfile().and_then(|p| crate::limits::read_text_capped(&p).ok()) else {
        return out;
    };
    let Ok(lock) = toml::from_str::<Lock>(&text) else {
        return out;
    };
    for p in lock.package {
        if KEY_DEPENDENCIES.contains(&p.name.as_str()) {
            out.entry(p.name)
                .and_modify(|v| {
                    v.push_str(", ");
                    v.push_str(&p.version);
                })
                .or_insert(p.version);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_manifest_round_trips_and_a_bad_one_names_its_file() {
        let dir = tempfile::tempdir().unwrap();
        let m = Manifest::new(
            SelectionRecord {
                backends: vec!["sweep".into()],
                dt: Some(1.0 / 60.0),
                traces: "failing".into(),
                ..Default::default()
            },
            vec![LevelRecord {
                name: "plain".into(),
                source: "plain.toml".into(),
                hash: content_hash(b"x"),
                scenarios: vec!["drop".into()],
            }],
            vec![ConfigRecord {
                backend: "sweep".into(),
                label: "default".into(),
            }],
        );
        m.write(dir.path()).unwrap();
        assert_eq!(Manifest::read(dir.path()).unwrap(), m);
        assert!(m.version_changes().is_empty());
        std::fs::write(dir.path().join(FILE), "format = 1\nplatbench = 3\n").unwrap();
        let e = Manifest::read(dir.path()).unwrap_err().to_string();
        assert!(e.contains("manifest.toml"), "{e}");
        let e = Manifest::read(&dir.path().join("nowhere"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("manifest.toml"), "{e}");
    }

    #[test]
    fn the_hash_tells_bytes_apart() {
        assert_eq!(content_hash(b""), "fnv1a64:cbf29ce484222325");
        assert_ne!(content_hash(b"a"), content_hash(b"b"));
    }
}
