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
//! assert_eq!(feature.geometry.kind, "LineString");
//! assert!(feature.properties.length_m > 100.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use super::from_plan;
use super::graph::{Track, TrackGraph, TrackKind};
use super::search::{shortest_path, TrackPath, TrackQuery, Turning};
use crate::error::{ErrorCode, PlanError};
use crate::field::{Coordinates, Frame, TransverseMercator};
use crate::plan::Plan;
use geo::Coord;
use serde::de::{self, IgnoredAny, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize};
use serde_json::value::RawValue;
use std::fmt;

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
    /// `around: "field"` and `pass: 1` is the boundary lane. Other features, and members of
    /// other types than the planner writes, are passed over; a track's position that is not
    /// two numbers is an error.
    pub fn from_geojson(text: &str, coordinates: Coordinates) -> Result<PlanTracks, PlanError> {
        let invalid = |m: &str| PlanError::new(ErrorCode::InvalidGeojson, m.to_string());
        let plan: RawPlan = serde_json::from_str(text).map_err(|e| {
            if e.is_syntax() || e.is_eof() {
                PlanError::new(ErrorCode::InvalidJson, format!("the plan is not JSON: {e}"))
            } else {
                invalid("a plan is a FeatureCollection: it has no `features`")
            }
        })?;
        let mut lines: Vec<PlanLine> = Vec::new();
        for f in plan.features {
            let Some(track) = track_of(f)? else {
                continue;
            };
            lines.push(track);
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
    pub fn to_feature(&self, path: &TrackPath, turning: Turning) -> TrackPathFeature {
        let coordinates: Vec<[f64; 2]> = path
            .points
            .iter()
            .map(|&p| self.frame.to_output(p))
            .collect();
        let mut tracks: Vec<&'static str> = Vec::new();
        for s in &path.stretches {
            let kind = self.graph.tracks()[s.track].kind.as_str();
            if tracks.last() != Some(&kind) {
                tracks.push(kind);
            }
        }
        TrackPathFeature {
            kind: "Feature",
            properties: TrackPathProperties {
                kind: "track_path",
                length_m: (path.length * 1000.0).round() / 1000.0,
                turning: turning.as_str(),
                target: path.target,
                start_offset_m: (path.start_offset * 1000.0).round() / 1000.0,
                turns_on_the_spot: path.turns_on_the_spot,
                expanded: path.expanded,
                tracks,
            },
            geometry: TrackPathGeometry {
                kind: "LineString",
                coordinates,
            },
        }
    }
}

/// A shortest path along the tracks as a GeoJSON Feature ([`PlanTracks::to_feature`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TrackPathFeature {
    /// `"Feature"`.
    #[serde(rename = "type")]
    pub kind: &'static str,
    /// What the path is.
    pub properties: TrackPathProperties,
    /// Its line.
    pub geometry: TrackPathGeometry,
}

/// The properties of a [`TrackPathFeature`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TrackPathProperties {
    /// `"track_path"`.
    pub kind: &'static str,
    /// Length, metres (to the millimetre).
    pub length_m: f64,
    /// The way of turning asked for.
    pub turning: &'static str,
    /// Which of the targets was reached (index).
    pub target: usize,
    /// How far the machine was from the tracks, metres.
    pub start_offset_m: f64,
    /// Turns on the spot on the way.
    pub turns_on_the_spot: usize,
    /// States the search expanded.
    pub expanded: usize,
    /// The kinds of the tracks driven, in order, each once per stretch.
    pub tracks: Vec<&'static str>,
}

/// The line of a [`TrackPathFeature`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TrackPathGeometry {
    /// `"LineString"`.
    #[serde(rename = "type")]
    pub kind: &'static str,
    /// Positions in the input's coordinates.
    pub coordinates: Vec<[f64; 2]>,
}

/// A plan's GeoJSON as the track reader sees it: its features, each read on its own.
#[derive(Deserialize)]
struct RawPlan<'a> {
    #[serde(borrow)]
    features: Vec<&'a RawValue>,
}

/// The members of a feature that make a track, unread until they are needed.
#[derive(Deserialize)]
struct RawFeature<'a> {
    #[serde(default, borrow)]
    properties: Option<RawMembers<'a>>,
    #[serde(default, borrow)]
    geometry: Option<RawMembers<'a>>,
}

/// The members of a feature's properties and geometry the reader looks at.
#[derive(Deserialize)]
struct RawMembers<'a> {
    #[serde(default, borrow, rename = "type")]
    kind_of_geometry: Option<&'a RawValue>,
    #[serde(default, borrow)]
    coordinates: Option<&'a RawValue>,
    #[serde(default, borrow)]
    kind: Option<&'a RawValue>,
    #[serde(default, borrow)]
    around: Option<&'a RawValue>,
    #[serde(default, borrow)]
    pass: Option<&'a RawValue>,
}

/// A member's value if it is of type `T`.
fn member<'a, T: Deserialize<'a>>(raw: Option<&'a RawValue>) -> Option<T> {
    raw.and_then(|r| serde_json::from_str(r.get()).ok())
}

/// A track as a plan's GeoJSON gives it: its kind, whether it is the boundary lane, and its
/// positions in the plan's coordinates.
type PlanLine = (TrackKind, bool, Vec<[f64; 2]>);

/// The track a feature of a plan is, if it is one: its kind, whether it is the boundary lane,
/// and its positions.
fn track_of(feature: &RawValue) -> Result<Option<PlanLine>, PlanError> {
    let Ok(f) = serde_json::from_str::<RawFeature>(feature.get()) else {
        return Ok(None);
    };
    let (Some(props), Some(geometry)) = (f.properties, f.geometry) else {
        return Ok(None);
    };
    let kind = match member::<String>(props.kind).as_deref() {
        Some("swath") => TrackKind::Swath,
        Some("headland") => TrackKind::HeadlandPass,
        Some("turn") => TrackKind::Turn,
        Some("connection") => TrackKind::Connection,
        _ => return Ok(None),
    };
    if member::<String>(geometry.kind_of_geometry).as_deref() != Some("LineString") {
        return Ok(None);
    }
    let Some(positions) = member::<Vec<&RawValue>>(geometry.coordinates) else {
        return Ok(None);
    };
    let mut pts = Vec::with_capacity(positions.len());
    for p in positions {
        match serde_json::from_str::<Position>(p.get()) {
            Ok(Position([x, y])) if x.is_finite() && y.is_finite() => pts.push([x, y]),
            _ => {
                return Err(PlanError::new(
                    ErrorCode::InvalidGeojson,
                    "a track's position is not two numbers",
                ))
            }
        }
    }
    let boundary = kind == TrackKind::HeadlandPass
        && member::<String>(props.around).as_deref() == Some("field")
        && member::<u64>(props.pass) == Some(1);
    Ok(Some((kind, boundary, pts)))
}

/// A position: its first two numbers (an altitude after them is passed over).
struct Position([f64; 2]);

impl<'de> Deserialize<'de> for Position {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct PositionVisitor;
        impl<'de> Visitor<'de> for PositionVisitor {
            type Value = Position;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a position of two numbers")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Position, A::Error> {
                let x: f64 = seq
                    .next_element()?
                    .ok_or_else(|| de::Error::invalid_length(0, &self))?;
                let y: f64 = seq
                    .next_element()?
                    .ok_or_else(|| de::Error::invalid_length(1, &self))?;
                while seq.next_element::<IgnoredAny>()?.is_some() {}
                Ok(Position([x, y]))
            }
        }
        d.deserialize_seq(PositionVisitor)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LANE: &str = r#"{"type":"Feature","properties":{"kind":"headland","around":"field","pass":1},
        "geometry":{"type":"LineString","coordinates":[[0,0],[100,0,3.5],[100,50],[0,50],[0,0]]}}"#;
    const SWATH: &str = r#"{"type":"Feature","properties":{"kind":"swath","index":0},
        "geometry":{"type":"LineString","coordinates":[[10,10],[90,10]]}}"#;

    fn read(features: &[&str]) -> Result<PlanTracks, PlanError> {
        let text = format!(
            r#"{{"type":"FeatureCollection","features":[{}]}}"#,
            features.join(",")
        );
        PlanTracks::from_geojson(&text, Coordinates::Metric)
    }

    #[test]
    fn the_drivable_lines_of_a_plan_are_its_tracks() {
        // A point, a polygon, a feature without properties, a kind the reader does not know,
        // members of other types, a number for a feature: passed over.
        let others = [
            r#"{"type":"Feature","properties":{"kind":"entrance"},"geometry":{"type":"Point","coordinates":[0,0]}}"#,
            r#"{"type":"Feature","properties":{"kind":"block"},"geometry":{"type":"Polygon","coordinates":[[[0,0],[1,0],[1,1],[0,0]]]}}"#,
            r#"{"type":"Feature","geometry":{"type":"LineString","coordinates":[[0,0],[1,0]]}}"#,
            r#"{"type":"Feature","properties":{"kind":7},"geometry":{"type":"LineString","coordinates":[[0,0],[1,0]]}}"#,
            r#"{"type":"Feature","properties":{"kind":"turn"},"geometry":{"type":"LineString","coordinates":"none"}}"#,
            "42",
        ];
        let mut all = vec![LANE, SWATH];
        all.extend(others);
        let tracks = read(&all).unwrap();
        let kinds: Vec<TrackKind> = tracks.graph.tracks().iter().map(|t| t.kind).collect();
        assert_eq!(kinds.len(), 2, "{kinds:?}");
        assert!(kinds.contains(&TrackKind::HeadlandPass) && kinds.contains(&TrackKind::Swath));
        assert_eq!(
            tracks.graph.tracks().iter().filter(|t| t.boundary).count(),
            1
        );
    }

    #[test]
    fn a_plan_that_is_no_plan_is_refused_with_its_code() {
        let no_json = PlanTracks::from_geojson("{\"features\": [", Coordinates::Metric);
        assert_eq!(no_json.unwrap_err().code, ErrorCode::InvalidJson);
        let no_features = PlanTracks::from_geojson(r#"{"type":"Feature"}"#, Coordinates::Metric);
        assert_eq!(no_features.unwrap_err().code, ErrorCode::InvalidGeojson);
        assert_eq!(read(&[]).unwrap_err().code, ErrorCode::NoPath);
        // JSON.stringify writes NaN as null.
        let nan = SWATH.replace("[90,10]", "[null,10]");
        assert_eq!(read(&[&nan]).unwrap_err().code, ErrorCode::InvalidGeojson);
    }

    #[test]
    fn a_path_is_written_as_a_line_feature() {
        let tracks = read(&[LANE, SWATH]).unwrap();
        let path = tracks
            .shortest_path([50.0, 0.0], 90.0, &[[0.0, 50.0]], Turning::Tracks)
            .unwrap();
        let feature = tracks.to_feature(&path, Turning::Tracks);
        let v: serde_json::Value = serde_json::to_value(&feature).unwrap();
        assert_eq!(v["type"], "Feature");
        assert_eq!(v["geometry"]["type"], "LineString");
        assert_eq!(v["properties"]["kind"], "track_path");
        assert_eq!(v["properties"]["turning"], Turning::Tracks.as_str());
        assert!(v["properties"]["length_m"].as_f64().unwrap() > 40.0);
        assert!(v["properties"]["tracks"]
            .as_array()
            .is_some_and(|t| !t.is_empty()));
    }
}
