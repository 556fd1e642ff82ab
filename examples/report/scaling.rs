//! How planning time grows with the field's size: the L-shaped field scaled from 1 to 1,000
//! ha, timed, and fitted against area and swath count.

use super::*;

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

pub(super) struct Scaling {
    base_area_ha: f64,
    centroid: [f64; 2],
    series: Vec<Series>,
    pub(super) seconds: f64,
}

pub(super) fn scaling(quick: bool) -> Result<Scaling> {
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

/// Prints the sizes planned and the fitted slopes.
pub(super) fn print_scaling(sc: &Scaling) {
    println!(
        "Scaling ({}, width {} m, {} headland passes, turning radius {} m, {} sizes {:.1}-{:.0} ha):",
        SCALING_FIELD,
        SCALING_WIDTH,
        SCALING_PASSES,
        SCALING_RADIUS,
        sc.series.first().map_or(0, |s| s.points.len()),
        sc.series.first().and_then(|s| s.points.first()).map_or(0.0, |p| p.area_ha),
        sc.series.first().and_then(|s| s.points.last()).map_or(0.0, |p| p.area_ha),
    );
    for s in &sc.series {
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
}

pub(super) fn write_scaling(out: &Path, sc: &Scaling, quick: bool) -> Result<()> {
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
