//! How many headland passes run along each edge of the field boundary.
//!
//! In constant mode every edge gets the same number of passes, as in Fields2Cover. In
//! only-where-needed mode (Oksanen & Visala 2.7) an edge within a tolerance of the swath
//! direction gets none: the swaths run along it, so no turns happen there. On top of either,
//! the user may set the number of passes of any edge of the boundary as drawn (0 allowed).

use crate::error::{ErrorCode, PlanError};
use crate::geometry::{point_segment_distance, swath_direction};
use geo::{Coord, Polygon};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Where headland passes run.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum HeadlandMode {
    /// All around the field (Fields2Cover's constant-width headland).
    #[default]
    Constant,
    /// Only along edges where swaths end: none along edges within the tolerance of the swath
    /// direction (Oksanen & Visala 2.7).
    Needed,
}

crate::named::named!(HeadlandMode { "constant" => Constant, "needed" => Needed });

/// The number of headland passes along one edge of the boundary as drawn: edge `i` runs from
/// point `i` to point `i + 1` of the boundary's outer ring in the input.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EdgePasses {
    /// Index of the edge in the ring as drawn.
    pub edge: usize,
    /// Number of passes along it (0 for none).
    pub passes: u32,
}

/// The rule that sets the passes of each edge.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeRule {
    /// Constant or only where needed.
    pub mode: HeadlandMode,
    /// Passes along an edge that needs a headland.
    pub passes: u32,
    /// The swath direction, compass radians.
    pub bearing: f64,
    /// Edges within this angle (radians) of the swath direction need no headland.
    pub tolerance: f64,
}

/// Number of edges of a ring as drawn (a closing point repeating the first is not an edge).
pub fn drawn_edge_count(drawn: &[Coord]) -> usize {
    match (drawn.first(), drawn.last()) {
        (Some(a), Some(b)) if drawn.len() > 1 && a == b => drawn.len() - 1,
        _ => drawn.len(),
    }
}

/// The passes along each edge of `boundary`'s outer ring (edge `i` from point `i` to `i + 1`).
///
/// `drawn` is the boundary's outer ring as drawn, in local metres: `overrides` name its edges,
/// and each planned edge takes the override of the drawn edge nearest its middle.
///
/// ```
/// use furrow::headland::edges::{passes_per_edge, EdgePasses, EdgeRule, HeadlandMode};
/// use geo::{polygon, Coord};
///
/// let field = polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 100., y: 50.), (x: 0., y: 50.)];
/// let drawn: Vec<Coord> = field.exterior().0.clone();
/// // Swaths running north: the east and west edges need no headland.
/// let rule = EdgeRule { mode: HeadlandMode::Needed, passes: 2, bearing: 0.0, tolerance: 5f64.to_radians() };
/// assert_eq!(passes_per_edge(&field, &drawn, &rule, &[])?, vec![2, 0, 2, 0]);
/// // The user wants 3 passes along the northern edge (edge 2 as drawn).
/// let extra = [EdgePasses { edge: 2, passes: 3 }];
/// assert_eq!(passes_per_edge(&field, &drawn, &rule, &extra)?, vec![2, 0, 3, 0]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn passes_per_edge(
    boundary: &Polygon,
    drawn: &[Coord],
    rule: &EdgeRule,
    overrides: &[EdgePasses],
) -> Result<Vec<u32>, PlanError> {
    let drawn_edges = drawn_edge_count(drawn);
    if let Some(o) = overrides.iter().find(|o| o.edge >= drawn_edges) {
        return Err(PlanError::new(
            ErrorCode::OptionOutOfRange,
            format!(
                "option `edgePasses` names edge {}, but the boundary has {drawn_edges} edges (0 to {})",
                o.edge,
                drawn_edges.saturating_sub(1)
            ),
        ));
    }
    let ring = &boundary.exterior().0;
    let swath = swath_direction(rule.bearing);
    let mut out = Vec::with_capacity(ring.len().saturating_sub(1));
    for w in ring.windows(2) {
        let (a, b) = (w[0], w[1]);
        let mut n = rule.passes;
        if rule.mode == HeadlandMode::Needed {
            let edge = swath_direction((b.x - a.x).atan2(b.y - a.y));
            let diff = (edge - swath).abs();
            if diff.min(PI - diff) <= rule.tolerance {
                n = 0;
            }
        }
        if !overrides.is_empty() {
            let mid = Coord {
                x: (a.x + b.x) / 2.0,
                y: (a.y + b.y) / 2.0,
            };
            let nearest = nearest_drawn_edge(drawn, drawn_edges, mid);
            // The last override of an edge wins, as when a user sets it twice.
            if let Some(o) = overrides.iter().rev().find(|o| Some(o.edge) == nearest) {
                n = o.passes;
            }
        }
        out.push(n);
    }
    Ok(out)
}

fn nearest_drawn_edge(drawn: &[Coord], edges: usize, p: Coord) -> Option<usize> {
    let mut best: Option<(f64, usize)> = None;
    for i in 0..edges {
        let (a, b) = (drawn[i], drawn[(i + 1) % drawn.len()]);
        let d = point_segment_distance(p, a, b);
        if best.is_none_or(|(bd, _)| d < bd) {
            best = Some((d, i));
        }
    }
    best.map(|(_, i)| i)
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::polygon;

    #[test]
    fn an_edge_index_beyond_the_ring_is_refused() {
        let field = polygon![(x: 0., y: 0.), (x: 10., y: 0.), (x: 10., y: 10.)];
        let drawn = field.exterior().0.clone();
        let rule = EdgeRule {
            mode: HeadlandMode::Constant,
            passes: 1,
            bearing: 0.0,
            tolerance: 0.0,
        };
        let e = passes_per_edge(&field, &drawn, &rule, &[EdgePasses { edge: 3, passes: 0 }])
            .unwrap_err();
        assert_eq!(e.code, ErrorCode::OptionOutOfRange);
    }

    #[test]
    fn overrides_follow_the_drawn_edges_after_repair() {
        // Drawn with an extra collinear point on the southern edge (edges 0 and 1 are both
        // south), which repair removes: the planned southern edge takes their override.
        let drawn: Vec<Coord> = vec![
            Coord { x: 0., y: 0. },
            Coord { x: 40., y: 0. },
            Coord { x: 100., y: 0. },
            Coord { x: 100., y: 50. },
            Coord { x: 0., y: 50. },
        ];
        let field = polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 100., y: 50.), (x: 0., y: 50.)];
        let rule = EdgeRule {
            mode: HeadlandMode::Constant,
            passes: 2,
            bearing: 0.0,
            tolerance: 0.0,
        };
        let o = [
            EdgePasses { edge: 1, passes: 0 },
            EdgePasses { edge: 4, passes: 1 },
        ];
        assert_eq!(
            passes_per_edge(&field, &drawn, &rule, &o).unwrap(),
            vec![0, 2, 2, 1]
        );
    }
}
