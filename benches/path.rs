//! Native benchmarks of path building (turns, corners, connections) and sampling on the large
//! corpus field, for a machine that drives forward, one that may reverse, and one with a
//! curvature rate. Run with `cargo bench --bench path`.
#![allow(clippy::result_large_err)] // benchmarks keep the plan result whole

#[path = "../tests/common/corpus.rs"]
mod corpus;

use criterion::{criterion_group, criterion_main, Criterion};
use furrow::path::build_path;
use furrow::path::sample::sample;
use furrow::path::turn::Area;
use furrow::route::headland_graph::HeadlandGraph;
use std::hint::black_box;

fn path_building(c: &mut Criterion) {
    let mut group = c.benchmark_group("path");
    for field in corpus::valid_fields() {
        if !["large-250ha-10-obstacles", "obstacles-4", "h-shape"].contains(&field.name.as_str()) {
            continue;
        }
        for (machine, reverse, rate) in [
            ("forward", false, None),
            ("reversing", true, None),
            ("continuous-curvature", false, Some(0.1)),
        ] {
            let options = furrow::PlanOptions {
                reverse,
                curvature_rate: rate,
                ..field.options.clone()
            };
            let Ok(plan) = furrow::plan_geojson(&field.text(), &options) else {
                continue;
            };
            let vehicle = options.vehicle();
            let obstacles: Vec<&geo::Polygon> =
                plan.field.obstacles.iter().map(|o| &o.polygon).collect();
            let area = Area::new(&plan.field.boundary, &obstacles);
            let graph = HeadlandGraph::new(&plan.headlands.passes, options.width)
                .with_crop(&plan.headlands.inner);
            group.bench_function(format!("{}/{machine}/build", field.name), |b| {
                b.iter(|| {
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
            if machine == "forward" {
                group.bench_function(format!("{}/sample-0.5m", field.name), |b| {
                    b.iter(|| sample(black_box(&plan.path), 0.5, &vehicle))
                });
                // With the positions converted to longitude and latitude, as the JS API gives them.
                group.bench_function(format!("{}/samples-lon-lat", field.name), |b| {
                    b.iter(|| black_box(&plan).samples())
                });
            }
        }
    }
    group.finish();
}

criterion_group!(benches, path_building);
criterion_main!(benches);
