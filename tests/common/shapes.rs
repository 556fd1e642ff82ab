//! Smooth outlines as a GNSS receiver records them (discs, circular segments, bays, S-bends),
//! sampled densely, for the property tests of ring cleaning, simplification and the no-panic
//! runs.
#![allow(dead_code)]

use geo::Coord;
use proptest::prelude::*;
use std::f64::consts::{PI, TAU};

/// Most vertices a generated outline has, so that a case takes a fraction of a second.
pub const MAX_POINTS: f64 = 40_000.0;

/// A smooth outline in local metres, counter-clockwise, not closed.
#[derive(Debug, Clone, Copy)]
pub enum Shape {
    /// A disc of this radius.
    Disc { radius: f64 },
    /// A circular segment: an arc of `radius` over `2 * half_angle`, closed by its chord.
    Arc { radius: f64, half_angle: f64 },
    /// A square of `side` with a round bay of `radius` cut from the middle of its southern edge.
    Bay { side: f64, radius: f64 },
    /// A strip of `width` along a sine wave of `wavelength` (amplitude an eighth of it), two
    /// wavelengths long: an S-bend and back.
    SBend { wavelength: f64, width: f64 },
}

impl Shape {
    /// The outline with a vertex every `spacing` metres or so (fewer where that would exceed
    /// [`MAX_POINTS`]).
    pub fn outline(self, spacing: f64) -> Vec<Coord> {
        self.outline_within(spacing, MAX_POINTS)
    }

    /// The outline with a vertex every `spacing` metres or so, at most `max_points` of them.
    pub fn outline_within(self, spacing: f64, max_points: f64) -> Vec<Coord> {
        let spacing = spacing.max(self.perimeter() / max_points);
        match self {
            Shape::Disc { radius } => arc(Coord::zero(), radius, 0.0, TAU, spacing, false),
            Shape::Arc { radius, half_angle } => {
                let mut pts = arc(
                    Coord::zero(),
                    radius,
                    -half_angle,
                    half_angle,
                    spacing,
                    true,
                );
                let (a, b) = (pts[pts.len() - 1], pts[0]);
                pts.extend(segment(a, b, spacing));
                pts
            }
            Shape::Bay { side, radius } => {
                let m = side / 2.0;
                let c = |x, y| Coord { x, y };
                let mut pts = segment(c(0.0, 0.0), c(m - radius, 0.0), spacing);
                // Round the bay clockwise about its centre: the field runs on counter-clockwise.
                let mut bay = arc(c(m, 0.0), radius, 0.0, PI, spacing, true);
                bay.reverse();
                bay.pop();
                pts.extend(bay);
                for (a, b) in [
                    (c(m + radius, 0.0), c(side, 0.0)),
                    (c(side, 0.0), c(side, side)),
                    (c(side, side), c(0.0, side)),
                    (c(0.0, side), c(0.0, 0.0)),
                ] {
                    pts.extend(segment(a, b, spacing));
                }
                pts
            }
            Shape::SBend { wavelength, width } => s_bend(wavelength, width, spacing),
        }
    }

    pub fn perimeter(self) -> f64 {
        match self {
            Shape::Disc { radius } => TAU * radius,
            Shape::Arc { radius, half_angle } => radius * (2.0 * half_angle + 2.0),
            Shape::Bay { side, radius } => 4.0 * side + PI * radius,
            Shape::SBend { wavelength, width } => 2.0 * (2.5 * wavelength + width),
        }
    }
}

/// Points on a circle from angle `from` to `to`, `spacing` apart (the last one included when
/// `closed_end`).
pub fn arc(c: Coord, r: f64, from: f64, to: f64, spacing: f64, closed_end: bool) -> Vec<Coord> {
    let n = ((to - from) * r / spacing).ceil().max(3.0) as usize;
    let last = if closed_end { n + 1 } else { n };
    (0..last)
        .map(|i| {
            let t = from + (to - from) * i as f64 / n as f64;
            Coord {
                x: c.x + r * t.cos(),
                y: c.y + r * t.sin(),
            }
        })
        .collect()
}

/// Points from `a` towards `b`, `spacing` apart, without `b`.
pub fn segment(a: Coord, b: Coord, spacing: f64) -> Vec<Coord> {
    let d = b - a;
    let n = ((d.x.hypot(d.y)) / spacing).ceil().max(1.0) as usize;
    (0..n).map(|i| a + d * (i as f64 / n as f64)).collect()
}

/// A strip of `width` along y = A sin(2πx/λ), A = λ/8, for x from 0 to 2λ: its left side
/// forwards, its right side back.
fn s_bend(wavelength: f64, width: f64, spacing: f64) -> Vec<Coord> {
    let amplitude = wavelength / 8.0;
    let k = TAU / wavelength;
    let length = 2.0 * wavelength;
    // Steps along x fine enough that neither side's points are farther apart than `spacing`.
    let n = (length * 1.8 / spacing).ceil() as usize;
    let side = |offset: f64| -> Vec<Coord> {
        (0..=n)
            .map(|i| {
                let x = length * i as f64 / n as f64;
                let slope = amplitude * k * (k * x).cos();
                let norm = 1.0f64.hypot(slope);
                Coord {
                    x: x - offset * slope / norm,
                    y: amplitude * (k * x).sin() + offset / norm,
                }
            })
            .collect()
    };
    // The right side runs forwards (counter-clockwise round the strip), the left side back.
    let mut pts = side(-width / 2.0);
    let mut left = side(width / 2.0);
    left.reverse();
    pts.extend(left);
    pts
}

pub fn shape() -> impl Strategy<Value = Shape> {
    prop_oneof![
        (20.0..800.0f64).prop_map(|radius| Shape::Disc { radius }),
        (20.0..600.0f64, 0.2..3.0f64)
            .prop_map(|(radius, half_angle)| Shape::Arc { radius, half_angle }),
        (100.0..800.0f64, 0.1..0.45f64).prop_map(|(side, r)| Shape::Bay {
            side,
            radius: side * r
        }),
        (60.0..600.0f64, 0.05..0.3f64).prop_map(|(wavelength, w)| Shape::SBend {
            wavelength,
            width: (wavelength * w).max(5.0),
        }),
    ]
}

/// The largest disc well inside a shape: (centre, radius).
pub fn interior_disc(shape: Shape) -> (Coord, f64) {
    let c = |x, y| Coord { x, y };
    match shape {
        Shape::Disc { radius } => (c(radius * 0.3, 0.0), radius * 0.2),
        Shape::Arc { radius, half_angle } => {
            let inner = radius * half_angle.cos().max(0.0);
            (c((inner + radius) / 2.0, 0.0), (radius - inner) / 6.0)
        }
        Shape::Bay { side, radius } => {
            (c(side / 2.0, (side + radius) / 2.0), (side - radius) / 6.0)
        }
        Shape::SBend { wavelength, width } => (c(wavelength / 2.0, 0.0), width / 6.0),
    }
}

/// Moves every point by up to `amount` metres either way (a GNSS receiver's noise), the same for
/// the same seed.
pub fn jitter(points: &mut [Coord], amount: f64, seed: u64) {
    let mut x = seed | 1;
    let mut next = || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    for p in points {
        p.x += amount * next();
        p.y += amount * next();
    }
}
