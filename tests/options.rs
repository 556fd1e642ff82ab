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
