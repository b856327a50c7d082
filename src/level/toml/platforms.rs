//! `[[platform]]` entries: a moving platform's box and its one motion (a path at a speed, a
//! sine or a circle).

use glam::Vec2;
use serde::Deserialize;
use toml::Spanned;

use crate::level::{Platform, PlatformMotion};
use crate::limits;

use super::error::{LevelError, Locator};
use super::numbers::{coord, period, ranged};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawPlatform {
    #[serde(deserialize_with = "super::exact::array")]
    rect: [f64; 4],
    #[serde(default, deserialize_with = "super::exact::opt_list")]
    path: Option<Vec<[f64; 2]>>,
    speed: Option<f64>,
    sine: Option<RawSine>,
    circle: Option<RawCircle>,
    #[serde(default)]
    one_way: bool,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSine {
    #[serde(deserialize_with = "super::exact::array")]
    amplitude: [f64; 2],
    period: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCircle {
    radius: f64,
    period: f64,
}

pub(super) fn parse_platform(
    loc: &Locator,
    p: &Spanned<RawPlatform>,
) -> Result<Platform, LevelError> {
    let span = p.span();
    let r = p.get_ref();
    let [x, y, w, h] = r.rect;
    let start = Vec2::new(
        coord(loc, &span, "rect x", x)?,
        coord(loc, &span, "rect y", y)?,
    );
    let size = Vec2::new(
        ranged(
            loc,
            &span,
            "rect width",
            w,
            (f64::MIN_POSITIVE, limits::MAX_COORD),
            "tiles",
        )?,
        ranged(
            loc,
            &span,
            "rect height",
            h,
            (f64::MIN_POSITIVE, limits::MAX_COORD),
            "tiles",
        )?,
    );
    let kinds = r.path.is_some() as u8 + r.sine.is_some() as u8 + r.circle.is_some() as u8;
    if kinds != 1 {
        return Err(loc.at(
            &span,
            format!("a platform needs exactly one motion: `path` with `speed`, `sine` or `circle` (found {kinds})"),
        ));
    }
    let motion = if let Some(path) = &r.path {
        let speed = r
            .speed
            .ok_or_else(|| loc.at(&span, "a platform with a `path` needs a `speed` (tiles/s)"))?;
        let speed = ranged(
            loc,
            &span,
            "speed",
            speed,
            (f64::MIN_POSITIVE, limits::MAX_SPEED),
            "tiles/s",
        )?;
        if path.len() > limits::MAX_PATH_POINTS {
            return Err(loc.at(
                &span,
                format!(
                    "the platform path has {} waypoints; expected at most {}",
                    path.len(),
                    limits::MAX_PATH_POINTS
                ),
            ));
        }
        let mut points = Vec::with_capacity(path.len());
        for [px, py] in path {
            points.push(Vec2::new(
                coord(loc, &span, "path x", *px)?,
                coord(loc, &span, "path y", *py)?,
            ));
        }
        if points.len() < 2 {
            return Err(loc.at(
                &span,
                format!(
                    "a platform path needs at least 2 waypoints, found {}",
                    points.len()
                ),
            ));
        }
        if points[0] != start {
            return Err(loc.at(
                &span,
                format!("the path starts at ({}, {}) but rect starts at ({}, {}); expected the first waypoint to be the rect's corner", points[0].x, points[0].y, start.x, start.y),
            ));
        }
        if points.windows(2).all(|w| w[0] == w[1]) {
            return Err(loc.at(
                &span,
                "the platform path has zero length; expected waypoints that differ",
            ));
        }
        PlatformMotion::Waypoints { points, speed }
    } else if let Some(s) = &r.sine {
        let [ax, ay] = s.amplitude;
        PlatformMotion::Sine {
            amplitude: Vec2::new(
                coord(loc, &span, "sine amplitude", ax)?,
                coord(loc, &span, "sine amplitude", ay)?,
            ),
            period: period(loc, &span, "sine period", s.period)?,
        }
    } else {
        let c = r
            .circle
            .as_ref()
            .ok_or_else(|| loc.at(&span, "missing motion"))?;
        PlatformMotion::Circle {
            radius: ranged(
                loc,
                &span,
                "circle radius",
                c.radius,
                (f64::MIN_POSITIVE, limits::MAX_COORD),
                "tiles",
            )?,
            period: period(loc, &span, "circle period", c.period)?,
        }
    };
    Ok(Platform {
        start,
        size,
        motion,
        one_way: r.one_way,
    })
}
