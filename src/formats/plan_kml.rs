//! A plan as KML, for Google Earth and the GIS tools that read it: the field (boundary and
//! obstacles), the blocks, the swaths, the headland passes and the path between them (turns
//! and connections), each in a folder of its own, the swaths and passes numbered in driving
//! order. Written with `quick-xml`.
//!
//! ```
//! use furrow::formats::plan_kml::plan_kml;
//! use furrow::{plan_geojson, PlanOptions};
//!
//! let field = r#"{"type": "Polygon", "coordinates": [[[24.05, 60.25], [24.056, 60.25],
//!     [24.056, 60.252], [24.05, 60.252], [24.05, 60.25]]]}"#;
//! let plan = plan_geojson(field, &PlanOptions::default())?.to_geojson_string();
//! let kml = plan_kml(field, &plan)?;
//! assert!(kml.contains("<Folder><name>Swaths</name>"));
//! # Ok::<(), furrow::PlanError>(())
//! ```

use super::outline::{field_outline, line_of, plan_features, LonLat};
use crate::error::PlanError;
use quick_xml::events::{BytesDecl, BytesEnd, BytesStart, BytesText, Event};
use serde_json::Value;

/// The folders of plan features: the folder's name, the features' `kind`, how each is named.
const FOLDERS: [(&str, &str, &str); 4] = [
    ("Swaths", "swath", "Swath"),
    ("Headland passes", "headland", "Headland pass"),
    ("Turns", "turn", "Turn"),
    ("Connections", "connection", "Connection"),
];

/// The KML text of a plan (`plan`: its GeoJSON text) of `field` (its GeoJSON as planned, in
/// WGS84).
pub fn plan_kml(field: &str, plan: &str) -> Result<String, PlanError> {
    let outline = field_outline(field)?;
    let features = plan_features(plan)?;
    let mut w = Kml::new();
    w.start("kml", &[("xmlns", "http://www.opengis.net/kml/2.2")]);
    w.start("Document", &[]);
    w.text_element("name", outline.name.as_deref().unwrap_or("Field"));
    for (id, colour, width) in STYLES {
        style(&mut w, id, colour, width);
    }
    w.folder("Field");
    polygon(
        &mut w,
        "Boundary",
        "boundary",
        std::slice::from_ref(&outline.boundary),
    );
    for (i, rings) in outline.obstacles.iter().enumerate() {
        polygon(&mut w, &format!("Obstacle {}", i + 1), "obstacle", rings);
    }
    w.end("Folder");
    w.folder("Blocks");
    for f in features
        .iter()
        .filter(|f| f["properties"]["kind"] == "block")
    {
        let p = &f["properties"];
        let order = p["order"].as_u64().unwrap_or(0) + 1;
        let rings = rings_of(&f["geometry"]);
        polygon(&mut w, &format!("Block {order}"), "block", &rings);
    }
    w.end("Folder");
    for (folder, kind, name) in FOLDERS {
        w.folder(folder);
        for f in features.iter().filter(|f| f["properties"]["kind"] == kind) {
            let sequence = f["properties"]["sequence"].as_u64().unwrap_or(0);
            if let Some(points) = line_of(&f["geometry"]) {
                line(&mut w, &format!("{name} {sequence}"), kind, &points);
            }
        }
        w.end("Folder");
    }
    w.end("Document");
    w.end("kml");
    Ok(w.finish())
}

/// Line styles (KML colours are aabbggrr): the field's edge, obstacles, blocks, swaths, passes,
/// turns, connections.
const STYLES: [(&str, &str, &str); 7] = [
    ("boundary", "ff1e64dc", "3"),
    ("obstacle", "ff2020c0", "2"),
    ("block", "ff909090", "1"),
    ("swath", "ff3c9a2e", "2"),
    ("headland", "ff00a5ff", "2"),
    ("turn", "ffd08030", "1"),
    ("connection", "ffc040c0", "1"),
];

fn style(w: &mut Kml, id: &str, colour: &str, width: &str) {
    w.start("Style", &[("id", id)]);
    w.start("LineStyle", &[]);
    w.text_element("color", colour);
    w.text_element("width", width);
    w.end("LineStyle");
    w.start("PolyStyle", &[]);
    w.text_element("fill", "0");
    w.end("PolyStyle");
    w.end("Style");
}

fn rings_of(geometry: &Value) -> Vec<Vec<LonLat>> {
    geometry["coordinates"]
        .as_array()
        .map(|rings| {
            rings
                .iter()
                .filter_map(|r| line_of(&serde_json::json!({ "coordinates": r })))
                .collect()
        })
        .unwrap_or_default()
}

fn coordinates(points: &[LonLat]) -> String {
    let mut text = String::with_capacity(points.len() * 28);
    for [lon, lat] in points {
        if !text.is_empty() {
            text.push(' ');
        }
        text.push_str(&format!("{lon:.9},{lat:.9}"));
    }
    text
}

fn placemark_start(w: &mut Kml, name: &str, style: &str) {
    w.start("Placemark", &[]);
    w.text_element("name", name);
    w.text_element("styleUrl", &format!("#{style}"));
}

fn polygon(w: &mut Kml, name: &str, style: &str, rings: &[Vec<LonLat>]) {
    let Some((outer, inner)) = rings.split_first() else {
        return;
    };
    placemark_start(w, name, style);
    w.start("Polygon", &[]);
    for (boundary, ring) in std::iter::once(("outerBoundaryIs", outer))
        .chain(inner.iter().map(|r| ("innerBoundaryIs", r)))
    {
        w.start(boundary, &[]);
        w.start("LinearRing", &[]);
        w.text_element("coordinates", &coordinates(ring));
        w.end("LinearRing");
        w.end(boundary);
    }
    w.end("Polygon");
    w.end("Placemark");
}

fn line(w: &mut Kml, name: &str, style: &str, points: &[LonLat]) {
    placemark_start(w, name, style);
    w.start("LineString", &[]);
    w.text_element("tessellate", "1");
    w.text_element("coordinates", &coordinates(points));
    w.end("LineString");
    w.end("Placemark");
}

/// KML written with `quick-xml`: text and attributes escaped.
struct Kml {
    writer: quick_xml::Writer<Vec<u8>>,
}

impl Kml {
    fn new() -> Self {
        let mut writer = quick_xml::Writer::new(Vec::new());
        // ok to ignore: writing to a Vec cannot fail.
        let _ = writer.write_event(Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None)));
        Kml { writer }
    }

    fn start(&mut self, name: &str, attrs: &[(&str, &str)]) {
        let mut e = BytesStart::new(name);
        for &(k, v) in attrs {
            e.push_attribute((k, v));
        }
        let _ = self.writer.write_event(Event::Start(e));
    }

    fn end(&mut self, name: &str) {
        let _ = self.writer.write_event(Event::End(BytesEnd::new(name)));
    }

    fn text_element(&mut self, name: &str, text: &str) {
        self.start(name, &[]);
        let _ = self.writer.write_event(Event::Text(BytesText::new(text)));
        self.end(name);
    }

    fn folder(&mut self, name: &str) {
        self.start("Folder", &[]);
        self.text_element("name", name);
    }

    fn finish(self) -> String {
        let mut text = String::from_utf8(self.writer.into_inner()).unwrap_or_default();
        text.push('\n');
        text
    }
}
