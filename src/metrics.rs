//! Metrics: the figures by which a plan is judged (Zhou et al. table 1, Fields2Cover's objectives).

use crate::decompose::Blocks;
use crate::field::Field;
use crate::headland::Headlands;
use crate::path::{Path, SegmentKind};
use crate::swath::Swaths;
use geo::Area;
use serde::Serialize;

/// The summary of a plan: counts, distances and areas. Distances are metres, areas square metres.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Number of swaths.
    pub swath_count: usize,
    /// Number of turns between swaths of one block.
    pub turn_count: usize,
    /// Number of blocks.
    pub block_count: usize,
    /// Number of headland passes (a pass split at a neck counts once per part).
    pub headland_pass_count: usize,
    /// Distance driven working: swaths and headland passes.
    pub working_distance_m: f64,
    /// Of which along swaths.
    pub swath_distance_m: f64,
    /// Of which along headland passes.
    pub headland_distance_m: f64,
    /// Distance driven in turns between swaths.
    pub turning_distance_m: f64,
    /// Distance driven in connections between blocks and onto the headland.
    pub connection_distance_m: f64,
    /// All the distance driven.
    pub total_distance_m: f64,
    /// Area of the field, inside the boundary and outside obstacles.
    pub field_area_m2: f64,
    /// Area of the headland band.
    pub headland_area_m2: f64,
    /// Area of the inner field where the swaths lie (outside obstacles).
    pub inner_field_area_m2: f64,
    /// Swath pieces shorter than the minimum swath length, left to the headland.
    pub dropped_swath_count: usize,
    /// The swath direction as a compass bearing in degrees, in `[0, 180)`.
    pub bearing_deg: f64,
    /// Time the planner took, milliseconds.
    pub planning_ms: f64,
}

/// Measures a plan.
pub fn summarise(
    field: &Field,
    headlands: &Headlands,
    swaths: &Swaths,
    blocks: &Blocks,
    path: &Path,
) -> Summary {
    let swath_distance_m = path.length_of(SegmentKind::Swath);
    let headland_distance_m = path.length_of(SegmentKind::HeadlandPass);
    let turning_distance_m = path.length_of(SegmentKind::Turn);
    let connection_distance_m = path.length_of(SegmentKind::Connection);
    let working_distance_m = swath_distance_m + headland_distance_m;
    Summary {
        swath_count: swaths.swaths.len(),
        turn_count: path.count_of(SegmentKind::Turn),
        block_count: blocks.blocks.len(),
        headland_pass_count: headlands.passes.len(),
        working_distance_m,
        swath_distance_m,
        headland_distance_m,
        turning_distance_m,
        connection_distance_m,
        total_distance_m: working_distance_m + turning_distance_m + connection_distance_m,
        field_area_m2: field.area_m2(),
        headland_area_m2: headlands.area_m2,
        inner_field_area_m2: headlands.inner.unsigned_area(),
        dropped_swath_count: swaths.dropped,
        bearing_deg: swaths.bearing.to_degrees(),
        planning_ms: 0.0,
    }
}
