//! The path: the route as one continuous line the machine drives, segment by segment.
//!
//! Worked segments (swaths, headland passes) are joined by connectors: a `turn` between two
//! swaths of one block, a `connection` anywhere else (between blocks, onto the headland, from the
//! entrance and to the exit). Connections follow the lines the route found along the headland.
//! In this version a turn is the straight line between the two swath ends; drivable turns at the
//! machine's turning radius replace them in a later version (the summary already measures turns
//! by the turn model).

use crate::geometry::point_segment_distance;
use crate::headland::HeadlandPass;
use crate::route::{nearest_on_ring, Route, RouteStep};
use crate::swath::Swaths;
use geo::{Coord, Euclidean, Length, LineString};

/// What a segment of the path is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SegmentKind {
    /// Working along a swath.
    Swath,
    /// Working along a headland pass.
    HeadlandPass,
    /// Turning from the end of one swath to the next swath of the same block.
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
}

/// One segment of the path.
#[derive(Debug, Clone, PartialEq)]
pub struct PathSegment {
    /// What the segment is.
    pub kind: SegmentKind,
    /// Its line, in driving order.
    pub line: LineString,
    /// The route step it works (swaths and headland passes), as an index into `Route::steps`.
    pub step: Option<usize>,
}

impl PathSegment {
    /// Length of the segment, metres.
    pub fn length(&self) -> f64 {
        Euclidean.length(&self.line)
    }

    /// Whether the implement works along this segment.
    pub fn is_working(&self) -> bool {
        matches!(self.kind, SegmentKind::Swath | SegmentKind::HeadlandPass)
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

/// Builds the path of a route: worked segments joined by the route's connections, and by straight
/// turns between the swaths of a block.
///
/// ```
/// use furrow::{decompose::cluster_swaths, path::{build_path, SegmentKind}};
/// use furrow::{route::{plan_route, RouteSettings}, swath::generate};
/// use geo::{polygon, MultiPolygon};
///
/// let field = polygon![(x: 0., y: 0.), (x: 30., y: 0.), (x: 30., y: 100.), (x: 0., y: 100.)];
/// let swaths = generate(&MultiPolygon::new(vec![field]), 0.0, 6.0, 6.0)?;
/// let route = plan_route(&swaths, &cluster_swaths(&swaths), &[], &RouteSettings::default());
/// let path = build_path(&route, &swaths, &[]);
/// let turns = path.segments.iter().filter(|s| s.kind == SegmentKind::Turn).count();
/// assert_eq!(turns, 4); // five swaths, four turns between them
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn build_path(route: &Route, swaths: &Swaths, passes: &[HeadlandPass]) -> Path {
    let mut segments: Vec<PathSegment> = Vec::with_capacity(route.steps.len() * 2);
    let mut last: Option<(Coord, Option<usize>)> = None; // (position, block of the last swath)
    for (k, step) in route.steps.iter().enumerate() {
        let (line, kind, block) = match *step {
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
                (LineString::new(vec![a, b]), SegmentKind::Swath, Some(block))
            }
            RouteStep::HeadlandPass { pass, reversed } => {
                let Some(p) = passes.get(pass) else {
                    continue;
                };
                let line = if p.closed {
                    // Where the connection into it ends, else where the machine is.
                    let at = route
                        .connections
                        .get(k)
                        .and_then(|c| c.as_ref())
                        .and_then(|c| c.line.0.last().copied())
                        .or(last.map(|l| l.0));
                    let (_, entry) = nearest_on_ring(&p.line, at);
                    ring_starting_at(&p.line, entry)
                } else if reversed {
                    LineString::new(p.line.0.iter().rev().copied().collect())
                } else {
                    p.line.clone()
                };
                (line, SegmentKind::HeadlandPass, None)
            }
        };
        let (Some(&start), Some(&end)) = (line.0.first(), line.0.last()) else {
            continue;
        };
        if let Some(Some(c)) = route.connections.get(k) {
            segments.push(PathSegment {
                kind: SegmentKind::Connection,
                line: c.line.clone(),
                step: None,
            });
        } else if let Some((from, from_block)) = last {
            if (from.x - start.x).hypot(from.y - start.y) > MIN_CONNECTOR_M {
                let kind = if block.is_some() && block == from_block {
                    SegmentKind::Turn
                } else {
                    SegmentKind::Connection
                };
                segments.push(PathSegment {
                    kind,
                    line: LineString::new(vec![from, start]),
                    step: None,
                });
            }
        }
        segments.push(PathSegment {
            kind,
            line,
            step: Some(k),
        });
        last = Some((end, block));
    }
    if let Some(c) = &route.finish {
        segments.push(PathSegment {
            kind: SegmentKind::Connection,
            line: c.line.clone(),
            step: None,
        });
    }
    Path { segments }
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
    out.dedup_by(|a, b| (a.x - b.x).hypot(a.y - b.y) < MIN_CONNECTOR_M);
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
        let path = build_path(&route, &swaths, &passes);
        for w in path.segments.windows(2) {
            let a = *w[0].line.0.last().unwrap();
            let b = w[1].line.0[0];
            assert!((a.x - b.x).hypot(a.y - b.y) < 1e-9);
        }
        assert_eq!(path.count_of(SegmentKind::HeadlandPass), 1);
        assert_eq!(path.count_of(SegmentKind::Connection), 1);
    }
}
