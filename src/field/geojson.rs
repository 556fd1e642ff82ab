//! Reading GeoJSON: a FeatureCollection with roles, a single Feature, or a bare geometry.
//!
//! The reader is deliberately small and strict about structure: it streams the input through
//! serde without an intermediate JSON tree, keeps each feature's index for error messages, and
//! accepts positions with altitude (the third number is ignored). It knows the properties
//! `role` (`boundary`, `obstacle`, `prohibited`, and `entrance` for a Point or `reference_line`
//! for a LineString, as the viewer saves them), `name` and `forbidden_bearings_deg`; other
//! properties are ignored.

use crate::error::{ErrorCode, PlanError};
use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::Deserialize;
use std::fmt;

/// Input larger than this many bytes of GeoJSON text is refused.
pub const MAX_INPUT_BYTES: usize = 32 * 1024 * 1024;

/// What a polygon of the input stands for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// The field's outer boundary; its holes are obstacles.
    Boundary,
    /// An area the machine cannot enter.
    Obstacle,
    /// An area where some driving directions are forbidden.
    Prohibited,
    /// No role given: the boundary if it is the only polygon.
    Unspecified,
}

/// One polygon of the input, with where it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct InputPolygon {
    /// Index of its feature in the input's `features` (0 for a lone Feature or geometry).
    pub feature: usize,
    /// The feature's role.
    pub role: Role,
    /// Rings as given (exterior first), positions as [x, y] (longitude, latitude for WGS84).
    pub rings: Vec<Vec<[f64; 2]>>,
    /// For prohibited regions: forbidden driving bearings as [from, to] compass degrees.
    pub forbidden_bearings_deg: Vec<[f64; 2]>,
    /// The feature's `name` property.
    pub name: Option<String>,
}

/// The polygons of an input, in input order, and the features that were skipped (with the reason,
/// a phrase such as "it has no geometry").
#[derive(Debug, Clone, Default, PartialEq)]
pub struct InputFeatures {
    /// Polygons (a MultiPolygon gives one entry per part, all with the same feature index).
    pub polygons: Vec<InputPolygon>,
    /// Features ignored because of an unknown role, as (feature index, role).
    pub ignored: Vec<(usize, String)>,
    /// The first Point with `role: "entrance"`: where the machine enters the field.
    pub entrance: Option<[f64; 2]>,
    /// The index of the entrance's feature.
    pub entrance_feature: Option<usize>,
    /// The first LineString with `role: "reference_line"` (its first and last positions): an AB
    /// line for the swaths to run along.
    pub reference_line: Option<[[f64; 2]; 2]>,
}

/// Parses GeoJSON text.
pub fn parse_str(text: &str) -> Result<InputFeatures, PlanError> {
    if text.len() > MAX_INPUT_BYTES {
        return Err(PlanError::new(
            ErrorCode::InputTooLarge,
            format!(
                "the input is {} MB; the planner accepts up to {} MB of GeoJSON",
                text.len() / (1024 * 1024),
                MAX_INPUT_BYTES / (1024 * 1024)
            ),
        ));
    }
    let raw: RawObject = serde_json::from_str(text).map_err(|e| {
        if e.is_syntax() || e.is_eof() {
            let hint = if non_number_at(text, e.line(), e.column()) {
                " (NaN and Infinity are not numbers JSON can carry)"
            } else {
                ""
            };
            PlanError::new(
                ErrorCode::InvalidJson,
                format!(
                    "the input is not valid JSON: {}{hint}",
                    plain(&e.to_string())
                ),
            )
            .at_text(e.line(), e.column())
        } else {
            let error = PlanError::new(
                ErrorCode::InvalidGeojson,
                format!("the input is not valid GeoJSON: {}", plain(&e.to_string())),
            );
            match failing_feature(text) {
                Some(i) => error.at_feature(i),
                None => error,
            }
        }
    })?;
    collect(raw)
}

/// serde's message with its internal type names put in GeoJSON's words.
fn plain(message: &str) -> String {
    message
        .replace("struct RawObject", "a GeoJSON object")
        .replace("struct RawProperties", "a properties object")
        .replace("a number or an array of coordinates", "coordinates")
}

/// For JSON that is not the GeoJSON expected: the first feature that does not read on its own.
/// Only called on the error path, so reading the text twice costs nothing in a good plan.
fn failing_feature(text: &str) -> Option<usize> {
    /// The features of a collection as their text, each read again on its own.
    #[derive(Deserialize)]
    struct Features<'a> {
        #[serde(borrow)]
        features: Vec<&'a serde_json::value::RawValue>,
    }
    let collection: Features = serde_json::from_str(text).ok()?;
    collection
        .features
        .iter()
        .position(|f| serde_json::from_str::<RawObject>(f.get()).is_err())
}

/// Whether the text at a 1-based line and column starts with NaN or Infinity.
fn non_number_at(text: &str, line: usize, column: usize) -> bool {
    let Some(l) = text.lines().nth(line.saturating_sub(1)) else {
        return false;
    };
    let rest = l.get(column.saturating_sub(1)..).unwrap_or("");
    let rest = rest.trim_start_matches('-');
    rest.starts_with("NaN") || rest.starts_with("Infinity")
}

/// A GeoJSON object of any type: FeatureCollection, Feature or geometry. Unknown members are
/// ignored.
#[derive(Debug, Deserialize)]
pub(crate) struct RawObject {
    #[serde(rename = "type")]
    kind: String,
    #[serde(default)]
    features: Option<Vec<RawObject>>,
    #[serde(default)]
    geometry: Option<Box<RawObject>>,
    #[serde(default)]
    properties: Option<RawProperties>,
    #[serde(default)]
    coordinates: Option<Coords>,
}

#[derive(Debug, Default, Deserialize)]
struct RawProperties {
    #[serde(default)]
    role: Option<String>,
    #[serde(default)]
    name: Option<NameValue>,
    #[serde(default)]
    forbidden_bearings_deg: Option<Vec<[f64; 2]>>,
}

/// A `name` may be a string or a number in the wild.
#[derive(Debug)]
enum NameValue {
    Text(String),
    Number(f64),
}

impl<'de> Deserialize<'de> for NameValue {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct NameVisitor;
        impl Visitor<'_> for NameVisitor {
            type Value = NameValue;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a string or a number")
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<NameValue, E> {
                Ok(NameValue::Text(v.to_string()))
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<NameValue, E> {
                Ok(NameValue::Number(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<NameValue, E> {
                Ok(NameValue::Number(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<NameValue, E> {
                Ok(NameValue::Number(v as f64))
            }
        }
        d.deserialize_any(NameVisitor)
    }
}

/// GeoJSON coordinates of any depth.
#[derive(Debug, Clone, PartialEq)]
enum Coords {
    Number(f64),
    List(Vec<Coords>),
}

impl<'de> Deserialize<'de> for Coords {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct CoordsVisitor;
        impl<'de> Visitor<'de> for CoordsVisitor {
            type Value = Coords;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a number or an array of coordinates")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Coords, E> {
                Ok(Coords::Number(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Coords, E> {
                Ok(Coords::Number(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Coords, E> {
                Ok(Coords::Number(v as f64))
            }
            // A number JSON cannot carry: JavaScript's JSON.stringify writes NaN and Infinity
            // as null. Validation refuses it as a coordinate that is not a finite number.
            fn visit_unit<E: de::Error>(self) -> Result<Coords, E> {
                Ok(Coords::Number(f64::NAN))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Coords, A::Error> {
                let mut items = Vec::with_capacity(seq.size_hint().unwrap_or(0).min(4096));
                while let Some(item) = seq.next_element()? {
                    items.push(item);
                }
                Ok(Coords::List(items))
            }
        }
        d.deserialize_any(CoordsVisitor)
    }
}

fn invalid(feature: usize, message: impl Into<String>) -> PlanError {
    PlanError::new(ErrorCode::InvalidGeojson, message).at_feature(feature)
}

fn collect(raw: RawObject) -> Result<InputFeatures, PlanError> {
    let mut out = InputFeatures::default();
    match raw.kind.as_str() {
        "FeatureCollection" => {
            let features = raw.features.ok_or_else(|| {
                PlanError::new(
                    ErrorCode::InvalidGeojson,
                    "a FeatureCollection needs a `features` array",
                )
            })?;
            for (i, f) in features.into_iter().enumerate() {
                if f.kind != "Feature" {
                    return Err(invalid(
                        i,
                        format!(
                            "feature {i} has type `{}`; a FeatureCollection holds Features",
                            f.kind
                        ),
                    ));
                }
                collect_feature(i, f, &mut out)?;
            }
        }
        "Feature" => collect_feature(0, raw, &mut out)?,
        _ => collect_geometry(0, &raw, Role::Unspecified, None, Vec::new(), &mut out)?,
    }
    Ok(out)
}

fn collect_feature(i: usize, f: RawObject, out: &mut InputFeatures) -> Result<(), PlanError> {
    let props = f.properties.unwrap_or_default();
    let role = match props.role.as_deref() {
        None => Role::Unspecified,
        Some("boundary") | Some("field") => Role::Boundary,
        Some("obstacle") => Role::Obstacle,
        Some("prohibited") => Role::Prohibited,
        Some(extra @ ("entrance" | "reference_line")) => {
            collect_extra(i, extra, f.geometry.as_deref(), out);
            return Ok(());
        }
        Some(other) => {
            out.ignored.push((
                i,
                format!("its role \"{other}\" is not one the planner knows (boundary, obstacle, prohibited)"),
            ));
            return Ok(());
        }
    };
    let name = props.name.map(|n| match n {
        NameValue::Text(s) => s,
        NameValue::Number(x) => format!("{x}"),
    });
    let forbidden = props.forbidden_bearings_deg.unwrap_or_default();
    if role == Role::Prohibited && forbidden.is_empty() {
        return Err(invalid(
            i,
            format!("prohibited region (feature {i}) has no `forbidden_bearings_deg`"),
        ));
    }
    match f.geometry {
        Some(g) => collect_geometry(i, &g, role, name, forbidden, out),
        None if role == Role::Unspecified => {
            out.ignored.push((i, "it has no geometry".to_string()));
            Ok(())
        }
        None => Err(invalid(i, format!("feature {i} has no geometry"))),
    }
}

/// The entrance (a Point) or AB line (a LineString) a feature gives; anything else is ignored
/// with the reason.
fn collect_extra(i: usize, role: &str, geometry: Option<&RawObject>, out: &mut InputFeatures) {
    let position = |c: &Coords| match c {
        Coords::List(v) => match v.as_slice() {
            [Coords::Number(x), Coords::Number(y), ..] if x.is_finite() && y.is_finite() => {
                Some([*x, *y])
            }
            _ => None,
        },
        Coords::Number(_) => None,
    };
    let kind = geometry.map(|g| g.kind.as_str());
    let coords = geometry.and_then(|g| g.coordinates.as_ref());
    match (role, kind, coords) {
        ("entrance", Some("Point"), Some(c)) => match position(c) {
            Some(p) if out.entrance.is_none() => {
                out.entrance = Some(p);
                out.entrance_feature = Some(i);
            }
            Some(_) => out
                .ignored
                .push((i, "the field has an entrance already".into())),
            None => out.ignored.push((i, "its Point is not two numbers".into())),
        },
        ("reference_line", Some("LineString"), Some(Coords::List(points))) => {
            let ends = points
                .first()
                .and_then(position)
                .zip(points.last().and_then(position));
            match ends {
                Some((a, b)) if points.len() >= 2 && out.reference_line.is_none() => {
                    out.reference_line = Some([a, b]);
                }
                Some(_) if points.len() >= 2 => out
                    .ignored
                    .push((i, "the field has an AB line already".into())),
                _ => out
                    .ignored
                    .push((i, "its LineString needs two positions".into())),
            }
        }
        _ => out.ignored.push((
            i,
            format!(
                "its role \"{role}\" needs a {}",
                if role == "entrance" {
                    "Point"
                } else {
                    "LineString"
                }
            ),
        )),
    }
}

fn collect_geometry(
    i: usize,
    g: &RawObject,
    role: Role,
    name: Option<String>,
    forbidden: Vec<[f64; 2]>,
    out: &mut InputFeatures,
) -> Result<(), PlanError> {
    let coords = || {
        g.coordinates.as_ref().ok_or_else(|| {
            invalid(
                i,
                format!("the {} of feature {i} has no coordinates", g.kind),
            )
        })
    };
    match g.kind.as_str() {
        "Polygon" => {
            let rings = polygon_rings(i, coords()?)?;
            out.polygons.push(InputPolygon {
                feature: i,
                role,
                rings,
                forbidden_bearings_deg: forbidden,
                name,
            });
        }
        "MultiPolygon" => {
            let Coords::List(parts) = coords()? else {
                return Err(invalid(
                    i,
                    format!("the MultiPolygon of feature {i} must be an array of polygons"),
                ));
            };
            for part in parts {
                let rings = polygon_rings(i, part)?;
                out.polygons.push(InputPolygon {
                    feature: i,
                    role,
                    rings,
                    forbidden_bearings_deg: forbidden.clone(),
                    name: name.clone(),
                });
            }
        }
        "Point" | "MultiPoint" | "LineString" | "MultiLineString" | "GeometryCollection" => {
            if role == Role::Unspecified {
                out.ignored
                    .push((i, format!("it is a {}, not a polygon", g.kind)));
            } else {
                return Err(PlanError::new(
                    ErrorCode::UnsupportedGeometry,
                    format!(
                        "feature {i} is a {}, but {} must be a Polygon or MultiPolygon",
                        g.kind,
                        role_phrase(role)
                    ),
                )
                .at_feature(i));
            }
        }
        other => {
            return Err(invalid(
                i,
                format!("feature {i} has the unknown geometry type `{other}`"),
            ))
        }
    }
    Ok(())
}

impl InputPolygon {
    /// How messages name this polygon, or ring `ring` of it: "the field boundary", "hole 1 of the
    /// field boundary", `obstacle "Pond"`, "the obstacle (feature 3)".
    pub fn subject(&self, ring: usize) -> String {
        let whole = match (self.role, &self.name) {
            (Role::Boundary | Role::Unspecified, _) => "the field boundary".to_string(),
            (Role::Obstacle, Some(name)) => format!("obstacle \"{name}\""),
            (Role::Prohibited, Some(name)) => format!("prohibited region \"{name}\""),
            (Role::Obstacle, None) => format!("the obstacle (feature {})", self.feature),
            (Role::Prohibited, None) => format!("the prohibited region (feature {})", self.feature),
        };
        if ring == 0 {
            whole
        } else {
            format!("hole {ring} of {whole}")
        }
    }
}

/// What a role must be, with its article: "the field boundary", "an obstacle".
fn role_phrase(role: Role) -> &'static str {
    match role {
        Role::Boundary | Role::Unspecified => "the field boundary",
        Role::Obstacle => "an obstacle",
        Role::Prohibited => "a prohibited region",
    }
}

fn polygon_rings(i: usize, c: &Coords) -> Result<Vec<Vec<[f64; 2]>>, PlanError> {
    let Coords::List(rings) = c else {
        return Err(invalid(
            i,
            format!("the polygon of feature {i} must be an array of rings"),
        ));
    };
    if rings.is_empty() {
        return Err(PlanError::new(
            ErrorCode::TooFewPoints,
            format!("the polygon of feature {i} has no rings"),
        )
        .at_feature(i));
    }
    rings
        .iter()
        .enumerate()
        .map(|(r, ring)| {
            let Coords::List(positions) = ring else {
                return Err(invalid(
                    i,
                    format!("ring {r} of feature {i} must be an array of positions"),
                )
                .at_ring(r));
            };
            positions
                .iter()
                .enumerate()
                .map(|(v, p)| {
                    position(p).ok_or_else(|| {
                        invalid(
                            i,
                            format!(
                                "vertex {v} of ring {r} of feature {i} is not a position [x, y]"
                            ),
                        )
                        .at_ring(r)
                        .at_vertex(v)
                    })
                })
                .collect()
        })
        .collect()
}

fn position(c: &Coords) -> Option<[f64; 2]> {
    match c {
        Coords::List(xs) if xs.len() >= 2 => match (&xs[0], &xs[1]) {
            (Coords::Number(x), Coords::Number(y)) => Some([*x, *y]),
            _ => None,
        },
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entrance_and_ab_line_features_are_read() {
        let text = r#"{"type": "FeatureCollection", "features": [
            {"type":"Feature","properties":{"role":"boundary"},
             "geometry":{"type":"Polygon","coordinates":[[[0,0],[10,0],[10,10],[0,10],[0,0]]]}},
            {"type":"Feature","properties":{"role":"entrance"},"geometry":{"type":"Point","coordinates":[10,5]}},
            {"type":"Feature","properties":{"role":"reference_line"},
             "geometry":{"type":"LineString","coordinates":[[0,0],[5,5],[10,10]]}},
            {"type":"Feature","properties":{"role":"entrance"},"geometry":{"type":"Polygon","coordinates":[]}}
        ]}"#;
        let f = parse_str(text).expect("parses");
        assert_eq!(f.polygons.len(), 1, "the extras are not polygons");
        assert_eq!(f.entrance, Some([10.0, 5.0]));
        assert_eq!(f.entrance_feature, Some(1));
        assert_eq!(f.reference_line, Some([[0.0, 0.0], [10.0, 10.0]]));
        assert_eq!(
            f.ignored.len(),
            1,
            "an entrance that is not a Point is ignored"
        );
        assert!(f.ignored[0].1.contains("Point"), "{}", f.ignored[0].1);
    }

    #[test]
    fn reads_a_feature_collection_with_roles() {
        let text = r#"{"type":"FeatureCollection","features":[
            {"type":"Feature","properties":{"role":"boundary","name":"f"},
             "geometry":{"type":"Polygon","coordinates":[[[0,0],[1,0],[1,1],[0,0]]]}},
            {"type":"Feature","properties":{"role":"prohibited","forbidden_bearings_deg":[[10,20]]},
             "geometry":{"type":"Polygon","coordinates":[[[0,0],[1,0,5],[1,1],[0,0]]]}},
            {"type":"Feature","properties":{"role":"road"},"geometry":null}
        ]}"#;
        let f = parse_str(text).unwrap();
        assert_eq!(f.polygons.len(), 2);
        assert_eq!(f.polygons[0].role, Role::Boundary);
        assert_eq!(f.polygons[0].name.as_deref(), Some("f"));
        assert_eq!(f.polygons[1].role, Role::Prohibited);
        assert_eq!(f.polygons[1].rings[0][1], [1.0, 0.0]);
        assert_eq!(f.polygons[1].forbidden_bearings_deg, vec![[10.0, 20.0]]);
        assert_eq!(f.ignored.len(), 1);
        assert_eq!(f.ignored[0].0, 2);
        assert!(f.ignored[0].1.contains("\"road\""), "{}", f.ignored[0].1);
    }

    #[test]
    fn reads_bare_geometry_and_multipolygon() {
        let f =
            parse_str(r#"{"type":"Polygon","coordinates":[[[0,0],[1,0],[1,1],[0,0]]]}"#).unwrap();
        assert_eq!(f.polygons.len(), 1);
        assert_eq!(f.polygons[0].role, Role::Unspecified);
        let f = parse_str(
            r#"{"type":"Feature","properties":null,"geometry":{"type":"MultiPolygon",
            "coordinates":[[[[0,0],[1,0],[1,1],[0,0]]],[[[5,5],[6,5],[6,6],[5,5]]]]}}"#,
        )
        .unwrap();
        assert_eq!(f.polygons.len(), 2);
    }

    #[test]
    fn truncated_json_is_invalid_json() {
        let e = parse_str("{\"type\":\"FeatureCollection\",\n\"features\":[{").unwrap_err();
        assert_eq!(e.code, ErrorCode::InvalidJson);
        assert_eq!((e.line, e.column), (Some(2), Some(13)));
        let e = parse_str(r#"{"type":"Polygon","coordinates":[[[NaN,0]]]}"#).unwrap_err();
        assert_eq!(e.code, ErrorCode::InvalidJson);
        assert!(e.message.contains("NaN"), "{}", e.message);
    }

    #[test]
    fn malformed_structure_is_invalid_geojson_with_location() {
        let e = parse_str(
            r#"{"type":"Feature","geometry":{"type":"Polygon","coordinates":[[[0,0],[1],[1,1]]]}}"#,
        )
        .unwrap_err();
        assert_eq!(e.code, ErrorCode::InvalidGeojson);
        assert_eq!((e.feature, e.ring, e.vertex), (Some(0), Some(0), Some(1)));
        let e = parse_str(r#"{"features":[]}"#).unwrap_err();
        assert_eq!(e.code, ErrorCode::InvalidGeojson);
        let e = parse_str(r#"[1,2,3]"#).unwrap_err();
        assert_eq!(e.code, ErrorCode::InvalidGeojson);
        assert!(!e.message.contains("Raw"), "{}", e.message);
        let e = parse_str(
            r#"{"type":"FeatureCollection","features":[
            {"type":"Feature","geometry":null}, null]}"#,
        )
        .unwrap_err();
        assert_eq!((e.code, e.feature), (ErrorCode::InvalidGeojson, Some(1)));
    }

    #[test]
    fn null_coordinates_are_numbers_that_are_not_finite() {
        // JSON.stringify writes NaN and Infinity of a JavaScript object as null.
        let input = parse_str(
            r#"{"type":"Feature","properties":{"name":7},
            "geometry":{"type":"Polygon","coordinates":[[[0,0],[null,0],[1,1],[0,0]]]}}"#,
        )
        .unwrap();
        let ring = &input.polygons[0].rings[0];
        assert!(ring[1][0].is_nan() && ring[1][1] == 0.0);
        assert_eq!(input.polygons[0].name.as_deref(), Some("7"));
        let e = crate::field::validate::field_from_input(input, crate::field::Coordinates::Metric)
            .unwrap_err();
        assert_eq!(e.code, ErrorCode::NonFiniteCoordinate);
        assert_eq!((e.feature, e.ring, e.vertex), (Some(0), Some(0), Some(1)));
    }

    #[test]
    fn text_over_the_size_limit_is_refused() {
        let text = format!(
            "{{\"type\":\"Polygon\",\"x\":\"{}\"}}",
            " ".repeat(MAX_INPUT_BYTES)
        );
        assert_eq!(parse_str(&text).unwrap_err().code, ErrorCode::InputTooLarge);
    }

    #[test]
    fn a_line_as_boundary_is_unsupported() {
        let e = parse_str(
            r#"{"type":"Feature","properties":{"role":"boundary"},
            "geometry":{"type":"LineString","coordinates":[[0,0],[1,1]]}}"#,
        )
        .unwrap_err();
        assert_eq!(e.code, ErrorCode::UnsupportedGeometry);
    }
}
