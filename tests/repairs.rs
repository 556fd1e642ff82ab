//! Each repair the field reader makes, end to end: the input with the defect plans, the warning
//! names the repair and the feature, and the planned geometry is the repaired one.

use furrow::{plan_geojson, PlanOptions, WarningCode};
use geo::Area;

const SQUARE: [[f64; 2]; 4] = [
    [24.05, 60.25],
    [24.056, 60.25],
    [24.056, 60.253],
    [24.05, 60.253],
];

fn ring(points: &[[f64; 2]]) -> String {
    let p: Vec<String> = points.iter().map(|[x, y]| format!("[{x},{y}]")).collect();
    format!("[{}]", p.join(","))
}

fn closed(points: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut v = points.to_vec();
    v.push(points[0]);
    v
}

fn polygon(rings: &[Vec<[f64; 2]>]) -> String {
    let r: Vec<String> = rings.iter().map(|x| ring(x)).collect();
    format!(r#"{{"type":"Polygon","coordinates":[{}]}}"#, r.join(","))
}

fn collection(features: &[(&str, String)]) -> String {
    let f: Vec<String> = features
        .iter()
        .map(|(role, geometry)| {
            format!(r#"{{"type":"Feature","properties":{{"role":"{role}","forbidden_bearings_deg":[[0,10]]}},"geometry":{geometry}}}"#)
        })
        .collect();
    format!(
        r#"{{"type":"FeatureCollection","features":[{}]}}"#,
        f.join(",")
    )
}

/// Plans the text; returns the plan and the codes of its warnings on `feature`.
fn plan_with(text: &str) -> (furrow::Plan, Vec<WarningCode>) {
    let plan = plan_geojson(text, &PlanOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    let codes = plan.warnings.iter().map(|w| w.code).collect();
    (plan, codes)
}

fn reference_area() -> f64 {
    plan_with(&polygon(&[closed(&SQUARE)]))
        .0
        .field
        .boundary
        .unsigned_area()
}

/// The warnings of the field reader's repairs (the plan's own, such as turns over crop, aside).
const REPAIRS: [WarningCode; 10] = [
    WarningCode::RingClosed,
    WarningCode::RepeatedVertices,
    WarningCode::CollinearVertices,
    WarningCode::SpikesRemoved,
    WarningCode::RingReoriented,
    WarningCode::ObstacleClipped,
    WarningCode::ObstaclesMerged,
    WarningCode::ProhibitedClipped,
    WarningCode::OutlineSimplified,
    WarningCode::IgnoredFeature,
];

#[test]
fn a_clean_field_needs_no_repair() {
    let (_, codes) = plan_with(&polygon(&[closed(&SQUARE)]));
    assert!(codes.iter().all(|c| !REPAIRS.contains(c)), "{codes:?}");
}

#[test]
fn an_open_ring_is_closed() {
    let (plan, codes) = plan_with(&polygon(&[SQUARE.to_vec()]));
    assert!(codes.contains(&WarningCode::RingClosed));
    assert!(plan.field.boundary.exterior().is_closed());
    assert!((plan.field.boundary.unsigned_area() - reference_area()).abs() < 1e-6);
}

#[test]
fn repeated_vertices_are_removed() {
    let mut points = closed(&SQUARE);
    points.insert(2, points[1]);
    points.insert(2, points[1]);
    let (plan, codes) = plan_with(&polygon(&[points]));
    assert!(codes.contains(&WarningCode::RepeatedVertices));
    assert_eq!(plan.field.boundary.exterior().0.len(), 5);
}

#[test]
fn collinear_vertices_are_removed() {
    // In metres, so that the middle vertex lies exactly on the edge (a parallel of latitude is a
    // slight curve in the local frame, and a vertex on it is a real, if tiny, corner).
    let text =
        r#"{"type":"Polygon","coordinates":[[[0,0],[150,0],[300,0],[300,200],[0,200],[0,0]]]}"#;
    let options = PlanOptions {
        coordinates: furrow::field::Coordinates::Metric,
        ..PlanOptions::default()
    };
    let plan = plan_geojson(text, &options).expect("plans");
    assert!(plan
        .warnings
        .iter()
        .any(|w| w.code == WarningCode::CollinearVertices));
    assert_eq!(plan.field.boundary.exterior().0.len(), 5);
}

#[test]
fn a_spike_is_removed() {
    // Out from the east edge 30 m and straight back.
    let mut points = closed(&SQUARE);
    points.insert(2, [24.056, 60.2515]);
    points.insert(3, [24.0565, 60.2515]);
    points.insert(4, [24.056, 60.2515]);
    let (plan, codes) = plan_with(&polygon(&[points]));
    assert!(codes.contains(&WarningCode::SpikesRemoved), "{codes:?}");
    assert!((plan.field.boundary.unsigned_area() - reference_area()).abs() < 1e-3);
}

#[test]
fn clockwise_rings_are_turned() {
    let mut points = closed(&SQUARE);
    points.reverse();
    let (plan, codes) = plan_with(&polygon(&[points]));
    assert!(codes.contains(&WarningCode::RingReoriented));
    assert!(plan.field.boundary.exterior().0.len() == 5 && plan.summary.swath_count > 0);
}

#[test]
fn a_dense_recorded_boundary_is_simplified() {
    // The square's edges sampled every metre or so, with centimetres of wobble.
    let mut points = Vec::new();
    for k in 0..4 {
        let (a, b) = (SQUARE[k], SQUARE[(k + 1) % 4]);
        for i in 0..300 {
            let t = i as f64 / 300.0;
            let wobble = if i % 2 == 0 { 1e-7 } else { -1e-7 };
            points.push([
                a[0] + (b[0] - a[0]) * t + wobble,
                a[1] + (b[1] - a[1]) * t + wobble,
            ]);
        }
    }
    let (plan, codes) = plan_with(&polygon(&[closed(&points)]));
    assert!(codes.contains(&WarningCode::OutlineSimplified), "{codes:?}");
    assert!(plan.field.boundary.exterior().0.len() <= 12);
    assert!((plan.field.boundary.unsigned_area() / reference_area() - 1.0).abs() < 0.01);
}

#[test]
fn overlapping_obstacles_are_merged_and_reaching_ones_clipped() {
    let a = closed(&[
        [24.051, 60.251],
        [24.052, 60.251],
        [24.052, 60.252],
        [24.051, 60.252],
    ]);
    let b = closed(&[
        [24.0515, 60.2515],
        [24.0525, 60.2515],
        [24.0525, 60.2525],
        [24.0515, 60.2525],
    ]);
    let over = closed(&[
        [24.0555, 60.251],
        [24.058, 60.251],
        [24.058, 60.2515],
        [24.0555, 60.2515],
    ]);
    let text = collection(&[
        ("boundary", polygon(&[closed(&SQUARE)])),
        ("obstacle", polygon(&[a])),
        ("obstacle", polygon(&[b])),
        ("obstacle", polygon(&[over])),
    ]);
    let (plan, codes) = plan_with(&text);
    assert!(codes.contains(&WarningCode::ObstaclesMerged));
    assert!(codes.contains(&WarningCode::ObstacleClipped));
    assert_eq!(plan.field.obstacles.len(), 2);
    let clipped = plan
        .field
        .obstacles
        .iter()
        .find(|o| o.feature == 3)
        .expect("obstacle 3");
    // Only the part inside the field (0.0005 of 0.0025 degrees of longitude) is kept.
    let full = 0.0025 * 0.0005 * 111_320.0 * 60.251f64.to_radians().cos() * 111_400.0;
    assert!((clipped.polygon.unsigned_area() / full - 0.2).abs() < 0.01);
}

#[test]
fn a_prohibited_region_over_the_boundary_is_clipped() {
    let region = closed(&[
        [24.049, 60.2505],
        [24.052, 60.2505],
        [24.052, 60.2515],
        [24.049, 60.2515],
    ]);
    let text = collection(&[
        ("boundary", polygon(&[closed(&SQUARE)])),
        ("prohibited", polygon(&[region])),
    ]);
    let (plan, codes) = plan_with(&text);
    assert!(codes.contains(&WarningCode::ProhibitedClipped));
    assert_eq!(plan.field.prohibited.len(), 1);
    assert_eq!(plan.field.prohibited[0].forbidden.len(), 1);
}

#[test]
fn metric_input_plans_in_metres() {
    let text = r#"{"type":"Polygon","coordinates":[[[1000,2000],[1300,2000],[1300,2150],[1000,2150],[1000,2000]]]}"#;
    let options = PlanOptions {
        coordinates: furrow::field::Coordinates::Metric,
        ..PlanOptions::default()
    };
    let plan = plan_geojson(text, &options).expect("plans");
    assert!((plan.summary.field_area_m2 - 45_000.0).abs() < 1e-6);
    let out: serde_json::Value = serde_json::from_str(&plan.to_geojson_string()).expect("json");
    // The plan comes back in the same metres: the outermost headland pass is 3 m inside.
    let pass = out["features"]
        .as_array()
        .expect("features")
        .iter()
        .find(|f| f["properties"]["kind"] == "headland" && f["properties"]["pass"] == 1)
        .expect("pass 1");
    for p in pass["geometry"]["coordinates"].as_array().expect("line") {
        let (x, y) = (p[0].as_f64().expect("x"), p[1].as_f64().expect("y"));
        assert!(
            (1002.999..=1297.001).contains(&x) && (2002.999..=2147.001).contains(&y),
            "{x} {y}"
        );
    }
    // The same numbers read as degrees are out of range.
    let e = plan_geojson(text, &PlanOptions::default()).unwrap_err();
    assert_eq!(e.code, furrow::ErrorCode::CoordinateOutOfRange);
}
