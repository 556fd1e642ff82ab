//! The pieces a drivable path is made of: straight lines, circular arcs and clothoids, each
//! driven forward or in reverse, and the poses along them.
//!
//! Conventions (local metres, x east, y north): a [`Pose`]'s heading is the direction the
//! machine faces, radians counter-clockwise from east (the compass bearing is
//! `π/2 − heading`). A [`Segment`]'s curvature is that of its steering, positive to the left;
//! driven a distance `s` (always positive) in gear `g` (+1 forward, −1 reverse), the machine
//! moves `g·(cos θ, sin θ)·ds` and turns `dθ = g·κ(s)·ds`, with `κ(s) = κ₀ + σ·s` (σ, the
//! sharpness, is zero on lines and arcs).
//!
//! ```
//! use furrow::path::curve::{Gear, Pose, Segment};
//! use std::f64::consts::PI;
//!
//! // A quarter circle of radius 10 m to the left, from the origin facing east.
//! let arc = Segment::arc(Pose::new(0.0, 0.0, 0.0), 10.0 * PI / 2.0, 0.1, Gear::Forward);
//! let end = arc.end();
//! assert!((end.x - 10.0).abs() < 1e-9 && (end.y - 10.0).abs() < 1e-9);
//! assert!((end.heading - PI / 2.0).abs() < 1e-12);
//! ```

use crate::geometry::PlanarHypot;
use std::f64::consts::PI;

/// Where the machine is and which way it faces.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// East, metres.
    pub x: f64,
    /// North, metres.
    pub y: f64,
    /// Heading, radians counter-clockwise from east.
    pub heading: f64,
}

impl Pose {
    /// A pose at (x, y) facing `heading` (radians counter-clockwise from east).
    pub fn new(x: f64, y: f64, heading: f64) -> Self {
        Pose { x, y, heading }
    }

    /// Distance to another pose's position, metres.
    pub fn distance(&self, o: &Pose) -> f64 {
        (self.x - o.x).planar_hypot(self.y - o.y)
    }

    /// The difference of headings `o − self` wrapped into (−π, π].
    pub fn heading_change(&self, o: &Pose) -> f64 {
        wrap(o.heading - self.heading)
    }

    /// This pose expressed in the frame of `origin` (origin at (0, 0) facing east).
    pub fn relative_to(&self, origin: &Pose) -> Pose {
        let (s, c) = origin.heading.sin_cos();
        let (dx, dy) = (self.x - origin.x, self.y - origin.y);
        Pose::new(
            c * dx + s * dy,
            -s * dx + c * dy,
            wrap(self.heading - origin.heading),
        )
    }

    /// The pose given in the frame of `origin` back in the frame `origin` is given in.
    pub fn from_frame(&self, origin: &Pose) -> Pose {
        let (s, c) = origin.heading.sin_cos();
        Pose::new(
            origin.x + c * self.x - s * self.y,
            origin.y + s * self.x + c * self.y,
            wrap(self.heading + origin.heading),
        )
    }
}

/// An angle wrapped into (−π, π].
pub fn wrap(a: f64) -> f64 {
    let mut x = a.rem_euclid(2.0 * PI);
    if x > PI {
        x -= 2.0 * PI;
    }
    x
}

/// Forward or reverse.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Gear {
    /// Driving forward.
    Forward,
    /// Reversing.
    Reverse,
}

impl Gear {
    /// +1 forward, −1 in reverse.
    pub fn sign(self) -> f64 {
        match self {
            Gear::Forward => 1.0,
            Gear::Reverse => -1.0,
        }
    }
}

/// One piece of a path: a line (κ₀ = σ = 0), an arc (σ = 0) or a clothoid, driven `length`
/// metres from `start` in `gear` (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// Where it starts.
    pub start: Pose,
    /// Distance driven along it, metres (at least zero).
    pub length: f64,
    /// Steering curvature at the start, 1/metres, positive to the left.
    pub curvature: f64,
    /// Change of curvature per metre driven (1/m²); zero on lines and arcs.
    pub sharpness: f64,
    /// Forward or reverse.
    pub gear: Gear,
}

/// Gauss-Legendre nodes and weights on [−1, 1], 8 points: exact for polynomials of degree 15;
/// on pieces of a clothoid whose heading turns by at most a radian the position is exact to
/// well under a micrometre.
#[allow(clippy::excessive_precision)]
const GAUSS: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_2, 0.101_228_536_290_376_26),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (-0.525_532_409_916_329_0, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362_0),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362_0),
    (0.525_532_409_916_329_0, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (0.960_289_856_497_536_2, 0.101_228_536_290_376_26),
];

impl Segment {
    /// A straight line.
    pub fn line(start: Pose, length: f64, gear: Gear) -> Self {
        Segment {
            start,
            length,
            curvature: 0.0,
            sharpness: 0.0,
            gear,
        }
    }

    /// A circular arc of steering curvature `curvature` (positive to the left).
    pub fn arc(start: Pose, length: f64, curvature: f64, gear: Gear) -> Self {
        Segment {
            start,
            length,
            curvature,
            sharpness: 0.0,
            gear,
        }
    }

    /// A clothoid: curvature from `curvature` changing by `sharpness` per metre.
    pub fn clothoid(start: Pose, length: f64, curvature: f64, sharpness: f64, gear: Gear) -> Self {
        Segment {
            start,
            length,
            curvature,
            sharpness,
            gear,
        }
    }

    /// Steering curvature after `s` metres.
    pub fn curvature_at(&self, s: f64) -> f64 {
        self.curvature + self.sharpness * s
    }

    /// The heading after `s` metres.
    pub fn heading_at(&self, s: f64) -> f64 {
        self.start.heading + self.gear.sign() * (self.curvature * s + 0.5 * self.sharpness * s * s)
    }

    /// The pose after `s` metres (0 ≤ s ≤ length).
    pub fn pose_at(&self, s: f64) -> Pose {
        self.poses().at(s)
    }

    /// Its poses at many distances: [`Segment::pose_at`] with the sine and cosine of the start
    /// heading found once, not at every pose.
    pub fn poses(&self) -> Poses<'_> {
        let (sin, cos) = self.start.heading.sin_cos();
        Poses {
            segment: self,
            start_sin: sin,
            start_cos: cos,
        }
    }

    /// Where it ends.
    pub fn end(&self) -> Pose {
        self.pose_at(self.length)
    }

    /// The largest steering curvature on it, in size.
    pub fn max_curvature(&self) -> f64 {
        self.curvature
            .abs()
            .max(self.curvature_at(self.length).abs())
    }
}

/// The poses along a [`Segment`], from [`Segment::poses`].
#[derive(Debug, Clone, Copy)]
pub struct Poses<'a> {
    segment: &'a Segment,
    start_sin: f64,
    start_cos: f64,
}

impl<'a> Poses<'a> {
    /// The pose after `s` metres (0 ≤ s ≤ length).
    pub fn at(&self, s: f64) -> Pose {
        let seg = self.segment;
        let g = seg.gear.sign();
        let p = seg.start;
        let heading = seg.heading_at(s);
        if seg.sharpness == 0.0 {
            let k = seg.curvature;
            if k == 0.0 {
                return Pose::new(
                    p.x + g * s * self.start_cos,
                    p.y + g * s * self.start_sin,
                    heading,
                );
            }
            if k.abs() * s < 1e-9 {
                // An arc so flat it is a line to a nanometre.
                let mid = p.heading + 0.5 * g * k * s;
                return Pose::new(p.x + g * s * mid.cos(), p.y + g * s * mid.sin(), heading);
            }
            // dθ = g·k·ds: the position is the arc's chord.
            let r = 1.0 / k;
            let (sin, cos) = heading.sin_cos();
            return Pose::new(
                p.x + r * (sin - self.start_sin),
                p.y - r * (cos - self.start_cos),
                heading,
            );
        }
        // A clothoid: integrate (cos θ, sin θ) piecewise, each piece turning under a radian.
        let turn = seg.curvature.abs() * s + 0.5 * seg.sharpness.abs() * s * s;
        let pieces = (turn.ceil() as usize)
            .clamp(1, 1000)
            .max((s / 20.0).ceil() as usize);
        let h = s / pieces as f64;
        let (mut x, mut y) = (p.x, p.y);
        for i in 0..pieces {
            let a = i as f64 * h;
            for (t, w) in GAUSS {
                let u = a + 0.5 * h * (t + 1.0);
                let th = seg.heading_at(u);
                x += g * 0.5 * h * w * th.cos();
                y += g * 0.5 * h * w * th.sin();
            }
        }
        Pose::new(x, y, heading)
    }

    /// The poses at `n + 1` even steps along `length` metres, from the start: those of
    /// [`Poses::at`] at `length * i / n`. On an arc the sine and cosine of each heading come
    /// from the last ones turned by the step's angle (found once), every
    /// [`EXACT_EVERY`]th afresh, which keeps them within a few units in the last place of
    /// `at`'s: a path's chord points and samples without a sine and a cosine at each.
    ///
    /// ```
    /// use furrow::path::curve::{Gear, Pose, Segment};
    ///
    /// let arc = Segment::arc(Pose::new(0.0, 0.0, 0.3), 40.0, 1.0 / 6.0, Gear::Forward);
    /// let poses = arc.poses();
    /// for (i, p) in poses.evenly(40.0, 80).enumerate() {
    ///     let q = poses.at(40.0 * i as f64 / 80.0);
    ///     assert!(p.distance(&q) < 1e-12 && (p.heading - q.heading).abs() < 1e-15);
    /// }
    /// ```
    pub fn evenly(self, length: f64, n: usize) -> impl Iterator<Item = Pose> + 'a {
        let n = n.max(1);
        let seg = self.segment;
        let k = seg.curvature;
        // The step's sine and cosine, where the poses are those of a true arc.
        let rotation =
            (seg.sharpness == 0.0 && k != 0.0 && (k * length).abs() >= 1e-9).then(|| {
                let delta = seg.gear.sign() * k * (length / n as f64);
                delta.sin_cos()
            });
        let mut trig = (self.start_sin, self.start_cos);
        (0..=n).map(move |i| {
            let s = length * i as f64 / n as f64;
            let Some((sin_d, cos_d)) = rotation else {
                return self.at(s);
            };
            let heading = seg.heading_at(s);
            if i > 0 {
                trig = if i % EXACT_EVERY == 0 {
                    heading.sin_cos()
                } else {
                    let (sin, cos) = trig;
                    (sin * cos_d + cos * sin_d, cos * cos_d - sin * sin_d)
                };
            }
            let (sin, cos) = trig;
            let r = 1.0 / k;
            Pose::new(
                seg.start.x + r * (sin - self.start_sin),
                seg.start.y - r * (cos - self.start_cos),
                heading,
            )
        })
    }
}

/// How often [`Poses::evenly`] finds a heading's sine and cosine afresh.
pub const EXACT_EVERY: usize = 32;

/// Total length of a run of segments, metres.
pub fn length(segments: &[Segment]) -> f64 {
    segments.iter().map(|s| s.length).sum()
}

/// Where a run of segments ends (`None` if there are none).
pub fn end(segments: &[Segment]) -> Option<Pose> {
    segments.last().map(Segment::end)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reversing_on_an_arc_moves_backwards_and_turns_the_other_way() {
        // Steering left while reversing from the origin facing east: the machine circles the
        // centre 5 m to its left clockwise, moving west, and comes to face south.
        let s = Segment::arc(Pose::new(0.0, 0.0, 0.0), 5.0 * PI / 2.0, 0.2, Gear::Reverse);
        let e = s.end();
        assert!((e.x + 5.0).abs() < 1e-9, "{e:?}");
        assert!((e.y - 5.0).abs() < 1e-9, "{e:?}");
        assert!((e.heading + PI / 2.0).abs() < 1e-12);
    }

    #[test]
    fn a_clothoid_matches_its_fresnel_integral() {
        // κ = s/A²: from a straight start, after s = A·√(2t) the heading is t; with A = 10 and
        // s = 10·√π the position is A·√π·(C(1), S(1)) in Fresnel's normalised integrals.
        let a: f64 = 10.0;
        let s = a * PI.sqrt();
        let c = Segment::clothoid(
            Pose::new(0.0, 0.0, 0.0),
            s,
            0.0,
            1.0 / (a * a),
            Gear::Forward,
        );
        let e = c.end();
        let k = a * PI.sqrt();
        // C(1) = 0.779893400376823, S(1) = 0.438259147390355 (normalised: ∫cos(πt²/2)).
        assert!((e.x - k * 0.779_893_400_376_823).abs() < 1e-9, "{e:?}");
        assert!((e.y - k * 0.438_259_147_390_355).abs() < 1e-9, "{e:?}");
        assert!((e.heading - PI / 2.0).abs() < 1e-12);
    }

    #[test]
    fn even_poses_are_those_at_their_distances() {
        let start = Pose::new(12.0, -7.0, 2.9);
        let mut segments = Vec::new();
        for gear in [Gear::Forward, Gear::Reverse] {
            for k in [1.0f64 / 6.0, -1.0 / 9.0, 1e-4] {
                // Three times round (far past the fresh sines every EXACT_EVERY poses).
                segments.push(Segment::arc(start, 6.0 * PI / k.abs(), k, gear));
            }
            segments.push(Segment::arc(start, 30.0, 0.0, gear));
            segments.push(Segment::clothoid(start, 8.0, 0.05, 0.01, gear));
        }
        for seg in &segments {
            for n in [1, 7, EXACT_EVERY, 1000] {
                let poses = seg.poses();
                let even: Vec<Pose> = poses.evenly(seg.length, n).collect();
                assert_eq!(even.len(), n + 1);
                for (i, p) in even.iter().enumerate() {
                    let q = poses.at(seg.length * i as f64 / n as f64);
                    // Lines and clothoids are `at` itself; arcs within rounding (a metre is
                    // 1e-16 m in the last place; a thousand turned steps, a few hundred units).
                    let exact = seg.curvature == 0.0 || seg.sharpness != 0.0;
                    let tolerance = if exact { 0.0 } else { 1e-9 };
                    assert!(
                        p.distance(&q) <= tolerance && p.heading == q.heading,
                        "{seg:?} n {n} i {i}: {p:?} {q:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn poses_move_between_frames_and_back() {
        let origin = Pose::new(3.0, -2.0, 0.7);
        let p = Pose::new(10.0, 4.0, -2.5);
        let q = p.relative_to(&origin).from_frame(&origin);
        assert!(p.distance(&q) < 1e-12 && p.heading_change(&q).abs() < 1e-12);
    }
}
