//! What every export of a plan starts from: the field's outline in WGS84 (read by the planner's
//! own GeoJSON reader, the boundary as drawn) and the plan's features.

use crate::error::{ErrorCode, PlanError};
use crate::field::{Coordinates, Field, Frame};
use crate::geometry::{buffer_region, BooleanOps};
use geo::{Coord, LineString, MultiPolygon, Polygon};
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
    /// The way between longitude and latitude and the planner's metres for this field.
    pub frame: Frame,
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
        frame: field.frame.clone(),
    })
}

/// The headland's inner edge, where the plan has closed headland passes round the field: the
/// innermost pass's ring half a working width further in, less the innermost passes round
/// obstacles half a width further out. Polygons of rings, the first of each its outline.
pub fn headland_edge(outline: &Outline, features: &[Value], width: f64) -> Vec<Vec<Vec<LonLat>>> {
    let innermost = |around: &str| -> Vec<Polygon> {
        let rings: Vec<(u64, LineString)> = features
            .iter()
            .filter(|f| {
                let p = &f["properties"];
                p["kind"] == "headland" && p["around"] == around && p["closed"] == true
            })
            .filter_map(|f| {
                let pass = f["properties"]["pass"].as_u64()?;
                let points = line_of(&f["geometry"])?;
                let ring: LineString = points.iter().map(|&p| outline.frame.to_local(p)).collect();
                (ring.0.len() >= 4).then_some((pass, ring))
            })
            .collect();
        let deepest = rings.iter().map(|(pass, _)| *pass).max().unwrap_or(0);
        rings
            .into_iter()
            .filter(|(pass, _)| *pass == deepest)
            .map(|(_, ring)| Polygon::new(ring, Vec::new()))
            .collect()
    };
    let field_rings = innermost("field");
    if field_rings.is_empty() {
        return Vec::new();
    }
    let step = 0.1;
    let inner = buffer_region(&MultiPolygon::new(field_rings), -width / 2.0, step);
    let around_obstacles =
        buffer_region(&MultiPolygon::new(innermost("obstacle")), width / 2.0, step);
    let inner = inner.difference(&around_obstacles);
    let ring = |r: &LineString| -> Vec<LonLat> {
        r.0.iter()
            .map(|&c: &Coord| outline.frame.to_input(c))
            .collect()
    };
    inner
        .0
        .iter()
        .map(|p| {
            std::iter::once(p.exterior())
                .chain(p.interiors())
                .map(ring)
                .collect()
        })
        .collect()
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
