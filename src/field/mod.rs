//! The field: its boundary, obstacles and prohibited regions in local metres, read and checked
//! from GeoJSON.
//!
//! [`Field::from_geojson_str`] is the way in: it parses the input ([`geojson`]), projects it to a
//! local metric frame ([`projection`]), repairs what can safely be repaired and refuses the rest
//! with a typed error ([`validate`], [`ring`]).

pub mod geojson;
pub mod landmask;
pub mod place;
pub mod projection;
pub mod ring;
pub mod simplify;
pub mod validate;

pub use crate::geometry::BearingRange;
pub use projection::{Frame, TransverseMercator};

use crate::error::{PlanError, Warning};
use geo::{Area, Coord, Polygon};
use serde::Serialize;

/// The coordinates a field comes in.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Coordinates {
    /// WGS84 longitude and latitude in degrees, as GeoJSON (RFC 7946) has them.
    #[default]
    Wgs84,
    /// Metres in a local frame (x east, y north), for apps that project the field themselves.
    Metric,
}

crate::named::named!(Coordinates { "wgs84" => Wgs84, "metric" => Metric });

/// A field ready for planning, in local metres (x east, y north).
#[derive(Debug, Clone)]
pub struct Field {
    /// The outer boundary: exterior ring counter-clockwise, no interior rings (holes of the input
    /// boundary are [`obstacles`](Self::obstacles)).
    pub boundary: Polygon,
    /// The boundary's outer ring as drawn (before repair and simplification), in local metres:
    /// options that name edges of the boundary (`edgePasses`) count its edges.
    pub drawn_boundary: Vec<Coord>,
    /// Areas inside the field the machine cannot enter.
    pub obstacles: Vec<Obstacle>,
    /// Areas where some driving directions are forbidden.
    pub prohibited: Vec<ProhibitedRegion>,
    /// The boundary feature's `name`, if it had one.
    pub name: Option<String>,
    /// Index of the boundary feature in the input's `features`.
    pub feature: usize,
    /// How to get from the input's coordinates to metres and back.
    pub frame: Frame,
    /// The input's entrance (a Point with `role: "entrance"`), input coordinates: used when the
    /// options give none.
    pub entrance: Option<[f64; 2]>,
    /// The input's AB line (a LineString with `role: "reference_line"`), input coordinates: used
    /// when the options give no bearing, reference or other direction.
    pub reference_line: Option<[[f64; 2]; 2]>,
}

/// An area the machine cannot enter (a pond, a pole, a tree island).
#[derive(Debug, Clone)]
pub struct Obstacle {
    /// Its outline, counter-clockwise, in local metres.
    pub polygon: Polygon,
    /// Index of the input feature it came from.
    pub feature: usize,
    /// The feature's `name`, if it had one.
    pub name: Option<String>,
}

/// An area where some driving directions are forbidden (an escarpment, drainage laterals).
#[derive(Debug, Clone)]
pub struct ProhibitedRegion {
    /// Its outline, counter-clockwise, in local metres, clipped to the field.
    pub polygon: Polygon,
    /// Bearing ranges that may not be driven inside it.
    pub forbidden: Vec<BearingRange>,
    /// Index of the input feature it came from.
    pub feature: usize,
    /// The feature's `name`, if it had one.
    pub name: Option<String>,
}

impl Obstacle {
    /// How messages name it: `obstacle "Pond"`, or "the obstacle (feature 3)".
    pub fn subject(&self) -> String {
        match &self.name {
            Some(name) => format!("obstacle \"{name}\""),
            None => format!("the obstacle (feature {})", self.feature),
        }
    }
}

impl ProhibitedRegion {
    /// How messages name it: `prohibited region "Slope"`, or "the prohibited region (feature 3)".
    pub fn subject(&self) -> String {
        match &self.name {
            Some(name) => format!("prohibited region \"{name}\""),
            None => format!("the prohibited region (feature {})", self.feature),
        }
    }
}

impl Field {
    /// Reads a field from GeoJSON text in WGS84 longitude and latitude.
    ///
    /// Returns the field and the warnings about what was repaired or ignored.
    ///
    /// ```
    /// use furrow::field::Field;
    ///
    /// let text = r#"{"type": "Polygon", "coordinates": [[[24.05, 60.25], [24.06, 60.25],
    ///     [24.06, 60.255], [24.05, 60.255], [24.05, 60.25]]]}"#;
    /// let (field, warnings) = Field::from_geojson_str(text)?;
    /// assert!((field.area_m2() / 10_000.0 - 30.9).abs() < 0.1); // hectares
    /// assert!(warnings.is_empty());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn from_geojson_str(text: &str) -> Result<(Field, Vec<Warning>), PlanError> {
        Self::from_geojson_str_in(text, Coordinates::Wgs84)
    }

    /// Reads a field from GeoJSON text in the given coordinates.
    pub fn from_geojson_str_in(
        text: &str,
        coordinates: Coordinates,
    ) -> Result<(Field, Vec<Warning>), PlanError> {
        let input = geojson::parse_str(text)?;
        validate::field_from_input(input, coordinates)
    }

    /// Area of the field inside its boundary and outside its obstacles, square metres.
    pub fn area_m2(&self) -> f64 {
        let holes: f64 = self
            .obstacles
            .iter()
            .map(|o| o.polygon.unsigned_area())
            .sum();
        (self.boundary.unsigned_area() - holes).max(0.0)
    }
}
