//! Dense and smooth outlines, as a GNSS receiver records them: ring cleaning keeps the field as
//! given (every vertex removed within a millimetre of the ring left, the area within 0.1 %,
//! wherever the ring starts), and the simplification of dense outlines is conservative (the
//! planned field lies inside the boundary as given and outside every obstacle as given). The
//! reproducers of `tests/fields/reproducers` are tests here too.
//!
//! Distances and areas are checked with geo's own Hausdorff distance and boolean operations, not
//! with the planner's figures.

use furrow::field::ring::COLLINEAR_M;
use furrow::field::{Coordinates, Field};
use furrow::headland::PassAround;
use furrow::{plan_geojson, ErrorCode, PlanOptions};
use geo::{Area, BooleanOps, Coord, Distance, Euclidean, Length, LineString, Point, Polygon};
use proptest::prelude::*;
use std::f64::consts::{PI, TAU};

mod common;

use common::shapes::{arc, interior_disc, jitter, shape, Shape};

/// Where the outline lies on Earth: in metres around the origin, or in WGS84 near `lon`, `lat`.
#[derive(Debug, Clone, Copy)]
enum Place {
    Metric,
    Wgs84 { lon: f64, lat: f64 },
}

fn place() -> impl Strategy<Value = Place> {
    prop_oneof![
        Just(Place::Metric),
        // Farmland on land (a field at sea is refused): Finland, Denmark, the Netherlands,
        // Kansas, Brazil, Australia, New Zealand, Fiji by the antimeridian, Iceland.
        prop::sample::select(vec![
            (24.05, 60.25),
            (9.5, 56.1),
            (5.3, 52.4),
            (-98.5, 38.5),
            (-51.9, -14.2),
            (147.1, -35.1),
            (172.6, -43.5),
            (179.9, -16.6),
            (-20.3, 63.9),
        ])
        .prop_map(|(lon, lat)| Place::Wgs84 { lon, lat }),
    ]
}

impl Place {
    fn coordinates(self) -> Coordinates {
        match self {
            Place::Metric => Coordinates::Metric,
            Place::Wgs84 { .. } => Coordinates::Wgs84,
        }
    }

    /// The input position of a point in local metres (a plain equirectangular map: any map will
    /// do, the checks project the input back with the field's own frame).
    fn position(self, p: Coord) -> [f64; 2] {
        match self {
            Place::Metric => [p.x, p.y],
            Place::Wgs84 { lon, lat } => {
                let m = 111_320.0;
                [lon + p.x / (m * lat.to_radians().cos()), lat + p.y / m]
            }
        }
    }
}

/// A GeoJSON ring of the points (closed), starting at point `start`, reversed if asked: the
/// positions as the planner reads them from the text.
fn ring_json(points: &[Coord], place: Place, start: usize, reversed: bool) -> Vec<[f64; 2]> {
    let n = points.len();
    let mut ring: Vec<[f64; 2]> = (0..n)
        .map(|i| place.position(points[(start + i) % n]))
        .collect();
    if reversed {
        ring.reverse();
    }
    ring.push(ring[0]);
    // serde_json reads decimals to within an ulp, not always to the number written.
    serde_json::from_str(&coords_text(&ring)).expect("positions")
}

fn polygon_text(rings: &[Vec<[f64; 2]>]) -> String {
    let r: Vec<String> = rings.iter().map(|r| coords_text(r)).collect();
    format!(r#"{{"type":"Polygon","coordinates":[{}]}}"#, r.join(","))
}

fn coords_text(ring: &[[f64; 2]]) -> String {
    let p: Vec<String> = ring.iter().map(|[x, y]| format!("[{x},{y}]")).collect();
    format!("[{}]", p.join(","))
}

/// The input ring in the field's local metres.
fn local(field: &Field, ring: &[[f64; 2]]) -> LineString {
    LineString::new(ring.iter().map(|&p| field.frame.to_local(p)).collect())
}

proptest! {
    #![proptest_config(common::seeded::config(48))]

    /// Cleaning a smooth outline keeps it: within a millimetre (Hausdorff) and 0.1 % of its area,
    /// wherever it starts and whichever way it runs.
    #[test]
    fn smooth_outlines_clean_to_themselves(
        shape in shape(),
        spacing in prop::sample::select(vec![0.05, 0.1, 0.2, 0.4, 0.8, 1.5, 2.0]),
        place in place(),
        start in 0.0..1.0f64,
        reversed in any::<bool>(),
    ) {
        let points = shape.outline(spacing);
        let start = (start * points.len() as f64) as usize;
        let ring = ring_json(&points, place, start, reversed);
        let (field, _) = Field::from_geojson_str_in(&polygon_text(std::slice::from_ref(&ring)), place.coordinates())
            .map_err(|e| TestCaseError::fail(format!("{shape:?}: {e}")))?;
        let given = local(&field, &ring);
        let distance = farthest_removed(&given, field.boundary.exterior())
            .map_err(|e| TestCaseError::fail(format!("{shape:?}: {e}")))?;
        prop_assert!(distance <= COLLINEAR_M + 1e-9, "{shape:?}: a vertex {distance} m from the outline as cleaned");
        let (a, b) = (Polygon::new(given, vec![]).unsigned_area(), field.boundary.unsigned_area());
        prop_assert!((a - b).abs() <= 1e-3 * a, "{shape:?}: area {b} m² for {a} m²");
    }

    /// Dense outlines with noise and obstacles: the field as planned lies inside the boundary as
    /// given and outside its obstacles as given, and the outermost headland pass works no crop
    /// outside the field.
    #[test]
    fn simplified_outlines_stay_inside_the_field(
        shape in shape(),
        spacing in prop::sample::select(vec![0.2, 0.5, 1.0, 2.0]),
        noise in prop::sample::select(vec![0.0, 0.05, 0.2, 0.5]),
        width in prop::sample::select(vec![1.0, 3.0, 6.0, 12.0, 24.0]),
        place in place(),
        seed in any::<u64>(),
    ) {
        let mut points = shape.outline(spacing);
        jitter(&mut points, noise, seed);
        let ring = ring_json(&points, place, 0, false);
        // A noisy round obstacle well inside: a pond recorded by walking round it.
        let inner = interior_disc(shape);
        let mut pond = arc(inner.0, inner.1, 0.0, TAU, spacing, false);
        jitter(&mut pond, noise.min(inner.1 / 20.0), seed ^ 1);
        let pond = ring_json(&pond, place, 0, true);
        let text = polygon_text(&[ring.clone(), pond.clone()]);
        let options = PlanOptions {
            width,
            coordinates: place.coordinates(),
            headland_passes: 1.into(),
            turn_radius: width.min(8.0),
            decomposition: furrow::decompose::Decomposition::None,
            ..PlanOptions::default()
        };
        let plan = match plan_geojson(&text, &options) {
            Ok(plan) => plan,
            // Noise may make a ring cross itself, and a wide implement may not fit a small field.
            Err(e) if e.code == ErrorCode::SelfIntersection && noise > 0.0 => return Ok(()),
            Err(e) if e.code == ErrorCode::HeadlandConsumesField => return Ok(()),
            Err(e) => return Err(TestCaseError::fail(format!("{shape:?}: {e}"))),
        };
        // Cleaning may move an outline by a millimetre either way; simplification only inwards
        // (outwards round the pond).
        let given = Polygon::new(local(&plan.field, &ring), vec![]);
        let outside = plan.field.boundary.difference(&given).unsigned_area();
        let cleaning = COLLINEAR_M * Euclidean.length(given.exterior());
        prop_assert!(outside <= cleaning, "{shape:?}: {outside} m² of the planned field outside the boundary");
        let pond = Polygon::new(local(&plan.field, &pond), vec![]);
        let obstacle = plan.field.obstacles.first().map(|o| o.polygon.clone())
            .ok_or_else(|| TestCaseError::fail("the pond is gone"))?;
        let uncovered = pond.difference(&obstacle).unsigned_area();
        let cleaning = COLLINEAR_M * Euclidean.length(pond.exterior());
        prop_assert!(uncovered <= cleaning, "{shape:?}: {uncovered} m² of the pond outside the obstacle");
        check_outer_passes(&plan, &given, &pond, width)?;
    }
}

/// How far the vertices of `given` that cleaning removed lie from the edge of `clean` that
/// replaces each (the most it moved the outline): every vertex of `clean` must be one of
/// `given`, in the same order round the ring.
fn farthest_removed(given: &LineString, clean: &LineString) -> Result<f64, String> {
    // The field's rings run counter-clockwise, whichever way they were given.
    let mut given = given.clone();
    if Polygon::new(given.clone(), vec![]).signed_area() < 0.0 {
        given.0.reverse();
    }
    let n = given.0.len() - 1;
    let key = |c: &Coord| (c.x.to_bits(), c.y.to_bits());
    let index: std::collections::HashMap<_, usize> = given.0[..n]
        .iter()
        .enumerate()
        .map(|(i, c)| (key(c), i))
        .collect();
    let kept: Vec<usize> = clean.0[..clean.0.len() - 1]
        .iter()
        .map(|c| {
            index
                .get(&key(c))
                .copied()
                .ok_or(format!("{c:?} is not a vertex as given"))
        })
        .collect::<Result<_, _>>()?;
    let mut farthest = 0.0f64;
    let mut covered = 0;
    for (k, &from) in kept.iter().enumerate() {
        let to = kept[(k + 1) % kept.len()];
        let edge = geo::Line::new(given.0[from], given.0[to]);
        let mut i = (from + 1) % n;
        while i != to {
            farthest = farthest.max(Euclidean.distance(&Point(given.0[i]), &edge));
            i = (i + 1) % n;
            covered += 1;
        }
        covered += 1;
    }
    if covered != n {
        return Err(format!(
            "the kept vertices go round {covered} vertices of {n}: out of order"
        ));
    }
    Ok(farthest)
}

/// Every point of the headland passes next to the field boundary or the pond lies half a width
/// or more from them, inside the field: the implement's footprint stays in the field.
fn check_outer_passes(
    plan: &furrow::Plan,
    field: &Polygon,
    pond: &Polygon,
    width: f64,
) -> Result<(), TestCaseError> {
    // Round joins are chords of their arcs, and a pass is offset and opened: passes are held to
    // a centimetre of their true place (headland::offset).
    let slack = 1e-2;
    for pass in plan.headlands.passes.iter().filter(|p| p.index == 1) {
        let edges = match pass.around {
            PassAround::Field => vec![field.exterior()],
            PassAround::Obstacle => vec![pond.exterior()],
            // Passes along what is left keep clear of both.
            PassAround::Fill => vec![field.exterior(), pond.exterior()],
            PassAround::Block => continue,
        };
        for &c in pass.line.0.iter() {
            let d = edges
                .iter()
                .map(|e| Euclidean.distance(&Point(c), *e))
                .fold(f64::INFINITY, f64::min);
            prop_assert!(
                d >= width / 2.0 - slack,
                "a {:?} pass at {c:?} is {d} m from its edge, less than half the width {width}",
                pass.around
            );
        }
    }
    Ok(())
}

#[test]
fn a_dense_disc_in_metres_plans() {
    // The reproducer circle_r50_n1000_metric: 1,000 vertices on a 50 m circle.
    let points = Shape::Disc { radius: 50.0 }.outline(TAU * 50.0 / 1000.0);
    assert_eq!(points.len(), 1000);
    let text = polygon_text(&[ring_json(&points, Place::Metric, 0, false)]);
    let options = PlanOptions {
        coordinates: Coordinates::Metric,
        ..PlanOptions::default()
    };
    let plan = plan_geojson(&text, &options).unwrap_or_else(|e| panic!("{e}"));
    let disc = PI * 50.0 * 50.0;
    assert!(plan.field.area_m2() <= disc && plan.field.area_m2() > 0.97 * disc);
    assert!(plan.summary.swath_count > 0);
}

#[test]
fn a_400_m_disc_of_199_000_vertices_in_wgs84_is_read_whole() {
    let n = 199_000;
    let points = arc(
        Coord::zero(),
        400.0,
        0.0,
        TAU,
        TAU * 400.0 / n as f64,
        false,
    );
    assert_eq!(points.len(), n);
    let place = Place::Wgs84 {
        lon: 24.05,
        lat: 60.25,
    };
    let ring = ring_json(&points, place, 0, false);
    let (field, _) = Field::from_geojson_str(&polygon_text(std::slice::from_ref(&ring))).unwrap();
    let given = Polygon::new(local(&field, &ring), vec![]);
    let area = given.unsigned_area();
    assert!((field.area_m2() - area).abs() < 1e-3 * area);
}

#[test]
fn reproducers_plan_what_they_are() {
    let dir = common::corpus::fields_dir().join("reproducers");
    let metric = PlanOptions {
        coordinates: Coordinates::Metric,
        ..PlanOptions::default()
    };
    let read = |name: &str| std::fs::read_to_string(dir.join(name)).expect("reproducer");
    // A dense disc and a valid GNSS-like ring that cleaning collapsed onto a line.
    for name in [
        "circle_r50_n1000_metric.geojson",
        "gnss_zero_area_201_1000_metric.geojson",
    ] {
        let plan = plan_geojson(&read(name), &metric).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(plan.summary.swath_count > 0, "{name}");
    }
    // The bay that cleaning filled: the area as given within 0.1 %, no swath through the bay.
    let text = read("bay_filled_metric.geojson");
    let (field, _) = Field::from_geojson_str_in(&text, Coordinates::Metric).unwrap();
    assert!((field.area_m2() - 124_657.0).abs() < 1e-3 * 124_657.0);
    let plan = plan_geojson(&text, &metric).unwrap();
    let given = field.boundary;
    for swath in &plan.swaths.swaths {
        let line = geo::LineString::from(vec![swath.centre.start, swath.centre.end]);
        let outside: f64 = geo::BooleanOps::clip(
            &geo::MultiPolygon::new(vec![given.clone()]),
            &geo::MultiLineString::new(vec![line]),
            true,
        )
        .0
        .iter()
        .map(|l| geo::Length::length(&Euclidean, l))
        .sum();
        assert!(outside < 1e-6, "a swath runs {outside} m outside the field");
    }
}

#[test]
fn fuzzed_rings_with_stray_holes_are_refused_for_the_holes() {
    // Both outer rings are valid (one a 1,278 m by 5 m wedge with a corner of 0.32 degrees);
    // each file also has a hole outside or across its outer ring, and that is the error.
    let dir = common::corpus::fields_dir().join("reproducers");
    for name in [
        "false_self_intersection_101_2045.geojson",
        "thin_wedge_zero_area_103_2048.geojson",
    ] {
        let text = std::fs::read_to_string(dir.join(name)).expect("reproducer");
        let e = plan_geojson(&text, &PlanOptions::default()).unwrap_err();
        assert_eq!(e.code, ErrorCode::HoleCrossingBoundary, "{name}: {e}");
        assert_eq!(e.ring, Some(if name.starts_with("thin") { 1 } else { 4 }));
    }
}

#[test]
fn a_thin_wedge_plans() {
    // 1,278 m long and 5 m wide at its foot: a corner of 0.22 degrees, thin but a field.
    let wedge = [[0.0, 0.0], [1278.0, 2.5], [1278.0, -2.5], [0.0, 0.0]];
    let options = PlanOptions {
        coordinates: Coordinates::Metric,
        width: 2.0,
        headland_passes: 0.into(),
        turn_radius: 1.0,
        ..PlanOptions::default()
    };
    let plan = plan_geojson(&polygon_text(&[wedge.to_vec()]), &options).unwrap();
    assert!((plan.field.area_m2() - 1278.0 * 2.5).abs() < 1.0);
    assert!(plan.summary.swath_count > 0);
}

#[test]
fn the_gnss_traced_corpus_field_is_worked_inside_its_boundary() {
    let path = common::corpus::fields_dir().join("gps-traced-600-vertices.geojson");
    let text = std::fs::read_to_string(path).expect("corpus field");
    let given: Vec<[f64; 2]> = {
        let v: serde_json::Value = serde_json::from_str(&text).expect("json");
        let ring = v["features"]
            .as_array()
            .and_then(|f| f.first())
            .map(|f| f["geometry"]["coordinates"][0].clone())
            .unwrap_or_else(|| v["geometry"]["coordinates"][0].clone());
        serde_json::from_value(ring).expect("the boundary's ring")
    };
    for width in [1.0, 3.0, 6.0, 12.0] {
        let options = PlanOptions {
            width,
            ..PlanOptions::default()
        };
        let plan = plan_geojson(&text, &options).unwrap();
        // Its vertices are 1.1 to 5 m apart: samples to simplify from a width of 3 m.
        let simplified = plan
            .warnings
            .iter()
            .any(|w| w.code == furrow::WarningCode::OutlineSimplified);
        assert_eq!(simplified, width >= 3.0, "at {width} m");
        let field = Polygon::new(local(&plan.field, &given), vec![]);
        let outside = plan.field.boundary.difference(&field).unsigned_area();
        assert!(
            outside <= COLLINEAR_M * Euclidean.length(field.exterior()),
            "{outside} m² outside at {width} m"
        );
        check_outer_passes(&plan, &field, &field, width).unwrap();
    }
}
