//! Shortest paths along the tracks: from where the machine is, facing where it faces, to a
//! target on the boundary lane (or the nearest of several), using only tracks already driven
//! (Plessen & Bemporad, 2016).
//!
//! The search runs over *directed states*: a node of a track together with the way the machine
//! travels along that track. Which ways on through a junction a state may take depends on how the
//! machine may turn ([`Turning`]) and only on the way it came in, so Dijkstra's method over these
//! states is exact, with no restarts: the constraint of the paper's section III (only three-node
//! transitions that exist as traces) is a constraint between a state and its successors. The
//! paper's Algorithm 1 searches nodes with one parent each and restarts where that deadlocks;
//! over directed states nothing deadlocks. The search is A* with the straight-line distance to
//! the nearest target, which never overestimates a way along tracks, so it prunes and stays exact.
//!
//! ```
//! use furrow::tracks::{shortest_path, Track, TrackGraph, TrackKind, TrackQuery, Turning};
//! use geo::coord;
//!
//! // A square loop (the boundary lane) and a lane up its middle.
//! let square = vec![
//!     coord! { x: 0.0, y: 0.0 }, coord! { x: 100.0, y: 0.0 }, coord! { x: 100.0, y: 100.0 },
//!     coord! { x: 0.0, y: 100.0 }, coord! { x: 0.0, y: 0.0 },
//! ];
//! let lane = vec![coord! { x: 50.0, y: 0.0 }, coord! { x: 50.0, y: 100.0 }];
//! let graph = TrackGraph::new(vec![
//!     Track::new(TrackKind::HeadlandPass, square, true).ok_or("no track")?,
//!     Track::new(TrackKind::Swath, lane, false).ok_or("no track")?,
//! ]);
//! // On the lane at y = 30, facing north; the exit at (0, 50). Turning at the lane's end without
//! // turning on the spot: up 70, west 50, down 50.
//! let query = TrackQuery {
//!     from: coord! { x: 50.0, y: 30.0 },
//!     heading: std::f64::consts::FRAC_PI_2,
//!     targets: vec![coord! { x: 0.0, y: 50.0 }],
//!     turning: Turning::Heading,
//!     ..TrackQuery::default()
//! };
//! let path = shortest_path(&graph, &query)?;
//! assert!((path.length - 170.0).abs() < 1e-9);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use super::graph::{Track, TrackGraph};
use crate::error::{ErrorCode, PlanError};
use crate::geometry::PlanarHypot;
use crate::sort::SharedSort;
use geo::Coord;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// How the machine may change its way at a junction. The default is [`Turning::Heading`]: with
/// the strict [`Turning::Tracks`] most ways out of a coverage plan do not exist (its turns are
/// U-turns in the headland, not junctions at the same heading).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Turning {
    /// It may turn on the spot (orchard-like areas, the paper's section II-A): any way at any
    /// junction, and either way at the start.
    OnTheSpot,
    /// No turning on the spot (II-B): the first move follows the heading, and at a junction any
    /// way on that turns by less than [`MAX_JUNCTION_TURN`].
    #[default]
    Heading,
    /// Only tracks already driven, as they were driven (III, the repressed-area constraint): at a
    /// junction only the ways on at the heading it came in with, within [`SMOOTH_TURN`].
    Tracks,
}

impl Turning {
    /// The name in the API: `on-the-spot`, `heading`, `tracks`.
    pub fn as_str(self) -> &'static str {
        match self {
            Turning::OnTheSpot => "on-the-spot",
            Turning::Heading => "heading",
            Turning::Tracks => "tracks",
        }
    }

    /// The turning of a name of [`Turning::as_str`].
    pub fn parse(name: &str) -> Option<Turning> {
        match name {
            "on-the-spot" => Some(Turning::OnTheSpot),
            "heading" => Some(Turning::Heading),
            "tracks" => Some(Turning::Tracks),
            _ => None,
        }
    }
}

/// The largest change of heading at a junction without turning on the spot, radians (135°: a
/// machine can take a side track, not go back the way it came).
pub const MAX_JUNCTION_TURN: f64 = 3.0 * std::f64::consts::FRAC_PI_4;
/// The largest change of heading at a junction of tracks as driven, radians (10°): tracks that
/// meet as smoothed curves meet at the same heading; the rest is where a connection leaves a
/// pass it ran along (see [`super::graph`]).
pub const SMOOTH_TURN: f64 = 10.0 * std::f64::consts::PI / 180.0;
/// How far (metres) the start may be from the nearest track.
pub const MAX_START_OFFSET_M: f64 = 25.0;

/// A shortest-path question.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackQuery {
    /// Where the machine is (local metres); it is placed on the nearest track.
    pub from: Coord,
    /// Where it faces, radians counter-clockwise from east (local metres' x axis).
    pub heading: f64,
    /// The exits (local metres), each placed on the nearest point of the boundary lane (or of
    /// any track when the plan has none); the path goes to the nearest.
    pub targets: Vec<Coord>,
    /// How it may turn.
    pub turning: Turning,
    /// With [`Turning::OnTheSpot`]: keep the search inside the band across the swaths that the
    /// paper's Proposition 1 proves the shortest path stays in on an orchard grid (straight
    /// parallel lanes whose ends the boundary lane links). Exact there; elsewhere it may miss a
    /// shorter way round an obstacle, so it is off by default.
    pub monotone_band: bool,
}

impl Default for TrackQuery {
    fn default() -> Self {
        TrackQuery {
            from: Coord { x: 0.0, y: 0.0 },
            heading: 0.0,
            targets: Vec::new(),
            turning: Turning::default(),
            monotone_band: false,
        }
    }
}

/// One stretch of a path: along one track from one distance to another.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stretch {
    /// The track.
    pub track: usize,
    /// Distance along it where the stretch starts, metres.
    pub from: f64,
    /// Where it ends: less than `from` when driven against the track; on a closed track it may
    /// pass the track's length or zero (`to - from` is the way travelled).
    pub to: f64,
}

/// A shortest path along the tracks.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackPath {
    /// Its length, metres.
    pub length: f64,
    /// The stretches driven, in order.
    pub stretches: Vec<Stretch>,
    /// Its points (local metres), from the start on the tracks to the target.
    pub points: Vec<Coord>,
    /// Which of the query's targets it reaches.
    pub target: usize,
    /// Where the start was placed on the tracks, and how far the machine is from it (metres).
    pub start: Coord,
    /// How far the machine is from the tracks, metres.
    pub start_offset: f64,
    /// Turns on the spot (only with [`Turning::OnTheSpot`]): at the start and at junctions.
    pub turns_on_the_spot: usize,
    /// States the search expanded (a measure of its work).
    pub expanded: usize,
}

/// A state: at node `node`, travelling along its track forwards (`dir` 0) or backwards (1).
type State = (usize, usize);

/// A place the search starts from or aims at, on a track: (track, distance along it).
#[derive(Debug, Clone, Copy)]
struct Place {
    track: usize,
    at: f64,
}

/// The shortest path for `query` over `graph`.
///
/// Errors: `invalid_option` without targets or with a number that is not finite; `off_tracks`
/// when the start is more than [`MAX_START_OFFSET_M`] from any track; `no_path` when no way
/// along the tracks reaches a target with the turning allowed.
pub fn shortest_path(graph: &TrackGraph, query: &TrackQuery) -> Result<TrackPath, PlanError> {
    Search::new(graph, query)?.run(true)
}

/// The same answer by an exhaustive search over the same states (Dijkstra without the
/// straight-line bound, every state settled): for tests and comparisons.
pub fn shortest_path_exhaustive(
    graph: &TrackGraph,
    query: &TrackQuery,
) -> Result<TrackPath, PlanError> {
    Search::new(graph, query)?.run(false)
}

/// Whether a machine arriving at a junction heading `a` (unit) may leave heading `b` (unit).
pub fn may_turn(turning: Turning, a: Coord, b: Coord) -> bool {
    let cos = (a.x * b.x + a.y * b.y).clamp(-1.0, 1.0);
    match turning {
        Turning::OnTheSpot => true,
        Turning::Heading => cos >= MAX_JUNCTION_TURN.cos() - 1e-12,
        Turning::Tracks => cos >= SMOOTH_TURN.cos() - 1e-12,
    }
}

struct Search<'a> {
    graph: &'a TrackGraph,
    query: &'a TrackQuery,
    start: Place,
    start_offset: f64,
    targets: Vec<Place>,
    /// Where the targets are (local metres), for the straight-line bound.
    target_points: Vec<Coord>,
    band: Option<(Coord, f64, f64)>,
}

/// An entry of the open list: ordered by the smallest estimate first.
#[derive(Debug, Clone, Copy)]
struct Open {
    estimate: f64,
    cost: f64,
    state: State,
}

impl PartialEq for Open {
    fn eq(&self, other: &Self) -> bool {
        self.estimate == other.estimate
    }
}
impl Eq for Open {}
impl PartialOrd for Open {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Open {
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .estimate
            .total_cmp(&self.estimate)
            .then_with(|| other.cost.total_cmp(&self.cost))
    }
}

/// How a state was reached: from another state (or the start, `None`), along a track from one
/// distance to another, with a turn on the spot before it or not.
#[derive(Debug, Clone, Copy)]
struct Came {
    from: Option<State>,
    stretch: Stretch,
    turned: bool,
}

impl<'a> Search<'a> {
    fn new(graph: &'a TrackGraph, query: &'a TrackQuery) -> Result<Search<'a>, PlanError> {
        let invalid = |m: String| PlanError::new(ErrorCode::InvalidOption, m);
        if query.targets.is_empty() {
            return Err(invalid("a shortest path needs at least one target".into()));
        }
        let finite = |c: &Coord| c.x.is_finite() && c.y.is_finite();
        if !finite(&query.from) || !query.heading.is_finite() || !query.targets.iter().all(finite) {
            return Err(invalid(
                "the start, heading and targets must be finite numbers".into(),
            ));
        }
        let (track, at, offset) = graph
            .nearest(query.from, |_| true)
            .ok_or_else(|| PlanError::new(ErrorCode::NoPath, "the plan has no tracks"))?;
        if offset > MAX_START_OFFSET_M {
            return Err(PlanError::new(ErrorCode::OffTracks, format!(
                "the start is {offset:.1} m from the nearest track (at most {MAX_START_OFFSET_M} m): the machine must be on the tracks"
            )));
        }
        let has_boundary = graph.tracks().iter().any(|t| t.boundary);
        let targets = query
            .targets
            .iter()
            .map(|&p| {
                graph
                    .nearest(p, |t: &Track| t.boundary || !has_boundary)
                    .map(|(track, at, _)| Place { track, at })
                    .ok_or_else(|| PlanError::new(ErrorCode::NoPath, "the plan has no tracks"))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let target_points = targets
            .iter()
            .map(|t| graph.tracks()[t.track].point_at(t.at))
            .collect();
        let mut search = Search {
            graph,
            query,
            start: Place { track, at },
            start_offset: offset,
            targets,
            target_points,
            band: None,
        };
        if query.monotone_band && query.turning == Turning::OnTheSpot {
            search.band = search.monotone_band();
        }
        Ok(search)
    }

    /// The paper's band (Proposition 1): across the swaths' direction, from one lane end beyond
    /// the start and target on one side to one beyond on the other. `None` when the swaths are
    /// not parallel (no orchard grid).
    fn monotone_band(&self) -> Option<(Coord, f64, f64)> {
        let tracks = self.graph.tracks();
        let swaths: Vec<&Track> = tracks
            .iter()
            .filter(|t| t.kind == super::graph::TrackKind::Swath)
            .collect();
        let first = swaths.first()?;
        let d = first.heading_at(0.0, true, true);
        let across = Coord { x: -d.y, y: d.x };
        for t in &swaths {
            let h = t.heading_at(0.0, true, true);
            if (h.x * d.y - h.y * d.x).abs() > 1e-3 {
                return None;
            }
        }
        let x = |p: Coord| p.x * across.x + p.y * across.y;
        let mut ends: Vec<f64> = swaths
            .iter()
            .flat_map(|t| [x(t.points[0]), x(t.points[t.points.len() - 1])])
            .collect();
        ends.shared_sort_by(f64::total_cmp);
        ends.dedup_by(|a, b| (*a - *b).abs() < 1e-6);
        let all: Vec<f64> = self
            .graph
            .junctions()
            .iter()
            .map(|j| x(j.point))
            .chain(ends.iter().copied())
            .collect();
        let (xmin, xmax) = all
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
        let step = ends
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold(f64::INFINITY, f64::min);
        let step = if step.is_finite() { step } else { 0.0 };
        let xs = x(self.graph.tracks()[self.start.track].point_at(self.start.at));
        let (mut lo, mut hi) = (xs, xs);
        for &t in &self.target_points {
            let xt = x(t);
            lo = lo.min(xt);
            hi = hi.max(xt);
        }
        let last_max = ends
            .iter()
            .copied()
            .filter(|&e| e < hi)
            .fold(f64::NEG_INFINITY, f64::max);
        let last_min = ends
            .iter()
            .copied()
            .filter(|&e| e > lo)
            .fold(f64::INFINITY, f64::min);
        let fmin = (last_min - step).max(xmin).min(lo);
        let fmax = (last_max + step).min(xmax).max(hi);
        Some((across, fmin - 1e-6, fmax + 1e-6))
    }

    fn in_band(&self, p: Coord) -> bool {
        match self.band {
            None => true,
            Some((across, lo, hi)) => {
                let x = p.x * across.x + p.y * across.y;
                x >= lo && x <= hi
            }
        }
    }

    /// Straight-line distance from `p` to the nearest target: never more than any way along
    /// the tracks.
    fn bound(&self, p: Coord) -> f64 {
        self.target_points
            .iter()
            .map(|q| (p.x - q.x).planar_hypot(p.y - q.y))
            .fold(f64::INFINITY, f64::min)
    }

    /// The next node from distance `at` on track `t` in direction `dir`, and the distance to it
    /// (round a closed track); `None` at the end of an open one.
    fn next_node(&self, t: usize, at: f64, dir: usize, exclusive: bool) -> Option<(usize, f64)> {
        let g = self.graph;
        let track = &g.tracks()[t];
        let list = g.nodes_on(t);
        if list.is_empty() {
            return None;
        }
        let len = track.length();
        let eps = if exclusive { 1e-9 } else { -1e-9 };
        if dir == 0 {
            let i = list.partition_point(|&n| g.nodes()[n].at <= at + eps);
            if i < list.len() {
                let n = list[i];
                return Some((n, g.nodes()[n].at - at));
            }
            if track.closed {
                let n = list[0];
                return Some((n, len - at + g.nodes()[n].at));
            }
            None
        } else {
            let i = list.partition_point(|&n| g.nodes()[n].at < at - eps);
            if i > 0 {
                let n = list[i - 1];
                return Some((n, at - g.nodes()[n].at));
            }
            if track.closed {
                let n = list[list.len() - 1];
                return Some((n, at + len - g.nodes()[n].at));
            }
            None
        }
    }

    /// The distance from `at` to a target on the same track in direction `dir` before `limit`
    /// (metres of travel), and which target.
    fn target_ahead(&self, t: usize, at: f64, dir: usize, limit: f64) -> Option<(f64, usize)> {
        let track = &self.graph.tracks()[t];
        let len = track.length();
        let mut best: Option<(f64, usize)> = None;
        for (k, p) in self.targets.iter().enumerate() {
            if p.track != t {
                continue;
            }
            let mut d = if dir == 0 { p.at - at } else { at - p.at };
            if d < -1e-9 && track.closed {
                d += len;
            }
            if d >= -1e-9 && d <= limit + 1e-9 && best.is_none_or(|b| d < b.0) {
                best = Some((d.max(0.0), k));
            }
        }
        best
    }

    fn heading(&self, t: usize, at: f64, dir: usize, leaving: bool) -> Coord {
        self.graph.tracks()[t].heading_at(at, dir == 0, leaving)
    }

    fn run(&self, bounded: bool) -> Result<TrackPath, PlanError> {
        let g = self.graph;
        let n_states = g.nodes().len() * 2;
        let mut cost = vec![f64::INFINITY; n_states];
        let mut came: Vec<Option<Came>> = vec![None; n_states];
        let mut open = BinaryHeap::new();
        let idx = |s: State| s.0 * 2 + s.1;
        // The best way to a target found so far: (length, target, last state, stretch to it).
        let mut best: Option<(f64, usize, Option<State>, Stretch, bool)> = None;
        let face = Coord {
            x: self.query.heading.cos(),
            y: self.query.heading.sin(),
        };
        let start = self.start;
        for dir in 0..2 {
            let h = self.heading(start.track, start.at, dir, true);
            let along = h.x * face.x + h.y * face.y;
            // Without turning on the spot, the first move follows the heading (the way along the
            // track closer to it).
            let turned = along < 0.0;
            if turned && self.query.turning != Turning::OnTheSpot {
                continue;
            }
            let next = self.next_node(start.track, start.at, dir, false);
            let limit = next.map_or(f64::INFINITY, |n| n.1);
            if let Some((d, k)) = self.target_ahead(start.track, start.at, dir, limit) {
                let stretch = stretch(start.track, start.at, d, dir);
                if best.is_none_or(|b| d < b.0) {
                    best = Some((d, k, None, stretch, turned));
                }
            }
            if let Some((n, d)) = next {
                let s = (n, dir);
                if d < cost[idx(s)] {
                    cost[idx(s)] = d;
                    came[idx(s)] = Some(Came {
                        from: None,
                        stretch: stretch(start.track, start.at, d, dir),
                        turned,
                    });
                    let estimate = d + if bounded {
                        self.bound(g.nodes()[n].point)
                    } else {
                        0.0
                    };
                    open.push(Open {
                        estimate,
                        cost: d,
                        state: s,
                    });
                }
            }
        }
        let mut expanded = 0;
        let mut done = vec![false; n_states];
        while let Some(Open {
            estimate,
            cost: c,
            state,
        }) = open.pop()
        {
            if done[idx(state)] || c > cost[idx(state)] {
                continue;
            }
            if best.is_some_and(|b| estimate >= b.0) && bounded {
                break;
            }
            done[idx(state)] = true;
            expanded += 1;
            let (node, dir) = state;
            let here = g.nodes()[node];
            let arrive = self.heading(here.track, here.at, dir, false);
            let junction = &g.junctions()[here.junction];
            if !self.in_band(here.point) {
                continue;
            }
            for &m in &junction.nodes {
                let there = g.nodes()[m];
                // The nodes of a junction lie a few centimetres apart at most: the step from one
                // to the other is driven too.
                let gap = (here.point.x - there.point.x).planar_hypot(here.point.y - there.point.y);
                for e in 0..2 {
                    let leave = self.heading(there.track, there.at, e, true);
                    let straight_on = m == node && e == dir;
                    if !straight_on && !may_turn(self.query.turning, arrive, leave) {
                        continue;
                    }
                    let turned = self.query.turning == Turning::OnTheSpot
                        && arrive.x * leave.x + arrive.y * leave.y < 0.0;
                    let next = self.next_node(there.track, there.at, e, true);
                    let limit = next.map_or(f64::INFINITY, |n| n.1);
                    if let Some((d, k)) = self.target_ahead(there.track, there.at, e, limit) {
                        let total = c + gap + d;
                        if best.is_none_or(|b| total < b.0) {
                            best = Some((
                                total,
                                k,
                                Some(state),
                                stretch(there.track, there.at, d, e),
                                turned,
                            ));
                        }
                    }
                    let Some((n, d)) = next else { continue };
                    let s = (n, e);
                    let total = c + gap + d;
                    if !done[idx(s)] && total < cost[idx(s)] - 1e-12 {
                        cost[idx(s)] = total;
                        came[idx(s)] = Some(Came {
                            from: Some(state),
                            stretch: stretch(there.track, there.at, d, e),
                            turned,
                        });
                        open.push(Open {
                            estimate: total
                                + if bounded {
                                    self.bound(g.nodes()[n].point)
                                } else {
                                    0.0
                                },
                            cost: total,
                            state: s,
                        });
                    }
                }
            }
        }
        let Some((length, target, last, final_stretch, final_turned)) = best else {
            return Err(PlanError::new(
                ErrorCode::NoPath,
                "no way along the tracks reaches the target from here with this turning",
            ));
        };
        // Back along the states to the start.
        let mut stretches = vec![final_stretch];
        let mut turns = usize::from(final_turned);
        let mut at = last;
        while let Some(s) = at {
            let Some(c) = came[idx(s)] else { break };
            stretches.push(c.stretch);
            turns += usize::from(c.turned);
            at = c.from;
        }
        stretches.reverse();
        let points = path_points(g.tracks(), &stretches);
        Ok(TrackPath {
            length,
            stretches,
            points,
            target,
            start: g.tracks()[start.track].point_at(start.at),
            start_offset: self.start_offset,
            turns_on_the_spot: turns,
            expanded,
        })
    }
}

/// The stretch of `d` metres from `at` on track `t` in direction `dir`. On a closed track `to`
/// may pass its length (or zero): `to - from` is the way travelled.
fn stretch(t: usize, at: f64, d: f64, dir: usize) -> Stretch {
    Stretch {
        track: t,
        from: at,
        to: if dir == 0 { at + d } else { at - d },
    }
}

/// The points of the stretches, one after another.
fn path_points(tracks: &[Track], stretches: &[Stretch]) -> Vec<Coord> {
    let mut out: Vec<Coord> = Vec::new();
    for s in stretches {
        let t = &tracks[s.track];
        let len = t.length();
        let at = |v: f64| {
            if t.closed {
                t.point_at(v.rem_euclid(len))
            } else {
                t.point_at(v)
            }
        };
        let mut push = |p: Coord| {
            if out
                .last()
                .is_none_or(|q| (q.x - p.x).planar_hypot(q.y - p.y) > 1e-9)
            {
                out.push(p);
            }
        };
        push(at(s.from));
        // The track's own points between.
        let (lo, hi) = (s.from.min(s.to), s.from.max(s.to));
        let mut inner: Vec<f64> = Vec::new();
        let laps: &[f64] = if t.closed { &[-len, 0.0, len] } else { &[0.0] };
        for &a in &t.at {
            for lap in laps {
                let v = a + lap;
                if v > lo + 1e-9 && v < hi - 1e-9 {
                    inner.push(v);
                }
            }
        }
        inner.shared_sort_by(f64::total_cmp);
        inner.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
        if s.to < s.from {
            inner.reverse();
        }
        for v in inner {
            push(at(v));
        }
        push(at(s.to));
    }
    if out.len() == 1 {
        out.push(out[0]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tracks::graph::TrackKind;
    use geo::coord;
    use std::f64::consts::{FRAC_PI_2, PI};

    /// An orchard-like grid: a loop round 100 × 60 m (counter-clockwise, the boundary lane) and
    /// lanes north-south at x = 10, 20, ..., 90 meeting it at both ends; with `arcs`, at the top
    /// of each lane a quarter circle of radius 5 m from the lane (heading north) onto the loop
    /// (heading east): the smoothed junctions of the paper's figure 2.
    fn grid(arcs: bool) -> TrackGraph {
        let c = |x: f64, y: f64| coord! { x: x, y: y };
        let mut tracks = vec![Track::new(
            TrackKind::HeadlandPass,
            vec![
                c(0.0, 0.0),
                c(100.0, 0.0),
                c(100.0, 60.0),
                c(0.0, 60.0),
                c(0.0, 0.0),
            ],
            true,
        )
        .expect("loop")];
        for k in 1..10 {
            let x = 10.0 * k as f64;
            tracks.push(
                Track::new(TrackKind::Swath, vec![c(x, 0.0), c(x, 60.0)], false).expect("lane"),
            );
            if arcs {
                let pts = (0..=64)
                    .map(|i| {
                        let a = PI - FRAC_PI_2 * i as f64 / 64.0;
                        c(x + 5.0 + 5.0 * a.cos(), 55.0 + 5.0 * a.sin())
                    })
                    .collect();
                tracks.push(Track::new(TrackKind::Turn, pts, false).expect("arc"));
            }
        }
        TrackGraph::new(tracks)
    }

    fn query(from: (f64, f64), heading: f64, to: (f64, f64), turning: Turning) -> TrackQuery {
        TrackQuery {
            from: coord! { x: from.0, y: from.1 },
            heading,
            targets: vec![coord! { x: to.0, y: to.1 }],
            turning,
            monotone_band: false,
        }
    }

    fn both(g: &TrackGraph, q: &TrackQuery) -> Result<f64, ErrorCode> {
        let a = shortest_path(g, q).map(|p| p.length).map_err(|e| e.code);
        let b = shortest_path_exhaustive(g, q)
            .map(|p| p.length)
            .map_err(|e| e.code);
        match (a, b) {
            (Ok(x), Ok(y)) => assert!((x - y).abs() < 1e-9, "{x} vs exhaustive {y}"),
            (x, y) => assert_eq!(x, y),
        }
        a
    }

    #[test]
    fn the_default_turning_is_no_turning_on_the_spot() {
        assert_eq!(Turning::default(), Turning::Heading);
        assert_eq!(TrackQuery::default().turning, Turning::Heading);
    }

    #[test]
    fn on_the_spot_takes_the_shorter_way_round() {
        let g = grid(false);
        // At (50, 40) facing south; the exit at (0, 30). Turning round: up 20, west 50, down 30.
        let q = query((50.0, 40.0), -FRAC_PI_2, (0.0, 30.0), Turning::OnTheSpot);
        let len = both(&g, &q).expect("a path");
        assert!((len - 100.0).abs() < 1e-9, "{len}");
        let p = shortest_path(&g, &q).expect("a path");
        assert_eq!(p.turns_on_the_spot, 1, "turned round at the start");
        assert_eq!(p.points.first().map(|p| (p.x, p.y)), Some((50.0, 40.0)));
        assert_eq!(p.points.last().map(|p| (p.x, p.y)), Some((0.0, 30.0)));
        // The paper's band (Proposition 1) finds the same with less work.
        let banded = shortest_path(
            &g,
            &TrackQuery {
                monotone_band: true,
                ..q.clone()
            },
        )
        .expect("a path");
        assert!((banded.length - 100.0).abs() < 1e-9);
        assert!(
            banded.expanded <= p.expanded,
            "{} vs {}",
            banded.expanded,
            p.expanded
        );
    }

    #[test]
    fn without_turning_on_the_spot_the_first_move_follows_the_heading() {
        let g = grid(false);
        // Facing south: down 40, west 50, up 30.
        let q = query((50.0, 40.0), -FRAC_PI_2, (0.0, 30.0), Turning::Heading);
        let len = both(&g, &q).expect("a path");
        assert!((len - 120.0).abs() < 1e-9, "{len}");
        // Facing north: up 20, west 50, down 30.
        let q = query((50.0, 40.0), FRAC_PI_2, (0.0, 30.0), Turning::Heading);
        assert!((both(&g, &q).expect("a path") - 100.0).abs() < 1e-9);
        // Facing a little east of north still means north along the lane.
        let q = query((50.0, 40.0), 1.2, (0.0, 30.0), Turning::Heading);
        assert!((both(&g, &q).expect("a path") - 100.0).abs() < 1e-9);
    }

    #[test]
    fn as_driven_only_the_smoothed_junctions_change_track() {
        let g = grid(true);
        let arc = g.tracks()[2].length();
        assert!((arc - 5.0 * FRAC_PI_2).abs() < 1e-3);
        // Facing north on lane x = 50: up to the arc at y = 55, onto the loop heading east, round
        // the far corner, along the bottom westwards and up the west side to the exit: the
        // lanes' ends meet the loop square on and cannot be turned into as driven.
        let q = query((50.0, 40.0), FRAC_PI_2, (0.0, 30.0), Turning::Tracks);
        let len = both(&g, &q).expect("a path");
        let want = 15.0 + arc + 45.0 + 60.0 + 100.0 + 30.0;
        assert!((len - want).abs() < 1e-6, "{len} vs {want}");
        // Facing south there is no smoothed way off the lane: no path.
        let q = query((50.0, 40.0), -FRAC_PI_2, (0.0, 30.0), Turning::Tracks);
        assert_eq!(both(&g, &q), Err(ErrorCode::NoPath));
        // The same without the repressed-area constraint: the square junction at the top.
        let q = query((50.0, 40.0), FRAC_PI_2, (0.0, 30.0), Turning::Heading);
        assert!((both(&g, &q).expect("a path") - 100.0).abs() < 1e-6);
        // On the loop heading west along the top, the arcs are met the wrong way round, except
        // as a reversal: from (95, 60) westwards to (0, 30) is 95 + 30.
        let q = query((95.0, 60.0), PI, (0.0, 30.0), Turning::Tracks);
        assert!((both(&g, &q).expect("a path") - 125.0).abs() < 1e-6);
    }

    #[test]
    fn several_exits_the_nearest_wins_and_the_start_is_placed_on_a_track() {
        let g = grid(false);
        let mut q = query((50.0, 40.0), FRAC_PI_2, (0.0, 30.0), Turning::Heading);
        q.targets.push(coord! { x: 100.0, y: 50.0 });
        // Up 20, east 50, down 10.
        let p = shortest_path(&g, &q).expect("a path");
        assert!((p.length - 80.0).abs() < 1e-9);
        assert_eq!(p.target, 1);
        // A start 2 m off the lane is placed on it.
        let q = query((52.0, 40.0), FRAC_PI_2, (0.0, 30.0), Turning::Heading);
        let p = shortest_path(&g, &q).expect("a path");
        assert!((p.start_offset - 2.0).abs() < 1e-9 && (p.start.x - 50.0).abs() < 1e-9);
    }

    #[test]
    fn turning_names_round_trip() {
        for t in [Turning::OnTheSpot, Turning::Heading, Turning::Tracks] {
            assert_eq!(Turning::parse(t.as_str()), Some(t));
        }
        assert_eq!(Turning::parse("sideways"), None);
    }
}
