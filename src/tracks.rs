//! Tracks: the lanes a plan leaves in the field (swaths and headland passes), which a machine can
//! later drive again without crushing new crop (Plessen & Bemporad).
//!
//! This module extracts the lanes from a plan; the graph of lanes and the shortest-path queries
//! over it build on these.

use crate::plan::Plan;
use crate::route::RouteStep;
use geo::LineString;

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
