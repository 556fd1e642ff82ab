//! Field files read back: zipped Shapefiles written by an independent program (GDAL's ogr2ogr,
//! `scripts/format-fixtures.sh`) from the register parcels of `tests/fields/real/`, in the
//! national grids of their registers (RD New for the Netherlands with ESRI's `.prj`, which
//! names no datum shift; ETRS89 / UTM 32N for Denmark and Germany; TM35FIN for Finland), in
//! UTM on WGS84 and in WGS84, and KML and KMZ written by GDAL too, give the parcels' polygons
//! within a centimetre. Damaged and unknown files give typed errors, and no file panics the
//! reader.

#![cfg(feature = "formats")]
#![allow(clippy::result_large_err)] // the planner's error, as every public function returns it

use furrow::formats::zip::unzip;
use furrow::formats::{read_field_file, read_shapefile_files, FieldFile, MAX_FILE_BYTES};
use furrow::ErrorCode;
use proptest::prelude::*;
use serde_json::Value;

const FIXTURES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/format-fixtures");
const REAL: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fields/real");

fn fixture(name: &str) -> Vec<u8> {
    fixture_file(&format!("{name}.zip"))
}

fn fixture_file(file: &str) -> Vec<u8> {
    std::fs::read(format!("{FIXTURES}/{file}")).unwrap()
}

/// The parcels' rings as the register's GeoJSON has them: `[parcel][ring][vertex]`.
fn register(name: &str) -> Vec<Vec<Vec<[f64; 2]>>> {
    let text = std::fs::read_to_string(format!("{REAL}/{name}.geojson")).unwrap();
    let json: Value = serde_json::from_str(&text).unwrap();
    json["features"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| rings_of(&f["geometry"]["coordinates"]))
        .collect()
}

fn rings_of(coordinates: &Value) -> Vec<Vec<[f64; 2]>> {
    coordinates
        .as_array()
        .unwrap()
        .iter()
        .map(|ring| {
            ring.as_array()
                .unwrap()
                .iter()
                .map(|p| [p[0].as_f64().unwrap(), p[1].as_f64().unwrap()])
                .collect()
        })
        .collect()
}

/// The parcels read, by record: `[record][ring][vertex]` (a record's parts together).
fn read_back(file: &FieldFile) -> Vec<Vec<Vec<[f64; 2]>>> {
    let json = file.to_geojson();
    let mut records: Vec<Vec<Vec<[f64; 2]>>> = Vec::new();
    for (parcel, feature) in file
        .parcels
        .iter()
        .zip(json["features"].as_array().unwrap())
    {
        if records.len() <= parcel.record {
            records.resize(parcel.record + 1, Vec::new());
        }
        records[parcel.record].extend(rings_of(&feature["geometry"]["coordinates"]));
    }
    records
}

/// Metres between two longitude-latitude points (a local flat approximation: fine at the
/// centimetres compared).
fn metres(a: [f64; 2], b: [f64; 2]) -> f64 {
    let k = std::f64::consts::PI / 180.0 * 6_371_000.0;
    let dx = (a[0] - b[0]) * k * a[1].to_radians().cos();
    let dy = (a[1] - b[1]) * k;
    dx.hypot(dy)
}

/// The farthest any vertex of one set of rings lies from the nearest vertex of the other, both
/// ways, metres; infinite where they differ in their number of vertices.
fn vertex_distance(a: &[Vec<[f64; 2]>], b: &[Vec<[f64; 2]>]) -> f64 {
    let pa: Vec<[f64; 2]> = a.iter().flatten().copied().collect();
    let pb: Vec<[f64; 2]> = b.iter().flatten().copied().collect();
    if pa.len() != pb.len() || a.len() != b.len() {
        return f64::INFINITY;
    }
    let one_way = |from: &[[f64; 2]], to: &[[f64; 2]]| {
        from.iter()
            .map(|&p| {
                to.iter()
                    .map(|&q| metres(p, q))
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max)
    };
    one_way(&pa, &pb).max(one_way(&pb, &pa))
}

fn assert_same_parcels(fixture_name: &str, register_name: &str, crs: &str) {
    let file = read_field_file(&fixture(fixture_name), &format!("{fixture_name}.zip")).unwrap();
    assert_eq!(file.format, "shapefile");
    assert_eq!(file.crs, crs, "{fixture_name}");
    assert_same_as_register(&file, fixture_name, register_name);
}

fn assert_same_as_register(file: &FieldFile, fixture_name: &str, register_name: &str) {
    let expected = register(register_name);
    let got = read_back(file);
    assert_eq!(got.len(), expected.len(), "{fixture_name}: parcels");
    for (i, (g, e)) in got.iter().zip(&expected).enumerate() {
        let d = vertex_distance(g, e);
        assert!(
            d < 0.01,
            "{fixture_name}: parcel {i} read {d} m from the register's"
        );
    }
}

#[test]
fn rd_new_with_esri_s_prj_reads_back_where_the_parcels_are() {
    assert_same_parcels(
        "nl_brp_rd_new",
        "nl_brp_2023_sample",
        "EPSG:28992 (Amersfoort / RD New)",
    );
}

#[test]
fn etrs89_utm_32n_reads_back_the_danish_parcels() {
    assert_same_parcels(
        "dk_marker_etrs89_utm32n",
        "dk_marker_2026_sample",
        "EPSG:25832 (ETRS89 / UTM zone 32N)",
    );
}

#[test]
fn tm35fin_reads_back_the_parcels() {
    assert_same_parcels(
        "dk_marker_tm35fin",
        "dk_marker_2026_sample",
        "EPSG:3067 (ETRS89 / TM35FIN(E,N))",
    );
}

#[test]
fn utm_on_wgs84_and_wgs84_read_back_the_parcels() {
    assert_same_parcels(
        "dk_marker_wgs84_utm32n",
        "dk_marker_2026_sample",
        "EPSG:32632 (WGS 84 / UTM zone 32N)",
    );
    assert_same_parcels("nl_brp_wgs84", "nl_brp_2023_sample", "EPSG:4326 (WGS 84)");
}

#[test]
fn without_a_prj_degrees_are_wgs84_and_metres_are_refused() {
    assert_same_parcels(
        "nl_brp_wgs84_no_prj",
        "nl_brp_2023_sample",
        "EPSG:4326 (WGS 84)",
    );
    let e = read_field_file(&fixture("dk_marker_utm32n_no_prj"), "x.zip").unwrap_err();
    assert_eq!(e.code, ErrorCode::UnknownCrs);
    assert!(e.message.contains(".prj"), "{}", e.message);
}

#[test]
fn the_attributes_come_with_each_parcel() {
    let file = read_field_file(&fixture("dk_marker_etrs89_utm32n"), "dk.zip").unwrap();
    let first = &file.parcels[0].properties;
    assert_eq!(first["id"], "dk_marker_2026_sample_000");
    // dBase names are at most 10 characters: ogr2ogr cut `src_Afgroede` short.
    assert_eq!(first["src_Afgroe"], "Poppel");
    assert_eq!(first["area_ha"], 4.0399);
}

#[test]
fn kml_and_kmz_read_back_the_parcels_with_their_names() {
    for (file_name, format) in [("dk_marker.kml", "kml"), ("dk_marker.kmz", "kmz")] {
        let file = read_field_file(&fixture_file(file_name), file_name).unwrap();
        assert_eq!(file.format, format);
        assert_eq!(file.crs, "EPSG:4326 (WGS 84)");
        assert_same_as_register(&file, file_name, "dk_marker_2026_sample");
        let first = &file.parcels[0].properties;
        assert_eq!(first["name"], "dk_marker_2026_sample_000");
        assert_eq!(first["src_Afgroede"], "Poppel");
    }
}

#[test]
fn isoxml_taskdata_v4_and_v3_read_back_the_parcels_with_their_ab_lines() {
    for (file_name, register_name) in [
        ("dk_marker_taskdata_v4.zip", "dk_marker_2026_sample"),
        ("nl_brp_taskdata_v3.zip", "nl_brp_2023_sample"),
    ] {
        let file = read_field_file(&fixture_file(file_name), file_name).unwrap();
        assert_eq!(file.format, "isoxml");
        assert_same_as_register(&file, file_name, register_name);
        // Each partfield's AB line (written along its first edge) is its reference line.
        let register = register(register_name);
        for (parcel, rings) in file.parcels.iter().zip(&register) {
            let line = &parcel.properties["reference_line"];
            let a = [line[0][0].as_f64().unwrap(), line[0][1].as_f64().unwrap()];
            let b = [line[1][0].as_f64().unwrap(), line[1][1].as_f64().unwrap()];
            assert!(
                metres(a, rings[0][0]) < 0.01 && metres(b, rings[0][1]) < 0.01,
                "{file_name}"
            );
            assert_eq!(parcel.properties["guidance"][0]["kind"], "ab");
        }
    }
    // A file of one partfield is a field the planner reads as it is: its boundary and the AB
    // line its swaths follow.
    let one = r#"<ISO11783_TaskData VersionMajor="4"><PFD A="PFD1" C="One">
        <PLN A="1"><LSG A="1"><PNT A="2" C="60.25" D="24.05"/><PNT A="2" C="60.25" D="24.056"/>
        <PNT A="2" C="60.252" D="24.056"/><PNT A="2" C="60.252" D="24.05"/></LSG></PLN>
        <GGP A="GGP1"><GPN A="GPN1" C="1"><LSG A="5"><PNT A="6" C="60.25" D="24.05"/>
        <PNT A="7" C="60.252" D="24.0505"/></LSG></GPN></GGP></PFD></ISO11783_TaskData>"#;
    let file = read_field_file(one.as_bytes(), "TASKDATA.XML").unwrap();
    let geojson = file.to_geojson_string();
    let plan = furrow::plan_geojson(&geojson, &furrow::PlanOptions::default()).unwrap();
    assert_eq!(
        plan.summary.direction.mode,
        furrow::direction::DirectionMode::Reference
    );
}

/// The fixture's files (unzipped) but those whose name ends in one of `leave_out`.
fn parts_without(name: &str, leave_out: &[&str]) -> Vec<(String, Vec<u8>)> {
    unzip(&fixture(name))
        .unwrap()
        .into_iter()
        .filter(|f| !leave_out.iter().any(|ext| f.path.ends_with(ext)))
        .map(|f| (f.path, f.bytes))
        .collect()
}

fn read_parts(parts: &[(String, Vec<u8>)]) -> Result<FieldFile, furrow::PlanError> {
    let named: Vec<(&str, &[u8])> = parts
        .iter()
        .map(|(p, b)| (p.as_str(), b.as_slice()))
        .collect();
    read_shapefile_files(&named)
}

#[test]
fn the_parts_dropped_together_read_as_the_zip_does() {
    let parts = parts_without("nl_brp_rd_new", &[]);
    let file = read_parts(&parts).unwrap();
    assert_eq!(file.parcels.len(), 53);
    assert_eq!(file.crs, "EPSG:28992 (Amersfoort / RD New)");
}

#[test]
fn damaged_and_unknown_files_give_typed_errors() {
    let zip = fixture("nl_brp_rd_new");
    // A truncated download.
    let e = read_field_file(&zip[..zip.len() * 2 / 3], "cut.zip").unwrap_err();
    assert_eq!(e.code, ErrorCode::InvalidFile);
    // No .shp among the files.
    let e = read_parts(&parts_without("nl_brp_rd_new", &[".shp"])).unwrap_err();
    assert_eq!(e.code, ErrorCode::InvalidFile);
    assert!(e.message.contains(".shp"), "{}", e.message);
    // A .prj of a system furrow does not convert from, named in the error.
    let mut parts = parts_without("nl_brp_rd_new", &[".prj"]);
    parts.push((
        "nl_brp_rd_new.prj".into(),
        br#"PROJCS["DHDN_3_Degree_Gauss_Zone_3",GEOGCS["GCS_Deutsches_Hauptdreiecksnetz"]]"#
            .to_vec(),
    ));
    let e = read_parts(&parts).unwrap_err();
    assert_eq!(e.code, ErrorCode::UnknownCrs);
    assert!(
        e.message.contains("DHDN_3_Degree_Gauss_Zone_3"),
        "{}",
        e.message
    );
    // A .shp cut short.
    let mut parts = parts_without("nl_brp_rd_new", &[]);
    for (path, bytes) in &mut parts {
        if path.ends_with(".shp") {
            bytes.truncate(bytes.len() / 2);
        }
    }
    assert_eq!(read_parts(&parts).unwrap_err().code, ErrorCode::InvalidFile);
    // Not a zip or a Shapefile at all, XML that is not TaskData, a partfield without a
    // boundary, and a file over the size cap.
    let e = read_field_file(b"TASKDATA", "TASKDATA.XML").unwrap_err();
    assert_eq!(e.code, ErrorCode::InvalidFile);
    let e = read_field_file(b"<?xml version=\"1.0\"?><gpx/>", "track.gpx").unwrap_err();
    assert_eq!(e.code, ErrorCode::InvalidFile);
    let bare =
        br#"<ISO11783_TaskData VersionMajor="4"><PFD A="PFD1" C="Bare"/></ISO11783_TaskData>"#;
    let e = read_field_file(bare, "TASKDATA.XML").unwrap_err();
    assert_eq!(e.code, ErrorCode::NoBoundary);
    assert!(e.message.contains("Bare"), "{}", e.message);
    let huge = vec![0u8; MAX_FILE_BYTES + 1];
    assert_eq!(
        read_field_file(&huge, "huge.zip").unwrap_err().code,
        ErrorCode::InputTooLarge
    );
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// A zip archive with bytes changed or cut off reads or gives a typed error.
    #[test]
    fn a_damaged_zip_never_panics(
        cut in 0.0..1.0f64,
        changes in prop::collection::vec((0.0..1.0f64, any::<u8>()), 0..8),
    ) {
        let mut zip = fixture("nl_brp_wgs84");
        for (at, byte) in changes {
            let i = ((zip.len() - 1) as f64 * at) as usize;
            zip[i] = byte;
        }
        let keep = (zip.len() as f64 * cut) as usize;
        if let Err(e) = read_field_file(&zip[..keep.max(2)], "x.zip") {
            prop_assert_ne!(e.code, ErrorCode::Internal);
        }
    }

    /// KML with bytes changed or cut off reads or gives a typed error (and returns: the `kml`
    /// crate never returns on some files cut short).
    #[test]
    fn a_damaged_kml_never_panics(
        cut in 0.0..1.0f64,
        changes in prop::collection::vec((0.0..1.0f64, prop::sample::select(b"<>/\"= a1.,-".to_vec())), 0..8),
    ) {
        let mut kml = fixture_file("dk_marker.kml");
        kml.truncate(60_000);
        kml.extend_from_slice(b"</Folder></Document></kml>");
        for (at, byte) in changes {
            let i = ((kml.len() - 1) as f64 * at) as usize;
            kml[i] = byte;
        }
        let keep = (kml.len() as f64 * cut) as usize;
        if let Err(e) = read_field_file(&kml[..keep.max(5)], "x.kml") {
            prop_assert_ne!(e.code, ErrorCode::Internal);
        }
    }

    /// TaskData with bytes changed or cut off reads or gives a typed error.
    #[test]
    fn a_damaged_taskdata_never_panics(
        cut in 0.0..1.0f64,
        changes in prop::collection::vec((0.0..1.0f64, prop::sample::select(b"<>/\"= A1.,-".to_vec())), 0..8),
    ) {
        let zip = fixture_file("nl_brp_taskdata_v3.zip");
        let mut xml = unzip(&zip).unwrap().into_iter().find(|f| f.path.ends_with(".XML")).unwrap().bytes;
        xml.truncate(40_000);
        for (at, byte) in changes {
            let i = ((xml.len() - 1) as f64 * at) as usize;
            xml[i] = byte;
        }
        let keep = (xml.len() as f64 * cut) as usize;
        if let Err(e) = read_field_file(&xml[..keep.max(5)], "TASKDATA.XML") {
            prop_assert_ne!(e.code, ErrorCode::Internal);
        }
    }

    /// A Shapefile whose .shp, .shx, .dbf or .prj has bytes changed (headers, counts and sizes
    /// included) reads or gives a typed error.
    #[test]
    fn a_damaged_shapefile_never_panics(
        part in 0usize..4,
        changes in prop::collection::vec((0.0..1.0f64, any::<u8>()), 1..12),
        head in any::<bool>(),
    ) {
        let mut parts = parts_without("dk_marker_etrs89_utm32n", &[".cpg"]);
        parts.sort_by(|a, b| a.0.cmp(&b.0)); // .dbf, .prj, .shp, .shx
        let bytes = &mut parts[part].1;
        for (at, byte) in changes {
            // Half the time in the first 120 bytes: the headers, counts and sizes.
            let span = if head { bytes.len().min(120) } else { bytes.len() };
            let i = ((span - 1) as f64 * at) as usize;
            bytes[i] = byte;
        }
        if let Err(e) = read_parts(&parts) {
            prop_assert_ne!(e.code, ErrorCode::Internal);
        }
    }
}
