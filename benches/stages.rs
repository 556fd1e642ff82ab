//! Native benchmarks of the stages that can run alone, on every corpus field with its README
//! settings: reading, checking and simplifying the field (`validation`), and, from the finished
//! plan, its route, its path and its output (the GeoJSON text). Each is timed as the planner
//! calls it for the decomposition auto chose (auto runs route and path once per candidate it
//! compares; the stage clocks in `summary.stages_ms`, which `examples/report.rs` reports, count
//! them all). Direction, headlands and decomposition take what the planner builds between the
//! stages: their times are in the stage clocks only. Run with `cargo bench --bench stages`.
#![allow(clippy::result_large_err)] // benchmarks keep the plan result whole

#[path = "../tests/common/corpus.rs"]
mod corpus;

use criterion::{criterion_group, criterion_main, Criterion};
use furrow::field::Field;
use furrow::path::build_path;
use furrow::path::turn::Area;
use furrow::plan::route_settings;
use furrow::route::headland_graph::HeadlandGraph;
use furrow::route::plan_route;
use std::hint::black_box;

fn stages(c: &mut Criterion) {
    let fields: Vec<(corpus::CorpusField, String, furrow::Plan)> = corpus::valid_fields()
        .into_iter()
        .filter_map(|field| {
            let text = field.text();
            let plan = furrow::plan_geojson(&text, &field.options).ok()?;
            Some((field, text, plan))
        })
        .collect();
    let mut group = c.benchmark_group("stage-validation");
    for (field, text, _) in &fields {
        let width = field.options.width;
        group.bench_function(&field.name, |b| {
            b.iter(|| {
                let read = Field::from_geojson_str_in(black_box(text), field.options.coordinates);
                read.map(|(mut f, _)| f.simplify(width))
            })
        });
    }
    group.finish();
    let mut group = c.benchmark_group("stage-route");
    for (field, _, plan) in &fields {
        let settings = furrow::route::RouteSettings {
            crop: Some(plan.headlands.inner.clone()),
            ..route_settings(&plan.options, &plan.field)
        };
        group.bench_function(&field.name, |b| {
            b.iter(|| {
                plan_route(
                    black_box(&plan.swaths),
                    &plan.blocks,
                    &plan.headlands.passes,
                    &settings,
                )
            })
        });
    }
    group.finish();
    let mut group = c.benchmark_group("stage-path");
    for (field, _, plan) in &fields {
        let obstacles: Vec<&geo::Polygon> =
            plan.field.obstacles.iter().map(|o| &o.polygon).collect();
        let vehicle = plan.options.vehicle();
        let graph = HeadlandGraph::new(&plan.headlands.passes, plan.options.width)
            .with_crop(&plan.headlands.inner);
        group.bench_function(&field.name, |b| {
            b.iter(|| {
                // The driving area is built once per plan, as the planner does.
                let area = Area::new(&plan.field.boundary, &obstacles);
                build_path(
                    black_box(&plan.route),
                    &plan.swaths,
                    &plan.headlands.passes,
                    &vehicle,
                    Some(&area),
                    Some(&graph),
                )
            })
        });
    }
    group.finish();
    let mut group = c.benchmark_group("stage-output");
    for (field, _, plan) in &fields {
        group.bench_function(&field.name, |b| {
            b.iter(|| black_box(plan).to_geojson_string())
        });
    }
    group.finish();
}

criterion_group!(benches, stages);
criterion_main!(benches);
