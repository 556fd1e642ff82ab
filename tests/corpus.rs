//! The benchmark corpus end to end: every valid field plans with the settings its README
//! suggests and the plan keeps the geometric invariants; every invalid input gives its error;
//! every real parcel plans or is refused with a typed error.

mod common;

use common::corpus::{
    fields_dir, invalid_fields, passes_driven, real_parcels, strip_out_of_region, valid_fields,
};
use furrow::path::SegmentKind;
use furrow::{plan_geojson, ErrorCode, Plan, PlanOptions};
use geo::{Area, Contains, Coord, Distance, Euclidean, Point};
use std::path::Path;

/// Metres of slack for "on the boundary" (geo's boolean operations snap to a grid of about 1e-6
/// of the field's extent).
const EPS: f64 = 1e-3;

#[test]
fn test_copy_of_the_fields_matches_the_shared_corpus() {
    let shared = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/fields");
    if !shared.is_dir() {
        eprintln!("no ../shared/fields beside this clone: nothing to compare");
        return;
    }
    let mut stale = Vec::new();
    for entry in walk(&shared) {
        let rel = entry.strip_prefix(&shared).expect("under shared");
        let ours = fields_dir().join(rel);
        let same = std::fs::read(&ours).ok() == std::fs::read(&entry).ok();
        if !same {
            stale.push(rel.display().to_string());
        }
    }
    assert!(
        stale.is_empty(),
        "tests/fields is out of date with ../shared/fields ({stale:?}): run scripts/sync-fields.sh"
    );
}

fn walk(dir: &Path) -> Vec<std::path::PathBuf> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).expect("readable dir").flatten() {
        let p = e.path();
        if p.is_dir() {
            out.extend(walk(&p));
        } else {
            out.push(p);
        }
    }
    out
}

/// (planar area in the frame, geodesic area by geo on the WGS84 ellipsoid) of each outer ring.
fn ring_areas(text: &str, frame: &furrow::field::Frame) -> Vec<(f64, f64)> {
    use geo::{GeodesicArea, LineString, Polygon};
    let v: serde_json::Value = serde_json::from_str(text).expect("JSON");
    let mut out = Vec::new();
    for f in v["features"].as_array().expect("features") {
        let ring: Vec<[f64; 2]> = f["geometry"]["coordinates"][0]
            .as_array()
            .expect("ring")
            .iter()
            .map(|p| [p[0].as_f64().expect("lon"), p[1].as_f64().expect("lat")])
            .collect();
        let lon_lat = Polygon::new(LineString::from(ring.clone()), vec![]);
        let local: Vec<Coord> = ring.iter().map(|&p| frame.to_local(p)).collect();
        let planar = Polygon::new(LineString::new(local), vec![]).unsigned_area();
        out.push((planar, lon_lat.geodesic_area_unsigned()));
    }
    out
}

fn plan_field(text: &str, options: &PlanOptions) -> Plan {
    plan_geojson(text, options).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn every_valid_field_plans_and_keeps_the_invariants() {
    for field in valid_fields() {
        let plan = plan_field(&field.text(), &field.options);
        let name = &field.name;
        let s = &plan.summary;
        assert!(s.swath_count > 0, "{name}: no swaths");
        // The README's areas are rounded and were computed on a sphere: within 1 %.
        let area_ha = s.field_area_m2 / 10_000.0;
        assert!(
            (area_ha - field.area_ha).abs() <= field.area_ha * 0.01,
            "{name}: area {area_ha} ha, README says {} ha",
            field.area_ha
        );
        // Every input ring's area in the local frame matches geo's geodesic area on the ellipsoid.
        for (planar, geodesic) in ring_areas(&field.text(), &plan.field.frame) {
            assert!(
                (planar - geodesic).abs() <= geodesic * 5e-4,
                "{name}: planar {planar} m², geodesic {geodesic} m²"
            );
        }
        // Obstacles are kept, except that overlapping ones are merged (with a warning).
        let merged = plan
            .warnings
            .iter()
            .any(|w| w.code == furrow::WarningCode::ObstaclesMerged);
        let kept = plan.field.obstacles.len();
        assert!(
            kept == field.obstacles || (merged && kept < field.obstacles && kept > 0),
            "{name}: {kept} obstacles of {}",
            field.obstacles
        );
        check_swaths(&plan, name);
        check_path(&plan, name);
        check_headland_passes(&plan, name);
    }
}

/// Swaths work the inner field with their strips in the region, parallel to the bearing, one
/// width apart.
fn check_swaths(plan: &Plan, name: &str) {
    let w = plan.options.width;
    let inner = &plan.headlands.inner;
    let fill: Vec<std::ops::Range<usize>> = plan
        .swaths
        .areas
        .iter()
        .filter(|a| a.fill)
        .map(|a| a.swaths.clone())
        .collect();
    let fills = |i: usize| fill.iter().any(|r| r.contains(&i));
    for s in &plan.swaths.swaths {
        if fills(s.index) {
            check_fill_swath(plan, s, name);
            continue;
        }
        // A swath runs on into the headland as far as the line a quarter width beside its
        // centre is in the inner field, its whole strip in the region (the field less the
        // obstacles with headlands).
        for at in [
            s.centre.start,
            (s.centre.start + s.centre.end) / 2.0,
            s.centre.end,
        ] {
            let d = Euclidean.distance(&Point(at), inner);
            assert!(
                d < w / 4.0 + EPS,
                "{name}: swath {} runs {d} m from the inner field",
                s.index
            );
        }
        let out = strip_out_of_region(plan, s);
        assert!(
            out < EPS,
            "{name}: swath {}'s strip reaches {out} m out of the region",
            s.index
        );
        let b = furrow::geometry::bearing_of(s.centre.start, s.centre.end);
        let diff = furrow::geometry::swath_direction(b - s.bearing);
        assert!(
            diff.min(std::f64::consts::PI - diff) < 1e-9,
            "{name}: swath {} not parallel",
            s.index
        );
        assert!(s.length() >= plan.options.min_swath_length_m() - 1e-9);
    }
    // Within each area worked at one direction (the field's, a block's, a prohibited region's),
    // lines lie a width apart.
    let covered: usize = plan.swaths.areas.iter().map(|a| a.swaths.len()).sum();
    assert_eq!(
        covered,
        plan.swaths.swaths.len(),
        "{name}: swaths outside areas"
    );
    for area in &plan.swaths.areas {
        let mut by_line: Vec<(usize, f64, f64)> = Vec::new();
        for s in &plan.swaths.swaths[area.swaths.clone()] {
            assert_eq!(
                s.bearing, area.bearing,
                "{name}: swath {} off its area's direction",
                s.index
            );
            if by_line.last().map(|l| l.0) != Some(s.line_index) {
                by_line.push((s.line_index, s.across, s.overlap_m));
            }
        }
        for pair in by_line.windows(2) {
            let ((i, a, oa), (j, b, ob)) = (pair[0], pair[1]);
            let gap = b - a;
            let expected = (j - i) as f64 * w;
            if area.fill {
                // The fill's lines are spread over the part: no gap between their strips.
                assert!(
                    gap > 0.0 && gap <= expected + 1e-6,
                    "{name}: fill lines {gap} m apart"
                );
            } else if oa > 0.0 || ob > 0.0 {
                // A line moved to work a leftover strip: closer, never further.
                assert!(
                    gap <= expected + 1e-6 && gap > 0.0,
                    "{name}: last gap {gap}"
                );
            } else {
                assert!(
                    (gap - expected).abs() < 1e-6,
                    "{name}: lines {i} and {j} are {gap} m apart, expected {expected}"
                );
            }
        }
    }
}

/// A swath that fills what the others leave: parallel to its area, and its whole strip in the
/// field and off every obstacle (its centre line half a width in from them, to the arcs'
/// chords).
fn check_fill_swath(plan: &Plan, s: &furrow::swath::Swath, name: &str) {
    let half = plan.options.width / 2.0;
    let boundary = &plan.field.boundary;
    for k in 0..=10 {
        let t = k as f64 / 10.0;
        let p = Point(s.centre.start + (s.centre.end - s.centre.start) * t);
        assert!(
            boundary.contains(&p),
            "{name}: fill swath {} leaves the field",
            s.index
        );
        let to_edge = Euclidean.distance(&p, boundary.exterior());
        assert!(
            to_edge > half - 0.01,
            "{name}: fill swath {}'s strip reaches {} m past the boundary",
            s.index,
            half - to_edge
        );
        for o in &plan.field.obstacles {
            let d = Euclidean.distance(&p, &o.polygon);
            assert!(
                d > half - 0.01,
                "{name}: fill swath {} over an obstacle",
                s.index
            );
        }
    }
    let b = furrow::geometry::bearing_of(s.centre.start, s.centre.end);
    let diff = furrow::geometry::swath_direction(b - s.bearing);
    assert!(
        diff.min(std::f64::consts::PI - diff) < 1e-9,
        "{name}: fill swath {} not parallel",
        s.index
    );
}

/// The path is continuous, every swath and headland pass is driven once, and the GeoJSON
/// numbers drivable features 0, 1, 2, ... in driving order.
fn check_path(plan: &Plan, name: &str) {
    let segs = &plan.path.segments;
    for pair in segs.windows(2) {
        let a: Coord = *pair[0].line.0.last().expect("non-empty segment");
        let b: Coord = pair[1].line.0[0];
        assert!(
            (a.x - b.x).hypot(a.y - b.y) < 1e-6,
            "{name}: gap in the path"
        );
    }
    assert_eq!(
        plan.path.count_of(SegmentKind::Swath),
        plan.swaths.swaths.len(),
        "{name}"
    );
    // Every headland pass is driven.
    assert_eq!(passes_driven(plan), plan.headlands.passes.len(), "{name}");
    let geojson: serde_json::Value =
        serde_json::from_str(&plan.to_geojson_string()).expect("plan output is JSON");
    let mut next = 0;
    for f in geojson["features"].as_array().expect("features") {
        let kind = f["properties"]["kind"].as_str().expect("kind");
        match kind {
            "swath" | "headland" | "turn" | "connection" => {
                assert_eq!(f["properties"]["sequence"], next, "{name}: sequence");
                assert_eq!(f["geometry"]["type"], "LineString");
                next += 1;
            }
            "block" | "obstacle" | "obstacle_group" | "uncovered" => {
                assert_eq!(f["geometry"]["type"], "Polygon")
            }
            other => panic!("{name}: unknown kind {other}"),
        }
    }
    assert_eq!(next, segs.len());
    for key in [
        "swath_count",
        "turn_count",
        "working_distance_m",
        "turning_distance_m",
        "connection_distance_m",
        "total_distance_m",
        "field_area_m2",
        "headland_area_m2",
        "bearing_deg",
        "planning_ms",
    ] {
        assert!(geojson["summary"][key].is_number(), "{name}: summary.{key}");
    }
    assert!(geojson["warnings"].is_array());
}

/// The inner field is part of the field (the passes are checked in tests/headlands.rs), and
/// none is left where the field is worked by passes to its middle.
fn check_headland_passes(plan: &Plan, name: &str) {
    let inner_area = plan.headlands.inner.unsigned_area();
    let swaths = plan.summary.swath_count > plan.summary.fill_swath_count;
    assert!(inner_area < plan.field.boundary.unsigned_area(), "{name}");
    assert_eq!(
        inner_area > 0.0,
        swaths,
        "{name}: inner field {inner_area} m²"
    );
}

#[test]
fn every_invalid_field_gives_its_error() {
    for (path, code) in invalid_fields() {
        let text = std::fs::read_to_string(&path).expect("readable");
        let e = plan_geojson(&text, &PlanOptions::default())
            .err()
            .unwrap_or_else(|| panic!("{} planned", path.display()));
        assert_eq!(e.code.as_str(), code, "{}: {e}", path.display());
        assert!(!e.message.is_empty());
    }
}

#[test]
fn every_invalid_input_is_covered() {
    // A new file in invalid/ must get its expected code in tests/common/corpus.rs.
    let known: Vec<_> = invalid_fields().into_iter().map(|(p, _)| p).collect();
    for entry in std::fs::read_dir(fields_dir().join("invalid"))
        .expect("invalid/")
        .flatten()
    {
        let p = entry.path();
        if p.extension().is_some_and(|e| e == "geojson") {
            assert!(
                known.contains(&p),
                "{} has no expected error code",
                p.display()
            );
        }
    }
}

#[test]
fn every_real_parcel_plans_with_the_passes_that_leave_it_swaths() {
    let drill = PlanOptions {
        width: 6.0,
        headland_passes: 2.into(),
        turn_radius: 8.0,
        ..PlanOptions::default()
    };
    let sprayer = PlanOptions {
        width: 24.0,
        headland_passes: 1.into(),
        turn_radius: 9.0,
        ..PlanOptions::default()
    };
    let parcels = real_parcels();
    for options in [&drill, &sprayer] {
        let (mut reduced, mut refused) = (0, 0);
        for (file, i, text) in &parcels {
            let at = format!("{file}[{i}] at {} m", options.width);
            let plan = match plan_geojson(text, options) {
                Ok(plan) => plan,
                Err(e) => {
                    // Refused only where the implement cannot reach most of the field.
                    assert_eq!(e.code, ErrorCode::HeadlandConsumesField, "{at}: {e}");
                    let reachable = reachable_ratio(text, options.width);
                    assert!(reachable < 0.5, "{at}: refused, {reachable} reachable: {e}");
                    refused += 1;
                    continue;
                }
            };
            check_path(&plan, &at);
            let warned = plan
                .warnings
                .iter()
                .any(|w| w.code == furrow::WarningCode::HeadlandPassesReduced);
            // With fewer passes than asked only where the passes asked for leave no swath, and
            // then with a warning.
            assert_eq!(
                plan.options.headland_pass_count() < options.headland_pass_count(),
                warned,
                "{at}"
            );
            if warned {
                reduced += 1;
                assert!(plan.summary.swath_count > 0, "{at}: no swaths");
            }
        }
        eprintln!(
            "real parcels at {} m: {reduced} of {} with fewer headland passes, {refused} refused",
            options.width,
            parcels.len()
        );
        // Some parcels cannot hold the passes asked for at these widths (without this
        // fallback, 27 were refused at 6 m and 53 at 24 m). Since a pass the turning disc fits
        // nowhere is laid exact, rather than dropped, 5 of the rest at 6 m and 1 at 24 m are
        // planned with fewer passes (10 and 15 before).
        assert!(reduced >= 1, "{reduced}");
    }
    // Parcel 63 of the Danish sample is invalid as the register gives it: its ring goes out to a
    // point 0.7 m away and straight back, touching itself. That spike is repaired, with a warning.
    let (_, _, text) = &parcels[63];
    let plan = plan_geojson(text, &drill).expect("the spike is repaired");
    assert!(plan
        .warnings
        .iter()
        .any(|w| w.code == furrow::WarningCode::SpikesRemoved));
}

/// The share of a parcel a strip of `width` can reach at all: its outline (in local metres, as
/// read) opened by a disc of that diameter, with geo's buffer.
fn reachable_ratio(text: &str, width: f64) -> f64 {
    use geo::Buffer;
    let (field, _) = furrow::field::Field::from_geojson_str(text).expect("a valid parcel");
    let opened = field.boundary.buffer(-width / 2.0).buffer(width / 2.0);
    opened.unsigned_area() / field.boundary.unsigned_area()
}

/// A strip 20 m wide, the width of three drill passes: two headland passes on each side leave
/// it nothing, so it is planned with fewer (here none), warned of, and worked from end to end.
#[test]
fn a_strip_too_narrow_for_its_headland_is_worked_with_fewer_passes() {
    let strip =
        r#"{"type": "Polygon", "coordinates": [[[0, 0], [300, 0], [300, 20], [0, 20], [0, 0]]]}"#;
    let options = PlanOptions {
        width: 6.0,
        headland_passes: 2.into(),
        turn_radius: 8.0,
        coordinates: furrow::field::Coordinates::Metric,
        ..PlanOptions::default()
    };
    let plan = plan_geojson(strip, &options).expect("a 20 m strip plans at 6 m");
    let warning = plan
        .warnings
        .iter()
        .find(|w| w.code == furrow::WarningCode::HeadlandPassesReduced)
        .expect("warned of the passes laid");
    assert!(warning.message.contains("0 laid"), "{}", warning.message);
    assert_eq!(plan.options.headland_pass_count(), 0);
    // Three or four swaths along the strip cover it (the planner's own figure, and the swaths'
    // lengths: the strip is 300 m long and 20 m wide).
    let swath_length: f64 = plan.swaths.swaths.iter().map(|s| s.length()).sum();
    assert!(
        plan.summary.swath_count >= 3,
        "{}",
        plan.summary.swath_count
    );
    assert!(swath_length * 6.0 >= 0.95 * 300.0 * 20.0, "{swath_length}");
    assert!(plan.summary.coverage.coverage_ratio > 0.95);
    // The same field without the fallback's cause: one pass leaves an inner field, and is kept.
    let wide = strip.replace("20]", "60]");
    let plan = plan_geojson(&wide, &options).expect("a 60 m strip plans at 6 m");
    assert_eq!(plan.options.headland_pass_count(), 2);
    assert!(plan
        .warnings
        .iter()
        .all(|w| w.code != furrow::WarningCode::HeadlandPassesReduced));
}

#[test]
fn planning_is_deterministic() {
    for field in valid_fields().into_iter().take(6) {
        let a = plan_field(&field.text(), &field.options);
        let b = plan_field(&field.text(), &field.options);
        let strip = |p: &Plan| {
            let mut g = p.to_geojson();
            // Only the clocks may differ.
            g.summary.planning_ms = 0.0;
            g.summary.stages_ms = Default::default();
            serde_json::to_string(&g).expect("json")
        };
        assert_eq!(strip(&a), strip(&b), "{}", field.name);
    }
}

#[test]
fn rectangle_acceptance_case() {
    // The acceptance case of the foundation issue: rectangle.geojson at 6 m with 2 passes.
    let text = std::fs::read_to_string(fields_dir().join("rectangle.geojson")).expect("readable");
    let options = PlanOptions {
        width: 6.0,
        headland_passes: 2.into(),
        ..PlanOptions::default()
    };
    let plan = plan_field(&text, &options);
    // About 251 m by 150 m: the longest edge runs east, so 22 swaths (150 - 24 = 126 m across:
    // 21 whole strips and one overlapping), each as long as the field less two 12 m headlands.
    use geo::BoundingRect;
    let rect = plan.field.boundary.bounding_rect().expect("bounded");
    assert!((plan.summary.bearing_deg - 90.0).abs() < 0.01);
    // The field's 22 swaths, then the fill of the corners the passes round off.
    assert_eq!(plan.summary.swath_count - plan.summary.fill_swath_count, 22);
    assert!(plan.summary.fill_swath_count > 0);
    for s in &plan.swaths.swaths[..22] {
        assert!(
            (s.length() - (rect.width() - 24.0)).abs() < 0.01,
            "{}",
            s.length()
        );
    }
}
