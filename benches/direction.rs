//! The direction search alone on the large corpus field (210 ha, 10 obstacles, 24 m): brute
//! force at 1 degree (Fields2Cover's method) and Oksanen & Visala's coarse-to-fine search, with
//! the default objective (estimated operation time, coverage integrated in the sweep), and brute
//! force with each other objective. Run with `cargo bench --bench direction`.
#![allow(clippy::result_large_err)]

#[path = "../tests/common/corpus.rs"]
mod corpus;

use criterion::{criterion_group, criterion_main, Criterion};
use furrow::direction::{edge_directions, search_field, search_region, AreaSearch, SearchMethod};
use furrow::field::Field;
use furrow::objective::ObjectiveKind;
use std::hint::black_box;

fn direction_search(c: &mut Criterion) {
    let Some(large) = corpus::valid_fields()
        .into_iter()
        .find(|f| f.name == "large-250ha-10-obstacles")
    else {
        return;
    };
    let o = &large.options;
    let Ok((field, _)) = Field::from_geojson_str(&large.text()) else {
        return;
    };
    let area = search_region(
        &field,
        o.obstacle_threshold_m(),
        o.headland_pass_count() as f64 * o.width,
        o.width,
    );
    let seeds = edge_directions(std::iter::once(field.boundary.exterior()), o.width / 2.0);
    let mut group = c.benchmark_group("direction/large-250ha-10-obstacles");
    for (label, method, objective) in [
        (
            "brute-force-1deg/time",
            SearchMethod::BruteForce,
            ObjectiveKind::Time,
        ),
        (
            "coarse-to-fine/time",
            SearchMethod::CoarseToFine,
            ObjectiveKind::Time,
        ),
        (
            "brute-force-1deg/swath-count",
            SearchMethod::BruteForce,
            ObjectiveKind::SwathCount,
        ),
        (
            "brute-force-1deg/coverage",
            SearchMethod::BruteForce,
            ObjectiveKind::Coverage,
        ),
        (
            "brute-force-1deg/oksanen",
            SearchMethod::BruteForce,
            ObjectiveKind::Oksanen,
        ),
    ] {
        let objective = objective.objective();
        let search = AreaSearch {
            method,
            step_deg: 1.0,
            width: o.width,
            min_length: o.min_swath_length_m(),
            machine: o.machine(),
            objective: objective.as_ref(),
        };
        group.bench_function(label, |b| {
            b.iter(|| search_field(black_box(&area), &field.prohibited, &[], &seeds, &search))
        });
    }
    group.finish();
}

criterion_group!(benches, direction_search);
criterion_main!(benches);
