//! Nothing is worked outside the field or in an obstacle: over random fields, obstacles and
//! options, no stretch the plan's GeoJSON says is worked (lifted stretches aside) puts any part
//! of the implement's bar more than 1 cm outside the field or into an obstacle. Checked at
//! points across the bar and along the stretch with geo, apart from the planner.

use furrow::{plan_geojson, ErrorCode, Plan, PlanOptions};
use geo::{Contains, Coord, Distance, Euclidean, Point, Polygon};
use proptest::prelude::*;

mod common;

use common::shapes::{jitter, shape};
use common::worked::worked_stretches_by_kind;

/// How far the implement may reach past the boundary or into an obstacle, metres: the lines are
/// drawn in chords within 5 mm of arcs held within 3 mm.
const TOLERANCE: f64 = 0.01;

/// How far a point lies outside the field or inside an obstacle (0 where neither).
fn depth_outside(p: Coord, boundary: &Polygon, obstacles: &[&Polygon]) -> f64 {
    let point = Point(p);
    let edge_distance = |poly: &Polygon| {
        std::iter::once(poly.exterior())
            .chain(poly.interiors())
            .flat_map(|ring| ring.lines())
            .map(|l| Euclidean.distance(&l, &point))
            .fold(f64::INFINITY, f64::min)
    };
    let mut depth: f64 = 0.0;
    if !boundary.contains(&point) {
        depth = edge_distance(boundary);
    }
    for o in obstacles {
        if o.contains(&point) {
            depth = depth.max(edge_distance(o));
        }
    }
    depth
}

/// The deepest point outside the field or in an obstacle that a worked stretch puts the bar
/// over, with the kind of the feature working it.
fn deepest_outside(plan: &Plan) -> Option<(f64, String, Coord)> {
    let half = plan.options.width / 2.0;
    let (stretches, _) = worked_stretches_by_kind(plan);
    let boundary = &plan.field.boundary;
    let obstacles: Vec<&Polygon> = plan.field.obstacles.iter().map(|o| &o.polygon).collect();
    let across_steps = ((2.0 * half) / 0.25).ceil().max(2.0) as usize;
    let mut worst: Option<(f64, String, Coord)> = None;
    for ((a, b), kind) in stretches {
        let d = b - a;
        let length = d.x.hypot(d.y);
        if length == 0.0 {
            continue;
        }
        let (along, normal) = (
            d / length,
            Coord {
                x: -d.y / length,
                y: d.x / length,
            },
        );
        let along_steps = (length / 0.25).ceil() as usize;
        for i in 0..=along_steps {
            let centre = a + along * (length * i as f64 / along_steps as f64);
            for j in 0..=across_steps {
                let offset = -half + 2.0 * half * j as f64 / across_steps as f64;
                let p = centre + normal * offset;
                let depth = depth_outside(p, boundary, &obstacles);
                if depth > TOLERANCE && worst.as_ref().is_none_or(|w| depth > w.0) {
                    worst = Some((depth, kind.clone(), p));
                }
            }
        }
    }
    worst
}

fn ring_json(pts: &[(f64, f64)]) -> String {
    let closed: Vec<String> = pts
        .iter()
        .chain(pts.first())
        .map(|(x, y)| format!("[{x},{y}]"))
        .collect();
    format!("[{}]", closed.join(","))
}

/// A star-shaped ring around (cx, cy) in metres with these radii, so that it is simple.
fn star(cx: f64, cy: f64, radii: &[f64]) -> Vec<(f64, f64)> {
    let n = radii.len() as f64;
    radii
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let t = i as f64 / n * std::f64::consts::TAU;
            (cx + r * t.cos(), cy + r * t.sin())
        })
        .collect()
}

/// A field (a star-shaped boundary, 40 to 400 m from its centre) with up to three obstacles.
fn field() -> impl Strategy<Value = String> {
    (
        prop::collection::vec(40.0..400.0f64, 3..16),
        prop::collection::vec(((-150.0..150.0f64, -150.0..150.0f64), 2.0..40.0f64, 3usize..9), 0..4),
    )
        .prop_map(|(radii, obstacles)| {
            let mut features = vec![format!(
                r#"{{"type":"Feature","properties":{{"role":"boundary"}},"geometry":{{"type":"Polygon","coordinates":[{}]}}}}"#,
                ring_json(&star(0.0, 0.0, &radii))
            )];
            for ((x, y), r, sides) in obstacles {
                features.push(format!(
                    r#"{{"type":"Feature","properties":{{"role":"obstacle"}},"geometry":{{"type":"Polygon","coordinates":[{}]}}}}"#,
                    ring_json(&star(x, y, &vec![r; sides]))
                ));
            }
            format!(r#"{{"type":"FeatureCollection","features":[{}]}}"#, features.join(","))
        })
}

/// Options a farmer might set: width, headland passes (or auto), turning radius, reversing.
fn options() -> impl Strategy<Value = PlanOptions> {
    (
        1.0..40.0f64,
        0u32..5,
        0.0..25.0f64,
        any::<bool>(),
        prop::option::of(0.0..180.0f64),
    )
        .prop_map(
            |(width, passes, turn_radius, reverse, bearing_deg)| PlanOptions {
                width,
                headland_passes: if passes == 4 {
                    furrow::headland::passes::HeadlandPasses::Auto
                } else {
                    passes.into()
                },
                turn_radius,
                reverse,
                bearing_deg,
                search_step_deg: 7.0,
                coordinates: furrow::field::Coordinates::Metric,
                ..PlanOptions::default()
            },
        )
}

proptest! {
    #![proptest_config(common::seeded::config(80))]

    #[test]
    fn no_worked_stretch_puts_the_implement_outside_the_field_or_into_an_obstacle(
        text in field(),
        options in options(),
    ) {
        check(&text, &options)?;
    }
}

proptest! {
    // Dense outlines plan slower: fewer cases.
    #![proptest_config(common::seeded::config(30))]

    #[test]
    fn no_worked_stretch_leaves_a_smooth_noisy_outline(
        shape in shape(),
        spacing in prop::sample::select(vec![0.5, 1.0, 2.0]),
        noise in prop::sample::select(vec![0.0, 0.1, 0.5]),
        seed in any::<u64>(),
        options in options(),
    ) {
        // Outlines as a GNSS receiver records them (discs, circular segments, bays, S-bends).
        let mut points = shape.outline_within(spacing, 3_000.0);
        jitter(&mut points, noise, seed);
        let pts: Vec<(f64, f64)> = points.iter().map(|p| (p.x, p.y)).collect();
        let text = format!(r#"{{"type":"Polygon","coordinates":[{}]}}"#, ring_json(&pts));
        check(&text, &options)?;
    }
}

/// Plans `text` (metric) and fails where a worked stretch reaches out of the field or into an
/// obstacle; a refusal passes if it is typed.
fn check(text: &str, options: &PlanOptions) -> Result<(), TestCaseError> {
    match plan_geojson(text, options) {
        Ok(plan) => {
            if let Some((depth, kind, at)) = deepest_outside(&plan) {
                return Err(TestCaseError::fail(format!(
                    "a {kind} puts the implement {depth:.3} m outside the field or into an obstacle at {:?}",
                    plan.field.frame.to_output(at)
                )));
            }
        }
        Err(e) => prop_assert_ne!(e.code, ErrorCode::Internal, "{}", e),
    }
    Ok(())
}

/// A swath laid without headland beside a side not parallel to it: the implement is lifted
/// where its bar would reach past that side, and the farmer is told why the crop there stands.
#[test]
fn a_swath_beside_a_slanted_side_without_headland_is_lifted_where_the_bar_would_reach_out() {
    // 60 m wide at the south, its west side leaning 10 m east over 100 m; a 12 m implement
    // along it: the first strip (x = 0..12) runs past the west side nearly all its length.
    let text = r#"{"type":"Polygon","coordinates":[[[0,0],[60,0],[60,100],[10,100],[0,0]]]}"#;
    let options = PlanOptions {
        width: 12.0,
        headland_passes: 0.into(),
        turn_radius: 5.0,
        bearing_deg: Some(0.0),
        coordinates: furrow::field::Coordinates::Metric,
        ..PlanOptions::default()
    };
    let plan = plan_geojson(text, &options).unwrap_or_else(|e| panic!("{e}"));
    assert!(plan.summary.lifted_distance_m > 50.0, "{:?}", plan.summary);
    assert_eq!(deepest_outside(&plan).map(|w| w.0), None);
    assert!(
        plan.warnings
            .iter()
            .any(|w| w.code == furrow::WarningCode::ImplementLiftedAtEdges),
        "{:?}",
        plan.warnings
    );
    // With a headland pass round it, nothing reaches out and nothing is lifted.
    let with_pass = PlanOptions {
        headland_passes: 1.into(),
        ..options
    };
    let plan = plan_geojson(text, &with_pass).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(plan.summary.lifted_distance_m, 0.0);
    assert!(!plan
        .warnings
        .iter()
        .any(|w| w.code == furrow::WarningCode::ImplementLiftedAtEdges));
}

/// A pole in the headland: the pass over it is lifted there, and the farmer is told of the pole
/// (`implement_lifted`), not told that headland passes would work crop beside the boundary.
#[test]
fn a_pass_over_a_pole_is_lifted_and_warned_of_as_the_pole() {
    let text = r#"{"type":"FeatureCollection","features":[
        {"type":"Feature","properties":{"role":"boundary"},"geometry":{"type":"Polygon","coordinates":[[[0,0],[100,0],[100,60],[0,60],[0,0]]]}},
        {"type":"Feature","properties":{"role":"obstacle"},"geometry":{"type":"Polygon","coordinates":[[[2.5,29.5],[3.5,29.5],[3.5,30.5],[2.5,30.5],[2.5,29.5]]]}}]}"#;
    let options = PlanOptions {
        width: 6.0,
        headland_passes: 2.into(),
        turn_radius: 5.0,
        bearing_deg: Some(0.0),
        coordinates: furrow::field::Coordinates::Metric,
        ..PlanOptions::default()
    };
    let plan = plan_geojson(text, &options).unwrap_or_else(|e| panic!("{e}"));
    let (stretches, _) = worked_stretches_by_kind(&plan);
    assert!(stretches.iter().any(|(_, kind)| kind == "headland"));
    assert!(plan.summary.lifted_distance_m > 0.9, "{:?}", plan.summary);
    assert_eq!(deepest_outside(&plan).map(|w| w.0), None);
    let codes: Vec<_> = plan.warnings.iter().map(|w| w.code).collect();
    assert!(
        codes.contains(&furrow::WarningCode::ImplementLifted),
        "{codes:?}"
    );
    assert!(
        !codes.contains(&furrow::WarningCode::ImplementLiftedAtEdges),
        "{codes:?}"
    );
}
