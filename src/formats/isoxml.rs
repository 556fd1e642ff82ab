//! A plan as ISO 11783-10 TaskData (ISOXML), the file every ISOBUS terminal imports: one
//! partfield with the field's boundary (`PLN` type 1) and its obstacles (type 6); in version 4
//! the headland's inner edge (type 10), a guidance group per block with an AB line along its
//! swaths (heading and swath width, extended both ways), and one of the headland passes as
//! curves (or as AB segments, for terminals that take no curves). Version 3 has no guidance
//! groups:
//! the lines go as `LSG` type 5 under the partfield, as older terminals read them. Written with
//! `quick-xml` and zipped as `TASKDATA/TASKDATA.XML`.
//!
//! Names are at most 32 characters of plain ASCII, coordinates nine decimals (a tenth of a
//! millimetre), IDs of the element's own prefix: what terminals are known to refuse otherwise.
//!
//! ```
//! use furrow::formats::isoxml::{taskdata_xml, TaskDataSettings, TaskDataVersion};
//! use furrow::{plan_geojson, PlanOptions};
//!
//! let field = r#"{"type": "Polygon", "coordinates": [[[24.05, 60.25], [24.056, 60.25],
//!     [24.056, 60.252], [24.05, 60.252], [24.05, 60.25]]]}"#;
//! let options = PlanOptions { width: 6.0, ..Default::default() };
//! let plan = plan_geojson(field, &options)?.to_geojson_string();
//! let settings = TaskDataSettings { width_m: 6.0, ..Default::default() };
//! let xml = taskdata_xml(field, &plan, &settings)?;
//! assert!(xml.contains(r#"<PFD A="PFD1""#) && xml.contains(r#"<GPN A="GPN1""#));
//! # Ok::<(), furrow::PlanError>(())
//! ```

use super::outline::{field_outline, headland_edge, line_of, plan_features, LonLat};
use crate::error::{ErrorCode, PlanError};
use geo::{Bearing, Geodesic, Point};
use quick_xml::events::{BytesDecl, BytesEnd, BytesStart, Event};
use serde_json::Value;

/// The TaskData version written.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum TaskDataVersion {
    /// Version 3, for older terminals: guidance lines as line strings of the partfield.
    V3,
    /// Version 4 (4.3): guidance groups and patterns, the headland polygon.
    #[default]
    V4,
}

/// How the plan is written.
#[derive(Debug, Clone, PartialEq)]
pub struct TaskDataSettings {
    /// The implement's working width, metres: the swath width of the guidance lines.
    pub width_m: f64,
    /// The version.
    pub version: TaskDataVersion,
    /// The headland passes as AB segments rather than curves.
    pub curves_as_ab: bool,
    /// The partfield's name (the field's own name where this is `None`).
    pub name: Option<String>,
}

impl Default for TaskDataSettings {
    fn default() -> Self {
        TaskDataSettings {
            width_m: 6.0,
            version: TaskDataVersion::V4,
            curves_as_ab: false,
            name: None,
        }
    }
}

/// A block's guidance: its designator and the AB line along its longest swath.
struct BlockLine {
    name: String,
    a: LonLat,
    b: LonLat,
}

/// What the TaskData holds, read from the field and the plan.
struct Export {
    name: String,
    boundary: Vec<Vec<LonLat>>,
    obstacles: Vec<Vec<Vec<LonLat>>>,
    area_m2: f64,
    blocks: Vec<BlockLine>,
    passes: Vec<(String, Vec<LonLat>)>,
    /// The headland's inner edge (version 4's polygon of type 10).
    headland: Vec<Vec<Vec<LonLat>>>,
}

/// The TaskData of a plan (`plan`: its GeoJSON text) of `field` (the field's GeoJSON as it was
/// planned, in WGS84), as the text of `TASKDATA.XML`.
pub fn taskdata_xml(
    field: &str,
    plan: &str,
    settings: &TaskDataSettings,
) -> Result<String, PlanError> {
    if !(settings.width_m.is_finite() && settings.width_m > 0.0) {
        return Err(PlanError::new(
            ErrorCode::OptionOutOfRange,
            "the working width of the guidance lines must be a positive number of metres",
        ));
    }
    let export = read_export(field, plan, settings)?;
    Ok(write_xml(&export, settings))
}

/// [`taskdata_xml`] zipped as `TASKDATA/TASKDATA.XML`, as terminals read it from a stick.
pub fn taskdata_zip(
    field: &str,
    plan: &str,
    settings: &TaskDataSettings,
) -> Result<Vec<u8>, PlanError> {
    let xml = taskdata_xml(field, plan, settings)?;
    super::zip::zip_one("TASKDATA/TASKDATA.XML", xml.as_bytes())
}

fn read_export(field: &str, plan: &str, settings: &TaskDataSettings) -> Result<Export, PlanError> {
    let outline = field_outline(field)?;
    let features = plan_features(plan)?;
    let name = settings
        .name
        .clone()
        .or_else(|| outline.name.clone())
        .unwrap_or_else(|| "Field".to_string());
    let headland = headland_edge(&outline, &features, settings.width_m);
    Ok(Export {
        name,
        headland,
        boundary: vec![outline.boundary],
        obstacles: outline.obstacles,
        area_m2: outline.area_m2,
        blocks: block_lines(&features),
        passes: headland_passes(&features),
    })
}

/// Each block's AB line: along its longest swath, in the order the blocks are worked.
fn block_lines(features: &[Value]) -> Vec<BlockLine> {
    let mut blocks: Vec<(u64, u64, bool)> = features
        .iter()
        .filter(|f| f["properties"]["kind"] == "block")
        .filter_map(|f| {
            let p = &f["properties"];
            Some((
                p["index"].as_u64()?,
                p["order"].as_u64()?,
                p["fill"] == true,
            ))
        })
        .collect();
    blocks.sort_by_key(|&(_, order, _)| order);
    blocks
        .iter()
        .filter_map(|&(index, order, fill)| {
            let longest = features
                .iter()
                .filter(|f| {
                    f["properties"]["kind"] == "swath"
                        && f["properties"]["block"].as_u64() == Some(index)
                })
                .filter_map(|f| {
                    Some((
                        f["properties"]["length_m"].as_f64()?,
                        line_of(&f["geometry"])?,
                    ))
                })
                .max_by(|a, b| a.0.total_cmp(&b.0))?;
            let (a, b) = (*longest.1.first()?, *longest.1.last()?);
            let kind = if fill { " fill" } else { "" };
            Some(BlockLine {
                name: format!("Block {}{kind}", order + 1),
                a,
                b,
            })
        })
        .collect()
}

/// The headland passes in the order they are driven, each named by its pass and what it runs
/// round.
fn headland_passes(features: &[Value]) -> Vec<(String, Vec<LonLat>)> {
    features
        .iter()
        .filter(|f| f["properties"]["kind"] == "headland")
        .filter_map(|f| {
            let p = &f["properties"];
            let around = p["around"].as_str().unwrap_or("field");
            let name = format!(
                "Headland {} {around} {}",
                p["pass"].as_u64()?,
                p["sequence"].as_u64()?
            );
            Some((name, line_of(&f["geometry"])?))
        })
        .filter(|(_, line)| line.len() >= 2)
        .collect()
}

/// The true heading from `a` to `b`, degrees clockwise from north in [0, 360).
pub fn heading_deg(a: LonLat, b: LonLat) -> f64 {
    Geodesic
        .bearing(Point::new(a[0], a[1]), Point::new(b[0], b[1]))
        .rem_euclid(360.0)
}

/// The XML text: the root, and the partfield with its polygons and guidance.
fn write_xml(export: &Export, settings: &TaskDataSettings) -> String {
    let mut w = Xml::new();
    let v4 = settings.version == TaskDataVersion::V4;
    w.start(
        "ISO11783_TaskData",
        &[
            ("VersionMajor", if v4 { "4" } else { "3" }.into()),
            // 4.3, or 3.3 for older terminals.
            ("VersionMinor", "3".into()),
            ("ManagementSoftwareManufacturer", "furrow".into()),
            (
                "ManagementSoftwareVersion",
                env!("CARGO_PKG_VERSION").into(),
            ),
            ("DataTransferOrigin", "1".into()),
        ],
    );
    w.start(
        "PFD",
        &[
            ("A", "PFD1".into()),
            ("C", designator(&export.name)),
            ("D", format!("{}", export.area_m2.round() as u64)),
        ],
    );
    let mut ids = Ids::default();
    polygon(&mut w, &mut ids, "1", "Boundary", &export.boundary, v4);
    for (i, o) in export.obstacles.iter().enumerate() {
        polygon(&mut w, &mut ids, "6", &format!("Obstacle {}", i + 1), o, v4);
    }
    if v4 {
        for rings in &export.headland {
            polygon(&mut w, &mut ids, "10", "Headland", rings, v4);
        }
        guidance_groups(&mut w, &mut ids, export, settings);
    } else {
        guidance_lines_v3(&mut w, export, settings);
    }
    w.end("PFD");
    w.end("ISO11783_TaskData");
    w.finish()
}

/// A polygon of `kind` (`PLN` A): its rings as line strings, the first the exterior.
fn polygon(w: &mut Xml, ids: &mut Ids, kind: &str, name: &str, rings: &[Vec<LonLat>], v4: bool) {
    let mut attrs = vec![("A", kind.to_string()), ("B", designator(name))];
    if v4 {
        attrs.push(("E", ids.next("PLN")));
    }
    w.start("PLN", &attrs);
    for (i, r) in rings.iter().enumerate() {
        w.start("LSG", &[("A", if i == 0 { "1" } else { "2" }.into())]);
        for &p in r {
            point(w, "2", p);
        }
        w.end("LSG");
    }
    w.end("PLN");
}

fn point(w: &mut Xml, kind: &str, [lon, lat]: LonLat) {
    w.empty(
        "PNT",
        &[
            ("A", kind.into()),
            ("C", format!("{lat:.9}")),
            ("D", format!("{lon:.9}")),
        ],
    );
}

/// Version 4: a guidance group per block (its AB line), and one for the headland passes.
fn guidance_groups(w: &mut Xml, ids: &mut Ids, export: &Export, settings: &TaskDataSettings) {
    let width = width_mm(settings.width_m);
    for block in &export.blocks {
        w.start(
            "GGP",
            &[("A", ids.next("GGP")), ("B", designator(&block.name))],
        );
        ab_pattern(w, ids, &block.name, block.a, block.b, &width);
        w.end("GGP");
    }
    if export.passes.is_empty() {
        return;
    }
    w.start(
        "GGP",
        &[("A", ids.next("GGP")), ("B", "Headland passes".into())],
    );
    for (name, line) in &export.passes {
        if settings.curves_as_ab {
            for (k, s) in line.windows(2).enumerate() {
                ab_pattern(w, ids, &format!("{name} {}", k + 1), s[0], s[1], &width);
            }
        } else {
            curve_pattern(w, ids, name, line, &width);
        }
    }
    w.end("GGP");
}

/// An AB line (`GPN` type 1) from `a` to `b`, extended both ways.
fn ab_pattern(w: &mut Xml, ids: &mut Ids, name: &str, a: LonLat, b: LonLat, width: &str) {
    w.start(
        "GPN",
        &[
            ("A", ids.next("GPN")),
            ("B", designator(name)),
            ("C", "1".into()),
            ("E", "1".into()),
            ("F", "1".into()),
            ("G", format!("{:.6}", heading_deg(a, b))),
        ],
    );
    w.start("LSG", &[("A", "5".into()), ("C", width.to_string())]);
    guidance_points(w, &[a, b]);
    w.end("LSG");
    w.end("GPN");
}

/// A curve (`GPN` type 3) through the points of `line`: A, guidance points, B.
fn curve_pattern(w: &mut Xml, ids: &mut Ids, name: &str, line: &[LonLat], width: &str) {
    w.start(
        "GPN",
        &[
            ("A", ids.next("GPN")),
            ("B", designator(name)),
            ("C", "3".into()),
            ("E", "1".into()),
            ("F", "1".into()),
        ],
    );
    w.start("LSG", &[("A", "5".into()), ("C", width.to_string())]);
    guidance_points(w, line);
    w.end("LSG");
    w.end("GPN");
}

/// A guidance line's points: A (type 6), the points between (9), B (7).
fn guidance_points(w: &mut Xml, line: &[LonLat]) {
    let last = line.len().saturating_sub(1);
    for (i, &p) in line.iter().enumerate() {
        let kind = match i {
            0 => "6",
            _ if i == last => "7",
            _ => "9",
        };
        point(w, kind, p);
    }
}

/// Version 3: each block's AB line and each headland pass as a guidance line string of the
/// partfield (`LSG` type 5).
fn guidance_lines_v3(w: &mut Xml, export: &Export, settings: &TaskDataSettings) {
    let width = width_mm(settings.width_m);
    let mut line = |name: &str, points: &[LonLat]| {
        w.start(
            "LSG",
            &[
                ("A", "5".into()),
                ("B", designator(name)),
                ("C", width.clone()),
            ],
        );
        guidance_points(w, points);
        w.end("LSG");
    };
    for block in &export.blocks {
        line(&block.name, &[block.a, block.b]);
    }
    for (name, points) in &export.passes {
        if settings.curves_as_ab {
            for (k, s) in points.windows(2).enumerate() {
                line(&format!("{name} {}", k + 1), s);
            }
        } else {
            line(name, points);
        }
    }
}

fn width_mm(width_m: f64) -> String {
    format!("{}", (width_m * 1000.0).round() as u64)
}

/// A designator terminals take: at most 32 characters of letters, digits, spaces and `-_.()`;
/// other characters become `_`.
pub fn designator(name: &str) -> String {
    let clean: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || " -_.()".contains(c) {
                c
            } else {
                '_'
            }
        })
        .take(32)
        .collect();
    let clean = clean.trim().to_string();
    if clean.is_empty() {
        "Field".into()
    } else {
        clean
    }
}

/// The next ID of each element type: `GGP1`, `GGP2`, …
#[derive(Default)]
struct Ids {
    counts: Vec<(&'static str, u32)>,
}

impl Ids {
    fn next(&mut self, prefix: &'static str) -> String {
        let n = match self.counts.iter_mut().find(|(p, _)| *p == prefix) {
            Some((_, n)) => {
                *n += 1;
                *n
            }
            None => {
                self.counts.push((prefix, 1));
                1
            }
        };
        format!("{prefix}{n}")
    }
}

/// XML written with `quick-xml`, indented, attributes escaped.
struct Xml {
    writer: quick_xml::Writer<Vec<u8>>,
}

impl Xml {
    fn new() -> Self {
        let mut writer = quick_xml::Writer::new_with_indent(Vec::new(), b' ', 1);
        // ok to ignore: writing to a Vec cannot fail.
        let _ = writer.write_event(Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None)));
        Xml { writer }
    }

    fn element<'a>(name: &'a str, attrs: &'a [(&'a str, String)]) -> BytesStart<'a> {
        let mut e = BytesStart::new(name);
        for (k, v) in attrs {
            e.push_attribute((*k, v.as_str()));
        }
        e
    }

    fn start(&mut self, name: &str, attrs: &[(&str, String)]) {
        let _ = self
            .writer
            .write_event(Event::Start(Self::element(name, attrs)));
    }

    fn empty(&mut self, name: &str, attrs: &[(&str, String)]) {
        let _ = self
            .writer
            .write_event(Event::Empty(Self::element(name, attrs)));
    }

    fn end(&mut self, name: &str) {
        let _ = self.writer.write_event(Event::End(BytesEnd::new(name)));
    }

    fn finish(self) -> String {
        let mut text = String::from_utf8(self.writer.into_inner()).unwrap_or_default();
        text.push('\n');
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn designators_are_short_plain_and_never_empty() {
        let d = designator("Nørre mark <øst> & \"vest\" 2026 — långa åkern");
        assert!(d.starts_with("N_rre mark __st_ _ _vest_ 2026"), "{d}");
        assert!(
            d.len() <= 32
                && d.chars()
                    .all(|c| c.is_ascii_alphanumeric() || " -_.()".contains(c))
        );
        assert_eq!(designator("  "), "Field");
        assert_eq!(designator(&"x".repeat(40)).len(), 32);
    }

    #[test]
    fn headings_are_compass_bearings() {
        assert!((heading_deg([24.0, 60.0], [24.0, 60.01]) - 0.0).abs() < 1e-9);
        assert!((heading_deg([24.0, 60.0], [24.0, 59.99]) - 180.0).abs() < 1e-9);
        let west = heading_deg([24.0, 60.0], [23.99, 60.0]);
        assert!((west - 270.0).abs() < 0.01, "{west}");
    }
}
