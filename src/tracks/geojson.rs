//! Track graphs in the API's terms: built from a plan (or from a plan's GeoJSON, saved or
//! passed back from JavaScript), asked in the input's coordinates and compass degrees, answered
//! as a GeoJSON Feature.
//!
//! ```
//! use furrow::{plan_geojson, PlanOptions};
//! use furrow::tracks::{PlanTracks, Turning};
//!
//! let field = r#"{"type": "Polygon", "coordinates": [[[24.05, 60.25], [24.056, 60.25],
//!     [24.056, 60.252], [24.05, 60.252], [24.05, 60.25]]]}"#;
//! let plan = plan_geojson(field, &PlanOptions::default())?;
//! // The same tracks from the plan's GeoJSON as from the plan.
//! let text = serde_json::to_string(&plan.to_geojson())?;
//! let saved = PlanTracks::from_geojson(&text, Default::default())?;
//! let direct = PlanTracks::from_plan(&plan);
//! assert_eq!(saved.graph.tracks().len(), direct.graph.tracks().len());
//! // From mid-field, facing north, to the field's south-west corner.
//! let path = direct.shortest_path([24.053, 60.251], 0.0, &[[24.05, 60.25]], Turning::Heading)?;
//! let feature = direct.to_feature(&path, Turning::Heading);
//! assert_eq!(feature["geometry"]["type"], "LineString");
//! assert!(feature["properties"]["length_m"].as_f64().unwrap_or(0.0) > 100.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use super::from_plan;
use super::graph::{Track, TrackGraph, TrackKind};
use super::search::{shortest_path, TrackPath, TrackQuery, Turning};
use crate::error::{ErrorCode, PlanError};
use crate::field::{Coordinates, Frame, TransverseMercator};
use crate::plan::Plan;
use geo::Coord;
use serde_json::{json, Value};

/// A plan's track graph and the frame between its metres and the input's coordinates.
#[derive(Debug, Clone)]
pub struct PlanTracks {
    /// The tracks and their junctions, local metres.
    pub graph: TrackGraph,
    /// The input's coordinates and the planner's metres.
    pub frame: Frame,
}

impl PlanTracks {
    /// The tracks of a plan.
    pub fn from_plan(plan: &Plan) -> PlanTracks {
        PlanTracks {
            graph: from_plan(plan),
            frame: plan.field.frame.clone(),
        }
    }

    /// The tracks of a plan's GeoJSON text (the planner's output, as saved or passed back):
    /// its drivable features (`kind` swath, headland, turn, connection); the headland pass with
    /// `around: "field"` and `pass: 1` is the boundary lane.
    pub fn from_geojson(text: &str, coordinates: Coordinates) -> Result<PlanTracks, PlanError> {
        let value: Value = serde_json::from_str(text).map_err(|e| {
            PlanError::new(ErrorCode::InvalidJson, format!("the plan is not JSON: {e}"))
        })?;
        PlanTracks::from_value(&value, coordinates)
    }

    /// As [`PlanTracks::from_geojson`], from a parsed value.
    pub fn from_value(value: &Value, coordinates: Coordinates) -> Result<PlanTracks, PlanError> {
        let invalid = |m: &str| PlanError::new(ErrorCode::InvalidGeojson, m.to_string());
        let features = value
            .get("features")
            .and_then(Value::as_array)
            .ok_or_else(|| invalid("a plan is a FeatureCollection: it has no `features`"))?;
        let mut lines: Vec<(TrackKind, bool, Vec<[f64; 2]>)> = Vec::new();
        for f in features {
            let props = f.get("properties");
            let kind = match props.and_then(|p| p.get("kind")).and_then(Value::as_str) {
                Some("swath") => TrackKind::Swath,
                Some("headland") => TrackKind::HeadlandPass,
                Some("turn") => TrackKind::Turn,
                Some("connection") => TrackKind::Connection,
                _ => continue,
            };
            let geometry = f.get("geometry");
            if geometry.and_then(|g| g.get("type")).and_then(Value::as_str) != Some("LineString") {
                continue;
            }
            let Some(coords) = geometry
                .and_then(|g| g.get("coordinates"))
                .and_then(Value::as_array)
            else {
                continue;
            };
            let mut pts = Vec::with_capacity(coords.len());
            for c in coords {
                let x = c.get(0).and_then(Value::as_f64);
                let y = c.get(1).and_then(Value::as_f64);
                match (x, y) {
                    (Some(x), Some(y)) if x.is_finite() && y.is_finite() => pts.push([x, y]),
                    _ => return Err(invalid("a track's position is not two numbers")),
                }
            }
            let boundary = kind == TrackKind::HeadlandPass
                && props.and_then(|p| p.get("around")).and_then(Value::as_str) == Some("field")
                && props.and_then(|p| p.get("pass")).and_then(Value::as_u64) == Some(1);
            lines.push((kind, boundary, pts));
        }
        if lines.is_empty() {
            return Err(PlanError::new(
                ErrorCode::NoPath,
                "the plan has no drivable features (swath, headland, turn or connection lines)",
            ));
        }
        let frame = match coordinates {
            Coordinates::Metric => Frame::Metric,
            Coordinates::Wgs84 => {
                let (mut x0, mut y0, mut x1, mut y1) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
                for p in lines.iter().flat_map(|l| l.2.iter()) {
                    x0 = x0.min(p[0]);
                    y0 = y0.min(p[1]);
                    x1 = x1.max(p[0]);
                    y1 = y1.max(p[1]);
                }
                if x0 < -180.0 || x1 > 180.0 || y0 < -90.0 || y1 > 90.0 {
                    return Err(PlanError::new(
                        ErrorCode::CoordinateOutOfRange,
                        "the plan's positions are not longitude and latitude (give `coordinates: \"metric\"` for a plan in metres)",
                    ));
                }
                Frame::Wgs84(TransverseMercator::centred_at(
                    (x0 + x1) / 2.0,
                    (y0 + y1) / 2.0,
                ))
            }
        };
        let tracks = lines
            .into_iter()
            .filter_map(|(kind, boundary, pts)| {
                Track::new(
                    kind,
                    pts.into_iter().map(|p| frame.to_local(p)).collect(),
                    boundary,
                )
            })
            .collect();
        Ok(PlanTracks {
            graph: TrackGraph::new(tracks),
            frame,
        })
    }

    /// The shortest path along the tracks from `from` (input coordinates) facing `heading_deg`
    /// (compass degrees, 0 north, clockwise) to the nearest of `targets` (input coordinates).
    pub fn shortest_path(
        &self,
        from: [f64; 2],
        heading_deg: f64,
        targets: &[[f64; 2]],
        turning: Turning,
    ) -> Result<TrackPath, PlanError> {
        let query = TrackQuery {
            from: self.local(from)?,
            heading: (90.0 - heading_deg).to_radians(),
            targets: targets
                .iter()
                .map(|&t| self.local(t))
                .collect::<Result<Vec<_>, _>>()?,
            turning,
            monotone_band: false,
        };
        shortest_path(&self.graph, &query)
    }

    fn local(&self, p: [f64; 2]) -> Result<Coord, PlanError> {
        let ok = p[0].is_finite()
            && p[1].is_finite()
            && match self.frame {
                Frame::Wgs84(_) => p[0].abs() <= 180.0 && p[1].abs() <= 90.0,
                Frame::Metric => true,
            };
        if !ok {
            return Err(PlanError::new(
                ErrorCode::InvalidOption,
                format!(
                    "[{}, {}] is not a position in the plan's coordinates",
                    p[0], p[1]
                ),
            ));
        }
        Ok(self.frame.to_local(p))
    }

    /// The path as a GeoJSON Feature: a LineString in the input's coordinates with its
    /// `length_m`, the `turning` asked for, the `target` reached (index), `start_offset_m` (how
    /// far the machine was from the tracks), `turns_on_the_spot`, `expanded` (states the search
    /// expanded) and `tracks` (the kinds of the tracks driven, in order, each once per stretch).
    pub fn to_feature(&self, path: &TrackPath, turning: Turning) -> Value {
        let coords: Vec<[f64; 2]> = path
            .points
            .iter()
            .map(|&p| self.frame.to_output(p))
            .collect();
        let mut kinds: Vec<&'static str> = Vec::new();
        for s in &path.stretches {
            let kind = self.graph.tracks()[s.track].kind.as_str();
            if kinds.last() != Some(&kind) {
                kinds.push(kind);
            }
        }
        json!({
            "type": "Feature",
            "properties": {
                "kind": "track_path",
                "length_m": (path.length * 1000.0).round() / 1000.0,
                "turning": turning.as_str(),
                "target": path.target,
                "start_offset_m": (path.start_offset * 1000.0).round() / 1000.0,
                "turns_on_the_spot": path.turns_on_the_spot,
                "expanded": path.expanded,
                "tracks": kinds,
            },
            "geometry": { "type": "LineString", "coordinates": coords },
        })
    }
}
