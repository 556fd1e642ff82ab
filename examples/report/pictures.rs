//! The plans' pictures: each corpus field's plan as a small SVG, and the page that shows them.

use super::*;

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
pub(super) fn plan_svg(plan: &Plan) -> String {
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

pub(super) fn plans_markdown(rows: &[Row]) -> String {
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
