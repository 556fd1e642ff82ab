//! Boustrophedon decomposition (Zhou et al. 2.3, after Choset): the inner field at one driving
//! direction cut into cells that can each be worked back and forth without leaving them.
//!
//! A slice parallel to the direction sweeps across the area; the trapezoidal split of
//! [`super::cells`] puts an event at every vertex of the inner field and of the obstacle
//! headlands, and its trapezoids are the preliminary blocks. Preliminary blocks of neighbouring
//! slabs that share a full edge are merged, so that cells only break where the slice meets an
//! obstacle or a bay (an *in* event) or leaves one (*out*). The adjacency graph joins cells that
//! touch along the slice. Swaths of the direction are then clustered into the cells
//! (Zhou et al. 2.3.2): each swath piece lies in exactly one slab, in one trapezoid of it.

use super::cells::{
    adjacency, merge, split, trapezoid_estimate, Cell, MergeRule, PreparedArea, Trapezoid,
};
use crate::geometry::SweepFrame;
use crate::sort::SharedSort;
use crate::swath::{sort_lifts, Swath, SwathArea, Swaths};
use geo::MultiPolygon;

/// Across coordinates (metres) within which a point counts as on a slab line.
const ON_LINE_M: f64 = 1e-6;

/// The most trapezoids (about) the sweep may cut an area into for boustrophedon cells: a noisy
/// outline of 199,000 vertices at 0.1 m cut into 6 million took 7 s and 2 GB natively; the
/// corpus's fields are cut into at most a few thousand.
pub const MAX_TRAPEZOIDS: usize = 1_000_000;

/// Whether boustrophedon cells take on `area` at `bearing` (compass radians), split with the
/// simplification `tolerance` (metres): at most about [`MAX_TRAPEZOIDS`] trapezoids; else why
/// not, as a sentence.
///
/// ```
/// use furrow::decompose::boustrophedon::within_limits;
/// use geo::{polygon, MultiPolygon};
///
/// let field = polygon![(x: 0., y: 0.), (x: 300., y: 0.), (x: 300., y: 200.), (x: 0., y: 200.)];
/// assert!(within_limits(&MultiPolygon::new(vec![field]), 0.0, 0.1).is_ok());
/// ```
pub fn within_limits(area: &MultiPolygon, bearing: f64, tolerance: f64) -> Result<(), String> {
    let prepared = PreparedArea::new(area, tolerance);
    let trapezoids = trapezoid_estimate(&prepared, &SweepFrame::new(bearing));
    if trapezoids > MAX_TRAPEZOIDS {
        return Err(format!(
            "the sweep across its inner field cuts it into about {trapezoids} trapezoids (boustrophedon cells take on up to {MAX_TRAPEZOIDS})"
        ));
    }
    Ok(())
}

/// The boustrophedon cells of an area at one direction.
#[derive(Debug, Clone)]
pub struct BoustrophedonCells {
    /// The frame of the direction.
    pub frame: SweepFrame,
    /// The trapezoids of the split (the preliminary blocks).
    pub trapezoids: Vec<Trapezoid>,
    /// The cells, each a chain of trapezoids, in the order the sweep closes them.
    pub cells: Vec<Cell>,
    /// The cell of each trapezoid.
    cell_of: Vec<usize>,
}

/// Sweeps `area` at swath direction `bearing` (compass radians) into boustrophedon cells; the
/// split draws slab lines through the vertices the simplification of each ring by `tolerance`
/// metres keeps (see [`split`]).
///
/// ```
/// use furrow::decompose::boustrophedon::decompose;
/// use geo::{polygon, Area, MultiPolygon};
///
/// // A 60 x 100 field with a pond in its middle, driven north: the cells left of the pond,
/// // below it, above it and right of it.
/// let field = polygon!(
///     exterior: [(x: 0., y: 0.), (x: 60., y: 0.), (x: 60., y: 100.), (x: 0., y: 100.)],
///     interiors: [[(x: 20., y: 40.), (x: 40., y: 40.), (x: 40., y: 60.), (x: 20., y: 60.)]],
/// );
/// let cells = decompose(&MultiPolygon::new(vec![field.clone()]), 0.0, 0.0);
/// assert_eq!(cells.cells.len(), 4);
/// let sum: f64 = cells.cells.iter().map(|c| c.outline.unsigned_area()).sum();
/// assert!((sum - field.unsigned_area()).abs() < 1e-6);
/// // The side cells touch the cells below and above the pond.
/// assert_eq!(cells.adjacency().len(), 4);
/// ```
pub fn decompose(area: &MultiPolygon, bearing: f64, tolerance: f64) -> BoustrophedonCells {
    let frame = SweepFrame::new(bearing);
    let trapezoids = split(area, &frame, tolerance);
    let cells = merge(&trapezoids, &frame, MergeRule::Boustrophedon);
    let mut cell_of = vec![usize::MAX; trapezoids.len()];
    for (c, cell) in cells.iter().enumerate() {
        for &t in &cell.trapezoids {
            if let Some(slot) = cell_of.get_mut(t) {
                *slot = c;
            }
        }
    }
    BoustrophedonCells {
        frame,
        trapezoids,
        cells,
        cell_of,
    }
}

impl BoustrophedonCells {
    /// The adjacency graph: `(left cell, right cell, length of the common stretch)` for cells
    /// touching along a slab line.
    pub fn adjacency(&self) -> Vec<(usize, usize, f64)> {
        adjacency(&self.trapezoids, &self.cells)
    }

    /// The cell holding the point at `(across, along)` in the frame: the trapezoid whose slab
    /// and ends enclose it, or the nearest one within `margin` across (metres) of its slab and
    /// any distance along it.
    pub fn cell_at(&self, across: f64, along: f64, margin: f64) -> Option<usize> {
        let reach = margin.max(0.0) + ON_LINE_M;
        let from = self
            .trapezoids
            .partition_point(|t| t.across.1 < across - reach);
        let mut best: Option<(f64, usize)> = None;
        for (i, t) in self.trapezoids.iter().enumerate().skip(from) {
            if t.across.0 > across + reach {
                break;
            }
            if t.across.1 < across - reach {
                continue;
            }
            let at = across.max(t.across.0).min(t.across.1);
            let (lo, hi) = t.ends_at(at);
            let miss = (lo - along)
                .max(along - hi)
                .max(t.across.0 - across)
                .max(across - t.across.1)
                .max(0.0);
            if best.is_none_or(|(m, _)| miss < m) {
                best = Some((miss, i));
            }
        }
        best.and_then(|(_, i)| self.cell_of.get(i).copied())
    }
}

/// Clusters the swaths (all of the cells' direction) into the cells: reorders them cell by
/// cell, in line order within a cell, renumbers them, and replaces their areas by one area per
/// cell (cells no swath reaches get an empty one, so that the areas still cover the field).
/// Swaths that fill what the others leave ([`SwathArea::fill`], after the others) keep their
/// numbers and areas, after the cells'.
pub fn cluster_into_cells(swaths: &mut Swaths, cells: &BoustrophedonCells) {
    let frame = cells.frame;
    // A swath reaching into the inner field from the headland lies up to a quarter width beside it.
    let reach = swaths.width / 4.0;
    let fill_from = swaths.first_fill_swath();
    let fill_swaths = swaths.swaths.split_off(fill_from);
    let fill_areas: Vec<SwathArea> = swaths.areas.iter().filter(|a| a.fill).cloned().collect();
    let mut keyed: Vec<(usize, Swath)> = swaths
        .swaths
        .iter()
        .map(|s| {
            let (c, a) = frame.project((s.centre.start + s.centre.end) / 2.0);
            (cells.cell_at(c, a, reach).unwrap_or(usize::MAX), *s)
        })
        .collect();
    // Stable: within a cell the swaths keep their line order.
    keyed.shared_sort_by_key(|(cell, _)| *cell);
    let mut renumber = vec![0; swaths.swaths.len()];
    let mut areas: Vec<SwathArea> = Vec::with_capacity(cells.cells.len());
    let mut out: Vec<Swath> = Vec::with_capacity(keyed.len());
    let mut k = 0;
    for (c, cell) in cells.cells.iter().enumerate() {
        let start = out.len();
        while k < keyed.len() && keyed[k].0 == c {
            let mut s = keyed[k].1;
            renumber[s.index] = out.len();
            s.index = out.len();
            out.push(s);
            k += 1;
        }
        areas.push(SwathArea {
            swaths: start..out.len(),
            bearing: swaths.bearing,
            region: None,
            area: MultiPolygon::new(vec![cell.outline.clone()]),
            fill: false,
        });
    }
    // Swaths no cell holds (none, unless the swaths were cut from another area): one more area.
    if k < keyed.len() {
        let start = out.len();
        for (_, mut s) in keyed.drain(k..) {
            renumber[s.index] = out.len();
            s.index = out.len();
            out.push(s);
        }
        areas.push(SwathArea {
            swaths: start..out.len(),
            bearing: swaths.bearing,
            region: None,
            area: MultiPolygon::new(vec![]),
            fill: false,
        });
    }
    for l in &mut swaths.lifts {
        if let Some(&n) = renumber.get(l.swath) {
            l.swath = n;
        }
    }
    sort_lifts(&mut swaths.lifts);
    swaths.swaths = out;
    swaths.swaths.extend(fill_swaths);
    swaths.areas = areas;
    swaths.areas.extend(fill_areas);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::decompose::cluster_swaths;
    use crate::swath::generate;
    use geo::polygon;

    #[test]
    fn swaths_cluster_into_the_cells_around_a_pond() {
        let field = polygon!(
            exterior: [(x: 0., y: 0.), (x: 60., y: 0.), (x: 60., y: 100.), (x: 0., y: 100.)],
            interiors: [[(x: 20., y: 40.), (x: 40., y: 40.), (x: 40., y: 60.), (x: 20., y: 60.)]],
        );
        let area = MultiPolygon::new(vec![field]);
        let mut swaths = generate(&area, 0.0, 6.0, 6.0).unwrap();
        let n = swaths.swaths.len();
        let cells = decompose(&area, 0.0, 0.0);
        cluster_into_cells(&mut swaths, &cells);
        assert_eq!(swaths.swaths.len(), n);
        assert_eq!(swaths.areas.len(), 4);
        for (i, s) in swaths.swaths.iter().enumerate() {
            assert_eq!(s.index, i);
        }
        let blocks = cluster_swaths(&swaths);
        assert_eq!(blocks.blocks.len(), 4);
        // Each block's swaths lie in its cell.
        for (b, a) in blocks.blocks.iter().zip(&swaths.areas) {
            use geo::Contains;
            for &i in &b.swaths {
                let mid =
                    geo::Point((swaths.swaths[i].centre.start + swaths.swaths[i].centre.end) / 2.0);
                assert!(a.area.contains(&mid));
            }
        }
    }
}
