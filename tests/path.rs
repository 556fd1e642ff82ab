//! The drivable path on every corpus field, for a machine that only drives forward, one that
//! may reverse, and one with a curvature rate (continuous-curvature turns): curvature never
//! exceeds 1/radius, position and heading are continuous, the machine reverses only where it
//! may, the sampled path keeps its spacing and follows its curvature, and turns stay in the
//! field where the headland has room (two passes or more), or are reported with their cause.

mod common;

use common::corpus::valid_fields;
use furrow::path::curve::{Gear, Pose};
use furrow::path::sample::sample;
use furrow::path::turn::{Area, Vehicle};
use furrow::path::SegmentKind;
use furrow::{plan_geojson, Plan, PlanOptions, WarningCode};

fn plan(text: &str, options: &PlanOptions, name: &str) -> Plan {
    plan_geojson(text, options).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// A 6 m drill with two passes turning at 8 m, forward only.
fn drill() -> PlanOptions {
    PlanOptions {
        width: 6.0,
        headland_passes: furrow::headland::passes::HeadlandPasses::Count(2),
        turn_radius: 8.0,
        ..PlanOptions::default()
    }
}

/// The machines every field is planned for.
fn machines(base: &PlanOptions) -> Vec<(&'static str, PlanOptions)> {
    vec![
        ("forward", base.clone()),
        (
            "reversing",
            PlanOptions {
                reverse: true,
                ..base.clone()
            },
        ),
        (
            "continuous-curvature",
            PlanOptions {
                curvature_rate: Some(0.1),
                ..base.clone()
            },
        ),
    ]
}

fn check_path(plan: &Plan, what: &str) {
    let r = plan.options.turn_radius;
    let mut previous: Option<Pose> = None;
    let mut pieces = 0;
    for (k, seg) in plan.path.segments.iter().enumerate() {
        assert!(!seg.pieces.is_empty(), "{what}: segment {k} has no pieces");
        for p in &seg.pieces {
            pieces += 1;
            assert!(
                p.max_curvature() <= 1.0 / r + 1e-6,
                "{what}: segment {k} ({:?}) curvature {} over 1/{r}",
                seg.kind,
                p.max_curvature()
            );
            if !plan.options.reverse {
                assert_eq!(p.gear, Gear::Forward, "{what}: reverses in segment {k}");
            }
            if plan.options.curvature_rate.is_none() {
                assert_eq!(p.sharpness, 0.0, "{what}: a clothoid without a rate");
            } else if let Some(rate) = plan.options.curvature_rate {
                assert!(p.sharpness.abs() <= rate + 1e-9, "{what}: sharpness");
            }
            if let Some(e) = previous {
                let gap = e.distance(&p.start);
                let kink = e.heading_change(&p.start).abs();
                assert!(
                    gap < 1e-3,
                    "{what}: gap of {gap} m before segment {k} ({:?})",
                    seg.kind
                );
                // The heading is continuous everywhere, cusps included: at a cusp the machine
                // stops and drives the other way facing the same way.
                assert!(
                    kink < 1e-3,
                    "{what}: heading jumps {kink} rad before segment {k} ({:?})",
                    seg.kind
                );
            }
            previous = Some(p.end());
        }
    }
    assert!(pieces > 0, "{what}: no path");
    // The continuous-curvature machine: curvature continuous from piece to piece, outside cusps.
    if let Some(rate) = plan.options.curvature_rate {
        let all: Vec<_> = plan
            .path
            .segments
            .iter()
            .flat_map(|s| s.pieces.iter())
            .collect();
        for w in all.windows(2) {
            if w[0].gear != w[1].gear {
                continue;
            }
            let jump = (w[0].curvature_at(w[0].length) - w[1].curvature).abs();
            // Swaths and headland passes meet turns at zero curvature: every turn starts
            // and ends straight.
            assert!(jump < 1e-6, "{what}: curvature jumps {jump} (rate {rate})");
        }
    }
}

fn check_samples(plan: &Plan, what: &str) {
    let spacing = plan.options.sample_spacing;
    let s = sample(&plan.path, spacing, &plan.options.vehicle());
    assert!(s.len() > 1, "{what}: no samples");
    for i in 1..s.len() {
        let step = (s.x[i] - s.x[i - 1]).hypot(s.y[i] - s.y[i - 1]);
        let along = s.distance_m[i] - s.distance_m[i - 1];
        assert!(
            along <= spacing + 1e-9 && along >= 0.0,
            "{what}: samples {along} m apart"
        );
        assert!(
            step <= along + 1e-3,
            "{what}: a jump of {step} m over {along} m at sample {i} (segment {}, kind {}, reverse {} {})",
            s.segment[i],
            s.kind[i],
            s.reverse[i - 1],
            s.reverse[i]
        );
        assert!(s.time_s[i] >= s.time_s[i - 1], "{what}: time runs back");
        // The heading changes as the curvature says (a turn of at most 1/r per metre).
        let dh = ((s.heading_deg[i] - s.heading_deg[i - 1] + 540.0).rem_euclid(360.0) - 180.0)
            .to_radians()
            .abs();
        assert!(
            dh <= along / plan.options.turn_radius + 1e-3,
            "{what}: heading jumps {dh} rad over {along} m at sample {i}"
        );
        assert!(s.curvature[i].abs() <= 1.0 / plan.options.turn_radius + 1e-6);
        if s.reverse[i] == 1 {
            assert!(plan.options.reverse, "{what}: reverses");
        }
    }
    let total: f64 = plan.path.segments.iter().map(|s| s.length()).sum();
    let last = s.distance_m[s.len() - 1];
    assert!((last - total).abs() < 1e-6, "{what}: {last} of {total} m");
}

#[test]
fn paths_are_drivable_on_every_corpus_field() {
    let mut rows = Vec::new();
    for field in valid_fields() {
        for (machine, options) in machines(&field.options) {
            let what = format!("{} ({machine})", field.name);
            let p = plan(&field.text(), &options, &what);
            check_path(&p, &what);
            check_samples(&p, &what);
            let s = &p.summary;
            rows.push(format!(
                "| {} | {machine} | {} | {:.0} | {:.0} | {:.0} | {:.3} | {} | {:?} |",
                field.name,
                s.turn_count,
                s.turning_distance_m,
                s.total_distance_m,
                s.on_the_spot_distance_m,
                s.total_distance_m / s.on_the_spot_distance_m,
                s.turns_outside_field,
                s.turn_forms
            ));
        }
    }
    println!("| field | machine | turns | turning m | path m | on the spot m | ratio | outside | forms |");
    println!("|---|---|---|---|---|---|---|---|---|");
    for r in rows {
        println!("{r}");
    }
}

#[test]
fn turns_stay_in_the_field_or_are_reported_with_their_cause() {
    for field in valid_fields() {
        for (machine, options) in machines(&field.options) {
            let what = format!("{} ({machine})", field.name);
            let p = plan(&field.text(), &options, &what);
            let outside: Vec<_> = p
                .path
                .segments
                .iter()
                .filter(|s| s.kind == SegmentKind::Turn)
                .filter(|s| s.turn.as_ref().is_some_and(|t| !t.inside))
                .collect();
            assert_eq!(outside.len(), p.summary.turns_outside_field, "{what}");
            let warned = p
                .warnings
                .iter()
                .find(|w| w.code == WarningCode::TurnLeavesField);
            if outside.is_empty() {
                assert!(warned.is_none(), "{what}: warned of no turn");
            } else {
                let w = warned.unwrap_or_else(|| panic!("{what}: turns leave unreported"));
                assert!(
                    w.message.contains(&outside.len().to_string()),
                    "{what}: {}",
                    w.message
                );
                assert!(w.message.contains("beyond the swath ends"), "{what}");
            }
            // Connections are joined to the swath ends by turns that stay in the field where one
            // does: for a machine that may reverse, one always does on the corpus.
            if machine == "reversing" {
                let obstacles: Vec<&geo::Polygon> =
                    p.field.obstacles.iter().map(|o| &o.polygon).collect();
                let area = Area::new(&p.field.boundary, &obstacles);
                for c in p
                    .path
                    .segments
                    .iter()
                    .filter(|s| s.kind == SegmentKind::Connection)
                {
                    assert!(
                        area.contains(&c.pieces),
                        "{what}: a connection of {:.0} m leaves the field",
                        c.length()
                    );
                }
            }
            // Where the headland has room for a turn (two passes or more, at least one turning
            // radius deep) and the machine may reverse, every turn stays in.
            let depth = options.headland_pass_count() as f64 * options.width;
            if machine == "reversing"
                && options.headland_pass_count() >= 2
                && depth >= options.turn_radius
            {
                assert_eq!(
                    outside.len(),
                    0,
                    "{what}: {} turns leave the field ({:?})",
                    outside.len(),
                    warned.map(|w| &w.message)
                );
            }
        }
    }
}

/// How far (metres) the line runs outside the field's boundary or into one of its obstacles at
/// its worst, by geo's point-in-polygon and distances on the line's points.
fn depth_outside(plan: &Plan, line: &geo::LineString) -> f64 {
    use geo::{Contains, Distance, Euclidean};
    let boundary = &plan.field.boundary;
    line.points()
        .map(|q| {
            let out = if boundary.contains(&q) {
                0.0
            } else {
                Euclidean.distance(&q, boundary.exterior())
            };
            plan.field
                .obstacles
                .iter()
                .filter(|o| o.polygon.contains(&q))
                .map(|o| Euclidean.distance(&q, o.polygon.exterior()))
                .fold(out, f64::max)
        })
        .fold(0.0, f64::max)
}

/// Whether the line leaves the field's boundary or touches one of its obstacles, by geo's
/// predicates.
fn touches_outside(plan: &Plan, line: &geo::LineString) -> bool {
    use geo::{Contains, Intersects};
    !plan.field.boundary.contains(line)
        || plan
            .field
            .obstacles
            .iter()
            .any(|o| o.polygon.intersects(line))
}

/// Every connection between worked stretches that runs more than 5 cm out of the field or into
/// an obstacle is flagged (`inside: false` in the output), counted in the summary and warned of
/// with its cause; the flagged ones do leave the field.
fn check_connections_leaving(p: &Plan, what: &str) {
    // Those from the entrance and to the exit run from and to where the user put them.
    let segments = &p.path.segments;
    let between = segments.len().saturating_sub(1);
    let connections: Vec<_> = segments
        .iter()
        .enumerate()
        .filter(|&(k, s)| s.kind == SegmentKind::Connection && k > 0 && k < between)
        .map(|(_, s)| s)
        .collect();
    for end in [segments.first(), segments.last()].into_iter().flatten() {
        assert!(
            !end.leaves_field,
            "{what}: the entrance's or exit's connection is flagged"
        );
    }
    for c in &connections {
        let depth = depth_outside(p, &c.line);
        if depth > 0.05 {
            assert!(
                c.leaves_field,
                "{what}: a connection {depth:.2} m out is not flagged"
            );
        }
        if c.leaves_field {
            assert!(
                touches_outside(p, &c.line),
                "{what}: a connection inside is flagged"
            );
        }
    }
    let flagged = connections.iter().filter(|c| c.leaves_field).count();
    assert_eq!(flagged, p.summary.connections_outside_field, "{what}");
    check_warned(
        p,
        WarningCode::ConnectionLeavesField,
        flagged,
        "headland",
        what,
    );
}

/// The plan warns (`code`) exactly where `flagged` connections are flagged, with their count
/// and `cause` in the message.
fn check_warned(p: &Plan, code: WarningCode, flagged: usize, cause: &str, what: &str) {
    match p.warnings.iter().find(|w| w.code == code) {
        None => assert_eq!(flagged, 0, "{what}: {flagged} flagged, no warning"),
        Some(w) => {
            assert!(flagged > 0, "{what}: warned of no connection");
            let m = &w.message;
            assert!(m.contains(&flagged.to_string()), "{what}: {m}");
            assert!(m.contains(cause), "{what}: {m}");
        }
    }
}

#[test]
fn connections_that_leave_the_field_are_flagged_and_warned_of() {
    for field in valid_fields() {
        for (machine, options) in machines(&field.options) {
            let what = format!("{} ({machine})", field.name);
            check_connections_leaving(&plan(&field.text(), &options, &what), &what);
        }
    }
    // A 6 m drill with two passes turning at 8 m (forward only): the l- and h-shaped fields have
    // corners where its joins onto the passes cannot stay in.
    let drill = drill();
    let mut flagged = 0;
    for field in valid_fields()
        .into_iter()
        .filter(|f| ["l-shape", "h-shape"].contains(&f.name.as_str()))
    {
        let p = plan(&field.text(), &drill, &field.name);
        check_connections_leaving(&p, &field.name);
        flagged += p.summary.connections_outside_field;
    }
    assert!(flagged > 0, "no connection of the drill leaves the field");
}

/// Every connection between worked stretches, and every turn between swaths (in the field or
/// out of it), that crosses crop of a swath the path works after it is flagged (`crosses_crop`) and
/// warned of with its cause; a flagged one does cross some. The crop: [`later_crop`]. Returns
/// how many connections and turns are flagged.
fn check_connections_crossing(p: &Plan, what: &str) -> (usize, usize) {
    use geo::Intersects;
    let segments = &p.path.segments;
    let between = segments.len().saturating_sub(1);
    let (mut flagged, mut turns) = (0, 0);
    for (k, c) in segments.iter().enumerate() {
        let next_swath = segments[k + 1..]
            .iter()
            .find(|s| s.step.is_some())
            .is_some_and(|s| s.kind == SegmentKind::Swath);
        let turn_between = c.kind == SegmentKind::Turn && c.step.is_none() && next_swath;
        let connection = c.kind == SegmentKind::Connection && k > 0 && k < between;
        if !connection && !turn_between {
            assert!(!c.crosses_crop, "{what}: segment {k} is flagged");
            continue;
        }
        let crossing = later_crop(p, k + 1).iter().any(|l| l.intersects(&c.line));
        assert_eq!(
            c.crosses_crop, crossing,
            "{what}: {:?} {k} crosses a swath worked later: {crossing}",
            c.kind
        );
        flagged += usize::from(connection && c.crosses_crop);
        turns += usize::from(turn_between && c.crosses_crop);
    }
    check_warned(
        p,
        WarningCode::ConnectionCrossesCrop,
        flagged,
        "turning radius",
        what,
    );
    check_warned(p, WarningCode::TurnCrossesCrop, turns, "headland", what);
    (flagged, turns)
}

/// The swaths the path works from its segment `from` on.
fn later_swaths(p: &Plan, from: usize) -> impl Iterator<Item = &furrow::swath::Swath> {
    p.path.segments[from..]
        .iter()
        .filter(|s| s.kind == SegmentKind::Swath)
        .filter_map(|s| match s.step.and_then(|k| p.route.steps.get(k)) {
            Some(&furrow::route::RouteStep::Swath { swath, .. }) => p.swaths.swaths.get(swath),
            _ => None,
        })
}

/// The crop of the swaths the path works from its segment `from` on, by geo's lines: each
/// swath's centre line and (on strips over 2 m wide) the outline of its strip a metre in from
/// its sides, all a metre in from its ends.
fn later_crop(p: &Plan, from: usize) -> Vec<geo::Line> {
    use geo::Line;
    let side = p.options.width / 2.0 - 1.0;
    later_swaths(p, from)
        .filter(|w| w.length() > 0.0)
        .flat_map(|w| {
            let d = (w.centre.end - w.centre.start) / w.length();
            let cut = d * 1f64.min(w.length() / 4.0);
            let (a, b) = (w.centre.start + cut, w.centre.end - cut);
            let n = geo::coord! { x: -d.y, y: d.x } * side;
            let mut lines = vec![Line::new(a, b)];
            if side > 0.0 {
                lines.extend([
                    Line::new(a + n, b + n),
                    Line::new(a - n, b - n),
                    Line::new(a + n, a - n),
                    Line::new(b + n, b - n),
                ]);
            }
            lines
        })
        .collect()
}

#[test]
fn connections_and_turns_over_crop_worked_later_are_flagged_and_warned_of() {
    let drill = drill();
    let (mut flagged, mut turns) = (0, 0);
    for field in valid_fields() {
        for (machine, options) in machines(&field.options) {
            let what = format!("{} ({machine})", field.name);
            check_connections_crossing(&plan(&field.text(), &options, &what), &what);
        }
        let what = format!("{} (drill)", field.name);
        let (c, t) = check_connections_crossing(&plan(&field.text(), &drill, &what), &what);
        flagged += c;
        turns += t;
    }
    assert!(flagged > 0, "no connection of the drill crosses crop");
    assert!(turns > 0, "no turn of the drill crosses crop");
}

/// The longest run of `line` (points every half metre) over the crop of the swaths the path
/// works from its segment `from` on: inside a swath's strip less a metre at its sides and ends.
fn longest_over_crop(p: &Plan, from: usize, line: &geo::LineString) -> f64 {
    over_crop(p, from, line).0
}

/// The longest run of `line` over the crop worked from segment `from` on, as
/// [`longest_over_crop`], and all its runs together (a line across swaths crosses each strip's
/// crop in a short run).
fn over_crop(p: &Plan, from: usize, line: &geo::LineString) -> (f64, f64) {
    use geo::{Densify, Euclidean};
    let side = p.options.width / 2.0 - 1.0;
    let strips: Vec<_> = later_swaths(p, from)
        .filter(|w| w.length() > 2.0)
        .map(|w| {
            (
                w.centre.start,
                (w.centre.end - w.centre.start) / w.length(),
                w.length(),
            )
        })
        .collect();
    let over = |q: geo::Coord| {
        strips.iter().any(|&(a, d, length)| {
            let along = (q.x - a.x) * d.x + (q.y - a.y) * d.y;
            let across = (-(q.x - a.x) * d.y + (q.y - a.y) * d.x).abs();
            along > 1.0 && along < length - 1.0 && across < side
        })
    };
    let (mut longest, mut total, mut run) = (0.0_f64, 0.0, 0.0);
    let mut last: Option<geo::Coord> = None;
    for q in Euclidean.densify(line, 0.5).0 {
        let step = last.map_or(0.0, |l| ((q.x - l.x).powi(2) + (q.y - l.y).powi(2)).sqrt());
        run = if over(q) { run + step } else { 0.0 };
        total += if run > 0.0 { step } else { 0.0 };
        longest = longest.max(run);
        last = Some(q);
    }
    (longest, total)
}

/// A field with an edge at 27 degrees to swaths running east (metric coordinates).
const TRAPEZOID: &str =
    r#"{"type":"Polygon","coordinates":[[[0,0],[400,0],[636,120],[0,120],[0,0]]]}"#;

/// Parcel `index` of the Danish register's sample in `tests/fields/real/`.
fn danish_parcel(index: usize) -> String {
    common::corpus::real_parcels()
        .into_iter()
        .find(|(file, i, _)| file == "dk_marker_2026_sample" && *i == index)
        .map(|(_, _, text)| text)
        .unwrap_or_else(|| panic!("parcel {index}"))
}

/// A field whose swaths end along an edge at 27 degrees to them at one end and square at the
/// other, worked by a 6 m drill that reverses, with two passes and turns of 8 m: between ends
/// staggered along the oblique edge, U-turns between swaths 18 m apart (the snake that skips
/// two) reach 44 m beyond the nearer end, where the headland is 26 m deep along the swaths, and
/// drove over the ends of the swaths between (5 turns over crop). The block is worked swath
/// after swath with three-point turns made level with the end further out, which keep to the
/// headland.
#[test]
fn a_reversing_machine_turns_along_an_oblique_edge_off_the_crop() {
    let text = TRAPEZOID;
    let options = PlanOptions {
        reverse: true,
        coordinates: furrow::field::Coordinates::Metric,
        ..drill()
    };
    let p = plan(text, &options, "trapezoid");
    let segments = &p.path.segments;
    let mut turns = 0;
    for (k, s) in segments.iter().enumerate() {
        if s.kind == SegmentKind::Turn && s.step.is_none() {
            turns += 1;
            let over = longest_over_crop(&p, k + 1, &s.line);
            assert!(over < 1.0, "turn {k} over {over:.1} m of crop");
        }
    }
    assert!(turns >= 15, "{turns} turns");
    assert!(!p
        .warnings
        .iter()
        .any(|w| w.code == WarningCode::TurnCrossesCrop));
    check_connections_crossing(&p, "trapezoid");
}

/// The trapezoid's oblique edge for the drill forward only: a U-turn between ends staggered
/// along an edge at 27 degrees to the swaths needs 15 m of headland at a turning radius of 8
/// m, and two passes give 12. The cheapest forms that stayed in the field looped back over the
/// ends of swaths worked later. A turn now crosses that crop only where no form the machine
/// can drive between its ends keeps off it (each form measured here against the strips), out
/// over the edge where it must; each that leaves is counted and warned of.
#[test]
fn a_forward_machine_turns_along_an_oblique_edge_off_the_crop() {
    let text = TRAPEZOID;
    let options = PlanOptions {
        coordinates: furrow::field::Coordinates::Metric,
        bearing_deg: Some(90.0),
        ..drill()
    };
    let p = plan(text, &options, "trapezoid");
    let vehicle = options.vehicle();
    let (mut turns, mut over_crop) = (0, 0);
    for (k, s) in p.path.segments.iter().enumerate() {
        if s.kind != SegmentKind::Turn || s.step.is_some() {
            continue;
        }
        turns += 1;
        let over = longest_over_crop(&p, k + 1, &s.line);
        if over < 1.0 {
            continue;
        }
        over_crop += 1;
        let (Some(from), Some(to)) = (s.start(), s.end()) else {
            panic!("turn {k} without its ends");
        };
        for form in vehicle.candidates(from, to) {
            let line: geo::LineString = form
                .segments
                .iter()
                .flat_map(furrow::path::turn::chord_points)
                .collect();
            let off = longest_over_crop(&p, k + 1, &line);
            assert!(
                off >= 0.5,
                "turn {k} over {over:.1} m of crop, where {} keeps off it",
                form.form.word()
            );
        }
    }
    assert!(turns >= 15, "{turns} turns");
    // Two of them, where no form keeps off the crop.
    assert!(over_crop <= 2, "{over_crop} turns over crop");
    let outside = p
        .path
        .segments
        .iter()
        .filter(|s| s.turn.as_ref().is_some_and(|t| !t.inside))
        .count();
    assert!(outside > 0, "no turn leaves the field");
    assert_eq!(outside, p.summary.turns_outside_field);
    assert!(p
        .warnings
        .iter()
        .any(|w| w.code == WarningCode::TurnLeavesField));
    check_connections_crossing(&p, "trapezoid");
}

/// A register parcel where the forward drill's connection into its first block joined the
/// block's first swath by a loop back over the crop of the swaths beside it (43 m by
/// `scripts/coverage-table.py`, 8.4 m a metre in from the strips' sides): no join in the
/// headland of two passes keeps off that crop, and one out over the boundary does. Of its
/// connections four ran over crop worked later; two do now, each flagged and warned of (the
/// strips a metre in from their sides and ends, measured here), and those that leave the field
/// are warned of.
#[test]
fn a_forward_machine_joins_a_block_off_the_crop() {
    let text = danish_parcel(25);
    let what = "dk_marker_2026_sample 25";
    let p = plan(&text, &drill(), what);
    let mut over_crop = Vec::new();
    for (k, s) in p.path.segments.iter().enumerate() {
        if s.kind == SegmentKind::Connection {
            let over = longest_over_crop(&p, k + 1, &s.line);
            if over >= 1.0 {
                assert!(
                    s.crosses_crop,
                    "{what}: connection {k} over {over:.1} m unflagged"
                );
                over_crop.push((k, over));
            }
        }
    }
    assert!(over_crop.len() <= 2, "{what}: {over_crop:?}");
    // The first connection after the first worked stretch: the one into the first block.
    let segments = &p.path.segments;
    let first_worked = segments.iter().position(|s| s.step.is_some());
    let into_block = (first_worked.unwrap_or(0)..segments.len())
        .find(|&k| segments[k].kind == SegmentKind::Connection);
    assert!(
        into_block.is_some() && over_crop.iter().all(|&(k, _)| Some(k) != into_block),
        "{what}: {over_crop:?}, into the first block {into_block:?}"
    );
    check_connections_crossing(&p, what);
    check_connections_leaving(&p, what);
}

/// A register parcel whose long edge runs nearly along its swaths, with neighbouring lines in
/// other blocks: a turn between two swaths of a block whose ends lie hundreds of metres apart
/// drove back past the ends of the lines between, over some 340 to 400 m of their crop (the
/// forward drill's 428 m "u-turn"). It is driven along the headland instead, crossing at most
/// the crop its joins onto and off the headland cannot avoid.
#[test]
fn turns_between_far_staggered_ends_keep_to_the_headland() {
    let text = danish_parcel(53);
    for (machine, options) in machines(&drill()).into_iter().take(2) {
        let what = format!("dk_marker_2026_sample 53 ({machine})");
        let p = plan(&text, &options, &what);
        let segments = &p.path.segments;
        let mut worst = (0.0, 0);
        for (k, s) in segments.iter().enumerate() {
            if s.kind == SegmentKind::Turn && s.step.is_none() {
                let over = longest_over_crop(&p, k + 1, &s.line);
                if over > worst.0 {
                    worst = (over, k);
                }
            }
        }
        assert!(
            worst.0 < 60.0,
            "{what}: turn {} over {:.0} m of crop",
            worst.1,
            worst.0
        );
    }
}

/// `dk_marker_2026_sample_030` for a 3 m mower forward only (two passes, turns of 5 m): a
/// block's swaths end at a step in the field's side, 100 m back from where the swaths beside
/// it end. The turn from one to the other drove diagonally back across the block, over 24 m of
/// the crop of swaths worked later (their strips less a metre at the sides), because the way
/// along the headland left the field where it joins the headland. A forward machine leaves the
/// field rather than cross crop (as its turns between neighbouring swaths do): the turn is
/// driven along the headland, and where it leaves the field it says so.
#[test]
fn a_forward_machine_drives_between_far_staggered_ends_along_the_headland() {
    check_mower_turns_along_the_headland(30);
}

/// Plans Danish parcel `index` for the 3 m mower forward only (two passes, turns of 5 m): no
/// turn over 10 m of crop worked later (the strips less a metre at their sides), at least one
/// driven along the headland, and each of those that leaves the field says so.
fn check_mower_turns_along_the_headland(index: usize) {
    let text = danish_parcel(index);
    let what = format!("dk_marker_2026_sample {index} (mower)");
    let options = PlanOptions {
        width: 3.0,
        turn_radius: 5.0,
        ..drill()
    };
    let p = plan(&text, &options, &what);
    let mut along = 0;
    for (k, s) in p.path.segments.iter().enumerate() {
        let Some(turn) = s.turn.as_ref().filter(|_| s.kind == SegmentKind::Turn) else {
            continue;
        };
        let (_, over) = over_crop(&p, k + 1, &s.line);
        assert!(over < 10.0, "{what}: turn {k} over {over:.1} m of crop");
        if turn.form == furrow::path::turn::TurnForm::Headland {
            along += 1;
            let leaves = depth_outside(&p, &s.line) > 0.01;
            assert!(
                !leaves || !turn.inside,
                "{what}: turn {k} leaves unreported"
            );
        }
    }
    assert!(along >= 1, "{what}: no turn along the headland");
}

/// `dk_marker_2026_sample_076` (mower): a swath ends at the corner of a notch, 120 m short of
/// the next, which runs on beside the notch. Driven straight, the turn between them crossed
/// the block's crop worked later diagonally (15.7 m of the strips less a metre at their sides,
/// as measured here); along the headland only its joins cross some, and one leaves the field.
/// A forward machine whose turn crosses crop either way takes the way over less of it.
#[test]
fn a_forward_machine_turning_over_crop_either_way_takes_the_way_over_less() {
    check_mower_turns_along_the_headland(76);
}

/// Register parcels where the forward drill (two passes, turns of 8 m) turned between swath
/// ends near each other over crop worked later: a loop swinging over the next swaths' ends at a
/// step in the field's side, a U-turn cutting a corner. No form of turn between the ends keeps
/// off the crop there; driven along the headland instead, each turn crosses less of it.
#[test]
fn a_forward_machine_turning_over_crop_near_its_ends_drives_along_the_headland() {
    for index in [7, 13, 72, 84] {
        let text = danish_parcel(index);
        let what = format!("dk_marker_2026_sample {index} (drill)");
        let p = plan(&text, &drill(), &what);
        for (k, s) in p.path.segments.iter().enumerate() {
            if s.kind == SegmentKind::Turn && s.step.is_none() {
                let (_, over) = over_crop(&p, k + 1, &s.line);
                assert!(over < 3.0, "{what}: turn {k} over {over:.1} m of crop");
            }
        }
    }
}

/// The H-shaped corpus field, cut by split and merge into its two long blocks and the cross
/// block between them, whose swaths end against the long blocks' sides: the cross block turns
/// on their ground. Worked before them it turned over their crop (a turn warned of as crossing
/// it); the block order now works the long blocks first, and no turn between swaths crosses
/// crop worked later.
#[test]
fn a_block_that_turns_on_its_neighbour_is_worked_after_it() {
    let field = valid_fields()
        .into_iter()
        .find(|f| f.name.starts_with("h-shape"))
        .expect("h-shape in the corpus");
    let p = plan(&field.text(), &field.options, &field.name);
    assert!(
        p.blocks.blocks.len() >= 3,
        "{} blocks",
        p.blocks.blocks.len()
    );
    for (k, s) in p.path.segments.iter().enumerate() {
        if s.kind == SegmentKind::Turn && s.step.is_none() {
            let (_, over) = over_crop(&p, k + 1, &s.line);
            assert!(over < 1.0, "turn {k} over {over:.1} m of crop");
        }
    }
    assert!(!p
        .warnings
        .iter()
        .any(|w| w.code == WarningCode::TurnCrossesCrop));
}

#[test]
fn the_path_follows_the_route_and_turns_cost_what_they_are() {
    // The rectangle: the path's working distance is the route's (swaths and headland passes
    // as laid), every turn joins two swaths of one block, and the total against the same route
    // with turns on the spot is longer but by no more than the turns.
    let field = valid_fields()
        .into_iter()
        .find(|f| f.name == "rectangle")
        .expect("the corpus has a rectangle");
    let p = plan(&field.text(), &field.options, "rectangle");
    let s = &p.summary;
    assert!(s.turn_count > 10);
    assert_eq!(s.turn_forms.values().sum::<usize>(), s.turn_count);
    assert!(s.total_distance_m > s.on_the_spot_distance_m);
    assert!(
        s.total_distance_m - s.on_the_spot_distance_m
            <= s.turning_distance_m + s.connection_distance_m
    );
    let swaths: f64 = p.swaths.swaths.iter().map(|w| w.length()).sum();
    assert!((s.swath_distance_m - swaths).abs() < 1e-6);
    // Every turn is at least the straight line between its ends, and at least the turn model's
    // U-turn for its spacing (πr, or the loop below 2r).
    let v = p.options.vehicle();
    for seg in p
        .path
        .segments
        .iter()
        .filter(|s| s.kind == SegmentKind::Turn)
    {
        let (a, b) = (seg.start().unwrap(), seg.end().unwrap());
        assert!(seg.length() >= a.distance(&b) - 1e-9);
        assert!(seg.length() >= v.turn_radius * std::f64::consts::PI * 0.999);
    }
}

#[test]
fn samples_go_to_the_output_coordinates() {
    let field = valid_fields()
        .into_iter()
        .find(|f| f.name == "square-1ha")
        .expect("square");
    let p = plan(&field.text(), &field.options, "square");
    let s = p.samples();
    // Longitude and latitude near the corpus's home (24.05 E, 60.25 N).
    assert!(s.x.iter().all(|x| (24.0..24.1).contains(x)));
    assert!(s.y.iter().all(|y| (60.2..60.3).contains(y)));
    let local = sample(&p.path, p.options.sample_spacing, &Vehicle::default());
    assert_eq!(local.len(), s.len());
}
