//! Dubins shortest paths: the shortest way *forward* from one pose to another for a machine that
//! turns no tighter than a given radius (Dubins 1957).
//!
//! Every shortest such path is one of six *words* of three parts, each arc of exactly the
//! minimum radius: arc–line–arc (LSL, RSR, LSR, RSL) or three arcs (RLR, LRL), L turning left
//! and R right. The parts are solved in closed form in the usual normalised frame (Shkel &
//! Lumelsky 2001, LaValle 2006 §15.3.1): lengths divided by the radius, the goal on the x axis
//! at `d = D / r`, the start and goal headings `α`, `β` measured from the line between them.
//!
//! Driving conventions are those of [`super::curve`]: arcs are [`Segment`]s of curvature
//! `+1/r` (left) or `−1/r` (right), all in [`Gear::Forward`].
//!
//! ```
//! use furrow::path::curve::Pose;
//! use furrow::path::dubins::{dubins_all, dubins_shortest, DubinsWord};
//! use std::f64::consts::PI;
//!
//! // Straight ahead: a line (the two arcs have length zero).
//! let from = Pose::new(0.0, 0.0, 0.0);
//! let to = Pose::new(40.0, 0.0, 0.0);
//! let path = dubins_shortest(from, to, 10.0).ok_or("no path")?;
//! assert_eq!(path.word, DubinsWord::Lsl);
//! assert!((path.length() - 40.0).abs() < 1e-9);
//!
//! // Turning back on the spot, forward only, takes three arcs: 7π/3 radii.
//! let back = Pose::new(0.0, 0.0, PI);
//! let path = dubins_shortest(from, back, 1.0).ok_or("no path")?;
//! assert_eq!(path.word, DubinsWord::Rlr);
//! assert!((path.length() - 7.0 * PI / 3.0).abs() < 1e-9);
//! let end = path.end(from);
//! assert!(end.distance(&back) < 1e-9);
//!
//! // Every word that exists between two poses, each a drivable path.
//! for p in dubins_all(from, Pose::new(5.0, 3.0, 1.0), 2.0) {
//!     let segments = p.segments(from);
//!     assert_eq!(segments.len(), 3);
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use super::curve::{wrap, Gear, Pose, Segment};
use crate::geometry::PlanarHypot;
use std::f64::consts::TAU;

/// Normalised angles within this of a full turn are taken as no turn at all (they come from
/// rounding an exact zero); the path then misses its goal by at most this many radians.
const SNAP: f64 = 1e-10;

/// Normalised straight lengths under this are taken as zero when their direction is needed.
const TINY: f64 = 1e-10;

/// The six Dubins words: which way each of the three parts steers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DubinsWord {
    /// Left, straight, left.
    Lsl,
    /// Right, straight, right.
    Rsr,
    /// Left, straight, right.
    Lsr,
    /// Right, straight, left.
    Rsl,
    /// Right, left, right.
    Rlr,
    /// Left, right, left.
    Lrl,
}

impl DubinsWord {
    /// All six words, in the order ties are broken (the first wins).
    pub const ALL: [DubinsWord; 6] = [
        DubinsWord::Lsl,
        DubinsWord::Rsr,
        DubinsWord::Lsr,
        DubinsWord::Rsl,
        DubinsWord::Rlr,
        DubinsWord::Lrl,
    ];

    /// The word in capitals, e.g. `"LSL"`.
    pub fn as_str(self) -> &'static str {
        match self {
            DubinsWord::Lsl => "LSL",
            DubinsWord::Rsr => "RSR",
            DubinsWord::Lsr => "LSR",
            DubinsWord::Rsl => "RSL",
            DubinsWord::Rlr => "RLR",
            DubinsWord::Lrl => "LRL",
        }
    }

    /// Steering of each part: +1 left, 0 straight, −1 right.
    fn steering(self) -> [f64; 3] {
        match self {
            DubinsWord::Lsl => [1.0, 0.0, 1.0],
            DubinsWord::Rsr => [-1.0, 0.0, -1.0],
            DubinsWord::Lsr => [1.0, 0.0, -1.0],
            DubinsWord::Rsl => [-1.0, 0.0, 1.0],
            DubinsWord::Rlr => [-1.0, 1.0, -1.0],
            DubinsWord::Lrl => [1.0, -1.0, 1.0],
        }
    }
}

/// A Dubins path: three parts steering as its word says, driven forward one after the other.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DubinsPath {
    /// How each part steers.
    pub word: DubinsWord,
    /// Metres driven on each of the three parts (each at least zero; any may be zero).
    pub lengths: [f64; 3],
    /// Radius of the arcs, metres.
    pub radius: f64,
}

impl DubinsPath {
    /// Total length, metres.
    pub fn length(&self) -> f64 {
        self.lengths[0] + self.lengths[1] + self.lengths[2]
    }

    /// The three segments driven from `from` (zero-length parts are kept, so there are always
    /// three): arcs of curvature `±1/radius`, the middle part a line for LSL, RSR, LSR and RSL,
    /// all forward. Each starts where the one before ends.
    pub fn segments(&self, from: Pose) -> Vec<Segment> {
        let mut out = Vec::with_capacity(3);
        let mut at = from;
        for i in 0..3 {
            let s = self.part(i, at);
            at = s.end();
            out.push(s);
        }
        out
    }

    /// Where the path ends when driven from `from`.
    pub fn end(&self, from: Pose) -> Pose {
        let mut at = from;
        for i in 0..3 {
            at = self.part(i, at).end();
        }
        at
    }

    fn part(&self, i: usize, start: Pose) -> Segment {
        let steer = self.word.steering()[i];
        if steer == 0.0 {
            Segment::line(start, self.lengths[i], Gear::Forward)
        } else {
            Segment::arc(start, self.lengths[i], steer / self.radius, Gear::Forward)
        }
    }
}

/// The problem in the normalised frame: unit radius, the goal `d` along the x axis.
#[derive(Debug, Clone, Copy)]
struct Frame {
    d: f64,
    alpha: f64,
    beta: f64,
    sa: f64,
    ca: f64,
    sb: f64,
    cb: f64,
    /// cos(α − β).
    cab: f64,
}

impl Frame {
    fn new(from: Pose, to: Pose, radius: f64) -> Option<Frame> {
        let finite = [from.x, from.y, from.heading, to.x, to.y, to.heading, radius];
        if finite.iter().any(|v| !v.is_finite()) || radius <= 0.0 {
            return None;
        }
        let (dx, dy) = (to.x - from.x, to.y - from.y);
        let dist = dx.planar_hypot(dy);
        let d = dist / radius;
        if !d.is_finite() {
            return None;
        }
        // atan2(0, 0) is 0: with the poses on top of each other any direction will do.
        let theta = dy.atan2(dx);
        let alpha = wrap(from.heading - theta);
        let beta = wrap(to.heading - theta);
        let (sa, ca) = alpha.sin_cos();
        let (sb, cb) = beta.sin_cos();
        Some(Frame {
            d,
            alpha,
            beta,
            sa,
            ca,
            sb,
            cb,
            cab: (alpha - beta).cos(),
        })
    }

    /// The normalised lengths `[t, p, q]` of `word`, if it exists.
    fn solve(&self, word: DubinsWord) -> Option<[f64; 3]> {
        let f = self;
        match word {
            DubinsWord::Lsl => {
                // From the start's left circle to the goal's: the line is their outer tangent.
                let (vx, vy) = (f.d + f.sa - f.sb, f.cb - f.ca);
                let p = vx.planar_hypot(vy);
                let dir = if p < TINY { f.alpha } else { vy.atan2(vx) };
                Some([turn(dir - f.alpha), p, turn(f.beta - dir)])
            }
            DubinsWord::Rsr => {
                let (vx, vy) = (f.d - f.sa + f.sb, f.ca - f.cb);
                let p = vx.planar_hypot(vy);
                let dir = if p < TINY { f.alpha } else { vy.atan2(vx) };
                Some([turn(f.alpha - dir), p, turn(dir - f.beta)])
            }
            DubinsWord::Lsr => {
                // Inner tangent from the left circle to the goal's right circle.
                let p2 = -2.0 + f.d * f.d + 2.0 * f.cab + 2.0 * f.d * (f.sa + f.sb);
                let p = inner(p2)?;
                let (vx, vy) = (f.d + f.sa + f.sb, -f.ca - f.cb);
                let dir = vy.atan2(vx) - (-2.0f64).atan2(p);
                Some([turn(dir - f.alpha), p, turn(dir - f.beta)])
            }
            DubinsWord::Rsl => {
                let p2 = -2.0 + f.d * f.d + 2.0 * f.cab - 2.0 * f.d * (f.sa + f.sb);
                let p = inner(p2)?;
                let (vx, vy) = (f.d - f.sa - f.sb, f.ca + f.cb);
                let dir = vy.atan2(vx) - 2.0f64.atan2(p);
                Some([turn(f.alpha - dir), p, turn(f.beta - dir)])
            }
            DubinsWord::Rlr => {
                let c = (6.0 - f.d * f.d + 2.0 * f.cab + 2.0 * f.d * (f.sa - f.sb)) / 8.0;
                let p = middle(c)?;
                let (vx, vy) = (f.d - f.sa + f.sb, f.ca - f.cb);
                let t = turn(f.alpha - vy.atan2(vx) + 0.5 * p);
                Some([t, p, turn(f.alpha - f.beta - t + p)])
            }
            DubinsWord::Lrl => {
                let c = (6.0 - f.d * f.d + 2.0 * f.cab + 2.0 * f.d * (f.sb - f.sa)) / 8.0;
                let p = middle(c)?;
                let (vx, vy) = (f.d + f.sa - f.sb, f.cb - f.ca);
                let t = turn(vy.atan2(vx) - f.alpha + 0.5 * p);
                Some([t, p, turn(f.beta - f.alpha - t + p)])
            }
        }
    }
}

/// An angle in [0, 2π), a hair under a full turn read as none.
fn turn(a: f64) -> f64 {
    let v = a.rem_euclid(TAU);
    if v > TAU - SNAP {
        0.0
    } else {
        v
    }
}

/// The length of an inner tangent from its square (a rounding hair below zero is zero).
fn inner(p2: f64) -> Option<f64> {
    if p2 >= 0.0 {
        Some(p2.sqrt())
    } else if p2 > -1e-10 {
        Some(0.0)
    } else {
        None
    }
}

/// The middle arc of a three-arc word from the cosine of its supplement (it is over a half
/// turn: the shorter solution is never shortest).
fn middle(c: f64) -> Option<f64> {
    if c.is_nan() || c.abs() > 1.0 + 1e-10 {
        return None;
    }
    Some(TAU - c.clamp(-1.0, 1.0).acos())
}

fn path(word: DubinsWord, n: [f64; 3], radius: f64) -> Option<DubinsPath> {
    let lengths = [n[0] * radius, n[1] * radius, n[2] * radius];
    if lengths.iter().all(|l| l.is_finite() && *l >= 0.0) {
        Some(DubinsPath {
            word,
            lengths,
            radius,
        })
    } else {
        None
    }
}

/// The Dubins path of `word` from `from` to `to` with arcs of `radius` metres, if that word
/// connects them (LSL and RSR always do, the others not always). No allocation.
///
/// ```
/// use furrow::path::curve::Pose;
/// use furrow::path::dubins::{dubins_word, DubinsWord};
/// use std::f64::consts::PI;
///
/// // A half turn to the left: the left arc alone.
/// let from = Pose::new(0.0, 0.0, 0.0);
/// let to = Pose::new(0.0, 20.0, PI);
/// let p = dubins_word(from, to, 10.0, DubinsWord::Lsl).ok_or("no LSL path")?;
/// assert!((p.length() - 10.0 * PI).abs() < 1e-9);
/// // Three arcs cannot join poses this far apart.
/// assert!(dubins_word(from, Pose::new(100.0, 0.0, 0.0), 10.0, DubinsWord::Lrl).is_none());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn dubins_word(from: Pose, to: Pose, radius: f64, word: DubinsWord) -> Option<DubinsPath> {
    let f = Frame::new(from, to, radius)?;
    path(word, f.solve(word)?, radius)
}

/// Every Dubins word that connects `from` to `to`, in [`DubinsWord::ALL`] order (empty where
/// [`dubins_shortest`] gives `None`).
pub fn dubins_all(from: Pose, to: Pose, radius: f64) -> Vec<DubinsPath> {
    let Some(f) = Frame::new(from, to, radius) else {
        return Vec::new();
    };
    DubinsWord::ALL
        .iter()
        .filter_map(|&w| path(w, f.solve(w)?, radius))
        .collect()
}

/// The shortest forward path from `from` to `to` turning no tighter than `radius` metres; of
/// equally short words the first in [`DubinsWord::ALL`]. `None` only for a radius that is not
/// positive, an input that is not finite, or one so extreme that the distance in radii
/// overflows. No allocation.
///
/// ```
/// use furrow::path::curve::Pose;
/// use furrow::path::dubins::dubins_shortest;
///
/// let from = Pose::new(0.0, 0.0, 0.0);
/// let to = Pose::new(30.0, -12.0, -1.0);
/// let p = dubins_shortest(from, to, 6.0).ok_or("no path")?;
/// let end = p.end(from);
/// assert!(end.distance(&to) < 1e-9 && end.heading_change(&to).abs() < 1e-9);
/// assert!(p.length() >= from.distance(&to));
/// assert!(dubins_shortest(from, to, 0.0).is_none());
/// assert!(dubins_shortest(from, Pose::new(f64::NAN, 0.0, 0.0), 6.0).is_none());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn dubins_shortest(from: Pose, to: Pose, radius: f64) -> Option<DubinsPath> {
    let f = Frame::new(from, to, radius)?;
    let mut best: Option<(DubinsWord, [f64; 3], f64)> = None;
    for w in DubinsWord::ALL {
        if let Some(n) = f.solve(w) {
            let len = n[0] + n[1] + n[2];
            let better = match best {
                None => true,
                Some((_, _, b)) => len < b,
            };
            if len.is_finite() && better {
                best = Some((w, n, len));
            }
        }
    }
    let (w, n, _) = best?;
    path(w, n, radius)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    use crate::rng::SplitMix64 as Rng;

    use super::super::testing::{assert_reaches, case, drive};

    /// Checks a path's shape and that it is drivable from `from` to `to`.
    fn check_path(p: &DubinsPath, from: Pose, to: Pose) {
        assert!(
            p.lengths.iter().all(|l| l.is_finite() && *l >= 0.0),
            "{p:?}"
        );
        let segs = p.segments(from);
        assert_eq!(segs.len(), 3);
        for (s, k) in segs.iter().zip(p.word.steering()) {
            assert_eq!(s.gear, Gear::Forward);
            assert_eq!(s.sharpness, 0.0);
            if k == 0.0 {
                assert_eq!(s.curvature, 0.0);
            } else {
                assert_eq!(s.curvature.abs(), 1.0 / p.radius, "{p:?}");
                assert_eq!(s.curvature.signum(), k);
            }
        }
        assert!((super::super::curve::length(&segs) - p.length()).abs() < 1e-12);
        assert_reaches(drive(from, &segs), to, p);
        assert_reaches(p.end(from), to, p);
    }

    #[test]
    fn every_word_found_reaches_its_goal() {
        let mut rng = Rng::new(1);
        let mut counts = [0usize; 6];
        for _ in 0..4000 {
            let (from, to, r) = case(&mut rng);
            let all = dubins_all(from, to, r);
            // The two same-side words always exist.
            assert!(all.iter().any(|p| p.word == DubinsWord::Lsl));
            assert!(all.iter().any(|p| p.word == DubinsWord::Rsr));
            for p in &all {
                check_path(p, from, to);
                assert_eq!(p.radius, r);
                assert_eq!(dubins_word(from, to, r, p.word), Some(*p));
                counts[DubinsWord::ALL
                    .iter()
                    .position(|w| *w == p.word)
                    .unwrap_or(9)] += 1;
            }
            for w in DubinsWord::ALL {
                assert_eq!(
                    dubins_word(from, to, r, w).is_some(),
                    all.iter().any(|p| p.word == w)
                );
            }
        }
        // Every word turns up.
        assert!(counts.iter().all(|&c| c > 100), "{counts:?}");
    }

    #[test]
    fn poses_on_a_grid_are_reached() {
        // Exact alignments: integer offsets in half radii, headings in quarter turns.
        let r = 2.0;
        let from = Pose::new(0.0, 0.0, 0.0);
        for i in -6..=6 {
            for j in -6..=6 {
                for k in -1..=2 {
                    let to = Pose::new(i as f64 * r / 2.0, j as f64 * r / 2.0, k as f64 * PI / 2.0);
                    let all = dubins_all(from, to, r);
                    for p in &all {
                        check_path(p, from, to);
                    }
                    let best = dubins_shortest(from, to, r);
                    let Some(best) = best else {
                        panic!("no path to {to:?}")
                    };
                    check_path(&best, from, to);
                    assert!(all.iter().all(|p| best.length() <= p.length()));
                    // Nothing beats a straight line, or turning on the way.
                    assert!(best.length() >= from.distance(&to) - 1e-9);
                    assert!(best.length() >= r * from.heading_change(&to).abs() - 1e-9);
                }
            }
        }
    }

    #[test]
    fn shortest_is_the_first_least_of_all_words() {
        let mut rng = Rng::new(2);
        for _ in 0..4000 {
            let (from, to, r) = case(&mut rng);
            let all = dubins_all(from, to, r);
            let Some(best) = dubins_shortest(from, to, r) else {
                panic!("no path from {from:?} to {to:?}")
            };
            check_path(&best, from, to);
            let min = all
                .iter()
                .map(DubinsPath::length)
                .fold(f64::INFINITY, f64::min);
            assert_eq!(best.length(), min);
            let first = all.iter().find(|p| p.length() == min);
            assert_eq!(first, Some(&best));
            assert!(best.length() >= from.distance(&to) - 1e-9);
            assert!(best.length() >= r * from.heading_change(&to).abs() - 1e-9);
            // Deterministic.
            assert_eq!(dubins_shortest(from, to, r), Some(best));
        }
    }

    #[test]
    fn known_values() {
        let o = Pose::new(0.0, 0.0, 0.0);
        for r in [0.5, 1.0, 7.0] {
            let len = |to: Pose| dubins_shortest(o, to, r).map(|p| p.length());
            let near = |a: Option<f64>, b: f64| a.is_some_and(|a| (a - b).abs() < 1e-9 * (1.0 + b));
            // Straight ahead 4r: a line; LSL wins the tie with RSR.
            let p = dubins_shortest(o, Pose::new(4.0 * r, 0.0, 0.0), r);
            assert_eq!(p.map(|p| p.word), Some(DubinsWord::Lsl));
            assert!(near(p.map(|p| p.length()), 4.0 * r));
            // No move at all.
            assert!(near(len(o), 0.0));
            // A half and a quarter circle to each side.
            assert!(near(len(Pose::new(0.0, 2.0 * r, PI)), PI * r));
            assert!(near(len(Pose::new(0.0, -2.0 * r, PI)), PI * r));
            assert!(near(len(Pose::new(r, r, PI / 2.0)), PI * r / 2.0));
            assert!(near(len(Pose::new(r, -r, -PI / 2.0)), PI * r / 2.0));
            // Turning back on the spot: R π/3, L 5π/3, R π/3.
            let back = dubins_shortest(o, Pose::new(0.0, 0.0, PI), r);
            assert_eq!(back.map(|p| p.word), Some(DubinsWord::Rlr));
            assert!(near(back.map(|p| p.length()), 7.0 * PI * r / 3.0));
            // The same place facing the same way a hair later: no loop.
            assert!(near(len(Pose::new(0.0, 0.0, 1e-13)), 1e-13 * r));
            // An S-bend two radii across and along: L π/2 then R π/2.
            let bend = dubins_shortest(o, Pose::new(2.0 * r, 2.0 * r, 0.0), r);
            assert_eq!(bend.map(|p| p.word), Some(DubinsWord::Lsr));
            assert!(near(bend.map(|p| p.length()), PI * r));
            // Two radii straight behind, facing the same way: a half turn, 2r back, a half turn.
            let behind = dubins_shortest(o, Pose::new(-2.0 * r, 0.0, 0.0), r);
            assert_eq!(behind.map(|p| p.word), Some(DubinsWord::Lsl));
            assert!(near(behind.map(|p| p.length()), 2.0 * PI * r + 2.0 * r));
        }
    }

    #[test]
    fn bad_input_gives_none() {
        let o = Pose::new(0.0, 0.0, 0.0);
        let to = Pose::new(10.0, 3.0, 1.0);
        for r in [0.0, -1.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(dubins_shortest(o, to, r).is_none());
            assert!(dubins_all(o, to, r).is_empty());
            assert!(dubins_word(o, to, r, DubinsWord::Lsl).is_none());
        }
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            for p in [
                Pose::new(bad, 0.0, 0.0),
                Pose::new(0.0, bad, 0.0),
                Pose::new(0.0, 0.0, bad),
            ] {
                assert!(dubins_shortest(p, to, 1.0).is_none());
                assert!(dubins_shortest(o, p, 1.0).is_none());
                assert!(dubins_all(o, p, 1.0).is_empty());
            }
        }
        // Extreme but finite: no panic, and any answer is finite.
        for (a, b, r) in [
            (o, Pose::new(1e300, -1e300, 1e300), 1.0),
            (o, Pose::new(1e300, 0.0, 0.0), 1e-300),
            (o, Pose::new(1.0, 1.0, 0.0), 1e300),
            (o, Pose::new(1e-300, 0.0, 0.0), 1e-300),
            (
                Pose::new(-1e308, 1e308, -1e308),
                Pose::new(1e308, -1e308, 3.0),
                5.0,
            ),
        ] {
            for p in dubins_all(a, b, r) {
                assert!(p.length().is_finite());
            }
            if let Some(p) = dubins_shortest(a, b, r) {
                assert!(p.length().is_finite());
            }
        }
        // Far from the origin the answer is the same as near it.
        let shift = |p: Pose| Pose::new(p.x + 1e6, p.y - 2e6, p.heading);
        let near = dubins_shortest(o, to, 3.0).map(|p| p.length());
        let far = dubins_shortest(shift(o), shift(to), 3.0).map(|p| p.length());
        assert!(near.zip(far).is_some_and(|(a, b)| (a - b).abs() < 1e-8));
    }

    // ---- An independent brute force: circle tangents built geometrically, not the formulas.

    /// A forward piece: steering (+1 left, 0 straight, −1 right) and metres.
    type Piece = (f64, f64);

    fn centre(p: Pose, s: f64, r: f64) -> (f64, f64) {
        (p.x - s * r * p.heading.sin(), p.y + s * r * p.heading.cos())
    }

    /// The forward turn, radians, to go from heading `a` to heading `b` steering `s`.
    fn fwd(s: f64, a: f64, b: f64) -> f64 {
        let v = (s * (b - a)).rem_euclid(TAU);
        if v > TAU - 1e-10 {
            0.0
        } else {
            v
        }
    }

    /// The pose on the circle of `p` steering `s` after turning `delta` (signed heading change).
    fn arc_end(p: Pose, s: f64, delta: f64, r: f64) -> Pose {
        let (cx, cy) = centre(p, s, r);
        let h = p.heading + delta;
        Pose::new(cx + s * r * h.sin(), cy - s * r * h.cos(), h)
    }

    /// The shortest forward arc–line–arc from `a` to `b`, over both steerings at each end and
    /// every common tangent of the two circles.
    fn csc(a: Pose, b: Pose, r: f64) -> Option<(f64, [Piece; 3])> {
        let mut best: Option<(f64, [Piece; 3])> = None;
        for s1 in [1.0, -1.0] {
            for s2 in [1.0, -1.0] {
                let c1 = centre(a, s1, r);
                let c2 = centre(b, s2, r);
                let (wx, wy) = (c2.0 - c1.0, c2.1 - c1.1);
                let w = wx.planar_hypot(wy);
                let aw = wy.atan2(wx);
                let k = r * (s2 - s1) / w;
                if k.is_nan() || k.abs() > 1.0 {
                    continue;
                }
                let asn = k.asin();
                for psi in [aw - asn, aw - PI + asn] {
                    let lambda = wx * psi.cos() + wy * psi.sin();
                    if lambda < 0.0 {
                        continue;
                    }
                    let t1 = fwd(s1, a.heading, psi);
                    let t2 = fwd(s2, psi, b.heading);
                    let len = r * (t1 + t2) + lambda;
                    if best.is_none_or(|(l, _)| len < l) {
                        best = Some((len, [(s1, r * t1), (0.0, lambda), (s2, r * t2)]));
                    }
                }
            }
        }
        best
    }

    /// The shortest forward three-arc path from `a` to `b`: the middle circle touches both.
    fn ccc(a: Pose, b: Pose, r: f64) -> Option<(f64, [Piece; 3])> {
        let mut best: Option<(f64, [Piece; 3])> = None;
        for s1 in [1.0, -1.0] {
            let s2 = -s1;
            let c1 = centre(a, s1, r);
            let c3 = centre(b, s1, r);
            let (wx, wy) = (c3.0 - c1.0, c3.1 - c1.1);
            let w = wx.planar_hypot(wy);
            if w.is_nan() || w > 4.0 * r || w < 1e-9 {
                continue;
            }
            let h = (4.0 * r * r - 0.25 * w * w).max(0.0).sqrt();
            let (mx, my) = (0.5 * (c1.0 + c3.0), 0.5 * (c1.1 + c3.1));
            for side in [1.0, -1.0] {
                let c2 = (mx - side * h * wy / w, my + side * h * wx / w);
                let e1 = ((c2.0 - c1.0) / (2.0 * r), (c2.1 - c1.1) / (2.0 * r));
                let e2 = ((c3.0 - c2.0) / (2.0 * r), (c3.1 - c2.1) / (2.0 * r));
                let psi1 = (s1 * e1.0).atan2(-s1 * e1.1);
                let psi2 = (s2 * e2.0).atan2(-s2 * e2.1);
                let t1 = fwd(s1, a.heading, psi1);
                let t2 = fwd(s2, psi1, psi2);
                let t3 = fwd(s1, psi2, b.heading);
                let len = r * (t1 + t2 + t3);
                if best.is_none_or(|(l, _)| len < l) {
                    best = Some((len, [(s1, r * t1), (s2, r * t2), (s1, r * t3)]));
                }
            }
        }
        best
    }

    /// The shortest forward path found by trying a first arc of every length in half-degree
    /// steps, each finished by the best geometric arc–line–arc or three arcs.
    fn brute(a: Pose, b: Pose, r: f64) -> (f64, Vec<Piece>) {
        let mut best = (f64::INFINITY, Vec::new());
        for s0 in [1.0, -1.0] {
            for i in 0..720 {
                let t0 = i as f64 * PI / 360.0;
                let p = arc_end(a, s0, s0 * t0, r);
                for rest in [csc(p, b, r), ccc(p, b, r)].into_iter().flatten() {
                    let len = r * t0 + rest.0;
                    if len < best.0 {
                        let mut pieces = vec![(s0, r * t0)];
                        pieces.extend_from_slice(&rest.1);
                        best = (len, pieces);
                    }
                }
            }
        }
        best
    }

    fn pieces_to_segments(from: Pose, pieces: &[Piece], r: f64) -> Vec<Segment> {
        let mut at = from;
        let mut out = Vec::new();
        for &(s, len) in pieces {
            let seg = if s == 0.0 {
                Segment::line(at, len, Gear::Forward)
            } else {
                Segment::arc(at, len, s / r, Gear::Forward)
            };
            at = seg.end();
            out.push(seg);
        }
        out
    }

    #[test]
    fn brute_force_agrees() {
        let mut rng = Rng::new(3);
        for _ in 0..300 {
            let (from, to, r) = case(&mut rng);
            let (b, pieces) = brute(from, to, r);
            // The brute force's own path is real.
            let segs = pieces_to_segments(from, &pieces, r);
            assert!(pieces.iter().all(|p| p.1 >= 0.0));
            assert_reaches(drive(from, &segs), to, &pieces);
            assert!((super::super::curve::length(&segs) - b).abs() < 1e-9);
            let Some(d) = dubins_shortest(from, to, r) else {
                panic!("no path")
            };
            let tol = 1e-9 * (1.0 + b);
            assert!(d.length() <= b + tol, "{d:?} longer than brute force {b}");
            assert!(b <= d.length() + tol, "brute force {b} shorter than {d:?}");
        }
    }

    #[test]
    fn brute_force_agrees_close_up() {
        // Within four radii, where the three-arc words are shortest.
        let mut rng = Rng::new(6);
        let mut three_arcs = 0;
        for _ in 0..1000 {
            let r = rng.range(1.0, 15.0);
            let from = Pose::new(
                rng.range(-50.0, 50.0),
                rng.range(-50.0, 50.0),
                rng.range(-PI, PI),
            );
            let (dist, dir) = (rng.range(0.0, 4.0 * r), rng.range(-PI, PI));
            let to = Pose::new(
                from.x + dist * dir.cos(),
                from.y + dist * dir.sin(),
                rng.range(-PI, PI),
            );
            let (b, _) = brute(from, to, r);
            let Some(d) = dubins_shortest(from, to, r) else {
                panic!("no path")
            };
            let tol = 1e-9 * (1.0 + b);
            assert!(
                d.length() <= b + tol && b <= d.length() + tol,
                "{d:?} vs {b}"
            );
            if matches!(d.word, DubinsWord::Rlr | DubinsWord::Lrl) {
                three_arcs += 1;
            }
        }
        assert!(three_arcs > 50, "{three_arcs}");
    }

    #[test]
    fn no_random_forward_path_is_shorter() {
        // Drive random arcs and lines forward; the Dubins path to where they end is no longer.
        let mut rng = Rng::new(4);
        let mut equal = 0;
        for _ in 0..5000 {
            let r = rng.range(1.0, 15.0);
            let from = Pose::new(
                rng.range(-50.0, 50.0),
                rng.range(-50.0, 50.0),
                rng.range(-PI, PI),
            );
            let n = 1 + (rng.next_u64() % 4) as usize;
            let mut pieces = Vec::new();
            for _ in 0..n {
                let s = [1.0, 0.0, -1.0][(rng.next_u64() % 3) as usize];
                let len = if s == 0.0 {
                    rng.range(0.0, 30.0)
                } else {
                    r * rng.range(0.0, 1.5 * PI)
                };
                pieces.push((s, len));
            }
            let segs = pieces_to_segments(from, &pieces, r);
            let Some(to) = super::super::curve::end(&segs) else {
                panic!("no segments")
            };
            let len = super::super::curve::length(&segs);
            let Some(d) = dubins_shortest(from, to, r) else {
                panic!("no path")
            };
            check_path(&d, from, to);
            assert!(
                d.length() <= len + 1e-9 * (1.0 + len),
                "{d:?} vs {pieces:?}"
            );
            if d.length() > len - 1e-6 {
                equal += 1;
            }
        }
        // Many random paths are themselves shortest: the bound is tight, not vacuous.
        assert!(equal > 500, "{equal}");
    }

    #[test]
    fn timing() {
        let mut rng = Rng::new(5);
        let cases: Vec<_> = (0..1000).map(|_| case(&mut rng)).collect();
        let start = std::time::Instant::now();
        let mut total = 0.0;
        let reps = 200;
        for _ in 0..reps {
            for &(a, b, r) in &cases {
                total += dubins_shortest(a, b, r).map_or(0.0, |p| p.length());
            }
        }
        let per = start.elapsed().as_secs_f64() / (reps * cases.len()) as f64;
        println!(
            "dubins_shortest: {:.3} µs per call (checksum {total:.1})",
            per * 1e6
        );
    }
}
