//! Planning in shares (`furrow::plan::share`, what the npm package's worker pool runs): split
//! among 2, 3, 4 or 5 planners, with their summaries sent as numbers, every field gives the
//! plan it gets planned alone, and exactly one share gives it.

#![allow(clippy::result_large_err)] // PlanError is a plain struct with its place in the input

mod common;

use common::corpus::{real_parcels, valid_field, valid_fields};
use furrow::field::{Coordinates, Field};
use furrow::plan::share::{decode, encode, Pending, Share};
use furrow::{plan, Plan, PlanError, PlanOptions};

/// The plan as GeoJSON text, without the planning times (which differ run to run).
fn text(mut plan: Plan) -> String {
    plan.summary.planning_ms = 0.0;
    plan.summary.stages_ms = Default::default();
    plan.to_geojson_string()
}

/// `field` planned in `of` shares, one after another, their summaries sent as numbers: the
/// plan (or error) of the one share that finishes.
fn planned_in_shares(field: &Field, options: &PlanOptions, of: usize) -> Result<Plan, PlanError> {
    let pending: Vec<Pending> = (0..of)
        .map(|index| Pending::start(field.clone(), options, Vec::new(), Share { index, of }))
        .collect::<Result<_, _>>()?;
    let sent: Vec<f64> = pending
        .iter()
        .flat_map(|p| encode(&p.summaries()))
        .collect();
    let summaries = decode(&sent).expect("the summaries read back");
    let mut finished: Vec<Result<Plan, PlanError>> = pending
        .into_iter()
        .filter_map(|p| p.finish(&summaries))
        .collect();
    assert_eq!(finished.len(), 1, "one share finishes the plan");
    finished.remove(0)
}

/// Every share count gives the plan (or the error) of planning alone.
fn check_same(name: &str, field: &Field, options: &PlanOptions) {
    let alone = plan(field.clone(), options).map(text);
    for of in 2..=5 {
        let shared = planned_in_shares(field, options, of).map(text);
        match (&alone, &shared) {
            (Ok(a), Ok(b)) => assert!(a == b, "{name}: the plan in {of} shares differs"),
            (Err(a), Err(b)) => assert_eq!(
                (a.code, &a.message),
                (b.code, &b.message),
                "{name}: the error in {of} shares differs"
            ),
            _ => panic!(
                "{name}: alone {:?}, in {of} shares {:?}",
                alone.is_ok(),
                shared.is_ok()
            ),
        }
    }
}

#[test]
fn every_corpus_field_plans_the_same_in_shares() {
    for f in valid_fields() {
        let (field, _) = Field::from_geojson_str(&f.text()).expect("corpus field reads");
        check_same(&f.name, &field, &f.options);
    }
}

#[test]
fn register_parcels_plan_the_same_in_shares_with_every_fallback() {
    // The drill with passes counted by the machine: parcels planned again with fewer passes,
    // by passes to the middle (contour work weighed), or refused.
    let drill = PlanOptions {
        width: 6.0,
        turn_radius: 8.0,
        headland_passes: furrow::headland::passes::HeadlandPasses::Auto,
        ..PlanOptions::default()
    };
    for (file, i, feature) in real_parcels().into_iter().step_by(7) {
        let Ok((field, _)) = Field::from_geojson_str(&feature) else {
            continue;
        };
        check_same(&format!("{file} {i}"), &field, &drill);
    }
}

#[test]
fn the_fallbacks_plan_the_same_in_shares() {
    let metric = |ring: &str| {
        let text = format!(r#"{{"type": "Polygon", "coordinates": [{ring}]}}"#);
        Field::from_geojson_str_in(&text, Coordinates::Metric)
            .expect("field reads")
            .0
    };
    let options = |passes: u32| PlanOptions {
        width: 6.0,
        headland_passes: passes.into(),
        coordinates: Coordinates::Metric,
        ..PlanOptions::default()
    };
    // A strip 20 m wide: five passes leave no inner field, fewer are laid.
    let strip = metric("[[0, 0], [400, 0], [400, 20], [0, 20], [0, 0]]");
    let fewer = plan(strip.clone(), &options(5)).expect("plans");
    assert!(fewer
        .warnings
        .iter()
        .any(|w| w.code == furrow::WarningCode::HeadlandPassesReduced));
    check_same("strip, 5 passes", &strip, &options(5));
    // A strip 4 m wide at 6 m: no plan covers it, refused.
    let thin = metric("[[0, 0], [400, 0], [400, 4], [0, 4], [0, 0]]");
    assert!(plan(thin.clone(), &options(2)).is_err());
    check_same("thin strip", &thin, &options(2));
    // Passes to the middle.
    let square = metric("[[0, 0], [120, 0], [120, 90], [0, 90], [0, 0]]");
    let all = PlanOptions {
        headland_passes: furrow::headland::passes::HeadlandPasses::All,
        ..options(1)
    };
    check_same("square, all passes", &square, &all);
    // The bent strip contour work is kept on.
    let bent = valid_field("narrow-curved-strip");
    let (field, _) = Field::from_geojson_str(&bent.text()).expect("corpus field reads");
    let contour = plan(field.clone(), &bent.options).expect("plans");
    assert_eq!(
        contour.summary.decomposition.reason,
        furrow::plan::contour::REASON
    );
    check_same("narrow-curved-strip", &field, &bent.options);
}

#[test]
fn a_share_that_does_not_exist_is_refused() {
    let f = valid_field("square-1ha");
    let (field, _) = Field::from_geojson_str(&f.text()).expect("corpus field reads");
    for share in [Share { index: 2, of: 2 }, Share { index: 0, of: 0 }] {
        let e = Pending::start(field.clone(), &f.options, Vec::new(), share)
            .err()
            .expect("refused");
        assert_eq!(e.code, furrow::error::ErrorCode::InvalidOption);
    }
}
