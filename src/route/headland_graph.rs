//! The headland graph: the lines a machine may drive along between blocks without crossing the
//! crop of the inner field (Zhou et al. 2.4.1).
//!
//! Its lines are the centre lines of the headland passes: round the field, round obstacles, and
//! along borders between blocks. A point (a swath end, the entrance) joins the graph by a short
//! straight *spur* to the nearest point of a line; a machine changes from one line to another by
//! a straight *hop* where they come within a working width of each other (neighbouring passes of
//! one headland, a block's pass meeting the field's), but not across the crop of the inner field
//! ([`HeadlandGraph::with_crop`]). A connection is the shortest way through
//! that graph: spur, lines and hops, spur. Points the graph cannot reach are joined straight, at
//! a cost the block sequence avoids (see [`CROSSING_PENALTY_M`]).
//!
//! Only the parts of the lines between the points asked about matter, so the graph searched is
//! small: its nodes are the points' spur feet, the hop ends from them and the ends of open
//! passes; its edges run along each line between consecutive nodes.
//!
//! ```
//! use furrow::headland::{HeadlandPass, PassAround};
//! use furrow::route::headland_graph::HeadlandGraph;
//! use geo::{coord, LineString};
//!
//! // One pass round a 100 m square, 3 m in.
//! let ring = LineString::from(vec![(3., 3.), (97., 3.), (97., 97.), (3., 97.), (3., 3.)]);
//! let passes = [HeadlandPass { index: 1, line: ring, closed: true, around: PassAround::Field }];
//! let graph = HeadlandGraph::new(&passes, 6.0);
//! // Two swath ends 3 m inside the pass, on opposite sides of the field.
//! let ends = [coord! { x: 10.0, y: 6.0 }, coord! { x: 10.0, y: 94.0 }];
//! let c = graph.connect(&ends);
//! let d = c.distance(0, 1);
//! // Along the west side: 3 + 7 + 94 + 7 + 3 m.
//! assert!((d - 114.0).abs() < 1e-9);
//! assert!(c.line(0, 1).is_some());
//! ```

use crate::geometry::{
    point_segment_distance, segment_foot, Extremes, IndexedSegment, PlanarHypot,
};
use crate::headland::HeadlandPass;
use crate::sort::SharedSort;
use geo::{Coord, LineString, MultiPolygon};
use rstar::{RTree, AABB};
use std::cell::{Cell, RefCell};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Added to the length of a connection that has to cross the inner field (metres): more than any
/// plan drives, so that the block sequence takes such a connection only when there is no other
/// way.
pub const CROSSING_PENALTY_M: f64 = 1e7;

/// The most nodes the searches for [`Connections::line`] settle, together: once they have,
/// the lines not found yet count as not found (the route then connects straight, and warns).
/// A route searches a line for each connection, and where the headland has none after the
/// swaths, another along the swaths' tracks: a field with 1,000 ponds, islands in the crop each
/// with its own passes, searched the tracks (85,000 nodes) 2,000 times, settling 22 million
/// nodes (over 10 s). A node settles in about half a microsecond natively, so that at this
/// bound a route's searches take about a second at most. A corpus route settles at most 1,100
/// nodes along the headland and 21,400 along the tracks.
pub const MAX_LINE_SEARCH_NODES: usize = 1_000_000;

/// How far (in working widths) a point may be from the nearest line to join it by a spur: a
/// swath end lies half a width inside the innermost pass.
const SPUR_WIDTHS: f64 = 1.5;
/// How far apart (in working widths) two lines may be for a hop between them: neighbouring
/// passes are one width apart.
const HOP_WIDTHS: f64 = 1.05;
/// How far apart (in working widths) two neighbouring passes round the same thing may be for a
/// hop: up to √2 widths at a right-angled corner rounded to the same radius.
const CORNER_HOP_WIDTHS: f64 = 1.5;

/// One segment of a line, for the nearest-point search (`line` the graph's line).
type Segment = IndexedSegment;

/// A line of the graph: a pass's centre line with the distance along it at each point.
#[derive(Debug, Clone)]
struct GraphLine {
    points: Vec<Coord>,
    /// Distance along the line at each point, metres.
    at: Vec<f64>,
    closed: bool,
    /// The pass's index and what it runs round; `None` for a track.
    pass: Option<(usize, crate::headland::PassAround)>,
    /// Its place among the passes (or, after them, the tracks) the graph was made of.
    source: usize,
}

impl GraphLine {
    fn length(&self) -> f64 {
        self.at.last().copied().unwrap_or(0.0)
    }

    /// The line from distance `from` to distance `to` along it, forwards (wrapping round a
    /// closed line when `to < from`).
    fn piece(&self, from: f64, to: f64) -> Vec<Coord> {
        let mut out = vec![self.point_at(from)];
        if to >= from {
            out.extend(
                self.at
                    .iter()
                    .zip(&self.points)
                    .filter(|(&a, _)| a > from && a < to)
                    .map(|(_, &p)| p),
            );
        } else {
            out.extend(
                self.at
                    .iter()
                    .zip(&self.points)
                    .filter(|(&a, _)| a > from)
                    .map(|(_, &p)| p),
            );
            out.extend(
                self.at
                    .iter()
                    .zip(&self.points)
                    .skip(1)
                    .filter(|(&a, _)| a < to)
                    .map(|(_, &p)| p),
            );
        }
        out.push(self.point_at(to));
        out
    }

    fn point_at(&self, s: f64) -> Coord {
        let i = self
            .at
            .partition_point(|&a| a <= s)
            .clamp(1, self.at.len().max(2) - 1);
        match (self.points.get(i - 1), self.points.get(i)) {
            (Some(&a), Some(&b)) => {
                let span = self.at[i] - self.at[i - 1];
                let t = if span > 0.0 {
                    ((s - self.at[i - 1]) / span).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                a + (b - a) * t
            }
            (Some(&a), None) => a,
            _ => Coord { x: 0.0, y: 0.0 },
        }
    }
}

/// The lines a machine may drive along between blocks, indexed for nearest-point search.
#[derive(Debug, Clone)]
pub struct HeadlandGraph {
    lines: Vec<GraphLine>,
    tree: RTree<Segment>,
    width: f64,
    /// The crop no hop may cross, if given ([`HeadlandGraph::with_crop`]).
    crop: Option<Crop>,
}

/// How deep (metres) a hop may reach into the crop: a pass rounded at the turning radius cuts
/// the sharp corners of the inner field by a little.
const CROP_TOLERANCE_M: f64 = 0.05;

/// The crop standing while the machine moves between blocks (the inner field), its edges
/// indexed.
#[derive(Debug, Clone)]
struct Crop {
    edges: RTree<Segment>,
}

impl Crop {
    fn new(area: &MultiPolygon) -> Self {
        let mut edges = Vec::new();
        for p in &area.0 {
            for ring in std::iter::once(p.exterior()).chain(p.interiors()) {
                for (index, w) in ring.0.windows(2).enumerate() {
                    edges.push(Segment::new(w[0], w[1], 0, index));
                }
            }
        }
        Crop {
            edges: RTree::bulk_load(edges),
        }
    }

    /// Whether the straight way from `a` to `b` runs through the crop deeper than
    /// [`CROP_TOLERANCE_M`]: it is cut where it crosses the crop's edges, and each piece longer
    /// than the tolerance is tested at its middle. (`geometry::clip_segment` gives the pieces
    /// too, but projects and sorts every edge of the field at each call: a hop meets a few.)
    fn crossed_by(&self, a: Coord, b: Coord) -> bool {
        let t = CROP_TOLERANCE_M;
        let envelope = AABB::from_corners(
            [a.x.lesser(b.x) - t, a.y.lesser(b.y) - t],
            [a.x.greater(b.x) + t, a.y.greater(b.y) + t],
        );
        let d = b - a;
        let length = d.x.planar_hypot(d.y);
        let mut cuts = vec![0.0, 1.0];
        for e in self.edges.locate_in_envelope_intersecting(&envelope) {
            let f = e.b - e.a;
            let denominator = d.x * f.y - d.y * f.x;
            if denominator.abs() < 1e-12 {
                continue;
            }
            let g = e.a - a;
            let along = (g.x * f.y - g.y * f.x) / denominator;
            let on_edge = (g.x * d.y - g.y * d.x) / denominator;
            if (0.0..=1.0).contains(&along) && (0.0..=1.0).contains(&on_edge) {
                cuts.push(along);
            }
        }
        cuts.shared_sort_by(f64::total_cmp);
        cuts.windows(2).any(|w| {
            if (w[1] - w[0]) * length <= 2.0 * t {
                return false;
            }
            let m = a + d * ((w[0] + w[1]) / 2.0);
            let deep = self
                .edges
                .nearest_neighbor(&[m.x, m.y])
                .is_none_or(|e| point_segment_distance(m, e.a, e.b) > t);
            deep && self.holds(m)
        })
    }

    /// Whether the crop holds `p`, a point farther than [`CROP_TOLERANCE_M`] from its edges:
    /// the rings' edges crossed by the ray east from `p`, counted in the R-tree (odd: inside; a
    /// point that far from every edge is on no edge, so the count is geo's `contains`, without
    /// walking every ring).
    fn holds(&self, p: Coord) -> bool {
        let east = self.edges.root().envelope().upper()[0] + 1.0;
        let ray = AABB::from_corners([p.x, p.y], [east.greater(p.x), p.y]);
        let crossings = self
            .edges
            .locate_in_envelope_intersecting(&ray)
            .filter(|e| {
                (e.a.y > p.y) != (e.b.y > p.y)
                    && e.a.x + (p.y - e.a.y) * (e.b.x - e.a.x) / (e.b.y - e.a.y) > p.x
            })
            .count();
        crossings % 2 == 1
    }
}

impl HeadlandGraph {
    /// The graph of the passes' centre lines, for a machine of working width `width`.
    pub fn new(passes: &[HeadlandPass], width: f64) -> Self {
        Self::with_tracks(passes, &[], width)
    }

    /// The graph of the passes' centre lines and of `tracks`: open lines the machine may also
    /// drive along, such as swaths already worked.
    pub fn with_tracks(passes: &[HeadlandPass], tracks: &[LineString], width: f64) -> Self {
        let mut lines = Vec::with_capacity(passes.len() + tracks.len());
        let mut segments = Vec::new();
        let all = passes
            .iter()
            .map(|p| (&p.line, p.closed, Some((p.index, p.around))))
            .chain(tracks.iter().map(|t| (t, false, None)));
        for (source, (line_string, closed, pass)) in all.enumerate() {
            let points = &line_string.0;
            if points.len() < 2 {
                continue;
            }
            let line = lines.len();
            let mut at = Vec::with_capacity(points.len());
            let mut s = 0.0;
            at.push(0.0);
            for (index, w) in points.windows(2).enumerate() {
                s += (w[1] - w[0]).x.planar_hypot((w[1] - w[0]).y);
                at.push(s);
                segments.push(Segment::new(w[0], w[1], line, index));
            }
            lines.push(GraphLine {
                points: points.clone(),
                at,
                closed,
                pass,
                source,
            });
        }
        HeadlandGraph {
            lines,
            tree: RTree::bulk_load(segments),
            width,
            crop: None,
        }
    }

    /// The graph with the crop its hops must not cross: the inner field, where the crop stands
    /// while the machine moves between blocks. A hop that would run through it (deeper than a
    /// few centimetres) is not made: two passes that come near each other across a narrow neck
    /// of the field are not joined across the crop.
    ///
    /// ```
    /// use furrow::headland::{HeadlandPass, PassAround};
    /// use furrow::route::headland_graph::HeadlandGraph;
    /// use geo::{coord, polygon, LineString, MultiPolygon};
    ///
    /// // Two passes 4 m apart, and between them, longer than they are, a 3 m strip of crop that
    /// // a 6 m machine would hop across.
    /// let west = LineString::from(vec![(0., 0.), (0., 100.)]);
    /// let east = LineString::from(vec![(4., 0.), (4., 100.)]);
    /// let passes = [
    ///     HeadlandPass { index: 1, line: west, closed: false, around: PassAround::Field },
    ///     HeadlandPass { index: 1, line: east, closed: false, around: PassAround::Field },
    /// ];
    /// let crop = polygon![(x: 0.5, y: -10.), (x: 3.5, y: -10.), (x: 3.5, y: 110.), (x: 0.5, y: 110.)];
    /// let ends = [coord! { x: -1.0, y: 50.0 }, coord! { x: 5.0, y: 50.0 }];
    /// let open = HeadlandGraph::new(&passes, 6.0);
    /// assert!(open.connect(&ends).line(0, 1).is_some());
    /// let with_crop = HeadlandGraph::new(&passes, 6.0).with_crop(&MultiPolygon::new(vec![crop]));
    /// assert!(with_crop.connect(&ends).line(0, 1).is_none());
    /// ```
    pub fn with_crop(mut self, crop: &MultiPolygon) -> Self {
        self.crop = Some(Crop::new(crop));
        self
    }

    /// The passes of the graph (their places in the passes it was made of) by the distance of
    /// each of their segments from `p`, nearest first: a pass comes once for each segment, and
    /// passes of fewer than two points never.
    pub fn passes_by_distance(&self, p: Coord) -> impl Iterator<Item = (usize, f64)> + '_ {
        self.tree
            .nearest_neighbor_iter_with_distance_2(&[p.x, p.y])
            .filter_map(|(seg, d2)| {
                let line = &self.lines[seg.line];
                line.pass.map(|_| (line.source, d2.sqrt()))
            })
    }

    /// Whether the graph has no line at all (a field without headland passes).
    pub fn is_empty(&self) -> bool {
        self.lines.is_empty()
    }

    /// The nearest point of any line to `p` within `radius`: (line, distance along it, point).
    fn nearest(&self, p: Coord, radius: f64) -> Option<(usize, f64, Coord)> {
        let seg = self.tree.nearest_neighbor(&[p.x, p.y])?;
        let (foot, along) = segment_foot(p, seg.a, seg.b);
        let d = (foot - p).x.planar_hypot((foot - p).y);
        (d <= radius).then(|| {
            let at = self.lines[seg.line].at[seg.index] + along;
            (seg.line, at, foot)
        })
    }

    /// Whether a point joins the graph: whether a line of it is within a spur's reach (one and a
    /// half widths).
    ///
    /// ```
    /// use furrow::headland::{HeadlandPass, PassAround};
    /// use furrow::route::headland_graph::HeadlandGraph;
    /// use geo::{coord, LineString};
    ///
    /// let line = LineString::from(vec![(0., 0.), (100., 0.)]);
    /// let passes = [HeadlandPass { index: 1, line, closed: false, around: PassAround::Field }];
    /// let graph = HeadlandGraph::new(&passes, 6.0);
    /// assert!(graph.reaches(coord! { x: 50.0, y: 8.9 }));
    /// assert!(!graph.reaches(coord! { x: 50.0, y: 9.1 }));
    /// ```
    pub fn reaches(&self, p: Coord) -> bool {
        self.nearest(p, SPUR_WIDTHS * self.width + 1e-6).is_some()
    }

    /// The graph between these points (swath ends, the entrance and the exit): each joins by a
    /// spur of at most one and a half widths, or `unlimited` for the points in that set (the
    /// user's entrance and exit, which may lie anywhere).
    pub fn connect(&self, points: &[Coord]) -> Connections<'_> {
        self.connect_with(points, &[])
    }

    /// [`connect`](Self::connect), with the points of index in `unlimited` joining the nearest
    /// line however far it is.
    pub fn connect_with(&self, points: &[Coord], unlimited: &[usize]) -> Connections<'_> {
        let mut nodes: Vec<Node> = Vec::new();
        let mut spurs: Vec<Option<(usize, f64)>> = Vec::with_capacity(points.len());
        for (i, &p) in points.iter().enumerate() {
            let radius = if unlimited.contains(&i) {
                f64::INFINITY
            } else {
                SPUR_WIDTHS * self.width + 1e-6
            };
            match self.nearest(p, radius) {
                Some((line, at, foot)) => {
                    spurs.push(Some((nodes.len(), (foot - p).x.planar_hypot((foot - p).y))));
                    nodes.push(Node {
                        line,
                        at,
                        point: foot,
                    });
                }
                None => spurs.push(None),
            }
        }
        // The ends of open lines join the lines beside them.
        for (line, l) in self.lines.iter().enumerate() {
            if !l.closed {
                for (at, point) in [
                    (0.0, l.points[0]),
                    (l.length(), l.points[l.points.len() - 1]),
                ] {
                    nodes.push(Node { line, at, point });
                }
            }
        }
        // Hops from every node so far to the nearest point of each other line within reach.
        let reach = HOP_WIDTHS * self.width + 1e-6;
        let corner_reach = CORNER_HOP_WIDTHS * self.width + 1e-6;
        let neighbours = |a: usize, b: usize| match (self.lines[a].pass, self.lines[b].pass) {
            (Some((i, x)), Some((j, y))) => x == y && i.abs_diff(j) == 1,
            _ => false,
        };
        let mut hops: Vec<(usize, usize, f64)> = Vec::new();
        let base = nodes.len();
        for n in 0..base {
            let Node { line, point, .. } = nodes[n];
            let mut best: Vec<(usize, f64, f64, Coord)> = Vec::new(); // (line, distance, at, foot)
            for seg in self
                .tree
                .locate_within_distance([point.x, point.y], corner_reach * corner_reach)
            {
                if seg.line == line {
                    continue;
                }
                let (foot, along) = segment_foot(point, seg.a, seg.b);
                let d = (foot - point).x.planar_hypot((foot - point).y);
                if d > reach && !neighbours(line, seg.line) {
                    continue;
                }
                let at = self.lines[seg.line].at[seg.index] + along;
                match best.iter_mut().find(|b| b.0 == seg.line) {
                    Some(b) if d < b.1 => *b = (seg.line, d, at, foot),
                    Some(_) => {}
                    None => best.push((seg.line, d, at, foot)),
                }
            }
            for (other, d, at, foot) in best {
                if self
                    .crop
                    .as_ref()
                    .is_some_and(|c| c.crossed_by(point, foot))
                {
                    continue;
                }
                hops.push((n, nodes.len(), d));
                nodes.push(Node {
                    line: other,
                    at,
                    point: foot,
                });
            }
        }
        // Edges along each line between consecutive nodes, and the hops.
        let mut edges: Vec<Vec<Edge>> = vec![Vec::new(); nodes.len()];
        let mut on_line: Vec<Vec<usize>> = vec![Vec::new(); self.lines.len()];
        for (n, node) in nodes.iter().enumerate() {
            on_line[node.line].push(n);
        }
        for (line, ids) in on_line.iter_mut().enumerate() {
            ids.shared_sort_by(|&a, &b| nodes[a].at.total_cmp(&nodes[b].at));
            let l = &self.lines[line];
            for w in ids.windows(2) {
                let len = nodes[w[1]].at - nodes[w[0]].at;
                edges[w[0]].push(Edge {
                    to: w[1],
                    cost: len,
                    way: EdgeWay::Forward,
                });
                edges[w[1]].push(Edge {
                    to: w[0],
                    cost: len,
                    way: EdgeWay::Backward,
                });
            }
            if l.closed && ids.len() > 1 {
                if let (Some(&last), Some(&first)) = (ids.last(), ids.first()) {
                    let len = l.length() - nodes[last].at + nodes[first].at;
                    edges[last].push(Edge {
                        to: first,
                        cost: len,
                        way: EdgeWay::Forward,
                    });
                    edges[first].push(Edge {
                        to: last,
                        cost: len,
                        way: EdgeWay::Backward,
                    });
                }
            }
        }
        for (a, b, d) in hops {
            edges[a].push(Edge {
                to: b,
                cost: d,
                way: EdgeWay::Hop,
            });
            edges[b].push(Edge {
                to: a,
                cost: d,
                way: EdgeWay::Hop,
            });
        }
        Connections {
            graph: self,
            points: points.to_vec(),
            spurs,
            nodes,
            edges,
            scratch: RefCell::new(Scratch::default()),
            line_work: Cell::new(MAX_LINE_SEARCH_NODES),
        }
    }
}

#[derive(Debug, Clone, Copy)]
struct Node {
    line: usize,
    at: f64,
    point: Coord,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum EdgeWay {
    /// Along the line, the way its points run.
    Forward,
    /// Along the line, against its points.
    Backward,
    /// Straight across to another line.
    Hop,
}

#[derive(Debug, Clone, Copy)]
struct Edge {
    to: usize,
    cost: f64,
    way: EdgeWay,
}

/// The graph between a set of points: their connection distances and lines.
#[derive(Debug, Clone)]
pub struct Connections<'a> {
    graph: &'a HeadlandGraph,
    points: Vec<Coord>,
    /// Each point's spur: its node and length, or `None` when no line is near enough.
    spurs: Vec<Option<(usize, f64)>>,
    nodes: Vec<Node>,
    edges: Vec<Vec<Edge>>,
    /// The tables every search works in (see `search`).
    scratch: RefCell<Scratch>,
    /// The nodes the searches of [`line`](Self::line) may still settle, of
    /// [`MAX_LINE_SEARCH_NODES`].
    line_work: Cell<usize>,
}

/// A search's tables, by node: the distance from the source (infinite where not reached), the
/// edge each node was reached by, whether it is a target not yet settled; the nodes reached, and
/// the queue.
#[derive(Debug, Clone, Default)]
struct Scratch {
    dist: Vec<f64>,
    came: Vec<Option<(usize, Edge)>>,
    wanted: Vec<bool>,
    reached: Vec<usize>,
    heap: BinaryHeap<Queued>,
}

#[derive(Debug, Clone, Copy, PartialEq)]
struct Queued(f64, usize);
impl Eq for Queued {}
impl Ord for Queued {
    fn cmp(&self, other: &Self) -> Ordering {
        other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
    }
}
impl PartialOrd for Queued {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Connections<'_> {
    /// Shortest distances from node `source` to the nodes `targets`, and the edge each node on
    /// the way was reached by, handed to `read`. The search ends once every target is settled:
    /// their distances and the edges back to `source` are then final, as a search of the whole
    /// graph would leave them (a settled node's entries never change again); other nodes' may
    /// be larger, and those it did not reach are infinite and `None`. It settles at most
    /// `budget` nodes, and takes those it settles off it: the targets not settled by then count
    /// as not reached.
    ///
    /// The tables are the connections' own, reused by every search and cleared after each where
    /// it wrote (a fresh table for each search made the route of a field with thousands of
    /// blocks quadratic in them).
    fn search<R>(
        &self,
        source: usize,
        targets: &[usize],
        budget: &Cell<usize>,
        read: impl FnOnce(&[f64], &[Option<(usize, Edge)>]) -> R,
    ) -> R {
        let n = self.nodes.len();
        let mut guard = self.scratch.borrow_mut();
        let Scratch {
            dist,
            came,
            wanted,
            reached,
            heap,
        } = &mut *guard;
        if dist.len() != n {
            *dist = vec![f64::INFINITY; n];
            *came = vec![None; n];
            *wanted = vec![false; n];
        }
        let mut left = 0;
        for &t in targets {
            if let Some(w) = wanted.get_mut(t).filter(|w| !**w) {
                *w = true;
                left += 1;
            }
        }
        if source < n && left > 0 {
            dist[source] = 0.0;
            reached.push(source);
            heap.push(Queued(0.0, source));
        }
        let mut left_to_settle = budget.get();
        while let Some(Queued(d, u)) = heap.pop() {
            if d > dist[u] {
                continue;
            }
            if left_to_settle == 0 {
                // Out of work: the targets not settled count as not reached.
                for &t in targets {
                    if wanted.get(t) == Some(&true) {
                        dist[t] = f64::INFINITY;
                    }
                }
                break;
            }
            left_to_settle -= 1;
            if wanted[u] {
                wanted[u] = false;
                left -= 1;
                if left == 0 {
                    break;
                }
            }
            for e in &self.edges[u] {
                let nd = d + e.cost;
                if nd < dist[e.to] {
                    if dist[e.to] == f64::INFINITY {
                        reached.push(e.to);
                    }
                    dist[e.to] = nd;
                    came[e.to] = Some((u, *e));
                    heap.push(Queued(nd, e.to));
                }
            }
        }
        budget.set(left_to_settle);
        let out = read(dist, came);
        for &v in reached.iter() {
            dist[v] = f64::INFINITY;
            came[v] = None;
        }
        for &t in targets {
            if let Some(w) = wanted.get_mut(t) {
                *w = false;
            }
        }
        reached.clear();
        heap.clear();
        out
    }

    /// The number of nodes a search may settle: the points' feet on the lines, the open lines'
    /// ends and the hops' ends.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Whether point `i` joins the graph.
    pub fn is_joined(&self, i: usize) -> bool {
        matches!(self.spurs.get(i), Some(Some(_)))
    }

    /// The length of the shortest way from point `from` to each point in `to`, through the
    /// graph; `None` where there is no way (a point not joined, or lines that never meet).
    pub fn distances(&self, from: usize, to: &[usize]) -> Vec<Option<f64>> {
        let Some(&Some((source, spur))) = self.spurs.get(from) else {
            return vec![None; to.len()];
        };
        let targets: Vec<usize> = to
            .iter()
            .filter_map(|&t| self.spurs.get(t).copied().flatten().map(|(node, _)| node))
            .collect();
        self.search(source, &targets, &Cell::new(usize::MAX), |dist, _| {
            to.iter()
                .map(|&t| match self.spurs.get(t) {
                    Some(&Some((node, back))) if dist[node].is_finite() => {
                        Some(spur + dist[node] + back)
                    }
                    _ => None,
                })
                .collect()
        })
    }

    /// The shortest way between two points through the graph (as [`distances`](Self::distances)),
    /// or straight across with [`CROSSING_PENALTY_M`] added where there is none.
    pub fn distance(&self, from: usize, to: usize) -> f64 {
        match self.distances(from, &[to]).first() {
            Some(&Some(d)) => d,
            _ => match (self.points.get(from), self.points.get(to)) {
                (Some(&a), Some(&b)) => (b - a).x.planar_hypot((b - a).y) + CROSSING_PENALTY_M,
                _ => CROSSING_PENALTY_M,
            },
        }
    }

    /// The line of the shortest way from point `from` to point `to` through the graph, from the
    /// one to the other; `None` where there is none.
    pub fn line(&self, from: usize, to: usize) -> Option<LineString> {
        let &Some((source, _)) = self.spurs.get(from)? else {
            return None;
        };
        let &Some((target, _)) = self.spurs.get(to)? else {
            return None;
        };
        // The nodes of the way back from the target.
        let budget = &self.line_work;
        let back: Vec<(usize, usize, Edge)> =
            self.search(source, &[target], budget, |dist, came| {
                if !dist.get(target)?.is_finite() {
                    return None;
                }
                let mut way = Vec::new();
                let mut v = target;
                while v != source {
                    let (u, e) = came[v]?;
                    way.push((u, v, e));
                    v = u;
                }
                Some(way)
            })?;
        // Walk back from the target, collecting the pieces.
        let mut pieces: Vec<Vec<Coord>> = Vec::new();
        for (u, v, e) in back {
            let (a, b) = (self.nodes[u], self.nodes[v]);
            let l = &self.graph.lines[a.line];
            pieces.push(match e.way {
                EdgeWay::Hop => vec![a.point, b.point],
                EdgeWay::Forward => l.piece(a.at, b.at),
                EdgeWay::Backward => {
                    let mut p = l.piece(b.at, a.at);
                    p.reverse();
                    p
                }
            });
        }
        let mut out: Vec<Coord> = vec![self.points[from]];
        for piece in pieces.into_iter().rev() {
            out.extend(piece);
        }
        out.push(self.points[to]);
        out.dedup_by(|a, b| (a.x - b.x).planar_hypot(a.y - b.y) < 1e-9);
        Some(LineString::new(out))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::headland::PassAround;
    use geo::{coord, polygon, Euclidean, Length};

    fn ring(d: f64, size: f64) -> LineString {
        LineString::from(vec![
            (d, d),
            (size - d, d),
            (size - d, size - d),
            (d, size - d),
            (d, d),
        ])
    }

    fn pass(index: usize, line: LineString, closed: bool) -> HeadlandPass {
        HeadlandPass {
            index,
            line,
            closed,
            around: PassAround::Field,
        }
    }

    /// A 100 m square of crop with a 20 m square hole (an obstacle's headland) in its middle.
    fn square_crop() -> Crop {
        let outer = ring(0.0, 100.0);
        let hole = ring(40.0, 100.0);
        Crop::new(&MultiPolygon::new(vec![geo::Polygon::new(
            outer,
            vec![hole],
        )]))
    }

    #[test]
    fn a_way_through_the_crop_crosses_it_and_one_round_it_does_not() {
        let crop = square_crop();
        // Outside, along the south edge 3 m out.
        assert!(!crop.crossed_by(coord! { x: -3.0, y: -3.0 }, coord! { x: 103.0, y: -3.0 }));
        // From outside into the crop, and across it.
        assert!(crop.crossed_by(coord! { x: -3.0, y: 50.0 }, coord! { x: 10.0, y: 50.0 }));
        assert!(crop.crossed_by(coord! { x: -3.0, y: 50.0 }, coord! { x: 103.0, y: 50.0 }));
        // Within the hole, and from the hole's edge into it.
        assert!(!crop.crossed_by(coord! { x: 42.0, y: 42.0 }, coord! { x: 58.0, y: 58.0 }));
        assert!(!crop.crossed_by(coord! { x: 40.0, y: 50.0 }, coord! { x: 55.0, y: 45.0 }));
        // Along an edge, and across the field's corner by less than the tolerance: not
        // crossings.
        assert!(!crop.crossed_by(coord! { x: 0.0, y: 10.0 }, coord! { x: 0.0, y: 90.0 }));
        assert!(!crop.crossed_by(coord! { x: -1.0, y: 1.02 }, coord! { x: 1.02, y: -1.0 }));
        // Across the same corner 1.4 m deep: a crossing.
        assert!(crop.crossed_by(coord! { x: -1.0, y: 3.0 }, coord! { x: 3.0, y: -1.0 }));
    }

    /// The square of side `side` from (`x`, `y`).
    fn square(x: f64, y: f64, side: f64) -> LineString {
        LineString::from(vec![
            (x, y),
            (x + side, y),
            (x + side, y + side),
            (x, y + side),
            (x, y),
        ])
    }

    #[test]
    fn the_crop_holds_what_geo_says_it_contains() {
        use geo::Contains;
        // A field with a bay and two ponds, one pond with an island of crop in it; points on a
        // grid that meets vertices and edges, those farther than the tolerance from every edge.
        let field = geo::Polygon::new(
            LineString::from(vec![
                (0., 0.),
                (100., 0.),
                (100., 100.),
                (60., 100.),
                (60., 40.),
                (40., 40.),
                (40., 100.),
                (0., 100.),
                (0., 0.),
            ]),
            vec![square(10.0, 10.0, 20.0), square(65.0, 10.0, 30.0)],
        );
        let island = geo::Polygon::new(square(72.0, 17.0, 16.0), vec![]);
        let area = MultiPolygon::new(vec![field, island]);
        let crop = Crop::new(&area);
        let mut tested = 0;
        for i in -4..=208 {
            for j in -4..=208 {
                let p = coord! { x: i as f64 * 0.5, y: j as f64 * 0.5 + 0.25 };
                let deep = crop
                    .edges
                    .nearest_neighbor(&[p.x, p.y])
                    .is_none_or(|e| point_segment_distance(p, e.a, e.b) > CROP_TOLERANCE_M);
                if deep {
                    tested += 1;
                    assert_eq!(crop.holds(p), area.contains(&p), "{p:?}");
                }
            }
        }
        assert!(tested > 40_000);
        assert!(!Crop::new(&MultiPolygon::new(vec![])).holds(coord! { x: 1.0, y: 1.0 }));
    }

    #[test]
    fn a_hop_across_the_crop_is_not_made() {
        // Two passes round the field 3 m apart and, between them along the west side, a strip of
        // crop 1 m wide: two points beside the west side are a hop apart, but not across the
        // strip. With no other way between the passes, they are joined straight, at the
        // crossing penalty.
        let outer = ring(0.0, 100.0);
        let inner = ring(3.0, 100.0);
        let passes = [pass(1, outer, true), pass(2, inner, true)];
        let strip =
            polygon![(x: 1.0, y: 10.), (x: 2.0, y: 10.), (x: 2.0, y: 90.), (x: 1.0, y: 90.)];
        let ends = [coord! { x: -1.0, y: 50.0 }, coord! { x: 4.0, y: 50.0 }];
        let plain = HeadlandGraph::new(&passes, 6.0);
        let cropped = HeadlandGraph::new(&passes, 6.0).with_crop(&MultiPolygon::new(vec![strip]));
        let (near, round) = (plain.connect(&ends), cropped.connect(&ends));
        assert!((near.distance(0, 1) - 5.0).abs() < 1e-9);
        assert!(near.line(0, 1).is_some());
        assert!(round.distance(0, 1) >= CROSSING_PENALTY_M);
        assert!(round.line(0, 1).is_none());
        // Beyond the strip's end the same hop is made.
        let north = [coord! { x: -1.0, y: 95.0 }, coord! { x: 4.0, y: 95.0 }];
        assert!((cropped.connect(&north).distance(0, 1) - 5.0).abs() < 1e-9);
    }

    #[test]
    fn the_line_runs_the_shorter_way_round_and_has_the_distance_s_length() {
        let passes = [pass(1, ring(3.0, 100.0), true)];
        let g = HeadlandGraph::new(&passes, 6.0);
        // Near the south-east and the north-east corners: the way round the east side.
        let ends = [coord! { x: 90.0, y: 6.0 }, coord! { x: 94.0, y: 80.0 }];
        let c = g.connect(&ends);
        let d = c.distance(0, 1);
        assert!((d - (3.0 + 7.0 + 77.0 + 3.0)).abs() < 1e-9, "{d}");
        let line = c.line(0, 1).unwrap();
        assert!((Euclidean.length(&line) - d).abs() < 1e-9);
        assert_eq!(line.0.first(), Some(&ends[0]));
        assert_eq!(line.0.last(), Some(&ends[1]));
        // And back, the same way.
        assert!((c.distance(1, 0) - d).abs() < 1e-9);
    }

    #[test]
    fn a_search_ended_at_its_targets_finds_their_ways_as_a_search_of_the_whole_graph() {
        // Three rings of passes round a field with an obstacle's pass, and points all about.
        let passes = [
            pass(1, ring(3.0, 100.0), true),
            pass(2, ring(9.0, 100.0), true),
            pass(3, ring(15.0, 100.0), true),
            pass(4, ring(44.0, 100.0), true),
        ];
        let g = HeadlandGraph::new(&passes, 6.0);
        let points: Vec<Coord> = (0..24)
            .map(|i| {
                let t = i as f64 * 0.7;
                coord! { x: 50.0 + 47.0 * t.cos(), y: 50.0 + 47.0 * t.sin() * (1.0 - 0.03 * i as f64) }
            })
            .collect();
        let c = g.connect(&points);
        let every: Vec<usize> = (0..c.nodes.len()).collect();
        let mut ended_early = 0;
        let unlimited = Cell::new(usize::MAX);
        let tables = |d: &[f64], c: &[Option<(usize, Edge)>]| (d.to_vec(), c.to_vec());
        for source in 0..c.nodes.len() {
            let (all_dist, all_came) = c.search(source, &every, &unlimited, tables);
            for target in (0..c.nodes.len()).step_by(3) {
                let (dist, came) = c.search(source, &[target], &unlimited, tables);
                assert_eq!(dist[target].to_bits(), all_dist[target].to_bits());
                // The way back from the target, edge by edge.
                let mut v = target;
                while v != source {
                    let Some((u, e)) = came[v] else {
                        assert!(all_came[v].is_none() && !dist[target].is_finite());
                        break;
                    };
                    let (au, ae) = all_came[v].expect("the whole search reaches it too");
                    assert_eq!((u, e.to, e.cost.to_bits()), (au, ae.to, ae.cost.to_bits()));
                    v = u;
                }
                ended_early += usize::from(
                    dist.iter().filter(|d| d.is_finite()).count()
                        < all_dist.iter().filter(|d| d.is_finite()).count(),
                );
            }
        }
        assert!(ended_early > 0, "some searches end before the whole graph");
        // The searches for lines stop once they have settled their budget of nodes between
        // them: the lines not found by then are not found.
        let (a, b) = (0..points.len())
            .flat_map(|a| (0..points.len()).map(move |b| (a, b)))
            .filter(|&(a, b)| c.line(a, b).is_some())
            .max_by(|x, y| c.distance(x.0, x.1).total_cmp(&c.distance(y.0, y.1)))
            .expect("ways");
        c.line_work.set(MAX_LINE_SEARCH_NODES);
        let far = c.line(a, b).expect("a way");
        let spent = MAX_LINE_SEARCH_NODES - c.line_work.get();
        assert!(spent > 3);
        c.line_work.set(spent - 1);
        assert_eq!(c.line(a, b), None);
        assert_eq!(c.line_work.get(), 0);
        assert_eq!(c.line(b, a), None);
        c.line_work.set(spent);
        assert_eq!(c.line(a, b), Some(far));
        // And the distances between the points, one target or many.
        let everyone: Vec<usize> = (0..points.len()).collect();
        for from in 0..points.len() {
            let many = c.distances(from, &everyone);
            for (to, &d) in many.iter().enumerate() {
                assert_eq!(c.distances(from, &[to]), vec![d]);
            }
        }
    }

    #[test]
    fn a_hop_joins_neighbouring_passes_and_open_passes() {
        // Two open passes along the west and east ends, and a ring pass 6 m outside them.
        let west = LineString::from(vec![(9.0, 9.0), (9.0, 91.0)]);
        let east = LineString::from(vec![(91.0, 9.0), (91.0, 91.0)]);
        let passes = [
            pass(1, ring(3.0, 100.0), true),
            pass(2, west, false),
            pass(2, east, false),
        ];
        let g = HeadlandGraph::new(&passes, 6.0);
        let ends = [coord! { x: 12.0, y: 50.0 }, coord! { x: 88.0, y: 50.0 }];
        let c = g.connect(&ends);
        let d = c.distance(0, 1);
        // Out to the west pass, to its end, hop to the ring, along it, hop, and in.
        assert!(d < CROSSING_PENALTY_M);
        let line = c.line(0, 1).unwrap();
        assert!((Euclidean.length(&line) - d).abs() < 1e-6);
        assert!(d > 76.0 + 2.0 * 41.0);
    }

    #[test]
    fn lines_that_never_meet_are_crossed_at_a_penalty() {
        let passes = [
            pass(1, ring(3.0, 100.0), true),
            pass(1, ring(45.0, 100.0), true),
        ];
        let g = HeadlandGraph::new(&passes, 6.0);
        let ends = [coord! { x: 50.0, y: 6.0 }, coord! { x: 50.0, y: 42.0 }];
        let c = g.connect(&ends);
        assert!(c.distance(0, 1) > CROSSING_PENALTY_M);
        assert!(c.line(0, 1).is_none());
        // A point far from every line is not joined.
        let far = [coord! { x: 50.0, y: 25.0 }, coord! { x: 50.0, y: 6.0 }];
        let c = g.connect(&far);
        assert!(!c.is_joined(0));
        assert!(c.distance(0, 1) > CROSSING_PENALTY_M);
        // Unless it is the user's entrance.
        let c = g.connect_with(&far, &[0]);
        assert!(c.is_joined(0));
    }

    #[test]
    fn an_empty_graph_joins_nothing() {
        let g = HeadlandGraph::new(&[], 6.0);
        assert!(g.is_empty());
        let c = g.connect(&[coord! { x: 0.0, y: 0.0 }, coord! { x: 1.0, y: 0.0 }]);
        assert!(c.line(0, 1).is_none());
        assert!((c.distance(0, 1) - 1.0 - CROSSING_PENALTY_M).abs() < 1e-6);
        assert!(c.line(5, 7).is_none());
    }
}
