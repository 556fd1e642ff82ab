//! Parcels from KML (Google Earth's format; KMZ is a zip of it): every Polygon of every
//! Placemark, in folders or not, with its inner boundaries as holes (obstacles to the planner),
//! the placemark's name and extended data as properties. Read with georust's `kml` crate. KML
//! coordinates are WGS84 longitude, latitude (and an altitude, dropped) by definition.

use super::Parcel;
use crate::error::{ErrorCode, PlanError};
use geo::{Coord, LineString, Polygon};
use kml::types::{Element, Geometry, LinearRing, Placemark};
use kml::Kml;
use serde_json::{Map, Value};

/// The deepest nesting of elements read: a field's polygon in a folder is eight levels deep
/// (`kml`, `Document`, `Folder`, `Placemark`, `Polygon`, `outerBoundaryIs`, `LinearRing`,
/// `coordinates`); `kml` recurses once a level, with several kilobytes of stack each (tens
/// unoptimised), and a file nested thousands deep would take all of it.
const MAX_DEPTH: usize = 32;

/// The parcels of a KML document's text.
pub fn read_kml(text: &str) -> Result<Vec<Parcel>, PlanError> {
    check_xml(text)?;
    let kml: Kml<f64> = text.parse().map_err(|_| {
        PlanError::new(
            ErrorCode::InvalidFile,
            "the KML file cannot be read: it is not well-formed KML (cut short, or another XML); export it again",
        )
    })?;
    let mut parcels = Vec::new();
    let mut placemarks = 0;
    collect(&kml, &mut parcels, &mut placemarks);
    if parcels.is_empty() {
        return Err(PlanError::new(
            ErrorCode::UnsupportedGeometry,
            format!("the KML file holds no polygons ({placemarks} placemarks, none of them a polygon: a field is a polygon)"),
        ));
    }
    Ok(parcels)
}

/// The parcels of every placemark in `kml`, in document order.
fn collect(kml: &Kml<f64>, parcels: &mut Vec<Parcel>, placemarks: &mut usize) {
    match kml {
        Kml::KmlDocument(d) => d
            .elements
            .iter()
            .for_each(|k| collect(k, parcels, placemarks)),
        Kml::Document { elements, .. } => elements
            .iter()
            .for_each(|k| collect(k, parcels, placemarks)),
        Kml::Folder(f) => f
            .elements
            .iter()
            .for_each(|k| collect(k, parcels, placemarks)),
        Kml::Placemark(p) => {
            let record = *placemarks;
            *placemarks += 1;
            let mut polygons = Vec::new();
            if let Some(g) = &p.geometry {
                polygons_of(g, &mut polygons);
            }
            parcels.extend(Parcel::parts(polygons, &properties_of(p), record));
        }
        _ => {}
    }
}

fn polygons_of(geometry: &Geometry<f64>, out: &mut Vec<Polygon>) {
    match geometry {
        Geometry::Polygon(p) => out.push(Polygon::new(
            ring(&p.outer),
            p.inner.iter().map(ring).collect(),
        )),
        Geometry::MultiGeometry(m) => m.geometries.iter().for_each(|g| polygons_of(g, out)),
        _ => {}
    }
}

fn ring(r: &LinearRing<f64>) -> LineString {
    r.coords.iter().map(|c| Coord { x: c.x, y: c.y }).collect()
}

/// The placemark's name and description, and its extended data (`<Data name="…"><value>` and
/// `<SimpleData name="…">`), as properties.
fn properties_of(p: &Placemark<f64>) -> Map<String, Value> {
    let mut properties = Map::new();
    if let Some(name) = p.name.as_deref().map(str::trim).filter(|n| !n.is_empty()) {
        properties.insert("name".into(), Value::from(name));
    }
    if let Some(d) = p
        .description
        .as_deref()
        .map(str::trim)
        .filter(|d| !d.is_empty())
    {
        properties.insert("description".into(), Value::from(d));
    }
    for child in &p.children {
        extended_data(child, &mut properties);
    }
    properties
}

fn extended_data(e: &Element, properties: &mut Map<String, Value>) {
    let local = e.name.rsplit(':').next().unwrap_or(&e.name);
    let key = e
        .attrs
        .get("name")
        .map(|n| n.trim())
        .filter(|n| !n.is_empty());
    match (local, key) {
        ("Data", Some(key)) => {
            let value = e
                .children
                .iter()
                .find(|c| c.name.rsplit(':').next() == Some("value"))
                .and_then(|v| v.content.as_deref());
            if let Some(v) = value.map(str::trim).filter(|v| !v.is_empty()) {
                properties.insert(key.to_string(), Value::from(v));
            }
        }
        ("SimpleData", Some(key)) => {
            if let Some(v) = e
                .content
                .as_deref()
                .map(str::trim)
                .filter(|v| !v.is_empty())
            {
                properties.insert(key.to_string(), Value::from(v));
            }
        }
        _ => e.children.iter().for_each(|c| extended_data(c, properties)),
    }
}

/// Whether the XML is well-formed and nests at most `MAX_DEPTH` deep (read with `quick-xml`):
/// the `kml` crate loops forever on some files cut short, and recurses once a level.
fn check_xml(text: &str) -> Result<(), PlanError> {
    let invalid = |why: &str| {
        PlanError::new(
            ErrorCode::InvalidFile,
            format!("the KML file cannot be read: {why}; export it again"),
        )
    };
    let mut reader = quick_xml::Reader::from_str(text);
    let mut depth = 0usize;
    loop {
        match reader.read_event() {
            Ok(quick_xml::events::Event::Start(_)) => {
                depth += 1;
                if depth > MAX_DEPTH {
                    return Err(invalid(&format!(
                        "its elements nest more than {MAX_DEPTH} deep, as no field's do"
                    )));
                }
            }
            Ok(quick_xml::events::Event::End(_)) => depth = depth.saturating_sub(1),
            Ok(quick_xml::events::Event::Eof) if depth == 0 => return Ok(()),
            Ok(quick_xml::events::Event::Eof) => return Err(invalid("it is cut short")),
            Ok(_) => {}
            Err(_) => return Err(invalid("it is not well-formed XML")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const FIELD: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<kml xmlns="http://www.opengis.net/kml/2.2"><Document><Folder><name>Farm</name>
<Placemark><name>North field</name>
<ExtendedData><Data name="crop"><value>wheat</value></Data></ExtendedData>
<Polygon><outerBoundaryIs><LinearRing><coordinates>
24.05,60.25,0 24.056,60.25,0 24.056,60.252,0 24.05,60.252,0 24.05,60.25,0
</coordinates></LinearRing></outerBoundaryIs>
<innerBoundaryIs><LinearRing><coordinates>
24.052,60.2505 24.053,60.2505 24.053,60.251 24.052,60.2505
</coordinates></LinearRing></innerBoundaryIs></Polygon></Placemark>
<Placemark><name>A gate</name><Point><coordinates>24.05,60.25</coordinates></Point></Placemark>
</Folder></Document></kml>"#;

    #[test]
    fn a_placemark_s_polygon_with_its_hole_name_and_data_is_a_parcel() {
        let parcels = read_kml(FIELD).unwrap();
        assert_eq!(parcels.len(), 1);
        let p = &parcels[0];
        assert_eq!(p.polygon.exterior().0.len(), 5);
        assert_eq!(p.polygon.interiors().len(), 1);
        assert_eq!(
            p.polygon.exterior().0[1],
            Coord {
                x: 24.056,
                y: 60.25
            }
        );
        assert_eq!(p.properties["name"], "North field");
        assert_eq!(p.properties["crop"], "wheat");
    }

    #[test]
    fn no_polygon_and_deep_nesting_are_refused() {
        let points = FIELD
            .replace("<Polygon>", "<!--")
            .replace("</Polygon>", "-->");
        assert_eq!(
            read_kml(&points).unwrap_err().code,
            ErrorCode::UnsupportedGeometry
        );
        let deep = format!(
            "<kml>{}{}</kml>",
            "<Folder>".repeat(5_000),
            "</Folder>".repeat(5_000)
        );
        assert_eq!(read_kml(&deep).unwrap_err().code, ErrorCode::InvalidFile);
        // Cut short (on which `kml` itself never returns), or not XML.
        assert_eq!(
            read_kml("<kml><Placemark>").unwrap_err().code,
            ErrorCode::InvalidFile
        );
        assert_eq!(
            read_kml(&FIELD[..FIELD.len() / 2]).unwrap_err().code,
            ErrorCode::InvalidFile
        );
        assert_eq!(
            read_kml("<kml><a></b></kml>").unwrap_err().code,
            ErrorCode::InvalidFile
        );
    }

    #[test]
    fn the_deepest_nesting_read_fits_a_small_stack() {
        // The polygon's coordinates 32 levels deep (25 folders), read on a thread of the stack
        // a wasm module has, 1 MB.
        let depth = MAX_DEPTH - 7;
        let text = FIELD
            .replace("<Folder>", &"<Folder>".repeat(depth))
            .replace("</Folder>", &"</Folder>".repeat(depth));
        let read = std::thread::Builder::new()
            .stack_size(1 << 20)
            .spawn(move || read_kml(&text).map(|p| p.len()))
            .unwrap()
            .join()
            .unwrap();
        assert_eq!(read.unwrap(), 1);
    }
}
