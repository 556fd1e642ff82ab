//! The documented contract stays in step with the code: every error and warning code, summary
//! member and option appears in the README and in the TypeScript definitions of the package.

use furrow::options::OPTION_DOCS;
use furrow::{plan_geojson, ErrorCode, PlanOptions, WarningCode};

fn read(path: &str) -> String {
    std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(path))
        .expect("readable")
}

#[test]
fn every_error_code_is_documented_and_typed() {
    let readme = read("README.md");
    let dts = read("src/bindings/plan.d.ts");
    for code in ErrorCode::ALL {
        let c = code.as_str();
        assert!(
            readme.contains(&format!("| `{c}` |")),
            "README error reference lacks {c}"
        );
        assert!(
            dts.contains(&format!("\"{c}\"")),
            "plan.d.ts ErrorCode lacks {c}"
        );
    }
}

#[test]
fn every_warning_code_is_documented() {
    let readme = read("README.md");
    for code in WarningCode::ALL {
        assert!(
            readme.contains(&format!("`{}`", code.as_str())),
            "README lacks {code:?}"
        );
    }
}

#[test]
fn every_summary_member_and_option_is_typed_and_documented() {
    let readme = read("README.md");
    let dts = read("src/bindings/plan.d.ts");
    let text = read("tests/fields/square-1ha.geojson");
    let plan = plan_geojson(&text, &PlanOptions::default()).expect("plans");
    let summary = serde_json::to_value(&plan.summary).expect("json");
    for (key, value) in summary.as_object().expect("object") {
        // Numbers are typed `number`; the one object (obstacle_classes) has a type of its own.
        let typed = if value.is_number() {
            dts.contains(&format!("  {key}: number;"))
        } else {
            dts.contains(&format!("  {key}: "))
        };
        assert!(typed, "PlanSummary lacks {key}");
        assert!(
            readme.contains(&format!("`{key}`")),
            "README lacks summary.{key}"
        );
    }
    for (key, _, _) in OPTION_DOCS {
        assert!(
            dts.contains(&format!("  {key}?:")),
            "PlanOptions lacks {key}"
        );
        assert!(
            readme.contains(&format!("| `{key}` |")),
            "README options table lacks {key}"
        );
    }
}

#[test]
fn the_direction_search_is_described_as_it_runs() {
    // The command line's help, the TypeScript declarations and the README give the same count of
    // directions the coarse-to-fine search evaluates, and the search evaluates about that many.
    let (_, _, help) = OPTION_DOCS
        .iter()
        .find(|(key, _, _)| *key == "search")
        .expect("the search option");
    assert!(help.contains("about 30 to 40 directions"), "{help}");
    assert!(read("src/bindings/plan.d.ts").contains("about 30 to 40 evaluations"));
    assert!(read("README.md").contains("about 30 to 40 evaluations"));
    let options = PlanOptions::from_json_str(r#"{"decomposition": "none", "direction": "search"}"#)
        .expect("options");
    for file in ["rectangle", "l-shape", "h-shape"] {
        let text = read(&format!("tests/fields/{file}.geojson"));
        let plan = plan_geojson(&text, &options).expect("plans");
        let n = plan.summary.direction.evaluations;
        assert!((28..=40).contains(&n), "{file}: {n} directions");
    }
}
