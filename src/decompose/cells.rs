//! Cells of an area at a driving direction: the trapezoidal split (Oksanen & Visala 2.3) and the
//! merges that make blocks of it, boustrophedon (Zhou et al. 2.3.1, after Choset) or Oksanen's
//! (2.4: sides matching exactly, end sides not steeper than 20 degrees to the direction).
//!
//! Lines parallel to the driving direction through every vertex of the area (outer rings and
//! holes) cut it into slabs; inside a slab the area is a stack of trapezoids, each bounded by the
//! two slab lines (its parallel sides, along the driving direction) and by two edges of the area
//! (its ends, where the swaths end). Work is done in the [`SweepFrame`] of the direction, where
//! the slab lines are `across = const`.

use crate::geometry::SweepFrame;
use geo::{Coord, LineString, MultiPolygon, Polygon};

/// Across coordinates closer than this (metres) are one slab line.
const SAME_LINE_M: f64 = 1e-9;
/// Sides that differ by less than this (metres) match.
const MATCH_M: f64 = 1e-6;

/// A trapezoid of the split, in the sweep frame: between the slab lines `across.0` and
/// `across.1`, from its lower end (smaller `along`) to its upper end.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Trapezoid {
    /// The slab it lies in (index into the slab lines, ordered across).
    pub slab: usize,
    /// Its parallel sides: `across` of the left and right slab lines.
    pub across: (f64, f64),
    /// `along` of its lower end on the left and on the right side.
    pub lower: (f64, f64),
    /// `along` of its upper end on the left and on the right side.
    pub upper: (f64, f64),
}

impl Trapezoid {
    /// Its area, square metres.
    pub fn area(&self) -> f64 {
        let left = self.upper.0 - self.lower.0;
        let right = self.upper.1 - self.lower.1;
        (self.across.1 - self.across.0) * (left + right) / 2.0
    }

    /// Angle (radians) of its lower and upper end to the driving direction: π/2 when the end
    /// runs straight across, 0 when it runs along the swaths.
    pub fn end_angles(&self) -> (f64, f64) {
        let width = self.across.1 - self.across.0;
        let angle = |d: f64| width.atan2(d.abs());
        (
            angle(self.lower.1 - self.lower.0),
            angle(self.upper.1 - self.upper.0),
        )
    }
}

/// One polygon edge in the sweep frame, left end first (`c0 < c1`).
#[derive(Debug, Clone, Copy)]
struct Edge {
    c0: f64,
    a0: f64,
    c1: f64,
    a1: f64,
}

impl Edge {
    fn along_at(&self, c: f64) -> f64 {
        self.a0 + (c - self.c0) / (self.c1 - self.c0) * (self.a1 - self.a0)
    }
}

/// Splits `area` into trapezoids at the driving direction of `frame`, ordered by slab and, in a
/// slab, along it.
///
/// ```
/// use furrow::decompose::cells::split;
/// use furrow::geometry::SweepFrame;
/// use geo::{polygon, Area, MultiPolygon};
///
/// // A square with a square hole, driven north: left of the hole, beside it (below and above),
/// // right of it.
/// let field = polygon!(
///     exterior: [(x: 0., y: 0.), (x: 10., y: 0.), (x: 10., y: 10.), (x: 0., y: 10.)],
///     interiors: [[(x: 4., y: 4.), (x: 6., y: 4.), (x: 6., y: 6.), (x: 4., y: 6.)]],
/// );
/// let t = split(&MultiPolygon::new(vec![field.clone()]), &SweepFrame::new(0.0));
/// assert_eq!(t.len(), 4);
/// let total: f64 = t.iter().map(|t| t.area()).sum();
/// assert!((total - field.unsigned_area()).abs() < 1e-9);
/// ```
pub fn split(area: &MultiPolygon, frame: &SweepFrame) -> Vec<Trapezoid> {
    let mut edges: Vec<Edge> = Vec::new();
    let mut lines: Vec<f64> = Vec::new();
    for polygon in &area.0 {
        for ring in std::iter::once(polygon.exterior()).chain(polygon.interiors()) {
            for w in ring.0.windows(2) {
                let (c0, a0) = frame.project(w[0]);
                let (c1, a1) = frame.project(w[1]);
                lines.push(c0);
                if (c1 - c0).abs() > SAME_LINE_M {
                    edges.push(if c0 < c1 {
                        Edge { c0, a0, c1, a1 }
                    } else {
                        Edge {
                            c0: c1,
                            a0: a1,
                            c1: c0,
                            a1: a0,
                        }
                    });
                }
            }
        }
    }
    lines.sort_by(f64::total_cmp);
    lines.dedup_by(|a, b| (*a - *b).abs() <= SAME_LINE_M);
    edges.sort_by(|e, f| e.c0.total_cmp(&f.c0));

    let mut out = Vec::new();
    let mut active: Vec<Edge> = Vec::new();
    let mut next = 0;
    let mut crossing: Vec<(f64, Edge)> = Vec::new();
    for (slab, pair) in lines.windows(2).enumerate() {
        let (x0, x1) = (pair[0], pair[1]);
        let mid = (x0 + x1) / 2.0;
        while next < edges.len() && edges[next].c0 < mid {
            active.push(edges[next]);
            next += 1;
        }
        active.retain(|e| e.c1 > mid);
        crossing.clear();
        crossing.extend(active.iter().map(|e| (e.along_at(mid), *e)));
        crossing.sort_by(|a, b| a.0.total_cmp(&b.0));
        // Even-odd: crossings pair up into the intervals inside.
        for pair in crossing.chunks_exact(2) {
            let (lo, hi) = (pair[0].1, pair[1].1);
            out.push(Trapezoid {
                slab,
                across: (x0, x1),
                lower: (lo.along_at(x0), lo.along_at(x1)),
                upper: (hi.along_at(x0), hi.along_at(x1)),
            });
        }
    }
    out
}

/// How trapezoids of neighbouring slabs are merged into cells.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MergeRule {
    /// Boustrophedon cells (Zhou et al. 2.3.1): merged wherever the side one trapezoid leaves
    /// off is the side the next begins with, so cells break only where the slice meets or
    /// leaves an obstacle or a bay.
    Boustrophedon,
    /// Oksanen & Visala 2.4: sides matching exactly, and both trapezoids' ends at least
    /// `min_end_angle` (radians; 20 degrees in the paper) to the driving direction.
    SplitMerge {
        /// The smallest angle of an end to the driving direction that still merges.
        min_end_angle: f64,
    },
}

/// A cell: trapezoids of consecutive slabs merged, one per slab.
#[derive(Debug, Clone, PartialEq)]
pub struct Cell {
    /// Its trapezoids (indices into the split), left to right.
    pub trapezoids: Vec<usize>,
    /// Its outline in the field's metres, counter-clockwise.
    pub outline: Polygon,
}

/// Merges the trapezoids of a split into cells.
///
/// ```
/// use furrow::decompose::cells::{merge, split, MergeRule};
/// use furrow::geometry::SweepFrame;
/// use geo::{polygon, MultiPolygon};
///
/// // A U open to the north, driven north: the base's slab holds one trapezoid, the arms' two.
/// let u = polygon![
///     (x: 0., y: 0.), (x: 90., y: 0.), (x: 90., y: 90.), (x: 60., y: 90.),
///     (x: 60., y: 30.), (x: 30., y: 30.), (x: 30., y: 90.), (x: 0., y: 90.)
/// ];
/// let frame = SweepFrame::new(0.0);
/// let t = split(&MultiPolygon::new(vec![u]), &frame);
/// assert_eq!(t.len(), 3); // lines at x = 0, 30, 60, 90: three slabs
/// let cells = merge(&t, &frame, MergeRule::Boustrophedon);
/// assert_eq!(cells.len(), 3);
/// ```
pub fn merge(trapezoids: &[Trapezoid], frame: &SweepFrame, rule: MergeRule) -> Vec<Cell> {
    let n = trapezoids.len();
    // The trapezoid each one continues into, if the rule merges them.
    let mut next: Vec<Option<usize>> = vec![None; n];
    let mut has_previous = vec![false; n];
    // Trapezoids are ordered by slab; find each slab's range.
    let mut start_of: Vec<usize> = Vec::new();
    for (i, t) in trapezoids.iter().enumerate() {
        while start_of.len() <= t.slab {
            start_of.push(i);
        }
    }
    start_of.push(n);
    for (i, t) in trapezoids.iter().enumerate() {
        let (from, to) = match (start_of.get(t.slab + 1), start_of.get(t.slab + 2)) {
            (Some(&a), Some(&b)) => (a, b),
            (Some(&a), None) => (a, n),
            _ => continue,
        };
        for j in from..to {
            let u = &trapezoids[j];
            if u.slab != t.slab + 1 || (u.across.0 - t.across.1).abs() > SAME_LINE_M {
                continue;
            }
            let matching =
                (u.lower.0 - t.lower.1).abs() < MATCH_M && (u.upper.0 - t.upper.1).abs() < MATCH_M;
            let steep_enough = match rule {
                MergeRule::Boustrophedon => true,
                MergeRule::SplitMerge { min_end_angle } => {
                    let (a, b) = t.end_angles();
                    let (c, d) = u.end_angles();
                    a.min(b).min(c).min(d) >= min_end_angle
                }
            };
            if matching && steep_enough {
                next[i] = Some(j);
                has_previous[j] = true;
                break;
            }
        }
    }
    let mut cells = Vec::new();
    for (i, &continued) in has_previous.iter().enumerate() {
        if continued {
            continue;
        }
        let mut chain = vec![i];
        let mut k = i;
        while let Some(j) = next[k] {
            chain.push(j);
            k = j;
        }
        let outline = outline(trapezoids, &chain, frame);
        cells.push(Cell {
            trapezoids: chain,
            outline,
        });
    }
    cells
}

/// Cells that touch along a slab line, as `(left cell, right cell, length of the shared
/// stretch)`: the adjacency graph of the decomposition (Zhou et al. fig. 7), over which blocks
/// are merged and routes pass from one block to the next.
///
/// ```
/// use furrow::decompose::cells::{adjacency, merge, split, MergeRule};
/// use furrow::geometry::SweepFrame;
/// use geo::{polygon, MultiPolygon};
///
/// // A square with a hole: the cell left of the hole touches the cells below and above it,
/// // and so does the cell right of it; below and above do not touch.
/// let field = polygon!(
///     exterior: [(x: 0., y: 0.), (x: 10., y: 0.), (x: 10., y: 10.), (x: 0., y: 10.)],
///     interiors: [[(x: 4., y: 4.), (x: 6., y: 4.), (x: 6., y: 6.), (x: 4., y: 6.)]],
/// );
/// let frame = SweepFrame::new(0.0);
/// let t = split(&MultiPolygon::new(vec![field]), &frame);
/// let cells = merge(&t, &frame, MergeRule::Boustrophedon);
/// let edges = adjacency(&t, &cells);
/// assert_eq!(edges.len(), 4);
/// assert!(edges.iter().all(|&(_, _, shared)| (shared - 4.0).abs() < 1e-9));
/// ```
pub fn adjacency(trapezoids: &[Trapezoid], cells: &[Cell]) -> Vec<(usize, usize, f64)> {
    let mut cell_of = vec![usize::MAX; trapezoids.len()];
    for (c, cell) in cells.iter().enumerate() {
        for &t in &cell.trapezoids {
            if let Some(slot) = cell_of.get_mut(t) {
                *slot = c;
            }
        }
    }
    let mut out: Vec<(usize, usize, f64)> = Vec::new();
    for (i, t) in trapezoids.iter().enumerate() {
        for (j, u) in trapezoids.iter().enumerate().skip(i + 1) {
            if u.slab > t.slab + 1 {
                break;
            }
            if u.slab != t.slab + 1 || (u.across.0 - t.across.1).abs() > SAME_LINE_M {
                continue;
            }
            let shared = t.upper.1.min(u.upper.0) - t.lower.1.max(u.lower.0);
            let (a, b) = (cell_of[i], cell_of[j]);
            if shared > MATCH_M && a != b {
                match out.iter_mut().find(|e| e.0 == a && e.1 == b) {
                    Some(e) => e.2 += shared,
                    None => out.push((a, b, shared)),
                }
            }
        }
    }
    out
}

/// The outline of a chain of trapezoids: along the lower ends left to right, back along the
/// upper ends.
fn outline(trapezoids: &[Trapezoid], chain: &[usize], frame: &SweepFrame) -> Polygon {
    let mut pts: Vec<Coord> = Vec::with_capacity(2 * chain.len() + 3);
    for (k, &i) in chain.iter().enumerate() {
        let t = &trapezoids[i];
        if k == 0 {
            pts.push(frame.point(t.across.0, t.lower.0));
        }
        pts.push(frame.point(t.across.1, t.lower.1));
    }
    for (k, &i) in chain.iter().enumerate().rev() {
        let t = &trapezoids[i];
        pts.push(frame.point(t.across.1, t.upper.1));
        if k == 0 {
            pts.push(frame.point(t.across.0, t.upper.0));
        }
    }
    // Where a trapezoid's ends meet at a side (a triangle), its two points coincide. (Not the
    // ring cleaning of the input: that takes sharp tips for spikes.)
    pts.dedup_by(|a, b| (a.x - b.x).hypot(a.y - b.y) < MATCH_M);
    while pts.len() > 1
        && pts
            .first()
            .zip(pts.last())
            .is_some_and(|(a, b)| (a.x - b.x).hypot(a.y - b.y) < MATCH_M)
    {
        pts.pop();
    }
    // The sweep frame (across, along) is right-handed like (east, north): lower ends left to
    // right, then upper ends back, runs counter-clockwise.
    if let Some(&first) = pts.first() {
        pts.push(first);
    }
    Polygon::new(LineString::new(pts), vec![])
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{polygon, Area, BooleanOps};
    use proptest::prelude::*;

    fn total(t: &[Trapezoid]) -> f64 {
        t.iter().map(Trapezoid::area).sum()
    }

    #[test]
    fn a_convex_field_is_one_cell_either_way() {
        let field = polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 80., y: 60.), (x: 10., y: 50.)];
        let frame = SweepFrame::new(0.3);
        let t = split(&MultiPolygon::new(vec![field.clone()]), &frame);
        assert_eq!(t.len(), 3); // four vertices, three slabs
        let cells = merge(&t, &frame, MergeRule::Boustrophedon);
        assert_eq!(cells.len(), 1);
        assert!((cells[0].outline.unsigned_area() - field.unsigned_area()).abs() < 1e-6);
        assert!(cells[0].outline.signed_area() > 0.0, "counter-clockwise");
    }

    #[test]
    fn split_merge_keeps_ends_nearly_along_the_swaths_apart() {
        // A rectangle 100 m across and a sliver triangle on its right whose ends run at about
        // 6 degrees to the north-running swaths.
        let field = polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 110., y: 95.), (x: 100., y: 100.), (x: 0., y: 100.)];
        let frame = SweepFrame::new(0.0);
        let t = split(&MultiPolygon::new(vec![field]), &frame);
        let bous = merge(&t, &frame, MergeRule::Boustrophedon);
        assert_eq!(bous.len(), 1);
        let oksanen = merge(
            &t,
            &frame,
            MergeRule::SplitMerge {
                min_end_angle: 20f64.to_radians(),
            },
        );
        assert_eq!(oksanen.len(), 2);
    }

    #[test]
    fn holes_split_the_field_into_four_boustrophedon_cells() {
        let field = polygon!(
            exterior: [(x: 0., y: 0.), (x: 100., y: 0.), (x: 100., y: 60.), (x: 0., y: 60.)],
            interiors: [[(x: 40., y: 20.), (x: 60., y: 25.), (x: 55., y: 40.), (x: 42., y: 38.)]],
        );
        let frame = SweepFrame::new(0.0);
        let t = split(&MultiPolygon::new(vec![field.clone()]), &frame);
        let cells = merge(&t, &frame, MergeRule::Boustrophedon);
        assert_eq!(cells.len(), 4);
        let sum: f64 = cells.iter().map(|c| c.outline.unsigned_area()).sum();
        assert!((sum - field.unsigned_area()).abs() < 1e-6);
    }

    proptest! {
        /// On random star-shaped fields with a hole, at random directions, the trapezoids and the
        /// cells partition the field: their areas add up to its area, and cells do not overlap.
        #[test]
        fn cells_partition_the_field(
            radii in proptest::collection::vec(30.0..100.0f64, 3..14),
            hole in proptest::option::of((-10.0..10.0f64, -10.0..10.0f64, 2.0..15.0f64)),
            bearing in 0.0..std::f64::consts::PI,
            split_merge in any::<bool>(),
        ) {
            let n = radii.len();
            let ring: Vec<Coord> = radii.iter().enumerate().map(|(i, r)| {
                let t = i as f64 / n as f64 * std::f64::consts::TAU;
                Coord { x: r * t.cos(), y: r * t.sin() }
            }).collect();
            let interiors = hole.map(|(x, y, r)| {
                let pts: Vec<Coord> = (0..6).rev().map(|k| {
                    let t = k as f64 / 6.0 * std::f64::consts::TAU;
                    Coord { x: x + r * t.cos(), y: y + r * t.sin() }
                }).collect();
                vec![LineString::from(pts)]
            }).unwrap_or_default();
            let outer = Polygon::new(LineString::from(ring), vec![]);
            for h in &interiors {
                use geo::Contains;
                prop_assume!(outer.contains(&Polygon::new(h.clone(), vec![])));
            }
            let field = Polygon::new(outer.exterior().clone(), interiors);
            let area = field.unsigned_area();
            let frame = SweepFrame::new(bearing);
            let t = split(&MultiPolygon::new(vec![field]), &frame);
            prop_assert!((total(&t) - area).abs() < 1e-6 * area);
            let rule = if split_merge {
                MergeRule::SplitMerge { min_end_angle: 20f64.to_radians() }
            } else {
                MergeRule::Boustrophedon
            };
            let cells = merge(&t, &frame, rule);
            let sum: f64 = cells.iter().map(|c| c.outline.unsigned_area()).sum();
            prop_assert!((sum - area).abs() < 1e-6 * area, "{} vs {}", sum, area);
            // The field is one piece, so its cells form one connected graph.
            let edges = adjacency(&t, &cells);
            let mut reached = vec![false; cells.len()];
            reached[0] = true;
            let mut changed = true;
            while changed {
                changed = false;
                for &(a, b, shared) in &edges {
                    prop_assert!(a != b && a < cells.len() && b < cells.len() && shared > 0.0);
                    if reached[a] != reached[b] {
                        reached[a] = true;
                        reached[b] = true;
                        changed = true;
                    }
                }
            }
            prop_assert!(reached.iter().all(|&r| r), "cells not connected: {:?}", edges);
            for (i, a) in cells.iter().enumerate() {
                for b in &cells[i + 1..] {
                    let overlap = MultiPolygon::new(vec![a.outline.clone()])
                        .intersection(&MultiPolygon::new(vec![b.outline.clone()]))
                        .unsigned_area();
                    prop_assert!(overlap < 1e-6 * area, "cells overlap by {}", overlap);
                }
            }
        }
    }
}
