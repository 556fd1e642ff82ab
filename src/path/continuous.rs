//! Continuous-curvature (CC) turns and forward CC-Dubins paths, after Fraichard & Scheuer,
//! "From Reeds and Shepp's to continuous-curvature paths" (IEEE T-RO 20(6), 2004).
//!
//! A machine whose steering can only change at a bounded rate cannot follow a Dubins path:
//! at every junction of a line and an arc the curvature would jump. Here every path starts
//! and ends with straight steering, its curvature changes continuously, never exceeds
//! `κmax = 1/r` in size and never changes faster than `σmax` per metre driven.
//!
//! # The CC turn and the CC circle
//!
//! A *CC turn* of deflection `δ ≥ δmin = κmax²/σmax` is a clothoid from curvature 0 to `κmax`
//! (length `κmax/σmax`, sharpness `σmax`, turning `θᵢ = κmax²/(2σmax)`), a circular arc of
//! curvature `κmax` turning `δ − δmin`, and the mirror clothoid back to curvature 0. Starting
//! at the origin facing east, the first clothoid ends at `(xᵢ, yᵢ)` and the arc's centre is
//! `Ω = (xᵢ − sin θᵢ/κmax, yᵢ + cos θᵢ/κmax)`. By symmetry every CC turn starts and ends on the
//! *CC circle* of radius `R_Ω = |Ω|` about `Ω`: it enters with its heading `μ = atan(Ωx/Ωy)`
//! inside the circle's tangent and leaves with its heading `μ` outside it. In the frame of a
//! pose (facing east) the centre of the left circle a turn *starts* on is at `(Ωx, Ωy)`, that
//! of the left circle a turn *ends* on is at `(−Ωx, Ωy)`; right circles mirror `y`. Going
//! round, a turn of deflection `δ` sweeps `δ + 2μ` of its circle.
//!
//! For `0 < δ < δmin` the CC turn is Scheuer & Fraichard's symmetric *elementary path*: two
//! clothoids of opposite sharpness `σ`, with `σ` chosen so that the path still ends on the CC
//! circle at the angle `μ`. Its chord must be `2·R_Ω·sin(δ/2 + μ)`, and a clothoid pair of
//! sharpness σ has chord `2(X cos δ/2 + Y sin δ/2)/√σ`, where `(X, Y)` is the end of the
//! unit-sharpness clothoid of length `√δ`; so `√σ = (X cos δ/2 + Y sin δ/2)/(R_Ω sin(δ/2 + μ))`.
//! This σ grows from 0 (at `δ = 0`) to `σmax` (at `δmin`), so `σ ≤ σmax` and the peak curvature
//! `√(σδ) < κmax` (checked numerically; it holds while `δ < 4.59` rad, beyond which the pair
//! cannot reach the circle at all). At `δ = 0` the turn is a line of length `2·R_Ω·sin μ`.
//! Because every turn ends exactly on its circle, the words below are exact.
//!
//! # The words
//!
//! `from`'s start circles and `to`'s end circles are joined as in Dubins' construction:
//!
//! * **CSC, same side** (LSL, RSR): the line leaves circle 1 at `μ` outside its tangent and
//!   joins circle 2 at `μ` inside it, so it runs parallel to the line of centres, and its
//!   length is the centre distance minus `2Ωx` (the word exists if that is not negative).
//! * **CSC, opposite sides** (LSR, RSL): in the frame of the line's heading ψ the centres differ
//!   by `(ℓ + 2Ωx, ∓2Ωy)`, so `ℓ = √(D² − 4Ωy²) − 2Ωx`, which needs `D ≥ 2R_Ω`.
//! * **CCC** (LRL, RLR): two opposite turns meet at a point of zero curvature that is the
//!   midpoint of their centres: the end pose of the first is the start pose of the second, so
//!   the centres are `2R_Ω` apart (`2·(Ωx, ∓Ωy)` in the frame of the heading there); the middle
//!   circle is found from the outer ones (`D ≤ 4R_Ω`), both solutions are tried.
//!
//! Each turn's deflection is taken in `[0, 2π)` in its own sense (so loops of nearly a full
//! circle are allowed). Every candidate is then *built* as [`Segment`]s, chained each from the
//! previous one's end, and *verified*: it must end at `to` within [`POSITION_TOLERANCE`] metres
//! and [`HEADING_TOLERANCE`] radians with curvature and sharpness within the limits; a candidate
//! that fails is dropped (with sound settings none does). A lone line ("S") is offered as well
//! when `to` lies straight ahead of `from`.
//!
//! # Headland turns
//!
//! [`cc_u_turn`] turns from the end of one swath onto the next, coming back. Besides the words
//! it tries a single CC turn of π whose curvature, below `κmax`, is chosen so that it lands on
//! the neighbour swath (`2·Ωy = spacing`): for spacings just over `2·R_Ω` no CC-Dubins word at
//! full lock arrives without a loop. Of the candidates it takes the shortest that never reaches
//! back behind the end line into the field ([`along_range`] gives that reach and the headland
//! depth a turn needs).
//!
//! # Limits
//!
//! CC-Dubins paths are not the shortest continuous-curvature paths. Each CC turn, even of zero
//! deflection, takes `2Ωx` of room, so where a Dubins path has a very short line or a nearly
//! vanishing turn the CC word may not exist and the next best word can be a long loop: over
//! random pairs (r 3–15 m, σmax 0.05–1 /m²) about 98 % are within 5 % of the Dubins length but
//! 0.3–1 % are more than 25 % longer (goals close by, reachable by Dubins with one turn and a
//! small correction). As `σmax → ∞` the paths tend to Dubins'. Settings with
//! `δmin = κmax²/σmax` above about 4.59 rad (very slow steering for the radius) cannot make
//! deflections between 4.59 rad and `δmin`, so fewer words exist.
//!
//! ```
//! use furrow::path::continuous::{cc_dubins_shortest, cc_u_turn, CcSettings};
//! use furrow::path::curve::Pose;
//! use std::f64::consts::PI;
//!
//! // Turning radius 6 m, steering from straight to full lock over 10 m (σ = κmax / 10 m).
//! let s = CcSettings::from_radius(6.0, 1.0 / 60.0);
//! let from = Pose::new(0.0, 0.0, 0.0);
//! let to = Pose::new(30.0, 20.0, PI / 2.0);
//! let path = cc_dubins_shortest(from, to, &s).ok_or("no path")?;
//! let end = path.end().ok_or("empty")?;
//! assert!(end.distance(&to) < 1e-6 && end.heading_change(&to).abs() < 1e-9);
//! for w in path.segments.windows(2) {
//!     // The steering never jumps.
//!     assert!((w[0].curvature_at(w[0].length) - w[1].curvature).abs() < 1e-9);
//! }
//!
//! // A headland turn onto the swath 4 m to the left, coming back the other way.
//! let u = cc_u_turn(from, 4.0, true, &s).ok_or("no u-turn")?;
//! let end = u.end().ok_or("empty")?;
//! assert!(end.distance(&Pose::new(0.0, 4.0, PI)) < 1e-6);
//! # Ok::<(), &str>(())
//! ```

use super::curve::{Gear, Pose, Segment};
use crate::geometry::PlanarHypot;
use crate::sort::SharedSort;
use std::f64::consts::{PI, TAU};

/// A built path must end this close to its goal, metres.
pub const POSITION_TOLERANCE: f64 = 1e-6;
/// A built path's final heading must be this close to its goal's, radians.
pub const HEADING_TOLERANCE: f64 = 1e-9;

/// Longest clothoid this module will build, metres (keeps the integration bounded).
const MAX_CLOTHOID: f64 = 1e6;
/// Deflections below this are straight lines.
const ZERO_TURN: f64 = 1e-12;
/// Deflections within this of a full circle are no turn at all (the remainder of a rounding).
const FULL_TURN_SNAP: f64 = 1e-11;

/// The machine's steering limits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CcSettings {
    /// Largest steering curvature, 1/m (one over the minimum turning radius).
    pub max_curvature: f64,
    /// Largest rate of change of curvature per metre driven, 1/m².
    pub max_sharpness: f64,
}

impl CcSettings {
    /// Settings from the minimum turning radius (metres) and the maximum sharpness (1/m²).
    pub fn from_radius(min_radius: f64, max_sharpness: f64) -> Self {
        CcSettings {
            max_curvature: 1.0 / min_radius,
            max_sharpness,
        }
    }

    /// The CC circle these settings give, or `None` if they are not finite and positive (or so
    /// extreme that a clothoid to full lock would be longer than 1000 km).
    pub fn geometry(&self) -> Option<CcGeometry> {
        let k = self.max_curvature;
        let sig = self.max_sharpness;
        if !(k.is_finite() && sig.is_finite() && k > 0.0 && sig > 0.0) {
            return None;
        }
        let clothoid_length = k / sig;
        if !(clothoid_length.is_finite() && clothoid_length <= MAX_CLOTHOID) {
            return None;
        }
        let origin = Pose::new(0.0, 0.0, 0.0);
        let e = Segment::clothoid(origin, clothoid_length, 0.0, sig, Gear::Forward).end();
        let theta = e.heading;
        let ox = e.x - theta.sin() / k;
        let oy = e.y + theta.cos() / k;
        let radius = ox.planar_hypot(oy);
        let g = CcGeometry {
            max_curvature: k,
            max_sharpness: sig,
            clothoid_length,
            centre_x: ox,
            centre_y: oy,
            radius,
            mu: ox.atan2(oy),
            min_deflection: k * k / sig,
        };
        let finite = [ox, oy, radius, g.mu, g.min_deflection]
            .iter()
            .all(|v| v.is_finite());
        (finite && radius > 0.0).then_some(g)
    }
}

/// The CC circle of some [`CcSettings`] (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CcGeometry {
    /// κmax, 1/m.
    pub max_curvature: f64,
    /// σmax, 1/m².
    pub max_sharpness: f64,
    /// Length of a clothoid from straight to full lock, `κmax/σmax`, metres.
    pub clothoid_length: f64,
    /// `Ωx`: the centre of a left turn's CC circle, ahead of its start pose, metres.
    pub centre_x: f64,
    /// `Ωy`: the centre of a left turn's CC circle, left of its start pose, metres.
    pub centre_y: f64,
    /// `R_Ω`, metres.
    pub radius: f64,
    /// `μ`, the angle between a CC turn's heading and its circle's tangent at either end.
    pub mu: f64,
    /// `δmin = κmax²/σmax`: the smallest deflection of a turn that reaches full lock.
    pub min_deflection: f64,
}

impl CcGeometry {
    /// The centre of the CC circle a turn from `from` runs on (left or right).
    pub fn start_centre(&self, from: Pose, left: bool) -> (f64, f64) {
        let side = if left { 1.0 } else { -1.0 };
        offset(from, self.centre_x, side * self.centre_y)
    }

    /// Where a CC turn of `deflection` (positive to the left) from `from` ends: on the CC
    /// circle, heading `μ` outside its tangent.
    pub fn turn_end(&self, from: Pose, deflection: f64) -> Pose {
        let side = if deflection < 0.0 { -1.0 } else { 1.0 };
        let c = self.start_centre(from, side > 0.0);
        let heading = from.heading + deflection;
        let end = Pose::new(c.0, c.1, heading);
        let (x, y) = offset(end, self.centre_x, -side * self.centre_y);
        Pose::new(x, y, heading)
    }
}

/// A forward continuous-curvature path and the word it follows.
#[derive(Debug, Clone, PartialEq)]
pub struct CcPath {
    /// "LSL", "RSR", "LSR", "RSL", "LRL", "RLR", "S" (a lone line) or, from [`cc_u_turn`], "L"
    /// or "R" (a single wide turn).
    pub word: &'static str,
    /// The pieces, each starting where the previous one ends.
    pub segments: Vec<Segment>,
}

impl CcPath {
    /// Total length, metres.
    pub fn length(&self) -> f64 {
        super::curve::length(&self.segments)
    }

    /// Where it ends.
    pub fn end(&self) -> Option<Pose> {
        super::curve::end(&self.segments)
    }
}

/// One CC turn of `deflection` radians from `from` (left if positive, right if negative),
/// forward: a clothoid, an arc at full lock and a clothoid if `|deflection| ≥ δmin`, otherwise
/// the elementary clothoid pair of lower sharpness that still ends on the CC circle (a line of
/// `2·R_Ω·sin μ` for a zero deflection; see the module documentation). It ends at
/// [`CcGeometry::turn_end`]. Empty if an input is not finite or the settings are unusable.
pub fn cc_turn(from: Pose, deflection: f64, s: &CcSettings) -> Vec<Segment> {
    let mut out = Vec::new();
    if !(pose_finite(&from) && deflection.is_finite()) {
        return out;
    }
    let Some(g) = s.geometry() else {
        return out;
    };
    let Some(plan) = plan_turn(&g, deflection.abs(), deflection >= 0.0) else {
        return out;
    };
    let mut cursor = from;
    emit_turn(&plan, &mut cursor, &mut out);
    out
}

/// Every CC-Dubins word from `from` to `to` that exists and verifies (the shortest solution of
/// each), in the order LSL, RSR, LSR, RSL, LRL, RLR (and "S" first if `to` lies straight ahead).
/// Empty if an input is not finite or the settings are unusable.
pub fn cc_dubins_all(from: Pose, to: Pose, s: &CcSettings) -> Vec<CcPath> {
    let Some((g, mut cands)) = prepare(from, to, s) else {
        return Vec::new();
    };
    cands.shared_sort_by(|a, b| a.length.total_cmp(&b.length));
    let mut found: Vec<CcPath> = Vec::new();
    for c in &cands {
        if found.iter().any(|p| p.word == c.word) {
            continue;
        }
        if let Some(p) = build_verified(c, from, to, &g) {
            found.push(p);
        }
    }
    found.shared_sort_by_key(|p| WORDS.iter().position(|w| *w == p.word));
    found
}

/// The shortest CC-Dubins path from `from` to `to` (see [`cc_dubins_all`]); `None` if an input
/// is not finite, the settings are unusable or no word verifies.
pub fn cc_dubins_shortest(from: Pose, to: Pose, s: &CcSettings) -> Option<CcPath> {
    let (g, mut cands) = prepare(from, to, s)?;
    cands.shared_sort_by(|a, b| a.length.total_cmp(&b.length));
    cands.iter().find_map(|c| build_verified(c, from, to, &g))
}

/// A headland turn: from the end of a swath (`from`, facing along it) to the start of the
/// neighbouring swath `spacing` metres to the left (`left`) or right, facing back
/// (`from.heading + π`), exactly on the same end line.
///
/// The shortest candidate that never reaches back behind the end line (into the field; see
/// [`along_range`]): the CC-Dubins words (CSC for wide spacings, the forward CCC "bulb" for
/// narrow ones) and, for spacings of at least `2·Ωy`, a single CC turn of π at a curvature
/// below `κmax` chosen so that its CC circle lands exactly on the neighbour swath (word "L" or
/// "R"); that fills the spacings just above `2·R_Ω` that no CC-Dubins word at full lock reaches
/// without a loop. `None` if `spacing` is not finite and positive, an input is not finite, the
/// settings are unusable or no candidate verifies.
pub fn cc_u_turn(from: Pose, spacing: f64, left: bool, s: &CcSettings) -> Option<CcPath> {
    if !(spacing.is_finite() && spacing > 0.0 && pose_finite(&from)) {
        return None;
    }
    let g = s.geometry()?;
    let side = if left { spacing } else { -spacing };
    let (x, y) = offset(from, 0.0, side);
    let to = Pose::new(x, y, from.heading + PI);
    let mut cands = candidates(&g, to.relative_to(&from));
    cands.extend(wide_u_turn(&g, spacing, left));
    cands.shared_sort_by(|a, b| a.length.total_cmp(&b.length));
    cands
        .iter()
        .filter_map(|c| build_verified(c, from, to, &g))
        .find(|p| along_range(&p.segments, from).is_some_and(|r| r.0 >= -POSITION_TOLERANCE))
}

/// The smallest and largest distance along `origin`'s heading, measured from `origin`, that
/// `segments` reach (exactly: at their ends and wherever their heading is perpendicular to
/// `origin`'s). For a headland turn from the end of a swath, a negative minimum is how far it
/// reaches back into the field and the maximum is how deep a headland it needs. `None` if
/// there are no segments, a value is not finite or a segment turns more than 10⁴ half-turns.
pub fn along_range(segments: &[Segment], origin: Pose) -> Option<(f64, f64)> {
    let (sn, cs) = origin.heading.sin_cos();
    let along = |p: Pose| (p.x - origin.x) * cs + (p.y - origin.y) * sn;
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    let mut note = |v: f64| {
        lo = lo.min(v);
        hi = hi.max(v);
    };
    for sg in segments {
        if !(sg.length.is_finite() && sg.length >= 0.0 && pose_finite(&sg.start)) {
            return None;
        }
        let len = sg.length;
        note(along(sg.start));
        note(along(sg.end()));
        // θ(s) = θ0 + g(κ0·s + σ·s²/2): its range over [0, len].
        let g = sg.gear.sign();
        let (a, b) = (0.5 * g * sg.sharpness, g * sg.curvature);
        let mut h_lo = sg.heading_at(0.0).min(sg.heading_at(len));
        let mut h_hi = sg.heading_at(0.0).max(sg.heading_at(len));
        if a != 0.0 {
            let vertex = -b / (2.0 * a);
            if vertex > 0.0 && vertex < len {
                h_lo = h_lo.min(sg.heading_at(vertex));
                h_hi = h_hi.max(sg.heading_at(vertex));
            }
        }
        // Critical headings origin.heading + π/2 + kπ within that range.
        let base = origin.heading + 0.5 * PI;
        let k0 = ((h_lo - base) / PI).ceil();
        let k1 = ((h_hi - base) / PI).floor();
        if !(k0.is_finite() && k1.is_finite()) || k1 - k0 > 1e4 {
            return None;
        }
        let mut k = k0;
        while k <= k1 {
            let c = sg.start.heading - (base + k * PI);
            for s in quadratic_roots(a, b, c) {
                if (0.0..=len).contains(&s) {
                    note(along(sg.pose_at(s)));
                }
            }
            k += 1.0;
        }
    }
    (lo.is_finite() && hi.is_finite()).then_some((lo, hi))
}

/// The real roots of a·s² + b·s + c = 0 (a double root counted once is fine; none if a = b = 0).
fn quadratic_roots(a: f64, b: f64, c: f64) -> Vec<f64> {
    if a == 0.0 {
        return if b == 0.0 { Vec::new() } else { vec![-c / b] };
    }
    let disc = (b * b - 4.0 * a * c).max(0.0);
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    if q == 0.0 {
        return vec![0.0];
    }
    vec![q / a, c / q]
}

/// The single CC turn of π, at a curvature below `κmax`, from the end of a swath onto the
/// neighbour `spacing` metres to the side: its CC circle's `Ωy` must be `spacing / 2`.
fn wide_u_turn(g: &CcGeometry, spacing: f64, left: bool) -> Option<Candidate> {
    let sigma = g.max_sharpness;
    let geo = |k: f64| {
        CcSettings {
            max_curvature: k,
            max_sharpness: sigma,
        }
        .geometry()
    };
    let miss = |k: f64| geo(k).map(|c| 2.0 * c.centre_y - spacing);
    // Ωy grows as the curvature falls: bracket the root between `lo` (too wide) and κmax.
    let mut hi = g.max_curvature;
    if miss(hi)? > 0.0 {
        return None;
    }
    let mut lo = 0.5 * hi;
    while miss(lo)? <= 0.0 {
        lo *= 0.5;
        if lo < 1e-300 {
            return None;
        }
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if !(mid > lo && mid < hi) {
            break;
        }
        let m = miss(mid)?;
        if m.abs() < 1e-12 * spacing.max(1.0) {
            lo = mid;
            hi = mid;
            break;
        }
        if m > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let k = if miss(lo)?.abs() < miss(hi)?.abs() {
        lo
    } else {
        hi
    };
    let turn = plan_turn(&geo(k)?, PI, left)?;
    Some(Candidate {
        word: if left { "L" } else { "R" },
        pieces: vec![Piece::Turn(turn)],
        length: turn.length(),
    })
}

// ---------------------------------------------------------------------------------------------

const WORDS: [&str; 7] = ["S", "LSL", "RSR", "LSR", "RSL", "LRL", "RLR"];

/// How one CC turn is made.
#[derive(Debug, Clone, Copy)]
enum TurnKind {
    /// Zero deflection: a line of `2·R_Ω·sin μ`.
    Straight(f64),
    /// A symmetric clothoid pair of this sharpness, each half this long.
    Elementary { sharpness: f64, half: f64 },
    /// Clothoid, arc of this length, clothoid (σmax, κmax).
    Full { arc: f64 },
}

#[derive(Debug, Clone, Copy)]
struct TurnPlan {
    /// +1 left, −1 right.
    side: f64,
    kind: TurnKind,
    kappa: f64,
    sigma: f64,
    clothoid: f64,
}

impl TurnPlan {
    fn length(&self) -> f64 {
        match self.kind {
            TurnKind::Straight(l) => l,
            TurnKind::Elementary { half, .. } => 2.0 * half,
            TurnKind::Full { arc } => 2.0 * self.clothoid + arc,
        }
    }
}

#[derive(Debug, Clone, Copy)]
enum Piece {
    Line(f64),
    Turn(TurnPlan),
}

impl Piece {
    fn length(&self) -> f64 {
        match self {
            Piece::Line(l) => *l,
            Piece::Turn(t) => t.length(),
        }
    }
}

#[derive(Debug, Clone)]
struct Candidate {
    word: &'static str,
    pieces: Vec<Piece>,
    length: f64,
}

fn pose_finite(p: &Pose) -> bool {
    p.x.is_finite() && p.y.is_finite() && p.heading.is_finite()
}

/// The point at (`ahead`, `left`) in the frame of `p`.
fn offset(p: Pose, ahead: f64, left: f64) -> (f64, f64) {
    let (sn, cs) = p.heading.sin_cos();
    (p.x + cs * ahead - sn * left, p.y + sn * ahead + cs * left)
}

/// A deflection in [0, 2π), a rounding short of a full circle counting as none.
fn turn_angle(a: f64) -> f64 {
    let x = a.rem_euclid(TAU);
    if x >= TAU - FULL_TURN_SNAP {
        0.0
    } else {
        x
    }
}

/// How to turn by `delta ≥ 0` to the left (`left`) or right, ending on the CC circle.
fn plan_turn(g: &CcGeometry, delta: f64, left: bool) -> Option<TurnPlan> {
    let side = if left { 1.0 } else { -1.0 };
    let mut plan = TurnPlan {
        side,
        kind: TurnKind::Straight(2.0 * g.radius * g.mu.sin()),
        kappa: g.max_curvature,
        sigma: g.max_sharpness,
        clothoid: g.clothoid_length,
    };
    if !(delta.is_finite() && delta >= 0.0) {
        return None;
    }
    if delta < ZERO_TURN {
        return Some(plan);
    }
    if delta >= g.min_deflection {
        plan.kind = TurnKind::Full {
            arc: (delta - g.min_deflection) / g.max_curvature,
        };
        return Some(plan);
    }
    // The elementary path: the unit-sharpness clothoid of length √δ turns δ/2.
    let unit = Segment::clothoid(
        Pose::new(0.0, 0.0, 0.0),
        delta.sqrt(),
        0.0,
        1.0,
        Gear::Forward,
    );
    let e = unit.end();
    let (sh, ch) = (0.5 * delta).sin_cos();
    let projection = e.x * ch + e.y * sh;
    let chord_half = g.radius * (0.5 * delta + g.mu).sin();
    if !(projection > 0.0 && chord_half > 0.0) {
        return None;
    }
    let mut sharpness = (projection / chord_half).powi(2);
    if sharpness > g.max_sharpness {
        if sharpness <= g.max_sharpness * (1.0 + 1e-9) {
            sharpness = g.max_sharpness;
        } else {
            return None;
        }
    }
    let half = (delta / sharpness).sqrt();
    if !(half.is_finite() && half <= MAX_CLOTHOID && sharpness > 0.0) {
        return None;
    }
    plan.kind = TurnKind::Elementary { sharpness, half };
    Some(plan)
}

/// Appends a piece driven forward from `cursor`, merging consecutive lines and skipping empty
/// pieces, and moves `cursor` to its end.
fn emit(out: &mut Vec<Segment>, cursor: &mut Pose, length: f64, curvature: f64, sharpness: f64) {
    if length <= 0.0 {
        return;
    }
    if curvature == 0.0 && sharpness == 0.0 {
        if let Some(last) = out.last_mut() {
            if last.curvature == 0.0 && last.sharpness == 0.0 {
                last.length += length;
                *cursor = last.end();
                return;
            }
        }
    }
    let seg = Segment::clothoid(*cursor, length, curvature, sharpness, Gear::Forward);
    *cursor = seg.end();
    out.push(seg);
}

fn emit_turn(t: &TurnPlan, cursor: &mut Pose, out: &mut Vec<Segment>) {
    let sd = t.side;
    match t.kind {
        TurnKind::Straight(l) => emit(out, cursor, l, 0.0, 0.0),
        TurnKind::Elementary { sharpness, half } => {
            emit(out, cursor, half, 0.0, sd * sharpness);
            emit(out, cursor, half, sd * sharpness * half, -sd * sharpness);
        }
        TurnKind::Full { arc } => {
            emit(out, cursor, t.clothoid, 0.0, sd * t.sigma);
            emit(out, cursor, arc, sd * t.kappa, 0.0);
            emit(out, cursor, t.clothoid, sd * t.kappa, -sd * t.sigma);
        }
    }
}

/// Checks the inputs and lists the candidate words.
fn prepare(from: Pose, to: Pose, s: &CcSettings) -> Option<(CcGeometry, Vec<Candidate>)> {
    if !(pose_finite(&from) && pose_finite(&to)) {
        return None;
    }
    let g = s.geometry()?;
    let cands = candidates(&g, to.relative_to(&from));
    Some((g, cands))
}

/// Builds a candidate from `from` and keeps it if it reaches `to` within the limits.
fn build_verified(c: &Candidate, from: Pose, to: Pose, g: &CcGeometry) -> Option<CcPath> {
    let mut cursor = from;
    let mut segments = Vec::with_capacity(9);
    for p in &c.pieces {
        match p {
            Piece::Line(l) => emit(&mut segments, &mut cursor, *l, 0.0, 0.0),
            Piece::Turn(t) => emit_turn(t, &mut cursor, &mut segments),
        }
    }
    let path = CcPath {
        word: c.word,
        segments,
    };
    verify(&path, to, g).then_some(path)
}

fn verify(p: &CcPath, to: Pose, g: &CcGeometry) -> bool {
    let (Some(first), Some(last)) = (p.segments.first(), p.segments.last()) else {
        return false;
    };
    let end = last.end();
    let k_tol = g.max_curvature + 1e-12;
    let s_tol = g.max_sharpness + 1e-12;
    let ok_segments = p.segments.iter().all(|s| {
        s.length.is_finite()
            && s.length >= 0.0
            && s.gear == Gear::Forward
            && s.max_curvature() <= k_tol
            && s.sharpness.abs() <= s_tol
    });
    let ok_joins = p
        .segments
        .windows(2)
        .all(|w| (w[0].curvature_at(w[0].length) - w[1].curvature).abs() < 1e-9);
    ok_segments
        && ok_joins
        && first.curvature.abs() < 1e-12
        && last.curvature_at(last.length).abs() < 1e-12
        && end.distance(&to) <= POSITION_TOLERANCE
        && end.heading_change(&to).abs() <= HEADING_TOLERANCE
}

fn push_candidate(out: &mut Vec<Candidate>, word: &'static str, pieces: Vec<Piece>) {
    let length: f64 = pieces.iter().map(Piece::length).sum();
    if length.is_finite() {
        out.push(Candidate {
            word,
            pieces,
            length,
        });
    }
}

/// A word of turns and lines; `None` if a turn cannot be made.
fn word(g: &CcGeometry, parts: &[(char, f64)]) -> Option<Vec<Piece>> {
    parts
        .iter()
        .map(|&(c, v)| match c {
            'S' => (v.is_finite() && v >= 0.0).then_some(Piece::Line(v)),
            _ => plan_turn(g, v, c == 'L').map(Piece::Turn),
        })
        .collect()
}

/// The candidates to the goal `q` given in the frame of the start.
fn candidates(g: &CcGeometry, q: Pose) -> Vec<Candidate> {
    let (ox, oy) = (g.centre_x, g.centre_y);
    let r = g.radius;
    let gh = q.heading;
    let mut out = Vec::new();

    // A lone line when the goal lies straight ahead.
    if q.x > 0.0 && q.y.abs() <= 0.1 * POSITION_TOLERANCE && gh.abs() <= 0.1 * HEADING_TOLERANCE {
        out.push(Candidate {
            word: "S",
            pieces: vec![Piece::Line(q.x)],
            length: q.x,
        });
    }

    let start = Pose::new(0.0, 0.0, 0.0);
    let ls = offset(start, ox, oy);
    let rs = offset(start, ox, -oy);
    let lg = offset(q, -ox, oy);
    let rg = offset(q, -ox, -oy);
    let alpha = oy.atan2(ox); // direction of (Ωx, Ωy)

    // LSL and RSR: the line parallel to the centres, 2Ωx shorter than their distance.
    for (name, c1, c2, left) in [("LSL", ls, lg, true), ("RSR", rs, rg, false)] {
        let (dx, dy) = (c2.0 - c1.0, c2.1 - c1.1);
        let l = snap_nonnegative(dx.planar_hypot(dy) - 2.0 * ox);
        let psi = dy.atan2(dx);
        let (d1, d2) = if left {
            (turn_angle(psi), turn_angle(gh - psi))
        } else {
            (turn_angle(-psi), turn_angle(psi - gh))
        };
        let t = if left { 'L' } else { 'R' };
        if let Some(p) = word(g, &[(t, d1), ('S', l), (t, d2)]) {
            push_candidate(&mut out, name, p);
        }
    }

    // LSR and RSL: centres differ by (ℓ + 2Ωx, ∓2Ωy) in the line's frame.
    for (name, c1, c2, left) in [("LSR", ls, rg, true), ("RSL", rs, lg, false)] {
        let (dx, dy) = (c2.0 - c1.0, c2.1 - c1.1);
        let d2 = dx * dx + dy * dy;
        let inner = d2 - 4.0 * oy * oy;
        if inner < 0.0 {
            continue;
        }
        let l = snap_nonnegative(inner.sqrt() - 2.0 * ox);
        let tilt = (2.0 * oy).atan2(l + 2.0 * ox);
        let theta = dy.atan2(dx);
        let (parts, psi) = if left {
            let psi = theta + tilt;
            (
                [
                    ('L', turn_angle(psi)),
                    ('S', l),
                    ('R', turn_angle(psi - gh)),
                ],
                psi,
            )
        } else {
            let psi = theta - tilt;
            (
                [
                    ('R', turn_angle(-psi)),
                    ('S', l),
                    ('L', turn_angle(gh - psi)),
                ],
                psi,
            )
        };
        if !psi.is_finite() {
            continue;
        }
        if let Some(p) = word(g, &parts) {
            push_candidate(&mut out, name, p);
        }
    }

    // LRL and RLR: the middle circle 2R_Ω from both outer ones.
    for (name, c1, c3, left) in [("LRL", ls, lg, true), ("RLR", rs, rg, false)] {
        let (dx, dy) = (c3.0 - c1.0, c3.1 - c1.1);
        let d = dx.planar_hypot(dy);
        if d > 4.0 * r {
            continue;
        }
        let h = (4.0 * r * r - 0.25 * d * d).max(0.0).sqrt();
        let (nx, ny) = if d > 1e-12 {
            (-dy / d, dx / d)
        } else {
            (0.0, 1.0)
        };
        let m = (0.5 * (c1.0 + c3.0), 0.5 * (c1.1 + c3.1));
        for sgn in [1.0, -1.0] {
            let c2 = (m.0 + sgn * h * nx, m.1 + sgn * h * ny);
            let a12 = (c2.1 - c1.1).atan2(c2.0 - c1.0);
            let a23 = (c3.1 - c2.1).atan2(c3.0 - c2.0);
            let parts = if left {
                let psi1 = a12 + alpha;
                let psi2 = a23 - alpha;
                [
                    ('L', turn_angle(psi1)),
                    ('R', turn_angle(psi1 - psi2)),
                    ('L', turn_angle(gh - psi2)),
                ]
            } else {
                let psi1 = a12 - alpha;
                let psi2 = a23 + alpha;
                [
                    ('R', turn_angle(-psi1)),
                    ('L', turn_angle(psi2 - psi1)),
                    ('R', turn_angle(psi2 - gh)),
                ]
            };
            if let Some(p) = word(g, &parts) {
                push_candidate(&mut out, name, p);
            }
        }
    }
    out
}

/// A length a rounding below zero counts as zero; a clearly negative one stays negative.
fn snap_nonnegative(l: f64) -> f64 {
    if (-1e-12..0.0).contains(&l) {
        0.0
    } else {
        l
    }
}

#[cfg(test)]
mod tests {
    use super::super::curve::wrap;
    use super::*;

    use crate::rng::SplitMix64 as Rng;

    /// Random poses and machines for the tests.
    trait Draw {
        fn pose(&mut self, extent: f64) -> Pose;
        fn settings(&mut self) -> CcSettings;
    }

    impl Draw for Rng {
        fn pose(&mut self, extent: f64) -> Pose {
            Pose::new(
                self.range(-extent, extent),
                self.range(-extent, extent),
                self.range(-PI, PI),
            )
        }
        fn settings(&mut self) -> CcSettings {
            CcSettings::from_radius(self.range(3.0, 15.0), self.range(0.05, 1.0))
        }
    }

    /// Every property a CC path must have; panics with a description otherwise.
    fn check_path(p: &CcPath, from: Pose, to: Pose, s: &CcSettings) {
        let segs = &p.segments;
        assert!(!segs.is_empty(), "{} empty", p.word);
        assert_eq!(segs[0].start, from, "{} does not start at from", p.word);
        for w in segs.windows(2) {
            let e = w[0].end();
            let gap = e.distance(&w[1].start);
            assert!(gap < 1e-9, "{}: gap {gap}", p.word);
            assert!(wrap(e.heading - w[1].start.heading).abs() < 1e-9);
            let dk = (w[0].curvature_at(w[0].length) - w[1].curvature).abs();
            assert!(dk < 1e-9, "{}: curvature jump {dk}", p.word);
        }
        let last = segs[segs.len() - 1];
        let end = last.end();
        assert!(
            end.distance(&to) < 1e-6,
            "{}: ends {} m off",
            p.word,
            end.distance(&to)
        );
        assert!(end.heading_change(&to).abs() < 1e-9, "{}: heading", p.word);
        assert!(segs[0].curvature.abs() < 1e-12);
        assert!(last.curvature_at(last.length).abs() < 1e-12);
        for sg in segs {
            assert_eq!(sg.gear, Gear::Forward);
            assert!(sg.length > 0.0 && sg.length.is_finite());
            assert!(
                sg.max_curvature() <= s.max_curvature + 1e-12,
                "{}: κ {} > {}",
                p.word,
                sg.max_curvature(),
                s.max_curvature
            );
            assert!(
                sg.sharpness.abs() <= s.max_sharpness + 1e-12,
                "{}: σ",
                p.word
            );
        }
        let sum: f64 = segs.iter().map(|s| s.length).sum();
        assert!((sum - p.length()).abs() < 1e-9);
    }

    // ---- plain Dubins, closed formulas (normalised by the radius) ----------------------------

    fn m2p(a: f64) -> f64 {
        a.rem_euclid(TAU)
    }

    /// (word, t, p, q) for every Dubins word that exists, in units of the radius.
    fn dubins_words(from: Pose, to: Pose, r: f64) -> Vec<(&'static str, f64, f64, f64)> {
        let (dx, dy) = (to.x - from.x, to.y - from.y);
        let d = dx.planar_hypot(dy) / r;
        let th = dy.atan2(dx);
        let a = m2p(from.heading - th);
        let b = m2p(to.heading - th);
        let (sa, ca, sb, cb) = (a.sin(), a.cos(), b.sin(), b.cos());
        let cab = (a - b).cos();
        let mut out = Vec::new();
        // LSL
        let p2 = 2.0 + d * d - 2.0 * cab + 2.0 * d * (sa - sb);
        if p2 >= 0.0 {
            let tmp = (cb - ca).atan2(d + sa - sb);
            out.push(("LSL", m2p(tmp - a), p2.sqrt(), m2p(b - tmp)));
        }
        // RSR
        let p2 = 2.0 + d * d - 2.0 * cab + 2.0 * d * (sb - sa);
        if p2 >= 0.0 {
            let tmp = (ca - cb).atan2(d - sa + sb);
            out.push(("RSR", m2p(a - tmp), p2.sqrt(), m2p(tmp - b)));
        }
        // LSR
        let p2 = -2.0 + d * d + 2.0 * cab + 2.0 * d * (sa + sb);
        if p2 >= 0.0 {
            let p = p2.sqrt();
            let tmp = (-ca - cb).atan2(d + sa + sb) - (-2.0f64).atan2(p);
            out.push(("LSR", m2p(tmp - a), p, m2p(tmp - b)));
        }
        // RSL
        let p2 = -2.0 + d * d + 2.0 * cab - 2.0 * d * (sa + sb);
        if p2 >= 0.0 {
            let p = p2.sqrt();
            let tmp = (ca + cb).atan2(d - sa - sb) - 2.0f64.atan2(p);
            out.push(("RSL", m2p(a - tmp), p, m2p(b - tmp)));
        }
        // RLR
        let tmp = (6.0 - d * d + 2.0 * cab + 2.0 * d * (sa - sb)) / 8.0;
        if tmp.abs() <= 1.0 {
            let p = m2p(TAU - tmp.acos());
            let t = m2p(a - (ca - cb).atan2(d - sa + sb) + p / 2.0);
            out.push(("RLR", t, p, m2p(a - b - t + p)));
        }
        // LRL
        let tmp = (6.0 - d * d + 2.0 * cab + 2.0 * d * (sb - sa)) / 8.0;
        if tmp.abs() <= 1.0 {
            let p = m2p(TAU - tmp.acos());
            let t = m2p(-a - (ca - cb).atan2(d + sa - sb) + p / 2.0);
            out.push(("LRL", t, p, m2p(b - a - t + p)));
        }
        out
    }

    /// The shortest plain Dubins length; every formula's path is built and checked too.
    fn dubins_shortest(from: Pose, to: Pose, r: f64) -> f64 {
        let mut best = f64::INFINITY;
        for (w, t, p, q) in dubins_words(from, to, r) {
            let mut cur = from;
            for (c, v) in w.chars().zip([t, p, q]) {
                let k = match c {
                    'L' => 1.0 / r,
                    'R' => -1.0 / r,
                    _ => 0.0,
                };
                cur = Segment::arc(cur, v * r, k, Gear::Forward).end();
            }
            assert!(
                cur.distance(&to) < 1e-6 && cur.heading_change(&to).abs() < 1e-9,
                "Dubins {w} formula wrong: {cur:?} vs {to:?}"
            );
            best = best.min((t + p + q) * r);
        }
        best
    }

    #[test]
    fn random_pairs_give_valid_paths_no_shorter_than_dubins() {
        let mut rng = Rng::new(0x5EED_CC01);
        let n = 4000;
        let mut counts = std::collections::BTreeMap::new();
        let mut worst_ratio = 0.0f64;
        let mut most_ratio = 1.0f64;
        let mut bins = [0usize; 5];
        for _ in 0..n {
            let s = rng.settings();
            let extent = rng.range(1.0, 80.0);
            let from = rng.pose(extent);
            let to = rng.pose(extent);
            let all = cc_dubins_all(from, to, &s);
            assert!(!all.is_empty(), "no path {from:?} -> {to:?} {s:?}");
            for p in &all {
                check_path(p, from, to, &s);
                *counts.entry(p.word).or_insert(0usize) += 1;
            }
            let best = cc_dubins_shortest(from, to, &s);
            let Some(best) = best else {
                panic!("no shortest {from:?} -> {to:?} {s:?}");
            };
            check_path(&best, from, to, &s);
            let min_all = all.iter().map(CcPath::length).fold(f64::INFINITY, f64::min);
            assert!((best.length() - min_all).abs() < 1e-9);
            let dub = dubins_shortest(from, to, 1.0 / s.max_curvature);
            assert!(
                best.length() >= dub - 1e-9,
                "CC {} shorter than Dubins {dub}",
                best.length()
            );
            let ratio = best.length() / dub;
            let bin = [1.01, 1.05, 1.25, 2.0, f64::INFINITY]
                .iter()
                .position(|b| ratio < *b)
                .unwrap_or(4);
            bins[bin] += 1;
            worst_ratio = worst_ratio.max(ratio);
            most_ratio = most_ratio.min(best.length() / dub);
        }
        println!("words found over {n} random pairs: {counts:?}");
        println!("CC/Dubins length ratio in [{most_ratio:.4}, {worst_ratio:.4}]");
        println!(
            "pairs with CC/Dubins in [1, 1.01), [1.01, 1.05), [1.05, 1.25), [1.25, 2), ≥ 2: {bins:?}"
        );
    }

    #[test]
    fn converges_to_dubins_as_sharpness_grows() {
        let mut rng = Rng::new(0xD0B1_2525);
        let mut worst = 0.0f64;
        for _ in 0..2000 {
            let r = rng.range(3.0, 15.0);
            let s = CcSettings::from_radius(r, 1e4);
            let extent = rng.range(1.0, 80.0);
            let (from, to) = (rng.pose(extent), rng.pose(extent));
            let Some(best) = cc_dubins_shortest(from, to, &s) else {
                panic!("no path {from:?} -> {to:?}");
            };
            check_path(&best, from, to, &s);
            let dub = dubins_shortest(from, to, r);
            let rel = best.length() / dub - 1.0;
            assert!((-1e-9..0.01).contains(&rel), "{rel} {from:?} {to:?} r {r}");
            worst = worst.max(rel);
        }
        println!("σmax = 1e4: CC at most {:.3e} longer than Dubins", worst);
    }

    #[test]
    fn every_word_appears_and_verifies() {
        let s = CcSettings::from_radius(5.0, 0.3);
        let mut rng = Rng::new(77);
        let mut seen = std::collections::BTreeSet::new();
        for _ in 0..3000 {
            let from = Pose::new(0.0, 0.0, 0.0);
            let to = rng.pose(12.0);
            for p in cc_dubins_all(from, to, &s) {
                check_path(&p, from, to, &s);
                seen.insert(p.word);
            }
        }
        for w in ["LSL", "RSR", "LSR", "RSL", "LRL", "RLR"] {
            assert!(seen.contains(w), "{w} never found");
        }
    }

    #[test]
    fn full_turns_end_on_the_predicted_point_of_the_cc_circle() {
        let mut rng = Rng::new(3);
        for _ in 0..500 {
            let s = rng.settings();
            let Some(g) = s.geometry() else {
                panic!("settings {s:?}");
            };
            let from = rng.pose(50.0);
            let mag = rng.range(g.min_deflection, TAU + 0.5);
            let d = if rng.unit() < 0.5 { mag } else { -mag };
            let segs = cc_turn(from, d, &s);
            assert!(segs.len() == 3 || (segs.len() == 2 && mag == g.min_deflection));
            let end = segs[segs.len() - 1].end();
            let want = g.turn_end(from, d);
            assert!(end.distance(&want) < 1e-9, "{end:?} {want:?}");
            assert!((end.heading - (from.heading + d)).abs() < 1e-12);
            // On the CC circle, at μ outside its tangent.
            let c = g.start_centre(from, d > 0.0);
            let rr = (end.x - c.0).planar_hypot(end.y - c.1);
            assert!((rr - g.radius).abs() < 1e-9);
            let polar = (end.y - c.1).atan2(end.x - c.0);
            let tangent = polar + d.signum() * PI / 2.0;
            assert!(wrap(end.heading - (tangent - d.signum() * g.mu)).abs() < 1e-9);
            assert!(segs
                .iter()
                .any(|x| x.max_curvature() > s.max_curvature - 1e-12));
            for x in &segs {
                assert!(x.max_curvature() <= s.max_curvature + 1e-12);
                assert!(x.sharpness.abs() <= s.max_sharpness + 1e-12);
            }
        }
    }

    #[test]
    fn small_turns_stay_below_full_lock_and_still_end_on_the_circle() {
        let mut rng = Rng::new(4);
        let mut max_ratio = 0.0f64;
        for i in 0..2000 {
            let s = rng.settings();
            let Some(g) = s.geometry() else {
                panic!("settings {s:?}");
            };
            let from = rng.pose(50.0);
            // Sweep (0, δmin) including both ends' neighbourhoods.
            let f = match i % 4 {
                0 => 1e-8 + rng.unit() * 1e-6,
                1 => 1.0 - rng.unit() * 1e-6,
                _ => rng.unit(),
            };
            let mag = f * g.min_deflection;
            let d = if i % 2 == 0 { mag } else { -mag };
            let segs = cc_turn(from, d, &s);
            assert_eq!(segs.len(), 2, "δ = {d}, δmin = {}", g.min_deflection);
            let peak = segs[0].curvature_at(segs[0].length).abs();
            assert!(peak < s.max_curvature, "κpeak {peak}");
            assert!((peak - (mag * segs[0].sharpness.abs()).sqrt()).abs() < 1e-12);
            for x in &segs {
                assert!(x.sharpness.abs() <= s.max_sharpness + 1e-12);
                max_ratio = max_ratio.max(x.sharpness.abs() / s.max_sharpness);
            }
            assert!(segs[1].curvature_at(segs[1].length).abs() < 1e-12);
            let end = segs[1].end();
            let want = g.turn_end(from, d);
            assert!(end.distance(&want) < 1e-9, "{end:?} {want:?}");
        }
        // A zero deflection is the line of 2·R_Ω·sin μ.
        let s = CcSettings::from_radius(5.0, 0.2);
        let Some(g) = s.geometry() else {
            panic!("settings");
        };
        let segs = cc_turn(Pose::new(1.0, 2.0, 0.3), 0.0, &s);
        assert_eq!(segs.len(), 1);
        assert!((segs[0].length - 2.0 * g.radius * g.mu.sin()).abs() < 1e-12);
        println!("elementary sharpness reaches {max_ratio:.9} of σmax");
    }

    #[test]
    fn u_turns_end_exactly_on_the_neighbour_swath() {
        let mut rng = Rng::new(11);
        for i in 0..3000 {
            let s = rng.settings();
            let r = 1.0 / s.max_curvature;
            let spacing = r * (0.5 + 5.5 * (i % 100) as f64 / 99.0);
            let left = i % 2 == 0;
            let from = rng.pose(100.0);
            let Some(p) = cc_u_turn(from, spacing, left, &s) else {
                panic!("no u-turn spacing {spacing} {s:?}");
            };
            let side = if left { spacing } else { -spacing };
            let (x, y) = offset(from, 0.0, side);
            let to = Pose::new(x, y, from.heading + PI);
            check_path(&p, from, to, &s);
            // The end lies on the end line: no along-swath offset.
            let rel = p.end().map(|e| e.relative_to(&from));
            let Some(rel) = rel else { panic!("empty") };
            assert!(rel.x.abs() < 1e-6 && (rel.y - side).abs() < 1e-6);
            let Some((lo, _)) = along_range(&p.segments, from) else {
                panic!("range");
            };
            assert!(lo >= -1e-6, "u-turn reaches {lo} m into the field");
        }
    }

    #[test]
    fn u_turn_words_by_spacing() {
        let s = CcSettings::from_radius(6.0, 0.1);
        let Some(g) = s.geometry() else {
            panic!("settings");
        };
        println!(
            "r 6 m, σmax 0.1: R_Ω {:.3} m, Ωx {:.3} m, Ωy {:.3} m, μ {:.4}",
            g.radius, g.centre_x, g.centre_y, g.mu
        );
        let from = Pose::new(0.0, 0.0, 0.0);
        let mut last = 0.0;
        for k in 0..=44 {
            let spacing = 3.0 + 0.75 * k as f64;
            let Some(p) = cc_u_turn(from, spacing, true, &s) else {
                panic!("none at {spacing}");
            };
            let Some((lo, hi)) = along_range(&p.segments, from) else {
                panic!("range");
            };
            assert!(
                lo >= -1e-6,
                "{spacing}: {} reaches {lo} into the field",
                p.word
            );
            let free = cc_dubins_shortest(from, Pose::new(0.0, spacing, PI), &s);
            let free = free.map_or(f64::NAN, |f| f.length());
            println!(
                "spacing {spacing:5.2} m: {:3} {:7.3} m (unconstrained shortest {:7.3} m), \
                 headland depth {hi:.3} m",
                p.word,
                p.length(),
                free
            );
            // No jump: the length changes by less than the spacing step times π/2 + slack.
            if k > 0 {
                assert!(
                    (p.length() - last).abs() < 6.0,
                    "{spacing}: {last} -> {}",
                    p.length()
                );
            }
            last = p.length();
        }
    }

    #[test]
    fn along_range_matches_dense_sampling() {
        let mut rng = Rng::new(21);
        for _ in 0..300 {
            let s = rng.settings();
            let (from, to) = (rng.pose(30.0), rng.pose(30.0));
            let origin = rng.pose(30.0);
            for p in cc_dubins_all(from, to, &s) {
                let Some((lo, hi)) = along_range(&p.segments, origin) else {
                    panic!("range");
                };
                let (sn, cs) = origin.heading.sin_cos();
                let (mut slo, mut shi) = (f64::INFINITY, f64::NEG_INFINITY);
                for sg in &p.segments {
                    let n = 400;
                    for j in 0..=n {
                        let q = sg.pose_at(sg.length * j as f64 / n as f64);
                        let a = (q.x - origin.x) * cs + (q.y - origin.y) * sn;
                        slo = slo.min(a);
                        shi = shi.max(a);
                    }
                }
                assert!(
                    lo <= slo + 1e-9 && hi >= shi - 1e-9,
                    "{lo} {slo} {hi} {shi}"
                );
                assert!(slo - lo < 1e-3 && hi - shi < 1e-3, "{lo} {slo} {hi} {shi}");
            }
        }
    }

    #[test]
    fn straight_ahead_is_a_line() {
        // Beyond 4·Ωx ahead LSL with two zero turns is the same single line; closer, only "S".
        let s = CcSettings::from_radius(5.0, 0.2);
        let Some(g) = s.geometry() else {
            panic!("settings");
        };
        let from = Pose::new(1.0, 1.0, 0.5);
        for ahead in [0.5, 1.5, 3.0, 30.0] {
            let (x, y) = offset(from, ahead, 0.0);
            let to = Pose::new(x, y, 0.5);
            let Some(p) = cc_dubins_shortest(from, to, &s) else {
                panic!("none");
            };
            if ahead < 4.0 * g.centre_x {
                assert_eq!(p.word, "S");
            }
            assert_eq!(p.segments.len(), 1, "{ahead}: {p:?}");
            assert!((p.length() - ahead).abs() < 1e-9);
            check_path(&p, from, to, &s);
        }
    }

    #[test]
    fn bad_inputs_give_nothing() {
        let ok = CcSettings::from_radius(5.0, 0.2);
        let a = Pose::new(0.0, 0.0, 0.0);
        let b = Pose::new(20.0, 5.0, 1.0);
        let bad_settings = [
            CcSettings {
                max_curvature: 0.0,
                max_sharpness: 0.2,
            },
            CcSettings {
                max_curvature: -0.2,
                max_sharpness: 0.2,
            },
            CcSettings {
                max_curvature: 0.2,
                max_sharpness: 0.0,
            },
            CcSettings {
                max_curvature: 0.2,
                max_sharpness: -1.0,
            },
            CcSettings {
                max_curvature: f64::NAN,
                max_sharpness: 0.2,
            },
            CcSettings {
                max_curvature: 0.2,
                max_sharpness: f64::INFINITY,
            },
            CcSettings {
                max_curvature: f64::INFINITY,
                max_sharpness: 0.2,
            },
            CcSettings {
                max_curvature: 0.2,
                max_sharpness: 1e-300,
            },
        ];
        for s in &bad_settings {
            assert!(cc_dubins_all(a, b, s).is_empty());
            assert!(cc_dubins_shortest(a, b, s).is_none());
            assert!(cc_turn(a, 1.0, s).is_empty());
            assert!(cc_u_turn(a, 4.0, true, s).is_none());
        }
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let p = Pose::new(bad, 0.0, 0.0);
            let h = Pose::new(0.0, 0.0, bad);
            assert!(cc_dubins_all(p, b, &ok).is_empty());
            assert!(cc_dubins_all(a, h, &ok).is_empty());
            assert!(cc_dubins_shortest(h, b, &ok).is_none());
            assert!(cc_turn(a, bad, &ok).is_empty());
            assert!(cc_turn(p, 1.0, &ok).is_empty());
            assert!(cc_u_turn(a, bad, true, &ok).is_none());
        }
        assert!(cc_u_turn(a, 0.0, true, &ok).is_none());
        assert!(cc_u_turn(a, -3.0, false, &ok).is_none());
        // Extreme but valid settings and poses never panic.
        for (k, sg) in [(1e-6, 1e-12), (1e3, 1e9), (1.0, 1e-3), (0.5, 1e300)] {
            let s = CcSettings {
                max_curvature: k,
                max_sharpness: sg,
            };
            for p in cc_dubins_all(a, b, &s) {
                check_path(&p, a, b, &s);
            }
            let _ = cc_turn(a, 100.0, &s);
        }
        let far = Pose::new(1e300, -1e300, 0.0);
        assert!(cc_dubins_shortest(a, far, &ok).is_none());
        // Identical poses: a loop.
        let Some(p) = cc_dubins_shortest(b, b, &ok) else {
            panic!("no loop");
        };
        check_path(&p, b, b, &ok);
    }

    #[test]
    fn time_per_shortest_call() {
        let mut rng = Rng::new(99);
        let cases: Vec<_> = (0..20_000)
            .map(|_| {
                let e = rng.range(1.0, 80.0);
                (rng.pose(e), rng.pose(e), rng.settings())
            })
            .collect();
        let t0 = std::time::Instant::now();
        let mut total = 0.0;
        for (a, b, s) in &cases {
            total += cc_dubins_shortest(*a, *b, s).map_or(0.0, |p| p.length());
        }
        let per = t0.elapsed().as_secs_f64() / cases.len() as f64;
        let t1 = std::time::Instant::now();
        let mut n_all = 0;
        for (a, b, s) in &cases {
            n_all += cc_dubins_all(*a, *b, s).len();
        }
        let per_all = t1.elapsed().as_secs_f64() / cases.len() as f64;
        println!(
            "cc_dubins_shortest: {:.2} µs per call; cc_dubins_all: {:.2} µs per call \
             ({} paths, total length {total:.0} m)",
            per * 1e6,
            per_all * 1e6,
            n_all
        );
        assert!(total > 0.0);
    }
}
