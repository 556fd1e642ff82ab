//! Parcels from ISO 11783-10 TaskData (`TASKDATA.XML`, versions 3 and 4, or its zip), the
//! files ISOBUS terminals and farm software exchange: each partfield (`PFD`) is a parcel, its
//! boundary the polygon of type 1 (or 9, as AgOpenGPS writes it), its obstacles (polygons of
//! type 6, and water and buildings, 3 and 4) holes in it, which the planner reads as obstacles.
//! Its guidance is kept: every AB line and curve (version 4's patterns, version 3's line
//! strings of type 5) in the parcel's `guidance`, and its first AB line as `reference_line`, so
//! that this year's swaths follow the terminal's. Read with `quick-xml`; partfields a
//! version 4 file keeps in files of their own (`XFR`) are read from the same archive.

use super::Parcel;
use crate::error::{ErrorCode, PlanError};
use geo::{Coord, LineString, Polygon};
use quick_xml::events::{BytesStart, Event};
use serde_json::{json, Map, Value};

type LonLat = [f64; 2];

/// A partfield as read: its name and ID, its polygons (type and rings) and guidance lines.
#[derive(Debug, Default)]
struct Partfield {
    name: Option<String>,
    id: Option<String>,
    polygons: Vec<(String, Vec<Vec<LonLat>>)>,
    guidance: Vec<Guidance>,
}

#[derive(Debug)]
struct Guidance {
    name: Option<String>,
    curve: bool,
    points: Vec<LonLat>,
}

/// Where the reader is.
#[derive(Default)]
struct State {
    partfields: Vec<Partfield>,
    /// The open polygon's type and rings.
    polygon: Option<(String, Vec<Vec<LonLat>>)>,
    /// The open guidance pattern: its name and whether it is a curve.
    pattern: Option<(Option<String>, bool)>,
    /// The open line string: its type, name and points.
    line: Option<(String, Option<String>, Vec<LonLat>)>,
    /// External files named by `XFR`.
    external: Vec<String>,
    /// Whether the root element was TaskData.
    task_data: bool,
}

/// The parcels of TaskData: `main` is `TASKDATA.XML`'s text, `external(name)` the text of an
/// external file it names (`PFD00001` for `PFD00001.XML`), where there is one.
pub fn read_taskdata(
    main: &str,
    external: impl Fn(&str) -> Option<String>,
) -> Result<Vec<Parcel>, PlanError> {
    let mut state = State::default();
    read_xml(main, &mut state)?;
    if !state.task_data {
        return Err(PlanError::new(
            ErrorCode::InvalidFile,
            "the XML is not ISOXML TaskData (its root is not ISO11783_TaskData)",
        ));
    }
    for name in std::mem::take(&mut state.external) {
        if let Some(text) = external(&name) {
            read_xml(&text, &mut state)?;
        }
    }
    parcels_of(state.partfields)
}

fn read_xml(text: &str, state: &mut State) -> Result<(), PlanError> {
    let mut reader = quick_xml::Reader::from_str(text);
    let mut depth = 0usize;
    loop {
        let event = reader.read_event().map_err(|_| {
            PlanError::new(
                ErrorCode::InvalidFile,
                "the TaskData file is not well-formed XML (cut short, or damaged): export it again",
            )
        })?;
        match event {
            Event::Start(e) => {
                depth += 1;
                open(&e, state);
            }
            Event::Empty(e) => {
                open(&e, state);
                close(e.name().as_ref(), state);
            }
            Event::End(e) => {
                depth = depth.saturating_sub(1);
                close(e.name().as_ref(), state);
            }
            Event::Eof if depth == 0 => return Ok(()),
            Event::Eof => {
                return Err(PlanError::new(
                    ErrorCode::InvalidFile,
                    "the TaskData file is cut short: export it again",
                ))
            }
            _ => {}
        }
    }
}

/// An attribute's value, unescaped.
fn attr(e: &BytesStart<'_>, key: &[u8]) -> Option<String> {
    e.attributes()
        .flatten()
        .find(|a| a.key.as_ref() == key)
        .and_then(|a| {
            a.normalized_value(quick_xml::XmlVersion::Implicit1_0)
                .ok()
                .map(|v| v.trim().to_string())
        })
}

fn open(e: &BytesStart<'_>, state: &mut State) {
    match e.name().as_ref() {
        b"ISO11783_TaskData" => state.task_data = true,
        b"XFR" => state.external.extend(attr(e, b"A")),
        b"PFD" => state.partfields.push(Partfield {
            name: attr(e, b"C"),
            id: attr(e, b"A"),
            ..Partfield::default()
        }),
        b"PLN" => state.polygon = Some((attr(e, b"A").unwrap_or_default(), Vec::new())),
        b"GPN" => state.pattern = Some((attr(e, b"B"), attr(e, b"C").as_deref() == Some("3"))),
        b"LSG" => state.line = Some((attr(e, b"A").unwrap_or_default(), attr(e, b"B"), Vec::new())),
        b"PNT" => {
            let (north, east) = (attr(e, b"C"), attr(e, b"D"));
            let point = north
                .zip(east)
                .and_then(|(n, e)| Some([e.parse().ok()?, n.parse().ok()?]));
            if let (Some((_, _, points)), Some(p)) = (&mut state.line, point) {
                points.push(p);
            }
        }
        _ => {}
    }
}

fn close(name: &[u8], state: &mut State) {
    match name {
        b"LSG" => close_line(state),
        b"PLN" => {
            if let (Some(polygon), Some(pfd)) = (state.polygon.take(), state.partfields.last_mut())
            {
                pfd.polygons.push(polygon);
            }
        }
        b"GPN" => state.pattern = None,
        _ => {}
    }
}

/// A line string ends: a ring of the open polygon, the line of the open guidance pattern, or
/// (version 3) a guidance line of type 5 of the partfield.
fn close_line(state: &mut State) {
    let Some((kind, name, points)) = state.line.take() else {
        return;
    };
    if let Some((_, rings)) = &mut state.polygon {
        rings.push(points);
        return;
    }
    let Some(pfd) = state.partfields.last_mut() else {
        return;
    };
    let guidance = match &state.pattern {
        Some((pattern, curve)) => Some(Guidance {
            name: pattern.clone().or(name),
            curve: *curve,
            points,
        }),
        None if kind == "5" => Some(Guidance {
            name,
            curve: points.len() > 2,
            points,
        }),
        None => None,
    };
    pfd.guidance
        .extend(guidance.filter(|g| g.points.len() >= 2));
}

/// Each partfield with a boundary as a parcel.
fn parcels_of(partfields: Vec<Partfield>) -> Result<Vec<Parcel>, PlanError> {
    let count = partfields.len();
    let mut parcels = Vec::new();
    let mut without: Vec<String> = Vec::new();
    for (record, pfd) in partfields.into_iter().enumerate() {
        match parcel_of(&pfd, record) {
            Some(p) => parcels.push(p),
            None => without.push(
                pfd.name
                    .or(pfd.id)
                    .unwrap_or_else(|| format!("{}", record + 1)),
            ),
        }
    }
    if parcels.is_empty() {
        return Err(PlanError::new(
            ErrorCode::NoBoundary,
            if count == 0 {
                "the TaskData holds no partfield (PFD): there is no field in it".to_string()
            } else {
                format!(
                    "no partfield of the TaskData has a boundary (a polygon of type 1): {}",
                    without.join(", ")
                )
            },
        ));
    }
    Ok(parcels)
}

fn parcel_of(pfd: &Partfield, record: usize) -> Option<Parcel> {
    let ring = |r: &Vec<LonLat>| -> LineString { r.iter().map(|&[x, y]| Coord { x, y }).collect() };
    let boundary = ["1", "9"].iter().find_map(|t| {
        pfd.polygons
            .iter()
            .find(|(kind, rings)| kind == t && !rings.is_empty())
    })?;
    let mut holes: Vec<LineString> = boundary.1[1..].iter().map(ring).collect();
    for (kind, rings) in &pfd.polygons {
        if matches!(kind.as_str(), "3" | "4" | "6") {
            holes.extend(rings.first().map(ring));
        }
    }
    let polygon = Polygon::new(ring(&boundary.1[0]), holes);
    let mut properties = Map::new();
    if let Some(name) = &pfd.name {
        properties.insert("name".into(), Value::from(name.as_str()));
    }
    if let Some(id) = &pfd.id {
        properties.insert("id".into(), Value::from(id.as_str()));
    }
    if !pfd.guidance.is_empty() {
        let lines: Vec<Value> = pfd
            .guidance
            .iter()
            .map(|g| json!({ "name": g.name, "kind": if g.curve { "curve" } else { "ab" }, "coordinates": g.points }))
            .collect();
        properties.insert("guidance".into(), Value::Array(lines));
    }
    if let Some(ab) = pfd.guidance.iter().find(|g| !g.curve) {
        let (a, b) = (ab.points[0], ab.points[ab.points.len() - 1]);
        properties.insert("reference_line".into(), json!([a, b]));
    }
    Some(Parcel {
        polygon,
        properties,
        record,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const V4: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<ISO11783_TaskData VersionMajor="4" VersionMinor="3" DataTransferOrigin="1">
 <PFD A="PFD1" C="North &amp; South" D="120000">
  <PLN A="1"><LSG A="1">
   <PNT A="2" C="60.25" D="24.05"/><PNT A="2" C="60.25" D="24.056"/>
   <PNT A="2" C="60.252" D="24.056"/><PNT A="2" C="60.252" D="24.05"/>
  </LSG></PLN>
  <PLN A="6"><LSG A="1">
   <PNT A="2" C="60.2505" D="24.052"/><PNT A="2" C="60.2505" D="24.053"/><PNT A="2" C="60.251" D="24.053"/>
  </LSG></PLN>
  <GGP A="GGP1" B="Lines"><GPN A="GPN1" B="AB 1" C="1"><LSG A="5">
   <PNT A="6" C="60.25" D="24.051"/><PNT A="7" C="60.252" D="24.052"/>
  </LSG></GPN>
  <GPN A="GPN2" B="Curve" C="3"><LSG A="5">
   <PNT A="6" C="60.25" D="24.05"/><PNT A="9" C="60.251" D="24.051"/><PNT A="7" C="60.252" D="24.05"/>
  </LSG></GPN></GGP>
 </PFD>
 <PFD A="PFD2" C="No boundary"/>
</ISO11783_TaskData>"#;

    #[test]
    fn a_partfield_s_boundary_obstacles_and_guidance_are_read() {
        let parcels = read_taskdata(V4, |_| None).unwrap();
        assert_eq!(parcels.len(), 1);
        let p = &parcels[0];
        assert_eq!(p.properties["name"], "North & South");
        assert_eq!(
            p.polygon.exterior().0[1],
            Coord {
                x: 24.056,
                y: 60.25
            }
        );
        assert_eq!(p.polygon.interiors().len(), 1);
        assert_eq!(
            p.properties["reference_line"],
            json!([[24.051, 60.25], [24.052, 60.252]])
        );
        let guidance = p.properties["guidance"].as_array().unwrap();
        assert_eq!(guidance.len(), 2);
        assert_eq!(guidance[1]["kind"], "curve");
    }

    #[test]
    fn version_3_guidance_and_external_partfields_are_read() {
        let main =
            r#"<ISO11783_TaskData VersionMajor="3"><XFR A="PFD00001" B="1"/></ISO11783_TaskData>"#;
        let pfd = r#"<XFC><PFD A="PFD1" C="Far"><PLN A="1"><LSG A="1"><PNT A="2" C="1" D="2"/><PNT A="2" C="1" D="3"/><PNT A="2" C="2" D="3"/></LSG></PLN>
            <LSG A="5" B="AB"><PNT A="6" C="1.1" D="2.1"/><PNT A="7" C="1.9" D="2.9"/></LSG></PFD></XFC>"#;
        let parcels =
            read_taskdata(main, |name| (name == "PFD00001").then(|| pfd.to_string())).unwrap();
        assert_eq!(parcels.len(), 1);
        assert_eq!(
            parcels[0].properties["reference_line"],
            json!([[2.1, 1.1], [2.9, 1.9]])
        );
    }

    #[test]
    fn not_task_data_and_no_boundary_are_refused() {
        let e = read_taskdata("<kml/>", |_| None).unwrap_err();
        assert_eq!(e.code, ErrorCode::InvalidFile);
        let e = read_taskdata(
            r#"<ISO11783_TaskData><PFD A="PFD1" C="Bare"/></ISO11783_TaskData>"#,
            |_| None,
        )
        .unwrap_err();
        assert_eq!(e.code, ErrorCode::NoBoundary);
        assert!(e.message.contains("Bare"), "{}", e.message);
        let e = read_taskdata(&V4[..V4.len() / 2], |_| None).unwrap_err();
        assert_eq!(e.code, ErrorCode::InvalidFile);
    }
}
