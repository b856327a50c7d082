//! The report's colours: each backend is a colour family (the hue of its chart colour,
//! [`crate::registry::Registry::colour`]), and each of its configurations a shade of that family,
//! so that a reader tells the controllers apart at a glance and the configurations of one
//! controller apart within it. A plugged-in controller gets a family of its own too (the
//! registry hands it a chart colour no built-in kind has, and its shades keep that hue), so it
//! never wears a built-in configuration's colour.

/// How a configuration appears in every picture: its key `(backend, config label)` and colour.
#[derive(Clone, Debug, PartialEq)]
pub struct Style {
    /// Backend name.
    pub backend: String,
    /// Configuration label.
    pub config: String,
    /// CSS colour.
    pub colour: String,
}

/// A colour as hue (degrees), saturation and lightness (0 to 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Hsl {
    pub h: f32,
    pub s: f32,
    pub l: f32,
}

/// `#rrggbb` as HSL; `None` for anything else.
pub(crate) fn parse_hex(c: &str) -> Option<Hsl> {
    let hex = c.strip_prefix('#').filter(|h| h.len() == 6)?;
    let byte = |i: usize| u8::from_str_radix(hex.get(i..i + 2)?, 16).ok();
    let (r, g, b) = (
        byte(0)? as f32 / 255.0,
        byte(2)? as f32 / 255.0,
        byte(4)? as f32 / 255.0,
    );
    let (max, min) = (r.max(g).max(b), r.min(g).min(b));
    let l = (max + min) / 2.0;
    let d = max - min;
    if d == 0.0 {
        return Some(Hsl { h: 0.0, s: 0.0, l });
    }
    let s = d / (1.0 - (2.0 * l - 1.0).abs());
    let h = if max == r {
        60.0 * ((g - b) / d).rem_euclid(6.0)
    } else if max == g {
        60.0 * ((b - r) / d + 2.0)
    } else {
        60.0 * ((r - g) / d + 4.0)
    };
    Some(Hsl { h, s, l })
}

/// HSL as `#rrggbb`.
pub(crate) fn to_hex(c: Hsl) -> String {
    let h = c.h.rem_euclid(360.0);
    let chroma = (1.0 - (2.0 * c.l - 1.0).abs()) * c.s;
    let x = chroma * (1.0 - ((h / 60.0).rem_euclid(2.0) - 1.0).abs());
    let m = c.l - chroma / 2.0;
    let (r, g, b) = match (h / 60.0) as u32 {
        0 => (chroma, x, 0.0),
        1 => (x, chroma, 0.0),
        2 => (0.0, chroma, x),
        3 => (0.0, x, chroma),
        4 => (x, 0.0, chroma),
        _ => (chroma, 0.0, x),
    };
    let byte = |v: f32| ((v + m).clamp(0.0, 1.0) * 255.0).round() as u8;
    format!("#{:02x}{:02x}{:02x}", byte(r), byte(g), byte(b))
}

/// The distance between two hues, in degrees (0 to 180).
pub(crate) fn hue_distance(a: f32, b: f32) -> f32 {
    let d = (a - b).rem_euclid(360.0);
    d.min(360.0 - d)
}

/// How far a shade's hue strays from its family's, at most, in degrees; less when another
/// family's hue is near (a shade stays nearer its own family's hue than the other's, by a third
/// of the gap). 15 degrees keeps a shade of Rapier's green green, not yellow or teal.
const MAX_HUE_SPREAD: f32 = 15.0;

/// The lightnesses of a family's shades, darker and lighter in turn, within the range where a
/// line of 1.5 px still shows on the light background (0.2 to 0.6).
const LIGHTNESS: [f32; 6] = [0.2, 0.52, 0.36, 0.6, 0.28, 0.44];

/// How far apart in lightness two shades of one hue are at least: 0.06 is about the step the
/// eye still tells apart between two small swatches.
const MIN_LIGHTNESS_STEP: f32 = 0.06;

/// The style of every configuration in `configs` (`(backend, config label)`, in run order). A
/// backend's family is its chart colour ([`crate::registry::Registry::colour`]); its first
/// configuration drawn in that colour by its kind ([`crate::controller::BackendKind::drawn`])
/// wears it, a colour its kind draws another configuration in is kept when it is of the family
/// (its hue within the family's spread), and every other configuration gets the next shade of
/// the family no configuration wears yet.
pub fn styles(registry: &crate::registry::Registry, configs: &[(String, String)]) -> Vec<Style> {
    let drawn = registry.drawn();
    let mut backends: Vec<&str> = Vec::new();
    for (b, _) in configs {
        if !backends.contains(&b.as_str()) {
            backends.push(b);
        }
    }
    let base = |b: &str| {
        parse_hex(registry.colour(b)).unwrap_or(Hsl {
            h: 0.0,
            s: 0.0,
            l: 0.45,
        })
    };
    let mut taken: Vec<String> = Vec::new();
    let mut out: Vec<Style> = configs
        .iter()
        .map(|(b, c)| Style {
            backend: b.clone(),
            config: c.clone(),
            colour: String::new(),
        })
        .collect();
    for b in &backends {
        let family = base(b);
        // The hue gap to the nearest other family bounds this family's spread.
        let gap = backends
            .iter()
            .filter(|o| *o != b)
            .map(|o| hue_distance(base(o).h, family.h))
            .fold(180.0f32, f32::min);
        let spread = MAX_HUE_SPREAD.min(gap / 3.0);
        let own = |col: &str| {
            parse_hex(col).is_some_and(|c| hue_distance(c.h, family.h) <= spread && c.s > 0.2)
        };
        // Hue: the family's, then a step either side; lightness: LIGHTNESS in turn.
        let mut shades = [0.0, -1.0, 1.0].into_iter().flat_map(|step| {
            LIGHTNESS.iter().map(move |&l| Hsl {
                h: family.h + step * spread,
                s: family.s.max(0.35),
                l,
            })
        });
        // A shade too near a colour the family already wears (same hue step, close lightness).
        let near = |a: Hsl, taken: &[String]| {
            taken.iter().filter_map(|t| parse_hex(t)).any(|t| {
                hue_distance(a.h, t.h) < spread / 2.0 + 1.0
                    && (a.l - t.l).abs() < MIN_LIGHTNESS_STEP
            })
        };
        let family_hex = to_hex(family);
        for (i, (cb, c)) in configs.iter().enumerate() {
            if cb != b {
                continue;
            }
            let declared = drawn
                .iter()
                .find(|(db, dc, _)| db == cb && dc == c)
                .map(|(_, _, col)| col.to_string());
            let colour = match declared {
                Some(col) if own(&col) && !taken.contains(&col) => col,
                _ if !taken.contains(&family_hex) => family_hex.clone(),
                _ => shades
                    .by_ref()
                    .find(|s| !near(*s, &taken))
                    .map(to_hex)
                    .unwrap_or_else(|| family_hex.clone()),
            };
            taken.push(colour.clone());
            out[i].colour = colour;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backend::{BackendError, CharacterId, CharacterState};
    use crate::config::RunConfig;
    use crate::controller::{Controller, Setup};
    use crate::level::Features;
    use crate::motion::Input;
    use crate::registry::Registry;

    /// A plugged-in controller with two configurations and no colours of its own.
    #[derive(Clone, Debug, Default, PartialEq)]
    struct Toy;

    impl Controller for Toy {
        type Mover = ();
        const NAME: &'static str = "toy";
        fn features(&self) -> Features {
            Features::NONE
        }
        fn build(&self, _: Setup<'_>) -> Result<(), BackendError> {
            Ok(())
        }
        fn step(&self, _: &mut (), _: &[Input], _: f32) {}
        fn state(&self, _: &(), _: CharacterId) -> CharacterState {
            CharacterState::default()
        }
        fn configs() -> Vec<RunConfig> {
            vec![RunConfig::new("default", Toy), RunConfig::new("other", Toy)]
        }
    }

    #[test]
    fn colours_round_trip() {
        for c in ["#1565c0", "#2e7d32", "#00838f", "#6a1b9a", "#757575"] {
            assert_eq!(to_hex(parse_hex(c).unwrap()), c);
        }
        assert_eq!(parse_hex("red"), None);
    }

    #[test]
    fn a_plugged_in_controller_is_a_family_of_its_own() {
        let reg = Registry::builtin().with::<Toy>();
        let configs: Vec<(String, String)> = reg
            .builtin_configs()
            .iter()
            .map(|r| (r.backend.backend().to_string(), r.label.clone()))
            .collect();
        assert!(configs.iter().any(|(b, _)| b == "toy"), "{configs:?}");
        let s = styles(&reg, &configs);
        // Every configuration has a colour of its own.
        for (i, a) in s.iter().enumerate() {
            for b in &s[i + 1..] {
                assert_ne!(a.colour, b.colour, "{a:?} {b:?}");
            }
        }
        let hue = |c: &str| parse_hex(c).unwrap().h;
        let toy_chart = reg.colour("toy");
        for other in s.iter().filter(|st| st.backend != "toy") {
            // The toy's chart colour is no other backend's configuration colour...
            assert_ne!(other.colour, toy_chart, "{other:?}");
            // ...nor near one: each of its shades is at least 30 degrees of hue from every other
            // backend's configuration (the toy's purple is 77 degrees from the sweep's blue, the
            // nearest built-in family; shades stray 15 at most; 30 tells hues apart at a glance).
            for toy in s.iter().filter(|st| st.backend == "toy") {
                let d = hue_distance(hue(&toy.colour), hue(&other.colour));
                assert!(d >= 30.0, "{toy:?} {other:?} {d}");
            }
        }
        // The built-in families keep their kinds' chart colours for their first configuration
        // (those this build has: without the default features, the sweep alone).
        for b in ["sweep", "rapier", "box2d"] {
            let Some(first) = s.iter().find(|st| st.backend == b) else {
                assert_ne!(b, "sweep", "the sweep is always built");
                continue;
            };
            assert_eq!(first.colour, reg.colour(b), "{first:?}");
        }
    }
}
