//! The paper's own method for shortest paths under the repressed-area constraint, "LCAmod" with
//! restarts (Plessen & Bemporad, 2016, section III-B, Algorithm 1), over the same
//! [`TrackGraph`] as [`super::search`]: a baseline to compare the directed-state search with.
//!
//! The paper's nodes are places: here the graph's junctions. Its arcs `T_ij` are the ways along
//! one track from a node to the next node on that track, either way (round a closed track); two
//! junctions may be linked by several arcs (different tracks), so an arc is kept with its track
//! and direction, which does what the paper's auxiliary nodes do. A three-node transition (the
//! list `U`) is admissible when the way out continues the same track the same way, or when
//! [`may_turn`] allows the change of heading; stepping between two nodes of one junction costs
//! the few centimetres between them, as in [`super::search`].
//!
//! LCAmod is a label-correcting search with a first-in first-out candidate list and *one label
//! and one parent arc per junction*: taking junction `i` from the list, each arc `i -> j` that is
//! admissible after `i`'s parent arc and passes `d_i + T_ij < min(d_j, UPPER)` sets `d_j` and
//! `j`'s parent, and puts `j` on the list. Because a junction keeps one label whatever the way
//! it was reached, a shorter way in that cannot go on hides a longer one that could: the search
//! may *deadlock* (the list empties without reaching the target). Algorithm 1 then restarts:
//! with `i` the junction taken last from the list and `b` its parent, it solves `[s, c2, b]` and
//! `[b, i, e]` separately and joins them, again while deadlocked, and does all this once for
//! every neighbour `n` of the target with only the arc `n -> e` kept, taking the best.
//!
//! Where the paper leaves details open, or where following it literally would return a path the
//! machine cannot drive, this implementation does the following:
//!
//! - **Target.** The exit is placed as [`super::search`] places it, at the nearest point of the
//!   boundary lane, and is a node `e` of its own on that track between two nodes of the graph
//!   (the paper's exit "somewhere along the perimetric lane"): its neighbours are those two, the
//!   arcs into it run along the boundary lane, and a query gives the same target to both
//!   searches. Several targets are solved one by one and the best is kept (the paper's IV-A).
//! - **Start.** The machine's place on the nearest track is `s`; `c2` is the first node ahead
//!   along that track in the direction of the heading (its "first move follows the heading").
//!   An exit between `s` and `c2` is reached directly.
//! - **Paths.** Each label remembers the path that gave it (an immutable record: arc and the
//!   record before it), and the path returned is the one whose length set `UPPER`. Chasing the
//!   parents current at the end instead can give a path with an inadmissible transition, or a
//!   loop, when a junction was relabelled after its label was passed on.
//! - **Restarts.** The restart node is the junction taken last from the list whose parent arc
//!   runs along a headland pass (the paper's heuristic: "the node removed last must together
//!   with its parent represent a transition along a perimetric lane-segment"), else the last
//!   one taken (never the entry of the current call, which would restart the same call). The
//!   first half `[s, c2, b]` ends with the arc `b -> i` (so that it arrives at `b` heading the
//!   way that arc leaves; a path to `b` arriving any way might not go on to `i`); it always
//!   succeeds, because it runs as the deadlocked call did until that arc was taken. The second
//!   half starts at `i` having come along `b -> i`, with `d_b = 0`. Algorithm 1 then calls
//!   LCAmod once more for the same `[b, i, e]` it just solved (line 6 after line 9); that
//!   repeat is left out, its answer being the same.
//! - **Limits.** At most [`MAX_RESTARTS`] restarts per neighbour of the target, and
//!   [`MAX_REMOVALS`] removals from the list per call; beyond either, when a deadlocked call
//!   removed nothing but its entry, or when a restart would be from an arc restarted from
//!   before (the calls after it would repeat those after the first for ever), that neighbour
//!   gives no path.
//!
//! ```
//! use furrow::tracks::lcamod::lcamod_shortest_path;
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
//! // On the lane at y = 30, facing north; the exit at (0, 50). Without turning on the spot:
//! // up 70, west 50, down 50.
//! let query = TrackQuery {
//!     from: coord! { x: 50.0, y: 30.0 },
//!     heading: std::f64::consts::FRAC_PI_2,
//!     targets: vec![coord! { x: 0.0, y: 50.0 }],
//!     turning: Turning::Heading,
//!     ..TrackQuery::default()
//! };
//! let lca = lcamod_shortest_path(&graph, &query)?;
//! assert!((lca.length - 170.0).abs() < 1e-9);
//! assert_eq!(lca.restarts, 0);
//! assert!((lca.length - shortest_path(&graph, &query)?.length).abs() < 1e-9);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use super::graph::{TrackGraph, TrackKind};
use super::search::{may_turn, TrackQuery, Turning, MAX_START_OFFSET_M};
use crate::error::{ErrorCode, PlanError};
use crate::geometry::PlanarHypot;
use crate::sort::SharedSort;
use geo::Coord;
use std::collections::VecDeque;

/// The most restarts Algorithm 1 makes for one neighbour of the target before giving up.
pub const MAX_RESTARTS: usize = 50;
/// The most junctions one LCAmod call takes from its candidate list before giving up.
pub const MAX_REMOVALS: usize = 10_000_000;

/// A path found by LCAmod with restarts.
#[derive(Debug, Clone, PartialEq)]
pub struct LcaPath {
    /// Its length, metres.
    pub length: f64,
    /// Restarts Algorithm 1 made to find this path (for the neighbour of the target it goes
    /// through; those of the other neighbours tried are not counted).
    pub restarts: usize,
    /// Junctions taken from the candidate lists, over every LCAmod call (the paper's `N_iter`).
    pub iterations: usize,
    /// Its points (local metres), from the start placed on the tracks to the target.
    pub points: Vec<Coord>,
}

/// The shortest path for `query` over `graph` by the paper's Algorithm 1 (LCAmod with restarts).
///
/// At junctions the machine may change its way as `query.turning` allows (the paper's method is
/// for [`Turning::Tracks`]); the first move always follows the heading (`c2`), whatever the
/// turning. `query.monotone_band` is not used.
///
/// Errors: `invalid_option` without targets or with a number that is not finite; `off_tracks`
/// when the start is more than [`MAX_START_OFFSET_M`] from any track; `no_path` when the
/// method finds no path: every neighbour of every target deadlocked beyond what restarts
/// resolve (or beyond the limits), or no way along the tracks exists.
pub fn lcamod_shortest_path(graph: &TrackGraph, query: &TrackQuery) -> Result<LcaPath, PlanError> {
    let invalid = |m: &str| PlanError::new(ErrorCode::InvalidOption, m);
    if query.targets.is_empty() {
        return Err(invalid("a shortest path needs at least one target"));
    }
    let finite = |c: &Coord| c.x.is_finite() && c.y.is_finite();
    if !finite(&query.from) || !query.heading.is_finite() || !query.targets.iter().all(finite) {
        return Err(invalid(
            "the start, heading and targets must be finite numbers",
        ));
    }
    let no_tracks = || PlanError::new(ErrorCode::NoPath, "the plan has no tracks");
    let (track, at, offset) = graph.nearest(query.from, |_| true).ok_or_else(no_tracks)?;
    if offset > MAX_START_OFFSET_M {
        return Err(PlanError::new(ErrorCode::OffTracks, format!(
            "the start is {offset:.1} m from the nearest track (at most {MAX_START_OFFSET_M} m): the machine must be on the tracks"
        )));
    }
    let has_boundary = graph.tracks().iter().any(|t| t.boundary);
    let mut targets = Vec::with_capacity(query.targets.len());
    for &p in &query.targets {
        let (t, a, _) = graph
            .nearest(p, |t| t.boundary || !has_boundary)
            .ok_or_else(no_tracks)?;
        targets.push((t, a));
    }
    let mut model = Model::new(graph, query.turning);
    let face = Coord {
        x: query.heading.cos(),
        y: query.heading.sin(),
    };
    let no_path = || {
        PlanError::new(
            ErrorCode::NoPath,
            "LCAmod found no way along the tracks to the target from here with this turning",
        )
    };
    let Some(forward) = model.start_direction(track, at, face) else {
        return Err(no_path());
    };
    let c2 = model.next_node(track, at, forward);
    let mut stats = Stats::default();
    // The best path found: its length, arcs and the restarts it took.
    let mut best: Option<(f64, Vec<usize>, usize)> = None;
    for &(t, a) in &targets {
        // An exit between s and c2: straight there.
        if let Some(d) = model.ahead(track, at, forward, t, a) {
            if c2.is_none_or(|(_, dc)| d <= dc + 1e-9) {
                let arc = model.push_arc([None, None], track, forward, at, a, d);
                if best.as_ref().is_none_or(|b| d < b.0) {
                    best = Some((d, vec![arc], 0));
                }
                continue;
            }
        }
        let Some((c2, dc)) = c2 else { continue };
        let to_at = graph.nodes()[c2].at;
        let start = model.push_arc([None, Some(c2)], track, forward, at, to_at, dc);
        for last in model.arcs_into_target(t, a) {
            let entry = Entry {
                arc: start,
                cost: dc,
                block: None,
            };
            if let Some((length, arcs, restarts)) = model.algorithm1(entry, last, &mut stats) {
                if best.as_ref().is_none_or(|b| length < b.0) {
                    best = Some((length, arcs, restarts));
                }
            }
        }
    }
    let Some((_, arcs, restarts)) = best else {
        return Err(no_path());
    };
    let (length, points) = model.trace(&arcs);
    Ok(LcaPath {
        length,
        restarts,
        iterations: stats.iterations,
        points,
    })
}

/// One arc: along `track` from `from_at` to `to_at` (round a closed track), `forward` in the
/// track's order or against it. `from` and `to` are the graph's nodes at its ends; `None` for the
/// start `s` or the target `e`, which are not junctions.
#[derive(Debug, Clone, Copy)]
struct Arc {
    from: Option<usize>,
    to: Option<usize>,
    track: usize,
    forward: bool,
    from_at: f64,
    to_at: f64,
    length: f64,
    /// Heading when arriving at its end.
    arrive: Coord,
    /// Heading when leaving its start.
    leave: Coord,
}

/// Work done, over all calls.
#[derive(Debug, Default)]
struct Stats {
    iterations: usize,
}

/// Where an LCAmod call starts: having come along `arc` to its end junction, whose label is
/// `cost`; `block` is a junction labelled 0 (the start of a second half, `d_b = 0`).
#[derive(Debug, Clone, Copy)]
struct Entry {
    arc: usize,
    cost: f64,
    block: Option<usize>,
}

/// What one LCAmod call gives.
enum Outcome {
    /// A path to the target: its cost (counting the entry's label), and its arcs from the entry's
    /// on.
    Found(f64, Vec<usize>),
    /// The list emptied with `UPPER` infinite: the arc into the junction to restart from.
    Deadlock(Option<usize>),
    /// Too many removals.
    Exhausted,
}

/// The transition graph: arcs and, for each junction, the arcs leaving it.
struct Model<'a> {
    graph: &'a TrackGraph,
    turning: Turning,
    /// The graph's arcs, then those to and from the start and targets.
    arcs: Vec<Arc>,
    /// How many arcs are the graph's.
    real: usize,
    /// The graph's arcs leaving each junction.
    out: Vec<Vec<usize>>,
}

impl<'a> Model<'a> {
    fn new(graph: &'a TrackGraph, turning: Turning) -> Model<'a> {
        let mut model = Model {
            graph,
            turning,
            arcs: Vec::new(),
            real: 0,
            out: vec![Vec::new(); graph.junctions().len()],
        };
        let nodes = graph.nodes();
        for (t, track) in graph.tracks().iter().enumerate() {
            let list = graph.nodes_on(t);
            let len = track.length();
            for (k, &n) in list.iter().enumerate() {
                let at = nodes[n].at;
                let next = match list.get(k + 1) {
                    Some(&m) => Some((m, nodes[m].at - at)),
                    None if track.closed => list.first().map(|&m| (m, len - at + nodes[m].at)),
                    None => None,
                };
                let prev = match k.checked_sub(1).and_then(|j| list.get(j)) {
                    Some(&m) => Some((m, at - nodes[m].at)),
                    None if track.closed => list.last().map(|&m| (m, at + len - nodes[m].at)),
                    None => None,
                };
                for (forward, end) in [(true, next), (false, prev)] {
                    if let Some((m, d)) = end {
                        let arc =
                            model.push_arc([Some(n), Some(m)], t, forward, at, nodes[m].at, d);
                        model.out[nodes[n].junction].push(arc);
                    }
                }
            }
        }
        model.real = model.arcs.len();
        model
    }

    /// Adds an arc between nodes `ends` (from, to) and gives its index.
    fn push_arc(
        &mut self,
        [from, to]: [Option<usize>; 2],
        track: usize,
        forward: bool,
        from_at: f64,
        to_at: f64,
        length: f64,
    ) -> usize {
        let t = &self.graph.tracks()[track];
        self.arcs.push(Arc {
            from,
            to,
            track,
            forward,
            from_at,
            to_at,
            length: length.max(0.0),
            arrive: t.heading_at(to_at, forward, false),
            leave: t.heading_at(from_at, forward, true),
        });
        self.arcs.len() - 1
    }

    fn junction(&self, node: Option<usize>) -> Option<usize> {
        node.and_then(|n| self.graph.nodes().get(n))
            .map(|n| n.junction)
    }

    /// The way along the start track the heading points (the one closer to it, and not against
    /// it): `true` forwards.
    fn start_direction(&self, track: usize, at: f64, face: Coord) -> Option<bool> {
        let t = &self.graph.tracks()[track];
        let along = |forward: bool| {
            let h = t.heading_at(at, forward, true);
            h.x * face.x + h.y * face.y
        };
        let (f, b) = (along(true), along(false));
        if f >= 0.0 && f >= b {
            Some(true)
        } else if b >= 0.0 {
            Some(false)
        } else {
            None
        }
    }

    /// The first node from `at` on track `t` going `forward` or back, this place included, and
    /// the distance to it (round a closed track), as [`super::search`] finds it.
    fn next_node(&self, t: usize, at: f64, forward: bool) -> Option<(usize, f64)> {
        let g = self.graph;
        let track = &g.tracks()[t];
        let list = g.nodes_on(t);
        let len = track.length();
        let node_at = |n: usize| g.nodes()[n].at;
        if forward {
            let i = list.partition_point(|&n| node_at(n) < at - 1e-9);
            match list.get(i) {
                Some(&n) => Some((n, node_at(n) - at)),
                None if track.closed => list.first().map(|&n| (n, len - at + node_at(n))),
                None => None,
            }
        } else {
            let i = list.partition_point(|&n| node_at(n) <= at + 1e-9);
            match i.checked_sub(1).and_then(|j| list.get(j)) {
                Some(&n) => Some((n, at - node_at(n))),
                None if track.closed => list.last().map(|&n| (n, at + len - node_at(n))),
                None => None,
            }
        }
    }

    /// The distance from `at` on track `t` going `forward` or back to distance `to` on track
    /// `u`, when they are one track (round it when closed); `None` when `to` is behind.
    fn ahead(&self, t: usize, at: f64, forward: bool, u: usize, to: f64) -> Option<f64> {
        if t != u {
            return None;
        }
        let track = &self.graph.tracks()[t];
        let mut d = if forward { to - at } else { at - to };
        if d < -1e-9 && track.closed {
            d += track.length();
        }
        (d >= -1e-9).then_some(d.max(0.0))
    }

    /// The arcs into the target at distance `at` on track `t`: from the node behind it going
    /// forwards and from the node ahead of it going back (both from the node it is at, if any).
    fn arcs_into_target(&mut self, t: usize, at: f64) -> Vec<usize> {
        let mut out = Vec::with_capacity(2);
        for forward in [true, false] {
            // The node behind the target when arriving forwards is the first node going back.
            if let Some((n, d)) = self.next_node(t, at, !forward) {
                let from_at = self.graph.nodes()[n].at;
                out.push(self.push_arc([Some(n), None], t, forward, from_at, at, d));
            }
        }
        out
    }

    /// Whether a machine that came along arc `a` may go on along arc `b`, and what the step
    /// between their nodes costs.
    fn transition(&self, a: &Arc, b: &Arc) -> Option<f64> {
        let (Some(here), Some(there)) = (a.to, b.from) else {
            return None;
        };
        let same = here == there && a.forward == b.forward && a.track == b.track;
        if !same && !may_turn(self.turning, a.arrive, b.leave) {
            return None;
        }
        let nodes = self.graph.nodes();
        let (p, q) = (nodes[here].point, nodes[there].point);
        Some((p.x - q.x).planar_hypot(p.y - q.y))
    }

    /// Algorithm 1 for one neighbour of the target: LCAmod from `entry` to the target by arc
    /// `last` only, restarting while it deadlocks. The path's length, its arcs (from the start)
    /// and the restarts made.
    fn algorithm1(
        &self,
        start: Entry,
        last: usize,
        stats: &mut Stats,
    ) -> Option<(f64, Vec<usize>, usize)> {
        let finals = [last];
        let mut entry = start;
        let mut total = 0.0;
        let mut path: Vec<usize> = Vec::new();
        // The arcs restarted from: the second half from one of them again would repeat itself
        // for ever.
        let mut restarted: Vec<usize> = Vec::new();
        loop {
            match self.lcamod(entry, &finals, stats) {
                Outcome::Found(cost, arcs) => {
                    join(&mut path, &arcs);
                    return Some((total + cost, path, restarted.len()));
                }
                Outcome::Exhausted | Outcome::Deadlock(None) => return None,
                Outcome::Deadlock(Some(arc)) => {
                    if restarted.len() >= MAX_RESTARTS || restarted.contains(&arc) {
                        return None;
                    }
                    restarted.push(arc);
                    // [s, c2, b], ending with b -> i.
                    let Outcome::Found(cost, arcs) = self.lcamod(entry, &[arc], stats) else {
                        return None;
                    };
                    join(&mut path, &arcs);
                    total += cost;
                    // [b, i, e].
                    entry = Entry {
                        arc,
                        cost: 0.0,
                        block: self.junction(self.arcs[arc].from),
                    };
                }
            }
        }
    }

    /// One LCAmod call: breadth-first label correcting from `entry`, one label and parent per
    /// junction, to the target reached by any arc of `finals`.
    fn lcamod(&self, entry: Entry, finals: &[usize], stats: &mut Stats) -> Outcome {
        let n = self.graph.junctions().len();
        let mut label = vec![f64::INFINITY; n];
        // The record of the path that gave each label: (arc, record before it).
        let mut label_of: Vec<Option<usize>> = vec![None; n];
        let mut records: Vec<(usize, Option<usize>)> = vec![(entry.arc, None)];
        let mut listed = vec![false; n];
        let mut list = VecDeque::new();
        let Some(first) = self.junction(self.arcs[entry.arc].to) else {
            return Outcome::Deadlock(None);
        };
        if let Some(b) = entry.block {
            label[b] = 0.0;
        }
        label[first] = entry.cost;
        label_of[first] = Some(0);
        list.push_back(first);
        listed[first] = true;
        let mut upper = f64::INFINITY;
        let mut best: Option<(usize, usize)> = None;
        // The last record taken from the list (not the entry's), and the last along a
        // headland pass.
        let (mut last_any, mut last_perimetric) = (None, None);
        let mut removals = 0;
        while let Some(i) = list.pop_front() {
            listed[i] = false;
            removals += 1;
            stats.iterations += 1;
            if removals > MAX_REMOVALS {
                return Outcome::Exhausted;
            }
            let Some(r) = label_of[i] else { continue };
            let came = self.arcs[records[r].0];
            if r != 0 {
                last_any = Some(r);
                if self.graph.tracks()[came.track].kind == TrackKind::HeadlandPass {
                    last_perimetric = Some(r);
                }
            }
            let d = label[i];
            let virtual_finals = finals
                .iter()
                .copied()
                .filter(|&f| f >= self.real && self.junction(self.arcs[f].from) == Some(i));
            for b in self.out[i].iter().copied().chain(virtual_finals) {
                let arc = &self.arcs[b];
                let Some(gap) = self.transition(&came, arc) else {
                    continue;
                };
                let total = d + gap + arc.length;
                if finals.contains(&b) {
                    if total < upper {
                        upper = total;
                        best = Some((r, b));
                    }
                    continue;
                }
                let Some(j) = self.junction(arc.to) else {
                    continue;
                };
                if total < label[j].min(upper) {
                    label[j] = total;
                    label_of[j] = Some(records.len());
                    records.push((b, Some(r)));
                    if !listed[j] {
                        list.push_back(j);
                        listed[j] = true;
                    }
                }
            }
        }
        let Some((r, b)) = best else {
            let restart = last_perimetric.or(last_any).map(|r| records[r].0);
            return Outcome::Deadlock(restart);
        };
        let mut arcs = vec![b];
        let mut at = Some(r);
        while let Some(k) = at {
            arcs.push(records[k].0);
            at = records[k].1;
        }
        arcs.reverse();
        Outcome::Found(upper, arcs)
    }

    /// The length and points of a path of arcs.
    fn trace(&self, arcs: &[usize]) -> (f64, Vec<Coord>) {
        let nodes = self.graph.nodes();
        let mut length = 0.0;
        let mut points: Vec<Coord> = Vec::new();
        let push = |p: Coord, points: &mut Vec<Coord>| {
            if points
                .last()
                .is_none_or(|q| (q.x - p.x).planar_hypot(q.y - p.y) > 1e-9)
            {
                points.push(p);
            }
        };
        let mut prev: Option<&Arc> = None;
        for &k in arcs {
            let arc = &self.arcs[k];
            if let (Some(a), Some(b)) = (prev.and_then(|p| p.to), arc.from) {
                let (p, q) = (nodes[a].point, nodes[b].point);
                length += (p.x - q.x).planar_hypot(p.y - q.y);
            }
            length += arc.length;
            let track = &self.graph.tracks()[arc.track];
            let len = track.length();
            let place = |s: f64| {
                if track.closed && len > 0.0 {
                    track.point_at(s.rem_euclid(len))
                } else {
                    track.point_at(s)
                }
            };
            push(place(arc.from_at), &mut points);
            // The track's own points on the way, by distance travelled.
            let mut inner: Vec<f64> = track
                .at
                .iter()
                .filter_map(|&v| {
                    let mut o = if arc.forward {
                        v - arc.from_at
                    } else {
                        arc.from_at - v
                    };
                    if track.closed && o < 0.0 {
                        o += len;
                    }
                    (o > 1e-9 && o < arc.length - 1e-9).then_some(o)
                })
                .collect();
            inner.shared_sort_by(f64::total_cmp);
            for o in inner {
                push(
                    place(if arc.forward {
                        arc.from_at + o
                    } else {
                        arc.from_at - o
                    }),
                    &mut points,
                );
            }
            push(place(arc.to_at), &mut points);
            prev = Some(arc);
        }
        if points.len() == 1 {
            points.push(points[0]);
        }
        (length, points)
    }
}

/// Appends the arcs of a next piece of a path to it: the piece's first arc is the one the last
/// piece ended with (its entry), unless the path is still empty.
fn join(path: &mut Vec<usize>, piece: &[usize]) {
    let skip = usize::from(!path.is_empty());
    path.extend(piece.iter().skip(skip));
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;
    use crate::tracks::{from_plan, shortest_path, Track};
    use crate::PlanOptions;
    use geo::coord;

    fn track(kind: TrackKind, pts: &[(f64, f64)], boundary: bool) -> Track {
        Track::new(
            kind,
            pts.iter().map(|&(x, y)| coord! { x: x, y: y }).collect(),
            boundary,
        )
        .expect("a track")
    }

    fn polyline_length(points: &[Coord]) -> f64 {
        points
            .windows(2)
            .map(|w| (w[0].x - w[1].x).planar_hypot(w[0].y - w[1].y))
            .sum()
    }

    /// The paper's figure 3: from `b` the straight way to `a` is shorter than the detour through
    /// `i`, but only the detour arrives at `a` heading the way on to the exit. LCAmod labels `a`
    /// by the straight way, discards `i -> a` and deadlocks; the restart from `i` (whose parent
    /// arc runs along a headland pass) finds the way.
    #[test]
    fn a_restart_resolves_the_figure_3_deadlock() {
        let t8 = 8f64.to_radians().tan();
        let graph = TrackGraph::new(vec![
            // The start lane, east to b = (100, 0).
            track(TrackKind::Swath, &[(0.0, 0.0), (100.0, 0.0)], false),
            // The straight way b -> a = (200, 0).
            track(TrackKind::Swath, &[(100.0, 0.0), (200.0, 0.0)], false),
            // The detour, leaving b at 8° and arriving at a heading about 198°; i at (250, 50).
            track(
                TrackKind::HeadlandPass,
                &[
                    (100.0, 0.0),
                    (150.0, 50.0 * t8),
                    (250.0, 50.0),
                    (260.0, 20.0),
                    (200.0, 0.0),
                ],
                false,
            ),
            // A dead-end stub making i a junction.
            track(
                TrackKind::Connection,
                &[(250.0, 90.0), (250.0, 50.0)],
                false,
            ),
            // The way on from a at the detour's heading, meeting the boundary lane at 188°.
            track(
                TrackKind::Connection,
                &[
                    (200.0, 0.0),
                    (140.0, -20.0),
                    (100.0, -40.0 + 40.0 * t8),
                    (60.0, -40.0),
                ],
                false,
            ),
            // The boundary lane.
            track(
                TrackKind::HeadlandPass,
                &[(0.0, -40.0), (300.0, -40.0)],
                true,
            ),
        ]);
        let query = TrackQuery {
            from: coord! { x: 10.0, y: 0.0 },
            heading: 0.0,
            targets: vec![coord! { x: 20.0, y: -40.0 }],
            turning: Turning::Tracks,
            ..TrackQuery::default()
        };
        let exact = shortest_path(&graph, &query).expect("a way exists");
        let lca = lcamod_shortest_path(&graph, &query).expect("LCAmod with restarts finds it");
        assert!(lca.restarts >= 1, "{lca:?}");
        assert!(
            (lca.length - exact.length).abs() < 1e-6,
            "{} vs {}",
            lca.length,
            exact.length
        );
        assert!((polyline_length(&lca.points) - lca.length).abs() < 1e-6);
        let via_i = lca
            .points
            .iter()
            .any(|p| (p.x - 250.0).abs() < 1e-9 && (p.y - 50.0).abs() < 1e-9);
        assert!(via_i, "the path takes the detour: {:?}", lca.points);
        // Without restarts: one LCAmod call deadlocks, for either neighbour of the exit (on the
        // boundary lane, track 5, at 20 m).
        let mut model = Model::new(&graph, Turning::Tracks);
        let (t, at) = (5, 20.0);
        let c2 = model.next_node(0, 10.0, true).expect("b ahead");
        let start = model.push_arc([None, Some(c2.0)], 0, true, 10.0, 100.0, c2.1);
        let mut stats = Stats::default();
        let deadlocked = model.arcs_into_target(t, at).into_iter().all(|last| {
            let entry = Entry {
                arc: start,
                cost: c2.1,
                block: None,
            };
            matches!(
                model.lcamod(entry, &[last], &mut stats),
                Outcome::Deadlock(_)
            )
        });
        assert!(
            deadlocked,
            "a single LCAmod call deadlocks for both neighbours of the exit"
        );
    }

    /// Width, headland passes and turning radius of a corpus field from the fields README.
    fn options_of(name: &str) -> PlanOptions {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fields");
        let readme = std::fs::read_to_string(format!("{dir}/README.md")).expect("fields README");
        let line = readme
            .lines()
            .find(|l| l.starts_with(&format!("| {name}.geojson ")))
            .expect("the field in the README table");
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        let num = |i: usize| -> f64 { cells[i].parse().expect("a number") };
        PlanOptions {
            width: num(6),
            headland_passes: (num(7) as u32).into(),
            turn_radius: num(8),
            ..PlanOptions::default()
        }
    }

    fn random_query(g: &TrackGraph, rng: &mut SplitMix64) -> TrackQuery {
        let total: f64 = g.tracks().iter().map(Track::length).sum();
        let mut pick = rng.unit() * total;
        let mut track = 0;
        for (i, t) in g.tracks().iter().enumerate() {
            if pick <= t.length() {
                track = i;
                break;
            }
            pick -= t.length();
        }
        let t = &g.tracks()[track];
        let at = pick.clamp(0.0, t.length());
        let h = t.heading_at(at, rng.unit() < 0.5, true);
        let boundary: Vec<usize> = (0..g.tracks().len())
            .filter(|&i| g.tracks()[i].boundary)
            .collect();
        let b = &g.tracks()[boundary[rng.below(boundary.len())]];
        TrackQuery {
            from: t.point_at(at),
            heading: h.y.atan2(h.x),
            targets: vec![b.point_at(rng.unit() * b.length())],
            turning: Turning::Tracks,
            ..TrackQuery::default()
        }
    }

    /// Counts over the queries of one field; the means are over those both searches answer.
    #[derive(Default)]
    struct Tally {
        exact: usize,
        both: usize,
        failures: usize,
        longer: usize,
        longer_1m: usize,
        neither: usize,
        excess: f64,
        restarts: usize,
        iterations: usize,
        expanded: usize,
    }

    /// 200 random queries on each of three corpus plans: LCAmod is never shorter than the
    /// directed-state search; the lines printed count where it fails or is longer.
    #[test]
    fn never_shorter_than_the_directed_state_search_on_corpus_plans() {
        const QUERIES: usize = 200;
        let mut rng = SplitMix64::new(2016);
        for name in ["rectangle", "h-shape", "obstacles-2"] {
            let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fields/").to_string()
                + name
                + ".geojson";
            let text = std::fs::read_to_string(&path).expect("corpus field");
            let plan = crate::plan_geojson(&text, &options_of(name)).expect("plans");
            let g = from_plan(&plan);
            assert!(
                g.tracks().iter().any(|t| t.boundary),
                "{name}: a boundary lane"
            );
            let mut n = Tally::default();
            for q in 0..QUERIES {
                let query = random_query(&g, &mut rng);
                let exact = shortest_path(&g, &query);
                let lca = lcamod_shortest_path(&g, &query);
                n.exact += usize::from(exact.is_ok());
                match (&lca, &exact) {
                    (Ok(l), Ok(e)) => {
                        assert!(
                            e.length <= l.length + 1e-6,
                            "{name} query {q}: LCAmod {} shorter than the exact {}",
                            l.length,
                            e.length
                        );
                        assert!(
                            (polyline_length(&l.points) - l.length).abs() < 1e-6,
                            "{name} query {q}: the points are the path"
                        );
                        let (start, end) = (l.points[0], l.points[l.points.len() - 1]);
                        let e_end = e.points[e.points.len() - 1];
                        assert!((start.x - e.start.x).planar_hypot(start.y - e.start.y) < 1e-6);
                        assert!(
                            (end.x - e_end.x).planar_hypot(end.y - e_end.y) < 1e-6,
                            "{name} query {q}: at the target"
                        );
                        n.both += 1;
                        n.restarts += l.restarts;
                        n.iterations += l.iterations;
                        n.expanded += e.expanded;
                        let excess = l.length - e.length;
                        n.longer += usize::from(excess > 1e-3);
                        n.longer_1m += usize::from(excess > 1.0);
                        n.excess = n.excess.max(excess);
                    }
                    (Ok(l), Err(e)) => {
                        panic!("{name} query {q}: LCAmod found {l:?} where there is no path ({e})")
                    }
                    (Err(l), Ok(_)) => {
                        assert_eq!(l.code, ErrorCode::NoPath, "{name} query {q}: {l}");
                        n.failures += 1;
                    }
                    (Err(l), Err(_)) => {
                        assert_eq!(l.code, ErrorCode::NoPath, "{name} query {q}: {l}");
                        n.neither += 1;
                    }
                }
            }
            let both = n.both.max(1) as f64;
            println!(
                "{name:<11} {:>3} junctions  queries {QUERIES}  exact finds {:>3}  LCAmod fails {:>3}  LCAmod longer {:>3} (by > 1 m {:>3}, at most {:.1} m)  neither {:>2}  mean restarts {:.2}  mean iterations {:.0} vs mean expanded {:.0}",
                g.junctions().len(),
                n.exact,
                n.failures,
                n.longer,
                n.longer_1m,
                n.excess,
                n.neither,
                n.restarts as f64 / both,
                n.iterations as f64 / both,
                n.expanded as f64 / both,
            );
        }
    }
}
