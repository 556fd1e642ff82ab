//! The plan's coverage figures against an independent count: points spread evenly over the
//! field (less its obstacles), each counted as worked when it lies within half a width of a
//! stretch the plan's GeoJSON says is worked (swaths less their lifted stretches, headland
//! passes), square to it and between its ends, or swept by the implement (a bar square to the
//! heading) as it swings round one of its joints from the one heading to the other.

use furrow::{plan_geojson, Plan};
use geo::{Contains, Coord, Distance, Point, Polygon};

mod common;

use common::worked::{worked_stretches, Joint, Stretch};

/// Whether `p` lies within `half` of the stretch, square to it and between its ends.
fn in_strip(p: Coord, (a, b): Stretch, half: f64) -> bool {
    let d = b - a;
    let l2 = d.x * d.x + d.y * d.y;
    if l2 == 0.0 {
        return false;
    }
    let t = ((p.x - a.x) * d.x + (p.y - a.y) * d.y) / l2;
    let across = ((p.x - a.x) * d.y - (p.y - a.y) * d.x).abs() / l2.sqrt();
    (0.0..=1.0).contains(&t) && across <= half
}

/// Whether `p` lies within `half` of the joint and on the bar square to the heading at some
/// heading between the joint's two, turning the shorter way: swept as the implement swings
/// round it.
fn swung_over(p: Coord, joint: &Joint, half: f64) -> bool {
    let q = p - joint.at;
    if q.x.hypot(q.y) > half {
        return false;
    }
    let (u, v) = (joint.from, joint.to);
    let turn = (u.x * v.y - u.y * v.x).atan2(u.x * v.x + u.y * v.y);
    // The bar's direction at the first heading, and where q lies from it (either half of the
    // bar: modulo a half turn).
    let bar = (u.x).atan2(-u.y);
    let past = (q.y.atan2(q.x) - bar).rem_euclid(std::f64::consts::PI);
    if turn >= 0.0 {
        past <= turn
    } else {
        past == 0.0 || past >= std::f64::consts::PI + turn
    }
}

/// The share of the field worked, counted at points `step` metres apart (each point moved by a
/// fixed irrational fraction of the step, off any grid the planner uses).
fn independent_coverage(plan: &Plan, step: f64) -> f64 {
    let half = plan.options.width / 2.0;
    let (stretches, corners) = worked_stretches(plan);
    let boundary = &plan.field.boundary;
    let obstacles: Vec<&Polygon> = plan.field.obstacles.iter().map(|o| &o.polygon).collect();
    let rect = geo::BoundingRect::bounding_rect(boundary).expect("bounds");
    // Buckets of stretches by cell of a coarse grid, for the nearest-stretch search.
    let size = (4.0 * half).max(step);
    let key = |c: Coord| {
        (
            ((c.x - rect.min().x) / size).floor() as i64,
            ((c.y - rect.min().y) / size).floor() as i64,
        )
    };
    let mut buckets: std::collections::HashMap<(i64, i64), Vec<usize>> = Default::default();
    for (k, &(a, b)) in stretches.iter().enumerate() {
        let (lo, hi) = (
            Coord {
                x: a.x.min(b.x) - half,
                y: a.y.min(b.y) - half,
            },
            Coord {
                x: a.x.max(b.x) + half,
                y: a.y.max(b.y) + half,
            },
        );
        let ((i0, j0), (i1, j1)) = (key(lo), key(hi));
        for i in i0..=i1 {
            for j in j0..=j1 {
                buckets.entry((i, j)).or_default().push(k);
            }
        }
    }
    let mut corner_buckets: std::collections::HashMap<(i64, i64), Vec<Joint>> = Default::default();
    for &c in &corners {
        corner_buckets.entry(key(c.at)).or_default().push(c);
    }
    let (mut inside, mut worked) = (0usize, 0usize);
    for p in grid_points(rect, 0.0, step) {
        if boundary.contains(&Point(p)) && !obstacles.iter().any(|o| o.contains(&Point(p))) {
            inside += 1;
            let (i, j) = key(p);
            let near_stretch = buckets
                .get(&(i, j))
                .is_some_and(|ks| ks.iter().any(|&k| in_strip(p, stretches[k], half)));
            let near_corner = || {
                (i - 1..=i + 1).any(|i| {
                    (j - 1..=j + 1).any(|j| {
                        corner_buckets
                            .get(&(i, j))
                            .is_some_and(|cs| cs.iter().any(|c| swung_over(p, c, half)))
                    })
                })
            };
            if near_stretch || near_corner() {
                worked += 1;
            }
        }
    }
    worked as f64 / inside.max(1) as f64
}

/// Points `step` metres apart over `rect` grown by `margin`, moved off its corner by fixed
/// irrational fractions of the step (off any grid the planner uses).
fn grid_points(rect: geo::Rect, margin: f64, step: f64) -> impl Iterator<Item = Coord> {
    let (x0, y0) = (
        rect.min().x - margin + std::f64::consts::FRAC_1_PI * step,
        rect.min().y - margin + 0.577_215_664 * step,
    );
    let (x1, y1) = (rect.max().x + margin, rect.max().y + margin);
    let (nx, ny) = (
        ((x1 - x0) / step).ceil().max(0.0) as usize,
        ((y1 - y0) / step).ceil().max(0.0) as usize,
    );
    (0..ny).flat_map(move |j| {
        (0..nx).map(move |i| Coord {
            x: x0 + i as f64 * step,
            y: y0 + j as f64 * step,
        })
    })
}

/// Area (m²) worked outside the field or over an obstacle, counted at points `step` metres apart
/// around the field: points outside it within half a width of a worked stretch (its flat ends,
/// not the joints between stretches).
fn worked_outside(plan: &Plan, step: f64) -> f64 {
    let half = plan.options.width / 2.0;
    let (stretches, _) = worked_stretches(plan);
    let boundary = &plan.field.boundary;
    let obstacles: Vec<&Polygon> = plan.field.obstacles.iter().map(|o| &o.polygon).collect();
    let rect = geo::BoundingRect::bounding_rect(boundary).expect("bounds");
    let mut count = 0usize;
    for p in grid_points(rect, half, step) {
        let outside =
            !boundary.contains(&Point(p)) || obstacles.iter().any(|o| o.contains(&Point(p)));
        // A point on the boundary's line is in neither; a strip along it touches it.
        let off = boundary
            .exterior()
            .lines()
            .all(|l| geo::Euclidean.distance(&l, &Point(p)) > 0.05);
        if outside && off && stretches.iter().any(|&s| in_strip(p, s, half)) {
            count += 1;
        }
    }
    count as f64 * step * step
}

#[test]
fn the_coverage_figure_agrees_with_an_independent_count_on_the_corpus() {
    for field in common::corpus::valid_fields() {
        let plan = plan_geojson(&field.text(), &field.options)
            .unwrap_or_else(|e| panic!("{}: {e}", field.name));
        let figure = plan.summary.coverage.coverage_ratio;
        // About 40,000 points over the field's bounding box.
        let rect = geo::BoundingRect::bounding_rect(&plan.field.boundary).expect("bounds");
        let step = (rect.width() * rect.height() / 40_000.0).sqrt();
        let counted = independent_coverage(&plan, step);
        assert!(
            (figure - counted).abs() <= 0.005,
            "{}: the plan says {figure:.4} of the field is worked, the count {counted:.4}",
            field.name
        );
        assert!(
            plan.summary.coverage.reachable_ratio >= figure - 0.002,
            "{}",
            field.name
        );
    }
}

#[test]
fn a_wide_implement_s_figure_agrees_with_an_independent_count_on_register_parcels() {
    // A 24 m sprayer with one pass: on small parcels its curved passes end within a half width
    // of much of the crop, where a disc swept at each of their points would count it as worked.
    let options = furrow::PlanOptions {
        width: 24.0,
        headland_passes: 1.into(),
        turn_radius: 9.0,
        ..furrow::PlanOptions::default()
    };
    let mut checked = 0;
    for (file, i, text) in common::corpus::real_parcels().into_iter().step_by(2) {
        let Ok(plan) = plan_geojson(&text, &options) else {
            continue;
        };
        let rect = geo::BoundingRect::bounding_rect(&plan.field.boundary).expect("bounds");
        let step = (rect.width() * rect.height() / 40_000.0).sqrt();
        let counted = independent_coverage(&plan, step);
        let figure = plan.summary.coverage.coverage_ratio;
        assert!(
            (figure - counted).abs() <= 0.005,
            "{file} {i}: the plan says {figure:.4} of the field is worked, the count {counted:.4}"
        );
        checked += 1;
    }
    assert!(checked > 50, "{checked} parcels planned");
}

#[test]
fn every_part_left_standing_is_a_feature_and_lies_in_the_field() {
    let field = common::corpus::valid_field("narrow-curved-strip");
    let plan = plan_geojson(&field.text(), &field.options).unwrap();
    let c = &plan.summary.coverage;
    assert!(!c.uncovered.is_empty());
    let listed: f64 = c.uncovered.iter().map(|u| u.area_m2).sum();
    assert!(listed <= c.uncovered_area_m2 + 1e-6);
    let json: serde_json::Value = serde_json::from_str(&plan.to_geojson_string()).unwrap();
    let features = json["features"].as_array().unwrap();
    let uncovered = features
        .iter()
        .filter(|f| f["properties"]["kind"] == "uncovered")
        .count();
    assert_eq!(uncovered, c.uncovered.len());
    let grown = geo::Buffer::buffer(&plan.field.boundary, c.resolution_m);
    for part in &c.uncovered {
        assert!(
            grown.contains(&part.polygon),
            "a part left standing outside the field"
        );
        assert!(part.reachable_m2 <= part.area_m2);
    }
}

/// A curved strip 40 m wide (half a ring, radii 110 and 150 m), in local metres.
fn curved_strip() -> String {
    let n = 60;
    let arc = |r: f64, from: f64, to: f64| {
        (0..=n).map(move |i| {
            let t = from + (to - from) * i as f64 / n as f64;
            format!("[{:.6},{:.6}]", r * t.cos(), r * t.sin())
        })
    };
    let pi = std::f64::consts::PI;
    let mut ring: Vec<String> = arc(150.0, 0.0, pi).chain(arc(110.0, pi, 0.0)).collect();
    ring.push(ring[0].clone());
    format!(
        r#"{{"type":"Polygon","coordinates":[[{}]]}}"#,
        ring.join(",")
    )
}

#[test]
fn a_strip_too_narrow_for_an_inner_field_is_worked_by_its_pass_round_it() {
    // A 24 m sprayer with one pass: the pass 12 m in leaves no inner field (24 m in). Worked
    // across by straight swaths without headland, the curved strip was 76 % covered and the
    // boom reached past its sides; its pass round the strip works both sides of it.
    let options = furrow::PlanOptions {
        width: 24.0,
        headland_passes: 1.into(),
        turn_radius: 5.0,
        coordinates: furrow::field::Coordinates::Metric,
        ..furrow::PlanOptions::default()
    };
    let plan = plan_geojson(&curved_strip(), &options).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(plan.summary.headland_pass_count, 1);
    assert_eq!(plan.summary.swath_count, plan.summary.fill_swath_count);
    let counted = independent_coverage(&plan, 0.5);
    assert!(counted > 0.96, "{counted:.4} of the strip worked");
    let c = &plan.summary.coverage;
    assert!(
        (c.coverage_ratio - counted).abs() <= 0.005,
        "{c:?} against {counted:.4}"
    );
    assert!(
        c.outside_area_m2 < 1.0,
        "{} m² worked outside",
        c.outside_area_m2
    );
}

#[test]
fn passes_to_the_middle_work_a_bent_strip_along_its_length() {
    // The 40 m strip at a 6 m drill's width: with two headland passes its middle is worked
    // across by straight swaths short of its bends; with `headlandPasses: "all"` three passes
    // go round it inside each other and a fourth round what they leave down its middle, each
    // along the whole strip: more of it worked, in less time or without turning out of it.
    for reverse in [false, true] {
        let options = |headland_passes| furrow::PlanOptions {
            width: 6.0,
            headland_passes,
            turn_radius: 8.0,
            reverse,
            coordinates: furrow::field::Coordinates::Metric,
            ..furrow::PlanOptions::default()
        };
        // Split and merge's swaths asked for (`auto` would work this strip by passes to the
        // middle itself).
        let swaths = furrow::PlanOptions {
            decomposition: furrow::decompose::Decomposition::SplitMerge,
            ..options(2.into())
        };
        let two = plan_geojson(&curved_strip(), &swaths).unwrap_or_else(|e| panic!("{e}"));
        let all = plan_geojson(
            &curved_strip(),
            &options(furrow::headland::passes::HeadlandPasses::All),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(all.summary.headland_passes, 4, "reversing {reverse}");
        assert!(two.summary.swath_count > two.summary.fill_swath_count);
        assert_eq!(all.summary.swath_count, all.summary.fill_swath_count);
        let (worked_two, worked_all) = (
            independent_coverage(&two, 0.5),
            independent_coverage(&all, 0.5),
        );
        let least = if reverse { 0.99 } else { 0.975 };
        assert!(
            worked_all >= least && worked_all > worked_two + 0.005,
            "reversing {reverse}: {worked_all:.4} worked along, {worked_two:.4} across"
        );
        assert!(
            (all.summary.coverage.coverage_ratio - worked_all).abs() <= 0.005,
            "reversing {reverse}: the planner's {:.4} against {worked_all:.4}",
            all.summary.coverage.coverage_ratio
        );
        // In less time, and in the field: forward only, the swaths across take 2,117 s (the
        // passes along 2,132 s) by turning out over the strip's sides on seven turns where
        // the forms in the field would loop back over crop still to be worked (2,184 s with
        // one turn out, when they did).
        assert_eq!(all.summary.turns_outside_field, 0, "reversing {reverse}");
        assert!(
            all.summary.estimated_time_s < two.summary.estimated_time_s
                || (!reverse && two.summary.turns_outside_field > 1),
            "reversing {reverse}: {} s along, {} s across with {} turns out of the field",
            all.summary.estimated_time_s,
            two.summary.estimated_time_s,
            two.summary.turns_outside_field
        );
        assert!(worked_outside(&all, 0.5) < 1.0);
    }
}

#[test]
fn auto_works_a_narrow_bent_field_by_passes_along_its_length() {
    // The corpus's 900 m curved strip, 45 m wide, at its suggested settings (6 m, one pass, r
    // 8): straight swaths are cut short at its bends and leave wedges of crop between the
    // pieces; passes following its outline to the middle work it along its length.
    let strip = common::corpus::valid_field("narrow-curved-strip");
    let plan = plan_geojson(&strip.text(), &strip.options).unwrap_or_else(|e| panic!("{e}"));
    let step = 0.5;
    let worked = independent_coverage(&plan, step);
    let reachable = plan.summary.coverage.reachable_ratio;
    assert!(
        worked >= 0.99 * reachable,
        "{worked:.4} worked of {reachable:.4} reachable"
    );
    assert_eq!(plan.summary.swath_count, plan.summary.fill_swath_count);
    assert_eq!(
        plan.summary.decomposition.reason,
        furrow::plan::contour::REASON
    );
    // Asked for swaths, the same field is worked across in pieces, covering less, slower.
    let swaths = furrow::PlanOptions {
        decomposition: furrow::decompose::Decomposition::SplitMerge,
        ..strip.options.clone()
    };
    let across = plan_geojson(&strip.text(), &swaths).unwrap_or_else(|e| panic!("{e}"));
    assert!(independent_coverage(&across, step) < worked - 0.01);
    assert!(across.summary.estimated_time_s > plan.summary.estimated_time_s);
    assert!(worked_outside(&plan, step) < 1.0);
}

/// A 120 x 80 m block with a bent arm 14 m wide off its north-west corner, in local metres:
/// north 106 m, then east 86 m to a dead end.
fn block_with_a_bent_arm() -> String {
    let ring = [
        (0, 0),
        (120, 0),
        (120, 80),
        (14, 80),
        (14, 186),
        (100, 186),
        (100, 200),
        (0, 200),
        (0, 0),
    ];
    let points: Vec<String> = ring.iter().map(|(x, y)| format!("[{x},{y}]")).collect();
    format!(
        r#"{{"type":"Polygon","coordinates":[[{}]]}}"#,
        points.join(",")
    )
}

#[test]
fn an_arm_too_narrow_to_turn_in_is_worked_by_fill_passes_up_and_down_it() {
    // A drill 6 m wide turning at 8 m: its headland passes, opened by the turning disc, do not
    // enter the arm (8 m between their centre lines' limits), and no straight set of pieces
    // works the bend. Passes along the arm's outline go up one side and back down the other.
    for reverse in [false, true] {
        let options = furrow::PlanOptions {
            width: 6.0,
            headland_passes: 2.into(),
            turn_radius: 8.0,
            reverse,
            coordinates: furrow::field::Coordinates::Metric,
            ..furrow::PlanOptions::default()
        };
        let plan =
            plan_geojson(&block_with_a_bent_arm(), &options).unwrap_or_else(|e| panic!("{e}"));
        let fill_passes = plan
            .headlands
            .passes
            .iter()
            .filter(|p| p.around == furrow::headland::PassAround::Fill)
            .count();
        if reverse {
            // A machine that reverses drives the field's exact passes up the arm and back.
            let up_the_arm = |p: &&furrow::headland::HeadlandPass| {
                p.around == furrow::headland::PassAround::Field
                    && p.line.0.iter().any(|c| c.x < 14.0 && c.y > 150.0)
            };
            assert!(
                plan.headlands.passes.iter().filter(up_the_arm).count() >= 1,
                "no pass up the arm"
            );
        } else {
            assert!(fill_passes >= 1, "no fill pass");
        }
        // Without them the arm (3,000 m², 22 % of the field) stood: 76 % was worked. Left
        // now: the strip between the two passes up the arm (14 m less two 6 m strips),
        // narrower than half a width, and, forward, the corners the passes round (a machine
        // that reverses works into them: 92.7 % worked when it rounded them too).
        let counted = independent_coverage(&plan, 0.5);
        let c = &plan.summary.coverage;
        assert!(
            counted > if reverse { 0.96 } else { 0.92 },
            "reverse {reverse}: {counted:.4} of the field worked, {:.4} reachable, {:.4} by the plan's figure",
            c.reachable_ratio,
            c.coverage_ratio
        );
        assert!(
            (c.coverage_ratio - counted).abs() <= 0.005,
            "{c:?} against {counted:.4}"
        );
        // The manoeuvres at the arm's dead end and at the passes' cusps are turns with the
        // implement lifted: nothing is worked outside the field (179 m² were, forward, when they
        // were driven as part of their passes).
        let outside = worked_outside(&plan, 0.25);
        assert!(
            outside <= 1.0,
            "reverse {reverse}: {outside:.1} m² worked outside"
        );
    }
}

/// The reproducer of a headland pass driven through a pond: rounded at a 50 m turning radius,
/// the pass round the field cut across the pond with the implement down (56 m of it). The
/// rounding is driven lifted now: nothing is worked in the pond or outside the field.
#[test]
fn no_pass_works_through_an_obstacle_at_a_large_turning_radius() {
    let path = common::corpus::fields_dir().join("reproducers/pass_through_obstacle_r50.geojson");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{e}"));
    let options = furrow::PlanOptions {
        headland_passes: 2.into(),
        turn_radius: 50.0,
        ..furrow::PlanOptions::default()
    };
    let plan = plan_geojson(&text, &options).unwrap_or_else(|e| panic!("{e}"));
    let outside = worked_outside(&plan, 0.25);
    assert!(
        outside <= 1.0,
        "{outside:.1} m² worked outside or in the pond"
    );
    let c = &plan.summary.coverage;
    let counted = independent_coverage(&plan, 0.5);
    assert!(
        (c.coverage_ratio - counted).abs() <= 0.005,
        "{c:?} against {counted:.4}"
    );
}

/// A strip whose first pass has no room for the turning disc: 40 m wide at 24 m with turns of
/// 9 m (the pass's room, 12 m in, is 16 m wide). The pass is laid exact, its corners driven
/// with manoeuvres, and works both sides of the strip; without it the field was planned with no
/// headland and its swaths, overhanging the ends, were lifted there (85 % worked).
#[test]
fn a_pass_the_turning_disc_does_not_fit_works_the_strip_round() {
    let text = r#"{"type":"Polygon","coordinates":[[[0,0],[150,0],[150,40],[0,40],[0,0]]]}"#;
    let options = furrow::PlanOptions {
        width: 24.0,
        headland_passes: 1.into(),
        turn_radius: 9.0,
        coordinates: furrow::field::Coordinates::Metric,
        ..furrow::PlanOptions::default()
    };
    let plan = plan_geojson(text, &options).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        plan.headlands
            .passes
            .iter()
            .any(|p| p.around == furrow::headland::PassAround::Field),
        "no pass round the field"
    );
    let counted = independent_coverage(&plan, 0.5);
    assert!(counted > 0.92, "{counted:.4} of the strip worked");
    let outside = worked_outside(&plan, 0.25);
    assert!(outside <= 1.0, "{outside:.1} m² worked outside");
}

/// A field with two acute corners and two obtuse ones. A drill that reverses works into each
/// corner of its exact passes (driving on until the bar meets the next side, then backing
/// round onto it) rather than rounding them at its turning radius: 97.98 % of the field was
/// worked when it rounded them (its fill patching what the rounding left), 98.9 % now, and
/// nothing outside. Asked to, it rounds them; asked to work into them, a machine that does not
/// reverse does so too, with loops out of the field, warned of.
#[test]
fn a_machine_that_reverses_works_into_the_corners_of_its_passes() {
    use furrow::headland::HeadlandCorners::{Auto, Manoeuvre, Round};
    let text = r#"{"type":"Polygon","coordinates":[[[0,0],[200,0],[140,90],[30,110],[0,0]]]}"#;
    for (reverse, corners, worked_into) in [
        (true, Auto, true),
        (true, Round, false),
        (false, Auto, false),
        (false, Manoeuvre, true),
    ] {
        let options = furrow::PlanOptions {
            width: 6.0,
            headland_passes: 2.into(),
            turn_radius: 8.0,
            reverse,
            headland_corners: corners,
            coordinates: furrow::field::Coordinates::Metric,
            ..furrow::PlanOptions::default()
        };
        let plan = plan_geojson(text, &options).unwrap_or_else(|e| panic!("{e}"));
        let counted = independent_coverage(&plan, 0.25);
        let c = &plan.summary.coverage;
        assert_eq!(
            counted > 0.985,
            worked_into,
            "reverse {reverse}, {corners:?}: {counted:.4} of the field worked, {:.4} reachable",
            c.reachable_ratio
        );
        assert!(
            (c.coverage_ratio - counted).abs() <= 0.005,
            "{c:?} against {counted:.4}"
        );
        let outside = worked_outside(&plan, 0.25);
        assert!(outside <= 1.0, "{outside:.1} m² worked outside");
        // The corners' manoeuvres: the turns before a headland pass's next piece (forward
        // only, a turn between swaths that no form in the field keeps off the crop worked later
        // leaves the field too).
        let segments = &plan.path.segments;
        let corners_out = segments
            .iter()
            .enumerate()
            .filter(|(_, s)| s.turn.as_ref().is_some_and(|t| !t.inside))
            .filter(|&(k, _)| {
                segments[k + 1..]
                    .iter()
                    .find(|s| s.step.is_some())
                    .is_some_and(|s| s.kind == furrow::path::SegmentKind::HeadlandPass)
            })
            .count();
        let loops_out = !reverse && worked_into;
        assert_eq!(
            corners_out > 1,
            loops_out,
            "reverse {reverse}, {corners:?}: {corners_out} corner manoeuvres outside"
        );
        if loops_out {
            assert!(plan
                .warnings
                .iter()
                .any(|w| w.code == furrow::error::WarningCode::TurnLeavesField));
        }
    }
}

/// A strip 14 m wide worked round by one exact pass of a 6 m drill that reverses: the pass leaves
/// a sliver 2 m wide down the middle, which no swath works (there is no inner field), filled by
/// a piece of its own. Without it the plan fell back to swaths across the strip, lifted at its
/// sides (89 % worked).
#[test]
fn the_sliver_a_pass_leaves_down_a_strip_is_filled() {
    let text = r#"{"type":"Polygon","coordinates":[[[0,0],[100,0],[100,14],[0,14],[0,0]]]}"#;
    let options = furrow::PlanOptions {
        width: 6.0,
        headland_passes: 2.into(),
        turn_radius: 8.0,
        reverse: true,
        coordinates: furrow::field::Coordinates::Metric,
        ..furrow::PlanOptions::default()
    };
    let plan = plan_geojson(text, &options).unwrap_or_else(|e| panic!("{e}"));
    assert!(plan.summary.fill_swath_count >= 1, "{:?}", plan.summary);
    let counted = independent_coverage(&plan, 0.25);
    assert!(counted > 0.99, "{counted:.4} of the strip worked");
    let outside = worked_outside(&plan, 0.25);
    assert!(outside <= 1.0, "{outside:.1} m² worked outside");
}
