//! The route on every corpus field: the block sequence is optimal (against an exhaustive
//! search over block orders and ways for 2 to 8 blocks), connections never cross the inner
//! field (they run along the headland, or along swaths already worked), each swath is worked
//! once with directions alternating in a block, patterns order a block's swaths as they should,
//! and the route starts at the entrance and ends at the exit.

mod common;

use common::corpus::{real_parcels, valid_fields};
use furrow::path::SegmentKind;
use furrow::plan::route_settings;
use furrow::route::block_sequence_problem;
use furrow::route::pattern::SwathPattern;
use furrow::route::sequence::{exhaustive, solve_exact};
use furrow::route::{RouteSettings, RouteStep};
use furrow::{plan_geojson, Plan, PlanOptions};
use geo::{Contains, Coord, Distance, Euclidean, Length, LineString, Point};

fn plan(text: &str, options: &PlanOptions, name: &str) -> Plan {
    plan_geojson(text, options).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Points every half metre along a line (and its vertices).
fn samples(line: &LineString) -> Vec<Coord> {
    let mut out = Vec::new();
    for w in line.0.windows(2) {
        let d = w[1] - w[0];
        let n = (d.x.hypot(d.y) / 0.5).ceil().max(1.0) as usize;
        for i in 0..n {
            out.push(w[0] + d * (i as f64 / n as f64));
        }
    }
    out.extend(line.0.last());
    out
}

/// Checks one connection line against the inner field (see [`check_connections`]).
fn check_connection(
    plan: &Plan,
    name: &str,
    line: &LineString,
    worked: &[LineString],
    passes: &[&LineString],
    rings: &[LineString],
    w: f64,
) {
    // Once every swath of the field is worked, there is no crop left in the inner field but
    // what the fill works (checked by [`check_standing_crop`]): the way to it, to an obstacle's
    // passes or to the exit may cross the stubble.
    if worked.len() >= field_swath_count(plan) {
        return;
    }
    let inner = &plan.headlands.inner;
    let pts = &line.0;
    let spur = |a: Coord, b: Coord| (b - a).x.hypot((b - a).y) <= 1.5 * w + 1e-6;
    let mut allowed: Vec<LineString> = Vec::new();
    if pts.len() >= 2 {
        if spur(pts[0], pts[1]) {
            allowed.push(LineString::new(vec![pts[0], pts[1]]));
        }
        let n = pts.len();
        if spur(pts[n - 2], pts[n - 1]) {
            allowed.push(LineString::new(vec![pts[n - 2], pts[n - 1]]));
        }
        // Out of a dead end, back along the swath just worked: the spur from its other end.
        let on_worked = |p: Coord| {
            worked
                .iter()
                .any(|t| Euclidean.distance(&Point(p), t) < 0.01)
        };
        if n >= 3 && on_worked(pts[0]) && on_worked(pts[1]) && spur(pts[1], pts[2]) {
            allowed.push(LineString::new(vec![pts[1], pts[2]]));
        }
    }
    for p in samples(line) {
        if !inner.contains(&Point(p)) {
            continue;
        }
        let to_edge = rings
            .iter()
            .map(|r| Euclidean.distance(&Point(p), r))
            .fold(f64::INFINITY, f64::min);
        let on_track = worked
            .iter()
            .chain(passes.iter().copied())
            .chain(&allowed)
            .any(|t| Euclidean.distance(&Point(p), t) < 0.01);
        assert!(
            to_edge < 0.05 || on_track,
            "{name}: a connection crosses the inner field at ({:.2}, {:.2}), {to_edge:.2} m from its edge ",
            p.x,
            p.y
        );
    }
}

/// Checks that no connection of a plan crosses its inner field: every point of a connection is
/// outside the inner field, on its edge (within 5 cm), on a headland pass (within 1 cm: a pass
/// rounded to the turning radius cuts the sharp corners of the inner field), on a swath worked
/// earlier in the route (within 1 cm of its centre line), or on the spur from a swath end to the
/// pass nearest to it (the first or last piece of the connection, at most 1.5 widths). After the
/// last swath nothing is left standing, so connections then are not checked. No connection may
/// run straight across.
fn check_connections(plan: &Plan, name: &str) {
    check_connections_but_straight(plan, name);
    assert_eq!(
        plan.summary.route.straight_connections, 0,
        "{name}: straight connections"
    );
}

/// [`check_connections`] for the connections along the headland: those that run straight across
/// the crop (where no way round it was found, announced by a warning) are not checked.
fn check_connections_but_straight(plan: &Plan, name: &str) {
    let w = plan.options.width;
    let passes: Vec<&LineString> = plan.headlands.passes.iter().map(|p| &p.line).collect();
    let inner = &plan.headlands.inner;
    let rings: Vec<LineString> = inner
        .0
        .iter()
        .flat_map(|p| std::iter::once(p.exterior().clone()).chain(p.interiors().iter().cloned()))
        .collect();
    let mut worked: Vec<LineString> = Vec::new();
    // The route's connections as routed along the headland graph (the path drives them with
    // their corners rounded at the turning radius), each checked against the swaths worked
    // before it.
    for (k, step) in plan.route.steps.iter().enumerate() {
        if let Some(Some(c)) = plan.route.connections.get(k) {
            if !c.straight {
                check_connection(plan, name, &c.line, &worked, &passes, &rings, w);
            }
        }
        if let RouteStep::Swath { swath, .. } = step {
            let s = &plan.swaths.swaths[*swath];
            worked.push(LineString::new(vec![s.centre.start, s.centre.end]));
        }
    }
    if let Some(c) = plan.route.finish.as_ref().filter(|c| !c.straight) {
        check_connection(plan, name, &c.line, &worked, &passes, &rings, w);
    }
}

/// The number of the field's swaths: those before the ones that fill what they leave.
fn field_swath_count(plan: &Plan) -> usize {
    plan.swaths.first_fill_swath()
}

/// The number of the field's blocks: those before the ones that fill what they leave.
fn field_block_count(plan: &Plan) -> usize {
    let first_fill = field_swath_count(plan);
    plan.blocks
        .blocks
        .iter()
        .take_while(|b| b.swaths.iter().any(|&i| i < first_fill))
        .count()
}

/// The greatest length, metres, of a connection along the headland (not one that runs straight
/// across, announced by a warning) through crop still standing when it is driven:
/// over the inner field (farther than 5 cm inside its edge and 1 cm off the headland passes,
/// whose track is driven anyway where a pass rounded at the turning radius cuts a corner of the
/// inner field), farther than half a width (less 1 cm) from every swath and headland pass
/// worked before it. The spurs between a swath end and
/// the headland (a connection's first or last piece, at most 1.5 widths) are not counted: they
/// cross the corner a slanted swath end leaves, as every turn does. Measured at points every
/// 10 cm.
fn longest_through_standing_crop(plan: &Plan) -> f64 {
    let w_m = plan.options.width;
    let half = w_m / 2.0 - 0.01;
    let inner = &plan.headlands.inner;
    let rings: Vec<LineString> = inner
        .0
        .iter()
        .flat_map(|p| std::iter::once(p.exterior().clone()).chain(p.interiors().iter().cloned()))
        .collect();
    let passes: Vec<&LineString> = plan.headlands.passes.iter().map(|p| &p.line).collect();
    let mut worked: Vec<LineString> = Vec::new();
    let mut longest: f64 = 0.0;
    let mut measure = |line: &LineString, worked: &[LineString]| {
        let mut run: f64 = 0.0;
        let n = line.0.len();
        // Out of a dead end, back along the swath just worked: the spur is the second piece.
        let on_worked = |p: Coord| {
            worked
                .iter()
                .any(|t| Euclidean.distance(&Point(p), t) < 0.01)
        };
        let back = n >= 3 && on_worked(line.0[0]) && on_worked(line.0[1]);
        for (k, w) in line.0.windows(2).enumerate() {
            let d = w[1] - w[0];
            let end = k == 0 || k + 2 == n || (k == 1 && back);
            let spur = end && d.x.hypot(d.y) <= 1.5 * w_m + 1e-6;
            if spur {
                continue;
            }
            let n = (d.x.hypot(d.y) / 0.1).ceil().max(1.0) as usize;
            let step = d.x.hypot(d.y) / n as f64;
            for i in 0..n {
                let p = Point(w[0] + d * ((i as f64 + 0.5) / n as f64));
                let standing = inner.contains(&p)
                    && rings.iter().all(|r| Euclidean.distance(&p, r) > 0.05)
                    && passes.iter().all(|t| Euclidean.distance(&p, *t) > 0.01)
                    && worked.iter().all(|t| Euclidean.distance(&p, t) > half);
                if standing {
                    run += step;
                }
            }
        }
        longest = longest.max(run);
    };
    for (k, step) in plan.route.steps.iter().enumerate() {
        if let Some(Some(c)) = plan
            .route
            .connections
            .get(k)
            .filter(|c| c.as_ref().is_some_and(|c| !c.straight))
        {
            measure(&c.line, &worked);
        }
        match *step {
            RouteStep::Swath { swath, .. } => {
                let s = &plan.swaths.swaths[swath];
                worked.push(LineString::new(vec![s.centre.start, s.centre.end]));
            }
            RouteStep::HeadlandPass { pass, .. } => {
                worked.push(plan.headlands.passes[pass].line.clone());
            }
        }
    }
    if let Some(c) = plan.route.finish.as_ref().filter(|c| !c.straight) {
        measure(&c.line, &worked);
    }
    longest
}

/// Each swath once; inside a block each is driven the other way from the one before.
fn check_swaths_once(plan: &Plan, name: &str) {
    let mut seen = vec![0usize; plan.swaths.swaths.len()];
    let mut previous: Option<(usize, bool)> = None;
    for step in &plan.route.steps {
        if let RouteStep::Swath {
            swath,
            reversed,
            block,
        } = *step
        {
            seen[swath] += 1;
            if let Some((b, r)) = previous {
                if b == block {
                    assert_ne!(
                        r, reversed,
                        "{name}: two swaths of a block driven the same way"
                    );
                }
            }
            previous = Some((block, reversed));
        } else {
            previous = None;
        }
    }
    assert!(
        seen.iter().all(|&n| n == 1),
        "{name}: swaths not worked once"
    );
}

#[test]
fn connections_never_cross_the_inner_field_on_any_corpus_field() {
    for field in valid_fields() {
        for first in [false, true] {
            let options = PlanOptions {
                headland_order: if first {
                    furrow::headland::HeadlandOrder::First
                } else {
                    furrow::headland::HeadlandOrder::Last
                },
                ..field.options.clone()
            };
            let p = plan(&field.text(), &options, &field.name);
            if first {
                // With the headland first the route starts where the passes end, and a block
                // may then be reachable only across crop: each such connection is reported.
                let straight = p.route.all_connections().filter(|c| c.straight).count();
                assert_eq!(p.summary.route.straight_connections, straight);
                assert_eq!(
                    p.warnings
                        .iter()
                        .any(|w| w.code == furrow::WarningCode::StraightConnections),
                    straight > 0,
                    "{}",
                    field.name
                );
            } else {
                check_connections(&p, &field.name);
                let crossed = longest_through_standing_crop(&p);
                assert!(
                    crossed < 1.0,
                    "{}: {crossed:.2} m through standing crop",
                    field.name
                );
            }
            check_swaths_once(&p, &field.name);
            // The path is continuous.
            for w in p.path.segments.windows(2) {
                let (a, b) = (w[0].line.0.last().unwrap(), w[1].line.0[0]);
                assert!(
                    (a.x - b.x).hypot(a.y - b.y) < 1e-6,
                    "{}: gap in the path",
                    field.name
                );
            }
        }
    }
}

/// The register parcels with a wide machine and one pass: the passes round two parts of a
/// parcel may come within a hop of each other across a narrow neck of crop (Dutch parcel 45),
/// and a connection must then go round, or straight across with a warning, not hop across.
#[test]
fn connections_along_the_headland_never_cross_the_crop_of_register_parcels() {
    let options = PlanOptions {
        width: 12.0,
        headland_passes: 1.into(),
        turn_radius: 9.0,
        ..PlanOptions::default()
    };
    let mut checked = 0;
    for (file, i, text) in real_parcels() {
        if let Ok(p) = plan_geojson(&text, &options) {
            check_connections_but_straight(&p, &format!("{file}[{i}]"));
            let crossed = longest_through_standing_crop(&p);
            assert!(
                crossed < 1.0,
                "{file}[{i}]: {crossed:.2} m through standing crop"
            );
            checked += 1;
        }
    }
    assert!(checked >= 100, "only {checked} register parcels planned");
}

#[test]
fn the_block_sequence_equals_an_exhaustive_search_on_fields_of_two_to_eight_blocks() {
    let mut checked = Vec::new();
    for field in valid_fields() {
        for pattern in [SwathPattern::Boustrophedon, SwathPattern::Auto] {
            let options = PlanOptions {
                pattern,
                ..field.options.clone()
            };
            let p = plan(&field.text(), &options, &field.name);
            // The field's blocks, sequenced first.
            let blocks = field_block_count(&p);
            if !(2..=8).contains(&blocks) {
                continue;
            }
            let settings = RouteSettings {
                crop: Some(p.headlands.inner.clone()),
                ..route_settings(&options, &p.field)
            };
            let problem =
                block_sequence_problem(&p.swaths, &p.blocks, &p.headlands.passes, &settings)
                    .expect("a few blocks' connections are searched");
            let exact = solve_exact(&problem);
            let all = exhaustive(&problem);
            assert!(
                (exact.cost - all.cost).abs() <= 1e-9 * all.cost.max(1.0),
                "{}: exact {} against exhaustive {}",
                field.name,
                exact.cost,
                all.cost
            );
            // The plan's route is that sequence (no detour along a swath was needed).
            let field_cost = p.route.sequence.cost_m - p.route.sequence.fill_cost_m;
            assert!(
                (field_cost - all.cost).abs() <= 1e-6 * all.cost.max(1.0),
                "{}: route {} against exhaustive {}",
                field.name,
                field_cost,
                all.cost
            );
            // The field's blocks in that order; the blocks that fill (numbered after them) come
            // after them or on the way between them, each once.
            let order: Vec<usize> = exact.order.iter().map(|&(b, _)| b).collect();
            let (field_order, mut fill): (Vec<usize>, Vec<usize>) =
                p.route.block_order.iter().partition(|&&b| b < blocks);
            assert_eq!(field_order, order, "{}", field.name);
            fill.sort_unstable();
            assert_eq!(fill, (blocks..p.blocks.blocks.len()).collect::<Vec<_>>());
            checked.push(format!("{} ({blocks})", field.name));
        }
    }
    assert!(
        checked.len() >= 8,
        "too few fields of 2-8 blocks: {checked:?}"
    );
}

#[test]
fn patterns_order_the_swaths_of_a_block() {
    let field = valid_fields()
        .into_iter()
        .find(|f| f.name == "rectangle")
        .expect("rectangle in the corpus");
    let base = PlanOptions {
        decomposition: furrow::decompose::Decomposition::None,
        ..field.options.clone()
    };
    let line_order = |p: &Plan| -> Vec<usize> {
        p.route
            .steps
            .iter()
            .filter_map(|s| match *s {
                RouteStep::Swath { swath, .. } => Some(p.swaths.swaths[swath].line_index),
                _ => None,
            })
            .collect()
    };
    let cases: [(SwathPattern, u32, Vec<u32>); 4] = [
        (SwathPattern::Boustrophedon, 1, vec![]),
        (SwathPattern::Snake, 2, vec![]),
        (SwathPattern::Spiral, 1, vec![]),
        (SwathPattern::Custom, 1, vec![0, 2, 1, 3]),
    ];
    for (pattern, skip, custom) in cases {
        let options = PlanOptions {
            pattern,
            snake_skip: skip,
            spiral_size: 4,
            custom_order: custom,
            ..base.clone()
        };
        let p = plan(&field.text(), &options, "rectangle");
        // One block of the field (the corners the rounded headland leaves are filled after it).
        assert_eq!(field_block_count(&p), 1);
        check_swaths_once(&p, "rectangle");
        let mut lines = line_order(&p);
        lines.truncate(field_swath_count(&p));
        let n = lines.len();
        // From either side: positions counted from the first line worked.
        let pos: Vec<usize> = if lines[0] == 0 {
            lines.clone()
        } else {
            lines.iter().map(|&l| n - 1 - l).collect()
        };
        let expected: Vec<usize> = match pattern {
            SwathPattern::Boustrophedon => (0..n).collect(),
            SwathPattern::Snake => {
                furrow::route::pattern::SwathOrder::Snake { skip: 2 }.positions(n)
            }
            SwathPattern::Spiral => {
                furrow::route::pattern::SwathOrder::Spiral { size: 4 }.positions(n)
            }
            _ => furrow::route::pattern::SwathOrder::Custom(vec![0, 2, 1, 3]).positions(n),
        };
        assert_eq!(pos, expected, "{}", pattern.as_str());
        assert_eq!(p.summary.route.block_patterns.len(), p.blocks.blocks.len());
    }
    // Auto takes the pattern whose turns are shortest: never longer than boustrophedon's.
    let auto = plan(&field.text(), &base, "rectangle");
    let bous = plan(
        &field.text(),
        &PlanOptions {
            pattern: SwathPattern::Boustrophedon,
            ..base.clone()
        },
        "rectangle",
    );
    assert!(auto.summary.turning_distance_m <= bous.summary.turning_distance_m + 1e-9);
}

#[test]
fn the_route_starts_at_the_entrance_and_ends_at_the_exit() {
    for name in ["rectangle", "obstacles-2", "obstacles-5"] {
        let field = valid_fields()
            .into_iter()
            .find(|f| f.name == name)
            .expect("field in the corpus");
        let free = plan(&field.text(), &field.options, name);
        // An entrance and an exit at two corners of the boundary, in the input's coordinates.
        let ring = &free.field.boundary.exterior().0;
        let (a, b) = (ring[0], ring[ring.len() / 2]);
        let options = PlanOptions {
            entrance: Some(free.field.frame.to_input(a)),
            exit: Some(free.field.frame.to_input(b)),
            ..field.options.clone()
        };
        let p = plan(&field.text(), &options, name);
        let first = p.path.segments.first().unwrap().line.0[0];
        let last = *p.path.segments.last().unwrap().line.0.last().unwrap();
        assert!(
            (first - a).x.hypot((first - a).y) < 1e-6,
            "{name}: starts at {first:?}"
        );
        assert!(
            (last - b).x.hypot((last - b).y) < 1e-6,
            "{name}: ends at {last:?}"
        );
        check_connections(&p, name);
        // The way in and the way out are connections.
        assert_eq!(p.path.segments[0].kind, SegmentKind::Connection, "{name}");
        assert_eq!(
            p.path.segments.last().unwrap().kind,
            SegmentKind::Connection,
            "{name}"
        );
        let to_exit = Euclidean.length(&p.route.finish.as_ref().expect("a finish").line);
        assert!(to_exit > 0.0);
    }
}
