//! Native benchmarks of the whole planner on the corpus fields, each with its README settings.
//! Run with `cargo bench --bench plan`.
#![allow(clippy::result_large_err)] // benchmarks keep the plan result whole

#[path = "../tests/common/corpus.rs"]
mod corpus;

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

fn plan_corpus(c: &mut Criterion) {
    let mut group = c.benchmark_group("plan");
    for field in corpus::valid_fields() {
        let text = field.text();
        group.bench_function(&field.name, |b| {
            b.iter(|| furrow::plan_geojson(black_box(&text), &field.options))
        });
    }
    group.finish();
}

/// Each decomposition on its own, on fields with arms, bays and obstacles: what auto's
/// candidates cost.
fn decompositions(c: &mut Criterion) {
    use furrow::decompose::Decomposition;
    let mut group = c.benchmark_group("decomposition");
    for field in corpus::valid_fields() {
        if ![
            "h-shape",
            "many-bays",
            "obstacles-4",
            "large-250ha-10-obstacles",
        ]
        .contains(&field.name.as_str())
        {
            continue;
        }
        let text = field.text();
        for d in [
            Decomposition::None,
            Decomposition::Boustrophedon,
            Decomposition::SplitMerge,
        ] {
            let options = furrow::PlanOptions {
                decomposition: d,
                ..field.options.clone()
            };
            group.bench_function(format!("{}/{}", field.name, d.as_str()), |b| {
                b.iter(|| furrow::plan_geojson(black_box(&text), &options))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, plan_corpus, decompositions);
criterion_main!(benches);
