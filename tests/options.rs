//! Options at and beyond the ends of what they may be, end to end: a value past any sense is
//! refused with a message that says what to change, or reduced to what it means.

use furrow::{plan_geojson, ErrorCode, PlanOptions};

/// A 300 m by 150 m rectangle at 60.25 N, its corner at 24.05 E.
const RECTANGLE: &str = r#"{"type":"Polygon","coordinates":[[[24.05,60.25],[24.055430963107863,60.25],[24.055430963107863,60.25134746676249],[24.05,60.25134746676249],[24.05,60.25]]]}"#;

/// The plan's features as GeoJSON text, without the summary (it holds the planning times).
fn features(options: &PlanOptions) -> String {
    let plan = plan_geojson(RECTANGLE, options).unwrap_or_else(|e| panic!("{e}"));
    let geojson: serde_json::Value =
        serde_json::from_str(&plan.to_geojson_string()).expect("GeoJSON");
    geojson["features"].to_string()
}

#[test]
fn a_reference_offset_counts_modulo_the_width() {
    let along_the_west_edge = |offset: f64| PlanOptions {
        width: 6.0,
        reference_line: Some([[24.05, 60.25], [24.05, 60.2513]]),
        reference_offset: Some(offset),
        ..PlanOptions::default()
    };
    // 10^17 m is 16666666666666666 widths of 6 m and 4 m more (in integers, exactly).
    assert_eq!(100_000_000_000_000_000u64 % 6, 4);
    let plan = plan_geojson(RECTANGLE, &along_the_west_edge(1e17)).expect("plans");
    assert!(
        plan.summary.objectives.coverage > 0.99,
        "coverage {}",
        plan.summary.objectives.coverage
    );
    let four = features(&along_the_west_edge(4.0));
    for offset in [1e17, 10.0, 6e6 + 4.0] {
        // (Compared as one boolean: the plans' text runs to hundreds of kilobytes.)
        let same = features(&along_the_west_edge(offset)) == four;
        assert!(
            same,
            "the plan for an offset of {offset} m is not that for 4 m"
        );
    }
}

/// The code and message of the error planning the rectangle with `options`.
fn refused(options: &PlanOptions) -> (ErrorCode, String) {
    let e = plan_geojson(RECTANGLE, options).expect_err("refused");
    (e.code, e.message)
}

#[test]
fn an_entrance_or_exit_must_be_a_place_near_the_field() {
    // The rectangle's north edge is at 60.25134746676249 N; a degree of latitude there is
    // 111.42 km (meridian arc of the WGS84 ellipsoid at 60.25 N): 9 km is 0.0808 degrees,
    // 11 km 0.0987.
    let north = 60.25134746676249;
    let near = [24.052, north + 0.0808];
    let far = [24.052, north + 0.0987];
    for name in ["entrance", "exit"] {
        let with = |p: [f64; 2]| {
            let mut o = PlanOptions::default();
            *(if name == "entrance" {
                &mut o.entrance
            } else {
                &mut o.exit
            }) = Some(p);
            o
        };
        let plan = plan_geojson(RECTANGLE, &with(near)).unwrap_or_else(|e| panic!("{e}"));
        assert!(plan.summary.connection_distance_m > 9000.0);
        for (p, says) in [
            (far, "km from the field boundary"),
            ([1e300, 1e300], "longitude"),
            ([24.05, 91.0], "latitude"),
            ([-155.95, -60.25], "km from the field boundary"),
        ] {
            let (code, message) = refused(&with(p));
            assert_eq!(code, ErrorCode::OptionOutOfRange, "{name} {p:?}");
            assert!(
                message.contains(&format!("`{name}`")) && message.contains(says),
                "{message}"
            );
            assert!(
                message.contains("within 10 km"),
                "what to change: {message}"
            );
        }
    }
    // In metres: within the metric frame's range, and near the field.
    let metric = |p: [f64; 2]| PlanOptions {
        coordinates: furrow::field::Coordinates::Metric,
        entrance: Some(p),
        ..PlanOptions::default()
    };
    let square = r#"{"type":"Polygon","coordinates":[[[0,0],[300,0],[300,150],[0,150],[0,0]]]}"#;
    plan_geojson(square, &metric([300.0 + 9_000.0, 75.0])).expect("9 km east");
    for p in [[300.0 + 11_000.0, 75.0], [1e300, 0.0], [0.0, -1e8]] {
        let e = plan_geojson(square, &metric(p)).expect_err("refused");
        assert_eq!(e.code, ErrorCode::OptionOutOfRange, "{p:?}");
    }
}
