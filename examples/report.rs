//! A report on the planner: how good its plans are on the benchmark corpus, what they look like,
//! and how its planning time grows with the size of the field.
//!
//! ```text
//! cargo run --release --example report -- [--out DIR] [--quick]
//! ```
//!
//! writes into `DIR` (default `target/bench`):
//!
//! - `quality.md` and `quality.json`: every corpus field planned with the settings of
//!   `tests/fields/README.md` (width, headland passes, turning radius; every other option at its
//!   default, so `decomposition: auto`): swaths, turns, working / turning / connection / total
//!   distance, the inner field's coverage and overlap by the swaths' strips (the summary's
//!   `objectives`), headland area, estimated time, and Oksanen & Visala's extra driving (total
//!   distance over field area / width, less one);
//! - `plans/<field>.svg` (about 320 px on the long side, north up, in the plan's local metres:
//!   boundary, obstacles, prohibited regions, and the path's headland passes, swaths, turns and
//!   connections in distinct colours) and `plans.md`, which shows them all;
//! - `stages.md` and `stages.json`: every corpus field planned 7 times (3 with `--quick`) after a
//!   warm-up: the median of the whole planning time and of each stage's (`summary.stages_ms`:
//!   validation, direction, headlands, decomposition, route, path, metrics; the last four summed
//!   over the decompositions auto compares), and of writing the plan's GeoJSON (`output`);
//! - `scaling.json`, `scaling.md`, `scaling-area.svg` and `scaling-swaths.svg`: the L-shaped
//!   field (`tests/fields/l-shape.geojson`, non-convex) scaled about its centroid to 12 areas
//!   from 1 to 1,000 ha (6 with `--quick`), planned at width 6 m, 2 headland passes, turning
//!   radius 8 m, with `decomposition: auto` and with `none`; each size timed natively (median of
//!   5 runs, 2 above 100 ha; 3 and 1 with `--quick`; after one warm-up), and log(time) fitted
//!   against log(area) and log(swath count) by least squares. The slopes are in the plots'
//!   titles (Fields2Cover found time growing with the square root of the area, a slope of 0.5).
//!
//! It prints the quality table, the slopes and the total run time (progress of the timing on
//! standard error). In release on this 2-core machine the full run takes a few seconds (the
//! 1,000 ha field plans in about 70 ms with auto), `--quick` a little less.

#[path = "../tests/common/corpus.rs"]
mod corpus;

use furrow::decompose::Decomposition;
use furrow::path::SegmentKind;
use furrow::{plan_geojson, Plan, PlanOptions};
use geo::BoundingRect;
use serde_json::{json, Value};
use std::error::Error;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

type Result<T> = std::result::Result<T, Box<dyn Error>>;

/// The command line.
struct Args {
    out: PathBuf,
    quick: bool,
}

fn parse_args() -> Result<Args> {
    let mut args = Args {
        out: PathBuf::from("target/bench"),
        quick: false,
    };
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        match a.as_str() {
            "--quick" => args.quick = true,
            "--out" => args.out = PathBuf::from(it.next().ok_or("--out needs a directory")?),
            "--help" | "-h" => {
                println!("cargo run --release --example report -- [--out DIR] [--quick]");
                std::process::exit(0);
            }
            other => {
                if let Some(dir) = other.strip_prefix("--out=") {
                    args.out = PathBuf::from(dir);
                } else {
                    return Err(format!("unknown argument `{other}` (try --help)").into());
                }
            }
        }
    }
    Ok(args)
}

fn main() -> Result<()> {
    let started = Instant::now();
    let args = parse_args()?;
    std::fs::create_dir_all(args.out.join("plans"))?;

    let rows = quality(&args.out)?;
    let quality_md = quality_markdown(&rows);
    write(&args.out.join("quality.md"), &quality_md)?;
    write(
        &args.out.join("quality.json"),
        &serde_json::to_string_pretty(&json!({
            "settings": "width, headland passes and turning radius from tests/fields/README.md; every other option at its default",
            "fields": rows.iter().map(Row::to_json).collect::<Vec<_>>(),
        }))?,
    )?;
    write(&args.out.join("plans.md"), &plans_markdown(&rows))?;
    let quality_s = started.elapsed().as_secs_f64();
    let (stages_md, stages_json) = stages(if args.quick { 3 } else { 7 })?;
    write(&args.out.join("stages.md"), &stages_md)?;
    write(
        &args.out.join("stages.json"),
        &serde_json::to_string_pretty(&stages_json)?,
    )?;

    let scaling = scaling(args.quick)?;
    write_scaling(&args.out, &scaling, args.quick)?;

    println!("{quality_md}");
    println!(
        "Scaling ({}, width {} m, {} headland passes, turning radius {} m, {} sizes {:.1}-{:.0} ha):",
        SCALING_FIELD,
        SCALING_WIDTH,
        SCALING_PASSES,
        SCALING_RADIUS,
        scaling.series.first().map_or(0, |s| s.points.len()),
        scaling.series.first().and_then(|s| s.points.first()).map_or(0.0, |p| p.area_ha),
        scaling.series.first().and_then(|s| s.points.last()).map_or(0.0, |p| p.area_ha),
    );
    for s in &scaling.series {
        println!(
            "  decomposition {:<5} time ~ area^{:.3} (r² {:.3}), time ~ swaths^{:.3} (r² {:.3}); {:.1} ms at the largest size",
            s.decomposition.as_str(),
            s.fit_area.slope,
            s.fit_area.r2,
            s.fit_swaths.slope,
            s.fit_swaths.r2,
            s.points.last().map_or(f64::NAN, |p| p.median_ms),
        );
    }
    println!(
        "Wrote {} (quality and pictures {:.1} s, scaling {:.1} s, total {:.1} s{})",
        args.out.display(),
        quality_s,
        scaling.seconds,
        started.elapsed().as_secs_f64(),
        if args.quick { ", --quick" } else { "" }
    );
    Ok(())
}

fn write(path: &Path, text: &str) -> Result<()> {
    std::fs::write(path, text).map_err(|e| format!("cannot write {}: {e}", path.display()).into())
}

// ---------------------------------------------------------------------------------------------
// Quality

/// One corpus field's plan, by the figures of the quality table.
struct Row {
    name: String,
    width: f64,
    passes: u32,
    radius: f64,
    field_area_ha: f64,
    decomposition: &'static str,
    swaths: usize,
    turns: usize,
    working_km: f64,
    turning_km: f64,
    connection_km: f64,
    total_km: f64,
    coverage_pct: f64,
    overlap_pct: f64,
    overlap_m2: f64,
    headland_ha: f64,
    time_min: f64,
    extra_driving_pct: f64,
    planning_ms: f64,
    warnings: Vec<String>,
}

impl Row {
    fn of(name: &str, plan: &Plan) -> Row {
        let s = &plan.summary;
        let o = &plan.options;
        let inner = s.inner_field_area_m2;
        // Oksanen & Visala: the ideal is the field driven in strips of one width and nothing
        // else, a distance of area / width.
        let ideal_m = s.field_area_m2 / o.width;
        Row {
            name: name.to_string(),
            width: o.width,
            passes: s.headland_passes,
            radius: o.turn_radius,
            field_area_ha: s.field_area_m2 / 1e4,
            decomposition: s.decomposition.method.as_str(),
            swaths: s.swath_count,
            turns: s.turn_count,
            working_km: s.working_distance_m / 1e3,
            turning_km: s.turning_distance_m / 1e3,
            connection_km: s.connection_distance_m / 1e3,
            total_km: s.total_distance_m / 1e3,
            coverage_pct: s.objectives.coverage * 100.0,
            overlap_pct: if inner > 0.0 {
                s.objectives.overlap_m2 / inner * 100.0
            } else {
                f64::NAN
            },
            overlap_m2: s.objectives.overlap_m2,
            headland_ha: s.headland_area_m2 / 1e4,
            time_min: s.estimated_time_s / 60.0,
            extra_driving_pct: if ideal_m > 0.0 {
                (s.total_distance_m / ideal_m - 1.0) * 100.0
            } else {
                f64::NAN
            },
            planning_ms: s.planning_ms,
            warnings: plan
                .warnings
                .iter()
                .map(|w| w.code.as_str().to_string())
                .collect(),
        }
    }

    fn to_json(&self) -> Value {
        json!({
            "field": self.name,
            "width_m": self.width,
            "headland_passes": self.passes,
            "turn_radius_m": self.radius,
            "field_area_ha": self.field_area_ha,
            "decomposition": self.decomposition,
            "swath_count": self.swaths,
            "turn_count": self.turns,
            "working_distance_km": self.working_km,
            "turning_distance_km": self.turning_km,
            "connection_distance_km": self.connection_km,
            "total_distance_km": self.total_km,
            "inner_field_coverage_pct": self.coverage_pct,
            "overlap_pct_of_inner_field": finite(self.overlap_pct),
            "overlap_m2": self.overlap_m2,
            "headland_area_ha": self.headland_ha,
            "estimated_time_min": self.time_min,
            "extra_driving_pct": finite(self.extra_driving_pct),
            "planning_ms": self.planning_ms,
            "warnings": self.warnings,
        })
    }
}

/// A number for JSON: NaN and infinities (which JSON cannot carry) as null.
fn finite(x: f64) -> Value {
    if x.is_finite() {
        json!(x)
    } else {
        Value::Null
    }
}

/// Plans every corpus field with its README settings, drawing each plan into `out/plans/`.
/// A field that cannot be read or planned is reported and skipped.
fn quality(out: &Path) -> Result<Vec<Row>> {
    let mut rows = Vec::new();
    for field in corpus::valid_fields() {
        let text = match std::fs::read_to_string(&field.path) {
            Ok(t) => t,
            Err(e) => {
                eprintln!("{}: cannot read {}: {e}", field.name, field.path.display());
                continue;
            }
        };
        let plan = match plan_geojson(&text, &field.options) {
            Ok(p) => p,
            Err(e) => {
                eprintln!("{}: not planned: {e}", field.name);
                continue;
            }
        };
        write(
            &out.join("plans").join(format!("{}.svg", field.name)),
            &plan_svg(&plan),
        )?;
        rows.push(Row::of(&field.name, &plan));
    }
    Ok(rows)
}

/// The stages' times on every corpus field: medians of `runs` plans after a warm-up.
fn stages(runs: usize) -> Result<(String, Value)> {
    const STAGES: [&str; 7] = [
        "validation",
        "direction",
        "headlands",
        "decomposition",
        "route",
        "path",
        "metrics",
    ];
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
    };
    let mut md = String::from(
        "Planning time by stage, milliseconds: the median of each over the runs, natively in release \
         (`summary.stages_ms`; decomposition, route, path and metrics summed over the decompositions auto \
         compares). `output` is writing the plan's GeoJSON text.\n\n\
         | field | ha | total | validation | direction | headlands | decomposition | route | path | metrics | output |\n\
         |---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    let mut rows = Vec::new();
    for field in corpus::valid_fields() {
        let Ok(text) = std::fs::read_to_string(&field.path) else {
            continue;
        };
        if plan_geojson(&text, &field.options).is_err() {
            continue;
        }
        let mut totals = Vec::new();
        let mut outputs = Vec::new();
        let mut by_stage: Vec<Vec<f64>> = vec![Vec::new(); STAGES.len()];
        for _ in 0..runs {
            let plan = plan_geojson(&text, &field.options)?;
            let t = Instant::now();
            let geojson = plan.to_geojson_string();
            outputs.push(t.elapsed().as_secs_f64() * 1000.0);
            std::hint::black_box(geojson);
            totals.push(plan.summary.planning_ms);
            let s = serde_json::to_value(plan.summary.stages_ms)?;
            for (k, name) in STAGES.iter().enumerate() {
                by_stage[k].push(s[*name].as_f64().unwrap_or(f64::NAN));
            }
        }
        let total = median(totals);
        let output = median(outputs);
        let stage: Vec<f64> = by_stage.into_iter().map(median).collect();
        let _ = writeln!(
            md,
            "| {} | {:.1} | {:.2} | {} | {:.2} |",
            field.name,
            field.area_ha,
            total,
            stage
                .iter()
                .map(|v| format!("{v:.2}"))
                .collect::<Vec<_>>()
                .join(" | "),
            output
        );
        let mut row = json!({ "field": field.name, "areaHa": field.area_ha, "totalMs": total, "outputMs": output });
        for (k, name) in STAGES.iter().enumerate() {
            row[*name] = json!(stage[k]);
        }
        rows.push(row);
    }
    Ok((md, json!({ "runs": runs, "fields": rows })))
}

fn quality_markdown(rows: &[Row]) -> String {
    let mut md = String::new();
    let _ = writeln!(md, "# Plan quality on the corpus\n");
    let _ = writeln!(
        md,
        "Settings (width, headland passes, turning radius) come from tests/fields/README.md; every other option is at its default (`decomposition: auto`, direction searched for the lowest time, working 8 km/h, turning 5 km/h). Distances in km, areas net of obstacles. *Covered* and *overlap* are the summary's `objectives`: the inner field's share covered by the swaths' strips, and the strips' area worked twice or over the inner field's edge, as a share of the inner field (the headland passes are not counted in either). *Extra driving* is Oksanen & Visala's: total distance / (field area / width) − 1.\n"
    );
    let _ = writeln!(
        md,
        "| field | w m | passes | r m | area ha | decomposition | swaths | turns | working km | turning km | connection km | total km | covered % | overlap % | headland ha | time min | extra driving % |"
    );
    let _ = writeln!(
        md,
        "|---|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    for r in rows {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {:.2} | {} | {} | {} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {} | {:.2} | {:.1} | {} |",
            r.name,
            r.width,
            r.passes,
            r.radius,
            r.field_area_ha,
            r.decomposition,
            r.swaths,
            r.turns,
            r.working_km,
            r.turning_km,
            r.connection_km,
            r.total_km,
            r.coverage_pct,
            pct(r.overlap_pct),
            r.headland_ha,
            r.time_min,
            pct(r.extra_driving_pct),
        );
    }
    md
}

/// A percentage to two decimals, or a dash where there is none.
fn pct(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.2}")
    } else {
        "–".into()
    }
}

// ---------------------------------------------------------------------------------------------
// Pictures

/// Side of a picture along the field's longer extent, pixels.
const PICTURE_PX: f64 = 320.0;
/// Margin round the field, pixels.
const PICTURE_PAD: f64 = 6.0;

/// The colour and stroke width of each kind of path segment.
fn style(kind: SegmentKind) -> (&'static str, f64) {
    match kind {
        SegmentKind::HeadlandPass => ("#1f6fb5", 0.9),
        SegmentKind::Swath => ("#2e7d32", 0.7),
        SegmentKind::Turn => ("#e08a00", 0.6),
        SegmentKind::Connection => ("#8e24aa", 1.1),
    }
}

/// Colour of turns that leave the field or cross an obstacle.
const OUTSIDE_TURN: &str = "#d50000";

/// Maps local metres to picture pixels (north up) and writes lines as SVG path data, leaving out
/// points closer than a fraction of a pixel to the last one kept.
struct Canvas {
    x0: f64,
    y1: f64,
    scale: f64,
    width: f64,
    height: f64,
}

impl Canvas {
    fn fit(ring: &geo::LineString) -> Canvas {
        let (x0, y0, x1, y1) = ring.bounding_rect().map_or((0.0, 0.0, 1.0, 1.0), |r| {
            (r.min().x, r.min().y, r.max().x, r.max().y)
        });
        let scale = (PICTURE_PX - 2.0 * PICTURE_PAD) / (x1 - x0).max(y1 - y0).max(1e-9);
        Canvas {
            x0,
            y1,
            scale,
            width: ((x1 - x0) * scale + 2.0 * PICTURE_PAD).ceil(),
            height: ((y1 - y0) * scale + 2.0 * PICTURE_PAD).ceil(),
        }
    }

    fn px(&self, c: &geo::Coord) -> (f64, f64) {
        (
            PICTURE_PAD + (c.x - self.x0) * self.scale,
            PICTURE_PAD + (self.y1 - c.y) * self.scale,
        )
    }

    /// Appends `line` to the path data `d` as one subpath (`Z`-closed if `close`).
    fn line(&self, d: &mut String, line: &geo::LineString, close: bool) {
        let n = line.0.len();
        let mut last: Option<(f64, f64)> = None;
        for (i, c) in line.0.iter().enumerate() {
            let (x, y) = self.px(c);
            let keep = match last {
                None => true,
                Some((lx, ly)) => i + 1 == n || (x - lx).hypot(y - ly) >= 0.4,
            };
            if keep {
                let _ = write!(d, "{}{x:.1},{y:.1}", if last.is_none() { "M" } else { "L" });
                last = Some((x, y));
            }
        }
        if close && last.is_some() {
            d.push('Z');
        }
    }
}

/// A small picture of a plan, north up, in its local metres.
fn plan_svg(plan: &Plan) -> String {
    let canvas = Canvas::fit(plan.field.boundary.exterior());
    let (w, h) = (canvas.width, canvas.height);
    let mut out = String::new();
    let _ = writeln!(
        out,
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">"##
    );
    let _ = writeln!(out, r##"<rect width="{w}" height="{h}" fill="#ffffff"/>"##);
    let mut d = String::new();
    canvas.line(&mut d, plan.field.boundary.exterior(), true);
    for hole in plan.field.boundary.interiors() {
        canvas.line(&mut d, hole, true);
    }
    let _ = writeln!(
        out,
        r##"<path d="{d}" fill="#f3efe4" stroke="#444" stroke-width="1" fill-rule="evenodd"/>"##
    );
    if !plan.field.obstacles.is_empty() {
        let mut d = String::new();
        for o in &plan.field.obstacles {
            canvas.line(&mut d, o.polygon.exterior(), true);
        }
        let _ = writeln!(
            out,
            r##"<path d="{d}" fill="#9a9a9a" stroke="#555" stroke-width="0.6"/>"##
        );
    }
    if !plan.field.prohibited.is_empty() {
        let mut d = String::new();
        for r in &plan.field.prohibited {
            canvas.line(&mut d, r.polygon.exterior(), true);
        }
        let _ = writeln!(
            out,
            r##"<path d="{d}" fill="#c62828" fill-opacity="0.08" stroke="#c62828" stroke-width="1" stroke-dasharray="4 3"/>"##
        );
    }
    // The path, one SVG path per kind, in the order headland, swaths, turns, connections (the
    // last drawn on top).
    for kind in [
        SegmentKind::HeadlandPass,
        SegmentKind::Swath,
        SegmentKind::Turn,
        SegmentKind::Connection,
    ] {
        let (colour, stroke) = style(kind);
        let mut d = String::new();
        let mut outside = String::new();
        for seg in plan.path.segments.iter().filter(|s| s.kind == kind) {
            if seg.turn.as_ref().is_some_and(|t| !t.inside) {
                canvas.line(&mut outside, &seg.line, false);
            } else {
                canvas.line(&mut d, &seg.line, false);
            }
        }
        let dash = if kind == SegmentKind::Connection {
            r#" stroke-dasharray="3 2""#
        } else {
            ""
        };
        for (data, colour) in [(d, colour), (outside, OUTSIDE_TURN)] {
            if !data.is_empty() {
                let _ = writeln!(
                    out,
                    r##"<path d="{data}" fill="none" stroke="{colour}" stroke-width="{stroke}" stroke-linejoin="round"{dash}/>"##
                );
            }
        }
    }
    out.push_str("</svg>\n");
    out
}

fn plans_markdown(rows: &[Row]) -> String {
    let mut md = String::new();
    let _ = writeln!(md, "# The corpus plans\n");
    let _ = writeln!(
        md,
        "Each corpus field planned with its settings from tests/fields/README.md, north up. Field grey-beige with its boundary, obstacles grey, prohibited regions dashed red; headland passes blue, swaths green, turns orange (red where a turn leaves the field or crosses an obstacle), connections dashed purple.\n"
    );
    for r in rows {
        let _ = writeln!(
            md,
            "## {}\n\n![{} plan](plans/{}.svg)\n\n{:.2} ha, width {} m, {} passes, r {} m: {} ({}), {} swaths, {} turns, {:.2} km, {:.1} min, extra driving {} %.\n",
            r.name,
            r.name,
            r.name,
            r.field_area_ha,
            r.width,
            r.passes,
            r.radius,
            r.decomposition,
            if r.warnings.is_empty() {
                "no warnings".to_string()
            } else {
                format!("warnings: {}", r.warnings.join(", "))
            },
            r.swaths,
            r.turns,
            r.total_km,
            r.time_min,
            pct(r.extra_driving_pct),
        );
    }
    md
}

// ---------------------------------------------------------------------------------------------
// Scaling

/// The field scaled: non-convex, so that split and merge has something to do.
const SCALING_FIELD: &str = "l-shape.geojson";
const SCALING_WIDTH: f64 = 6.0;
const SCALING_PASSES: u32 = 2;
const SCALING_RADIUS: f64 = 8.0;
/// The range of areas, hectares.
const SCALING_HA: (f64, f64) = (1.0, 1000.0);

/// One size of the scaled field, timed.
struct Point {
    scale: f64,
    area_ha: f64,
    swaths: usize,
    blocks: usize,
    method: &'static str,
    runs_ms: Vec<f64>,
    median_ms: f64,
}

/// A least-squares line log(time) = a + b log(x).
#[derive(Clone, Copy)]
struct Fit {
    intercept: f64,
    slope: f64,
    r2: f64,
}

struct Series {
    decomposition: Decomposition,
    points: Vec<Point>,
    fit_area: Fit,
    fit_swaths: Fit,
}

struct Scaling {
    base_area_ha: f64,
    centroid: [f64; 2],
    series: Vec<Series>,
    seconds: f64,
}

fn scaling(quick: bool) -> Result<Scaling> {
    let started = Instant::now();
    let path = corpus::fields_dir().join(SCALING_FIELD);
    let text = std::fs::read_to_string(&path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let doc: Value = serde_json::from_str(&text)?;
    let centroid = boundary_centroid(&doc).ok_or("no boundary polygon in the scaling field")?;
    let options = |d: Decomposition| PlanOptions {
        width: SCALING_WIDTH,
        headland_passes: SCALING_PASSES.into(),
        turn_radius: SCALING_RADIUS,
        decomposition: d,
        ..PlanOptions::default()
    };
    let base_area_ha = plan_geojson(&text, &options(Decomposition::Auto))?
        .summary
        .field_area_m2
        / 1e4;
    let sizes = if quick { 6 } else { 12 };
    let mut series = Vec::new();
    for d in [Decomposition::Auto, Decomposition::None] {
        let opts = options(d);
        let mut points = Vec::new();
        for i in 0..sizes {
            let t = i as f64 / (sizes - 1) as f64;
            let target_ha = SCALING_HA.0 * (SCALING_HA.1 / SCALING_HA.0).powf(t);
            let scale = (target_ha / base_area_ha).sqrt();
            let mut scaled = doc.clone();
            scale_document(&mut scaled, centroid, scale);
            let input = serde_json::to_string(&scaled)?;
            // The warm-up run, whose plan gives the size's figures.
            let plan = plan_geojson(&input, &opts)?;
            let k = match (quick, target_ha > 100.0) {
                (false, false) => 5,
                (false, true) => 2,
                (true, false) => 3,
                (true, true) => 1,
            };
            let mut runs_ms = Vec::with_capacity(k);
            for _ in 0..k {
                let t0 = Instant::now();
                let p = plan_geojson(&input, &opts)?;
                runs_ms.push(t0.elapsed().as_secs_f64() * 1e3);
                std::hint::black_box(p);
            }
            let median_ms = median(&mut runs_ms.clone());
            let s = &plan.summary;
            eprintln!(
                "scaling {:<4} {:>8.2} ha {:>5} swaths {:>10.2} ms (median of {k})",
                d.as_str(),
                s.field_area_m2 / 1e4,
                s.swath_count,
                median_ms
            );
            points.push(Point {
                scale,
                area_ha: s.field_area_m2 / 1e4,
                swaths: s.swath_count,
                blocks: s.block_count,
                method: s.decomposition.method.as_str(),
                runs_ms,
                median_ms,
            });
        }
        let fit_area = fit(points.iter().map(|p| (p.area_ha, p.median_ms)));
        let fit_swaths = fit(points.iter().map(|p| (p.swaths as f64, p.median_ms)));
        series.push(Series {
            decomposition: d,
            points,
            fit_area,
            fit_swaths,
        });
    }
    Ok(Scaling {
        base_area_ha,
        centroid,
        series,
        seconds: started.elapsed().as_secs_f64(),
    })
}

fn median(xs: &mut [f64]) -> f64 {
    xs.sort_by(f64::total_cmp);
    let n = xs.len();
    match n {
        0 => f64::NAN,
        _ if n % 2 == 1 => xs[n / 2],
        _ => (xs[n / 2 - 1] + xs[n / 2]) / 2.0,
    }
}

/// Least squares of ln(y) on ln(x).
fn fit(points: impl Iterator<Item = (f64, f64)>) -> Fit {
    let pts: Vec<(f64, f64)> = points
        .filter(|&(x, y)| x > 0.0 && y > 0.0)
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    let n = pts.len() as f64;
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let syy: f64 = pts.iter().map(|p| (p.1 - my).powi(2)).sum();
    let slope = sxy / sxx;
    Fit {
        intercept: my - slope * mx,
        slope,
        r2: if syy > 0.0 {
            sxy * sxy / (sxx * syy)
        } else {
            1.0
        },
    }
}

/// The area-weighted centroid (in degrees) of the outer ring of the document's boundary: the
/// feature with `role: boundary`, or else the first polygon.
fn boundary_centroid(doc: &Value) -> Option<[f64; 2]> {
    let features = doc["features"].as_array()?;
    let feature = features
        .iter()
        .find(|f| f["properties"]["role"] == "boundary")
        .or_else(|| features.first())?;
    let ring: Vec<[f64; 2]> = feature["geometry"]["coordinates"]
        .get(0)?
        .as_array()?
        .iter()
        .filter_map(|p| Some([p.get(0)?.as_f64()?, p.get(1)?.as_f64()?]))
        .collect();
    let (mut a, mut cx, mut cy) = (0.0, 0.0, 0.0);
    for w in ring.windows(2) {
        let cross = w[0][0] * w[1][1] - w[1][0] * w[0][1];
        a += cross;
        cx += (w[0][0] + w[1][0]) * cross;
        cy += (w[0][1] + w[1][1]) * cross;
    }
    (a.abs() > 0.0).then(|| [cx / (3.0 * a), cy / (3.0 * a)])
}

/// Scales every position of every feature's geometry about `centre` by `s` (longitude and
/// latitude offsets alike: the shape is kept for a field of a few kilometres).
fn scale_document(doc: &mut Value, centre: [f64; 2], s: f64) {
    fn positions(v: &mut Value, centre: [f64; 2], s: f64) {
        let Some(items) = v.as_array_mut() else {
            return;
        };
        if items.len() >= 2 && items.iter().all(Value::is_number) {
            for (k, c) in items.iter_mut().take(2).enumerate() {
                if let Some(x) = c.as_f64() {
                    *c = json!(centre[k] + (x - centre[k]) * s);
                }
            }
        } else {
            for item in items {
                positions(item, centre, s);
            }
        }
    }
    if let Some(features) = doc["features"].as_array_mut() {
        for f in features {
            positions(&mut f["geometry"]["coordinates"], centre, s);
        }
    }
}

fn write_scaling(out: &Path, sc: &Scaling, quick: bool) -> Result<()> {
    let series_json: Vec<Value> = sc
        .series
        .iter()
        .map(|s| {
            json!({
                "decomposition": s.decomposition.as_str(),
                "fit_area": {"intercept": s.fit_area.intercept, "slope": s.fit_area.slope, "r2": s.fit_area.r2},
                "fit_swaths": {"intercept": s.fit_swaths.intercept, "slope": s.fit_swaths.slope, "r2": s.fit_swaths.r2},
                "points": s.points.iter().map(|p| json!({
                    "scale": p.scale,
                    "area_ha": p.area_ha,
                    "swath_count": p.swaths,
                    "block_count": p.blocks,
                    "decomposition_used": p.method,
                    "runs_ms": p.runs_ms,
                    "median_ms": p.median_ms,
                })).collect::<Vec<_>>(),
            })
        })
        .collect();
    write(
        &out.join("scaling.json"),
        &serde_json::to_string_pretty(&json!({
            "field": format!("tests/fields/{SCALING_FIELD}"),
            "base_area_ha": sc.base_area_ha,
            "centroid_lon_lat": sc.centroid,
            "options": {"width": SCALING_WIDTH, "headlandPasses": SCALING_PASSES, "turnRadius": SCALING_RADIUS},
            "quick": quick,
            "timing": "median of k runs of plan_geojson after one warm-up (std::time::Instant), k = 5 up to 100 ha and 2 above (3 and 1 with --quick)",
            "fit": "ln(ms) = intercept + slope * ln(x), least squares",
            "series": series_json,
            "seconds": sc.seconds,
        }))?,
    )?;
    let area_svg = log_plot(
        sc,
        "Planning time against field area",
        "field area, ha",
        |p| p.area_ha,
        |s| s.fit_area,
    );
    write(&out.join("scaling-area.svg"), &area_svg)?;
    let swaths_svg = log_plot(
        sc,
        "Planning time against swath count",
        "swaths",
        |p| p.swaths as f64,
        |s| s.fit_swaths,
    );
    write(&out.join("scaling-swaths.svg"), &swaths_svg)?;

    let mut md = String::new();
    let _ = writeln!(md, "# Planning time against field size\n");
    let _ = writeln!(
        md,
        "tests/fields/{SCALING_FIELD} (non-convex: an L) scaled about its centroid ({:.6}, {:.6}) from its {:.2} ha to areas from {} to {} ha, longitude and latitude offsets scaled alike; width {SCALING_WIDTH} m, {SCALING_PASSES} headland passes, turning radius {SCALING_RADIUS} m, every other option at its default. Each size planned natively with `plan_geojson` (release build), the median of k runs after one warm-up: k = {} up to 100 ha and {} above{}. Slopes by least squares on log(time).\n",
        sc.centroid[0],
        sc.centroid[1],
        sc.base_area_ha,
        SCALING_HA.0,
        SCALING_HA.1,
        if quick { 3 } else { 5 },
        if quick { 1 } else { 2 },
        if quick { " (--quick)" } else { "" },
    );
    for s in &sc.series {
        let _ = writeln!(
            md,
            "- `decomposition: {}`: time ∝ area^**{:.3}** (r² {:.3}), time ∝ swaths^**{:.3}** (r² {:.3})",
            s.decomposition.as_str(),
            s.fit_area.slope,
            s.fit_area.r2,
            s.fit_swaths.slope,
            s.fit_swaths.r2
        );
    }
    let _ = writeln!(
        md,
        "\nFields2Cover (Mier et al. 2023) found planning time growing with the square root of the area (slope 0.5).\n"
    );
    let _ = writeln!(md, "![time against area](scaling-area.svg)\n");
    let _ = writeln!(md, "![time against swaths](scaling-swaths.svg)\n");
    let _ = write!(md, "| area ha |");
    for s in &sc.series {
        let d = s.decomposition.as_str();
        let _ = write!(md, " {d}: swaths | {d}: used | {d}: ms |");
    }
    let _ = writeln!(md);
    let _ = writeln!(md, "|---:|{}", "---:|---|---:|".repeat(sc.series.len()));
    let n = sc.series.iter().map(|s| s.points.len()).max().unwrap_or(0);
    for i in 0..n {
        let area = sc
            .series
            .iter()
            .find_map(|s| s.points.get(i))
            .map_or(f64::NAN, |p| p.area_ha);
        let _ = write!(md, "| {area:.2} |");
        for s in &sc.series {
            match s.points.get(i) {
                Some(p) => {
                    let _ = write!(
                        md,
                        " {} | {} ({} {}) | {:.2} |",
                        p.swaths,
                        p.method,
                        p.blocks,
                        if p.blocks == 1 { "block" } else { "blocks" },
                        p.median_ms
                    );
                }
                None => {
                    let _ = write!(md, " – | – | – |");
                }
            }
        }
        let _ = writeln!(md);
    }
    let _ = writeln!(md, "\nRun time of the scaling part: {:.1} s.", sc.seconds);
    write(&out.join("scaling.md"), &md)
}

/// Colours of the series in the plots.
const SERIES_COLOURS: [&str; 3] = ["#1f6fb5", "#d35400", "#2e7d32"];

/// A log-log plot of planning time against `x` for every series: decade ticks (and lighter ones
/// at 2-9), the points, the fitted lines, and the slopes in the title.
fn log_plot(
    sc: &Scaling,
    title: &str,
    x_label: &str,
    x_of: impl Fn(&Point) -> f64,
    fit_of: impl Fn(&Series) -> Fit,
) -> String {
    let (w, h) = (560.0, 380.0);
    let (left, right, top, bottom) = (64.0, 18.0, 52.0, 48.0);
    let pts = || {
        sc.series
            .iter()
            .flat_map(|s| s.points.iter())
            .filter(|p| x_of(p) > 0.0 && p.median_ms > 0.0)
    };
    let decades = |vals: &mut dyn Iterator<Item = f64>| {
        let (lo, hi) = vals.fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
        if lo > hi {
            (0, 1)
        } else {
            let (a, b) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
            (a, b.max(a + 1))
        }
    };
    let (xa, xb) = decades(&mut pts().map(&x_of));
    let (ya, yb) = decades(&mut pts().map(|p| p.median_ms));
    let px = |x: f64| left + (x.log10() - xa as f64) / (xb - xa) as f64 * (w - left - right);
    let py = |y: f64| h - bottom - (y.log10() - ya as f64) / (yb - ya) as f64 * (h - top - bottom);
    let slopes = sc
        .series
        .iter()
        .map(|s| format!("{} b = {:.2}", s.decomposition.as_str(), fit_of(s).slope))
        .collect::<Vec<_>>()
        .join(", ");
    let mut out = String::new();
    let _ = writeln!(
        out,
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="11">"##
    );
    let _ = writeln!(out, r##"<rect width="{w}" height="{h}" fill="#ffffff"/>"##);
    let _ = writeln!(
        out,
        r##"<text x="{}" y="18" font-size="13" text-anchor="middle" fill="#222">{title}: {slopes}</text>"##,
        w / 2.0
    );
    let _ = writeln!(
        out,
        r##"<text x="{}" y="34" text-anchor="middle" fill="#555">{SCALING_FIELD} scaled, w {SCALING_WIDTH} m, {SCALING_PASSES} passes, r {SCALING_RADIUS} m; time = a·x^b by least squares</text>"##,
        w / 2.0
    );
    // Grid and ticks.
    let (x_left, x_right, y_top, y_bottom) = (left, w - right, top, h - bottom);
    for e in xa..=xb {
        for m in 1..10 {
            let v = f64::from(m) * 10f64.powi(e);
            if e == xb && m > 1 {
                break;
            }
            let x = px(v);
            let (stroke, sw) = if m == 1 { ("#bbb", 0.8) } else { ("#eee", 0.6) };
            let _ = writeln!(
                out,
                r##"<line x1="{x:.1}" y1="{y_top}" x2="{x:.1}" y2="{y_bottom}" stroke="{stroke}" stroke-width="{sw}"/>"##
            );
            if m == 1 {
                let _ = writeln!(
                    out,
                    r##"<text x="{x:.1}" y="{}" text-anchor="middle" fill="#333">{}</text>"##,
                    y_bottom + 15.0,
                    decade_label(e)
                );
            }
        }
    }
    for e in ya..=yb {
        for m in 1..10 {
            let v = f64::from(m) * 10f64.powi(e);
            if e == yb && m > 1 {
                break;
            }
            let y = py(v);
            let (stroke, sw) = if m == 1 { ("#bbb", 0.8) } else { ("#eee", 0.6) };
            let _ = writeln!(
                out,
                r##"<line x1="{x_left}" y1="{y:.1}" x2="{x_right}" y2="{y:.1}" stroke="{stroke}" stroke-width="{sw}"/>"##
            );
            if m == 1 {
                let _ = writeln!(
                    out,
                    r##"<text x="{}" y="{:.1}" text-anchor="end" fill="#333">{}</text>"##,
                    x_left - 6.0,
                    y + 4.0,
                    decade_label(e)
                );
            }
        }
    }
    let _ = writeln!(
        out,
        r##"<rect x="{x_left}" y="{y_top}" width="{}" height="{}" fill="none" stroke="#444"/>"##,
        x_right - x_left,
        y_bottom - y_top
    );
    let _ = writeln!(
        out,
        r##"<text x="{}" y="{}" text-anchor="middle" fill="#222">{x_label}</text>"##,
        (x_left + x_right) / 2.0,
        h - 12.0
    );
    let _ = writeln!(
        out,
        r##"<text transform="translate(16 {}) rotate(-90)" text-anchor="middle" fill="#222">planning time, ms</text>"##,
        (y_top + y_bottom) / 2.0
    );
    // The series: fitted line over the points' range, then the points; a legend top left.
    for (k, s) in sc.series.iter().enumerate() {
        let colour = SERIES_COLOURS[k % SERIES_COLOURS.len()];
        let f = fit_of(s);
        let xs: Vec<f64> = s.points.iter().map(&x_of).filter(|&x| x > 0.0).collect();
        let (lo, hi) = xs
            .iter()
            .fold((f64::MAX, f64::MIN), |(lo, hi), &x| (lo.min(x), hi.max(x)));
        if lo < hi && f.slope.is_finite() {
            let y_at = |x: f64| (f.intercept + f.slope * x.ln()).exp();
            let _ = writeln!(
                out,
                r##"<line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="{colour}" stroke-width="1.4" stroke-dasharray="6 3"/>"##,
                px(lo),
                py(y_at(lo)),
                px(hi),
                py(y_at(hi))
            );
        }
        for p in s
            .points
            .iter()
            .filter(|p| x_of(p) > 0.0 && p.median_ms > 0.0)
        {
            let _ = writeln!(
                out,
                r##"<circle cx="{:.1}" cy="{:.1}" r="3.2" fill="{colour}"><title>{:.2} ha, {} swaths: {:.2} ms</title></circle>"##,
                px(x_of(p)),
                py(p.median_ms),
                p.area_ha,
                p.swaths,
                p.median_ms
            );
        }
        let ly = y_top + 16.0 + 16.0 * k as f64;
        let _ = writeln!(
            out,
            r##"<circle cx="{}" cy="{ly}" r="3.2" fill="{colour}"/><text x="{}" y="{}" fill="#222">decomposition {}: slope {:.3} (r² {:.3})</text>"##,
            x_left + 14.0,
            x_left + 24.0,
            ly + 4.0,
            s.decomposition.as_str(),
            f.slope,
            f.r2
        );
    }
    out.push_str("</svg>\n");
    out
}

/// 10^e written out: 0.01, 0.1, 1, 10, 100, 1000, 10000.
fn decade_label(e: i32) -> String {
    if e >= 0 {
        format!("1{}", "0".repeat(e as usize))
    } else {
        format!("0.{}1", "0".repeat((-e - 1) as usize))
    }
}
