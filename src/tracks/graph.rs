//! The track graph: the tracks a plan leaves in the field, and where a machine can change from
//! one to another (Plessen & Bemporad, 2016).
//!
//! A [`Track`] is a line the machine drove: a swath, a headland pass, a turn between swaths or a
//! connection. Any track can be driven again either way. Tracks meet at *junctions*:
//!
//! - where one track ends on another (the end of a swath and the start of its turn, a connection
//!   merging into a headland pass), found within [`JOIN_TOLERANCE_M`];
//! - where a connection runs along another track and leaves it (routed along a headland pass,
//!   it turns off towards a swath): the two are one trace between these points;
//! - where a headland pass or a connection crosses another track (a turn in the headland
//!   crossing a pass). Turns crossing turns are not junctions: see [`TrackGraph::new`].
//!
//! A junction is a place; which ways through it a machine may go is the search's business
//! ([`super::search`]): with the repressed-area constraint only where the tracks meet at the
//! same heading (the smoothed junctions of the paper's figure 2, driven the way they were made,
//! or the other way round), without turning on the spot through any turn but a reversal, and
//! with turning on the spot every way.
//!
//! ```
//! use furrow::tracks::{Track, TrackGraph, TrackKind};
//! use geo::coord;
//!
//! // A lane up the middle of a square loop, meeting it at both ends.
//! let square = vec![
//!     coord! { x: 0.0, y: 0.0 }, coord! { x: 100.0, y: 0.0 }, coord! { x: 100.0, y: 100.0 },
//!     coord! { x: 0.0, y: 100.0 }, coord! { x: 0.0, y: 0.0 },
//! ];
//! let lane = vec![coord! { x: 50.0, y: 0.0 }, coord! { x: 50.0, y: 100.0 }];
//! let graph = TrackGraph::new(vec![
//!     Track::new(TrackKind::HeadlandPass, square, true).ok_or("no track")?,
//!     Track::new(TrackKind::Swath, lane, false).ok_or("no track")?,
//! ]);
//! // The loop closes on itself, and the lane's two ends meet it.
//! assert_eq!(graph.junctions().len(), 3);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use crate::geometry::{segment_foot, IndexedSegment, PlanarHypot};
use crate::sort::SharedSort;
use geo::Coord;
use rstar::{RTree, RTreeObject};

/// How close (metres) a track's end must come to another track to join it, and how close two
/// tracks must run to be one trace.
pub const JOIN_TOLERANCE_M: f64 = 0.05;
/// How far apart (metres) the points are at which a track is compared with the others it might
/// run along.
const ALONG_STEP_M: f64 = 2.0;
/// Tracks running along each other differ in heading by less than this (radians, about 6°).
const ALONG_HEADING: f64 = 0.1;
/// Where a connection's stretch along another track is cut out, what is left reaches this far
/// into the stretch (metres), so that it ends on the other track.
const CUT_INSIDE_M: f64 = 0.05;
/// Nodes on one track closer than this (metres) are one node.
const SAME_NODE_M: f64 = 1e-3;

/// What a track is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TrackKind {
    /// A swath's centre line.
    Swath,
    /// A headland pass's centre line.
    HeadlandPass,
    /// A turn between two swaths.
    Turn,
    /// A connection: between blocks, onto the headland passes, from the entrance.
    Connection,
}

impl TrackKind {
    /// The name used in the output: `swath`, `headland`, `turn`, `connection`.
    pub fn as_str(self) -> &'static str {
        match self {
            TrackKind::Swath => "swath",
            TrackKind::HeadlandPass => "headland",
            TrackKind::Turn => "turn",
            TrackKind::Connection => "connection",
        }
    }
}

/// A line the machine drove, with the distance along it at each point.
#[derive(Debug, Clone, PartialEq)]
pub struct Track {
    /// What it is.
    pub kind: TrackKind,
    /// Its points in local metres, in the order driven.
    pub points: Vec<Coord>,
    /// Distance along it at each point, metres.
    pub at: Vec<f64>,
    /// The boundary lane: the field's outermost headland pass, where exits are.
    pub boundary: bool,
    /// It ends where it starts (a closed headland pass).
    pub closed: bool,
}

impl Track {
    /// A track through `points` (repeated points dropped); `None` when fewer than two distinct
    /// finite points are left.
    pub fn new(kind: TrackKind, points: Vec<Coord>, boundary: bool) -> Option<Track> {
        let mut pts: Vec<Coord> = Vec::with_capacity(points.len());
        for p in points {
            if !(p.x.is_finite() && p.y.is_finite()) {
                return None;
            }
            if pts.last().is_none_or(|q| distance(*q, p) > 1e-9) {
                pts.push(p);
            }
        }
        if pts.len() < 2 {
            return None;
        }
        let mut at = Vec::with_capacity(pts.len());
        let mut s = 0.0;
        at.push(0.0);
        for w in pts.windows(2) {
            s += distance(w[0], w[1]);
            at.push(s);
        }
        let closed = pts.len() > 2 && distance(pts[0], pts[pts.len() - 1]) <= SAME_NODE_M;
        Some(Track {
            kind,
            points: pts,
            at,
            boundary,
            closed,
        })
    }

    /// Its length, metres.
    pub fn length(&self) -> f64 {
        self.at.last().copied().unwrap_or(0.0)
    }

    /// The index of the segment holding distance `s` (the later one at a vertex when `ahead`).
    fn segment_at(&self, s: f64, ahead: bool) -> usize {
        let n = self.points.len() - 1;
        let i = if ahead {
            self.at.partition_point(|&a| a <= s)
        } else {
            self.at.partition_point(|&a| a < s)
        };
        i.saturating_sub(1).min(n - 1)
    }

    /// The point at distance `s` along the track (clamped to it).
    pub fn point_at(&self, s: f64) -> Coord {
        let s = s.clamp(0.0, self.length());
        let i = self.segment_at(s, true);
        let (a, b) = (self.points[i], self.points[i + 1]);
        let len = self.at[i + 1] - self.at[i];
        let t = if len > 0.0 {
            (s - self.at[i]) / len
        } else {
            0.0
        };
        a + (b - a) * t
    }

    /// The unit direction of travel at distance `s` when driving the track `forward` (in its
    /// order) or against it: of the segment ahead when `leaving` the point, else of the one behind.
    pub fn heading_at(&self, s: f64, forward: bool, leaving: bool) -> Coord {
        let n = self.points.len() - 1;
        let s = s.clamp(0.0, self.length());
        // Leaving forwards, or arriving backwards, uses the segment after the point.
        let mut i = self.segment_at(s, forward == leaving);
        if self.closed && forward == leaving && s >= self.length() - SAME_NODE_M {
            i = 0;
        } else if self.closed && forward != leaving && s <= SAME_NODE_M {
            i = n - 1;
        }
        let d = self.points[i + 1] - self.points[i];
        let len = d.x.planar_hypot(d.y);
        let u = if len > 0.0 {
            d / len
        } else {
            Coord { x: 1.0, y: 0.0 }
        };
        if forward {
            u
        } else {
            -u
        }
    }

    /// The part of the track from distance `from` to `to` (`from < to`), or `None` if it is a
    /// point.
    pub fn part(&self, from: f64, to: f64) -> Option<Track> {
        let mut pts = vec![self.point_at(from)];
        for (i, &a) in self.at.iter().enumerate() {
            if a > from && a < to {
                pts.push(self.points[i]);
            }
        }
        pts.push(self.point_at(to));
        Track::new(self.kind, pts, self.boundary)
    }

    /// The nearest point of the track to `p`: (distance along it, distance from it).
    pub fn nearest(&self, p: Coord) -> (f64, f64) {
        let mut best = (0.0, f64::INFINITY);
        for i in 0..self.points.len() - 1 {
            let (s, d) = foot(self.points[i], self.points[i + 1], p);
            if d < best.1 {
                best = (self.at[i] + s, d);
            }
        }
        best
    }
}

/// A place on a track where a junction is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Node {
    /// The track it is on.
    pub track: usize,
    /// Distance along the track, metres.
    pub at: f64,
    /// Where it is, local metres.
    pub point: Coord,
    /// The junction it belongs to (whose nodes lie within a few centimetres of each other).
    pub junction: usize,
}

/// Nodes of several tracks at one place.
#[derive(Debug, Clone, PartialEq)]
pub struct Junction {
    /// Its nodes, one per track through it (a closed track's start and end are one).
    pub nodes: Vec<usize>,
    /// Where it is, local metres.
    pub point: Coord,
}

/// The tracks of a plan and their junctions.
#[derive(Debug, Clone)]
pub struct TrackGraph {
    tracks: Vec<Track>,
    nodes: Vec<Node>,
    /// The nodes of each track, by distance along it.
    on_track: Vec<Vec<usize>>,
    junctions: Vec<Junction>,
    segments: RTree<Piece>,
}

/// One segment of a track, for the spatial searches (`line` the track).
type Piece = IndexedSegment;

impl TrackGraph {
    /// The graph of these tracks: their junctions found as the module explains.
    pub fn new(tracks: Vec<Track>) -> TrackGraph {
        let tracks = without_runs(tracks);
        let segments = index(&tracks);
        let mut builder = Builder::new(&tracks);
        for (t, track) in tracks.iter().enumerate() {
            // Ends: on whatever they touch.
            for s in [0.0, track.length()] {
                let p = track.point_at(s);
                let here = builder.node(t, s);
                for (u, su) in touching(&tracks, &segments, p, t, s) {
                    let there = builder.node(u, su);
                    builder.join(here, there);
                }
            }
        }
        // Crossings: of the headland passes and the connections with anything. (Turns cross each
        // other all over the headland too; changing from one to another there gains nothing a
        // pass does not offer, and would make the graph several times larger.)
        let crossed = index_of(&tracks, |t| {
            matches!(t.kind, TrackKind::HeadlandPass | TrackKind::Connection)
        });
        for piece in crossed.iter() {
            let env = piece.envelope();
            for other in segments.locate_in_envelope_intersecting(&env) {
                let both = tracks[other.line].kind != TrackKind::Turn
                    && tracks[other.line].kind != TrackKind::Swath;
                if other.line == piece.line || (both && other.line < piece.line) {
                    continue;
                }
                if let Some((s, u)) = crossing(piece, other) {
                    let ta = &tracks[piece.line];
                    let tb = &tracks[other.line];
                    let sa = ta.at[piece.index] + s;
                    let sb = tb.at[other.index] + u;
                    let a = builder.node(piece.line, sa);
                    let b = builder.node(other.line, sb);
                    builder.join(a, b);
                }
            }
        }
        builder.finish(tracks, segments)
    }

    /// The tracks.
    pub fn tracks(&self) -> &[Track] {
        &self.tracks
    }

    /// The nodes.
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// The junctions.
    pub fn junctions(&self) -> &[Junction] {
        &self.junctions
    }

    /// The nodes on track `t`, by distance along it.
    pub fn nodes_on(&self, t: usize) -> &[usize] {
        &self.on_track[t]
    }

    /// The place on the tracks nearest to `p`: (track, distance along it, distance from it),
    /// among the tracks `accept` takes; `None` when there is none.
    pub fn nearest(&self, p: Coord, accept: impl Fn(&Track) -> bool) -> Option<(usize, f64, f64)> {
        let mut best: Option<(usize, f64, f64)> = None;
        for piece in self.segments.nearest_neighbor_iter(&[p.x, p.y]) {
            let (s, d) = foot(piece.a, piece.b, p);
            if best.is_some_and(|b| d > b.2 + 1e-9) {
                break;
            }
            let track = &self.tracks[piece.line];
            if !accept(track) {
                continue;
            }
            if best.is_none_or(|b| d < b.2) {
                best = Some((piece.line, track.at[piece.index] + s, d));
            }
        }
        best
    }
}

/// The R-tree of the tracks' segments.
fn index(tracks: &[Track]) -> RTree<Piece> {
    index_of(tracks, |_| true)
}

/// The R-tree of the segments of the tracks `keep` takes.
fn index_of(tracks: &[Track], keep: impl Fn(&Track) -> bool) -> RTree<Piece> {
    let pieces: Vec<Piece> = tracks
        .iter()
        .enumerate()
        .filter(|(_, track)| keep(track))
        .flat_map(|(t, track)| {
            track
                .points
                .windows(2)
                .enumerate()
                .map(move |(index, w)| Piece::new(w[0], w[1], t, index))
        })
        .collect();
    RTree::bulk_load(pieces)
}

/// The tracks with the stretches of connections that run along other tracks (a connection
/// routed along a headland pass) cut out: there the two are one trace, the other track. What is
/// left of a connection (its turns off and onto the pass) ends on the pass, a little inside the
/// stretch, and joins it there like any track that ends on another.
fn without_runs(tracks: Vec<Track>) -> Vec<Track> {
    if !tracks.iter().any(|t| t.kind == TrackKind::Connection) {
        return tracks;
    }
    // What connections run along: anything but other connections.
    let segments = index_of(&tracks, |t| t.kind != TrackKind::Connection);
    let mut cuts: Vec<Vec<(f64, f64)>> = vec![Vec::new(); tracks.len()];
    for (t, track) in tracks.iter().enumerate() {
        if track.kind != TrackKind::Connection {
            continue;
        }
        let mut runs: Vec<(f64, f64)> = runs_along(&tracks, &segments, t)
            .into_iter()
            // Ends a little inside the run, so that what is left ends on the other track.
            .map(|r| (r.1 .0 + CUT_INSIDE_M, r.2 .0 - CUT_INSIDE_M))
            .filter(|r| r.1 > r.0)
            .collect();
        runs.shared_sort_by(|a, b| a.0.total_cmp(&b.0));
        cuts[t] = runs;
    }
    let mut out = Vec::with_capacity(tracks.len());
    for (track, runs) in tracks.into_iter().zip(cuts) {
        if runs.is_empty() {
            out.push(track);
            continue;
        }
        let mut from = 0.0;
        for (a, b) in runs.into_iter().chain([(track.length(), track.length())]) {
            if a > from + CUT_INSIDE_M {
                out.extend(track.part(from, a));
            }
            from = from.max(b);
        }
    }
    out
}

/// Collects nodes (merging those at one place on a track) and the junctions between them.
struct Builder {
    nodes: Vec<(usize, f64)>,
    on_track: Vec<Vec<usize>>,
    lengths: Vec<f64>,
    closed: Vec<bool>,
    parent: Vec<usize>,
}

impl Builder {
    fn new(tracks: &[Track]) -> Builder {
        Builder {
            nodes: Vec::new(),
            on_track: vec![Vec::new(); tracks.len()],
            lengths: tracks.iter().map(Track::length).collect(),
            closed: tracks.iter().map(|t| t.closed).collect(),
            parent: Vec::new(),
        }
    }

    /// The node at distance `s` on track `t` (made if there is none within `SAME_NODE_M`; a
    /// closed track's end is its start).
    fn node(&mut self, t: usize, s: f64) -> usize {
        let len = self.lengths[t];
        let mut s = s.clamp(0.0, len);
        if self.closed[t] && s >= len - SAME_NODE_M {
            s = 0.0;
        }
        for &n in &self.on_track[t] {
            if (self.nodes[n].1 - s).abs() <= SAME_NODE_M {
                return n;
            }
        }
        let n = self.nodes.len();
        self.nodes.push((t, s));
        self.parent.push(n);
        self.on_track[t].push(n);
        n
    }

    fn root(&mut self, mut n: usize) -> usize {
        while self.parent[n] != n {
            self.parent[n] = self.parent[self.parent[n]];
            n = self.parent[n];
        }
        n
    }

    fn join(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.root(a), self.root(b));
        if ra != rb {
            self.parent[ra.max(rb)] = ra.min(rb);
        }
    }

    fn finish(mut self, tracks: Vec<Track>, segments: RTree<Piece>) -> TrackGraph {
        let mut junction_of_root = vec![usize::MAX; self.nodes.len()];
        let mut junctions: Vec<Junction> = Vec::new();
        let mut nodes = Vec::with_capacity(self.nodes.len());
        for n in 0..self.nodes.len() {
            let r = self.root(n);
            let (t, s) = self.nodes[n];
            if junction_of_root[r] == usize::MAX {
                junction_of_root[r] = junctions.len();
                junctions.push(Junction {
                    nodes: Vec::new(),
                    point: tracks[t].point_at(s),
                });
            }
            let j = junction_of_root[r];
            junctions[j].nodes.push(n);
            nodes.push(Node {
                track: t,
                at: s,
                point: tracks[t].point_at(s),
                junction: j,
            });
        }
        let mut on_track = std::mem::take(&mut self.on_track);
        for list in &mut on_track {
            list.shared_sort_by(|&a, &b| nodes[a].at.total_cmp(&nodes[b].at));
        }
        TrackGraph {
            tracks,
            nodes,
            on_track,
            junctions,
            segments,
        }
    }
}

/// The places on other tracks (and on a closed track itself, at its other end) within
/// `JOIN_TOLERANCE_M` of point `p`, which is at distance `s` on track `t`.
fn touching(
    tracks: &[Track],
    segments: &RTree<Piece>,
    p: Coord,
    t: usize,
    s: f64,
) -> Vec<(usize, f64)> {
    let mut best: Vec<(usize, f64, f64)> = Vec::new();
    for piece in segments.locate_within_distance([p.x, p.y], JOIN_TOLERANCE_M * JOIN_TOLERANCE_M) {
        let (u, d) = foot(piece.a, piece.b, p);
        let su = tracks[piece.line].at[piece.index] + u;
        if piece.line == t && (su - s).abs() < 1.0 {
            continue; // the track itself, here
        }
        match best.iter_mut().find(|b| b.0 == piece.line) {
            Some(b) if d < b.2 => *b = (piece.line, su, d),
            Some(_) => {}
            None => best.push((piece.line, su, d)),
        }
    }
    best.into_iter().map(|(u, su, _)| (u, su)).collect()
}

/// A place on two tracks at once: (distance along the one, along the other).
type Pair = (f64, f64);

/// A stretch where one track runs along another: (the other, where it starts, where it ends).
type Run = (usize, Pair, Pair);

/// The stretches where track `t` runs along another track within `JOIN_TOLERANCE_M` and at
/// about the same heading (either way). The track is looked at every `ALONG_STEP_M`; where a run
/// starts or ends between two looks, the place is found by halving the gap to a centimetre.
fn runs_along(tracks: &[Track], segments: &RTree<Piece>, t: usize) -> Vec<Run> {
    let track = &tracks[t];
    let len = track.length();
    let steps = (len / ALONG_STEP_M).ceil().max(1.0) as usize;
    let at_step = |k: usize| len * k as f64 / steps as f64;
    let mut out = Vec::new();
    // Open runs: (other track, start, last seen).
    let mut open: Vec<(usize, Pair, Pair)> = Vec::new();
    for k in 0..=steps {
        let s = at_step(k);
        let here = alongside(tracks, segments, t, s);
        // Runs that go on, and those that ended since the last look.
        let mut going = Vec::with_capacity(open.len());
        for run in open {
            match here.iter().find(|h| h.0 == run.0) {
                Some(&(_, su)) => going.push((run.0, run.1, (s, su))),
                None => {
                    let end = refine(tracks, segments, t, run.0, run.2, s);
                    if end.0 > run.1 .0 {
                        out.push((run.0, run.1, end));
                    }
                }
            }
        }
        for &(u, su) in &here {
            if !going.iter().any(|r| r.0 == u) {
                // A run starts between the last look and this one.
                let start = if k == 0 {
                    (s, su)
                } else {
                    refine(tracks, segments, t, u, (s, su), at_step(k - 1))
                };
                going.push((u, start, (s, su)));
            }
        }
        open = going;
    }
    out.extend(open.into_iter().filter(|r| r.2 .0 > r.1 .0));
    out
}

/// The other tracks that track `t` runs along at distance `s`: (track, distance along it).
fn alongside(tracks: &[Track], segments: &RTree<Piece>, t: usize, s: f64) -> Vec<(usize, f64)> {
    let track = &tracks[t];
    let p = track.point_at(s);
    let h = track.heading_at(s, true, true);
    let mut out: Vec<(usize, f64)> = Vec::new();
    for piece in segments.locate_within_distance([p.x, p.y], JOIN_TOLERANCE_M * JOIN_TOLERANCE_M) {
        if piece.line == t || out.iter().any(|o| o.0 == piece.line) {
            continue;
        }
        let d = piece.b - piece.a;
        let dl = d.x.planar_hypot(d.y);
        if dl <= 0.0 || (h.x * d.y - h.y * d.x).abs() / dl > ALONG_HEADING.sin() {
            continue;
        }
        let (u, _) = foot(piece.a, piece.b, p);
        out.push((piece.line, tracks[piece.line].at[piece.index] + u));
    }
    out
}

/// The last place from `on` (where track `t` runs along track `u`) towards distance `off` on
/// `t` (where it does not) at which it still does, to within a centimetre.
fn refine(
    tracks: &[Track],
    segments: &RTree<Piece>,
    t: usize,
    u: usize,
    on: Pair,
    off: f64,
) -> Pair {
    let (mut good, mut bad) = (on, off);
    while (bad - good.0).abs() > 0.01 {
        let mid = (good.0 + bad) / 2.0;
        match alongside(tracks, segments, t, mid)
            .into_iter()
            .find(|h| h.0 == u)
        {
            Some((_, su)) => good = (mid, su),
            None => bad = mid,
        }
    }
    good
}

/// Where two segments cross at more than a small angle: distances along each from its start.
fn crossing(a: &Piece, b: &Piece) -> Option<(f64, f64)> {
    let r = a.b - a.a;
    let q = b.b - b.a;
    let denom = r.x * q.y - r.y * q.x;
    let (lr2, lq2) = (r.x * r.x + r.y * r.y, q.x * q.x + q.y * q.y);
    let sin = ALONG_HEADING.sin();
    if lr2 <= 0.0 || lq2 <= 0.0 || denom * denom < lr2 * lq2 * sin * sin {
        return None; // parallel or nearly: runs along, not a crossing
    }
    let w = b.a - a.a;
    let t = (w.x * q.y - w.y * q.x) / denom;
    let u = (w.x * r.y - w.y * r.x) / denom;
    // Strictly inside both, so that ends (found as touching) are not counted again.
    let eps = 1e-9;
    if t <= eps || t >= 1.0 - eps || u <= eps || u >= 1.0 - eps {
        return None;
    }
    Some((t * lr2.sqrt(), u * lq2.sqrt()))
}

/// The foot of `p` on segment ab: (distance from a along it, distance of p from it).
fn foot(a: Coord, b: Coord, p: Coord) -> (f64, f64) {
    let (f, along) = segment_foot(p, a, b);
    (along, distance(f, p))
}

fn distance(a: Coord, b: Coord) -> f64 {
    ((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::coord;

    fn track(kind: TrackKind, pts: &[(f64, f64)]) -> Track {
        Track::new(
            kind,
            pts.iter().map(|&(x, y)| coord! { x: x, y: y }).collect(),
            false,
        )
        .expect("a track")
    }

    #[test]
    fn ends_touching_join_and_crossings_are_junctions() {
        let a = track(TrackKind::Swath, &[(0.0, 0.0), (10.0, 0.0)]);
        let b = track(TrackKind::Turn, &[(10.0, 0.0), (10.0, 10.0)]);
        let c = track(TrackKind::HeadlandPass, &[(5.0, -5.0), (5.0, 5.0)]);
        let g = TrackGraph::new(vec![a, b, c]);
        // a's end with b's start; c crosses a at x = 5; the free ends: a's start, b's end, c's two.
        let sizes: Vec<usize> = g.junctions().iter().map(|j| j.nodes.len()).collect();
        assert_eq!(sizes.iter().filter(|&&n| n == 2).count(), 2, "{sizes:?}");
        assert_eq!(sizes.iter().filter(|&&n| n == 1).count(), 4, "{sizes:?}");
        let crossing = g
            .junctions()
            .iter()
            .find(|j| (j.point.x - 5.0).abs() < 1e-9 && j.point.y.abs() < 1e-9)
            .expect("the crossing");
        assert_eq!(crossing.nodes.len(), 2);
    }

    #[test]
    fn a_connection_running_along_a_pass_is_cut_there_and_joins_it_where_it_leaves() {
        // A pass along y = 0; a connection merging into it at x = 20 and leaving at x = 60.
        let pass = track(TrackKind::HeadlandPass, &[(0.0, 0.0), (100.0, 0.0)]);
        let conn = track(
            TrackKind::Connection,
            &[(10.0, 10.0), (20.0, 0.0), (60.0, 0.0), (70.0, 10.0)],
        );
        let g = TrackGraph::new(vec![pass, conn]);
        // The stretch along the pass is the pass: the connection is left as its two ends.
        assert_eq!(g.tracks().len(), 3);
        for part in &g.tracks()[1..] {
            assert_eq!(part.kind, TrackKind::Connection);
            assert!(
                (part.length() - (200f64.sqrt() + CUT_INSIDE_M)).abs() < 0.02,
                "{}",
                part.length()
            );
        }
        let on_pass: Vec<f64> = g.nodes_on(0).iter().map(|&n| g.nodes()[n].at).collect();
        // The pass's ends, and where the connection joins and leaves it: at 20 and 60 m.
        assert!(
            on_pass.iter().any(|&s| (s - 20.0).abs() < 0.1),
            "{on_pass:?}"
        );
        assert!(
            on_pass.iter().any(|&s| (s - 60.0).abs() < 0.1),
            "{on_pass:?}"
        );
        for t in 1..3 {
            let joined = g
                .nodes_on(t)
                .iter()
                .any(|&n| g.junctions()[g.nodes()[n].junction].nodes.len() == 2);
            assert!(joined, "part {t} joins the pass");
        }
    }

    #[test]
    fn closed_track_meets_itself() {
        let ring = track(
            TrackKind::HeadlandPass,
            &[
                (0.0, 0.0),
                (10.0, 0.0),
                (10.0, 10.0),
                (0.0, 10.0),
                (0.0, 0.0),
            ],
        );
        assert!(ring.closed);
        let g = TrackGraph::new(vec![ring]);
        assert_eq!(g.nodes().len(), 1, "start and end are one node");
        // Headings at the start: leaving forwards east, arriving forwards from the south.
        let t = &g.tracks()[0];
        let leave = t.heading_at(0.0, true, true);
        let arrive = t.heading_at(0.0, true, false);
        assert!((leave.x - 1.0).abs() < 1e-12);
        assert!((arrive.y + 1.0).abs() < 1e-12, "{arrive:?}");
    }

    #[test]
    fn point_and_nearest() {
        let t = track(TrackKind::Swath, &[(0.0, 0.0), (3.0, 4.0), (3.0, 14.0)]);
        assert!((t.length() - 15.0).abs() < 1e-12);
        let p = t.point_at(10.0);
        assert!((p.x - 3.0).abs() < 1e-12 && (p.y - 9.0).abs() < 1e-12);
        let (s, d) = t.nearest(coord! { x: 5.0, y: 9.0 });
        assert!((s - 10.0).abs() < 1e-12 && (d - 2.0).abs() < 1e-12);
        assert!(Track::new(TrackKind::Swath, vec![coord! { x: 1.0, y: 1.0 }; 3], false).is_none());
        assert!(Track::new(
            TrackKind::Swath,
            vec![coord! { x: f64::NAN, y: 1.0 }, coord! { x: 0.0, y: 0.0 }],
            false
        )
        .is_none());
    }
}
