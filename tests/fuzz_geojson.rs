//! Fuzzing the GeoJSON entry point: random JSON shaped like GeoJSON, byte-level mutations of the
//! corpus files, and structural mutations of valid fields (extreme, repeated, missing and
//! shuffled coordinates), each with random options. Every input must give a plan or a typed
//! error other than `internal`: never a panic, never a hang.
//!
//! The regular suite runs a few hundred cases. The long run, a million cases:
//! `PROPTEST_CASES=1000000 cargo test --release --test fuzz_geojson -- --nocapture`
//! (it prints each new slowest case, so a near-hang shows).

mod common;

use common::corpus::valid_fields;
use furrow::headland::passes::HeadlandPasses;
use furrow::{plan_geojson, ErrorCode, PlanOptions};
use proptest::prelude::*;
use serde_json::{json, Value};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::OnceLock;
use std::time::Instant;

static SLOWEST_NS: AtomicU64 = AtomicU64::new(0);

fn corpus() -> &'static Vec<String> {
    static TEXTS: OnceLock<Vec<String>> = OnceLock::new();
    TEXTS.get_or_init(|| valid_fields().iter().map(|f| f.text()).collect())
}

fn check(text: &str, options: &PlanOptions) -> Result<(), TestCaseError> {
    let t = Instant::now();
    let result = plan_geojson(text, options);
    let ns = t.elapsed().as_nanos() as u64;
    if ns > SLOWEST_NS.fetch_max(ns, Ordering::Relaxed) {
        eprintln!(
            "new slowest case: {:.1} ms ({} bytes)",
            ns as f64 / 1e6,
            text.len()
        );
    }
    match result {
        Ok(plan) => {
            prop_assert!(plan.summary.total_distance_m.is_finite());
            let out: Value = serde_json::from_str(&plan.to_geojson_string())
                .map_err(|e| TestCaseError::fail(format!("output is not JSON: {e}")))?;
            prop_assert_eq!(&out["type"], "FeatureCollection");
        }
        Err(e) => prop_assert_ne!(e.code, ErrorCode::Internal, "{}", e),
    }
    Ok(())
}

fn options() -> impl Strategy<Value = PlanOptions> {
    (
        prop::sample::select(vec![0.1, 0.5, 2.5, 6.0, 24.0, 200.0]),
        0u32..6,
        prop::option::of(-400.0..400.0f64),
        prop::collection::vec((0.0..360.0f64, 0.0..360.0f64), 0..3),
    )
        .prop_map(
            |(width, headland_passes, bearing_deg, forbidden)| PlanOptions {
                width,
                // The last count stands for `auto`.
                headland_passes: if headland_passes == 5 {
                    HeadlandPasses::Auto
                } else {
                    headland_passes.into()
                },
                bearing_deg,
                forbidden_bearings_deg: forbidden.into_iter().map(|(a, b)| [a, b].into()).collect(),
                ..PlanOptions::default()
            },
        )
}

/// A number a hostile or broken input might hold.
fn number() -> impl Strategy<Value = Value> {
    prop_oneof![
        (-200.0..200.0f64).prop_map(Value::from),
        (23.9..24.2f64).prop_map(Value::from),
        (60.1..60.4f64).prop_map(Value::from),
        prop::sample::select(vec![
            0.0, -0.0, 1e308, -1e308, 1e-300, 90.0, -180.0, 180.000001
        ])
        .prop_map(Value::from),
        any::<i64>().prop_map(Value::from),
    ]
}

/// Random JSON with GeoJSON's words in it.
fn geojsonish() -> impl Strategy<Value = Value> {
    let leaf = prop_oneof![
        number(),
        Just(Value::Null),
        any::<bool>().prop_map(Value::from),
        prop::sample::select(vec![
            "FeatureCollection",
            "Feature",
            "Polygon",
            "MultiPolygon",
            "LineString",
            "Point",
            "boundary",
            "obstacle",
            "prohibited",
            "",
        ])
        .prop_map(Value::from),
    ];
    leaf.prop_recursive(6, 200, 8, |inner| {
        prop_oneof![
            prop::collection::vec(inner.clone(), 0..8).prop_map(Value::from),
            prop::collection::vec(
                (
                    prop::sample::select(vec![
                        "type",
                        "features",
                        "geometry",
                        "properties",
                        "coordinates",
                        "role",
                        "name",
                        "forbidden_bearings_deg",
                    ]),
                    inner,
                ),
                0..6,
            )
            .prop_map(|kv| Value::Object(
                kv.into_iter().map(|(k, v)| (k.to_string(), v)).collect()
            )),
        ]
    })
}

/// A random ring near the corpus fields, made of the numbers above.
fn ring() -> impl Strategy<Value = Value> {
    prop::collection::vec((number(), number()), 0..10).prop_map(|pts| {
        let mut ring: Vec<Value> = pts.into_iter().map(|(x, y)| json!([x, y])).collect();
        if let Some(first) = ring.first().cloned() {
            ring.push(first);
        }
        Value::from(ring)
    })
}

#[derive(Debug, Clone)]
enum Mutation {
    /// Delete bytes [at, at + len).
    Delete(usize, usize),
    /// Insert text at a position.
    Insert(usize, String),
    /// Replace a character with another.
    Replace(usize, char),
    /// Repeat a slice of the text.
    Duplicate(usize, usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), 1usize..64).prop_map(|(a, l)| Mutation::Delete(a, l)),
        (
            any::<usize>(),
            prop::sample::select(vec![
                "[", "]", "{", "}", ",", "-", "1e999", "null", "\"", "NaN", "0", ".5", "[[0,0]]"
            ])
        )
            .prop_map(|(a, s)| Mutation::Insert(a, s.to_string())),
        (
            any::<usize>(),
            prop::sample::select(vec!['0', '9', '-', '.', 'e', ']', ',', ' '])
        )
            .prop_map(|(a, c)| Mutation::Replace(a, c)),
        (any::<usize>(), 1usize..200).prop_map(|(a, l)| Mutation::Duplicate(a, l)),
    ]
}

fn apply(text: &str, mutations: &[Mutation]) -> String {
    let mut bytes = text.as_bytes().to_vec();
    for m in mutations {
        let n = bytes.len().max(1);
        match m {
            Mutation::Delete(a, l) => {
                let a = a % n;
                let end = (a + l).min(bytes.len());
                if a < end {
                    bytes.drain(a..end);
                }
            }
            Mutation::Insert(a, s) => {
                let a = a % (bytes.len() + 1);
                bytes.splice(a..a, s.bytes());
            }
            Mutation::Replace(a, c) => {
                if !bytes.is_empty() {
                    let a = a % bytes.len();
                    bytes[a] = *c as u8;
                }
            }
            Mutation::Duplicate(a, l) => {
                let a = a % n;
                let end = (a + l).min(bytes.len());
                if a < end {
                    let copy = bytes[a..end].to_vec();
                    bytes.splice(end..end, copy);
                }
            }
        }
    }
    String::from_utf8_lossy(&bytes).into_owned()
}

proptest! {
    #![proptest_config(common::seeded::config(128))]

    #[test]
    fn random_geojsonish_json(value in geojsonish(), options in options()) {
        check(&value.to_string(), &options)?;
    }

    #[test]
    fn random_rings_in_a_feature_collection(
        boundary in ring(),
        holes in prop::collection::vec(ring(), 0..3),
        obstacles in prop::collection::vec(ring(), 0..3),
        options in options(),
    ) {
        let mut rings = vec![boundary];
        rings.extend(holes);
        let mut features = vec![json!({"type": "Feature", "properties": {"role": "boundary"},
            "geometry": {"type": "Polygon", "coordinates": rings}})];
        for o in obstacles {
            features.push(json!({"type": "Feature", "properties": {"role": "obstacle"},
                "geometry": {"type": "Polygon", "coordinates": [o]}}));
        }
        check(&json!({"type": "FeatureCollection", "features": features}).to_string(), &options)?;
    }

    #[test]
    fn mutated_corpus_text(
        field in any::<prop::sample::Index>(),
        mutations in prop::collection::vec(mutation(), 1..6),
        options in options(),
    ) {
        let texts = corpus();
        let text = &texts[field.index(texts.len())];
        check(&apply(text, &mutations), &options)?;
    }

    #[test]
    fn mutated_corpus_coordinates(
        field in any::<prop::sample::Index>(),
        edits in prop::collection::vec((any::<prop::sample::Index>(), any::<prop::sample::Index>(), 0u8..5, number()), 1..8),
        options in options(),
    ) {
        let texts = corpus();
        let mut value: Value = serde_json::from_str(&texts[field.index(texts.len())])
            .map_err(|e| TestCaseError::fail(e.to_string()))?;
        let features = value["features"].as_array_mut().ok_or_else(|| TestCaseError::fail("features"))?;
        for (f, v, op, x) in edits {
            let n = features.len();
            let Some(ring) = features[f.index(n)]["geometry"]["coordinates"][0].as_array_mut() else { continue };
            if ring.is_empty() { continue; }
            let i = v.index(ring.len());
            match op {
                0 => ring[i][0] = x,                      // one coordinate to an odd number
                1 => ring[i][1] = x,
                2 => { let p = ring[i].clone(); ring.insert(i, p); } // repeat a vertex
                3 => { ring.remove(i); }                 // drop a vertex (maybe the closing one)
                _ => ring.reverse(),                     // run the other way round
            }
        }
        check(&value.to_string(), &options)?;
    }
}
