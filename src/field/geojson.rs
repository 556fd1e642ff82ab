//! Reading GeoJSON: a FeatureCollection with roles, a single Feature, or a bare geometry.
//!
//! The reader is deliberately small and strict about structure: it streams the input through
//! serde without an intermediate JSON tree, keeps each feature's index for error messages, and
//! accepts positions with altitude (the third number is ignored). It knows the properties
//! `role` (`boundary`, `obstacle`, `prohibited`, and `entrance` for a Point or `reference_line`
//! for a LineString, as the viewer saves them), `name` and `forbidden_bearings_deg`; other
//! properties are ignored.
//!
//! What it keeps is bounded, whatever the input: each geometry's coordinates are read only when
//! its feature is used, counting points and lists as they come, and the reading stops with
//! `input_too_large` as soon as there are more than [`MAX_VERTICES`] points, or lists, in all;
//! features beyond [`MAX_FEATURES`] and forbidden ranges beyond [`MAX_FORBIDDEN_RANGES`] are
//! counted, not kept. So 32 MB of tiny arrays cost a few megabytes to refuse, not a gigabyte.

use super::validate::MAX_VERTICES;
use crate::error::{ErrorCode, PlanError};
use crate::numbers::Shortest;
use serde::de::{self, DeserializeSeed, Deserializer, IgnoredAny, SeqAccess, Visitor};
use serde::Deserialize;
use serde_json::value::RawValue;
use std::fmt;
use std::marker::PhantomData;

/// Input larger than this many bytes of GeoJSON text is refused.
pub const MAX_INPUT_BYTES: usize = 32 * 1024 * 1024;

/// Most features a FeatureCollection may hold: a polygon has at least four positions (three
/// corners and the first again), so no input within [`MAX_VERTICES`] has more polygons.
pub const MAX_FEATURES: usize = MAX_VERTICES / 4;

/// Most forbidden bearing ranges one prohibited region may have.
pub const MAX_FORBIDDEN_RANGES: usize = 1000;

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
///
/// ```
/// use furrow::field::geojson::parse_str;
/// use furrow::ErrorCode;
///
/// let input = parse_str(r#"{"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [1, 1], [0, 0]]]}"#)?;
/// assert_eq!(input.polygons[0].rings[0].len(), 4);
/// // Refused as soon as the points pass the limit, before the rest is read.
/// let many = format!(r#"{{"type": "Polygon", "coordinates": [[{}[0, 0]]]}}"#, "[0, 0],".repeat(300_000));
/// assert_eq!(parse_str(&many).unwrap_err().code, ErrorCode::InputTooLarge);
/// # Ok::<(), furrow::PlanError>(())
/// ```
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
        .replace("struct RawFeature", "a GeoJSON object")
        .replace("struct RawGeometry", "a GeoJSON object")
        .replace("struct RawProperties", "a properties object")
        .replace("a number or an array of coordinates", "coordinates")
}

/// For JSON that is not the GeoJSON expected: the first feature that does not read on its own.
/// Only called on the error path, so reading the text twice costs nothing in a good plan; the
/// features are read one at a time, none kept.
fn failing_feature(text: &str) -> Option<usize> {
    /// The index of the first feature that does not read, if any.
    struct FirstFailing(Option<usize>);
    impl<'de> Deserialize<'de> for FirstFailing {
        fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
            struct Each;
            impl<'de> Visitor<'de> for Each {
                type Value = FirstFailing;
                fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                    f.write_str("a list of features")
                }
                fn visit_seq<A: SeqAccess<'de>>(
                    self,
                    mut seq: A,
                ) -> Result<FirstFailing, A::Error> {
                    let mut i = 0;
                    let mut failing = None;
                    while let Some(feature) = seq.next_element::<&'de RawValue>()? {
                        if failing.is_none()
                            && serde_json::from_str::<RawFeature>(feature.get()).is_err()
                        {
                            failing = Some(i);
                        }
                        i += 1;
                    }
                    Ok(FirstFailing(failing))
                }
            }
            d.deserialize_seq(Each)
        }
    }
    #[derive(Deserialize)]
    struct Features {
        features: FirstFailing,
    }
    serde_json::from_str::<Features>(text).ok()?.features.0
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
/// ignored, unread.
#[derive(Debug, Deserialize)]
struct RawObject<'a> {
    #[serde(rename = "type")]
    kind: String,
    #[serde(default, borrow)]
    features: Option<Capped<RawFeature<'a>, MAX_FEATURES>>,
    #[serde(default, borrow)]
    geometry: Option<RawGeometry<'a>>,
    #[serde(default)]
    properties: Option<RawProperties>,
    #[serde(default, borrow)]
    coordinates: Option<&'a RawValue>,
}

/// A member of a FeatureCollection's `features`.
#[derive(Debug, Deserialize)]
struct RawFeature<'a> {
    #[serde(rename = "type")]
    kind: String,
    #[serde(default, borrow)]
    geometry: Option<RawGeometry<'a>>,
    #[serde(default)]
    properties: Option<RawProperties>,
}

/// A geometry, its coordinates left as text until the feature is used ([`read_coordinates`]).
#[derive(Debug, Deserialize)]
struct RawGeometry<'a> {
    #[serde(rename = "type")]
    kind: String,
    #[serde(default, borrow)]
    coordinates: Option<&'a RawValue>,
}

#[derive(Debug, Default, Deserialize)]
struct RawProperties {
    #[serde(default)]
    role: Option<String>,
    #[serde(default)]
    name: Option<NameValue>,
    #[serde(default)]
    forbidden_bearings_deg: Option<Capped<[f64; 2], MAX_FORBIDDEN_RANGES>>,
}

/// The first `N` items of a list, and how many it has: the items beyond are read (so that the
/// JSON is checked) but not kept.
#[derive(Debug)]
struct Capped<T, const N: usize> {
    items: Vec<T>,
    total: usize,
}

impl<'de, T: Deserialize<'de>, const N: usize> Deserialize<'de> for Capped<T, N> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct CappedVisitor<T, const N: usize>(PhantomData<T>);
        impl<'de, T: Deserialize<'de>, const N: usize> Visitor<'de> for CappedVisitor<T, N> {
            type Value = Capped<T, N>;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("an array")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Capped<T, N>, A::Error> {
                let mut items = Vec::new();
                while items.len() < N {
                    match seq.next_element()? {
                        Some(item) => items.push(item),
                        None => {
                            let total = items.len();
                            return Ok(Capped { items, total });
                        }
                    }
                }
                let mut total = items.len();
                while seq.next_element::<IgnoredAny>()?.is_some() {
                    total += 1;
                }
                Ok(Capped { items, total })
            }
        }
        d.deserialize_seq(CappedVisitor(PhantomData))
    }
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

/// GeoJSON coordinates of any depth, positions folded as they are read.
#[derive(Debug, Clone, PartialEq)]
enum Coords {
    /// A number where a list was expected (`null` is read as NaN: see [`CoordsSeed`]).
    Number(f64),
    /// A list starting with two numbers: a position. Further numbers (altitude) are dropped.
    Position([f64; 2]),
    /// A list starting with a number that is no position: `[1]`, `[1, [2]]`.
    NotPosition,
    /// A list of lists (a ring, a polygon), or an empty list.
    List(Vec<Coords>),
}

/// How much the coordinates read so far hold: points (positions, and numbers where positions
/// belong) and lists of them; each may reach [`MAX_VERTICES`].
#[derive(Debug, Default)]
struct Budget {
    points: usize,
    lists: usize,
}

impl Budget {
    /// Counts a point or a list; an error once either passes [`MAX_VERTICES`].
    fn count<E: de::Error>(&mut self, point: bool) -> Result<(), E> {
        let n = if point {
            &mut self.points
        } else {
            &mut self.lists
        };
        *n += 1;
        if *n > MAX_VERTICES {
            return Err(E::custom("the input is too large"));
        }
        Ok(())
    }

    fn exceeded(&self) -> Option<PlanError> {
        let what = if self.points > MAX_VERTICES {
            "points"
        } else if self.lists > MAX_VERTICES {
            "lists of points (rings, polygons)"
        } else {
            return None;
        };
        Some(PlanError::new(
            ErrorCode::InputTooLarge,
            format!("the input has more than {MAX_VERTICES} {what}; the planner accepts up to {MAX_VERTICES}: simplify the outlines"),
        ))
    }
}

/// Reads [`Coords`], counting what it keeps in a [`Budget`].
struct CoordsSeed<'b> {
    budget: &'b mut Budget,
}

impl<'de> DeserializeSeed<'de> for CoordsSeed<'_> {
    type Value = Coords;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<Coords, D::Error> {
        d.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for CoordsSeed<'_> {
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
    // A number JSON cannot carry: JavaScript's JSON.stringify writes NaN and Infinity as null.
    // Validation refuses it as a coordinate that is not a finite number.
    fn visit_unit<E: de::Error>(self) -> Result<Coords, E> {
        Ok(Coords::Number(f64::NAN))
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Coords, A::Error> {
        let budget = self.budget;
        let Some(first) = seq.next_element_seed(CoordsSeed { budget })? else {
            budget.count(false)?;
            return Ok(Coords::List(Vec::new()));
        };
        let Coords::Number(x) = first else {
            // A list of lists: a ring, a polygon, the polygons of a MultiPolygon.
            budget.count(false)?;
            let mut items = vec![first];
            while let Some(item) = seq.next_element_seed(CoordsSeed { budget })? {
                if let Coords::Number(_) = item {
                    budget.count(true)?;
                }
                items.push(item);
            }
            return Ok(Coords::List(items));
        };
        budget.count(true)?;
        let mut position = match seq.next_element_seed(CoordsSeed { budget })? {
            Some(Coords::Number(y)) => Coords::Position([x, y]),
            Some(_) => Coords::NotPosition,
            None => return Ok(Coords::NotPosition),
        };
        while let Some(more) = seq.next_element_seed(CoordsSeed { budget })? {
            if !matches!(more, Coords::Number(_)) {
                position = Coords::NotPosition;
            }
        }
        Ok(position)
    }
}

/// Reads the coordinates of feature `i`'s geometry, within the budget.
fn read_coordinates(i: usize, raw: &RawValue, budget: &mut Budget) -> Result<Coords, PlanError> {
    let mut reader = serde_json::Deserializer::from_str(raw.get());
    CoordsSeed { budget }
        .deserialize(&mut reader)
        .map_err(|e| match budget.exceeded() {
            Some(too_large) => too_large,
            None => {
                // The place in the coordinates' own text would mislead: the feature says where.
                let message = e.to_string();
                let at = message.rfind(" at line ").unwrap_or(message.len());
                invalid(
                    i,
                    format!(
                        "the coordinates of feature {i} are not valid GeoJSON: {}",
                        plain(&message[..at])
                    ),
                )
            }
        })
}

fn invalid(feature: usize, message: impl Into<String>) -> PlanError {
    PlanError::new(ErrorCode::InvalidGeojson, message).at_feature(feature)
}

fn collect(raw: RawObject) -> Result<InputFeatures, PlanError> {
    let mut out = InputFeatures::default();
    let mut budget = Budget::default();
    match raw.kind.as_str() {
        "FeatureCollection" => {
            let features = raw.features.ok_or_else(|| {
                PlanError::new(
                    ErrorCode::InvalidGeojson,
                    "a FeatureCollection needs a `features` array",
                )
            })?;
            if features.total > MAX_FEATURES {
                return Err(PlanError::new(
                    ErrorCode::InputTooLarge,
                    format!(
                        "the input has {} features; the planner accepts up to {MAX_FEATURES}",
                        features.total
                    ),
                ));
            }
            for (i, f) in features.items.into_iter().enumerate() {
                if f.kind != "Feature" {
                    return Err(invalid(
                        i,
                        format!(
                            "feature {i} has type `{}`; a FeatureCollection holds Features",
                            f.kind
                        ),
                    ));
                }
                collect_feature(i, f, &mut out, &mut budget)?;
            }
        }
        "Feature" => {
            let feature = RawFeature {
                kind: raw.kind,
                geometry: raw.geometry,
                properties: raw.properties,
            };
            collect_feature(0, feature, &mut out, &mut budget)?
        }
        _ => {
            let geometry = RawGeometry {
                kind: raw.kind,
                coordinates: raw.coordinates,
            };
            let unspecified = Polygons {
                role: Role::Unspecified,
                name: None,
                forbidden: Vec::new(),
            };
            collect_geometry(0, &geometry, unspecified, &mut out, &mut budget)?
        }
    }
    Ok(out)
}

/// What a feature's polygons carry: its role, name and forbidden bearings.
struct Polygons {
    role: Role,
    name: Option<String>,
    forbidden: Vec<[f64; 2]>,
}

fn collect_feature(
    i: usize,
    f: RawFeature,
    out: &mut InputFeatures,
    budget: &mut Budget,
) -> Result<(), PlanError> {
    let props = f.properties.unwrap_or_default();
    let role = match props.role.as_deref() {
        None => Role::Unspecified,
        Some("boundary") | Some("field") => Role::Boundary,
        Some("obstacle") => Role::Obstacle,
        Some("prohibited") => Role::Prohibited,
        Some(extra @ ("entrance" | "reference_line")) => {
            return collect_extra(i, extra, f.geometry.as_ref(), out, budget);
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
        NameValue::Number(x) => Shortest(x).to_string(),
    });
    let forbidden = match props.forbidden_bearings_deg {
        Some(ranges) if ranges.total > MAX_FORBIDDEN_RANGES => {
            return Err(PlanError::new(
                ErrorCode::InputTooLarge,
                format!(
                    "feature {i} has {} forbidden bearing ranges; the planner accepts up to {MAX_FORBIDDEN_RANGES} for a region",
                    ranges.total
                ),
            )
            .at_feature(i))
        }
        Some(ranges) => ranges.items,
        None => Vec::new(),
    };
    if role == Role::Prohibited && forbidden.is_empty() {
        return Err(invalid(
            i,
            format!("prohibited region (feature {i}) has no `forbidden_bearings_deg`"),
        ));
    }
    let polygons = Polygons {
        role,
        name,
        forbidden,
    };
    match f.geometry {
        Some(g) => collect_geometry(i, &g, polygons, out, budget),
        None if role == Role::Unspecified => {
            out.ignored.push((i, "it has no geometry".to_string()));
            Ok(())
        }
        None => Err(invalid(i, format!("feature {i} has no geometry"))),
    }
}

/// The entrance (a Point) or AB line (a LineString) a feature gives; anything else is ignored
/// with the reason.
fn collect_extra(
    i: usize,
    role: &str,
    geometry: Option<&RawGeometry>,
    out: &mut InputFeatures,
    budget: &mut Budget,
) -> Result<(), PlanError> {
    let position = |c: &Coords| match c {
        Coords::Position([x, y]) if x.is_finite() && y.is_finite() => Some([*x, *y]),
        _ => None,
    };
    let kind = geometry.map(|g| g.kind.as_str());
    let coords = match geometry.and_then(|g| g.coordinates) {
        Some(raw) if matches!(kind, Some("Point" | "LineString")) => {
            Some(read_coordinates(i, raw, budget)?)
        }
        _ => None,
    };
    match (role, kind, coords) {
        ("entrance", Some("Point"), Some(c)) => match position(&c) {
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
    Ok(())
}

fn collect_geometry(
    i: usize,
    g: &RawGeometry,
    polygons: Polygons,
    out: &mut InputFeatures,
    budget: &mut Budget,
) -> Result<(), PlanError> {
    let Polygons {
        role,
        name,
        forbidden,
    } = polygons;
    let mut coords = || {
        let raw = g.coordinates.ok_or_else(|| {
            invalid(
                i,
                format!("the {} of feature {i} has no coordinates", g.kind),
            )
        })?;
        read_coordinates(i, raw, budget)
    };
    match g.kind.as_str() {
        "Polygon" => {
            let rings = polygon_rings(i, &coords()?)?;
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
            for part in &parts {
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
                .map(|(v, p)| match p {
                    Coords::Position(xy) => Ok(*xy),
                    _ => Err(invalid(
                        i,
                        format!("vertex {v} of ring {r} of feature {i} is not a position [x, y]"),
                    )
                    .at_ring(r)
                    .at_vertex(v)),
                })
                .collect()
        })
        .collect()
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
    fn points_and_lists_past_the_limit_are_refused_as_they_come() {
        let ring = |unit: &str, n: usize| {
            let units = vec![unit; n].join(",");
            format!(r#"{{"type":"Polygon","coordinates":[[{units}]]}}"#)
        };
        // At the limit a ring reads (and is refused later, as a ring of one repeated point).
        let at = parse_str(&ring("[1,2,3]", MAX_VERTICES)).unwrap();
        assert_eq!(at.polygons[0].rings[0].len(), MAX_VERTICES);
        assert_eq!(at.polygons[0].rings[0][0], [1.0, 2.0]);
        for unit in ["[1,2]", "[1]", "[]"] {
            let e = parse_str(&ring(unit, MAX_VERTICES + 1)).unwrap_err();
            assert_eq!(e.code, ErrorCode::InputTooLarge, "{unit}");
            assert!(e.message.contains("200000"), "{}", e.message);
        }
        // Numbers where positions belong count as points; after a first number, as the rest
        // of one position, they are read and dropped.
        let numbers = vec!["7"; MAX_VERTICES + 1].join(",");
        let e = parse_str(&format!(
            r#"{{"type":"Polygon","coordinates":[[[0,0],{numbers}]]}}"#
        ))
        .unwrap_err();
        assert_eq!(e.code, ErrorCode::InputTooLarge);
        let e = parse_str(&format!(
            r#"{{"type":"Polygon","coordinates":[[{numbers}]]}}"#
        ))
        .unwrap_err();
        assert_eq!((e.code, e.ring), (ErrorCode::InvalidGeojson, Some(0)));
        // Rings: lists of lists.
        let rings = vec!["[]"; MAX_VERTICES + 1].join(",");
        let e = parse_str(&format!(r#"{{"type":"Polygon","coordinates":[{rings}]}}"#)).unwrap_err();
        assert_eq!(e.code, ErrorCode::InputTooLarge);
        // Points count across features.
        let half = vec!["[0,0]"; MAX_VERTICES / 2 + 1].join(",");
        let feature = format!(
            r#"{{"type":"Feature","properties":{{"role":"obstacle"}},"geometry":{{"type":"Polygon","coordinates":[[{half}]]}}}}"#
        );
        let two = format!(r#"{{"type":"FeatureCollection","features":[{feature},{feature}]}}"#);
        assert_eq!(parse_str(&two).unwrap_err().code, ErrorCode::InputTooLarge);
    }

    #[test]
    fn features_and_forbidden_ranges_past_their_limits_are_refused() {
        let features = |n: usize| {
            let f = vec![r#"{"type":"Feature","geometry":null}"#; n].join(",");
            format!(r#"{{"type":"FeatureCollection","features":[{f}]}}"#)
        };
        assert_eq!(
            parse_str(&features(MAX_FEATURES)).unwrap().ignored.len(),
            MAX_FEATURES
        );
        let e = parse_str(&features(MAX_FEATURES + 7)).unwrap_err();
        assert_eq!(e.code, ErrorCode::InputTooLarge);
        assert!(e.message.contains("50007 features"), "{}", e.message);
        let region = |n: usize| {
            let ranges = vec!["[10,20]"; n].join(",");
            format!(
                r#"{{"type":"Feature","properties":{{"role":"prohibited","forbidden_bearings_deg":[{ranges}]}},
                "geometry":{{"type":"Polygon","coordinates":[[[0,0],[1,0],[1,1],[0,0]]]}}}}"#
            )
        };
        let read = parse_str(&region(MAX_FORBIDDEN_RANGES)).unwrap();
        assert_eq!(
            read.polygons[0].forbidden_bearings_deg.len(),
            MAX_FORBIDDEN_RANGES
        );
        let e = parse_str(&region(MAX_FORBIDDEN_RANGES + 1)).unwrap_err();
        assert_eq!((e.code, e.feature), (ErrorCode::InputTooLarge, Some(0)));
    }

    #[test]
    fn coordinates_are_read_only_for_features_used() {
        // An ignored feature's coordinates are not read; a used feature's that are not
        // coordinates are refused at that feature.
        let text = |second: &str| {
            format!(
                r#"{{"type":"FeatureCollection","features":[
                {{"type":"Feature","properties":{{"role":"boundary"}},
                 "geometry":{{"type":"Polygon","coordinates":[[[0,0],[1,0],[1,1],[0,0]]]}}}},
                {{"type":"Feature","properties":{{"role":"{second}"}},
                 "geometry":{{"type":"Polygon","coordinates":[[[0,0],["a",0],[1,1],[0,0]]]}}}}]}}"#
            )
        };
        let read = parse_str(&text("road")).unwrap();
        assert_eq!((read.polygons.len(), read.ignored.len()), (1, 1));
        let e = parse_str(&text("obstacle")).unwrap_err();
        assert_eq!((e.code, e.feature), (ErrorCode::InvalidGeojson, Some(1)));
        assert!(!e.message.contains("line"), "{}", e.message);
        // A position's members beyond x and y must be numbers too.
        let e = parse_str(r#"{"type":"Polygon","coordinates":[[[0,0],[1,0,[2]],[1,1],[0,0]]]}"#)
            .unwrap_err();
        assert_eq!((e.code, e.vertex), (ErrorCode::InvalidGeojson, Some(1)));
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
