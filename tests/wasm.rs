//! The planner compiled to WebAssembly, run by wasm-bindgen-test in Node and in headless Chromium
//! (`WASM_BINDGEN_USE_BROWSER=1`): the Rust API on every corpus field, and the JavaScript API
//! (`plan` as JavaScript calls it, errors as JavaScript sees them), the tracks' and the field
//! files' entry points.
#![cfg(target_arch = "wasm32")]

use furrow::bindings::formats::{read_field_file_text, read_shapefile_text};
use furrow::bindings::plan::{default_options, plan_js, version};
use furrow::bindings::tracks::{shortest_path_js, TrackGraphJs};
use furrow::{plan_geojson, PlanOptions};
use js_sys::{Reflect, JSON};
use wasm_bindgen::{JsCast, JsValue};
use wasm_bindgen_test::wasm_bindgen_test;

macro_rules! corpus {
    ($($name:literal),* $(,)?) => {
        [$(($name, include_str!(concat!("fields/", $name, ".geojson")))),*]
    };
}

const FIELDS: [(&str, &str); 21] = corpus!(
    "boomerang",
    "c-shape-escarpment",
    "curved-edge",
    "gps-traced-600-vertices",
    "h-shape",
    "l-shape",
    "large-250ha-10-obstacles",
    "many-bays",
    "narrow-curved-strip",
    "no-straight-edge",
    "obstacle-types",
    "obstacles-1",
    "obstacles-2",
    "obstacles-3",
    "obstacles-4",
    "obstacles-5",
    "rectangle",
    "skew-quad",
    "square-1ha",
    "t-shape",
    "underdrain",
);

fn get(v: &JsValue, key: &str) -> JsValue {
    Reflect::get(v, &JsValue::from_str(key)).expect("readable property")
}

#[wasm_bindgen_test]
fn every_corpus_field_plans_in_wasm() {
    for (name, text) in FIELDS {
        let plan =
            plan_geojson(text, &PlanOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(plan.summary.swath_count > 0, "{name}");
        assert!(
            plan.summary.planning_ms > 0.0,
            "{name}: the clock works in wasm"
        );
    }
}

#[wasm_bindgen_test]
fn js_api_returns_a_feature_collection() {
    let field = JSON::parse(FIELDS[16].1).expect("rectangle is JSON");
    let options = JSON::parse(r#"{"width": 6, "headlandPasses": 2}"#).expect("JSON");
    let plan = plan_js(field, options).expect("plans");
    assert_eq!(get(&plan, "type"), "FeatureCollection");
    let summary = get(&plan, "summary");
    // 22 swaths across the inner field, and any that fill the corners the passes round off.
    let fill = get(&summary, "fill_swath_count")
        .as_f64()
        .unwrap_or(f64::NAN);
    assert_eq!(get(&summary, "swath_count").as_f64(), Some(22.0 + fill));
    let features = js_sys::Array::from(&get(&plan, "features"));
    assert!(features.length() > 22);
    // GeoJSON text is accepted as well as objects, and options may be left out.
    let again = plan_js(JsValue::from_str(FIELDS[16].1), JsValue::UNDEFINED).expect("plans");
    let again = get(&again, "summary");
    let fill = get(&again, "fill_swath_count").as_f64().unwrap_or(f64::NAN);
    assert_eq!(get(&again, "swath_count").as_f64(), Some(22.0 + fill));
}

#[wasm_bindgen_test]
fn js_api_gives_the_sampled_path_as_typed_arrays() {
    let field = JSON::parse(FIELDS[16].1).expect("rectangle is JSON");
    let options = JSON::parse(r#"{"width": 6, "headlandPasses": 2, "turnRadius": 8, "reverse": true, "sampleSpacing": 1}"#)
        .expect("JSON");
    let plan = plan_js(field, options).expect("plans");
    let samples = get(&plan, "samples");
    let x: js_sys::Float64Array = get(&samples, "x").dyn_into().expect("x is a Float64Array");
    let n = x.length();
    assert!(n > 1000, "{n} samples");
    for key in ["y", "heading_deg", "curvature", "distance_m", "time_s"] {
        let a: js_sys::Float64Array = get(&samples, key).dyn_into().expect(key);
        assert_eq!(a.length(), n, "{key}");
    }
    for key in ["kind", "reverse", "working"] {
        let a: js_sys::Uint8Array = get(&samples, key).dyn_into().expect(key);
        assert_eq!(a.length(), n, "{key}");
    }
    let segment: js_sys::Uint32Array = get(&samples, "segment").dyn_into().expect("segment");
    assert_eq!(segment.length(), n);
    // Longitude and latitude, a metre apart at most, the path's length at the end.
    let d: js_sys::Float64Array = get(&samples, "distance_m").dyn_into().expect("distance");
    let total = get(&get(&plan, "summary"), "total_distance_m")
        .as_f64()
        .expect("total");
    assert!((d.get_index(n - 1) - total).abs() < 0.01 * total);
    assert!((24.0..24.1).contains(&x.get_index(0)));
    // Turns carry their form; the GeoJSON text has no samples in it.
    let features = js_sys::Array::from(&get(&plan, "features"));
    let turn = features
        .iter()
        .find(|f| get(&get(f, "properties"), "kind") == "turn")
        .expect("a turn");
    assert!(get(&get(&turn, "properties"), "form").as_string().is_some());
}

#[wasm_bindgen_test]
fn js_errors_carry_a_code_and_a_place() {
    let bowtie = r#"{"type":"Polygon","coordinates":[[[24.05,60.25],[24.0518,60.2509],[24.0518,60.25],[24.05,60.2509],[24.05,60.25]]]}"#;
    let err = plan_js(JsValue::from_str(bowtie), JsValue::UNDEFINED).expect_err("bowtie fails");
    assert!(err.is_instance_of::<js_sys::Error>());
    assert_eq!(get(&err, "code"), "self_intersection");
    assert_eq!(get(&err, "name"), "FurrowError");
    assert_eq!(get(&err, "feature").as_f64(), Some(0.0));
    assert!(js_sys::Array::is_array(&get(&err, "coordinate")));

    let typo = JSON::parse(r#"{"widht": 3}"#).expect("JSON");
    let err = plan_js(JsValue::from_str(FIELDS[16].1), typo).expect_err("unknown option");
    assert_eq!(get(&err, "code"), "invalid_option");

    let err = plan_js(JsValue::from_str("{"), JsValue::UNDEFINED).expect_err("not JSON");
    assert_eq!(get(&err, "code"), "invalid_json");

    // NaN cannot be written in JSON, but a JavaScript object can hold it.
    let nan = JSON::parse(r#"{"type":"Polygon","coordinates":[[[0,0],[1,0],[1,1],[0,0]]]}"#)
        .expect("JSON");
    let ring = get(&get(&nan, "coordinates"), "0");
    Reflect::set(
        &get(&ring, "1"),
        &JsValue::from(0),
        &JsValue::from(f64::NAN),
    )
    .expect("set");
    let err = plan_js(nan, JsValue::UNDEFINED).expect_err("NaN fails");
    assert_eq!(get(&err, "code"), "non_finite_coordinate");
    assert_eq!(get(&err, "vertex").as_f64(), Some(1.0));

    // An object is read through its JSON text: its errors name the feature, not a place in
    // that text.
    let bad = JSON::parse(
        r#"{"type":"FeatureCollection","features":[{"type":"Feature","geometry":null},
        {"type":"Feature","geometry":{"type":"Polygon","coordinates":"none"}}]}"#,
    )
    .expect("JSON");
    let err = plan_js(bad, JsValue::UNDEFINED).expect_err("bad coordinates");
    assert_eq!(get(&err, "code"), "invalid_geojson");
    assert_eq!(get(&err, "feature").as_f64(), Some(1.0));
    assert!(get(&err, "line").is_undefined());
    let message = get(&err, "message").as_string().unwrap_or_default();
    assert!(
        !message.contains("line") && message.contains("GeoJSON"),
        "{message}"
    );
}

#[wasm_bindgen_test]
fn defaults_and_version() {
    let d = default_options().expect("defaults");
    assert_eq!(get(&d, "width").as_f64(), Some(6.0));
    assert_eq!(get(&d, "headlandPasses").as_f64(), Some(2.0));
    assert!(get(&d, "bearing").is_null());
    assert_eq!(version(), env!("CARGO_PKG_VERSION"));
}

#[wasm_bindgen_test]
fn js_api_finds_the_way_along_the_tracks() {
    let field = JSON::parse(FIELDS[16].1).expect("rectangle is JSON");
    let options =
        JSON::parse(r#"{"width": 6, "headlandPasses": 2, "turnRadius": 8}"#).expect("JSON");
    let plan = plan_js(field, options).expect("plans");
    let tracks = TrackGraphJs::new(plan.clone(), JsValue::UNDEFINED).expect("tracks");
    assert!(tracks.track_count() > 10 && tracks.junction_count() > 10);
    let from = JSON::parse("[24.0515, 60.2508]").expect("JSON");
    let to = JSON::parse("[24.05, 60.25]").expect("JSON");
    let heading_mode = JSON::parse(r#"{"turning": "heading"}"#).expect("JSON");
    let way = tracks
        .shortest_path(from.clone(), 0.0, to.clone(), heading_mode.clone())
        .expect("a way");
    assert_eq!(get(&way, "type"), "Feature");
    let length = get(&get(&way, "properties"), "length_m")
        .as_f64()
        .expect("length_m");
    assert!(length > 50.0, "{length}");
    // The one-call form gives the same; a bad turning is an Error with a code.
    let again =
        shortest_path_js(plan.clone(), from.clone(), 0.0, to.clone(), heading_mode).expect("a way");
    assert_eq!(
        get(&get(&again, "properties"), "length_m").as_f64(),
        Some(length)
    );
    let bad = JSON::parse(r#"{"turning": "sideways"}"#).expect("JSON");
    let e = tracks
        .shortest_path(from, 0.0, to, bad)
        .map(|_| ())
        .expect_err("refused");
    assert_eq!(get(&e, "code"), "invalid_option");
}

#[wasm_bindgen_test]
fn js_api_reads_a_zipped_shapefile_in_rd_new() {
    let zip = include_bytes!("format-fixtures/nl_brp_rd_new.zip");
    let text = read_field_file_text(zip, "nl_brp_rd_new.zip").expect("reads");
    let file = JSON::parse(&text).expect("GeoJSON");
    let features = js_sys::Array::from(&get(&file, "features"));
    assert_eq!(features.length(), 53);
    assert_eq!(
        get(&get(&file, "source"), "crs").as_string().as_deref(),
        Some("EPSG:28992 (Amersfoort / RD New)")
    );
    // The first corner, as the register has it (4.5793265, 52.1158312; GDAL wrote it in RD
    // New): within 1e-7 degrees, a centimetre.
    let corner = JSON::stringify(&get(&get(&features.get(0), "geometry"), "coordinates"))
        .ok()
        .and_then(|s| s.as_string())
        .unwrap_or_default();
    let first: Vec<f64> = corner
        .trim_start_matches('[')
        .split(']')
        .next()
        .unwrap_or_default()
        .split(',')
        .filter_map(|x| x.parse().ok())
        .collect();
    assert!(
        (first[0] - 4.5793265).abs() < 1e-7 && (first[1] - 52.1158312).abs() < 1e-7,
        "{first:?}"
    );
    // A cut archive, and parts without their .shp: FurrowErrors with the code invalid_file.
    for e in [
        read_field_file_text(&zip[..zip.len() / 2], "cut.zip").expect_err("cut"),
        read_shapefile_text(
            vec!["a.prj".into()],
            js_sys::Array::of1(&js_sys::Uint8Array::from(&b"GEOGCS"[..])),
        )
        .expect_err("no .shp"),
    ] {
        assert_eq!(get(&e, "code").as_string().as_deref(), Some("invalid_file"));
        assert_eq!(get(&e, "name").as_string().as_deref(), Some("FurrowError"));
    }
}
