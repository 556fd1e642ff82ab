//! Turns the machine can drive: the candidates between two poses, the classic headland turns,
//! and the choice of the cheapest that stays in the field.
//!
//! A [`Vehicle`] knows its minimum turning radius, whether it may reverse, and (optionally) how
//! fast it can change its curvature. Between two poses it offers every form it can drive:
//! - all six Dubins words ([`super::dubins`]), forward only;
//! - with reversing, every Reeds-Shepp path ([`super::reeds_shepp`]) and the classic
//!   three-point (fishtail) turn between neighbouring swaths: a quarter circle forward, straight
//!   back, a quarter circle forward, which stays within one turning radius of the swath ends;
//! - with a curvature rate, instead the continuous-curvature Dubins words
//!   ([`super::continuous`]): every arc entered and left along a clothoid.
//!
//! Dubins' CSC words between neighbouring swath ends are the classic U-turn (spacing at least
//! twice the radius) and its CCC words the loop (bulb, omega) turn (spacing under twice the
//! radius); [`TurnForm::name`] calls them so. Each cusp (change of gear) costs
//! [`CUSP_PENALTY_M`] on top of the length: stopping and changing gear takes time.
//! [`Vehicle::turn`] orders the candidates by cost and keeps the first that [`Area::contains`]
//! (the field less its obstacles); where none fits it keeps the cheapest and says so.
//!
//! ```
//! use furrow::path::curve::Pose;
//! use furrow::path::turn::Vehicle;
//! use std::f64::consts::PI;
//!
//! let v = Vehicle { turn_radius: 6.0, ..Vehicle::default() };
//! // From the end of a swath running east to the next one 12 m north, running west: a U-turn
//! // of two quarter circles, πr long.
//! let t = v.shortest(Pose::new(0.0, 0.0, 0.0), Pose::new(0.0, 12.0, PI));
//! assert!((t.length() - 6.0 * PI).abs() < 1e-9);
//! assert_eq!(t.form.name(), "u-turn");
//! ```

use super::continuous::{cc_dubins_all, cc_turn, cc_u_turn, CcSettings};
use super::curve::{self, Gear, Pose, Segment};
use super::dubins::dubins_all;
use super::reeds_shepp::reeds_shepp_all;
use crate::geometry::{point_segment_distance, Extremes, IndexedSegment, PlanarHypot};
use crate::sort::SharedSort;
use geo::{Coord, Line, LineString, Polygon};
use rstar::{RTree, AABB};
use std::f64::consts::FRAC_PI_2;

/// What a turn costs per change of gear, metres of driving: stopping, changing gear and
/// starting again take a few seconds.
pub const CUSP_PENALTY_M: f64 = 5.0;

/// Turning radii below this (metres) are a machine that turns on the spot.
pub const MIN_TURN_RADIUS_M: f64 = 1e-3;

/// The machine as the path sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Vehicle {
    /// Working width, metres.
    pub width: f64,
    /// Minimum turning radius, metres.
    pub turn_radius: f64,
    /// Whether it may reverse.
    pub reverse: bool,
    /// How it drives the sharp corners of headland passes (see [`crate::path::follow`]).
    pub corners: crate::headland::HeadlandCorners,
    /// Largest change of curvature per metre driven, 1/m²; `None`: arcs join lines directly.
    pub curvature_rate: Option<f64>,
    /// Working speed, metres per second.
    pub working_speed: f64,
    /// Speed in turns and connections, metres per second.
    pub turning_speed: f64,
}

impl Default for Vehicle {
    fn default() -> Self {
        Vehicle {
            width: 6.0,
            turn_radius: 8.0,
            reverse: false,
            corners: crate::headland::HeadlandCorners::Auto,
            curvature_rate: None,
            working_speed: 8.0 / 3.6,
            turning_speed: 5.0 / 3.6,
        }
    }
}

/// The shape of a turn.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum TurnForm {
    /// A Dubins path (forward only), by its word (`LSL` …).
    Dubins(&'static str),
    /// A Reeds-Shepp path, by its word (`L+S+R-` …).
    ReedsShepp(String),
    /// A continuous-curvature Dubins path, by its word.
    ContinuousCurvature(&'static str),
    /// The three-point (fishtail) turn: forward, straight back, forward.
    ThreePoint,
    /// A machine that turns on the spot (no turning radius): it pivots, drives straight to
    /// the next pose and pivots again.
    OnTheSpot,
    /// Nothing to turn: the poses meet.
    None,
    /// From one swath to the next along the headland (onto a headland pass, along it and off
    /// it), where their ends lie so far apart along the swaths that a turn would cross the
    /// crop of the swaths between.
    Headland,
    /// A bend of a headland pass driven with the implement lifted: working on, it would reach
    /// out of the field (a rounding over a concave corner tighter than the turning radius).
    Lifted,
}

impl TurnForm {
    /// Its name in the plan output: `u-turn` (a Dubins CSC word), `loop` (CCC), `three-point`,
    /// `reeds-shepp` (with its word in [`TurnForm::word`]), `cc-u-turn`, `cc-loop`, `none`.
    pub fn name(&self) -> &'static str {
        match self {
            TurnForm::Dubins(w) if is_ccc(w) => "loop",
            TurnForm::Dubins(_) => "u-turn",
            TurnForm::ContinuousCurvature(w) if is_ccc(w) => "cc-loop",
            TurnForm::ContinuousCurvature(_) => "cc-u-turn",
            TurnForm::ReedsShepp(_) => "reeds-shepp",
            TurnForm::ThreePoint => "three-point",
            TurnForm::OnTheSpot => "on-the-spot",
            TurnForm::None => "none",
            TurnForm::Lifted => "lifted",
            TurnForm::Headland => "headland",
        }
    }

    /// Its word (`LSL`, `L+R-L+` …), empty for the three-point turn and none.
    pub fn word(&self) -> String {
        match self {
            TurnForm::Dubins(w) | TurnForm::ContinuousCurvature(w) => (*w).to_string(),
            TurnForm::ReedsShepp(w) => w.clone(),
            TurnForm::ThreePoint
            | TurnForm::OnTheSpot
            | TurnForm::None
            | TurnForm::Lifted
            | TurnForm::Headland => String::new(),
        }
    }
}

fn is_ccc(word: &str) -> bool {
    !word.contains('S')
}

/// A turn: its form and the segments driven.
#[derive(Debug, Clone, PartialEq)]
pub struct Turn {
    /// Its shape.
    pub form: TurnForm,
    /// The segments, each starting where the one before ends.
    pub segments: Vec<Segment>,
    /// Whether it stays in the area it was checked against (true when not checked).
    pub inside: bool,
}

impl Turn {
    /// Length driven, metres.
    pub fn length(&self) -> f64 {
        curve::length(&self.segments)
    }

    /// Number of changes of gear.
    pub fn cusps(&self) -> usize {
        cusps(&self.segments)
    }

    /// Length plus [`CUSP_PENALTY_M`] per cusp: what the choice minimises.
    pub fn cost(&self) -> f64 {
        self.length() + CUSP_PENALTY_M * self.cusps() as f64
    }
}

/// Number of changes of gear along segments.
pub fn cusps(segments: &[Segment]) -> usize {
    segments
        .windows(2)
        .filter(|w| w[0].gear != w[1].gear && w[0].length > 0.0 && w[1].length > 0.0)
        .count()
}

impl Vehicle {
    /// Whether its headland passes are the field's exact offsets, worked into at their corners
    /// ([`crate::path::follow`]), rather than rounded at the turning radius: with headland
    /// corners `manoeuvre`, or `auto` where it reverses.
    pub fn exact_passes(&self) -> bool {
        match self.corners {
            crate::headland::HeadlandCorners::Round => false,
            crate::headland::HeadlandCorners::Auto => self.reverse,
            crate::headland::HeadlandCorners::Manoeuvre => true,
        }
    }

    /// Whether it turns on the spot: a turning radius of (nearly) nothing.
    pub fn pivots(&self) -> bool {
        self.turn_radius.is_nan() || self.turn_radius <= MIN_TURN_RADIUS_M
    }

    /// The continuous-curvature settings, if the vehicle has a curvature rate.
    fn cc(&self) -> Option<CcSettings> {
        self.curvature_rate.map(|rate| CcSettings {
            max_curvature: 1.0 / self.turn_radius,
            max_sharpness: rate,
        })
    }

    /// Every form of turn from `from` to `to` the vehicle can drive, cheapest first
    /// (see the module documentation).
    pub fn candidates(&self, from: Pose, to: Pose) -> Vec<Turn> {
        let r = self.turn_radius;
        let mut out: Vec<Turn> = Vec::new();
        if from.distance(&to) < 1e-9 && from.heading_change(&to).abs() < 1e-9 {
            return vec![Turn {
                form: TurnForm::None,
                segments: Vec::new(),
                inside: true,
            }];
        }
        if self.pivots() {
            // It turns on the spot: pivot, straight, pivot (the heading turns standing).
            let mut t = straight(from, to);
            t.form = TurnForm::OnTheSpot;
            t.inside = true;
            return vec![t];
        }
        if let Some(cc) = self.cc() {
            for p in cc_dubins_all(from, to, &cc) {
                out.push(Turn {
                    form: TurnForm::ContinuousCurvature(p.word),
                    segments: p.segments,
                    inside: true,
                });
            }
            // Between neighbouring swath ends, also the U-turn that keeps to the headland
            // (and the single wide turn where it is shorter).
            let rel = to.relative_to(&from);
            if (rel.heading.abs() - std::f64::consts::PI).abs() < 1e-9 && rel.x.abs() < 1e-6 {
                if let Some(p) = cc_u_turn(from, rel.y.abs(), rel.y > 0.0, &cc) {
                    if curve::end(&p.segments).is_some_and(|e| {
                        e.distance(&to) < 1e-6 && e.heading_change(&to).abs() < 1e-9
                    }) {
                        out.push(Turn {
                            form: TurnForm::ContinuousCurvature(p.word),
                            segments: p.segments,
                            inside: true,
                        });
                    }
                }
            }
        } else {
            for p in dubins_all(from, to, r) {
                out.push(Turn {
                    form: TurnForm::Dubins(p.word.as_str()),
                    segments: p.segments(from),
                    inside: true,
                });
            }
            if self.reverse {
                if let Some(t) = three_point(from, to, r) {
                    out.push(t);
                }
                for p in reeds_shepp_all(from, to, r) {
                    out.push(Turn {
                        form: TurnForm::ReedsShepp(p.word()),
                        segments: p.segments(from),
                        inside: true,
                    });
                }
            }
        }
        // Zero-length pieces say nothing; drop them so that cusps count real changes.
        for t in &mut out {
            t.segments.retain(|s| s.length > 1e-12);
        }
        out.shared_sort_by(|a, b| a.cost().total_cmp(&b.cost()));
        out
    }

    /// The cheapest turn from `from` to `to`, unchecked. Falls back to a straight line (and
    /// `inside: false`) only if no form exists, which does not happen for finite poses.
    pub fn shortest(&self, from: Pose, to: Pose) -> Turn {
        self.candidates(from, to)
            .into_iter()
            .next()
            .unwrap_or_else(|| straight(from, to))
    }

    /// The cheapest turn from `from` to `to` that stays in `area`, or the cheapest of all
    /// (with `inside: false`) if none does.
    pub fn turn(&self, from: Pose, to: Pose, area: &Area) -> Turn {
        self.turn_clear(from, to, area, &|_| true).0
    }

    /// [`Vehicle::turn`] that also keeps `clear` where a form does: the cheapest form inside
    /// the area for which `clear` holds; else, for a machine that only drives forward, the
    /// cheapest outside it for which `clear` holds; else the cheapest inside (for example a turn
    /// that must cross crop still to be worked, see [`super::crop`]). With whether `clear`
    /// holds for it (for a machine that reverses, `false` for a turn that leaves the area, not
    /// asked).
    ///
    /// A headland too shallow for a forward machine's loop between neighbouring swaths sends
    /// the loop out over the boundary; its U-turn between ends staggered along an oblique edge,
    /// which needs r(1 + sin θ) of headland for an edge θ from square to the swaths, goes out
    /// the same way rather than back over crop still to be worked. A machine that reverses has
    /// forms that keep in the field wherever the headland holds one turning radius.
    pub fn turn_clear(
        &self,
        from: Pose,
        to: Pose,
        area: &Area,
        clear: &dyn Fn(&[Segment]) -> bool,
    ) -> (Turn, bool) {
        self.first_inside_where(self.candidates(from, to), from, to, area, clear)
    }

    /// [`Vehicle::turn_clear`], but only if it may cost less than `limit`: `None` when even the
    /// cheapest form, inside or not, costs `limit` or more (then no turn is checked against
    /// the area, which is most of the work).
    pub fn turn_clear_below(
        &self,
        from: Pose,
        to: Pose,
        area: &Area,
        clear: &dyn Fn(&[Segment]) -> bool,
        limit: f64,
    ) -> Option<(Turn, bool)> {
        let candidates = self.candidates(from, to);
        if candidates.first().is_some_and(|t| t.cost() >= limit) {
            return None;
        }
        Some(self.first_inside_where(candidates, from, to, area, clear))
    }

    /// The first of `candidates` (cheapest first) inside `area` for which `clear` holds, else
    /// (forward only) the first outside it for which `clear` holds, else the first inside, else
    /// the cheapest of all with `inside: false`; with whether `clear` holds for it.
    fn first_inside_where(
        &self,
        candidates: Vec<Turn>,
        from: Pose,
        to: Pose,
        area: &Area,
        clear: &dyn Fn(&[Segment]) -> bool,
    ) -> (Turn, bool) {
        let clear_outside = !self.reverse;
        let mut first: Option<Turn> = None;
        let mut first_inside: Option<Turn> = None;
        let mut first_clear_outside: Option<Turn> = None;
        for mut t in candidates {
            t.inside = area.contains(&t.segments);
            if t.inside {
                if clear(&t.segments) {
                    return (t, true);
                }
                if first_inside.is_none() {
                    first_inside = Some(t);
                }
            } else if clear_outside && first_clear_outside.is_none() && clear(&t.segments) {
                first_clear_outside = Some(t);
            } else if first.is_none() {
                first = Some(t);
            }
        }
        if let Some(t) = first_clear_outside {
            return (t, true);
        }
        let t = first_inside.or(first).unwrap_or_else(|| straight(from, to));
        (t, false)
    }

    /// Tangent length of a corner of `deflection` radians rounded at the vehicle's limits: how
    /// far before the corner the rounding starts (and after it ends), metres. Infinite where it
    /// cannot be rounded (a deflection of π or more).
    pub fn tangent_length(&self, deflection: f64) -> f64 {
        let d = deflection.abs();
        if self.pivots() {
            return 0.0;
        }
        if d >= std::f64::consts::PI - 1e-9 {
            return f64::INFINITY;
        }
        if d < 1e-12 {
            return 0.0;
        }
        match self.cc() {
            Some(cc) => {
                let segs = cc_turn(Pose::new(0.0, 0.0, 0.0), d, &cc);
                let Some(e) = curve::end(&segs) else {
                    return self.turn_radius * (d / 2.0).tan();
                };
                // The corner of the lines y = 0 and the end's, which the symmetric turn
                // reaches as far before as after.
                e.x - e.y / d.tan()
            }
            None => self.turn_radius * (d / 2.0).tan(),
        }
    }

    /// The rounding of a corner of `deflection` radians (positive to the left) from `start`:
    /// an arc of the turning radius, or a continuous-curvature turn.
    pub fn fillet(&self, start: Pose, deflection: f64) -> Vec<Segment> {
        if self.pivots() {
            // Pivots standing: nothing to drive.
            return Vec::new();
        }
        match self.cc() {
            Some(cc) => cc_turn(start, deflection, &cc),
            None => vec![Segment::arc(
                start,
                self.turn_radius * deflection.abs(),
                deflection.signum() / self.turn_radius,
                Gear::Forward,
            )],
        }
    }
}

/// A straight line between two poses (the last resort: it may not match the end heading).
fn straight(from: Pose, to: Pose) -> Turn {
    let heading = (to.y - from.y).atan2(to.x - from.x);
    Turn {
        form: TurnForm::None,
        segments: vec![Segment::line(
            Pose::new(from.x, from.y, heading),
            from.distance(&to),
            Gear::Forward,
        )],
        inside: false,
    }
}

/// The three-point (fishtail) turn between the ends of neighbouring swaths: from the end of one
/// (facing out of the field) a quarter circle forward towards the next, straight back, and a
/// quarter circle forward into it; `None` unless `to` faces the opposite way of `from` and lies
/// at most twice the radius to one side of it. Where the ends are staggered along the swaths
/// (along an oblique headland edge) it is made level with the end further out: straight on
/// out of `from` first, or straight back along the swath just worked, so that it keeps beyond
/// the edge and off the crop of the swath it turns into.
///
/// ```
/// use furrow::path::curve::{Gear, Pose};
/// use furrow::path::turn::Vehicle;
/// use std::f64::consts::PI;
///
/// // Out of a swath heading north at the origin into the next one, 6 m east and starting 12 m
/// // further north: on 12 m, then the three-point turn.
/// let drill = Vehicle { turn_radius: 8.0, reverse: true, ..Vehicle::default() };
/// let (from, to) = (Pose::new(0.0, 0.0, PI / 2.0), Pose::new(6.0, 12.0, -PI / 2.0));
/// let turn = drill.candidates(from, to).into_iter().find(|t| t.form.name() == "three-point");
/// assert!(turn.is_some_and(|t| {
///     let backs = t.segments.iter().filter(|s| s.gear == Gear::Reverse).count();
///     (t.segments[0].length - 12.0).abs() < 1e-9 && backs == 1
/// }));
/// ```
fn three_point(from: Pose, to: Pose, r: f64) -> Option<Turn> {
    let rel = to.relative_to(&from);
    if (rel.heading.abs() - std::f64::consts::PI).abs() > 1e-6 {
        return None;
    }
    let spacing = rel.y.abs();
    if spacing > 2.0 * r || spacing < 1e-9 {
        return None;
    }
    // Level with `to`: on along the swath left, forward, or back along it.
    let gear = if rel.x < 0.0 {
        Gear::Reverse
    } else {
        Gear::Forward
    };
    let lead = Segment::line(from, rel.x.abs(), gear);
    let left = rel.y > 0.0;
    let k = if left { 1.0 / r } else { -1.0 / r };
    let quarter = r * FRAC_PI_2;
    let first = Segment::arc(lead.end(), quarter, k, Gear::Forward);
    let back = Segment::line(first.end(), 2.0 * r - spacing, Gear::Reverse);
    let last = Segment::arc(back.end(), quarter, k, Gear::Forward);
    // Pieces of no length are dropped with the other candidates'.
    Some(Turn {
        form: TurnForm::ThreePoint,
        segments: vec![lead, first, back, last],
        inside: true,
    })
}

/// Where the machine may drive: inside the field's boundary and outside its obstacles. Edges in
/// an R-tree: a turn is checked by its chords (at most 5 mm off the curve) against them.
#[derive(Debug, Clone)]
pub struct Area {
    pub(super) edges: RTree<Edge>,
}

/// An edge of the driving area's rings.
type Edge = IndexedSegment;

/// Chords of a sampled curve are at most this far off it, metres.
pub const CHORD_TOLERANCE_M: f64 = 0.005;

/// The tag of [`Area::new`]'s edges of the field boundary; those of obstacles are tagged
/// [`OBSTACLE_EDGE`] (both crossed by [`Area::contains`]).
pub(super) const BOUNDARY_EDGE: usize = 0;
/// The tag of [`Area::new`]'s edges of obstacles.
pub(super) const OBSTACLE_EDGE: usize = 1;

impl Area {
    /// The area inside `boundary` (with its holes) and outside `obstacles`.
    pub fn new(boundary: &Polygon, obstacles: &[&Polygon]) -> Self {
        let mut edges = Vec::new();
        let mut add = |ring: &LineString, tag: usize| {
            for l in ring.lines() {
                if l.start != l.end {
                    edges.push(Edge::new(l.start, l.end, tag, 0));
                }
            }
        };
        add(boundary.exterior(), BOUNDARY_EDGE);
        for ring in boundary.interiors() {
            add(ring, BOUNDARY_EDGE);
        }
        for o in obstacles {
            add(o.exterior(), OBSTACLE_EDGE);
            for ring in o.interiors() {
                add(ring, OBSTACLE_EDGE);
            }
        }
        Area {
            edges: RTree::bulk_load(edges),
        }
    }

    /// Whether a run of segments keeps `margin` metres or more from every edge of the area (to
    /// a centimetre): where an implement of twice that width working along it stays in. Sampled
    /// at most a fifth of the margin (and half a metre) apart.
    ///
    /// ```
    /// use furrow::path::curve::{Gear, Pose, Segment};
    /// use furrow::path::turn::Area;
    /// use geo::polygon;
    ///
    /// let field = polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 100., y: 20.), (x: 0., y: 20.)];
    /// let area = Area::new(&field, &[]);
    /// let along = Segment::line(Pose::new(10.0, 3.0, 0.0), 50.0, Gear::Forward);
    /// assert!(area.keeps_clear(&[along], 2.99));
    /// assert!(!area.keeps_clear(&[along], 3.5));
    /// ```
    pub fn keeps_clear(&self, segments: &[Segment], margin: f64) -> bool {
        let step = (margin / 5.0).clamp(0.01, 0.5);
        segments.iter().all(|s| {
            // The edges near the segment once (it stays within its length of its start), then
            // each sample against those alone.
            let reach = s.length.abs() + margin;
            let near: Vec<Edge> = self
                .edges
                .locate_in_envelope_intersecting(&AABB::from_corners(
                    [s.start.x - reach, s.start.y - reach],
                    [s.start.x + reach, s.start.y + reach],
                ))
                .copied()
                .collect();
            if near.is_empty() {
                return true;
            }
            let n = ((s.length / step).ceil() as usize).clamp(1, 100_000);
            let spacing = s.length / n as f64;
            let poses = s.poses();
            // The samples `step` apart, but those nearer along the segment to a sample than its
            // clearance beyond `margin` are as clear (the distance changes no faster than the
            // point moves) and are passed over: the same answer, far fewer samples in the open.
            let mut i = 0;
            while i <= n {
                let p = poses.at(spacing * i as f64);
                let p = Coord { x: p.x, y: p.y };
                let clearance = near
                    .iter()
                    .map(|e| point_segment_distance(p, e.a, e.b))
                    .fold(f64::INFINITY, f64::min);
                if clearance <= margin {
                    return false;
                }
                let ahead = ((clearance - margin) / spacing - 1e-9).ceil();
                i += if ahead.is_finite() && ahead > 1.0 {
                    ahead.min(n as f64 + 1.0) as usize
                } else {
                    1
                };
            }
            true
        })
    }

    /// Lines as the edges of an area, each `(start, end, tag)`: a run of segments that crosses
    /// none of those tagged `from` or later is [`Area::crosses_none_from`] them (the swaths
    /// still to be worked, tagged by the step of the route that works them, see
    /// [`super::crop`]).
    pub fn of_lines(lines: impl IntoIterator<Item = (Coord, Coord, usize)>) -> Self {
        let edges = lines
            .into_iter()
            .filter(|(a, b, _)| a != b)
            .map(|(a, b, tag)| Edge::new(a, b, tag, 0))
            .collect();
        Area {
            edges: RTree::bulk_load(edges),
        }
    }

    /// Whether a run of segments that starts inside stays inside: none of its chords crosses
    /// an edge. The tree is asked once, for the edges near the run (each segment stays within
    /// its length of its start); a run near no edge is inside without a chord drawn.
    pub fn contains(&self, segments: &[Segment]) -> bool {
        self.crosses_none_from(segments, 0)
    }

    /// Whether none of the chords of a run of segments crosses an edge tagged `from` or later
    /// ([`Area::of_lines`]; the edges of [`Area::new`] are tagged 0 and 1: all crossed from 0).
    pub fn crosses_none_from(&self, segments: &[Segment], from: usize) -> bool {
        let mut low = [f64::INFINITY; 2];
        let mut high = [f64::NEG_INFINITY; 2];
        for s in segments {
            let (x, y, reach) = (s.start.x, s.start.y, s.length.abs());
            low = [low[0].lesser(x - reach), low[1].lesser(y - reach)];
            high = [high[0].greater(x + reach), high[1].greater(y + reach)];
        }
        if !(low[0] <= high[0] && low[1] <= high[1]) {
            return true;
        }
        let mut near: Vec<Line> = Vec::new();
        for e in self
            .edges
            .locate_in_envelope_intersecting(&AABB::from_corners(low, high))
            .filter(|e| e.line >= from)
        {
            if near.len() == NEAR_EDGES_MAX {
                return match segments {
                    [one] => self.crosses_none_chordwise(one, from),
                    _ => segments
                        .iter()
                        .all(|s| self.crosses_none_from(std::slice::from_ref(s), from)),
                };
            }
            near.push(e.as_line());
        }
        if near.is_empty() {
            return true;
        }
        let mut previous: Option<Coord> = None;
        let mut beside: Vec<Line> = Vec::with_capacity(near.len());
        for s in segments {
            let n = chord_count(s);
            let poses = s.poses();
            let point = |i: usize| {
                let p = poses.at(chord_distance(s, i, n));
                Coord { x: p.x, y: p.y }
            };
            // The chords of an arc lie in a ring: between its circle and the circle one chord
            // tolerance inside. Edges that do not reach into the ring cross none of them, and
            // an arc that no edge reaches into is inside without a chord drawn. (The chord from
            // the run's previous point onto the arc is checked against every edge.)
            let edges: &[Line] = match arc_circle(s) {
                Some((centre, radius)) => {
                    beside.clear();
                    beside.extend(
                        near.iter()
                            .filter(|e| reaches_ring(e, centre, radius - CHORD_TOLERANCE_M, radius))
                            .copied(),
                    );
                    if beside.is_empty() {
                        let first = point(0);
                        if let Some(a) = previous {
                            if crosses_any(&near, a, first) {
                                return false;
                            }
                        }
                        previous = Some(point(n));
                        continue;
                    }
                    &beside
                }
                None => &near,
            };
            for (i, p) in poses.evenly(s.length, n).enumerate() {
                let p = Coord { x: p.x, y: p.y };
                if let Some(a) = previous {
                    let against = if i == 0 { &near[..] } else { edges };
                    if crosses_any(against, a, p) {
                        return false;
                    }
                }
                previous = Some(p);
            }
        }
        true
    }

    /// [`Area::crosses_none_from`] for one segment near more than [`NEAR_EDGES_MAX`] edges (a
    /// segment along an outline of thousands of vertices): its chords taken [`CHORD_GROUP`] at a
    /// time, each group measured against the edges the tree finds near it, rather than every
    /// chord against every edge near the segment.
    fn crosses_none_chordwise(&self, s: &Segment, from: usize) -> bool {
        let points: Vec<Coord> = s
            .poses()
            .evenly(s.length, chord_count(s))
            .map(|p| Coord { x: p.x, y: p.y })
            .collect();
        let mut near: Vec<Line> = Vec::new();
        let mut first = 0;
        while first + 1 < points.len() {
            let group = &points[first..points.len().min(first + CHORD_GROUP + 1)];
            let (mut low, mut high) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
            for p in group {
                low = [low[0].lesser(p.x), low[1].lesser(p.y)];
                high = [high[0].greater(p.x), high[1].greater(p.y)];
            }
            near.clear();
            near.extend(
                self.edges
                    .locate_in_envelope_intersecting(&AABB::from_corners(low, high))
                    .filter(|e| e.line >= from)
                    .map(Edge::as_line),
            );
            if group.windows(2).any(|w| crosses_any(&near, w[0], w[1])) {
                return false;
            }
            first += CHORD_GROUP;
        }
        true
    }
}

/// How many chords of a segment near many edges ask the tree together.
const CHORD_GROUP: usize = 8;

/// The most edges near a run of segments that [`Area::crosses_none_from`] measures every chord
/// against; near more, each segment is measured on its own, and a single segment a few chords at
/// a time.
const NEAR_EDGES_MAX: usize = 256;

/// Arcs of a radius up to this (metres) are checked against the edges near their ring; flatter
/// ones chord by chord.
const RING_CHECK_MAX_RADIUS_M: f64 = 1e5;

/// How far (metres) beyond a ring an edge may be found by [`reaches_ring`] and still be taken:
/// far above the rounding of coordinates of a field, far below the chord tolerance.
const RING_MARGIN_M: f64 = 1e-6;

/// The centre and radius of the circle a circular arc runs on; `None` for lines, clothoids and
/// arcs flatter than [`RING_CHECK_MAX_RADIUS_M`].
fn arc_circle(s: &Segment) -> Option<(Coord, f64)> {
    if s.sharpness != 0.0 || s.curvature == 0.0 || !s.curvature.is_finite() {
        return None;
    }
    let r = 1.0 / s.curvature;
    if r.abs() > RING_CHECK_MAX_RADIUS_M {
        return None;
    }
    // The positions are start + r (sin θ − sin θ₀, −(cos θ − cos θ₀)) (see curve::Poses::at).
    let (sin, cos) = s.start.heading.sin_cos();
    Some((
        Coord {
            x: s.start.x - r * sin,
            y: s.start.y + r * cos,
        },
        r.abs(),
    ))
}

/// Whether the edge comes within [`RING_MARGIN_M`] of the ring around `centre` between radii
/// `inner` and `outer`: not if it passes outside the outer circle, nor if it lies wholly inside
/// the inner one.
fn reaches_ring(edge: &Line, centre: Coord, inner: f64, outer: f64) -> bool {
    let nearest = point_segment_distance(centre, edge.start, edge.end);
    let farthest = (edge.start.x - centre.x)
        .planar_hypot(edge.start.y - centre.y)
        .greater((edge.end.x - centre.x).planar_hypot(edge.end.y - centre.y));
    nearest <= outer + RING_MARGIN_M && farthest >= inner - RING_MARGIN_M
}

/// Whether the chord from `a` to `b` crosses one of `edges`.
fn crosses_any(edges: &[Line], a: Coord, b: Coord) -> bool {
    let (x0, x1) = (a.x.lesser(b.x), a.x.greater(b.x));
    let (y0, y1) = (a.y.lesser(b.y), a.y.greater(b.y));
    let chord = Line::new(a, b);
    edges.iter().any(|e| {
        e.start.x.greater(e.end.x) >= x0
            && e.start.x.lesser(e.end.x) <= x1
            && e.start.y.greater(e.end.y) >= y0
            && e.start.y.lesser(e.end.y) <= y1
            && segments_intersect(&chord, e)
    })
}

/// Points along a segment whose chords stay within [`CHORD_TOLERANCE_M`] of it, ends included.
pub fn chord_points(s: &Segment) -> impl Iterator<Item = Coord> + '_ {
    chord_poses(s).map(|(p, _)| Coord { x: p.x, y: p.y })
}

/// The poses (with the steering curvature there) at [`chord_points`].
pub fn chord_poses(s: &Segment) -> impl Iterator<Item = (Pose, f64)> + '_ {
    chord_poses_within(s, CHORD_TOLERANCE_M)
}

/// [`chord_poses`] with the chords within `tolerance` metres of the segment.
pub fn chord_poses_within(s: &Segment, tolerance: f64) -> impl Iterator<Item = (Pose, f64)> + '_ {
    let n = chords_within(s, tolerance);
    let poses = s.poses();
    let at = (0..=n).map(move |i| chord_distance(s, i, n));
    poses
        .evenly(s.length, n)
        .zip(at)
        .map(move |(p, at)| (p, s.curvature_at(at)))
}

/// The number of chords [`chord_points`] divides a segment into.
fn chord_count(s: &Segment) -> usize {
    chords_within(s, CHORD_TOLERANCE_M)
}

/// The number of chords within `tolerance` metres of a segment (1 for a line): a chord of
/// length `c` on a curve of curvature `k` falls `c² k / 8` short of it.
pub fn chords_within(s: &Segment, tolerance: f64) -> usize {
    let k = s.max_curvature();
    let step = if k > 1e-12 {
        (8.0 * tolerance / k).sqrt()
    } else {
        f64::INFINITY
    };
    if step.is_finite() {
        ((s.length / step).ceil() as usize).clamp(1, 100_000)
    } else {
        1
    }
}

/// How far along the segment the `i`th of the points of `n` chords lies, metres.
fn chord_distance(s: &Segment, i: usize, n: usize) -> f64 {
    s.length * i as f64 / n as f64
}

/// Whether two closed segments meet.
fn segments_intersect(a: &Line, b: &Line) -> bool {
    let d = |p: Coord, q: Coord, r: Coord| (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
    let (d1, d2) = (d(b.start, b.end, a.start), d(b.start, b.end, a.end));
    let (d3, d4) = (d(a.start, a.end, b.start), d(a.start, a.end, b.end));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    // Touching counts as leaving only where a point lies on the other segment.
    let on = |p: Coord, q: Coord, r: Coord, dd: f64| {
        dd == 0.0
            && r.x >= p.x.lesser(q.x)
            && r.x <= p.x.greater(q.x)
            && r.y >= p.y.lesser(q.y)
            && r.y <= p.y.greater(q.y)
    };
    on(b.start, b.end, a.start, d1)
        || on(b.start, b.end, a.end, d2)
        || on(a.start, a.end, b.start, d3)
        || on(a.start, a.end, b.end, d4)
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::polygon;
    use proptest::prelude::*;
    use std::f64::consts::PI;

    /// [`Area::keeps_clear`] as it was first written: every sample `step` apart against every
    /// edge near the segment.
    fn keeps_clear_sample_by_sample(area: &Area, segments: &[Segment], margin: f64) -> bool {
        let step = (margin / 5.0).clamp(0.01, 0.5);
        segments.iter().all(|s| {
            let n = ((s.length / step).ceil() as usize).clamp(1, 100_000);
            let poses = s.poses();
            (0..=n).all(|i| {
                let p = poses.at(s.length * i as f64 / n as f64);
                area.edges
                    .iter()
                    .all(|e| point_segment_distance(Coord { x: p.x, y: p.y }, e.a, e.b) > margin)
            })
        })
    }

    proptest! {
        #[test]
        fn keeps_clear_passes_over_samples_without_changing_the_answer(
            x in 0.0f64..60.0, y in 0.0f64..40.0, heading in -PI..PI,
            length in 0.1f64..80.0, curvature in -0.3f64..0.3, margin in 0.02f64..4.0,
        ) {
            // An L-shaped field with a square pond: edges on every side of most segments.
            let field = polygon![(x: 0., y: 0.), (x: 60., y: 0.), (x: 60., y: 20.), (x: 30., y: 20.),
                (x: 30., y: 40.), (x: 0., y: 40.)];
            let pond = polygon![(x: 10., y: 10.), (x: 14., y: 10.), (x: 14., y: 14.), (x: 10., y: 14.)];
            let area = Area::new(&field, &[&pond]);
            let start = Pose::new(x, y, heading);
            let runs = [
                vec![Segment::line(start, length, Gear::Forward)],
                vec![Segment::arc(start, length, curvature, Gear::Forward)],
            ];
            for run in runs {
                prop_assert_eq!(
                    area.keeps_clear(&run, margin),
                    keeps_clear_sample_by_sample(&area, &run, margin)
                );
            }
        }
    }

    #[test]
    fn a_turn_keeps_off_what_clear_rules_out_where_a_form_does() {
        let v = Vehicle {
            turn_radius: 5.0,
            ..Vehicle::default()
        };
        let field =
            polygon![(x: -50., y: -50.), (x: 50., y: -50.), (x: 50., y: 50.), (x: -50., y: 50.)];
        let area = Area::new(&field, &[]);
        // A U-turn to the left, 20 m across: the cheapest (LSL) runs north along x = 5, across a
        // line from (2, 10) to (8, 10) worked at step 1.
        let crop = Area::of_lines([(Coord { x: 2.0, y: 10.0 }, Coord { x: 8.0, y: 10.0 }, 1)]);
        let (from, to) = (Pose::new(0.0, 0.0, 0.0), Pose::new(0.0, 20.0, PI));
        let cheapest = v.turn(from, to, &area);
        assert!(!crop.crosses_none_from(&cheapest.segments, 1));
        // Before step 1 the line is crop: the turn takes the way round the other side.
        let (clear, kept_off) = v.turn_clear(from, to, &area, &|s| crop.crosses_none_from(s, 1));
        assert!(clear.inside && kept_off);
        assert!(crop.crosses_none_from(&clear.segments, 1));
        assert!(clear.cost() > cheapest.cost());
        // After step 1 it is worked: nothing to keep off.
        assert!(crop.crosses_none_from(&cheapest.segments, 2));
        let (after, _) = v.turn_clear(from, to, &area, &|s| crop.crosses_none_from(s, 2));
        assert_eq!(after.form, cheapest.form);
        // Where no form keeps off it, the cheapest inside the field.
        let (everything, kept_off) = v.turn_clear(from, to, &area, &|_| false);
        assert_eq!(everything.form, cheapest.form);
        assert!(everything.inside && !kept_off);
    }

    /// [`Area::contains`] without the ring check: every chord against every edge.
    fn contains_chord_by_chord(area: &Area, segments: &[Segment]) -> bool {
        let edges: Vec<Line> = area.edges.iter().map(Edge::as_line).collect();
        let points: Vec<Coord> = segments.iter().flat_map(chord_points).collect();
        !points.windows(2).any(|w| crosses_any(&edges, w[0], w[1]))
    }

    proptest! {
        #![proptest_config(crate::seeded::config(2048))]
        /// Skipping the edges that do not reach into an arc's ring of chords gives the same
        /// answer as checking every chord against every edge: turns of every form, forward,
        /// reversing and with clothoids, between poses near a field's edge and an obstacle.
        #[test]
        fn the_ring_check_is_the_chord_by_chord_check(
            x in -30.0..30.0f64, y in -30.0..30.0f64, heading in -PI..PI,
            dx in -25.0..25.0f64, dy in -25.0..25.0f64, turn in -PI..PI,
            radius in 2.0..12.0f64, reverse: bool, clothoids: bool, edge in 5.0..40.0f64,
        ) {
            let area = Area::new(
                &polygon![(x: -60., y: -60.), (x: edge, y: -60.), (x: edge, y: 60.), (x: -60., y: 60.)],
                &[&polygon![(x: -20., y: 10.), (x: -12., y: 10.), (x: -12., y: 16.), (x: -20., y: 16.)]],
            );
            let v = Vehicle {
                turn_radius: radius,
                reverse: reverse && !clothoids,
                curvature_rate: clothoids.then_some(0.2),
                ..Vehicle::default()
            };
            let from = Pose::new(x, y, heading);
            let to = Pose::new(x + dx, y + dy, heading + turn);
            for t in v.candidates(from, to) {
                prop_assert_eq!(area.contains(&t.segments), contains_chord_by_chord(&area, &t.segments));
            }
        }

        /// Near an outline of many short edges (more than [`NEAR_EDGES_MAX`] near a turn) each
        /// segment is measured on its own, and one near as many a few chords at a time against
        /// the edges the tree finds near them: the same answer as every chord against every
        /// edge.
        #[test]
        fn chords_near_many_edges_are_checked_as_against_all(
            x in -30.0..30.0f64, y in -30.0..30.0f64, heading in -PI..PI,
            dx in -25.0..25.0f64, dy in -25.0..25.0f64, turn in -PI..PI,
            radius in 2.0..12.0f64, reverse: bool, edge in 5.0..40.0f64,
        ) {
            // The east side a wavy line of 600 edges 0.2 m apart.
            let mut ring: Vec<Coord> = vec![Coord { x: -60.0, y: -60.0 }];
            ring.extend((0..=600).map(|k| Coord {
                x: edge + 0.3 * (k as f64 * 0.7).sin(),
                y: -60.0 + 0.2 * k as f64,
            }));
            ring.push(Coord { x: -60.0, y: 60.0 });
            let area = Area::new(&Polygon::new(LineString::new(ring), vec![]), &[]);
            let v = Vehicle { turn_radius: radius, reverse, ..Vehicle::default() };
            let from = Pose::new(x, y, heading);
            let to = Pose::new(x + dx, y + dy, heading + turn);
            for t in v.candidates(from, to) {
                prop_assert_eq!(area.contains(&t.segments), contains_chord_by_chord(&area, &t.segments));
            }
        }
    }

    #[test]
    fn a_loop_turn_for_close_swaths_and_three_points_when_reversing() {
        let v = Vehicle {
            turn_radius: 6.0,
            ..Vehicle::default()
        };
        let from = Pose::new(0.0, 0.0, 0.0);
        let to = Pose::new(0.0, 3.0, PI);
        let t = v.shortest(from, to);
        assert_eq!(t.form.name(), "loop");
        // r(π + 4 acos((d + 2r)/4r)), the turn model's loop.
        let model = 6.0 * (PI + 4.0 * (15.0f64 / 24.0).acos());
        assert!((t.length() - model).abs() < 1e-6, "{} {model}", t.length());
        let reversing = Vehicle { reverse: true, ..v };
        let all = reversing.candidates(from, to);
        let fishtail = all.iter().find(|t| t.form == TurnForm::ThreePoint).unwrap();
        assert!((fishtail.length() - (6.0 * PI + 9.0)).abs() < 1e-9);
        assert_eq!(fishtail.cusps(), 2);
        let e = curve::end(&fishtail.segments).unwrap();
        assert!(e.distance(&to) < 1e-9 && e.heading_change(&to).abs() < 1e-9);
    }

    #[test]
    fn a_turn_that_leaves_the_area_gives_way_to_one_that_fits() {
        // Swath ends 10 m from the boundary: the loop bulges out further than that; the
        // three-point turn reaches r = 6 m out.
        let area = Area::new(
            &polygon![(x: -100., y: -50.), (x: 10., y: -50.), (x: 10., y: 50.), (x: -100., y: 50.)],
            &[],
        );
        let v = Vehicle {
            turn_radius: 6.0,
            reverse: true,
            ..Vehicle::default()
        };
        let from = Pose::new(0.0, 0.0, 0.0);
        let to = Pose::new(0.0, 3.0, PI);
        let forward = Vehicle {
            reverse: false,
            ..v
        };
        let cheapest = forward.shortest(from, to);
        assert_eq!(cheapest.form.name(), "loop");
        assert!(!area.contains(&cheapest.segments));
        let t = forward.turn(from, to, &area);
        assert!(t.inside && area.contains(&t.segments) && t.length() > cheapest.length());
        let t = v.turn(from, to, &area);
        assert!(t.inside && area.contains(&t.segments));
        let fishtail = three_point(from, to, 6.0).unwrap();
        assert!(area.contains(&fishtail.segments));
        assert!(t.cost() <= fishtail.cost() + 1e-9, "{:?}", t.form);
        // In a corridor 5 m wide no forward turn fits: the cheapest is kept and marked. A
        // machine that may reverse turns round in it (Reeds-Shepp, cusps and short arcs).
        let tight = Area::new(
            &polygon![(x: -100., y: -1.), (x: 1., y: -1.), (x: 1., y: 4.), (x: -100., y: 4.)],
            &[],
        );
        let t = forward.turn(from, to, &tight);
        assert!(!t.inside && t.form.name() == "loop");
        let t = v.turn(from, to, &tight);
        assert!(t.inside && t.cusps() >= 2, "{:?}", t.form);
    }

    #[test]
    fn a_three_point_turn_between_staggered_ends_is_made_level_with_the_end_further_out() {
        // From a swath heading north into the next one 6 m east, its start 10 m further on or
        // 10 m back: on out of the swath or back along it, then the three-point turn.
        let from = Pose::new(0.0, 0.0, FRAC_PI_2);
        for (y, gear) in [(10.0, Gear::Forward), (-10.0, Gear::Reverse)] {
            let to = Pose::new(6.0, y, -FRAC_PI_2);
            let t = three_point(from, to, 8.0).expect("a three-point turn");
            let lead = t.segments[0];
            assert!(
                lead.curvature == 0.0 && lead.gear == gear && (lead.length - 10.0).abs() < 1e-9
            );
            let end = curve::end(&t.segments).unwrap();
            assert!(end.distance(&to) < 1e-9 && end.heading_change(&to).abs() < 1e-9);
            // It reaches no further than the radius beyond the end further out.
            let top = t
                .segments
                .iter()
                .flat_map(|s| [s.start.y, s.end().y])
                .fold(f64::MIN, f64::max);
            assert!(top <= y.max(0.0) + 8.0 + 1e-9, "{top}");
        }
    }

    #[test]
    fn tangent_lengths_match_the_fillets() {
        for rate in [None, Some(0.2)] {
            let v = Vehicle {
                turn_radius: 5.0,
                curvature_rate: rate,
                ..Vehicle::default()
            };
            for d in [0.3, 1.0, -1.2, 2.5] {
                let t = v.tangent_length(d);
                let start = Pose::new(-t, 0.0, 0.0);
                let e = curve::end(&v.fillet(start, d)).unwrap();
                // It ends on the other line, t past the corner at the origin.
                let expect = Pose::new(t * d.cos(), t * d.sin(), d);
                assert!(e.distance(&expect) < 1e-6, "{rate:?} {d}: {e:?} {expect:?}");
                assert!(e.heading_change(&expect).abs() < 1e-9);
            }
        }
    }
}
