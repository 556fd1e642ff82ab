//! Parcels from a Shapefile: the polygons of its `.shp` (with `.shx`), their attributes from
//! its `.dbf`, converted to WGS84 from the system its `.prj` names ([`Crs`]). Read with the
//! `shapefile` and `dbase` crates.
//!
//! Each part of a polygon record (an outer ring and the holes inside it) is a parcel: the
//! planner plans one field at a time. A Shapefile without `.prj` is read as WGS84 where its
//! coordinates are longitudes and latitudes, and refused where they are not.

use super::crs::Crs;
use super::Parcel;
use crate::error::{ErrorCode, PlanError};
use ::shapefile::dbase;
use ::shapefile::{PolygonRing, Shape};
use geo::{Coord, Intersects, LineString, Polygon};
use serde_json::{Map, Value};
use std::io::Cursor;

/// The files of one Shapefile: `.shp` (required), `.shx`, `.dbf`, `.prj`.
#[derive(Debug, Default, Clone, Copy)]
pub struct ShapefileParts<'a> {
    /// The shapes.
    pub shp: Option<&'a [u8]>,
    /// Their index.
    pub shx: Option<&'a [u8]>,
    /// Their attributes.
    pub dbf: Option<&'a [u8]>,
    /// Their coordinate system, WKT.
    pub prj: Option<&'a [u8]>,
}

/// The parcels of a Shapefile, in WGS84, and the system they were converted from.
pub fn read_shapefile(parts: ShapefileParts<'_>) -> Result<(Vec<Parcel>, Crs), PlanError> {
    let shp = parts.shp.ok_or_else(|| {
        PlanError::new(
            ErrorCode::InvalidFile,
            "the Shapefile has no .shp file (the shapes): add it to the zip archive, or drop it together with the .shx, .dbf and .prj files",
        )
    })?;
    let shapes = read_shapes(shp, parts.shx)?;
    let records = match parts.dbf {
        Some(dbf) => read_records(dbf)?,
        None => Vec::new(),
    };
    let crs = match parts.prj {
        Some(prj) => Crs::from_wkt(&String::from_utf8_lossy(prj))?,
        None => crs_without_prj(&shapes)?,
    };
    let mut parcels = Vec::new();
    for (index, rings) in shapes.into_iter().enumerate() {
        let properties = records.get(index).cloned().unwrap_or_default();
        let polygons = polygons_of(rings, &crs)?;
        parcels.extend(Parcel::parts(polygons, &properties, index));
    }
    if parcels.is_empty() {
        return Err(PlanError::new(
            ErrorCode::UnsupportedGeometry,
            "the Shapefile holds no polygons (a field is a polygon: its shapes are points or lines, or empty)",
        ));
    }
    Ok((parcels, crs))
}

/// Each polygon record's rings (outer rings clockwise, holes anticlockwise, as the format has
/// them); other shapes as no rings.
fn read_shapes(
    shp: &[u8],
    shx: Option<&[u8]>,
) -> Result<Vec<Vec<PolygonRing<[f64; 2]>>>, PlanError> {
    let invalid = |_| {
        PlanError::new(
            ErrorCode::InvalidFile,
            "the Shapefile's .shp file is damaged or incomplete: export it again",
        )
    };
    let mut reader = match shx {
        Some(shx) => ::shapefile::ShapeReader::with_shx(Cursor::new(shp), Cursor::new(shx)),
        None => ::shapefile::ShapeReader::new(Cursor::new(shp)),
    }
    .map_err(invalid)?;
    let mut out = Vec::new();
    for shape in reader.iter_shapes() {
        let rings = match shape.map_err(invalid)? {
            Shape::Polygon(p) => rings_of(p.into_inner(), |p| [p.x, p.y]),
            Shape::PolygonM(p) => rings_of(p.into_inner(), |p| [p.x, p.y]),
            Shape::PolygonZ(p) => rings_of(p.into_inner(), |p| [p.x, p.y]),
            _ => Vec::new(),
        };
        out.push(rings);
    }
    Ok(out)
}

fn rings_of<P>(
    rings: Vec<PolygonRing<P>>,
    xy: impl Fn(&P) -> [f64; 2],
) -> Vec<PolygonRing<[f64; 2]>> {
    rings
        .into_iter()
        .map(|ring| match ring {
            PolygonRing::Outer(points) => PolygonRing::Outer(points.iter().map(&xy).collect()),
            PolygonRing::Inner(points) => PolygonRing::Inner(points.iter().map(&xy).collect()),
        })
        .collect()
}

/// Each record's attributes, as GeoJSON properties (text trimmed, numbers as numbers, empty
/// values left out).
fn read_records(dbf: &[u8]) -> Result<Vec<Map<String, Value>>, PlanError> {
    let invalid = |_| {
        PlanError::new(
            ErrorCode::InvalidFile,
            "the Shapefile's .dbf file (the attributes) is damaged or incomplete: export it again",
        )
    };
    let mut reader = dbase::ReaderBuilder::new()
        .with_encoding(dbase::encoding::UnicodeLossy)
        .build(Cursor::new(dbf))
        .map_err(invalid)?;
    let mut out = Vec::new();
    for record in reader.iter_records() {
        let record = record.map_err(invalid)?;
        let mut properties = Map::new();
        for (name, value) in record {
            if let Some(v) = json_value(value) {
                properties.insert(name, v);
            }
        }
        out.push(properties);
    }
    Ok(out)
}

fn json_value(value: dbase::FieldValue) -> Option<Value> {
    use dbase::FieldValue as F;
    let number = |x: f64| serde_json::Number::from_f64(x).map(Value::Number);
    match value {
        F::Character(Some(s)) | F::Memo(s) => {
            let s = s.trim();
            (!s.is_empty()).then(|| Value::from(s))
        }
        F::Numeric(Some(x)) | F::Double(x) => number(x),
        F::Float(Some(x)) => number(f64::from(x)),
        F::Integer(i) => Some(Value::from(i)),
        F::Logical(Some(b)) => Some(Value::from(b)),
        F::Date(Some(d)) => Some(Value::from(format!(
            "{:04}-{:02}-{:02}",
            d.year(),
            d.month(),
            d.day()
        ))),
        _ => None,
    }
}

/// Without a `.prj`: WGS84 if every coordinate is a longitude and a latitude.
fn crs_without_prj(shapes: &[Vec<PolygonRing<[f64; 2]>>]) -> Result<Crs, PlanError> {
    let degrees = shapes
        .iter()
        .flatten()
        .flat_map(|ring| ring.points())
        .all(|&[x, y]| (-180.0..=180.0).contains(&x) && (-90.0..=90.0).contains(&y));
    if degrees {
        return Crs::from_epsg(4326);
    }
    Err(PlanError::new(
        ErrorCode::UnknownCrs,
        "the Shapefile has no .prj file and its coordinates are not longitudes and latitudes, so its coordinate system is unknown: add the .prj file it was exported with",
    ))
}

/// A record's rings as polygons in WGS84: each outer ring with the holes inside it.
fn polygons_of(rings: Vec<PolygonRing<[f64; 2]>>, crs: &Crs) -> Result<Vec<Polygon>, PlanError> {
    let mut outers: Vec<Polygon> = Vec::new();
    let mut holes: Vec<LineString> = Vec::new();
    for ring in rings {
        let is_outer = matches!(ring, PolygonRing::Outer(_));
        let points = crs.to_wgs84(ring.points())?;
        let line: LineString = points.iter().map(|&[x, y]| Coord { x, y }).collect();
        if is_outer {
            outers.push(Polygon::new(line, Vec::new()));
        } else {
            holes.push(line);
        }
    }
    let areas: Vec<Polygon> = outers
        .iter()
        .map(|o| Polygon::new(o.exterior().clone(), Vec::new()))
        .collect();
    for hole in holes {
        // The hole belongs to the outer ring holding its first point; one held by none is
        // kept as a polygon of its own (a file whose rings run the wrong way round).
        let first = hole.0.first().copied();
        let owner = first.and_then(|p| areas.iter().position(|a| a.intersects(&p)));
        match owner {
            Some(i) => outers[i].interiors_push(hole),
            None => outers.push(Polygon::new(hole, Vec::new())),
        }
    }
    Ok(outers)
}
