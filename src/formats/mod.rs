//! Fields from the files farm software exports, read into the GeoJSON the planner takes.
//!
//! A field lives in a farm management system or a terminal, not in GeoJSON: most export zipped
//! Shapefiles, Google Earth KML and KMZ. [`read_field_file`] takes such a file's bytes and gives its parcels, each a
//! polygon in WGS84 longitude and latitude with its attributes, as a GeoJSON FeatureCollection
//! ([`FieldFile::to_geojson_string`]): a file of one parcel plans as it is, a file of several
//! is a register's export to pick one from (the viewer lists them; the CLI's `--parcel`).
//!
//! - [`zip`]: the files of a zip archive.
//! - [`shapefile`]: the parcels of a Shapefile.
//! - [`kml`]: the parcels of KML (and of KMZ, a zip of it).
//! - [`taskdata`]: the partfields of ISOXML TaskData (and of its zip), with their guidance.
//! - [`crs`]: the coordinate systems they come in, converted to WGS84.
//! - [`isoxml`]: a plan written as ISO 11783-10 TaskData, for ISOBUS terminals.
//! - [`plan_kml`]: a plan written as KML, for Google Earth.
//! - [`outline`]: what both start from, the field's outline and the plan's features.

pub mod crs;
pub mod isoxml;
pub mod kml;
pub mod outline;
pub mod plan_kml;
pub mod shapefile;
pub mod taskdata;
pub mod zip;

use self::shapefile::{read_shapefile, ShapefileParts};
use crate::error::{ErrorCode, PlanError};
use geo::Polygon;
use serde_json::{json, Map, Value};

/// The largest file read: a Shapefile of a farm's fields is a few megabytes.
pub const MAX_FILE_BYTES: usize = 64 << 20;

/// One parcel of a file: its outline (and holes) in WGS84 longitude and latitude.
#[derive(Debug, Clone)]
pub struct Parcel {
    /// Longitude and latitude, degrees.
    pub polygon: Polygon,
    /// Its attributes in the file (a Shapefile's `.dbf` columns), and `part` where its record
    /// held several polygons.
    pub properties: Map<String, Value>,
    /// The record of the file it comes from (0 for the first).
    pub record: usize,
}

impl Parcel {
    /// The parcels of one record of a file (a Shapefile record, a placemark): each of its
    /// polygons, with the record's properties and, where it has several, `part`.
    pub fn parts(
        polygons: Vec<Polygon>,
        properties: &Map<String, Value>,
        record: usize,
    ) -> impl Iterator<Item = Parcel> + '_ {
        let several = polygons.len() > 1;
        polygons
            .into_iter()
            .enumerate()
            .map(move |(part, polygon)| {
                let mut properties = properties.clone();
                if several {
                    properties.insert("part".into(), Value::from(part));
                }
                Parcel {
                    polygon,
                    properties,
                    record,
                }
            })
    }
}

/// What a field file holds.
#[derive(Debug, Clone)]
pub struct FieldFile {
    /// Its parcels, in the file's order.
    pub parcels: Vec<Parcel>,
    /// The format read: `"shapefile"`, `"kml"`, `"kmz"` or `"isoxml"`.
    pub format: &'static str,
    /// The coordinate system the file was in, converted from: `"EPSG:28992 (Amersfoort / RD New)"`.
    pub crs: String,
}

/// The parcels of a field file: a zipped Shapefile (`.zip` holding `.shp`, `.shx`, `.dbf`
/// and `.prj`), KML or KMZ. `name` is the file's name, for messages.
///
/// ```
/// use furrow::formats::read_field_file;
///
/// let kml = br#"<kml xmlns="http://www.opengis.net/kml/2.2"><Placemark><name>North</name>
///   <Polygon><outerBoundaryIs><LinearRing><coordinates>24.05,60.25 24.056,60.25
///   24.056,60.252 24.05,60.25</coordinates></LinearRing></outerBoundaryIs></Polygon>
///   </Placemark></kml>"#;
/// let file = read_field_file(kml, "fields.kml")?;
/// assert_eq!(file.format, "kml");
/// assert_eq!(file.parcels[0].properties["name"], "North");
/// let e = read_field_file(b"TASKDATA", "TASKDATA.XML").unwrap_err();
/// assert_eq!(e.code, furrow::ErrorCode::InvalidFile);
/// # Ok::<(), furrow::PlanError>(())
/// ```
pub fn read_field_file(bytes: &[u8], name: &str) -> Result<FieldFile, PlanError> {
    if bytes.len() > MAX_FILE_BYTES {
        return Err(PlanError::new(
            ErrorCode::InputTooLarge,
            format!(
                "the file is {} MB, more than the {} MB a field file may be",
                bytes.len() >> 20,
                MAX_FILE_BYTES >> 20
            ),
        ));
    }
    if bytes.starts_with(b"PK") {
        let files = zip::unzip(bytes)?;
        let named: Vec<(&str, &[u8])> = files
            .iter()
            .map(|f| (f.path.as_str(), f.bytes.as_slice()))
            .collect();
        let taskdata = named.iter().find(|(p, _)| {
            p.rsplit('/')
                .next()
                .is_some_and(|f| f.eq_ignore_ascii_case("TASKDATA.XML"))
        });
        if let Some(&(path, text)) = taskdata {
            let folder = &path[..path.len() - "TASKDATA.XML".len()];
            let external = |name: &str| {
                let wanted = format!("{folder}{name}.XML");
                named
                    .iter()
                    .find(|(p, _)| p.eq_ignore_ascii_case(&wanted))
                    .map(|(_, b)| String::from_utf8_lossy(b).into_owned())
            };
            return read_taskdata_file(text, external);
        }
        let kml = named.iter().find(|(p, _)| has_extension(p, ".kml"));
        if let (Some(&(_, text)), false) =
            (kml, named.iter().any(|(p, _)| has_extension(p, ".shp")))
        {
            return read_kml_file(text, "kmz");
        }
        return read_shapefile_files(&named);
    }
    match root_element(bytes).as_deref() {
        Some("kml") => return read_kml_file(bytes, "kml"),
        Some("ISO11783_TaskData") => return read_taskdata_file(bytes, |_| None),
        _ => {}
    }
    Err(PlanError::new(
        ErrorCode::InvalidFile,
        format!(
            "{name} is not a file furrow reads: a field is GeoJSON, KML or KMZ, ISOXML TaskData (TASKDATA.XML, or its zip), or a zipped Shapefile (.zip with .shp, .shx, .dbf and .prj)"
        ),
    ))
}

/// Whether `bytes` is a field file of a format [`read_field_file`] reads (a zip archive, KML
/// or TaskData), rather than GeoJSON: by its first bytes.
pub fn is_field_file(bytes: &[u8]) -> bool {
    bytes.starts_with(b"PK") || root_element(bytes).is_some()
}

/// The name of the first element of XML text (its local name, without a prefix), if `bytes`
/// is XML.
fn root_element(bytes: &[u8]) -> Option<String> {
    let head = String::from_utf8_lossy(&bytes[..bytes.len().min(4096)]);
    let mut rest = head.trim_start_matches('\u{feff}').trim_start();
    // The declaration, comments and processing instructions before the first element.
    while let Some(after) = rest.strip_prefix("<?").or_else(|| rest.strip_prefix("<!")) {
        rest = after[after.find('>')? + 1..].trim_start();
    }
    let element = rest.strip_prefix('<')?;
    let tag: String = element
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == ':' || *c == '_' || *c == '-')
        .collect();
    tag.rsplit(':')
        .next()
        .filter(|t| !t.is_empty())
        .map(str::to_string)
}

fn read_taskdata_file(
    bytes: &[u8],
    external: impl Fn(&str) -> Option<String>,
) -> Result<FieldFile, PlanError> {
    let text = String::from_utf8_lossy(bytes);
    Ok(FieldFile {
        parcels: taskdata::read_taskdata(&text, external)?,
        format: "isoxml",
        crs: "EPSG:4326 (WGS 84)".into(),
    })
}

fn read_kml_file(bytes: &[u8], format: &'static str) -> Result<FieldFile, PlanError> {
    let text = std::str::from_utf8(bytes).map_err(|_| {
        PlanError::new(
            ErrorCode::InvalidFile,
            "the KML file is not UTF-8 text, as KML must be: export it again",
        )
    })?;
    Ok(FieldFile {
        parcels: kml::read_kml(text)?,
        format,
        crs: "EPSG:4326 (WGS 84)".into(),
    })
}

/// Whether `path` ends in `ext` (`.shp`), in any case.
fn has_extension(path: &str, ext: &str) -> bool {
    path.len() > ext.len()
        && path.is_char_boundary(path.len() - ext.len())
        && path[path.len() - ext.len()..].eq_ignore_ascii_case(ext)
}

/// The parcels of a Shapefile given as its files (name and bytes): those of a zip archive, or
/// the parts dropped together. The first `.shp` is read, with the files of the same name.
pub fn read_shapefile_files(files: &[(&str, &[u8])]) -> Result<FieldFile, PlanError> {
    let extension = has_extension;
    let stem_of = |path: &str| path[..path.len() - 4].to_string();
    let shp = files.iter().find(|(p, _)| extension(p, ".shp"));
    let Some(&(shp_path, shp)) = shp else {
        return Err(PlanError::new(
            ErrorCode::InvalidFile,
            "the files hold no Shapefile: no .shp file (the shapes) among them",
        ));
    };
    let stem = stem_of(shp_path);
    let part = |ext: &str| {
        files
            .iter()
            .find(|(p, _)| extension(p, ext) && stem_of(p) == stem)
            .map(|&(_, bytes)| bytes)
    };
    let parts = ShapefileParts {
        shp: Some(shp),
        shx: part(".shx"),
        dbf: part(".dbf"),
        prj: part(".prj"),
    };
    let (parcels, crs) = read_shapefile(parts)?;
    Ok(FieldFile {
        parcels,
        format: "shapefile",
        crs: format!("EPSG:{} ({})", crs.epsg, crs.name),
    })
}

impl FieldFile {
    /// The parcels as a GeoJSON FeatureCollection of Polygon features (coordinates to nine
    /// decimals, a tenth of a millimetre), with their attributes as properties; and the
    /// format and the system read from as the collection's `source`.
    ///
    /// A file of one parcel whose properties have a `reference_line` (a TaskData partfield's AB
    /// line) is a field the planner reads as it is: the parcel is its `boundary`, the line its
    /// `reference_line` feature, which the swaths follow.
    pub fn to_geojson(&self) -> Value {
        let mut features: Vec<Value> = self
            .parcels
            .iter()
            .map(|p| {
                json!({
                    "type": "Feature",
                    "properties": p.properties,
                    "geometry": polygon_json(&p.polygon),
                })
            })
            .collect();
        if let ([parcel], [feature]) = (self.parcels.as_slice(), features.as_mut_slice()) {
            if let Some(line) = parcel.properties.get("reference_line") {
                feature["properties"]["role"] = json!("boundary");
                let line = json!({
                    "type": "Feature",
                    "properties": { "role": "reference_line" },
                    "geometry": { "type": "LineString", "coordinates": line },
                });
                features.push(line);
            }
        }
        json!({
            "type": "FeatureCollection",
            "source": { "format": self.format, "crs": self.crs },
            "features": features,
        })
    }

    /// [`to_geojson`](Self::to_geojson) as text.
    pub fn to_geojson_string(&self) -> String {
        self.to_geojson().to_string()
    }
}

fn polygon_json(polygon: &Polygon) -> Value {
    let ring = |line: &geo::LineString| -> Value {
        line.0
            .iter()
            .map(|c| json!([round9(c.x), round9(c.y)]))
            .collect()
    };
    let mut rings = vec![ring(polygon.exterior())];
    rings.extend(polygon.interiors().iter().map(ring));
    json!({ "type": "Polygon", "coordinates": rings })
}

fn round9(x: f64) -> f64 {
    (x * 1e9).round() / 1e9
}
