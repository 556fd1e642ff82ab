//! A grid of square cells over the field in local metres, and the shapes drawn on it: polygons
//! filled by the even-odd rule at the cells' centres, and the strips an implement of some width
//! sweeps along a line.
//!
//! A cell belongs to a shape when its centre does, so a shape's cells cover its area without
//! bias: the error is a fraction of a cell along the shape's outline, half of it either way.

use crate::geometry::{Extremes, PlanarHypot};
use crate::sort::SharedSort;
use geo::{Coord, LineString, Polygon, Rect};
use std::ops::Range;

/// A grid of `columns` by `rows` square cells of side `cell` metres, the first cell's lower-left
/// corner at `origin`; cell `(i, j)` (column, row) is at index `j * columns + i`.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// The lower-left corner of the first cell.
    pub origin: Coord,
    /// The side of a cell, metres.
    pub cell: f64,
    /// Cells across (x).
    pub columns: usize,
    /// Cells up (y).
    pub rows: usize,
}

impl Grid {
    /// A grid of cells of side `cell` (or larger, so that it has at most `max_cells`) over
    /// `bounds` and a margin of one cell.
    ///
    /// ```
    /// use furrow::coverage::raster::Grid;
    /// use geo::{coord, Rect};
    ///
    /// let g = Grid::over(Rect::new(coord! { x: 0.0, y: 0.0 }, coord! { x: 10.0, y: 5.0 }), 1.0, 1_000);
    /// assert_eq!((g.columns, g.rows), (12, 7));
    /// ```
    pub fn over(bounds: Rect, cell: f64, max_cells: usize) -> Grid {
        let (w, h) = (bounds.width(), bounds.height());
        let fits = |c: f64| (w / c + 3.0) * (h / c + 3.0) <= max_cells as f64;
        let mut cell = cell;
        if !fits(cell) {
            // The side that gives max_cells over the bounds, a little over for the margins.
            cell = ((w * h) / max_cells as f64).sqrt().max(cell);
            while !fits(cell) {
                cell *= 1.1;
            }
        }
        let columns = (w / cell).ceil() as usize + 2;
        let rows = (h / cell).ceil() as usize + 2;
        Grid {
            origin: Coord {
                x: bounds.min().x - cell,
                y: bounds.min().y - cell,
            },
            cell,
            columns,
            rows,
        }
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.columns * self.rows
    }

    /// Whether the grid has no cells.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The area of one cell, square metres.
    pub fn cell_area(&self) -> f64 {
        self.cell * self.cell
    }

    /// The y of the centres of row `j`.
    fn row_y(&self, j: usize) -> f64 {
        self.origin.y + (j as f64 + 0.5) * self.cell
    }

    /// The rows whose centres lie between `y0` and `y1`.
    fn rows_between(&self, y0: f64, y1: f64) -> std::ops::Range<usize> {
        let first = ((y0 - self.origin.y) / self.cell - 0.5).ceil().max(0.0);
        let last = ((y1 - self.origin.y) / self.cell - 0.5).floor() + 1.0;
        let last = last.clamp(0.0, self.rows as f64);
        (first.min(last) as usize)..(last as usize)
    }

    /// The columns whose centres lie between `x0` and `x1`.
    fn columns_between(&self, x0: f64, x1: f64) -> std::ops::Range<usize> {
        let first = ((x0 - self.origin.x) / self.cell - 0.5).ceil().max(0.0);
        let last = ((x1 - self.origin.x) / self.cell - 0.5).floor() + 1.0;
        let last = last.clamp(0.0, self.columns as f64);
        (first.min(last) as usize)..(last as usize)
    }

    /// Calls `visit` with the indices of the cells whose centres lie in the polygon (even-odd
    /// over its rings), a row's stretch at a time.
    pub fn fill_polygon(&self, polygon: &Polygon, visit: &mut dyn FnMut(Range<usize>)) {
        let rings = std::iter::once(polygon.exterior()).chain(polygon.interiors());
        let edges: Vec<(Coord, Coord)> = rings.flat_map(ring_edges).collect();
        self.fill_edges(edges, visit);
    }

    /// The even-odd fill of a set of edges, row by row: the edges crossing each row's centre
    /// line, in order across it, bound the stretches inside.
    fn fill_edges(&self, mut edges: Vec<(Coord, Coord)>, visit: &mut dyn FnMut(Range<usize>)) {
        // Each edge from its lower end; sorted by it, so that a row's edges are found in order.
        for e in &mut edges {
            if e.0.y > e.1.y {
                *e = (e.1, e.0);
            }
        }
        edges.retain(|e| e.0.y < e.1.y);
        edges.shared_sort_by_float_key(|e| e.0.y);
        let Some(low) = edges.first().map(|e| e.0.y) else {
            return;
        };
        let high = edges.iter().map(|e| e.1.y).fold(low, f64::greater);
        let mut next = 0;
        let mut active: Vec<usize> = Vec::new();
        let mut xs: Vec<f64> = Vec::new();
        for j in self.rows_between(low, high) {
            let y = self.row_y(j);
            while next < edges.len() && edges[next].0.y <= y {
                active.push(next);
                next += 1;
            }
            // Half-open in y: an edge counts for rows from its lower end up to below its upper.
            active.retain(|&k| edges[k].1.y > y);
            xs.clear();
            xs.extend(active.iter().map(|&k| {
                let (a, b) = edges[k];
                a.x + (b.x - a.x) * (y - a.y) / (b.y - a.y)
            }));
            xs.shared_sort_unstable_by(f64::total_cmp);
            for pair in xs.chunks_exact(2) {
                self.visit_row(j, self.columns_between(pair[0], pair[1]), visit);
            }
        }
    }

    /// Calls `visit` with the cells (a row's stretch at a time) whose centres lie within
    /// `half_width` of the segment from `a` to `b` measured square to it, and between its ends:
    /// the strip an implement of twice that width sweeps along it.
    pub fn fill_strip(
        &self,
        a: Coord,
        b: Coord,
        half_width: f64,
        visit: &mut dyn FnMut(Range<usize>),
    ) {
        if let Some(n) = side_offset(a, b, half_width) {
            self.fill_convex(&[a + n, b + n, b - n, a - n], visit);
        }
    }

    /// Calls `visit` with the cells (a row's stretch at a time) that the implement, a bar of
    /// half-width `half_width` square to its heading, sweeps as it swings round `b` from the
    /// heading of `a`→`b` to that of `b`→`c`: the two sectors between the ends of the strips
    /// along the two edges, one either side of `b` (the strips themselves are drawn apart, by
    /// [`Grid::fill_strip`]). A sector is drawn as triangles whose chords lie within a quarter
    /// of a cell of its arc: for a line turning slightly at `b`, one triangle either side (a
    /// sector of angle θ and its triangle differ by about r²θ³/12), so that a curve drawn as
    /// many short edges is worked in full; for a sharp turn, a fan of them. Never more: a bar
    /// swinging round a point sweeps no disc, so that a curved line is worked no farther than its
    /// ends.
    ///
    /// ```
    /// use furrow::coverage::raster::Grid;
    /// use geo::{coord, Rect};
    ///
    /// let grid = Grid::over(Rect::new(coord! { x: -20., y: -20. }, coord! { x: 20., y: 20. }), 0.1, 1_000_000);
    /// let (a, b) = (coord! { x: -10., y: 0. }, coord! { x: 0., y: 0. });
    /// let area = |c| {
    ///     let mut cells = 0;
    ///     grid.fill_swing(a, b, c, 12.0, &mut |r| cells += r.len());
    ///     cells as f64 * grid.cell_area()
    /// };
    /// // A turn of 0.02 rad at the origin with a half-width of 12 m: two sectors of 1.44 m².
    /// let slight = area(coord! { x: 10. * 0.02f64.cos(), y: 10. * 0.02f64.sin() });
    /// assert!((slight - 2.0 * 144.0 * 0.02 / 2.0).abs() < 0.5, "{slight}");
    /// // A right angle: two quarter discs, 226 m².
    /// let square = area(coord! { x: 0., y: 10. });
    /// assert!((square - 144.0 * std::f64::consts::FRAC_PI_2).abs() < 2.0, "{square}");
    /// ```
    pub fn fill_swing(
        &self,
        a: Coord,
        b: Coord,
        c: Coord,
        half_width: f64,
        visit: &mut dyn FnMut(Range<usize>),
    ) {
        let (Some(n1), Some(n2)) = (side_offset(a, b, half_width), side_offset(b, c, half_width))
        else {
            return;
        };
        // The signed angle from the one heading to the other, within half a turn either way.
        let turn = (n1.x * n2.y - n1.y * n2.x).atan2(n1.x * n2.x + n1.y * n2.y);
        // The arc's steps: a chord over an angle s lies h (1 - cos(s/2)) inside its arc.
        let sag = (self.cell / 4.0).lesser(half_width);
        let step = 2.0 * (1.0 - sag / half_width).acos();
        let pieces = (turn.abs() / step).ceil().clamp(1.0, MAX_SWING_PIECES) as usize;
        let mut from = n1;
        for k in 1..=pieces {
            let to = if k == pieces {
                n2
            } else {
                let (sin, cos) = (turn * k as f64 / pieces as f64).sin_cos();
                Coord {
                    x: n1.x * cos - n1.y * sin,
                    y: n1.x * sin + n1.y * cos,
                }
            };
            self.fill_convex(&[b, b + from, b + to], visit);
            self.fill_convex(&[b, b - from, b - to], visit);
            from = to;
        }
    }

    /// Calls `visit` with the cells (a row's stretch at a time) whose centres lie within
    /// `radius` of `c`.
    pub fn fill_disc(&self, c: Coord, radius: f64, visit: &mut dyn FnMut(Range<usize>)) {
        if radius.is_nan() || radius <= 0.0 {
            return;
        }
        for j in self.rows_between(c.y - radius, c.y + radius) {
            let dy = self.row_y(j) - c.y;
            let half = (radius * radius - dy * dy).max(0.0).sqrt();
            self.visit_row(j, self.columns_between(c.x - half, c.x + half), visit);
        }
    }

    /// The cells of a convex polygon (its corners in order, either way round).
    fn fill_convex(&self, corners: &[Coord], visit: &mut dyn FnMut(Range<usize>)) {
        let (low, high) = corners
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), c| {
                (l.lesser(c.y), h.greater(c.y))
            });
        for j in self.rows_between(low, high) {
            let y = self.row_y(j);
            let (mut x0, mut x1) = (f64::INFINITY, f64::NEG_INFINITY);
            for k in 0..corners.len() {
                let (p, q) = (corners[k], corners[(k + 1) % corners.len()]);
                if (p.y <= y && y <= q.y) || (q.y <= y && y <= p.y) {
                    let x = if q.y == p.y {
                        p.x
                    } else {
                        p.x + (q.x - p.x) * (y - p.y) / (q.y - p.y)
                    };
                    x0 = x0.lesser(x);
                    x1 = x1.greater(x);
                    if q.y == p.y {
                        x0 = x0.lesser(q.x);
                        x1 = x1.greater(q.x);
                    }
                }
            }
            if x0 <= x1 {
                self.visit_row(j, self.columns_between(x0, x1), visit);
            }
        }
    }

    /// Calls `visit` with the indices of `columns` in row `j`, if any.
    fn visit_row(&self, j: usize, columns: Range<usize>, visit: &mut dyn FnMut(Range<usize>)) {
        if !columns.is_empty() {
            let row = j * self.columns;
            visit(row + columns.start..row + columns.end);
        }
    }

    /// The centre of cell `index`.
    pub fn centre(&self, index: usize) -> Coord {
        let (i, j) = (index % self.columns, index / self.columns);
        Coord {
            x: self.origin.x + (i as f64 + 0.5) * self.cell,
            y: self.origin.y + (j as f64 + 0.5) * self.cell,
        }
    }

    /// The corner of the cell grid at column line `i`, row line `j`.
    pub fn corner(&self, i: usize, j: usize) -> Coord {
        Coord {
            x: self.origin.x + i as f64 * self.cell,
            y: self.origin.y + j as f64 * self.cell,
        }
    }
}

/// Most chords of a sector [`Grid::fill_swing`] draws (a half turn in steps of 3 degrees).
const MAX_SWING_PIECES: f64 = 60.0;

/// The edges of a closed ring.
fn ring_edges(ring: &LineString) -> impl Iterator<Item = (Coord, Coord)> + '_ {
    ring.0.windows(2).map(|w| (w[0], w[1]))
}

/// The offset `half_width` to the left of the segment from `a` to `b`; `None` for a segment
/// of no length or a width that is not a positive number.
fn side_offset(a: Coord, b: Coord, half_width: f64) -> Option<Coord> {
    let d = b - a;
    let length = d.x.planar_hypot(d.y);
    (length > 0.0 && length.is_finite() && half_width > 0.0).then(|| Coord {
        x: -d.y / length * half_width,
        y: d.x / length * half_width,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{coord, polygon, Area, BoundingRect};

    fn count(grid: &Grid, f: impl Fn(&Grid, &mut dyn FnMut(Range<usize>))) -> usize {
        let mut n = 0;
        f(grid, &mut |r| n += r.len());
        n
    }

    #[test]
    fn a_polygon_with_a_hole_fills_its_area() {
        let p = polygon!(
            exterior: [(x: 0., y: 0.), (x: 100., y: 0.), (x: 70., y: 80.), (x: 0., y: 60.)],
            interiors: [[(x: 20., y: 20.), (x: 40., y: 20.), (x: 30., y: 40.)]],
        );
        let grid = Grid::over(p.bounding_rect().unwrap(), 0.25, 1_000_000);
        let cells = count(&grid, |g, v| g.fill_polygon(&p, v));
        let area = cells as f64 * grid.cell_area();
        assert!(
            (area - p.unsigned_area()).abs() < 0.002 * p.unsigned_area(),
            "{area}"
        );
    }

    #[test]
    fn a_strip_and_a_disc_fill_their_areas() {
        let bounds = Rect::new(coord! { x: -10.0, y: -10.0 }, coord! { x: 110.0, y: 90.0 });
        let grid = Grid::over(bounds, 0.1, 2_000_000);
        let (a, b) = (coord! { x: 3.0, y: 7.0 }, coord! { x: 83.0, y: 67.0 });
        let strip = count(&grid, |g, v| g.fill_strip(a, b, 3.0, v)) as f64 * grid.cell_area();
        assert!((strip - 100.0 * 6.0).abs() < 0.01 * 600.0, "{strip}");
        let disc = count(&grid, |g, v| g.fill_disc(a, 5.0, v)) as f64 * grid.cell_area();
        let expected = std::f64::consts::PI * 25.0;
        assert!((disc - expected).abs() < 0.01 * expected, "{disc}");
    }

    #[test]
    fn the_grid_grows_its_cells_to_stay_within_its_budget() {
        let bounds = Rect::new(coord! { x: 0.0, y: 0.0 }, coord! { x: 5000.0, y: 4000.0 });
        let grid = Grid::over(bounds, 0.1, 100_000);
        assert!(grid.len() <= 100_000, "{}", grid.len());
        assert!(grid.cell > 10.0);
    }
}
