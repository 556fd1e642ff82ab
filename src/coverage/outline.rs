//! From cells to polygons: the connected parts of a set of cells (side by side, not corner to
//! corner) and their outlines along the cells' sides, as polygons with holes.

use super::raster::Grid;
use crate::geometry::{sleeve_ring, Sleeve};
use crate::sort::SharedSort;
use geo::{Coord, LineString, Polygon};

/// One connected part of a set of cells.
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    /// Its cells, by index.
    pub cells: Vec<usize>,
}

/// The connected parts of the cells for which `in_set` is true (cells sharing a side are
/// connected), in the order of their first cell.
///
/// ```
/// use furrow::coverage::outline::parts;
///
/// // 4 x 2 cells: two parts, the left column and the two right columns (x marks the set).
/// // row 1:  x . x x
/// // row 0:  x . . x
/// let set = [true, false, false, true, true, false, true, true];
/// let p = parts(4, 2, |i| set[i]);
/// assert_eq!(p.len(), 2);
/// assert_eq!(p[0].cells, vec![0, 4]);
/// assert_eq!(p[1].cells.len(), 3);
/// ```
pub fn parts(columns: usize, rows: usize, in_set: impl Fn(usize) -> bool) -> Vec<Part> {
    parts_from(columns, rows, 0..columns * rows, in_set)
}

/// [`parts`] where the set's cells are known: `starts` holds every cell of the set (and maybe
/// others), in ascending order, so that the grid is not searched for them.
pub fn parts_from(
    columns: usize,
    rows: usize,
    starts: impl IntoIterator<Item = usize>,
    in_set: impl Fn(usize) -> bool,
) -> Vec<Part> {
    let n = columns * rows;
    let mut seen = vec![false; n];
    let mut out = Vec::new();
    let mut stack = Vec::new();
    for start in starts {
        if start >= n || seen[start] || !in_set(start) {
            continue;
        }
        seen[start] = true;
        stack.push(start);
        let mut cells = Vec::new();
        while let Some(c) = stack.pop() {
            cells.push(c);
            let (i, j) = (c % columns, c / columns);
            let mut push = |k: usize| {
                if !seen[k] && in_set(k) {
                    seen[k] = true;
                    stack.push(k);
                }
            };
            if i > 0 {
                push(c - 1);
            }
            if i + 1 < columns {
                push(c + 1);
            }
            if j > 0 {
                push(c - columns);
            }
            if j + 1 < rows {
                push(c + columns);
            }
        }
        cells.shared_sort_unstable_by(usize::cmp);
        out.push(Part { cells });
    }
    out
}

/// The outline of a part as a polygon (outer ring counter-clockwise, holes clockwise), its
/// staircases smoothed to within `smoothing` metres.
pub fn outline(grid: &Grid, part: &Part, smoothing: f64) -> Option<Polygon> {
    let inside = |i: isize, j: isize| {
        i >= 0
            && j >= 0
            && (i as usize) < grid.columns
            && (j as usize) < grid.rows
            && part
                .cells
                .binary_search(&(j as usize * grid.columns + i as usize))
                .is_ok()
    };
    // Directed sides with the part on their left: (from corner, to corner).
    let mut sides: Vec<(Corner, Corner)> = Vec::new();
    for &c in &part.cells {
        let (i, j) = ((c % grid.columns) as isize, (c / grid.columns) as isize);
        if !inside(i, j - 1) {
            sides.push(((i, j), (i + 1, j)));
        }
        if !inside(i + 1, j) {
            sides.push(((i + 1, j), (i + 1, j + 1)));
        }
        if !inside(i, j + 1) {
            sides.push(((i + 1, j + 1), (i, j + 1)));
        }
        if !inside(i - 1, j) {
            sides.push(((i, j + 1), (i, j)));
        }
    }
    // Sorted through their indices: the sort of indices is the one the cells' use, where a sort
    // of the sides themselves would be another few kilobytes of the wasm module.
    let mut by_side: Vec<usize> = (0..sides.len()).collect();
    by_side.shared_sort_unstable_by(|&a, &b| sides[a].cmp(&sides[b]));
    let sides: Vec<(Corner, Corner)> = by_side.into_iter().map(|i| sides[i]).collect();
    let corner = |(i, j): Corner| grid.corner(i.max(0) as usize, j.max(0) as usize);
    let mut rings: Vec<LineString> = trace(&sides)
        .into_iter()
        .filter_map(|ring| {
            let points: Vec<Coord> = ring.into_iter().map(corner).collect();
            let mut smooth = sleeve_ring(&points, Sleeve::both(smoothing));
            (smooth.len() >= 3).then(|| {
                smooth.push(smooth[0]);
                LineString::new(smooth)
            })
        })
        .collect();
    // The outer ring encloses the most area, counter-clockwise; the others are holes.
    let area = |r: &LineString| {
        r.0.windows(2)
            .map(|w| w[0].x * w[1].y - w[1].x * w[0].y)
            .sum::<f64>()
    };
    let outer = (0..rings.len()).max_by(|&a, &b| area(&rings[a]).total_cmp(&area(&rings[b])))?;
    let exterior = rings.swap_remove(outer);
    Some(Polygon::new(exterior, rings))
}

/// A corner of the grid's cells: (column line, row line).
type Corner = (isize, isize);

/// Links directed sides (sorted) into closed rings. Where two rings touch at a corner, the side
/// taken is the one turning most to the left, so that rings never cross.
fn trace(sides: &[(Corner, Corner)]) -> Vec<Vec<Corner>> {
    let mut used = vec![false; sides.len()];
    let mut rings = Vec::new();
    for first in 0..sides.len() {
        if used[first] {
            continue;
        }
        used[first] = true;
        let (start, mut at) = sides[first];
        let mut heading = (at.0 - start.0, at.1 - start.1);
        let mut ring = vec![start];
        while at != start {
            ring.push(at);
            let Some(k) = next_side(sides, &used, at, heading) else {
                break;
            };
            used[k] = true;
            heading = (sides[k].1 .0 - at.0, sides[k].1 .1 - at.1);
            at = sides[k].1;
        }
        if ring.len() >= 4 {
            rings.push(ring);
        }
    }
    rings
}

/// The unused side leaving `corner` that turns most to the left of `heading`.
fn next_side(
    sides: &[(Corner, Corner)],
    used: &[bool],
    corner: Corner,
    heading: (isize, isize),
) -> Option<usize> {
    let from = sides.partition_point(|s| s.0 < corner);
    (from..sides.len())
        .take_while(|&k| sides[k].0 == corner)
        .filter(|&k| !used[k])
        .max_by_key(|&k| {
            let d = (sides[k].1 .0 - corner.0, sides[k].1 .1 - corner.1);
            // Left turn 2, straight on 1, right turn 0.
            heading.0 * d.1 - heading.1 * d.0 + 1
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{coord, Area, Rect};

    #[test]
    fn a_ring_of_cells_outlines_as_a_polygon_with_a_hole() {
        // 5 x 5 cells of 1 m, all but the middle one.
        let grid = Grid::over(
            Rect::new(coord! { x: 0.0, y: 0.0 }, coord! { x: 3.0, y: 3.0 }),
            1.0,
            100,
        );
        assert_eq!((grid.columns, grid.rows), (5, 5));
        let p = parts(5, 5, |i| i != 12);
        assert_eq!(p.len(), 1);
        let polygon = outline(&grid, &p[0], 0.0).unwrap();
        assert_eq!(polygon.interiors().len(), 1);
        assert!((polygon.unsigned_area() - 24.0).abs() < 1e-9);
    }

    #[test]
    fn parts_touching_at_a_corner_stay_apart() {
        // Two cells corner to corner.
        let grid = Grid::over(
            Rect::new(coord! { x: 0.0, y: 0.0 }, coord! { x: 0.0, y: 0.0 }),
            1.0,
            100,
        );
        let p = parts(grid.columns, grid.rows, |i| i == 0 || i == grid.columns + 1);
        assert_eq!(p.len(), 2);
        for part in &p {
            let polygon = outline(&grid, part, 0.0).unwrap();
            assert!((polygon.unsigned_area() - 1.0).abs() < 1e-9);
        }
    }

    #[test]
    fn parts_from_the_set_s_cells_are_the_parts_of_the_set() {
        // A 7 x 6 checkerboard of blocks: started from its cells alone (and cells beyond the
        // grid, ignored), the same parts in the same order as found by searching the grid.
        let (columns, rows) = (7, 6);
        let in_set = |i: usize| ((i % columns) / 2 + (i / columns) / 2).is_multiple_of(2);
        let cells: Vec<usize> = (0..columns * rows).filter(|&i| in_set(i)).collect();
        let starts = cells.iter().copied().chain([columns * rows, usize::MAX]);
        let from = parts_from(columns, rows, starts, in_set);
        assert_eq!(from, parts(columns, rows, in_set));
        assert_eq!(from.len(), 6);
    }
}
