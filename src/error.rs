//! Errors and warnings: what went wrong with an input or a plan, with a stable code.
//!
//! Every public function of furrow returns `Result<_, PlanError>`. The `code` is stable and
//! machine-readable (it crosses into JavaScript as `error.code`); the message is for people.
//! Where the problem sits in the input, the error says which feature (its index in the input's
//! `features`), which vertex of which ring, and the coordinate, in the input's own coordinates.

use serde::Serialize;
use std::fmt;

/// The stable code of a [`PlanError`]. The README's error reference lists each one.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum ErrorCode {
    /// The input is not JSON (truncated, not UTF-8 text, or a number such as `NaN` that JSON
    /// does not have).
    InvalidJson,
    /// The input is JSON but not the GeoJSON the planner reads.
    InvalidGeojson,
    /// No feature has `role: "boundary"` and no single polygon could stand for the field.
    NoBoundary,
    /// More than one boundary: several polygons without roles, or several `boundary` features.
    AmbiguousBoundary,
    /// A geometry type the role cannot have (e.g. a LineString as boundary).
    UnsupportedGeometry,
    /// A coordinate is NaN or infinite.
    NonFiniteCoordinate,
    /// Longitude outside [-180, 180] or latitude outside [-90, 90] (or too near a pole to farm).
    CoordinateOutOfRange,
    /// A ring has fewer than 3 distinct points.
    TooFewPoints,
    /// A ring encloses no area (collinear points) or an area too small to plan.
    ZeroArea,
    /// A ring crosses itself; `coordinate` is the crossing point.
    SelfIntersection,
    /// An obstacle does not lie inside the field boundary.
    ObstacleOutsideField,
    /// An interior ring (hole) of the boundary crosses the exterior ring.
    HoleCrossingBoundary,
    /// An option is unknown or has the wrong type.
    InvalidOption,
    /// An option's value is outside the range the planner accepts.
    OptionOutOfRange,
    /// The input is larger than the planner accepts (vertices, rings, features, forbidden
    /// ranges, or bytes).
    InputTooLarge,
    /// The field is too large to plan: too many kilometres across, or too many swaths at the
    /// working width.
    FieldTooLarge,
    /// The field is too complex to plan in bounded time and memory at these options: an outline
    /// too jagged for the working width's headland offsets, or too many blocks for the
    /// split-and-merge decomposition.
    FieldTooComplex,
    /// The headland passes leave no inner field to put swaths in.
    HeadlandConsumesField,
    /// Forbidden bearing ranges (global, or of one prohibited region) forbid every direction.
    NoAllowedDirection,
    /// The fixed bearing asked for lies in a forbidden range.
    BearingForbidden,
    /// A field file (a zipped Shapefile) is damaged, incomplete or not the format it claims.
    InvalidFile,
    /// A field file's coordinate system is one furrow cannot convert from, or unknown.
    UnknownCrs,
    /// The field's coordinates look like [latitude, longitude]: as given the field lies in the
    /// sea, swapped it lies on land.
    CoordinatesSwapped,
    /// A shortest path along the tracks: the machine's position is too far from every track.
    OffTracks,
    /// A shortest path along the tracks: no way along them reaches the target with the turning
    /// allowed.
    NoPath,
    /// JavaScript only: a function of the package was called before `init()` or `initSync()`
    /// loaded the planner.
    NotInitialised,
    /// A failure inside the planner that input should never cause; please report it.
    Internal,
}

impl ErrorCode {
    /// Every code, for documentation and tests.
    pub const ALL: &'static [ErrorCode] = &[
        ErrorCode::InvalidJson,
        ErrorCode::InvalidGeojson,
        ErrorCode::NoBoundary,
        ErrorCode::AmbiguousBoundary,
        ErrorCode::UnsupportedGeometry,
        ErrorCode::NonFiniteCoordinate,
        ErrorCode::CoordinateOutOfRange,
        ErrorCode::TooFewPoints,
        ErrorCode::ZeroArea,
        ErrorCode::SelfIntersection,
        ErrorCode::ObstacleOutsideField,
        ErrorCode::HoleCrossingBoundary,
        ErrorCode::InvalidOption,
        ErrorCode::OptionOutOfRange,
        ErrorCode::InputTooLarge,
        ErrorCode::FieldTooLarge,
        ErrorCode::FieldTooComplex,
        ErrorCode::HeadlandConsumesField,
        ErrorCode::NoAllowedDirection,
        ErrorCode::BearingForbidden,
        ErrorCode::InvalidFile,
        ErrorCode::UnknownCrs,
        ErrorCode::CoordinatesSwapped,
        ErrorCode::OffTracks,
        ErrorCode::NoPath,
        ErrorCode::NotInitialised,
        ErrorCode::Internal,
    ];

    /// The code as it appears in JSON and in JavaScript's `error.code`.
    pub fn as_str(self) -> &'static str {
        match self {
            ErrorCode::InvalidJson => "invalid_json",
            ErrorCode::InvalidGeojson => "invalid_geojson",
            ErrorCode::NoBoundary => "no_boundary",
            ErrorCode::AmbiguousBoundary => "ambiguous_boundary",
            ErrorCode::UnsupportedGeometry => "unsupported_geometry",
            ErrorCode::NonFiniteCoordinate => "non_finite_coordinate",
            ErrorCode::CoordinateOutOfRange => "coordinate_out_of_range",
            ErrorCode::TooFewPoints => "too_few_points",
            ErrorCode::ZeroArea => "zero_area",
            ErrorCode::SelfIntersection => "self_intersection",
            ErrorCode::ObstacleOutsideField => "obstacle_outside_field",
            ErrorCode::HoleCrossingBoundary => "hole_crossing_boundary",
            ErrorCode::InvalidOption => "invalid_option",
            ErrorCode::OptionOutOfRange => "option_out_of_range",
            ErrorCode::InputTooLarge => "input_too_large",
            ErrorCode::FieldTooLarge => "field_too_large",
            ErrorCode::FieldTooComplex => "field_too_complex",
            ErrorCode::HeadlandConsumesField => "headland_consumes_field",
            ErrorCode::NoAllowedDirection => "no_allowed_direction",
            ErrorCode::BearingForbidden => "bearing_forbidden",
            ErrorCode::InvalidFile => "invalid_file",
            ErrorCode::UnknownCrs => "unknown_crs",
            ErrorCode::CoordinatesSwapped => "coordinates_swapped",
            ErrorCode::OffTracks => "off_tracks",
            ErrorCode::NoPath => "no_path",
            ErrorCode::NotInitialised => "not_initialised",
            ErrorCode::Internal => "internal",
        }
    }
}

impl fmt::Display for ErrorCode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Why a field could not be planned.
///
/// ```
/// use furrow::{plan_geojson, ErrorCode, PlanOptions};
///
/// let err = plan_geojson("{\"type\": \"FeatureCollection\"", &PlanOptions::default()).unwrap_err();
/// assert_eq!(err.code, ErrorCode::InvalidJson);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlanError {
    /// What kind of problem this is.
    pub code: ErrorCode,
    /// A sentence for the user, naming the problem and where it is.
    pub message: String,
    /// Index of the offending feature in the input's `features` (0 for a lone Feature or geometry).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub feature: Option<usize>,
    /// Index of the offending ring in the feature's polygon (0 = exterior).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ring: Option<usize>,
    /// Index of the offending vertex in that ring.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub vertex: Option<usize>,
    /// The offending position in the input's coordinates (longitude, latitude for WGS84).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub coordinate: Option<[f64; 2]>,
    /// For input that is not JSON: the line (from 1) where reading stopped.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub line: Option<usize>,
    /// For input that is not JSON: the column (from 1) where reading stopped.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub column: Option<usize>,
}

impl PlanError {
    /// An error with a code and a message and no location. (Out of line: the planner's module
    /// is smaller so.)
    #[inline(never)]
    pub fn new(code: ErrorCode, message: impl Into<String>) -> Self {
        PlanError {
            code,
            message: message.into(),
            feature: None,
            ring: None,
            vertex: None,
            coordinate: None,
            line: None,
            column: None,
        }
    }

    /// The same error, located at a feature of the input.
    pub fn at_feature(mut self, feature: usize) -> Self {
        self.feature = Some(feature);
        self
    }

    /// The same error, located at a ring of the feature's polygon.
    pub fn at_ring(mut self, ring: usize) -> Self {
        self.ring = Some(ring);
        self
    }

    /// The same error, located at a vertex of the ring.
    pub fn at_vertex(mut self, vertex: usize) -> Self {
        self.vertex = Some(vertex);
        self
    }

    /// The same error, located at a coordinate (in the input's coordinates).
    pub fn at_coordinate(mut self, coordinate: [f64; 2]) -> Self {
        self.coordinate = Some(coordinate);
        self
    }

    /// The same error, located at a line and column of the input text.
    pub fn at_text(mut self, line: usize, column: usize) -> Self {
        self.line = Some(line);
        self.column = Some(column);
        self
    }

    /// The error as one line of JSON: `{"code": ..., "message": ..., ...}`.
    pub fn to_json(&self) -> String {
        // ok: serialising a struct of strings, numbers and options cannot fail.
        serde_json::to_string(self)
            .unwrap_or_else(|_| format!("{{\"code\":\"{}\",\"message\":\"\"}}", self.code.as_str()))
    }
}

impl fmt::Display for PlanError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.code, self.message)
    }
}

impl std::error::Error for PlanError {}

/// The stable code of a [`Warning`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum WarningCode {
    /// A ring's last point did not repeat its first; the ring was closed.
    RingClosed,
    /// Consecutive repeated vertices were removed.
    RepeatedVertices,
    /// Vertices lying on the straight line between their neighbours were removed.
    CollinearVertices,
    /// Spikes (a vertex where the outline goes out and straight back) were removed.
    SpikesRemoved,
    /// A ring ran the wrong way round (exterior clockwise or hole counter-clockwise) and was turned.
    RingReoriented,
    /// An obstacle reached over the field boundary; only its part inside the field is kept.
    ObstacleClipped,
    /// Overlapping obstacles were merged into one.
    ObstaclesMerged,
    /// A dense outline (GNSS-recorded) was simplified to a tolerance tied to the working width.
    OutlineSimplified,
    /// The field lies far out at sea: its coordinates are probably wrong.
    FieldAtSea,
    /// A prohibited region reached over the field boundary; only its part inside is kept.
    ProhibitedClipped,
    /// Features the planner does not use (unknown role, not a polygon) were ignored.
    IgnoredFeature,
    /// Swath pieces shorter than the minimum swath length were dropped.
    ShortSwathsDropped,
    /// Some connections found no way along the headland (no passes, or parts of the headland
    /// that never meet) and run straight, likely across crop.
    StraightConnections,
    /// An obstacle is small across the driving direction (class A): swaths run past it with the
    /// implement lifted.
    ImplementLifted,
    /// Swaths or passes are lifted where the implement would reach past the field's boundary
    /// (swaths laid without headland beside sides not parallel to them): the crop there is left
    /// standing.
    ImplementLiftedAtEdges,
    /// A prohibited region forbids the field's direction: it is worked in a direction of its own.
    RegionOwnDirection,
    /// The forbidden ranges leave a prohibited region no direction: it gets no swaths.
    RegionNotWorked,
    /// Some turns between swaths leave the field or cross an obstacle: no form the machine can
    /// drive fits the headland there (the message gives the depth needed and the depth there).
    TurnLeavesField,
    /// Some connections leave the field or cross an obstacle: no turn the machine can drive
    /// onto, off or along the headland passes keeps in there.
    ConnectionLeavesField,
    /// Some connections between blocks drive over crop the plan works later: no turn the
    /// machine can drive from one block into the next keeps to the headland there.
    ConnectionCrossesCrop,
    /// Some turns between swaths drive over crop the plan works later: no form of turn the
    /// machine can drive between them keeps off it within the field.
    TurnCrossesCrop,
    /// The field has too many swaths at this width to search every direction while the user
    /// waits: the swaths run along the longest edge.
    DirectionNotSearched,
    /// The plan is too large to output at full detail: its lines are drawn with coarser chords,
    /// or its path sampled farther apart than asked.
    OutputCoarsened,
    /// The headland passes asked for leave no inner field: as many as leave one are laid (the
    /// message says how many), none on a field narrower than them.
    HeadlandPassesReduced,
}

impl WarningCode {
    /// Every code, for documentation and tests.
    pub const ALL: &'static [WarningCode] = &[
        WarningCode::RingClosed,
        WarningCode::RepeatedVertices,
        WarningCode::CollinearVertices,
        WarningCode::SpikesRemoved,
        WarningCode::RingReoriented,
        WarningCode::ObstacleClipped,
        WarningCode::ObstaclesMerged,
        WarningCode::OutlineSimplified,
        WarningCode::FieldAtSea,
        WarningCode::ProhibitedClipped,
        WarningCode::IgnoredFeature,
        WarningCode::ShortSwathsDropped,
        WarningCode::StraightConnections,
        WarningCode::ImplementLifted,
        WarningCode::ImplementLiftedAtEdges,
        WarningCode::RegionOwnDirection,
        WarningCode::RegionNotWorked,
        WarningCode::DirectionNotSearched,
        WarningCode::TurnLeavesField,
        WarningCode::ConnectionLeavesField,
        WarningCode::ConnectionCrossesCrop,
        WarningCode::TurnCrossesCrop,
        WarningCode::OutputCoarsened,
        WarningCode::HeadlandPassesReduced,
    ];

    /// The code as it appears in JSON.
    pub fn as_str(self) -> &'static str {
        match self {
            WarningCode::RingClosed => "ring_closed",
            WarningCode::RepeatedVertices => "repeated_vertices",
            WarningCode::CollinearVertices => "collinear_vertices",
            WarningCode::SpikesRemoved => "spikes_removed",
            WarningCode::RingReoriented => "ring_reoriented",
            WarningCode::ObstacleClipped => "obstacle_clipped",
            WarningCode::ObstaclesMerged => "obstacles_merged",
            WarningCode::OutlineSimplified => "outline_simplified",
            WarningCode::FieldAtSea => "field_at_sea",
            WarningCode::ProhibitedClipped => "prohibited_clipped",
            WarningCode::IgnoredFeature => "ignored_feature",
            WarningCode::ShortSwathsDropped => "short_swaths_dropped",
            WarningCode::StraightConnections => "straight_connections",
            WarningCode::ImplementLifted => "implement_lifted",
            WarningCode::ImplementLiftedAtEdges => "implement_lifted_at_edges",
            WarningCode::RegionOwnDirection => "region_own_direction",
            WarningCode::RegionNotWorked => "region_not_worked",
            WarningCode::DirectionNotSearched => "direction_not_searched",
            WarningCode::TurnLeavesField => "turn_leaves_field",
            WarningCode::ConnectionLeavesField => "connection_leaves_field",
            WarningCode::ConnectionCrossesCrop => "connection_crosses_crop",
            WarningCode::TurnCrossesCrop => "turn_crosses_crop",
            WarningCode::OutputCoarsened => "output_coarsened",
            WarningCode::HeadlandPassesReduced => "headland_passes_reduced",
        }
    }
}

/// Something the planner repaired or simplified, or a property of the plan the user should know.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Warning {
    /// What kind of warning this is.
    pub code: WarningCode,
    /// A sentence for the user.
    pub message: String,
    /// Index of the feature concerned in the input's `features`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub feature: Option<usize>,
}

impl Warning {
    /// A warning about the plan or the input as a whole. (Out of line: the planner's module is
    /// smaller so.)
    #[inline(never)]
    pub fn new(code: WarningCode, message: impl Into<String>) -> Self {
        Warning {
            code,
            message: message.into(),
            feature: None,
        }
    }

    /// A warning about one feature of the input.
    pub fn at_feature(mut self, feature: usize) -> Self {
        self.feature = Some(feature);
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_serialise_as_their_stable_strings() {
        for &code in ErrorCode::ALL {
            let json = serde_json::to_string(&code).unwrap();
            assert_eq!(json, format!("\"{}\"", code.as_str()));
        }
        for &code in WarningCode::ALL {
            let json = serde_json::to_string(&code).unwrap();
            assert_eq!(json, format!("\"{}\"", code.as_str()));
        }
    }

    #[test]
    fn error_json_has_code_message_and_location() {
        let err = PlanError::new(ErrorCode::SelfIntersection, "boundary crosses itself")
            .at_feature(0)
            .at_ring(0)
            .at_coordinate([24.0, 60.0]);
        let v: serde_json::Value = serde_json::from_str(&err.to_json()).unwrap();
        assert_eq!(v["code"], "self_intersection");
        assert_eq!(v["message"], "boundary crosses itself");
        assert_eq!(v["feature"], 0);
        assert_eq!(v["coordinate"][1], 60.0);
        assert!(v.get("vertex").is_none());
    }
}
