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

#[path = "../../tests/common/corpus.rs"]
mod corpus;
mod pictures;
mod scaling;

use pictures::{plan_svg, plans_markdown};
use scaling::{print_scaling, scaling, write_scaling};

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
    print_scaling(&scaling);
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
