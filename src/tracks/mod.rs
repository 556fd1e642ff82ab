//! Tracks: the lines a plan leaves in the field (swaths, headland passes, turns, connections),
//! which a machine can drive again later without crushing new crop, and the shortest way along
//! them from where the machine is to the field's edge (Plessen & Bemporad, 2016).
//!
//! - [`lanes`]: the plan's working lanes, swaths and headland passes;
//! - [`graph`]: the track graph, every drivable line of the plan and where they meet;
//! - [`search`]: shortest paths over it under three ways of turning;
//! - [`lcamod`]: the paper's own method (LCAmod with restarts, Algorithm 1), for comparison;
//! - [`geojson`]: the same in the API's terms (input coordinates, compass degrees, GeoJSON).
//!
//! ```
//! use furrow::{plan_geojson, PlanOptions};
//! use furrow::tracks::{from_plan, shortest_path, TrackQuery, Turning};
//! use geo::coord;
//!
//! let text = r#"{"type": "Polygon", "coordinates": [[[0, 0], [300, 0], [300, 200], [0, 200], [0, 0]]]}"#;
//! let options = PlanOptions::from_json_str(r#"{"coordinates": "metric", "width": 6, "turnRadius": 6}"#)?;
//! let plan = plan_geojson(text, &options)?;
//! let graph = from_plan(&plan);
//! // From the middle of the field, facing north, to the south-west corner.
//! let query = TrackQuery {
//!     from: coord! { x: 150.0, y: 100.0 },
//!     heading: std::f64::consts::FRAC_PI_2,
//!     targets: vec![coord! { x: 0.0, y: 0.0 }],
//!     turning: Turning::Tracks,
//!     ..TrackQuery::default()
//! };
//! let path = shortest_path(&graph, &query)?;
//! assert!(path.length >= 150.0 + 100.0 - 20.0, "at least the way across, less the headland");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod geojson;
pub mod graph;
pub mod lcamod;
pub mod search;

pub use geojson::PlanTracks;
pub use graph::{Junction, Node, Track, TrackGraph, TrackKind};
pub use search::{
    may_turn, shortest_path, shortest_path_exhaustive, Stretch, TrackPath, TrackQuery, Turning,
};

use crate::headland::PassAround;
use crate::path::SegmentKind;
use crate::plan::Plan;
use crate::route::RouteStep;
use geo::LineString;

/// The track graph of a plan: every segment of its drivable path is a track; the field's
/// outermost headland pass is the boundary lane.
pub fn from_plan(plan: &Plan) -> TrackGraph {
    let tracks = plan
        .path
        .segments
        .iter()
        .filter_map(|seg| {
            let kind = match seg.kind {
                SegmentKind::Swath => TrackKind::Swath,
                SegmentKind::HeadlandPass => TrackKind::HeadlandPass,
                SegmentKind::Turn => TrackKind::Turn,
                SegmentKind::Connection => TrackKind::Connection,
            };
            let boundary = seg.kind == SegmentKind::HeadlandPass
                && seg
                    .step
                    .and_then(|i| plan.route.steps.get(i))
                    .and_then(|step| match *step {
                        RouteStep::HeadlandPass { pass, .. } => plan.headlands.passes.get(pass),
                        RouteStep::Swath { .. } => None,
                    })
                    .is_some_and(|p| p.index == 1 && p.around == PassAround::Field);
            Track::new(kind, seg.line.0.clone(), boundary)
        })
        .collect();
    TrackGraph::new(tracks)
}

/// What a lane is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LaneKind {
    /// A swath centre line.
    Swath,
    /// A headland pass centre line (closed, or open where some edges have no headland).
    HeadlandPass,
}

/// One lane: a track the machine drove while working.
#[derive(Debug, Clone, PartialEq)]
pub struct Lane {
    /// What the lane is.
    pub kind: LaneKind,
    /// Index of the swath or headland pass it comes from.
    pub index: usize,
    /// Its centre line in local metres.
    pub line: LineString,
}

/// The lanes of a plan: every swath and every headland pass, in route order.
///
/// ```
/// use furrow::{plan_geojson, tracks::{lanes, LaneKind}, PlanOptions};
///
/// let text = r#"{"type": "Polygon", "coordinates": [[[24.05, 60.25], [24.056, 60.25],
///     [24.056, 60.252], [24.05, 60.252], [24.05, 60.25]]]}"#;
/// let plan = plan_geojson(text, &PlanOptions::default())?;
/// let lanes = lanes(&plan);
/// let passes = lanes.iter().filter(|l| l.kind == LaneKind::HeadlandPass).count();
/// assert_eq!(passes, 2);
/// assert_eq!(lanes.len() - passes, plan.swaths.swaths.len());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn lanes(plan: &Plan) -> Vec<Lane> {
    plan.route
        .steps
        .iter()
        .filter_map(|step| match *step {
            RouteStep::Swath { swath, .. } => plan.swaths.swaths.get(swath).map(|s| Lane {
                kind: LaneKind::Swath,
                index: swath,
                line: LineString::new(vec![s.centre.start, s.centre.end]),
            }),
            RouteStep::HeadlandPass { pass, .. } => plan.headlands.passes.get(pass).map(|p| Lane {
                kind: LaneKind::HeadlandPass,
                index: pass,
                line: p.line.clone(),
            }),
        })
        .collect()
}
