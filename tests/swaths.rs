//! Swaths and the driving direction on the whole corpus: swaths lie inside the inner field and
//! outside obstacles, neighbours are exactly a width apart, convex inner fields are covered, no
//! swath runs in a forbidden direction (global ranges, prohibited regions, random ones included),
//! reference lines are followed, and the coarse-to-fine search stays within 1 % of brute force.

mod common;

use common::corpus::{real_parcels, strip_out_of_region, valid_fields, CorpusField};
use furrow::direction::{DirectionMode, SearchMethod};
use furrow::field::{Field, ProhibitedRegion};
use furrow::geometry::{bearing_of, forbids_every_direction, swath_direction, BearingRange};
use furrow::obstacles::ObstacleClass;
use furrow::{plan, plan_geojson, ErrorCode, Plan, PlanOptions};
use geo::{
    Area, BooleanOps, BoundingRect, Contains, ConvexHull, Coord, Distance, Euclidean, Intersects,
    Length, Line, LineString, MultiLineString, MultiPolygon, Point, Polygon,
};
use proptest::prelude::*;
use std::f64::consts::PI;

/// Metres of slack: geo's boolean operations snap to about 1e-6 of the field's extent.
const EPS: f64 = 1e-3;

/// The swath's centre line less 1 mm at each end.
fn shortened(line: &Line) -> Line {
    let d = line.delta();
    let len = d.x.hypot(d.y);
    let u = Coord {
        x: d.x / len * EPS,
        y: d.y / len * EPS,
    };
    Line::new(line.start + u, line.end - u)
}

/// Length of `line` inside `polygon`.
fn length_inside(line: &Line, polygon: &Polygon) -> f64 {
    let lines = MultiLineString::new(vec![LineString::from(vec![line.start, line.end])]);
    polygon
        .clip(&lines, false)
        .0
        .iter()
        .map(|l| geo::Euclidean.length(l))
        .sum()
}

/// A swath that fills what the others leave may run anywhere in the field (in the headland's
/// corners, say): its whole strip inside the field and off every obstacle (within 1 cm: the
/// field inset by half a width, where its centre line may run, rounds reflex corners by chords
/// of an arc).
fn check_fill_swath(plan: &Plan, id: &str, line: &Line) {
    let half = plan.options.width / 2.0;
    let mid = Point((line.start + line.end) / 2.0);
    assert!(plan.field.boundary.contains(&mid), "{id} leaves the field");
    let rings = std::iter::once(&plan.field.boundary)
        .chain(plan.field.obstacles.iter().map(|o| &o.polygon))
        .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()));
    for ring in rings {
        let d = geo::Euclidean.distance(line, ring);
        assert!(
            d >= half - 0.01,
            "{id}: its strip reaches {:.3} m over the field's edge or an obstacle",
            half - d
        );
    }
    for o in &plan.field.obstacles {
        assert!(!o.polygon.contains(&mid), "{id} runs on an obstacle");
    }
}

/// Every invariant of the swaths of a plan; `forbidden` are the global ranges.
fn check_swaths(plan: &Plan, name: &str) {
    let w = plan.options.width;
    let inner = &plan.headlands.inner;
    let edges: Vec<Line> = inner
        .0
        .iter()
        .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
        .flat_map(|r| r.lines())
        .collect();
    let holes: Vec<&Polygon> = plan
        .field
        .obstacles
        .iter()
        .enumerate()
        .filter(|(i, _)| plan.obstacles.class.get(*i) != Some(&ObstacleClass::A))
        .map(|(_, o)| &o.polygon)
        .collect();
    let fill_from = plan.swaths.first_fill_swath();
    for s in &plan.swaths.swaths {
        let id = format!("{name}: swath {}", s.index);
        let line = shortened(&s.centre);
        if s.index >= fill_from {
            check_fill_swath(plan, &id, &line);
        } else {
            // Working the inner field: inside it, or (where its strip reaches the inner field
            // from the headland) within a quarter width of it, its strip in the region.
            let mid = Point((s.centre.start + s.centre.end) / 2.0);
            let reached =
                |p: Point| inner.contains(&p) || Euclidean.distance(&p, inner) <= w / 4.0 + 1e-6;
            assert!(reached(mid), "{id} leaves the inner field");
            let bounds = line.bounding_rect();
            let inside = edges
                .iter()
                .filter(|e| e.bounding_rect().intersects(&bounds))
                .all(|e| !line.intersects(e));
            if !inside {
                for end in [s.centre.start, s.centre.end] {
                    assert!(
                        reached(Point(end)),
                        "{id} runs on beyond a quarter width of the inner field"
                    );
                }
                assert!(
                    strip_out_of_region(plan, s) < 1e-3,
                    "{id}'s strip reaches out of the region"
                );
            }
            for hole in &holes {
                assert!(!line.intersects(*hole), "{id} crosses an obstacle");
            }
            assert!(s.length() >= plan.options.min_swath_length_m() - 1e-9);
        }
        // Its bearing is its direction, and no range forbids it.
        let b = swath_direction(bearing_of(s.centre.start, s.centre.end));
        let diff = (b - s.bearing).rem_euclid(PI);
        assert!(diff.min(PI - diff) < 1e-9, "{id} is not at its bearing");
        for r in &plan.options.forbidden_bearings_deg {
            assert!(!r.forbids(s.bearing), "{id} runs at a forbidden {b}");
        }
        for (k, region) in plan.field.prohibited.iter().enumerate() {
            if length_inside(&line, &region.polygon) > EPS {
                for r in &region.forbidden {
                    assert!(
                        !r.forbids(s.bearing),
                        "{id} runs at {:.2} degrees through prohibited region {k}, which forbids {r:?}",
                        s.bearing.to_degrees()
                    );
                }
            }
        }
    }
    // Spacing, area by area: regular lines exactly a width apart; a leftover line closer, by its
    // overlap.
    for area in plan.swaths.areas.iter().filter(|a| !a.fill) {
        let mut lines: Vec<(usize, f64, f64)> = Vec::new();
        for s in &plan.swaths.swaths[area.swaths.clone()] {
            if lines.last().map(|l| l.0) != Some(s.line_index) {
                lines.push((s.line_index, s.across, s.overlap_m));
            }
        }
        for pair in lines.windows(2) {
            let ((i, a, oa), (j, b, ob)) = (pair[0], pair[1]);
            let gap = b - a;
            let expected = (j - i) as f64 * w;
            if oa == 0.0 && ob == 0.0 {
                assert!(
                    (gap - expected).abs() < EPS,
                    "{name}: lines {i} and {j} are {gap} m apart, expected {expected}"
                );
            } else {
                assert!(
                    gap > 0.0 && gap <= expected + EPS,
                    "{name}: leftover gap {gap}"
                );
                if j == i + 1 {
                    let overlap = oa.max(ob);
                    assert!(
                        (gap - (w - overlap)).abs() < EPS,
                        "{name}: lines {i} and {j} are {gap} m apart with overlap {overlap}"
                    );
                }
            }
        }
    }
    // A convex inner field (one part, no holes, no region cut out) is covered at the direction
    // the search chose. (At a direction given by the user, the strips' corners at slanted ends
    // leave w²/8 · tan(angle) per end uncovered: see `convex_inner_fields_are_covered`.)
    // Unconstrained, that is: forbidden directions may leave only worse ones.
    let searched = plan.summary.direction.mode == DirectionMode::Search
        && plan.options.forbidden_bearings_deg.is_empty()
        && plan.field.prohibited.is_empty();
    if searched
        && inner.0.len() == 1
        && inner.0[0].interiors().is_empty()
        && plan.swaths.areas.len() == 1
    {
        let hull = inner.convex_hull().unsigned_area();
        if inner.unsigned_area() > 0.999 * hull {
            let c = plan.summary.objectives.coverage;
            assert!(c >= 0.99, "{name}: convex inner field covered {c}");
        }
    }
}

fn plan_corpus(field: &CorpusField, options: &PlanOptions) -> Plan {
    plan_geojson(&field.text(), options).unwrap_or_else(|e| panic!("{}: {e}", field.name))
}

#[test]
fn swaths_keep_their_invariants_on_every_corpus_field() {
    for field in valid_fields() {
        let plan = plan_corpus(&field, &field.options);
        check_swaths(&plan, &field.name);
        // The summary reports every objective for the chosen direction.
        let o = &plan.summary.objectives;
        assert_eq!(o.swath_count, plan.summary.swath_count, "{}", field.name);
        assert!(o.coverage > 0.9 && o.coverage <= 1.0, "{}", field.name);
        assert!(o.time_s > 0.0 && o.oksanen_score > 0.0, "{}", field.name);
        assert_eq!(plan.summary.direction.mode, DirectionMode::Search);
        assert!(plan.summary.direction.evaluations >= 6);
    }
}

#[test]
fn convex_inner_fields_are_covered() {
    // Fields whose inner field is convex: the square, the rectangle, the skewed quadrilateral and
    // the field with one curved edge, at the searched direction and at awkward fixed ones.
    let mut checked = 0;
    for field in valid_fields() {
        if !["square-1ha", "rectangle", "skew-quad", "curved-edge"].contains(&field.name.as_str()) {
            continue;
        }
        for bearing in [None, Some(13.0), Some(77.7), Some(141.0)] {
            let options = PlanOptions {
                bearing_deg: bearing,
                ..field.options.clone()
            };
            let plan = plan_corpus(&field, &options);
            check_swaths(&plan, &field.name);
            let c = plan.summary.objectives.coverage;
            // At a given bearing, a swath ending on an edge at angle a to its normal leaves a
            // triangle of w²/8 · tan(a) uncovered (and as much of its strip over the edge). On
            // the 1 ha square at 2.5 m that is about 1 % at 45 degrees.
            let least = if bearing.is_none() { 0.99 } else { 0.985 };
            assert!(c >= least, "{} at {bearing:?}: {c}", field.name);
            checked += 1;
        }
    }
    assert_eq!(checked, 16);
}

#[test]
fn prohibited_regions_that_forbid_the_direction_get_their_own() {
    for (name, bearing) in [
        ("c-shape-escarpment", 45.0),
        ("underdrain", 0.0),
        ("underdrain", 90.0),
    ] {
        let field = valid_fields()
            .into_iter()
            .find(|f| f.name == name)
            .expect("corpus field");
        let options = PlanOptions {
            bearing_deg: Some(bearing),
            ..field.options.clone()
        };
        let plan = plan_corpus(&field, &options);
        check_swaths(&plan, name);
        let own: Vec<_> = plan
            .swaths
            .areas
            .iter()
            .filter(|a| a.region.is_some())
            .collect();
        assert!(!own.is_empty(), "{name} at {bearing}: no region cut out");
        for a in own {
            assert!(!a.swaths.is_empty(), "{name}: a region without swaths");
        }
        assert!(plan
            .warnings
            .iter()
            .any(|w| w.code == furrow::WarningCode::RegionOwnDirection));
        // Its blocks say which region they follow.
        let geojson = plan.to_geojson_string();
        assert!(geojson.contains(r#""region":"#), "{name}");
    }
}

#[test]
fn reference_edge_and_line_put_the_swaths_on_their_grid() {
    // A 200 x 120 m rectangle in metres, drawn from its south-west corner anticlockwise; edge 0
    // runs east along y = 0.
    let text =
        r#"{"type": "Polygon", "coordinates": [[[0, 0], [200, 0], [200, 120], [0, 120], [0, 0]]]}"#;
    let base = PlanOptions {
        width: 6.0,
        headland_passes: 2.into(),
        coordinates: furrow::field::Coordinates::Metric,
        ..PlanOptions::default()
    };
    let edge = plan_geojson(
        text,
        &PlanOptions {
            reference_edge: Some(0),
            ..base.clone()
        },
    )
    .expect("plans");
    assert_eq!(edge.summary.direction.mode, DirectionMode::Reference);
    assert!((edge.summary.bearing_deg - 90.0).abs() < 1e-9);
    for s in edge.swaths.swaths.iter().filter(|s| s.overlap_m == 0.0) {
        // Half a width plus whole widths from the edge: the headland passes' grid continued.
        let y = s.centre.start.y;
        let k = (y - 3.0) / 6.0;
        assert!((k - k.round()).abs() < 1e-6, "line at y = {y}");
    }
    check_swaths(&edge, "reference edge");
    // Last year's AB line ran north-east through (10, 10); this year, 1 m to its right.
    let line = plan_geojson(
        text,
        &PlanOptions {
            reference_line: Some([[10.0, 10.0], [60.0, 60.0]]),
            reference_offset: Some(1.0),
            ..base.clone()
        },
    )
    .expect("plans");
    assert!((line.summary.bearing_deg - 45.0).abs() < 1e-9);
    for s in line.swaths.swaths.iter().filter(|s| s.overlap_m == 0.0) {
        // Signed distance to the right of the AB line (direction (1, 1) / √2: right is (1, -1) / √2).
        let p = s.centre.start;
        let right = ((p.x - 10.0) - (p.y - 10.0)) / 2f64.sqrt();
        let k = (right - 1.0) / 6.0;
        assert!(
            (k - k.round()).abs() < 1e-6,
            "line {right} m right of the AB line"
        );
    }
    check_swaths(&line, "reference line");
    // A reference in a forbidden range is refused; an edge that does not exist too.
    let e = plan_geojson(
        text,
        &PlanOptions {
            reference_edge: Some(0),
            forbidden_bearings_deg: vec![BearingRange {
                from_deg: 80.0,
                to_deg: 100.0,
            }],
            ..base.clone()
        },
    )
    .unwrap_err();
    assert_eq!(e.code, ErrorCode::BearingForbidden);
    let e = plan_geojson(
        text,
        &PlanOptions {
            reference_edge: Some(4),
            ..base
        },
    )
    .unwrap_err();
    assert_eq!(e.code, ErrorCode::OptionOutOfRange);
}

/// The share of fields where the coarse-to-fine search's cost is within 1 % of brute force's.
#[test]
fn coarse_to_fine_is_within_one_percent_of_brute_force_on_95_percent_of_fields() {
    let mut cases: Vec<(String, String, PlanOptions)> = valid_fields()
        .into_iter()
        .map(|f| (f.name.clone(), f.text(), f.options))
        .collect();
    let real = PlanOptions {
        width: 6.0,
        headland_passes: 2.into(),
        turn_radius: 8.0,
        ..PlanOptions::default()
    };
    for (file, i, text) in real_parcels() {
        cases.push((format!("{file}[{i}]"), text, real.clone()));
    }
    let (mut within, mut compared) = (0, 0);
    let mut misses = Vec::new();
    for (name, text, options) in &cases {
        let cost = |method| {
            // The direction search alone: without the decompositions' own searches per block.
            let o = PlanOptions {
                search: method,
                decomposition: furrow::decompose::Decomposition::None,
                ..options.clone()
            };
            plan_geojson(text, &o).ok().map(|p| {
                let d = p.summary.direction;
                (d.search_cost.expect("searched"), d.evaluations)
            })
        };
        let (Some((brute, brute_evals)), Some((fine, fine_evals))) = (
            cost(SearchMethod::BruteForce),
            cost(SearchMethod::CoarseToFine),
        ) else {
            continue;
        };
        compared += 1;
        assert!(fine_evals < brute_evals, "{name}: {fine_evals} evaluations");
        if fine <= brute * 1.01 + 1e-9 {
            within += 1;
        } else {
            misses.push(format!("{name} {:+.2} %", 100.0 * (fine - brute) / brute));
        }
    }
    assert!(compared >= 140, "only {compared} fields compared");
    assert!(
        within as f64 >= 0.95 * compared as f64,
        "coarse-to-fine within 1 % on {within} of {compared}: {misses:?}"
    );
}

/// A random prohibited region: the part of the field inside a random rectangle of its bounds.
fn random_region(
    field: &Field,
    rect: (f64, f64, f64, f64),
    forbidden: Vec<BearingRange>,
) -> Option<ProhibitedRegion> {
    let b = field.boundary.bounding_rect()?;
    let (x0, y0, dx, dy) = rect;
    let min = Coord {
        x: b.min().x + x0 * b.width(),
        y: b.min().y + y0 * b.height(),
    };
    let max = Coord {
        x: min.x + dx * b.width(),
        y: min.y + dy * b.height(),
    };
    let r = geo::Rect::new(min, max).to_polygon();
    let part: MultiPolygon = field.boundary.intersection(&r);
    let polygon = part
        .0
        .into_iter()
        .max_by(|a, b| a.unsigned_area().total_cmp(&b.unsigned_area()))?;
    Some(ProhibitedRegion {
        polygon,
        forbidden,
        feature: 0,
        name: None,
    })
}

fn range() -> impl Strategy<Value = BearingRange> {
    (0.0..360.0f64, 1.0..70.0f64).prop_map(|(from, width)| BearingRange {
        from_deg: from,
        to_deg: from + width,
    })
}

proptest! {
    #![proptest_config(common::seeded::config(40))]

    /// Random global forbidden ranges and a random prohibited region with random ranges, at a
    /// random direction rule, on a random corpus field: no swath in a forbidden direction, and
    /// every other invariant kept.
    #[test]
    fn no_swath_runs_in_a_forbidden_direction(
        index in 0usize..64,
        global in proptest::collection::vec(range(), 0..3),
        own in proptest::collection::vec(range(), 1..3),
        rect in (0.0..0.7f64, 0.0..0.7f64, 0.2..0.6f64, 0.2..0.6f64),
        rule in 0usize..4,
        bearing in 0.0..180.0f64,
    ) {
        prop_assume!(!forbids_every_direction(&global));
        let fields = valid_fields();
        let corpus = &fields[index % fields.len()];
        let (mut field, _) = Field::from_geojson_str(&corpus.text()).expect("corpus field reads");
        for r in &mut field.prohibited {
            r.forbidden = own.clone();
        }
        if let Some(r) = random_region(&field, rect, own.clone()) {
            field.prohibited.push(r);
        }
        let mut options = PlanOptions {
            forbidden_bearings_deg: global.clone(),
            ..corpus.options.clone()
        };
        match rule {
            0 => {}
            1 => {
                options.search = SearchMethod::BruteForce;
                options.search_step_deg = 5.0;
            }
            2 => options.bearing_deg = Some(bearing),
            _ => options.direction = Some(DirectionMode::LongestEdge),
        }
        match plan(field, &options) {
            Ok(p) => check_swaths(&p, &corpus.name),
            Err(e) => {
                // Only a fixed bearing in a forbidden range may be refused.
                prop_assert_eq!(rule, 2, "{}: {}", corpus.name, e);
                prop_assert_eq!(e.code, ErrorCode::BearingForbidden);
            }
        }
    }
}

#[test]
fn a_region_left_no_direction_gets_no_swaths_and_a_warning() {
    // Underdrain's first region forbids 350-10 (and 170-190); with 10-170 forbidden everywhere,
    // the field runs at 5 degrees, which the region forbids, and nothing is left for the region.
    let field = valid_fields()
        .into_iter()
        .find(|f| f.name == "underdrain")
        .expect("corpus field");
    let options = PlanOptions {
        bearing_deg: Some(5.0),
        forbidden_bearings_deg: vec![BearingRange {
            from_deg: 10.0,
            to_deg: 170.0,
        }],
        ..field.options.clone()
    };
    let plan = plan_corpus(&field, &options);
    check_swaths(&plan, "underdrain");
    let w = plan
        .warnings
        .iter()
        .find(|w| w.code == furrow::WarningCode::RegionNotWorked)
        .expect("a region_not_worked warning");
    assert!(w.feature.is_some());
    assert!(plan.swaths.areas.iter().all(|a| a.region.is_none()));
}

#[test]
fn too_many_swath_lines_to_search_follow_the_longest_edge() {
    // 2 km x 300 m worked 0.2 m wide: 10,000 lines at most, times 40 directions, over budget.
    let text = r#"{"type": "Polygon", "coordinates": [[[0, 0], [2000, 0], [2000, 300], [0, 300], [0, 0]]]}"#;
    let options = PlanOptions {
        width: 0.2,
        headland_passes: 1.into(),
        turn_radius: 0.5,
        coordinates: furrow::field::Coordinates::Metric,
        ..PlanOptions::default()
    };
    let plan = plan_geojson(text, &options).expect("plans");
    assert_eq!(plan.summary.direction.mode, DirectionMode::LongestEdge);
    assert_eq!(plan.summary.direction.evaluations, 0);
    assert!((plan.summary.bearing_deg - 90.0).abs() < 1e-9);
    assert!(plan
        .warnings
        .iter()
        .any(|w| w.code == furrow::WarningCode::DirectionNotSearched));
    // At 6 m the same field is searched.
    let wide = plan_geojson(
        text,
        &PlanOptions {
            width: 6.0,
            ..options
        },
    )
    .expect("plans");
    assert_eq!(wide.summary.direction.mode, DirectionMode::Search);
}

#[test]
fn outlines_of_too_many_vertices_to_search_follow_the_longest_edge() {
    // 600 m x 300 m at 6 m: 112 lines; and 300 ponds of 24 vertices each, 7,200 vertices the
    // sweep of each direction sorts, over the budget.
    let pond = |cx: f64, cy: f64| {
        let ring: Vec<String> = (0..=24)
            .map(|k| {
                let t = (k % 24) as f64 / 24.0 * std::f64::consts::TAU;
                format!("[{},{}]", cx + 4.0 * t.cos(), cy - 4.0 * t.sin())
            })
            .collect();
        format!(
            r#"{{"type":"Feature","properties":{{"role":"obstacle"}},"geometry":{{"type":"Polygon","coordinates":[[{}]]}}}}"#,
            ring.join(",")
        )
    };
    let field = r#"{"type":"Feature","properties":{"role":"boundary"},"geometry":{"type":"Polygon","coordinates":[[[0,0],[600,0],[600,300],[0,300],[0,0]]]}}"#;
    let with_ponds = |n: usize| {
        let mut features = vec![field.to_string()];
        features.extend(
            (0..n).map(|i| pond(15.0 + 30.0 * (i % 20) as f64, 15.0 + 20.0 * (i / 20) as f64)),
        );
        format!(
            r#"{{"type":"FeatureCollection","features":[{}]}}"#,
            features.join(",")
        )
    };
    let options = PlanOptions {
        headland_passes: 0.into(),
        coordinates: furrow::field::Coordinates::Metric,
        ..PlanOptions::default()
    };
    let plan = plan_geojson(&with_ponds(300), &options).expect("plans");
    assert_eq!(plan.summary.direction.mode, DirectionMode::LongestEdge);
    let w = plan
        .warnings
        .iter()
        .find(|w| w.code == furrow::WarningCode::DirectionNotSearched)
        .expect("direction_not_searched");
    assert!(w.message.contains("vertices"), "{}", w.message);
    // With 30 ponds the same field is searched.
    let few = plan_geojson(&with_ponds(30), &options).expect("plans");
    assert_eq!(few.summary.direction.mode, DirectionMode::Search);
}
