//! The stretches a plan works, read back from its GeoJSON (not from the planner's own
//! structures): each working feature's line less its lifted stretches, in local metres.
#![allow(dead_code)]

use furrow::Plan;
use geo::Coord;

/// A worked stretch in local metres: the implement's centre runs straight from one end to the
/// other with the implement down.
pub type Stretch = (Coord, Coord);

/// A point where a worked line turns, the implement down on both its edges: the implement swings round `at` from the
/// heading `from` (the direction of the edge before it) to the heading `to` (the edge after).
#[derive(Debug, Clone, Copy)]
pub struct Joint {
    pub at: Coord,
    pub from: Coord,
    pub to: Coord,
}

/// The worked stretches of a plan and the joints between them.
pub fn worked_stretches(plan: &Plan) -> (Vec<Stretch>, Vec<Joint>) {
    let (stretches, corners): (Vec<_>, _) = worked_stretches_by_kind(plan);
    (stretches.into_iter().map(|(s, _)| s).collect(), corners)
}

/// The worked stretches of a plan, each with the `kind` of the feature it belongs to (`swath`,
/// `headland`, ...), and the joints between them.
pub fn worked_stretches_by_kind(plan: &Plan) -> (Vec<(Stretch, String)>, Vec<Joint>) {
    let json: serde_json::Value =
        serde_json::from_str(&plan.to_geojson_string()).expect("the plan's JSON");
    let mut stretches = Vec::new();
    let mut corners = Vec::new();
    for f in json["features"].as_array().expect("features") {
        let p = &f["properties"];
        if p["working"] != serde_json::Value::Bool(true) {
            continue;
        }
        let kind = p["kind"].as_str().unwrap_or("").to_string();
        let line: Vec<Coord> = f["geometry"]["coordinates"]
            .as_array()
            .expect("a line")
            .iter()
            .map(|c| {
                let (x, y) = (c[0].as_f64().expect("x"), c[1].as_f64().expect("y"));
                plan.field.frame.to_local([x, y])
            })
            .collect();
        let lifted: Vec<(f64, f64)> = p["lifted"]
            .as_array()
            .map(|l| {
                l.iter()
                    .map(|r| (r[0].as_f64().unwrap_or(0.0), r[1].as_f64().unwrap_or(0.0)))
                    .collect()
            })
            .unwrap_or_default();
        let mut along = 0.0;
        for (k, w) in line.windows(2).enumerate() {
            let d = w[1] - w[0];
            let length = d.x.hypot(d.y);
            // The parts of this stretch not lifted.
            let mut from = 0.0;
            for &(a, b) in &lifted {
                let (a, b) = (
                    (a - along).clamp(0.0, length),
                    (b - along).clamp(0.0, length),
                );
                if a > from {
                    stretches.push((
                        (w[0] + d * (from / length), w[0] + d * (a / length)),
                        kind.clone(),
                    ));
                }
                from = from.max(b);
            }
            if length > from {
                stretches.push(((w[0] + d * (from / length), w[1]), kind.clone()));
            }
            along += length;
            // The joint at this edge's end, where another follows: not where the implement is
            // lifted.
            if let Some(&next) = line.get(k + 2) {
                if lifted
                    .iter()
                    .all(|&(a, b)| along < a - 1e-3 || along > b + 1e-3)
                {
                    corners.push(Joint {
                        at: w[1],
                        from: d,
                        to: next - w[1],
                    });
                }
            }
        }
    }
    (stretches, corners)
}
