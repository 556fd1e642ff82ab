//! Cells of an area at a driving direction: the trapezoidal split (Oksanen & Visala 2.3) and the
//! merges that make blocks of it, boustrophedon (Zhou et al. 2.3.1, after Choset) or Oksanen's
//! (2.4: sides matching exactly, end sides not steeper than 20 degrees to the direction).
//!
//! Lines parallel to the driving direction through every vertex of the area (outer rings and
//! holes) cut it into slabs; inside a slab the area is a stack of trapezoids, each bounded by the
//! two slab lines (its parallel sides, along the driving direction) and by two edges of the area
//! (its ends, where the swaths end). Work is done in the [`SweepFrame`] of the direction, where
//! the slab lines are `across = const`.

use crate::geometry::simplify::planar_simplify_idx;
use crate::geometry::PlanarHypot;
use crate::geometry::SweepFrame;
use crate::sort::{sort_floats, SharedSort};
use geo::{Coord, LineString, MultiPolygon, Polygon};

/// Across coordinates closer than this (metres) are one slab line.
const SAME_LINE_M: f64 = 1e-6;
/// Sides that differ by less than this (metres) match.
const MATCH_M: f64 = 1e-6;

/// A trapezoid of the split, in the sweep frame: between the slab lines `across.0` and
/// `across.1`, from its lower end (smaller `along`) to its upper end.
///
/// Its ends are stretches of the area's boundary. Split with tolerance 0 they are straight
/// edges and the trapezoid is one in the strict sense; with a tolerance, the vertices of a curve
/// that lie within it of a straight line draw no slab line, and an end is the curve between two
/// slab lines: a polyline running monotonically across, within the tolerance of its chord.
#[derive(Debug, Clone, PartialEq)]
pub struct Trapezoid {
    /// The slab it lies in (index into the slab lines, ordered across).
    pub slab: usize,
    /// Its parallel sides: `across` of the left and right slab lines.
    pub across: (f64, f64),
    /// `along` of its lower end on the left and on the right side.
    pub lower: (f64, f64),
    /// `along` of its upper end on the left and on the right side.
    pub upper: (f64, f64),
    /// The lower end, `(across, along)` points from left to right.
    pub lower_end: Vec<(f64, f64)>,
    /// The upper end, `(across, along)` points from left to right.
    pub upper_end: Vec<(f64, f64)>,
}

impl Trapezoid {
    /// Its area, square metres.
    pub fn area(&self) -> f64 {
        chain_integral(&self.upper_end) - chain_integral(&self.lower_end)
    }

    /// Angle (radians) of the chords of its lower and upper end to the driving direction: π/2
    /// when the end runs straight across, 0 when it runs along the swaths.
    pub fn end_angles(&self) -> (f64, f64) {
        let width = self.across.1 - self.across.0;
        let angle = |d: f64| width.atan2(d.abs());
        (
            angle(self.lower.1 - self.lower.0),
            angle(self.upper.1 - self.upper.0),
        )
    }

    /// Whether both ends' chords make an angle with the driving direction whose tangent is at
    /// least `tan_min` (the same test as [`Trapezoid::end_angles`], without the arctangents).
    pub fn ends_steeper_than(&self, tan_min: f64) -> bool {
        let width = self.across.1 - self.across.0;
        let steep = |d: f64| width >= d.abs() * tan_min;
        steep(self.lower.1 - self.lower.0) && steep(self.upper.1 - self.upper.0)
    }

    /// `along` of its lower and upper end at `across` (clamped to its slab).
    pub fn ends_at(&self, across: f64) -> (f64, f64) {
        (
            chain_at(&self.lower_end, across),
            chain_at(&self.upper_end, across),
        )
    }
}

/// The integral of `along` over `across` under a chain running left to right.
fn chain_integral(chain: &[(f64, f64)]) -> f64 {
    chain
        .windows(2)
        .map(|w| (w[1].0 - w[0].0) * (w[0].1 + w[1].1) / 2.0)
        .sum()
}

/// `along` of a chain running left to right at `across` (clamped to its ends).
fn chain_at(chain: &[(f64, f64)], c: f64) -> f64 {
    let i = chain.partition_point(|p| p.0 < c);
    match (i.checked_sub(1).and_then(|j| chain.get(j)), chain.get(i)) {
        (Some(&(c0, a0)), Some(&(c1, a1))) if c1 - c0 > 0.0 => {
            a0 + (c - c0) / (c1 - c0) * (a1 - a0)
        }
        (_, Some(&(_, a))) | (Some(&(_, a)), None) => a,
        (None, None) => 0.0,
    }
}

/// Splits `area` into trapezoids at the driving direction of `frame`, ordered by slab and, in a
/// slab, along it.
///
/// Slab lines run through every vertex where the boundary turns back across the direction (a
/// vertex that is not strictly between its neighbours in `across`: there the number of pieces
/// of a swath line changes) and through every vertex that the Douglas-Peucker simplification of
/// its ring by `tolerance` (metres) keeps. With tolerance 0 that is every vertex, Oksanen &
/// Visala's split (2.3); with a tolerance of a fraction of the working width, a curved edge
/// drawn with many vertices (a rounded headland corner, a GNSS-recorded boundary) no longer
/// cuts the area into slivers one vertex apart, and the pieces still partition the area exactly.
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
/// let t = split(&MultiPolygon::new(vec![field.clone()]), &SweepFrame::new(0.0), 0.0);
/// assert_eq!(t.len(), 4);
/// let total: f64 = t.iter().map(|t| t.area()).sum();
/// assert!((total - field.unsigned_area()).abs() < 1e-9);
/// ```
pub fn split(area: &MultiPolygon, frame: &SweepFrame, tolerance: f64) -> Vec<Trapezoid> {
    split_prepared(&PreparedArea::new(area, tolerance), frame)
}

/// An area ready to be split at many directions: its rings, and which vertices the
/// simplification keeps (that does not depend on the direction).
#[derive(Debug, Clone, Default)]
pub struct PreparedArea {
    rings: Vec<(Vec<Coord>, Vec<bool>)>,
}

impl PreparedArea {
    /// Prepares `area` for splits with the given simplification tolerance (metres).
    pub fn new(area: &MultiPolygon, tolerance: f64) -> Self {
        let mut rings = Vec::new();
        for polygon in &area.0 {
            for ring in std::iter::once(polygon.exterior()).chain(polygon.interiors()) {
                let mut pts: Vec<Coord> = ring.0.clone();
                if pts.len() > 1 && pts.first() == pts.last() {
                    pts.pop();
                }
                let n = pts.len();
                if n < 3 {
                    continue;
                }
                let mut kept = vec![tolerance <= 0.0; n];
                if tolerance > 0.0 {
                    for i in planar_simplify_idx(ring, tolerance) {
                        if let Some(m) = kept.get_mut(i % n) {
                            *m = true;
                        }
                    }
                }
                rings.push((pts, kept));
            }
        }
        PreparedArea { rings }
    }

    /// The area with only the vertices the simplification keeps: within the tolerance of the
    /// area, with far fewer vertices where its edges curve, for splits that only estimate (a
    /// direction search scoring cells).
    pub fn simplified(&self) -> PreparedArea {
        let rings = self
            .rings
            .iter()
            .filter_map(|(pts, kept)| {
                let pts: Vec<Coord> = pts
                    .iter()
                    .zip(kept)
                    .filter(|(_, &k)| k)
                    .map(|(&p, _)| p)
                    .collect();
                (pts.len() >= 3).then(|| {
                    let n = pts.len();
                    (pts, vec![true; n])
                })
            })
            .collect();
        PreparedArea { rings }
    }
}

/// [`split`] of a prepared area.
pub fn split_prepared(area: &PreparedArea, frame: &SweepFrame) -> Vec<Trapezoid> {
    let (rings, lines) = slab_lines(area, frame);
    if lines.len() < 2 {
        return Vec::new();
    }
    // The slab line a coordinate lies on, if any.
    let on_line = |c: f64| -> Option<usize> {
        let i = lines.partition_point(|&l| l < c - SAME_LINE_M);
        lines
            .get(i)
            .filter(|&&l| (l - c).abs() <= SAME_LINE_M)
            .map(|_| i)
    };
    // Each ring cut at the slab lines into chains running from one line to the next.
    let mut chains: Vec<Vec<Vec<(f64, f64)>>> = vec![Vec::new(); lines.len() - 1];
    let mut emit = |chain: &mut Vec<(f64, f64)>, last: (f64, f64)| {
        // A chain between two slab lines is mostly a piece of one edge: two points.
        let mut next = Vec::with_capacity(4);
        next.push(last);
        let mut done = std::mem::replace(chain, next);
        let (Some(&first), Some(&end)) = (done.first(), done.last()) else {
            return;
        };
        if (end.0 - first.0).abs() <= SAME_LINE_M {
            return; // along a slab line
        }
        if first.0 > end.0 {
            done.reverse();
        }
        if let Some(slab) = on_line(done[0].0).filter(|&s| s + 1 < lines.len()) {
            chains[slab].push(done);
        }
    };
    for pts in &rings {
        let n = pts.len();
        // Start at the leftmost vertex: it always lies on a slab line.
        let s = (0..n)
            .min_by(|&i, &j| pts[i].0.total_cmp(&pts[j].0))
            .unwrap_or(0);
        let snap = |p: (f64, f64)| on_line(p.0).map_or(p, |i| (lines[i], p.1));
        let mut prev = snap(pts[s]);
        let mut chain = vec![prev];
        for k in 1..=n {
            let q = snap(pts[(s + k) % n]);
            let (lo, hi) = (prev.0.min(q.0), prev.0.max(q.0));
            let from = lines.partition_point(|&l| l <= lo + SAME_LINE_M);
            let to = lines.partition_point(|&l| l < hi - SAME_LINE_M);
            let between = lines.get(from..to).unwrap_or(&[]);
            let crossing = |x: f64| (x, prev.1 + (x - prev.0) / (q.0 - prev.0) * (q.1 - prev.1));
            if q.0 > prev.0 {
                for &x in between {
                    let p = crossing(x);
                    chain.push(p);
                    emit(&mut chain, p);
                }
            } else {
                for &x in between.iter().rev() {
                    let p = crossing(x);
                    chain.push(p);
                    emit(&mut chain, p);
                }
            }
            chain.push(q);
            if on_line(q.0).is_some() {
                emit(&mut chain, q);
            }
            prev = q;
        }
    }
    let mut out = Vec::new();
    for (slab, mut in_slab) in chains.into_iter().enumerate() {
        let (x0, x1) = (lines[slab], lines[slab + 1]);
        let mid = (x0 + x1) / 2.0;
        in_slab.shared_sort_by_float_key(|c| chain_at(c, mid));
        // Even-odd: the chains pair up into the pieces inside.
        let mut it = in_slab.into_iter();
        while let (Some(lo), Some(hi)) = (it.next(), it.next()) {
            let end = |c: &[(f64, f64)]| (c[0].1, c[c.len() - 1].1);
            out.push(Trapezoid {
                slab,
                across: (x0, x1),
                lower: end(&lo),
                upper: end(&hi),
                lower_end: lo,
                upper_end: hi,
            });
        }
    }
    out
}

/// The area's rings in the sweep frame, and the slab lines: across every vertex the
/// simplification keeps and every turn of direction across the sweep, sorted, one per place.
fn slab_lines(area: &PreparedArea, frame: &SweepFrame) -> (Vec<Vec<(f64, f64)>>, Vec<f64>) {
    let mut rings: Vec<Vec<(f64, f64)>> = Vec::with_capacity(area.rings.len());
    let mut lines: Vec<f64> = Vec::new();
    for (ring, kept) in &area.rings {
        let pts: Vec<(f64, f64)> = ring.iter().map(|&p| frame.project(p)).collect();
        let n = pts.len();
        for i in 0..n {
            let (p, c, q) = (pts[(i + n - 1) % n].0, pts[i].0, pts[(i + 1) % n].0);
            let monotone = (p < c - SAME_LINE_M && c < q - SAME_LINE_M)
                || (p > c + SAME_LINE_M && c > q + SAME_LINE_M);
            if kept[i] || !monotone {
                lines.push(c);
            }
        }
        rings.push(pts);
    }
    sort_floats(&mut lines);
    lines.dedup_by(|a, b| (*a - *b).abs() <= SAME_LINE_M);
    (rings, lines)
}

/// About how many trapezoids [`split_prepared`] would make of `area`, without making them: half
/// the pieces the slab lines cut its edges into. An outline noisy across the sweep has a slab
/// line at nearly every vertex, each crossing the outline many times: the count grows with the
/// square of its vertices.
pub fn trapezoid_estimate(area: &PreparedArea, frame: &SweepFrame) -> usize {
    let (rings, lines) = slab_lines(area, frame);
    let mut pieces = 0usize;
    for pts in &rings {
        for (k, &a) in pts.iter().enumerate() {
            let b = pts[(k + 1) % pts.len()];
            let (lo, hi) = (a.0.min(b.0), a.0.max(b.0));
            let from = lines.partition_point(|&l| l <= lo + SAME_LINE_M);
            let to = lines.partition_point(|&l| l < hi - SAME_LINE_M);
            pieces = pieces.saturating_add(to.saturating_sub(from) + 1);
        }
    }
    pieces / 2
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
/// let t = split(&MultiPolygon::new(vec![u]), &frame, 0.0);
/// assert_eq!(t.len(), 3); // lines at x = 0, 30, 60, 90: three slabs
/// let cells = merge(&t, &frame, MergeRule::Boustrophedon);
/// assert_eq!(cells.len(), 3);
/// ```
pub fn merge(trapezoids: &[Trapezoid], frame: &SweepFrame, rule: MergeRule) -> Vec<Cell> {
    merge_chains(trapezoids, rule)
        .into_iter()
        .map(|chain| Cell {
            outline: outline(trapezoids, &chain, frame),
            trapezoids: chain,
        })
        .collect()
}

/// The cells of [`merge`] as chains of trapezoids (indices, left to right), without outlines.
pub fn merge_chains(trapezoids: &[Trapezoid], rule: MergeRule) -> Vec<Vec<usize>> {
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
        // The next slab's trapezoids are ordered along it: the one that may match starts where
        // this one's right side starts.
        let Some(slab) = trapezoids.get(from..to) else {
            continue;
        };
        let j = from + slab.partition_point(|u| u.lower.0 < t.lower.1 - MATCH_M);
        let Some(u) = trapezoids.get(j).filter(|_| j < to) else {
            continue;
        };
        if u.slab != t.slab + 1 || (u.across.0 - t.across.1).abs() > SAME_LINE_M {
            continue;
        }
        let matching =
            (u.lower.0 - t.lower.1).abs() < MATCH_M && (u.upper.0 - t.upper.1).abs() < MATCH_M;
        let steep_enough = match rule {
            MergeRule::Boustrophedon => true,
            MergeRule::SplitMerge { min_end_angle } => {
                let tan = min_end_angle.tan();
                matching && t.ends_steeper_than(tan) && u.ends_steeper_than(tan)
            }
        };
        if matching && steep_enough {
            next[i] = Some(j);
            has_previous[j] = true;
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
        cells.push(chain);
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
/// let t = split(&MultiPolygon::new(vec![field]), &frame, 0.0);
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

/// The outline of a chain of trapezoids (a cell): along the lower ends left to right, back
/// along the upper ends, counter-clockwise.
pub fn outline(trapezoids: &[Trapezoid], chain: &[usize], frame: &SweepFrame) -> Polygon {
    let mut pts: Vec<Coord> = Vec::with_capacity(4 * chain.len() + 3);
    for (k, &i) in chain.iter().enumerate() {
        let end = &trapezoids[i].lower_end;
        let skip = usize::from(k > 0);
        pts.extend(end.iter().skip(skip).map(|&(c, a)| frame.point(c, a)));
    }
    for (k, &i) in chain.iter().enumerate().rev() {
        let end = &trapezoids[i].upper_end;
        let skip = usize::from(k + 1 < chain.len());
        pts.extend(end.iter().rev().skip(skip).map(|&(c, a)| frame.point(c, a)));
    }
    // Where a trapezoid's ends meet at a side (a triangle), its two points coincide. (Not the
    // ring cleaning of the input: that takes sharp tips for spikes.)
    pts.dedup_by(|a, b| (a.x - b.x).planar_hypot(a.y - b.y) < MATCH_M);
    while pts.len() > 1
        && pts
            .first()
            .zip(pts.last())
            .is_some_and(|(a, b)| (a.x - b.x).planar_hypot(a.y - b.y) < MATCH_M)
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

    /// A comb of `fingers` fingers 1 m wide, 1 m apart, pointing east from a spine, their tips
    /// a centimetre apart across: every slab line driving north crosses every finger.
    fn comb(fingers: usize) -> MultiPolygon {
        let mut ring = vec![Coord { x: 0.0, y: 0.0 }];
        for k in 0..fingers {
            let (y, tip) = (2.0 * k as f64, 100.0 + 0.01 * k as f64);
            ring.extend([
                Coord { x: 10.0, y },
                Coord { x: tip, y },
                Coord { x: tip, y: y + 1.0 },
                Coord {
                    x: 10.0,
                    y: y + 1.0,
                },
            ]);
        }
        ring.push(Coord {
            x: 0.0,
            y: 2.0 * fingers as f64,
        });
        MultiPolygon::new(vec![Polygon::new(LineString::new(ring), vec![])])
    }

    #[test]
    fn the_estimate_counts_the_trapezoids_of_the_split() {
        let pond = polygon!(
            exterior: [(x: 0., y: 0.), (x: 60., y: 0.), (x: 60., y: 100.), (x: 0., y: 100.)],
            interiors: [[(x: 20., y: 40.), (x: 40., y: 40.), (x: 35., y: 60.), (x: 20., y: 55.)]],
        );
        for (area, bearing) in [
            (MultiPolygon::new(vec![pond]), 0.3),
            (comb(40), 0.0),
            (comb(40), 1.0),
        ] {
            let prepared = PreparedArea::new(&area, 0.0);
            let frame = SweepFrame::new(bearing);
            let made = split_prepared(&prepared, &frame).len();
            let estimate = trapezoid_estimate(&prepared, &frame);
            assert!(
                estimate >= made && estimate <= made + made / 10 + 4,
                "{estimate} for {made}"
            );
        }
        // Driving north, the slab line of each finger's tip crosses the fingers longer than it:
        // n² / 2 trapezoids.
        let estimate =
            trapezoid_estimate(&PreparedArea::new(&comb(1_500), 0.0), &SweepFrame::new(0.0));
        assert!(estimate > 1_100_000, "{estimate}");
    }

    #[test]
    fn a_convex_field_is_one_cell_either_way() {
        let field = polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 80., y: 60.), (x: 10., y: 50.)];
        let frame = SweepFrame::new(0.3);
        let t = split(&MultiPolygon::new(vec![field.clone()]), &frame, 0.0);
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
        let t = split(&MultiPolygon::new(vec![field]), &frame, 0.0);
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
        let t = split(&MultiPolygon::new(vec![field.clone()]), &frame, 0.0);
        let cells = merge(&t, &frame, MergeRule::Boustrophedon);
        assert_eq!(cells.len(), 4);
        let sum: f64 = cells.iter().map(|c| c.outline.unsigned_area()).sum();
        assert!((sum - field.unsigned_area()).abs() < 1e-6);
    }

    #[test]
    fn a_tolerance_keeps_a_curved_edge_from_shattering_the_split() {
        // A 200 x 100 field whose north edge is a half circle drawn with 180 vertices.
        let mut pts = vec![Coord { x: 0.0, y: 0.0 }, Coord { x: 200.0, y: 0.0 }];
        for k in 0..=180 {
            let t = (k as f64).to_radians();
            pts.push(Coord {
                x: 100.0 + 100.0 * t.cos(),
                y: 100.0 + 100.0 * t.sin(),
            });
        }
        let field = MultiPolygon::new(vec![Polygon::new(LineString::from(pts), vec![])]);
        let area = field.unsigned_area();
        let frame = SweepFrame::new(0.0);
        let exact = split(&field, &frame, 0.0);
        let simplified = split(&field, &frame, 3.0);
        assert!(exact.len() > 150, "{} trapezoids", exact.len());
        assert!(simplified.len() < 20, "{} trapezoids", simplified.len());
        // Both partition the field exactly: the curved ends follow the arc.
        for t in [&exact, &simplified] {
            assert!((total(t) - area).abs() < 1e-6 * area);
        }
        // Split and merge's cells: the curve's ends are steep enough in the middle only.
        let cells = merge(
            &simplified,
            &frame,
            MergeRule::SplitMerge {
                min_end_angle: 20f64.to_radians(),
            },
        );
        let sum: f64 = cells.iter().map(|c| c.outline.unsigned_area()).sum();
        assert!((sum - area).abs() < 1e-6 * area);
        assert!(
            cells.len() >= 2 && cells.len() < 10,
            "{} cells",
            cells.len()
        );
    }

    proptest! {
        #![proptest_config(crate::seeded::config(256))]
        /// On random star-shaped fields with a hole, at random directions, the trapezoids and the
        /// cells partition the field: their areas add up to its area, and cells do not overlap.
        #[test]
        fn cells_partition_the_field(
            radii in proptest::collection::vec(30.0..100.0f64, 3..14),
            hole in proptest::option::of((-10.0..10.0f64, -10.0..10.0f64, 2.0..15.0f64)),
            bearing in 0.0..std::f64::consts::PI,
            split_merge in any::<bool>(),
            tolerance in prop_oneof![Just(0.0), 0.0..20.0f64],
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
            let t = split(&MultiPolygon::new(vec![field]), &frame, tolerance);
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
