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

criterion_group!(benches, plan_corpus);
criterion_main!(benches);
