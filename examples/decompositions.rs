//! The decompositions compared on the corpus: for every benchmark field (with its README
//! settings), the plan with one direction (the best of a brute-force search at 1 degree), with
//! Zhou et al.'s boustrophedon cells, and with Oksanen & Visala's split and merge: blocks, their
//! directions, turns within blocks, estimated operation time, and what auto chose. Prints a
//! Markdown table; with `--svg DIR` also draws each field's three plans side by side as
//! `DIR/NAME.svg` (blocks in colours, swaths, headland passes, block order).
//!
//! `cargo run --release --example decompositions [-- --svg target/decompositions] [--field NAME]`
#![allow(clippy::result_large_err)]

#[path = "../tests/common/corpus.rs"]
mod corpus;

use furrow::decompose::Decomposition;
use furrow::direction::SearchMethod;
use furrow::{plan_geojson, Plan, PlanOptions};
use geo::BoundingRect;
use std::fmt::Write as _;

fn plan_with(text: &str, options: &PlanOptions, d: Decomposition) -> Option<Plan> {
    let options = PlanOptions {
        decomposition: d,
        // The best single direction: brute force, so that the comparison is with the best there is.
        search: if d == Decomposition::None {
            SearchMethod::BruteForce
        } else {
            options.search
        },
        ..options.clone()
    };
    match plan_geojson(text, &options) {
        Ok(p) => Some(p),
        Err(e) => {
            eprintln!("{}: {}", d.as_str(), e);
            None
        }
    }
}

fn directions(plan: &Plan) -> String {
    let mut seen: Vec<f64> = Vec::new();
    for b in &plan.blocks.blocks {
        let d = b.bearing.to_degrees().round();
        if !seen.contains(&d) {
            seen.push(d);
        }
    }
    seen.iter()
        .map(|d| format!("{d:.0}"))
        .collect::<Vec<_>>()
        .join("/")
}

fn cell(plan: &Option<Plan>) -> String {
    match plan {
        Some(p) => format!(
            "{} | {} | {} | {:.1}",
            p.summary.block_count,
            directions(p),
            p.summary.turn_count,
            p.summary.estimated_time_s / 60.0
        ),
        None => "- | - | - | -".into(),
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let svg_dir = args
        .iter()
        .position(|a| a == "--svg")
        .and_then(|i| args.get(i + 1))
        .cloned();
    let only = args
        .iter()
        .position(|a| a == "--field")
        .and_then(|i| args.get(i + 1))
        .cloned();
    if let Some(dir) = &svg_dir {
        std::fs::create_dir_all(dir).expect("create the SVG directory");
    }
    println!("| field | none: blocks | directions | turns | time min | boustrophedon: blocks | directions | turns | time min | split-merge: blocks | directions | turns | time min | auto | gain |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for field in corpus::valid_fields() {
        if only.as_ref().is_some_and(|o| *o != field.name) {
            continue;
        }
        let text = field.text();
        let none = plan_with(&text, &field.options, Decomposition::None);
        let bous = plan_with(&text, &field.options, Decomposition::Boustrophedon);
        let sm = plan_with(&text, &field.options, Decomposition::SplitMerge);
        let auto = plan_with(&text, &field.options, Decomposition::Auto);
        let best_single = none
            .as_ref()
            .map_or(f64::NAN, |p| p.summary.estimated_time_s);
        let chosen = auto
            .as_ref()
            .map(|p| {
                (
                    p.summary.decomposition.method.as_str(),
                    p.summary.estimated_time_s,
                )
            })
            .unwrap_or(("-", f64::NAN));
        println!(
            "| {} | {} | {} | {} | {} | {:+.1} % |",
            field.name,
            cell(&none),
            cell(&bous),
            cell(&sm),
            chosen.0,
            (chosen.1 / best_single - 1.0) * 100.0
        );
        if let Some(dir) = &svg_dir {
            let plans: Vec<(&str, &Plan)> = [
                ("one direction", &none),
                ("boustrophedon", &bous),
                ("split and merge", &sm),
            ]
            .into_iter()
            .filter_map(|(n, p)| p.as_ref().map(|p| (n, p)))
            .collect();
            let path = format!("{dir}/{}.svg", field.name);
            std::fs::write(&path, svg(&field.name, &plans)).expect("write the SVG");
        }
    }
}

/// Colours of blocks, in turn.
const BLOCK_COLOURS: [&str; 8] = [
    "#cfe8b4", "#f6d7a7", "#c9dcf2", "#f2c9d8", "#e0d4f2", "#d9efe9", "#f2efb8", "#e8d0c0",
];

/// The plans side by side, each in its own panel, north up.
fn svg(name: &str, plans: &[(&str, &Plan)]) -> String {
    let panel = 360.0;
    let pad = 12.0;
    let title_h = 34.0;
    let width = panel * plans.len() as f64;
    let height = panel + title_h;
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="sans-serif">"#
    );
    let _ = writeln!(
        out,
        r##"<rect width="{width}" height="{height}" fill="#ffffff"/>"##
    );
    for (k, (label, plan)) in plans.iter().enumerate() {
        let ring = plan.field.boundary.exterior();
        let (x0, y0, x1, y1) = ring.bounding_rect().map_or((0.0, 0.0, 1.0, 1.0), |r| {
            (r.min().x, r.min().y, r.max().x, r.max().y)
        });
        let scale = (panel - 2.0 * pad) / (x1 - x0).max(y1 - y0).max(1.0);
        let ox = k as f64 * panel + pad + ((panel - 2.0 * pad) - (x1 - x0) * scale) / 2.0;
        let oy = title_h + pad + ((panel - 2.0 * pad) - (y1 - y0) * scale) / 2.0;
        let p = |c: &geo::Coord| {
            format!(
                "{:.1},{:.1}",
                ox + (c.x - x0) * scale,
                oy + (y1 - c.y) * scale
            )
        };
        let path_of = |ls: &geo::LineString| {
            ls.0.iter()
                .enumerate()
                .map(|(i, c)| format!("{}{}", if i == 0 { "M" } else { "L" }, p(c)))
                .collect::<String>()
        };
        let s = &plan.summary;
        let _ = writeln!(
            out,
            r##"<text x="{:.1}" y="16" font-size="13" fill="#222">{name}: {label}</text><text x="{:.1}" y="30" font-size="11" fill="#555">{} blocks, {} turns, {:.1} min</text>"##,
            k as f64 * panel + pad,
            k as f64 * panel + pad,
            s.block_count,
            s.turn_count,
            s.estimated_time_s / 60.0
        );
        let mut boundary = path_of(ring);
        for hole in plan.field.boundary.interiors() {
            boundary.push_str(&path_of(hole));
        }
        let _ = writeln!(
            out,
            r##"<path d="{boundary}Z" fill="#f4f1ea" stroke="#555" stroke-width="1"/>"##
        );
        for (i, b) in plan.blocks.blocks.iter().enumerate() {
            let colour = BLOCK_COLOURS[i % BLOCK_COLOURS.len()];
            let mut d = path_of(b.outline.exterior());
            for hole in b.outline.interiors() {
                d.push_str(&path_of(hole));
            }
            let _ = writeln!(
                out,
                r##"<path d="{d}Z" fill="{colour}" stroke="#777" stroke-width="0.6" fill-rule="evenodd"/>"##
            );
        }
        for o in &plan.field.obstacles {
            let _ = writeln!(
                out,
                r##"<path d="{}Z" fill="#8a8a8a"/>"##,
                path_of(o.polygon.exterior())
            );
        }
        for r in &plan.field.prohibited {
            let _ = writeln!(
                out,
                r##"<path d="{}Z" fill="none" stroke="#c0392b" stroke-dasharray="4 3" stroke-width="1.2"/>"##,
                path_of(r.polygon.exterior())
            );
        }
        for h in &plan.headlands.passes {
            let colour = if h.around == furrow::headland::PassAround::Block {
                "#d35400"
            } else {
                "#2e86c1"
            };
            let _ = writeln!(
                out,
                r##"<path d="{}" fill="none" stroke="{colour}" stroke-width="0.9"/>"##,
                path_of(&h.line)
            );
        }
        for sw in &plan.swaths.swaths {
            let _ = writeln!(
                out,
                r##"<path d="M{}L{}" stroke="#2e7d32" stroke-width="0.8"/>"##,
                p(&sw.centre.start),
                p(&sw.centre.end)
            );
        }
        for (order, &b) in plan.route.block_order.iter().enumerate() {
            if let Some(block) = plan.blocks.blocks.get(b) {
                use geo::Centroid;
                if let Some(c) = block.outline.centroid() {
                    let _ = writeln!(
                        out,
                        r##"<text x="{}" y="{}" font-size="12" font-weight="bold" fill="#000" text-anchor="middle" paint-order="stroke" stroke="#fff" stroke-width="3">{}</text>"##,
                        p(&c.0).split(',').next().unwrap_or("0"),
                        p(&c.0).split(',').nth(1).unwrap_or("0"),
                        order + 1
                    );
                }
            }
        }
    }
    out.push_str("</svg>\n");
    out
}
