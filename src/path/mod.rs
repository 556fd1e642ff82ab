//! The path: the route as one continuous, drivable line, segment by segment.
//!
//! Worked segments (swaths, headland passes) are joined by connectors: a `turn` between two
//! swaths of one block, a `connection` anywhere else (between blocks, onto the headland, from the
//! entrance and to the exit). Every segment is a run of drivable pieces ([`curve::Segment`]:
//! lines, arcs of at least the turning radius, clothoids), each starting where the one before
//! ends, facing the same way:
//! - a swath is its centre line;
//! - a headland pass follows its centre line with its corners rounded at the vehicle's limits
//!   ([`follow`]); at a corner too sharp to round (a dead end, a cusp) the implement is lifted
//!   for a `turn` of its own, the manoeuvre that stays in the field where one does;
//! - a turn is the cheapest form the vehicle can drive between the two swath ends that stays in
//!   the field ([`turn`]: Dubins, Reeds-Shepp, three-point, continuous-curvature); turns that
//!   cannot stay in are kept, marked and counted;
//! - a connection follows the route's line along the headland, joined to the poses at either
//!   end by the vehicle's cheapest turn that stays in the field (where one does) and off the crop
//!   of the swaths worked later (where one does, [`crop`]); between near poses it is one such
//!   turn, unless only the way along the line keeps off that crop.
//!
//! [`sample`] gives the path as points at a set spacing, for drawing and guidance.

pub mod continuous;
pub mod crop;
pub mod curve;
pub mod dubins;
pub mod follow;
pub mod lift;
pub mod reeds_shepp;
pub mod sample;
#[cfg(test)]
mod testing;
pub mod turn;

use crate::geometry::intervals::Intervals;
use crate::geometry::point_segment_distance;
use crate::geometry::{Extremes, PlanarHypot};
use crate::headland::HeadlandPass;
use crate::route::headland_graph::HeadlandGraph;
use crate::route::{nearest_on_ring, Route, RouteStep};
use crate::swath::Swaths;
use crop::StandingCrop;
use curve::{Gear, Pose, Segment};
use follow::{follow, follow_in, follow_round_in, Manoeuvre};
use geo::{Coord, Euclidean, Length, LineString};
use turn::{Area, TurnForm, Vehicle};

/// What a segment of the path is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SegmentKind {
    /// Working along a swath.
    Swath,
    /// Working along a headland pass.
    HeadlandPass,
    /// Turning from the end of one swath to the next swath of the same block, or a manoeuvre
    /// at a sharp corner or dead end of a headland pass (the implement lifted).
    Turn,
    /// Driving without working between blocks, or between swaths and headland passes.
    Connection,
}

impl SegmentKind {
    /// The kind's name in the plan output (`properties.kind`).
    pub fn as_str(self) -> &'static str {
        match self {
            SegmentKind::Swath => "swath",
            SegmentKind::HeadlandPass => "headland",
            SegmentKind::Turn => "turn",
            SegmentKind::Connection => "connection",
        }
    }

    /// A small number for the kind in flat sample arrays: 0 swath, 1 headland pass, 2 turn,
    /// 3 connection.
    pub fn code(self) -> u8 {
        match self {
            SegmentKind::Swath => 0,
            SegmentKind::HeadlandPass => 1,
            SegmentKind::Turn => 2,
            SegmentKind::Connection => 3,
        }
    }
}

/// How a turn came out.
#[derive(Debug, Clone, PartialEq)]
pub struct TurnReport {
    /// Its form.
    pub form: TurnForm,
    /// Whether it stays inside the field and off its obstacles.
    pub inside: bool,
    /// How far it reaches beyond the end of the swath it leaves, metres (along that swath).
    pub reach_m: f64,
}

/// One segment of the path.
#[derive(Debug, Clone, PartialEq)]
pub struct PathSegment {
    /// What the segment is.
    pub kind: SegmentKind,
    /// The pieces driven, in order.
    pub pieces: Vec<Segment>,
    /// Its shape as a line in driving order: the pieces' points, curves at chords within 5 mm.
    pub line: LineString,
    /// The route step it works (swaths and headland passes), as an index into `Route::steps`.
    pub step: Option<usize>,
    /// For a turn: its form and whether it stays in the field.
    pub turn: Option<TurnReport>,
    /// For a connection between two worked stretches (not from the entrance or to the exit):
    /// whether it leaves the field or crosses an obstacle (no turn the machine can drive onto,
    /// off or along the headland passes keeps in there).
    pub leaves_field: bool,
    /// For a connection between two worked stretches: whether it drives over crop the route
    /// works later ([`crop`]: no turn the machine can drive onto, off or along the headland
    /// keeps off it); for a turn between swaths, whether it does, keeping in the field.
    pub crosses_crop: bool,
    /// For a worked segment: the stretches driven with the implement lifted, metres along its
    /// line from its first point, sorted and disjoint ([`lift`]: over small obstacles, and
    /// wherever the implement would reach out of the field or over an obstacle).
    pub lifted: Intervals,
}

impl PathSegment {
    /// A segment of these pieces (its line drawn from them).
    pub fn new(kind: SegmentKind, pieces: Vec<Segment>, step: Option<usize>) -> Self {
        Self::new_visiting(kind, pieces, step, |_| {})
    }

    /// [`PathSegment::new`], showing `visit` each point of the pieces' chords as the line is
    /// drawn (those the line leaves out for lying on the point before too).
    fn new_visiting(
        kind: SegmentKind,
        pieces: Vec<Segment>,
        step: Option<usize>,
        mut visit: impl FnMut(Coord),
    ) -> Self {
        let mut pts: Vec<Coord> = Vec::new();
        for p in &pieces {
            for c in turn::chord_points(p) {
                visit(c);
                if pts
                    .last()
                    .is_none_or(|q: &Coord| (q.x - c.x).planar_hypot(q.y - c.y) > 1e-9)
                {
                    pts.push(c);
                }
            }
        }
        if pts.len() == 1 {
            pts.push(pts[0]);
        }
        PathSegment {
            kind,
            pieces,
            line: LineString::new(pts),
            step,
            turn: None,
            leaves_field: false,
            crosses_crop: false,
            lifted: Intervals::new(),
        }
    }

    /// Length driven along the segment, metres.
    pub fn length(&self) -> f64 {
        if self.pieces.is_empty() {
            Euclidean.length(&self.line)
        } else {
            curve::length(&self.pieces)
        }
    }

    /// Whether the implement works along this segment.
    pub fn is_working(&self) -> bool {
        matches!(self.kind, SegmentKind::Swath | SegmentKind::HeadlandPass)
    }

    /// The stretches of its line worked with the implement down (none for a segment that does
    /// not work).
    pub fn worked_stretches(&self) -> Vec<Vec<Coord>> {
        if !self.is_working() {
            return Vec::new();
        }
        if self.lifted.is_empty() {
            return vec![self.line.0.clone()];
        }
        let total = polyline_length(&self.line.0);
        let mut out = Vec::new();
        let mut from = 0.0;
        for &(a, b) in self.lifted.iter().chain(std::iter::once(&(total, total))) {
            if a > from {
                out.push(cut_polyline(&self.line.0, from, a));
            }
            from = from.greater(b);
        }
        out
    }

    /// Whether any piece of it is driven in reverse.
    pub fn reverses(&self) -> bool {
        self.pieces.iter().any(|p| p.gear == Gear::Reverse)
    }

    /// Where it starts.
    pub fn start(&self) -> Option<Pose> {
        self.pieces.first().map(|p| p.start)
    }

    /// Where it ends.
    pub fn end(&self) -> Option<Pose> {
        curve::end(&self.pieces)
    }
}

/// The path of a plan: its segments in driving order, each starting where the last one ended.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Path {
    /// The segments in driving order.
    pub segments: Vec<PathSegment>,
}

/// Connectors shorter than this (metres) are not drawn: the segments already meet.
const MIN_CONNECTOR_M: f64 = 1e-6;

/// A connection along a line shorter than this many turning radii is one turn between its
/// ends: following its corners would only add manoeuvres.
const DIRECT_CONNECTION_RADII: f64 = 6.0;

/// Builds the drivable path of a route (see the module documentation). `area` is where turns
/// must stay (the field less its obstacles); without it turns are not checked. `graph`, the
/// ways along the route's headland passes: a turn between swath ends far apart along the swaths
/// that crosses crop worked later is driven along it instead where that crosses less (form
/// `headland`); without it every turn is one form of turn.
///
/// ```
/// use furrow::{decompose::cluster_swaths, path::{build_path, SegmentKind, turn::Vehicle}};
/// use furrow::{route::{plan_route, RouteSettings}, swath::generate};
/// use geo::{polygon, MultiPolygon};
///
/// let field = polygon![(x: 0., y: 0.), (x: 30., y: 0.), (x: 30., y: 100.), (x: 0., y: 100.)];
/// let swaths = generate(&MultiPolygon::new(vec![field]), 0.0, 6.0, 6.0)?;
/// let route = plan_route(&swaths, &cluster_swaths(&swaths), &[], &RouteSettings::default());
/// let vehicle = Vehicle { width: 6.0, turn_radius: 3.0, ..Vehicle::default() };
/// let path = build_path(&route, &swaths, &[], &vehicle, None, None);
/// let turns: Vec<_> = path.segments.iter().filter(|s| s.kind == SegmentKind::Turn).collect();
/// assert_eq!(turns.len(), 4); // five swaths, four turns between them
/// // Swaths 6 m apart, a 3 m radius: each turn is a U of two quarter circles, πr long.
/// assert!(turns.iter().all(|t| (t.length() - 3.0 * std::f64::consts::PI).abs() < 1e-9));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn build_path(
    route: &Route,
    swaths: &Swaths,
    passes: &[HeadlandPass],
    vehicle: &Vehicle,
    area: Option<&Area>,
    graph: Option<&HeadlandGraph>,
) -> Path {
    // The worked segments first (a headland pass with manoeuvres is several, with the turns
    // between), each step with the connection the route found into it.
    let mut worked: Vec<Worked> = Vec::with_capacity(route.steps.len());
    let mut last_point: Option<Coord> = None;
    for (k, step) in route.steps.iter().enumerate() {
        let into = route
            .connections
            .get(k)
            .and_then(|c| c.as_ref())
            .map(|c| c.line.clone());
        let mut ring = None;
        let (segments, block) = match *step {
            RouteStep::Swath {
                swath,
                reversed,
                block,
            } => {
                let Some(s) = swaths.swaths.get(swath) else {
                    continue;
                };
                let (a, b) = if reversed {
                    (s.centre.end, s.centre.start)
                } else {
                    (s.centre.start, s.centre.end)
                };
                let d = b - a;
                let start = Pose::new(a.x, a.y, d.y.atan2(d.x));
                let line = Segment::line(start, d.x.planar_hypot(d.y), Gear::Forward);
                (
                    vec![PathSegment::new(SegmentKind::Swath, vec![line], Some(k))],
                    Some(block),
                )
            }
            RouteStep::HeadlandPass { pass, reversed } => {
                let Some(p) = passes.get(pass) else {
                    continue;
                };
                let (pieces, manoeuvres) = if p.closed {
                    // Where the connection into it ends, else where the machine is.
                    let at = into
                        .as_ref()
                        .and_then(|c| c.0.last().copied())
                        .or(last_point);
                    let (_, entry) = nearest_on_ring(&p.line, at);
                    // All the way round, back to where it was entered.
                    let round = ring_starting_at(&p.line, entry).0;
                    let driven = follow_round_in(&round, vehicle, area);
                    ring = Some((round, k));
                    driven
                } else if reversed {
                    let line: Vec<Coord> = p.line.0.iter().rev().copied().collect();
                    follow_in(&line, vehicle, area)
                } else {
                    follow_in(&p.line.0, vehicle, area)
                };
                (pass_segments(pieces, &manoeuvres, k), None)
            }
        };
        let Some(end) = segments.last().and_then(PathSegment::end) else {
            continue;
        };
        last_point = Some(Coord { x: end.x, y: end.y });
        worked.push(Worked {
            segments,
            block,
            into,
            ring,
            step: k,
        });
    }
    // The crop matters to the connections before the last swath; it is laid out when the
    // first of them is.
    let last_swath = route
        .steps
        .iter()
        .rposition(|s| matches!(s, RouteStep::Swath { .. }));
    let standing = std::cell::OnceCell::new();
    let mut segments: Vec<PathSegment> = Vec::with_capacity(worked.len() * 2 + 2);
    let mut previous: Option<(Pose, Option<usize>)> = None;
    // Turns that cross crop worked later: (segment, from, to, route step).
    let mut crossing_turns: Vec<(usize, Pose, Pose, usize)> = Vec::new();
    for mut w in worked {
        let Some(start) = w.segments.first().and_then(PathSegment::start) else {
            continue;
        };
        // Only connections before the last swath can cross crop worked later.
        let crop = || match (area, last_swath) {
            (Some(_), Some(last)) if w.step <= last => Some((
                standing.get_or_init(|| StandingCrop::of_route(route, swaths)),
                w.step,
            )),
            _ => None,
        };
        match previous {
            Some((from, from_block)) => {
                let same_block = w.block.is_some() && w.block == from_block;
                if same_block && w.into.is_none() {
                    if let Some((mut t, crossing)) = swath_turn(from, start, vehicle, area, crop())
                    {
                        t.crosses_crop = crossing;
                        // Where no form of turn keeps off the crop, the way along the
                        // headland may: past the ends of the swaths between, or round a
                        // corner the turn would cut.
                        if crossing && graph.is_some() {
                            crossing_turns.push((segments.len(), from, start, w.step));
                        }
                        segments.push(t);
                    }
                } else if let Some(c) = connection(
                    Some(from),
                    Some(start),
                    w.into.as_ref(),
                    vehicle,
                    area,
                    crop(),
                ) {
                    match c
                        .leaves_field
                        .then(|| the_other_way(&w, from, vehicle, area, crop()))
                    {
                        Some(Some((c, pass))) => {
                            segments.push(c);
                            w.segments = pass;
                        }
                        _ => segments.push(c),
                    }
                }
            }
            None => {
                // From the entrance: along the route's line into the first pose.
                if let Some(c) = connection(None, Some(start), w.into.as_ref(), vehicle, area, None)
                {
                    segments.push(c);
                }
            }
        }
        previous = w
            .segments
            .last()
            .and_then(PathSegment::end)
            .map(|e| (e, w.block));
        segments.extend(w.segments);
    }
    if let Some(c) = &route.finish {
        let to_exit = connection(
            previous.map(|p| p.0),
            None,
            Some(&c.line),
            vehicle,
            area,
            None,
        );
        if let Some(f) = to_exit {
            segments.push(f);
        }
    }
    if let (Some(g), Some(standing)) = (graph, standing.get()) {
        turns_along_headland(&mut segments, &crossing_turns, g, vehicle, area, standing);
    }
    lift::lift_where_needed(&mut segments, route, swaths, vehicle.width / 2.0, area);
    Path { segments }
}

/// A route step's worked segments, as `build_path` lays them before the connections.
struct Worked {
    segments: Vec<PathSegment>,
    block: Option<usize>,
    /// The route's connection into the step.
    into: Option<LineString>,
    /// A closed pass: its ring as driven (from where it is entered) and its route step.
    ring: Option<(Vec<Coord>, usize)>,
    /// Its route step.
    step: usize,
}

/// A closed pass whose connection from `from` leaves the field, driven round the other way: the
/// connection into it and its segments, where that connection stays in and the pass is worked
/// as far as the first way round.
fn the_other_way(
    w: &Worked,
    from: Pose,
    v: &Vehicle,
    area: Option<&Area>,
    crop: Option<(&StandingCrop, usize)>,
) -> Option<(PathSegment, Vec<PathSegment>)> {
    let (ring, step) = w.ring.as_ref()?;
    let reversed: Vec<Coord> = ring.iter().rev().copied().collect();
    // The connection onto the ring's first edge first: following the ring costs far more.
    let first = *reversed.first()?;
    let next = reversed
        .iter()
        .find(|q| (q.x - first.x).planar_hypot(q.y - first.y) > 1e-6)?;
    let onto = Pose::new(first.x, first.y, (next.y - first.y).atan2(next.x - first.x));
    let mut c = connection(Some(from), Some(onto), w.into.as_ref(), v, area, crop)?;
    if c.leaves_field {
        return None;
    }
    let (pieces, manoeuvres) = follow_round_in(&reversed, v, area);
    let pass = pass_segments(pieces, &manoeuvres, *step);
    let worked = |segments: &[PathSegment]| -> f64 {
        segments
            .iter()
            .filter(|s| s.is_working())
            .map(PathSegment::length)
            .sum()
    };
    if worked(&pass) < worked(&w.segments) - 0.5 {
        return None;
    }
    let start = pass.first().and_then(PathSegment::start)?;
    if start.distance(&onto) > 1e-9 || start.heading_change(&onto).abs() > 1e-9 {
        c = connection(Some(from), Some(start), w.into.as_ref(), v, area, crop)?;
    }
    (!c.leaves_field).then_some((c, pass))
}

/// The path's segments along a headland pass (route step `step`): its pieces worked, each of its
/// manoeuvres a turn of its own with the implement lifted.
fn pass_segments(pieces: Vec<Segment>, manoeuvres: &[Manoeuvre], step: usize) -> Vec<PathSegment> {
    let mut out = Vec::with_capacity(2 * manoeuvres.len() + 1);
    let mut rest = pieces.into_iter();
    let mut at = 0;
    for m in manoeuvres {
        let worked: Vec<Segment> = rest.by_ref().take(m.pieces.start - at).collect();
        if !worked.is_empty() {
            out.push(PathSegment::new(
                SegmentKind::HeadlandPass,
                worked,
                Some(step),
            ));
        }
        let turn: Vec<Segment> = rest.by_ref().take(m.pieces.len()).collect();
        if let Some(from) = turn.first().map(|s| s.start) {
            out.push(turn_segment(from, turn, m.form.clone(), m.inside));
        }
        at = m.pieces.end;
    }
    let worked: Vec<Segment> = rest.collect();
    if !worked.is_empty() {
        out.push(PathSegment::new(
            SegmentKind::HeadlandPass,
            worked,
            Some(step),
        ));
    }
    out
}

/// A turn of these pieces from `from`, reported with its form, whether it stays inside and how
/// far it reaches ahead of `from`.
fn turn_segment(from: Pose, pieces: Vec<Segment>, form: TurnForm, inside: bool) -> PathSegment {
    let (s, c) = from.heading.sin_cos();
    let mut reach: f64 = 0.0;
    let mut seg = PathSegment::new_visiting(SegmentKind::Turn, pieces, None, |q| {
        reach = reach.max((q.x - from.x) * c + (q.y - from.y) * s);
    });
    seg.turn = Some(TurnReport {
        form,
        inside,
        reach_m: reach,
    });
    seg
}

/// The turn between two swath ends of a block: the cheapest form that keeps in the field and
/// off `crop` (the crop standing before that route step); else, forward only, the cheapest off
/// it outside the field; else the cheapest in the field ([`Vehicle::turn_clear`]). With whether
/// it crosses that crop.
fn swath_turn(
    from: Pose,
    to: Pose,
    v: &Vehicle,
    area: Option<&Area>,
    crop: Option<(&StandingCrop, usize)>,
) -> Option<(PathSegment, bool)> {
    if from.distance(&to) < MIN_CONNECTOR_M && from.heading_change(&to).abs() < 1e-9 {
        return None;
    }
    let (t, crossing) = match (area, crop) {
        (Some(a), Some((crop, step))) => {
            let clear = |s: &[Segment]| !crop.crossed(s, step);
            let (t, kept_off) = v.turn_clear(from, to, a, &clear);
            // Of a machine that reverses, a turn that leaves the field is not asked.
            let crossing = !kept_off && (t.inside || !clear(&t.segments));
            (t, crossing)
        }
        (Some(a), None) => (v.turn(from, to, a), false),
        (None, _) => {
            let mut t = v.shortest(from, to);
            t.inside = true;
            (t, false)
        }
    };
    Some((turn_segment(from, t.segments, t.form, t.inside), crossing))
}

/// The turns between swath ends at `crossing` (their segment, end poses and route step) that
/// cross crop worked later, each driven instead along the headland graph's way between its
/// ends where that way falls less short ([`shortfall`]: for a forward machine, off the crop
/// even if its joins leave the field; for one that reverses, in the field) or as short and
/// crosses less of the crop; a forward machine's turn that crosses crop either way takes the
/// way over less of it, in the field or not (one search of the graph for all).
fn turns_along_headland(
    segments: &mut [PathSegment],
    crossing: &[(usize, Pose, Pose, usize)],
    graph: &HeadlandGraph,
    v: &Vehicle,
    area: Option<&Area>,
    standing: &StandingCrop,
) {
    if crossing.is_empty() {
        return;
    }
    let ends: Vec<Coord> = crossing
        .iter()
        .flat_map(|&(_, a, b, _)| [Coord { x: a.x, y: a.y }, Coord { x: b.x, y: b.y }])
        .collect();
    let joined = graph.connect(&ends);
    for (i, &(at, from, to, step)) in crossing.iter().enumerate() {
        let Some(line) = joined.line(2 * i, 2 * i + 1) else {
            continue;
        };
        let crop = Some((standing, step));
        let Some(c) = connection_minding(Some(from), Some(to), Some(&line), v, area, crop) else {
            continue;
        };
        // Kept where it falls less short than the turn, or as short and over less crop (at
        // most its joins, where no form keeps off it, against a turn driven past the ends of
        // the swaths between).
        let Some(turn) = segments.get(at) else {
            continue;
        };
        let crosses_crop = standing.crossed(&c.pieces, step);
        let along = shortfall(v, c.leaves_field, crosses_crop);
        let outside = turn.turn.as_ref().is_some_and(|t| !t.inside);
        let direct = shortfall(v, outside, turn.crosses_crop);
        let less_crop = || {
            standing.crossed_length(&c.pieces, step) < standing.crossed_length(&turn.pieces, step)
        };
        // A forward machine whose turn crosses crop either way takes the way over less of it,
        // in the field or not.
        let better = if !v.reverse && crosses_crop && turn.crosses_crop {
            less_crop()
        } else {
            along < direct || (along == direct && less_crop())
        };
        if !better {
            continue;
        }
        segments[at] = turn_segment(from, c.pieces, TurnForm::Headland, !c.leaves_field);
        segments[at].crosses_crop = crosses_crop;
    }
}

/// A connection from `from` (or the line's first point) to `to` (or its last point) along
/// `line`: the line's middle followed with its corners rounded, joined to the end poses by the
/// vehicle's cheapest turns onto it (each at the point along the line where joining costs least).
/// Short lines, and none, give one turn between the poses, unless that turn leaves the field or
/// crosses `crop` (the crop standing before that route step) and the way along the line does not.
/// Every join keeps in the field and off the crop where a form of turn does.
fn connection(
    from: Option<Pose>,
    to: Option<Pose>,
    line: Option<&LineString>,
    v: &Vehicle,
    area: Option<&Area>,
    crop: Option<(&StandingCrop, usize)>,
) -> Option<PathSegment> {
    // Most connections keep off the crop as they are: only those that do not are made again
    // minding it (the same connection where the first keeps off it), and the second kept
    // unless it is worse by [`shortfall`] (for a machine that reverses, where it leaves the
    // field and the first did not).
    let mut c = connection_minding(from, to, line, v, area, None)?;
    let between = from.is_some() && to.is_some();
    if let (true, Some((standing, step))) = (between, crop) {
        if standing.crossed(&c.pieces, step) {
            c.crosses_crop = true;
            if let Some(mut minding) = connection_minding(from, to, line, v, area, crop) {
                minding.crosses_crop = standing.crossed(&minding.pieces, step);
                let worse = |s: &PathSegment| shortfall(v, s.leaves_field, s.crosses_crop);
                if worse(&minding) <= worse(&c) {
                    c = minding;
                }
            }
        }
    }
    Some(c)
}

/// How far a connection or join falls short, to compare two: leaving the field is worse than
/// crossing crop worked later for a machine that reverses, and better for one that drives
/// forward only (as their turns, [`Vehicle::turn_clear`]).
fn shortfall(v: &Vehicle, leaves: bool, crosses: bool) -> (bool, bool) {
    if v.reverse {
        (leaves, crosses)
    } else {
        (crosses, leaves)
    }
}

/// [`connection`], minding `crop` throughout where it is given.
fn connection_minding(
    from: Option<Pose>,
    to: Option<Pose>,
    line: Option<&LineString>,
    v: &Vehicle,
    area: Option<&Area>,
    crop: Option<(&StandingCrop, usize)>,
) -> Option<PathSegment> {
    let clear = |s: &[Segment]| crop.is_none_or(|(c, step)| !c.crossed(s, step));
    // A join between two poses: the cheapest turn that stays in the field and off the crop
    // where one does (noted where none stays in the field).
    let leaves = std::cell::Cell::new(false);
    let join = |a: Pose, b: Pose| match area {
        Some(ar) => {
            let (t, _) = v.turn_clear(a, b, ar, &clear);
            leaves.set(leaves.get() || !t.inside);
            t
        }
        None => v.shortest(a, b),
    };
    // What a join costs when choosing where to join: the worse of leaving the field and
    // crossing crop ([`shortfall`]) costs more than any detour along the line, the other more
    // than any but a long one.
    let join_cost = |(t, kept_off): (turn::Turn, bool)| {
        let out = !t.inside && area.is_some();
        let through = !kept_off && crop.is_some();
        let (worse, other) = shortfall(v, out, through);
        let cost = |short: bool, metres: f64| if short { metres } else { 0.0 };
        t.cost() + cost(worse, WORSE_SHORTFALL_M) + cost(other, LESSER_SHORTFALL_M)
    };
    // The same, where only a cost below `limit` matters (any answer at or above it will do):
    // a join whose cheapest form costs more is not checked against the field.
    let join_cost_below = |a: Pose, b: Pose, limit: f64| match area {
        Some(ar) => v
            .turn_clear_below(a, b, ar, &clear, limit)
            .map_or(f64::INFINITY, join_cost),
        None => v.shortest(a, b).cost(),
    };
    let pts: Vec<Coord> = line.map(|l| l.0.clone()).unwrap_or_default();
    let length = polyline_length(&pts);
    // Along the line, joined at either end.
    let along_line = || -> Option<Vec<Segment>> {
        // Where to leave the line's start and end: the join that costs least over what it
        // saves of the line.
        let half = length / 2.0;
        let start_at = from.map_or(0.0, |a| {
            best_join(&pts, half, v, |p, limit| join_cost_below(a, p, limit), true)
        });
        let end_at = to.map_or(0.0, |b| {
            best_join(
                &pts,
                half,
                v,
                |p, limit| join_cost_below(p, b, limit),
                false,
            )
        });
        let middle = cut_polyline(&pts, start_at, length - end_at);
        let mut along = follow(&middle, v);
        // The joins are checked as they are chosen; the line followed between them here.
        leaves.set(area.is_some_and(|a| !along.is_empty() && !a.contains(&along)));
        if along.is_empty() {
            let (Some(a), Some(b)) = (from, to) else {
                return None;
            };
            along = join(a, b).segments;
        } else {
            if let (Some(a), Some(m0)) = (from, along.first().map(|s| s.start)) {
                let mut pieces = join(a, m0).segments;
                pieces.append(&mut along);
                along = pieces;
            }
            if let (Some(b), Some(m1)) = (to, curve::end(&along)) {
                along.extend(join(m1, b).segments);
            }
        }
        Some(along)
    };
    let direct = length < DIRECT_CONNECTION_RADII * v.turn_radius;
    let pieces = match (from, to) {
        (Some(a), Some(b)) if direct || pts.len() < 2 => {
            if a.distance(&b) < MIN_CONNECTOR_M && a.heading_change(&b).abs() < 1e-9 {
                return None;
            }
            let turn = join(a, b);
            let direct_leaves = leaves.get();
            let direct_left = shortfall(v, direct_leaves, !clear(&turn.segments));
            match (pts.len() >= 2 && direct_left != (false, false))
                .then(|| {
                    leaves.set(false);
                    along_line()
                })
                .flatten()
            {
                Some(along) if shortfall(v, leaves.get(), !clear(&along)) < direct_left => along,
                _ => {
                    leaves.set(direct_leaves);
                    turn.segments
                }
            }
        }
        _ => along_line()?,
    };
    let pieces: Vec<Segment> = pieces.into_iter().filter(|p| p.length > 1e-12).collect();
    if pieces.is_empty() {
        return None;
    }
    let mut segment = PathSegment::new(SegmentKind::Connection, pieces, None);
    // From the entrance and to the exit the machine drives where the user put them, often
    // outside: those are not checked.
    segment.leaves_field = from.is_some() && to.is_some() && leaves.get();
    Some(segment)
}

/// What the worse of leaving the field and crossing crop still to be worked ([`shortfall`])
/// adds to a join's cost when choosing where along a connection's line to join it (metres):
/// more than any detour.
const WORSE_SHORTFALL_M: f64 = 1e6;

/// What the lesser of the two adds: more than the detours along a headland take.
const LESSER_SHORTFALL_M: f64 = 1e4;

/// Distances along a connection's line (in turning radii) at which a join from the pose before
/// (or to the pose after) is tried.
const JOIN_RADII: [f64; 6] = [0.5, 1.0, 1.5, 2.0, 3.0, 4.0];

/// The distance from the line's start (`at_start`) or end at which joining it costs least:
/// the join's length less the stretch of line it replaces, over [`JOIN_RADII`] up to `most`.
/// `join(pose, limit)` is the cost of the join at `pose`, exact where it is below `limit`.
fn best_join(
    pts: &[Coord],
    most: f64,
    v: &Vehicle,
    join: impl Fn(Pose, f64) -> f64,
    at_start: bool,
) -> f64 {
    let length = polyline_length(pts);
    let mut best = (f64::INFINITY, 0.0);
    for k in JOIN_RADII {
        let d = (k * v.turn_radius).min(most);
        let Some(p) = polyline_pose(pts, if at_start { d } else { length - d }) else {
            continue;
        };
        // Only a cost below the best so far (by the margin below) is taken.
        let cost = join(p, best.0 - 1e-9 + d) - d;
        if cost < best.0 - 1e-9 {
            best = (cost, d);
        }
    }
    best.1
}

/// Length of a polyline, metres.
fn polyline_length(pts: &[Coord]) -> f64 {
    pts.windows(2)
        .map(|w| (w[1].x - w[0].x).planar_hypot(w[1].y - w[0].y))
        .sum()
}

/// The pose `d` metres along a polyline, facing along its edge there.
fn polyline_pose(pts: &[Coord], d: f64) -> Option<Pose> {
    let mut s = 0.0;
    let mut last = None;
    for w in pts.windows(2) {
        let e = w[1] - w[0];
        let l = e.x.planar_hypot(e.y);
        if l < 1e-9 {
            continue;
        }
        let heading = e.y.atan2(e.x);
        if s + l >= d {
            let t = ((d - s) / l).clamp(0.0, 1.0);
            return Some(Pose::new(w[0].x + e.x * t, w[0].y + e.y * t, heading));
        }
        s += l;
        last = Some(Pose::new(w[1].x, w[1].y, heading));
    }
    last
}

/// The part of a polyline from `a` to `b` metres along it.
fn cut_polyline(pts: &[Coord], a: f64, b: f64) -> Vec<Coord> {
    let mut out = Vec::new();
    if b <= a {
        return out;
    }
    let mut s = 0.0;
    for w in pts.windows(2) {
        let e = w[1] - w[0];
        let l = e.x.planar_hypot(e.y);
        let (s0, s1) = (s, s + l);
        s = s1;
        if l < 1e-12 || s1 < a || s0 > b {
            continue;
        }
        let at = |x: f64| w[0] + e * ((x - s0) / l).clamp(0.0, 1.0);
        if out.is_empty() {
            out.push(at(a.max(s0)));
        }
        out.push(at(b.min(s1)));
    }
    out
}

/// A closed ring re-started at a point on it (or at its first vertex without one).
fn ring_starting_at(ring: &LineString, at: Option<Coord>) -> LineString {
    let pts = &ring.0;
    let Some(p) = at else {
        return ring.clone();
    };
    if pts.len() < 2 {
        return ring.clone();
    }
    // The edge the point lies on: the one it is nearest to.
    let mut best = (f64::INFINITY, 0);
    for (i, w) in pts.windows(2).enumerate() {
        let d = point_segment_distance(p, w[0], w[1]);
        if d < best.0 {
            best = (d, i);
        }
    }
    let i = best.1;
    let mut out = Vec::with_capacity(pts.len() + 2);
    out.push(p);
    // From the end of edge i round to its start (the ring's last point repeats its first).
    out.extend_from_slice(&pts[i + 1..]);
    out.extend_from_slice(&pts[1..=i]);
    out.push(p);
    out.dedup_by(|a, b| (a.x - b.x).planar_hypot(a.y - b.y) < MIN_CONNECTOR_M);
    LineString::new(out)
}

impl Path {
    /// Total length of the segments of a kind, metres.
    pub fn length_of(&self, kind: SegmentKind) -> f64 {
        self.segments
            .iter()
            .filter(|s| s.kind == kind)
            .map(PathSegment::length)
            .sum()
    }

    /// Number of segments of a kind.
    pub fn count_of(&self, kind: SegmentKind) -> usize {
        self.segments.iter().filter(|s| s.kind == kind).count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::coord;

    #[test]
    fn a_turn_between_swaths_keeps_off_the_crop_where_a_form_does() {
        use crate::route::RouteStep;
        use crate::swath::generate;
        use geo::{polygon, MultiPolygon};
        use std::f64::consts::{FRAC_PI_2, PI};
        let v = Vehicle {
            turn_radius: 5.0,
            ..Vehicle::default()
        };
        let field =
            polygon![(x: -50., y: -50.), (x: 50., y: -50.), (x: 50., y: 50.), (x: -50., y: 50.)];
        let area = Area::new(&field, &[]);
        // A swath 2 m wide along y = 10 from x = 1 to 9, worked at the route's first step: its
        // crop is the line from (2, 10) to (8, 10).
        let strip = polygon![(x: 1., y: 9.), (x: 9., y: 9.), (x: 9., y: 11.), (x: 1., y: 11.)];
        let swaths = generate(&MultiPolygon::new(vec![strip]), FRAC_PI_2, 2.0, 2.0).unwrap();
        assert_eq!(swaths.swaths.len(), 1);
        let route = Route {
            steps: vec![RouteStep::Swath {
                swath: 0,
                reversed: false,
                block: 0,
            }],
            ..Route::default()
        };
        let crop = StandingCrop::of_route(&route, &swaths);
        // A U-turn to the left, 20 m across: the cheapest (LSL) runs north along x = 5, over
        // the crop.
        let (from, to) = (Pose::new(0.0, 0.0, 0.0), Pose::new(0.0, 20.0, PI));
        let cheapest = swath_turn(from, to, &v, Some(&area), None).unwrap().0;
        assert!(crop.crossed(&cheapest.pieces, 0));
        // Before the swath is worked the turn goes round the other way, still in the field; after
        // it, the cheapest again.
        let minded = swath_turn(from, to, &v, Some(&area), Some((&crop, 0)))
            .unwrap()
            .0;
        assert!(minded.turn.as_ref().is_some_and(|t| t.inside));
        assert!(!crop.crossed(&minded.pieces, 0));
        assert!(minded.length() > cheapest.length());
        // The pieces over the crop: the LSL's straight (the arcs at its ends do not reach it).
        let over = crop.crossed_length(&cheapest.pieces, 0);
        let straight: f64 = cheapest
            .pieces
            .iter()
            .filter(|p| p.curvature == 0.0)
            .map(|p| p.length)
            .sum();
        assert!(
            over > 0.0 && (over - straight).abs() < 1e-9,
            "{over} of {straight}"
        );
        assert_eq!(crop.crossed_length(&minded.pieces, 0), 0.0);
        let after = swath_turn(from, to, &v, Some(&area), Some((&crop, 1)))
            .unwrap()
            .0;
        assert_eq!(after.pieces, cheapest.pieces);
    }

    #[test]
    fn ring_restarts_at_a_point_on_an_edge() {
        let ring = LineString::from(vec![(0., 0.), (10., 0.), (10., 10.), (0., 10.), (0., 0.)]);
        let r = ring_starting_at(&ring, Some(coord! { x: 10.0, y: 4.0 }));
        assert_eq!(r.0.first(), Some(&coord! { x: 10.0, y: 4.0 }));
        assert_eq!(r.0.last(), Some(&coord! { x: 10.0, y: 4.0 }));
        assert!((Euclidean.length(&r) - 40.0).abs() < 1e-9);
        assert_eq!(r.0.len(), 6);
    }

    #[test]
    fn ring_restarts_at_a_vertex() {
        let ring = LineString::from(vec![(0., 0.), (10., 0.), (10., 10.), (0., 10.), (0., 0.)]);
        let r = ring_starting_at(&ring, Some(coord! { x: 10.0, y: 10.0 }));
        assert_eq!(r.0.len(), 5);
        assert!((Euclidean.length(&r) - 40.0).abs() < 1e-9);
    }

    #[test]
    fn segments_are_continuous() {
        use crate::decompose::cluster_swaths;
        use crate::headland::HeadlandPass;
        use crate::route::{plan_route, RouteSettings};
        use crate::swath::generate;
        use geo::{polygon, MultiPolygon};
        let inner = polygon![(x: 6., y: 6.), (x: 94., y: 6.), (x: 94., y: 94.), (x: 6., y: 94.)];
        let passes = vec![HeadlandPass {
            index: 1,
            line: LineString::from(vec![(3., 3.), (97., 3.), (97., 97.), (3., 97.), (3., 3.)]),
            closed: true,
            around: crate::headland::PassAround::Field,
        }];
        let swaths = generate(&MultiPolygon::new(vec![inner]), 0.4, 6.0, 6.0).unwrap();
        let route = plan_route(
            &swaths,
            &cluster_swaths(&swaths),
            &passes,
            &RouteSettings::default(),
        );
        let path = build_path(&route, &swaths, &passes, &Vehicle::default(), None, None);
        for w in path.segments.windows(2) {
            let a = *w[0].line.0.last().unwrap();
            let b = w[1].line.0[0];
            assert!((a.x - b.x).planar_hypot(a.y - b.y) < 1e-9);
        }
        // The pass is driven in one go: entered near a corner too tight to round from there,
        // it starts with a manoeuvre (a turn) and goes on round.
        let pass_steps: Vec<_> = path
            .segments
            .iter()
            .filter(|s| s.kind == SegmentKind::HeadlandPass)
            .map(|s| s.step)
            .collect();
        assert!(!pass_steps.is_empty() && pass_steps.iter().all(|&s| s == pass_steps[0]));
        assert_eq!(path.count_of(SegmentKind::Connection), 1);
    }
}
