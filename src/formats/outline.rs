//! What every export of a plan starts from: the field's outline in WGS84 (read by the planner's
//! own GeoJSON reader, the boundary as drawn) and the plan's features.

use crate::error::{ErrorCode, PlanError};
use crate::field::{Coordinates, Field};
use serde_json::Value;

/// Longitude, latitude in degrees.
pub type LonLat = [f64; 2];

/// A field's name, boundary and obstacles, WGS84.
pub struct Outline {
    /// The boundary feature's `name`, if it had one.
    pub name: Option<String>,
    /// The boundary's ring as drawn: before the planner's repairs (repeated and collinear
    /// vertices, spikes) and simplification.
    pub boundary: Vec<LonLat>,
    /// Each obstacle's rings, the first its outline.
    pub obstacles: Vec<Vec<Vec<LonLat>>>,
    /// The field's area, square metres.
    pub area_m2: f64,
}

/// The outline of `field` (its GeoJSON, WGS84).
pub fn field_outline(field: &str) -> Result<Outline, PlanError> {
    let (field, _) = Field::from_geojson_str_in(field, Coordinates::Wgs84)?;
    let ring = |r: &geo::LineString| -> Vec<LonLat> {
        r.0.iter().map(|&c| field.frame.to_input(c)).collect()
    };
    Ok(Outline {
        name: field.name.clone(),
        boundary: field
            .drawn_boundary
            .iter()
            .map(|&c| field.frame.to_input(c))
            .collect(),
        obstacles: field
            .obstacles
            .iter()
            .map(|o| {
                std::iter::once(o.polygon.exterior())
                    .chain(o.polygon.interiors())
                    .map(ring)
                    .collect()
            })
            .collect(),
        area_m2: geo::Area::unsigned_area(&field.boundary),
    })
}

/// The features of a plan's GeoJSON text.
pub fn plan_features(plan: &str) -> Result<Vec<Value>, PlanError> {
    let mut plan: Value = serde_json::from_str(plan).map_err(|_| {
        PlanError::new(
            ErrorCode::InvalidJson,
            "the plan is not JSON: give the plan's GeoJSON as planned",
        )
    })?;
    match plan.get_mut("features").map(Value::take) {
        Some(Value::Array(features)) => Ok(features),
        _ => Err(PlanError::new(
            ErrorCode::InvalidGeojson,
            "the plan has no features: give the plan's GeoJSON as planned",
        )),
    }
}

/// A line's coordinates, longitude and latitude.
pub fn line_of(geometry: &Value) -> Option<Vec<LonLat>> {
    geometry["coordinates"]
        .as_array()?
        .iter()
        .map(|p| Some([p[0].as_f64()?, p[1].as_f64()?]))
        .collect()
}
