//! Reeds-Shepp shortest paths: the shortest way from one pose to another for a machine that
//! turns no tighter than a given radius and may drive forward and in reverse (Reeds & Shepp
//! 1990, with the corrections of Sussmann & Tang 1991).
//!
//! A shortest path has at most five parts — arcs of exactly the minimum radius (C) and lines
//! (S) — with the gear changing (a *cusp*, `|`) only at some joins. Eight formulas in the
//! normalised frame (unit radius, the start at the origin facing east; Reeds & Shepp §8, the
//! same set as OMPL's `ReedsSheppStateSpace`) give the parts' lengths: L+S+L+ (8.1), L+S+R+
//! (8.2), L+R−L± (8.3 and 8.4: C|C|C and C|CC), L+R+L−R− (8.7: CCu|CuC), L+R−L−R+ (8.8:
//! C|CuCu|C), L+R−S−L− and L+R−S−R− (8.9 and 8.10: C|Cπ/2SC) and L+R−S−L−R+ (8.11:
//! C|Cπ/2SCπ/2|C). Each is applied to the goal as it is, mirrored in time (every gear
//! flipped), mirrored in the x axis (every left a right) and both; the three that do not read
//! the same backwards (L+R−L± and the two C|Cπ/2SC) are also applied to the path driven in
//! the opposite order (giving CC|C and CSCπ/2|C). These 44 applications cover all 48 path types; the shortest of their
//! candidates is the shortest path.
//!
//! Driving conventions are those of [`super::curve`]: a part steering left is an arc of
//! curvature `+1/r` whichever the gear, so in reverse it turns the machine clockwise
//! (`dθ = g·κ·ds`).
//!
//! ```
//! use furrow::path::curve::{Gear, Pose};
//! use furrow::path::reeds_shepp::{reeds_shepp_all, reeds_shepp_shortest, Steer};
//!
//! // Straight back 7 m: one part, in reverse.
//! let from = Pose::new(0.0, 0.0, 0.0);
//! let to = Pose::new(-7.0, 0.0, 0.0);
//! let p = reeds_shepp_shortest(from, to, 5.0).ok_or("no path")?;
//! assert_eq!(p.word(), "S-");
//! assert_eq!(p.parts[0].steer, Steer::Straight);
//! assert_eq!(p.parts[0].gear, Gear::Reverse);
//! assert!((p.length() - 7.0).abs() < 1e-9);
//!
//! // A sideways shift of 2 m with 5 m turns needs cusps; the path ends at the goal.
//! let to = Pose::new(0.0, 2.0, 0.0);
//! let p = reeds_shepp_shortest(from, to, 5.0).ok_or("no path")?;
//! assert!(p.cusps() >= 1);
//! let end = p.end(from);
//! assert!(end.distance(&to) < 1e-9 && end.heading_change(&to).abs() < 1e-9);
//!
//! // Every candidate found is a path to the goal, none shorter than the shortest.
//! for q in reeds_shepp_all(from, to, 5.0) {
//!     assert!(q.length() >= p.length());
//!     assert!(q.end(from).distance(&to) < 1e-9);
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use super::curve::{wrap, Gear, Pose, Segment};
use crate::geometry::PlanarHypot;
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use Steer::{Left as L, Right as R, Straight as S};

/// Normalised lengths within this of zero are zero: a formula's sign conditions accept them
/// and the part is dropped (the goal is then missed by at most this, in radii and radians).
const ZERO: f64 = 1e-11;

/// How far (normalised) a candidate may miss its goal before it is thrown away. The formulas
/// are exact, so this only ever catches rounding in extreme inputs.
const REACH: f64 = 1e-9;

/// Which way a part steers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Steer {
    /// An arc of curvature `+1/r`.
    Left,
    /// A line.
    Straight,
    /// An arc of curvature `−1/r`.
    Right,
}

impl Steer {
    fn mirrored(self) -> Steer {
        match self {
            Steer::Left => Steer::Right,
            Steer::Straight => Steer::Straight,
            Steer::Right => Steer::Left,
        }
    }

    fn letter(self) -> char {
        match self {
            Steer::Left => 'L',
            Steer::Straight => 'S',
            Steer::Right => 'R',
        }
    }
}

/// One part of a Reeds-Shepp path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RsPart {
    /// How it steers.
    pub steer: Steer,
    /// Forward or reverse.
    pub gear: Gear,
    /// Metres driven (more than zero).
    pub length: f64,
}

/// A Reeds-Shepp path: its parts driven one after the other.
///
/// Parts of zero length are left out and neighbours that steer the same way in the same gear
/// are joined, so there are at most five parts (none when start and goal coincide).
#[derive(Debug, Clone, PartialEq)]
pub struct RsPath {
    /// The parts in the order they are driven.
    pub parts: Vec<RsPart>,
    /// Radius of the arcs, metres.
    pub radius: f64,
    /// The formula family it came from: `"CSC"`, `"CCC"`, `"CCCC"`, `"CCSC"` (which includes
    /// its backwards form CSCC) or `"CCSCC"`.
    pub family: &'static str,
}

impl RsPath {
    /// Total length, metres.
    pub fn length(&self) -> f64 {
        self.parts.iter().map(|p| p.length).sum()
    }

    /// The segments driven from `from`, one per part, each starting where the one before
    /// ends: arcs of curvature `+1/radius` (left) or `−1/radius` (right) and lines, in the
    /// part's gear.
    pub fn segments(&self, from: Pose) -> Vec<Segment> {
        let mut out = Vec::with_capacity(self.parts.len());
        let mut at = from;
        for p in &self.parts {
            let s = self.segment(p, at);
            at = s.end();
            out.push(s);
        }
        out
    }

    /// Where the path ends when driven from `from`.
    pub fn end(&self, from: Pose) -> Pose {
        self.parts
            .iter()
            .fold(from, |at, p| self.segment(p, at).end())
    }

    /// How many times the gear changes along the path.
    pub fn cusps(&self) -> usize {
        self.parts
            .windows(2)
            .filter(|w| w[0].gear != w[1].gear)
            .count()
    }

    /// The path as letters and gears, e.g. `"L+S+R-"` (`+` forward, `-` reverse).
    pub fn word(&self) -> String {
        let mut w = String::with_capacity(2 * self.parts.len());
        for p in &self.parts {
            w.push(p.steer.letter());
            w.push(if p.gear == Gear::Forward { '+' } else { '-' });
        }
        w
    }

    fn segment(&self, p: &RsPart, start: Pose) -> Segment {
        match p.steer {
            Steer::Straight => Segment::line(start, p.length, p.gear),
            Steer::Left => Segment::arc(start, p.length, 1.0 / self.radius, p.gear),
            Steer::Right => Segment::arc(start, p.length, -1.0 / self.radius, p.gear),
        }
    }
}

/// A candidate in the normalised frame: signed lengths (negative in reverse; on arcs the
/// heading change is `+v` steering left and `−v` steering right).
#[derive(Debug, Clone, Copy)]
struct Candidate {
    family: &'static str,
    steers: [Steer; 5],
    values: [f64; 5],
    n: usize,
}

impl Candidate {
    fn new(family: &'static str, steers: &[Steer], values: &[f64]) -> Candidate {
        let mut c = Candidate {
            family,
            steers: [S; 5],
            values: [0.0; 5],
            n: steers.len(),
        };
        c.steers[..c.n].copy_from_slice(steers);
        for (slot, &v) in c.values.iter_mut().zip(values) {
            *slot = if v.abs() <= ZERO { 0.0 } else { v };
        }
        c
    }

    fn length(&self) -> f64 {
        self.values[..self.n].iter().map(|v| v.abs()).sum()
    }

    /// The candidate for the transformed goal turned back into one for the real goal.
    fn transformed(mut self, timeflip: bool, reflect: bool, backwards: bool) -> Candidate {
        let n = self.n;
        if backwards {
            self.steers[..n].reverse();
            self.values[..n].reverse();
        }
        if timeflip {
            for v in &mut self.values[..n] {
                *v = -*v;
            }
        }
        if reflect {
            for s in &mut self.steers[..n] {
                *s = s.mirrored();
            }
        }
        self
    }

    /// Whether, driven from the origin facing east, it ends at `(x, y)` facing `phi`.
    fn reaches(&self, x: f64, y: f64, phi: f64) -> bool {
        let (mut px, mut py, mut h) = (0.0f64, 0.0f64, 0.0f64);
        for (&s, &v) in self.steers[..self.n].iter().zip(&self.values[..self.n]) {
            let (sh, ch) = h.sin_cos();
            match s {
                Steer::Straight => {
                    px += v * ch;
                    py += v * sh;
                }
                Steer::Left => {
                    let (s2, c2) = (h + v).sin_cos();
                    px += s2 - sh;
                    py += ch - c2;
                    h += v;
                }
                Steer::Right => {
                    let (s2, c2) = (h - v).sin_cos();
                    px += sh - s2;
                    py += c2 - ch;
                    h -= v;
                }
            }
        }
        let tol = REACH * (1.0 + x.abs() + y.abs());
        (px - x).abs() <= tol && (py - y).abs() <= tol && wrap(h - phi).abs() <= REACH
    }

    fn path(&self, radius: f64) -> RsPath {
        let mut parts: Vec<RsPart> = Vec::with_capacity(self.n);
        for (&steer, &v) in self.steers[..self.n].iter().zip(&self.values[..self.n]) {
            if v == 0.0 {
                continue;
            }
            let gear = if v > 0.0 {
                Gear::Forward
            } else {
                Gear::Reverse
            };
            let length = v.abs() * radius;
            match parts.last_mut() {
                Some(last) if last.steer == steer && last.gear == gear => last.length += length,
                _ => parts.push(RsPart {
                    steer,
                    gear,
                    length,
                }),
            }
        }
        RsPath {
            parts,
            radius,
            family: self.family,
        }
    }
}

/// An arc angle that must be at least zero: a hair past −π is the same pose as a hair past π.
fn forward_arc(a: f64) -> Option<f64> {
    let a = if a < -PI + ZERO { a + TAU } else { a };
    (a >= -ZERO).then_some(a)
}

/// An arc angle that must be at most zero.
fn reverse_arc(a: f64) -> Option<f64> {
    let a = if a > PI - ZERO { a - TAU } else { a };
    (a <= ZERO).then_some(a)
}

/// The goal in the normalised frame, with the sine and cosine of its heading.
#[derive(Debug, Clone, Copy)]
struct Goal {
    x: f64,
    y: f64,
    phi: f64,
    s: f64,
    c: f64,
}

/// 8.1: L+ S+ L+.
fn lp_sp_lp(g: Goal) -> Option<Candidate> {
    let (xi, eta) = (g.x - g.s, g.y - 1.0 + g.c);
    let u = xi.planar_hypot(eta);
    let t = forward_arc(eta.atan2(xi))?;
    let v = forward_arc(wrap(g.phi - t))?;
    Some(Candidate::new("CSC", &[L, S, L], &[t, u, v]))
}

/// 8.2: L+ S+ R+.
fn lp_sp_rp(g: Goal) -> Option<Candidate> {
    let (xi, eta) = (g.x + g.s, g.y - 1.0 - g.c);
    let u1 = xi * xi + eta * eta;
    if u1 < 4.0 {
        return None;
    }
    let u = (u1 - 4.0).sqrt();
    let t = forward_arc(wrap(eta.atan2(xi) + 2.0f64.atan2(u)))?;
    let v = forward_arc(wrap(t - g.phi))?;
    Some(Candidate::new("CSC", &[L, S, R], &[t, u, v]))
}

/// 8.3 and 8.4: L+ R- L (C|C|C, C|CC).
fn lp_rm_l(g: Goal) -> Option<Candidate> {
    let (xi, eta) = (g.x - g.s, g.y - 1.0 + g.c);
    let u1 = xi.planar_hypot(eta);
    if u1 > 4.0 {
        return None;
    }
    let u = -2.0 * (0.25 * u1).asin();
    let t = forward_arc(wrap(eta.atan2(xi) + 0.5 * u + PI))?;
    let v = wrap(g.phi - t + u);
    Some(Candidate::new("CCC", &[L, R, L], &[t, u, v]))
}

/// The first and last arcs of the CCCC formulas (Reeds & Shepp's τ and ω).
fn tau_omega(u: f64, v: f64, xi: f64, eta: f64, phi: f64) -> (f64, f64) {
    let delta = wrap(u - v);
    let (su, cu) = u.sin_cos();
    let (sd, cd) = delta.sin_cos();
    let a = su - sd;
    let b = cu - cd - 1.0;
    let t1 = (eta * a - xi * b).atan2(xi * a + eta * b);
    let t2 = 2.0 * (cd - v.cos() - cu) + 3.0;
    let tau = if t2 < 0.0 { wrap(t1 + PI) } else { wrap(t1) };
    (tau, wrap(tau - u + v - phi))
}

/// 8.7: L+ R+ L- R- (CCu|CuC).
fn lp_rup_lum_rm(g: Goal) -> Option<Candidate> {
    let (xi, eta) = (g.x + g.s, g.y - 1.0 - g.c);
    let rho = 0.25 * (2.0 + xi.planar_hypot(eta));
    if rho > 1.0 {
        return None;
    }
    let u = rho.acos();
    let (t, v) = tau_omega(u, -u, xi, eta, g.phi);
    let t = forward_arc(t)?;
    let v = reverse_arc(v)?;
    Some(Candidate::new("CCCC", &[L, R, L, R], &[t, u, -u, v]))
}

/// 8.8: L+ R- L- R+ (C|CuCu|C).
fn lp_rum_lum_rp(g: Goal) -> Option<Candidate> {
    let (xi, eta) = (g.x + g.s, g.y - 1.0 - g.c);
    let rho = (20.0 - xi * xi - eta * eta) / 16.0;
    if !(0.0..=1.0).contains(&rho) {
        return None;
    }
    let u = -rho.acos();
    if u < -FRAC_PI_2 {
        return None;
    }
    let (t, v) = tau_omega(u, u, xi, eta, g.phi);
    let t = forward_arc(t)?;
    let v = forward_arc(v)?;
    Some(Candidate::new("CCCC", &[L, R, L, R], &[t, u, u, v]))
}

/// 8.9: L+ R-(π/2) S- L- (C|Cπ/2SC).
fn lp_rm_sm_lm(g: Goal) -> Option<Candidate> {
    let (xi, eta) = (g.x - g.s, g.y - 1.0 + g.c);
    let rho = xi.planar_hypot(eta);
    if rho < 2.0 {
        return None;
    }
    let r = (rho * rho - 4.0).sqrt();
    let u = 2.0 - r;
    if u > ZERO {
        return None;
    }
    let t = forward_arc(wrap(eta.atan2(xi) + r.atan2(-2.0)))?;
    let v = reverse_arc(wrap(g.phi - FRAC_PI_2 - t))?;
    Some(Candidate::new(
        "CCSC",
        &[L, R, S, L],
        &[t, -FRAC_PI_2, u, v],
    ))
}

/// 8.10: L+ R-(π/2) S- R- (C|Cπ/2SC).
fn lp_rm_sm_rm(g: Goal) -> Option<Candidate> {
    let (xi, eta) = (g.x + g.s, g.y - 1.0 - g.c);
    let rho = xi.planar_hypot(eta);
    if rho < 2.0 {
        return None;
    }
    let u = 2.0 - rho;
    if u > ZERO {
        return None;
    }
    let t = forward_arc(xi.atan2(-eta))?;
    let v = reverse_arc(wrap(t + FRAC_PI_2 - g.phi))?;
    Some(Candidate::new(
        "CCSC",
        &[L, R, S, R],
        &[t, -FRAC_PI_2, u, v],
    ))
}

/// 8.11: L+ R-(π/2) S- L-(π/2) R+ (C|Cπ/2SCπ/2|C).
fn lp_rm_s_lm_rp(g: Goal) -> Option<Candidate> {
    let (xi, eta) = (g.x + g.s, g.y - 1.0 - g.c);
    let rho = xi.planar_hypot(eta);
    if rho < 2.0 {
        return None;
    }
    let u = 4.0 - (rho * rho - 4.0).sqrt();
    if u > ZERO {
        return None;
    }
    let t = ((4.0 - u) * xi - 2.0 * eta).atan2(-2.0 * xi + (u - 4.0) * eta);
    let t = forward_arc(wrap(t))?;
    let v = forward_arc(wrap(t - g.phi))?;
    Some(Candidate::new(
        "CCSCC",
        &[L, R, S, L, R],
        &[t, -FRAC_PI_2, u, -FRAC_PI_2, v],
    ))
}

type Formula = fn(Goal) -> Option<Candidate>;

/// The base formulas, and whether each is also applied backwards (the path driven in the
/// opposite order, for words that are not their own reversal).
const FORMULAS: [(Formula, bool); 8] = [
    (lp_sp_lp, false),
    (lp_sp_rp, false),
    (lp_rm_l, true),
    (lp_rup_lum_rm, false),
    (lp_rum_lum_rp, false),
    (lp_rm_sm_lm, true),
    (lp_rm_sm_rm, true),
    (lp_rm_s_lm_rp, false),
];

/// How many formula applications [`candidates`] makes.
#[cfg(test)]
const APPLICATIONS: usize = 44;

/// Every candidate of every formula for the goal `(x, y, phi)` in the normalised frame, with
/// the index of the formula application that produced it, unverified.
fn candidates(x: f64, y: f64, phi: f64, visit: &mut impl FnMut(usize, Candidate)) {
    let (s, c) = phi.sin_cos();
    // The start seen from the goal, mirrored in time: the goal of the backwards words.
    let (xb, yb) = (x * c + y * s, x * s - y * c);
    let mut id = 0;
    for (formula, with_backwards) in FORMULAS {
        for backwards in [false, true] {
            if backwards && !with_backwards {
                continue;
            }
            let (gx, gy) = if backwards { (xb, yb) } else { (x, y) };
            // Identity, timeflip, reflect, both.
            for (timeflip, reflect) in [(false, false), (true, false), (false, true), (true, true)]
            {
                let fx = if timeflip { -gx } else { gx };
                let fy = if reflect { -gy } else { gy };
                let flip_phi = timeflip != reflect;
                let goal = Goal {
                    x: fx,
                    y: fy,
                    phi: if flip_phi { -phi } else { phi },
                    s: if flip_phi { -s } else { s },
                    c,
                };
                if let Some(cand) = formula(goal) {
                    visit(id, cand.transformed(timeflip, reflect, backwards));
                }
                id += 1;
            }
        }
    }
}

/// The goal in the start's frame divided by the radius, if the input is usable.
fn normalise(from: Pose, to: Pose, radius: f64) -> Option<(f64, f64, f64)> {
    let all = [from.x, from.y, from.heading, to.x, to.y, to.heading, radius];
    if all.iter().any(|v| !v.is_finite()) || radius <= 0.0 {
        return None;
    }
    let (s, c) = from.heading.sin_cos();
    let (dx, dy) = (to.x - from.x, to.y - from.y);
    let x = (c * dx + s * dy) / radius;
    let y = (c * dy - s * dx) / radius;
    let phi = wrap(to.heading - from.heading);
    (x.is_finite() && y.is_finite() && phi.is_finite()).then_some((x, y, phi))
}

/// Every candidate path from `from` to `to` with arcs of `radius` metres, of all the formula
/// families and their transforms, each checked to reach `to` (empty where
/// [`reeds_shepp_shortest`] gives `None`). The same path may appear more than once.
pub fn reeds_shepp_all(from: Pose, to: Pose, radius: f64) -> Vec<RsPath> {
    let mut out = Vec::new();
    if let Some((x, y, phi)) = normalise(from, to, radius) {
        candidates(x, y, phi, &mut |_, c| {
            if c.length().is_finite() && c.reaches(x, y, phi) {
                out.push(c.path(radius));
            }
        });
    }
    out
}

/// The shortest path from `from` to `to` turning no tighter than `radius` metres, driving
/// forward and in reverse as needed; of equally short candidates the first found. `None` only
/// for a radius that is not positive, an input that is not finite, or one so extreme that the
/// goal's distance in radii overflows.
///
/// ```
/// use furrow::path::curve::Pose;
/// use furrow::path::reeds_shepp::reeds_shepp_shortest;
/// use std::f64::consts::PI;
///
/// // A quarter turn to the left is one forward arc.
/// let from = Pose::new(0.0, 0.0, 0.0);
/// let to = Pose::new(4.0, 4.0, PI / 2.0);
/// let p = reeds_shepp_shortest(from, to, 4.0).ok_or("no path")?;
/// assert_eq!(p.word(), "L+");
/// assert_eq!(p.cusps(), 0);
/// assert!((p.length() - 2.0 * PI).abs() < 1e-9);
/// assert!(reeds_shepp_shortest(from, to, -1.0).is_none());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn reeds_shepp_shortest(from: Pose, to: Pose, radius: f64) -> Option<RsPath> {
    let (x, y, phi) = normalise(from, to, radius)?;
    let mut best: Option<(f64, Candidate)> = None;
    candidates(x, y, phi, &mut |_, c| {
        let len = c.length();
        let better = match best {
            None => true,
            Some((b, _)) => len < b,
        };
        if len.is_finite() && better && c.reaches(x, y, phi) {
            best = Some((len, c));
        }
    });
    best.map(|(_, c)| c.path(radius))
}

#[cfg(test)]
mod tests {
    use super::super::curve;
    use super::super::dubins::dubins_shortest;
    use super::*;

    use crate::rng::SplitMix64 as Rng;

    use super::super::testing::{assert_reaches, case, drive};

    /// Checks a path's shape and that it is drivable from `from` to `to`.
    fn check_path(p: &RsPath, from: Pose, to: Pose) {
        assert!(p.parts.len() <= 5, "{p:?}");
        assert!(["CSC", "CCC", "CCCC", "CCSC", "CCSCC"].contains(&p.family));
        for w in p.parts.windows(2) {
            assert!(w[0].steer != w[1].steer || w[0].gear != w[1].gear, "{p:?}");
        }
        let segs = p.segments(from);
        assert_eq!(segs.len(), p.parts.len());
        for (s, part) in segs.iter().zip(&p.parts) {
            assert!(part.length.is_finite() && part.length > 0.0, "{p:?}");
            assert_eq!(s.length, part.length);
            assert_eq!(s.gear, part.gear);
            assert_eq!(s.sharpness, 0.0);
            match part.steer {
                Steer::Straight => assert_eq!(s.curvature, 0.0),
                Steer::Left => assert_eq!(s.curvature, 1.0 / p.radius),
                Steer::Right => assert_eq!(s.curvature, -1.0 / p.radius),
            }
        }
        assert!((curve::length(&segs) - p.length()).abs() < 1e-12);
        let changes = p
            .parts
            .windows(2)
            .filter(|w| w[0].gear != w[1].gear)
            .count();
        assert_eq!(p.cusps(), changes);
        let word = p.word();
        assert_eq!(word.len(), 2 * p.parts.len());
        for (i, part) in p.parts.iter().enumerate() {
            let letter = match part.steer {
                Steer::Left => "L",
                Steer::Straight => "S",
                Steer::Right => "R",
            };
            let sign = if part.gear == Gear::Forward { "+" } else { "-" };
            assert_eq!(&word[2 * i..2 * i + 2], format!("{letter}{sign}"));
        }
        assert_reaches(drive(from, &segs), to, p);
        assert_reaches(p.end(from), to, p);
    }

    fn shortest(from: Pose, to: Pose, r: f64) -> RsPath {
        match reeds_shepp_shortest(from, to, r) {
            Some(p) => p,
            None => panic!("no path from {from:?} to {to:?}"),
        }
    }

    #[test]
    fn every_candidate_reaches_its_goal() {
        let mut rng = Rng::new(11);
        let mut hits = [0usize; APPLICATIONS];
        let mut wins = std::collections::HashMap::new();
        for _ in 0..4000 {
            let (from, to, r) = case(&mut rng);
            // Every formula's raw candidate is exact: nothing is thrown away.
            let Some((x, y, phi)) = normalise(from, to, r) else {
                panic!("bad input")
            };
            let mut raw = 0;
            candidates(x, y, phi, &mut |id, c| {
                assert!(
                    c.reaches(x, y, phi),
                    "application {id}: {c:?} misses {x} {y} {phi}"
                );
                hits[id] += 1;
                raw += 1;
            });
            let all = reeds_shepp_all(from, to, r);
            assert_eq!(all.len(), raw);
            assert!(!all.is_empty());
            for p in &all {
                check_path(p, from, to);
                assert_eq!(p.radius, r);
            }
            let best = shortest(from, to, r);
            check_path(&best, from, to);
            let min = all.iter().map(RsPath::length).fold(f64::INFINITY, f64::min);
            assert!((best.length() - min).abs() < 1e-9 * (1.0 + min));
            assert!(all.iter().all(|p| best.length() <= p.length() + 1e-9));
            *wins.entry(best.family).or_insert(0) += 1;
            // Nothing beats a straight line, or turning on the way.
            assert!(best.length() >= from.distance(&to) - 1e-9);
            assert!(best.length() >= r * from.heading_change(&to).abs() - 1e-9);
        }
        // Every formula application finds paths, and every family is sometimes shortest.
        assert!(hits.iter().all(|&h| h > 0), "{hits:?}");
        for f in ["CSC", "CCC", "CCCC", "CCSC", "CCSCC"] {
            assert!(wins.get(f).is_some_and(|&w| w > 5), "{wins:?}");
        }
    }

    #[test]
    fn poses_on_a_grid_are_reached() {
        // Exact alignments: integer offsets in half radii, headings in quarter turns.
        let r = 2.0;
        let from = Pose::new(0.0, 0.0, 0.0);
        for i in -8..=8 {
            for j in -8..=8 {
                for k in -1..=2 {
                    let to = Pose::new(i as f64 * r / 2.0, j as f64 * r / 2.0, k as f64 * PI / 2.0);
                    let all = reeds_shepp_all(from, to, r);
                    for p in &all {
                        check_path(p, from, to);
                    }
                    let best = shortest(from, to, r);
                    check_path(&best, from, to);
                    assert!(all.iter().all(|p| best.length() <= p.length()));
                    assert!(best.length() >= from.distance(&to) - 1e-9);
                    let back = shortest(to, from, r);
                    assert!(
                        (best.length() - back.length()).abs() < 1e-9,
                        "{best:?} {back:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn never_longer_than_dubins_either_way() {
        // Forward-only paths are Reeds-Shepp paths, and so are reverse-only ones: driving
        // from `to` to `from` forward, backwards in time.
        let mut rng = Rng::new(12);
        let mut shorter = 0;
        for _ in 0..4000 {
            let (from, to, r) = case(&mut rng);
            let rs = shortest(from, to, r).length();
            let (Some(fwd), Some(rev)) =
                (dubins_shortest(from, to, r), dubins_shortest(to, from, r))
            else {
                panic!("no Dubins path")
            };
            assert!(rs <= fwd.length() + 1e-9 * (1.0 + rs), "{rs} vs {fwd:?}");
            assert!(rs <= rev.length() + 1e-9 * (1.0 + rs), "{rs} vs {rev:?}");
            if rs < fwd.length().min(rev.length()) - 1e-6 {
                shorter += 1;
            }
        }
        assert!(shorter > 1000, "{shorter}");
    }

    #[test]
    fn symmetric_under_reversal_mirroring_and_moving() {
        let mut rng = Rng::new(13);
        for _ in 0..3000 {
            let (from, to, r) = case(&mut rng);
            let len = shortest(from, to, r).length();
            let tol = 1e-9 * (1.0 + len);
            // Driven backwards in time: the same length.
            let back = shortest(to, from, r).length();
            assert!((len - back).abs() < tol, "{len} vs {back}");
            // Mirrored in the x axis.
            let m = |p: Pose| Pose::new(p.x, -p.y, -p.heading);
            let mirrored = shortest(m(from), m(to), r).length();
            assert!((len - mirrored).abs() < tol, "{len} vs {mirrored}");
            // Turned and moved together.
            let frame = Pose::new(
                rng.range(-100.0, 100.0),
                rng.range(-100.0, 100.0),
                rng.range(-PI, PI),
            );
            let moved = shortest(from.from_frame(&frame), to.from_frame(&frame), r).length();
            assert!((len - moved).abs() < 1e-8 * (1.0 + len), "{len} vs {moved}");
            // Scaled with the radius.
            let s = |p: Pose| Pose::new(3.0 * p.x, 3.0 * p.y, p.heading);
            let scaled = shortest(s(from), s(to), 3.0 * r).length();
            assert!((3.0 * len - scaled).abs() < 3.0 * tol, "{len} vs {scaled}");
        }
    }

    #[test]
    fn straight_ahead_and_back() {
        let mut rng = Rng::new(14);
        for _ in 0..500 {
            let r = rng.range(0.5, 15.0);
            let from = Pose::new(
                rng.range(-50.0, 50.0),
                rng.range(-50.0, 50.0),
                rng.range(-PI, PI),
            );
            let d = rng.range(0.01, 100.0);
            let (s, c) = from.heading.sin_cos();
            for (sign, word) in [(1.0, "S+"), (-1.0, "S-")] {
                let to = Pose::new(from.x + sign * d * c, from.y + sign * d * s, from.heading);
                let p = shortest(from, to, r);
                check_path(&p, from, to);
                assert_eq!(p.word(), word);
                assert!((p.length() - d).abs() < 1e-9 * (1.0 + d), "{p:?} vs {d}");
                assert_eq!(p.cusps(), 0);
            }
        }
        // No move at all: no parts.
        let o = Pose::new(3.0, 4.0, 1.0);
        let p = shortest(o, o, 2.0);
        assert!(p.parts.is_empty() && p.length() == 0.0 && p.cusps() == 0);
        assert_eq!(p.end(o), o);
    }

    #[test]
    fn single_arcs() {
        // Up to a half turn, one arc in either gear is shortest.
        let o = Pose::new(0.0, 0.0, 0.0);
        let r = 3.0;
        for a in [0.1, 1.0, PI / 2.0, 2.5, 3.0, PI] {
            for (s, g) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
                let seg = Segment::arc(
                    o,
                    a * r,
                    s / r,
                    if g > 0.0 {
                        Gear::Forward
                    } else {
                        Gear::Reverse
                    },
                );
                let to = seg.end();
                let p = shortest(o, to, r);
                check_path(&p, o, to);
                assert_eq!(p.parts.len(), 1, "{p:?}");
                assert!((p.length() - a * r).abs() < 1e-9);
            }
        }
    }

    #[test]
    fn turning_on_the_spot() {
        let r = 1.0;
        let o = Pose::new(0.0, 0.0, 0.0);
        for h in [PI / 2.0, -PI / 2.0, PI, PI / 4.0, 3.0 * PI / 4.0] {
            let to = Pose::new(0.0, 0.0, h);
            let p = shortest(o, to, r);
            check_path(&p, o, to);
            let Some(d) = dubins_shortest(o, to, r) else {
                panic!("no Dubins path")
            };
            println!(
                "turn on the spot by {h:.4}: {} {} ({} cusps), Dubins {}",
                p.length(),
                p.word(),
                p.cusps(),
                d.length()
            );
            // Three arcs with two cusps turn it without leaving the spot for no more than the
            // turn itself, the least any path can take.
            assert!((p.length() - r * h.abs()).abs() < 1e-9, "{p:?}");
            assert!(p.length() < d.length());
            assert_eq!(p.cusps(), 2, "{p:?}");
            let (b, _) = brute(o, to, r);
            assert!(
                p.length() <= b + 1e-9 && b <= p.length() + 1e-4,
                "{p:?} vs {b}"
            );
        }
    }

    #[test]
    fn bad_input_gives_none() {
        let o = Pose::new(0.0, 0.0, 0.0);
        let to = Pose::new(10.0, 3.0, 1.0);
        for r in [0.0, -1.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(reeds_shepp_shortest(o, to, r).is_none());
            assert!(reeds_shepp_all(o, to, r).is_empty());
        }
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            for p in [
                Pose::new(bad, 0.0, 0.0),
                Pose::new(0.0, bad, 0.0),
                Pose::new(0.0, 0.0, bad),
            ] {
                assert!(reeds_shepp_shortest(p, to, 1.0).is_none());
                assert!(reeds_shepp_shortest(o, p, 1.0).is_none());
                assert!(reeds_shepp_all(o, p, 1.0).is_empty());
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
            for p in reeds_shepp_all(a, b, r) {
                assert!(p.length().is_finite());
            }
            if let Some(p) = reeds_shepp_shortest(a, b, r) {
                assert!(p.length().is_finite());
            }
        }
    }

    // ---- An independent brute force: circle tangents built geometrically, not the formulas.

    /// A piece: steering (+1 left, 0 straight, −1 right) and a signed amount: for arcs the
    /// heading change (radians), for lines the metres moved along the heading.
    type Piece = (f64, f64);

    fn centre(p: Pose, s: f64, r: f64) -> (f64, f64) {
        (p.x - s * r * p.heading.sin(), p.y + s * r * p.heading.cos())
    }

    /// The pose on the circle of `p` steering `s` after the heading changes by `delta`.
    fn arc_end(p: Pose, s: f64, delta: f64, r: f64) -> Pose {
        let (cx, cy) = centre(p, s, r);
        let h = p.heading + delta;
        Pose::new(cx + s * r * h.sin(), cy - s * r * h.cos(), h)
    }

    fn cost(pieces: &[Piece], r: f64) -> f64 {
        pieces
            .iter()
            .map(|&(s, v)| if s == 0.0 { v.abs() } else { r * v.abs() })
            .sum()
    }

    /// The shortest arc–line–arc in any gears: both steerings at each end, every common
    /// tangent of the two circles, each arc the shorter way round.
    fn csc(a: Pose, b: Pose, r: f64) -> Option<(f64, [Piece; 3])> {
        let mut best: Option<(f64, [Piece; 3])> = None;
        for s1 in [1.0, -1.0] {
            for s2 in [1.0, -1.0] {
                let c1 = centre(a, s1, r);
                let c2 = centre(b, s2, r);
                let (wx, wy) = (c2.0 - c1.0, c2.1 - c1.1);
                let w = wx.planar_hypot(wy);
                let k = r * (s2 - s1) / w;
                if k.is_nan() || k.abs() > 1.0 {
                    continue;
                }
                let (aw, asn) = (wy.atan2(wx), k.asin());
                for psi in [aw - asn, aw - PI + asn] {
                    let pieces = [
                        (s1, wrap(psi - a.heading)),
                        (0.0, wx * psi.cos() + wy * psi.sin()),
                        (s2, wrap(b.heading - psi)),
                    ];
                    let len = cost(&pieces, r);
                    if best.is_none_or(|(l, _)| len < l) {
                        best = Some((len, pieces));
                    }
                }
            }
        }
        best
    }

    /// The shortest three arcs in any gears: the middle circle touches both end circles.
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
                let pieces = [
                    (s1, wrap(psi1 - a.heading)),
                    (s2, wrap(psi2 - psi1)),
                    (s1, wrap(b.heading - psi2)),
                ];
                let len = cost(&pieces, r);
                if best.is_none_or(|(l, _)| len < l) {
                    best = Some((len, pieces));
                }
            }
        }
        best
    }

    /// The best of: a first arc, then the best arc–line–arc or three arcs; and a first and a
    /// last arc with the best arc–line–arc between. Each arc is tried in both steerings at
    /// every heading change in a grid over (−π, π] (¼° for the first search, 2° for the
    /// second), then the best found is refined on finer grids around it. Covers CSC, CCC,
    /// CCCC, CCSC, CSCC and CCSCC shapes in any gears.
    fn brute(a: Pose, b: Pose, r: f64) -> (f64, Vec<Piece>) {
        let one = |s0: f64, d0: f64| -> Option<(f64, Vec<Piece>)> {
            let p = arc_end(a, s0, d0, r);
            let rest = [csc(p, b, r), ccc(p, b, r)]
                .into_iter()
                .flatten()
                .min_by(|x, y| x.0.total_cmp(&y.0))?;
            let mut pieces = vec![(s0, d0)];
            pieces.extend_from_slice(&rest.1);
            Some((r * d0.abs() + rest.0, pieces))
        };
        let two = |s0: f64, d0: f64, s4: f64, d4: f64| -> Option<(f64, Vec<Piece>)> {
            let p = arc_end(a, s0, d0, r);
            let q = arc_end(b, s4, -d4, r);
            let rest = csc(p, q, r)?;
            let mut pieces = vec![(s0, d0)];
            pieces.extend_from_slice(&rest.1);
            pieces.push((s4, d4));
            Some((r * (d0.abs() + d4.abs()) + rest.0, pieces))
        };
        let keep = |best: &mut (f64, Vec<Piece>), c: Option<(f64, Vec<Piece>)>| {
            if let Some(c) = c {
                if c.0 < best.0 {
                    *best = c;
                }
            }
        };
        let mut best = (f64::INFINITY, Vec::new());
        // One free arc.
        let n1 = 720;
        for s0 in [1.0, -1.0] {
            let mut local = (f64::INFINITY, Vec::new());
            let mut at = 0.0;
            for i in -n1..=n1 {
                let d0 = i as f64 * PI / n1 as f64;
                let c = one(s0, d0);
                if c.as_ref().is_some_and(|c| c.0 < local.0) {
                    at = d0;
                }
                keep(&mut local, c);
            }
            let mut step = PI / n1 as f64;
            for _ in 0..6 {
                step /= 4.0;
                let centre = at;
                for i in -8..=8 {
                    let d0 = centre + i as f64 * step;
                    let c = one(s0, d0);
                    if c.as_ref().is_some_and(|c| c.0 < local.0) {
                        at = d0;
                    }
                    keep(&mut local, c);
                }
            }
            keep(&mut best, Some(local));
        }
        // Two free arcs.
        let n2 = 90;
        for s0 in [1.0, -1.0] {
            for s4 in [1.0, -1.0] {
                let mut local = (f64::INFINITY, Vec::new());
                let mut at = (0.0, 0.0);
                for i in -n2..=n2 {
                    for j in -n2..=n2 {
                        let (d0, d4) = (i as f64 * PI / n2 as f64, j as f64 * PI / n2 as f64);
                        let c = two(s0, d0, s4, d4);
                        if c.as_ref().is_some_and(|c| c.0 < local.0) {
                            at = (d0, d4);
                        }
                        keep(&mut local, c);
                    }
                }
                let mut step = PI / n2 as f64;
                for _ in 0..8 {
                    step /= 3.0;
                    let centre = at;
                    for i in -4..=4 {
                        for j in -4..=4 {
                            let d0 = centre.0 + i as f64 * step;
                            let d4 = centre.1 + j as f64 * step;
                            let c = two(s0, d0, s4, d4);
                            if c.as_ref().is_some_and(|c| c.0 < local.0) {
                                at = (d0, d4);
                            }
                            keep(&mut local, c);
                        }
                    }
                }
                keep(&mut best, Some(local));
            }
        }
        best
    }

    fn pieces_to_segments(from: Pose, pieces: &[Piece], r: f64) -> Vec<Segment> {
        let mut at = from;
        let mut out = Vec::new();
        for &(s, v) in pieces {
            // On an arc the heading changes by gear × steering × angle; on a line the
            // machine moves gear × metres along its heading.
            let forward = if s == 0.0 { v >= 0.0 } else { s * v >= 0.0 };
            let gear = if forward {
                Gear::Forward
            } else {
                Gear::Reverse
            };
            let seg = if s == 0.0 {
                Segment::line(at, v.abs(), gear)
            } else {
                Segment::arc(at, r * v.abs(), s / r, gear)
            };
            at = seg.end();
            out.push(seg);
        }
        out
    }

    /// For each of the 44 formula applications, a goal (normalised) where it alone gives the
    /// shortest path, by more than `margin` over every other application.
    fn sole_winners(margin: f64) -> Vec<Option<(f64, f64, f64)>> {
        let mut rng = Rng::new(18);
        let mut found = vec![None; APPLICATIONS];
        for _ in 0..300_000 {
            let (x, y, phi) = (
                rng.range(-4.0, 4.0),
                rng.range(-4.0, 4.0),
                rng.range(-PI, PI),
            );
            let mut lengths = [f64::INFINITY; APPLICATIONS];
            candidates(x, y, phi, &mut |id, c| {
                lengths[id] = lengths[id].min(c.length())
            });
            let (best, len) = lengths
                .iter()
                .enumerate()
                .fold(
                    (0, f64::INFINITY),
                    |b, (i, &l)| if l < b.1 { (i, l) } else { b },
                );
            let runner_up = lengths
                .iter()
                .enumerate()
                .filter(|&(i, _)| i != best)
                .fold(f64::INFINITY, |m, (_, &l)| m.min(l));
            if runner_up > len + margin && found[best].is_none() {
                found[best] = Some((x, y, phi));
            }
            if found.iter().all(Option::is_some) {
                break;
            }
        }
        found
    }

    #[test]
    fn every_formula_is_sometimes_the_only_shortest() {
        // No formula application is redundant: each has goals where nothing else comes close.
        let found = sole_winners(1e-3);
        let missing: Vec<usize> = (0..APPLICATIONS).filter(|&i| found[i].is_none()).collect();
        assert!(missing.is_empty(), "never the only shortest: {missing:?}");
    }

    #[test]
    fn brute_force_finds_nothing_shorter() {
        // Where each formula application alone is shortest, and at random poses: the brute
        // force, which knows nothing of the formulas, finds no shorter path and comes close.
        let mut rng = Rng::new(15);
        let mut cases = Vec::new();
        for (id, goal) in sole_winners(1e-3).into_iter().enumerate() {
            let Some((x, y, phi)) = goal else {
                panic!("application {id} is never the only shortest")
            };
            let r = rng.range(1.0, 15.0);
            let from = Pose::new(
                rng.range(-50.0, 50.0),
                rng.range(-50.0, 50.0),
                rng.range(-PI, PI),
            );
            let to = Pose::new(x * r, y * r, phi).from_frame(&from);
            cases.push((from, to, r));
        }
        cases.extend((0..10).map(|_| case(&mut rng)));
        let mut worst: f64 = 0.0;
        for (from, to, r) in cases {
            let (b, pieces) = brute(from, to, r);
            // The brute force's own path is real.
            let segs = pieces_to_segments(from, &pieces, r);
            assert_reaches(drive(from, &segs), to, &pieces);
            assert!((curve::length(&segs) - b).abs() < 1e-9 * (1.0 + b));
            let p = shortest(from, to, r);
            assert!(
                p.length() <= b + 1e-9 * (1.0 + b),
                "{p:?} longer than brute force {b} {pieces:?}"
            );
            worst = worst.max((b - p.length()) / r);
            // And it comes close: the formulas are not beating it by some mistake.
            assert!(b <= p.length() + 1e-6 * r, "brute force {b} vs {p:?}");
        }
        println!("brute force is at most {worst:.2e} radii longer");
    }

    #[test]
    fn no_random_path_is_shorter() {
        // Drive random arcs and lines in random gears; the shortest path to where they end is
        // no longer.
        let mut rng = Rng::new(16);
        let mut equal = 0;
        for _ in 0..10000 {
            let r = rng.range(1.0, 15.0);
            let from = Pose::new(
                rng.range(-50.0, 50.0),
                rng.range(-50.0, 50.0),
                rng.range(-PI, PI),
            );
            let n = 1 + (rng.next_u64() % 5) as usize;
            let mut segs: Vec<Segment> = Vec::new();
            let mut at = from;
            for _ in 0..n {
                let gear = if rng.unit() < 0.5 {
                    Gear::Forward
                } else {
                    Gear::Reverse
                };
                let seg = match rng.next_u64() % 4 {
                    0 => Segment::line(at, rng.range(0.0, 4.0 * r), gear),
                    1 => Segment::arc(
                        at,
                        r * PI / 2.0,
                        if rng.unit() < 0.5 { 1.0 } else { -1.0 } / r,
                        gear,
                    ),
                    _ => Segment::arc(
                        at,
                        r * rng.range(0.0, PI),
                        if rng.unit() < 0.5 { 1.0 } else { -1.0 } / r,
                        gear,
                    ),
                };
                at = seg.end();
                segs.push(seg);
            }
            let len = curve::length(&segs);
            let p = shortest(from, at, r);
            check_path(&p, from, at);
            assert!(p.length() <= len + 1e-9 * (1.0 + len), "{p:?} vs {segs:?}");
            if p.length() > len - 1e-6 {
                equal += 1;
            }
        }
        // Many random paths are themselves shortest: the bound is tight, not vacuous.
        assert!(equal > 1000, "{equal}");
    }

    #[test]
    fn timing() {
        let mut rng = Rng::new(17);
        let cases: Vec<_> = (0..1000).map(|_| case(&mut rng)).collect();
        let reps = 50;
        let start = std::time::Instant::now();
        let mut total = 0.0;
        for _ in 0..reps {
            for &(a, b, r) in &cases {
                total += reeds_shepp_shortest(a, b, r).map_or(0.0, |p| p.length());
            }
        }
        let per = start.elapsed().as_secs_f64() / (reps * cases.len()) as f64;
        let start = std::time::Instant::now();
        let mut count = 0;
        for &(a, b, r) in &cases {
            count += reeds_shepp_all(a, b, r).len();
        }
        let per_all = start.elapsed().as_secs_f64() / cases.len() as f64;
        println!(
            "reeds_shepp_shortest: {:.3} µs per call; reeds_shepp_all: {:.3} µs per call, {:.1} candidates (checksum {total:.1})",
            per * 1e6,
            per_all * 1e6,
            count as f64 / cases.len() as f64
        );
    }
}
