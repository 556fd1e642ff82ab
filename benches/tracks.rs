//! Shortest paths along a plan's tracks (Plessen & Bemporad): building the track graph of a plan,
//! and one query from a place on a swath to the field's first vertex under each way of turning,
//! on the large corpus field (210 ha, 10 obstacles) and two smaller ones.
//!
//!     cargo bench --bench tracks

use criterion::{criterion_group, criterion_main, Criterion};
use furrow::plan_geojson;
use furrow::tracks::{from_plan, shortest_path, TrackKind, TrackQuery, Turning};
use std::hint::black_box;

#[path = "../tests/common/corpus.rs"]
mod corpus;

fn bench(c: &mut Criterion) {
    for field in corpus::valid_fields().into_iter().filter(|f| {
        ["large-250ha-10-obstacles", "obstacles-4", "h-shape"].contains(&f.name.as_str())
    }) {
        let plan = match plan_geojson(&field.text(), &field.options) {
            Ok(p) => p,
            Err(e) => panic!("{}: {e}", field.name),
        };
        c.bench_function(&format!("track graph {}", field.name), |b| {
            b.iter(|| black_box(from_plan(black_box(&plan))))
        });
        let graph = from_plan(&plan);
        let corner = plan.field.boundary.exterior().0[0];
        // Starts in the middle of every fifth swath, facing along it both ways.
        let starts: Vec<_> = graph
            .tracks()
            .iter()
            .filter(|t| t.kind == TrackKind::Swath)
            .step_by(5)
            .flat_map(|t| {
                let at = t.length() / 2.0;
                let h = t.heading_at(at, true, true);
                let heading = h.y.atan2(h.x);
                [
                    (t.point_at(at), heading),
                    (t.point_at(at), heading + std::f64::consts::PI),
                ]
            })
            .collect();
        for turning in [Turning::OnTheSpot, Turning::Heading, Turning::Tracks] {
            let mut k = 0;
            c.bench_function(
                &format!("track path {} {}", field.name, turning.as_str()),
                |b| {
                    b.iter(|| {
                        let (from, heading) = starts[k % starts.len()];
                        k += 1;
                        let q = TrackQuery {
                            from,
                            heading,
                            targets: vec![corner],
                            turning,
                            monotone_band: false,
                        };
                        black_box(shortest_path(&graph, &q).map(|p| p.length).ok())
                    })
                },
            );
        }
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20).measurement_time(std::time::Duration::from_secs(2));
    targets = bench
}
criterion_main!(benches);
