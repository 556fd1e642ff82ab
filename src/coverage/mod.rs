//! Coverage: how much of the field the implement works, how much it could reach at all, how
//! much it works twice, and where crop is left standing.
//!
//! The implement's footprint is the strip of its width along every stretch it works (swaths,
//! headland passes, fill passes; not turns, connections or stretches lifted over an obstacle),
//! measured against the field less all its obstacles. The physical limit is the part of the
//! field a strip of the implement's width can reach at all: the field opened by a disc of the
//! working width across (a strip never reaches into a corner sharper than a right angle or a
//! neck narrower than itself).
//!
//! Measured on a grid ([`raster`]) of cells a sixth of the working width across, at most
//! [`MAX_CELL_M`] (coarser on large fields, so that the grid holds at most [`MAX_CELLS`]): the
//! field, the strips as driven and the field opened by the implement's half width (inset as a
//! polygon, swept round by the half width again on the grid) are drawn on it. The figures are
//! exact to a fraction of a cell along each outline; the crop left standing is given as polygons
//! ([`outline`]) of the parts larger than a quarter of a working width squared.

pub mod outline;
pub mod raster;

use crate::field::Field;
use crate::geometry::BooleanOps;
use crate::geometry::Extremes;
use crate::headland::offset::inset;
use crate::path::Path;
use crate::sort::SharedSort;
use geo::{BoundingRect, Coord, MultiPolygon, Polygon};
use raster::Grid;
use serde::Serialize;
use std::ops::Range;

/// Most cells of the coverage grid: its cells grow beyond a sixth of the width where the field
/// would need more (a 50 ha field worked at 6 m has cells of 1 m).
pub const MAX_CELLS: usize = 500_000;

/// Cells across one working width.
pub const CELLS_PER_WIDTH: f64 = 6.0;

/// The largest cell a field within [`MAX_CELLS`] gets, metres: a wide implement's sixth of a
/// width (4 m at 24 m) would misjudge a small field's area by several per cent.
pub const MAX_CELL_M: f64 = 1.0;

/// Turns of the inset's outline sharper than this (radians) get the disc round the point when
/// the reach is drawn (its sweep round the point by the half width); slighter ones the sectors
/// either side, the disc's only part outside the strips there.
const ROUND_ANGLE: f64 = 0.03;

/// The coverage of a plan.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Coverage {
    /// The field less its obstacles, square metres.
    pub field_area_m2: f64,
    /// Of it, worked at least once, square metres.
    pub covered_area_m2: f64,
    /// Covered share of the field.
    pub coverage_ratio: f64,
    /// The share of the field a strip of the implement's width can reach at all: the limit of
    /// `coverage_ratio`.
    pub reachable_ratio: f64,
    /// Area worked twice or more, as a share of the field.
    pub overlap_ratio: f64,
    /// Area left standing, square metres.
    pub uncovered_area_m2: f64,
    /// Area worked outside the field or over an obstacle, square metres: the implement's strip
    /// past the boundary (the outer swaths of a field worked without headland, along a side not
    /// parallel to them), or over an obstacle it is not lifted over.
    pub outside_area_m2: f64,
    /// The side of the grid's cells, metres: the figures' resolution.
    pub resolution_m: f64,
    /// The parts of the field left standing that are larger than the tolerance, largest first.
    #[serde(skip)]
    pub uncovered: Vec<Uncovered>,
}

/// A part of the field left standing.
#[derive(Debug, Clone, PartialEq)]
pub struct Uncovered {
    /// Its outline, local metres.
    pub polygon: Polygon,
    /// Its area, square metres (counted in cells).
    pub area_m2: f64,
    /// Of it, what a strip of the implement's width could reach, square metres.
    pub reachable_m2: f64,
}

/// Measures the coverage of `worked` lines (each a polyline driven with the implement down) of
/// an implement `width` metres wide over the field `boundary` less its `obstacles`.
///
/// ```
/// use furrow::coverage::measure;
/// use geo::{coord, polygon};
///
/// // A 30 x 100 m field worked by four 6 m swaths: the last 6 m strip left standing.
/// let field = polygon![(x: 0., y: 0.), (x: 30., y: 0.), (x: 30., y: 100.), (x: 0., y: 100.)];
/// let swaths: Vec<Vec<_>> = [3.0, 9.0, 15.0, 21.0]
///     .iter()
///     .map(|&x| vec![coord! { x: x, y: 0.0 }, coord! { x: x, y: 100.0 }])
///     .collect();
/// let c = measure(&field, &[], &swaths, 6.0);
/// assert!((c.coverage_ratio - 0.8).abs() < 0.01);
/// assert!((c.reachable_ratio - 1.0).abs() < 0.01);
/// assert_eq!(c.uncovered.len(), 1);
/// assert!((c.uncovered[0].area_m2 - 600.0).abs() < 10.0);
/// ```
pub fn measure(
    boundary: &Polygon,
    obstacles: &[Polygon],
    worked: &[Vec<Coord>],
    width: f64,
) -> Coverage {
    match Tally::new(boundary, obstacles, width) {
        Some(mut tally) => {
            tally.work(worked);
            tally.coverage()
        }
        None => Coverage::default(),
    }
}

/// The coverage of a field as it is worked: the field and what a strip can reach drawn once on
/// the grid, worked lines added to it as they come ([`Tally::work`]), the figures read at any
/// time ([`Tally::coverage`]). [`measure`] in steps: the fill of what the plan leaves
/// ([`crate::fill`]) adds its lines to the plan's.
///
/// ```
/// use furrow::coverage::Tally;
/// use geo::{coord, polygon};
///
/// let field = polygon![(x: 0., y: 0.), (x: 12., y: 0.), (x: 12., y: 100.), (x: 0., y: 100.)];
/// let mut tally = Tally::new(&field, &[], 6.0).ok_or("no field or no width")?;
/// tally.work(&[vec![coord! { x: 3.0, y: 0.0 }, coord! { x: 3.0, y: 100.0 }]]);
/// assert!((tally.coverage().coverage_ratio - 0.5).abs() < 0.01);
/// tally.work(&[vec![coord! { x: 9.0, y: 0.0 }, coord! { x: 9.0, y: 100.0 }]]);
/// assert!(tally.coverage().coverage_ratio > 0.99);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone)]
pub struct Tally {
    grid: Grid,
    width: f64,
    /// Each cell's state, row by row: what it is and what has worked it, in one place, so that
    /// a strip drawn over it touches one array.
    cells: Vec<Cell>,
    /// The number of the next line worked, for [`Cell::last`].
    next_line: u16,
    /// The cells of each kind, kept as lines are added.
    counts: Counts,
}

/// How many cells of a [`Tally`] are of each kind.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Counts {
    /// In the field.
    field: usize,
    /// In the field and in reach.
    reach: usize,
    /// Worked at least once.
    covered: usize,
    /// Worked twice or more.
    twice: usize,
    /// Worked, though out of reach (a plan reaches what it works).
    covered_beyond_reach: usize,
    /// Off the field and worked.
    outside: usize,
}

/// A cell of a [`Tally`]: whether it is in the field and in reach, and the lines over it.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Cell {
    /// The last line counted on it ([`NO_LINE`] before the first): a line is counted once per
    /// cell, however many of its pieces sweep it.
    last: u16,
    /// How many worked lines sweep it (in the field).
    count: u8,
    /// [`IN_FIELD`], [`IN_REACH`], [`SWEPT_OFF_FIELD`].
    flags: u8,
}

/// No line yet: the value of [`Cell::last`] before one is counted.
const NO_LINE: u16 = u16::MAX;
/// The cell is in the field and off its obstacles.
const IN_FIELD: u8 = 1;
/// The cell is of the field opened by the implement's half width.
const IN_REACH: u8 = 2;
/// The cell is off the field and a line sweeps it.
const SWEPT_OFF_FIELD: u8 = 4;

impl Cell {
    fn in_field(self) -> bool {
        self.flags & IN_FIELD != 0
    }
}

impl Tally {
    /// An empty tally of the field `boundary` less its `obstacles` for an implement `width`
    /// metres wide; `None` for a boundary without extent or a width that is not a positive
    /// number.
    pub fn new(boundary: &Polygon, obstacles: &[Polygon], width: f64) -> Option<Tally> {
        let centres = strip_centres(boundary, obstacles, width);
        Tally::with_centres(boundary, obstacles, width, &centres)
    }

    /// [`Tally::new`] where the field's [`strip_centres`] are at hand: the implement's reach is
    /// drawn from them.
    pub fn with_centres(
        boundary: &Polygon,
        obstacles: &[Polygon],
        width: f64,
        centres: &MultiPolygon,
    ) -> Option<Tally> {
        let bounds = boundary.bounding_rect()?;
        if !width.is_finite() || width <= 0.0 {
            return None;
        }
        // Half a width round the field, so that the grid holds every strip that reaches past it.
        let half = width / 2.0;
        let around = geo::Rect::new(
            Coord {
                x: bounds.min().x - half,
                y: bounds.min().y - half,
            },
            Coord {
                x: bounds.max().x + half,
                y: bounds.max().y + half,
            },
        );
        let grid = Grid::over(around, (width / CELLS_PER_WIDTH).min(MAX_CELL_M), MAX_CELLS);
        let mut cells = field_cells(&grid, boundary, obstacles);
        mark_reach(&grid, centres, &mut cells, half);
        let counts = Counts {
            field: cells.iter().filter(|c| c.in_field()).count(),
            reach: cells.iter().filter(|c| c.flags & IN_REACH != 0).count(),
            ..Counts::default()
        };
        Some(Tally {
            grid,
            width,
            cells,
            next_line: 0,
            counts,
        })
    }

    /// Forgets every line worked: the tally of the same field, empty again (the field's cells
    /// are kept, not drawn again).
    pub fn forget(&mut self) {
        for c in &mut self.cells {
            c.last = NO_LINE;
            c.count = 0;
            c.flags &= !SWEPT_OFF_FIELD;
        }
        self.counts = Counts {
            field: self.counts.field,
            reach: self.counts.reach,
            ..Counts::default()
        };
        self.next_line = 0;
    }

    /// Adds `worked` lines (each a polyline driven with the implement down).
    pub fn work(&mut self, worked: &[Vec<Coord>]) {
        let half = self.width / 2.0;
        for line in worked {
            if self.next_line == NO_LINE {
                // Numbers run out: every cell's last line forgotten, and counted afresh.
                for c in &mut self.cells {
                    c.last = NO_LINE;
                }
                self.next_line = 0;
            }
            let k = self.next_line;
            self.next_line += 1;
            let Tally {
                grid,
                cells,
                counts,
                ..
            } = self;
            let mut mark = |range: Range<usize>| {
                for c in &mut cells[range] {
                    if !c.in_field() {
                        if c.flags & SWEPT_OFF_FIELD == 0 {
                            c.flags |= SWEPT_OFF_FIELD;
                            counts.outside += 1;
                        }
                    } else if c.last != k {
                        c.last = k;
                        match c.count {
                            0 => {
                                counts.covered += 1;
                                counts.covered_beyond_reach += usize::from(c.flags & IN_REACH == 0);
                            }
                            1 => counts.twice += 1,
                            _ => {}
                        }
                        c.count = c.count.saturating_add(1);
                    }
                }
            };
            sweep(grid, line, half, &mut mark);
        }
    }

    /// The figures of the lines added so far.
    pub fn coverage(&self) -> Coverage {
        figures(&self.grid, &self.cells, &self.counts, self.width)
    }
}

/// The coverage of a plan's path over its field (less all its obstacles, those lifted over
/// too).
pub fn of_plan(field: &Field, path: &Path, width: f64) -> Coverage {
    let obstacles: Vec<Polygon> = field.obstacles.iter().map(|o| o.polygon.clone()).collect();
    measure(&field.boundary, &obstacles, &worked_lines(path), width)
}

/// The lines a path works along: each working segment as driven, less the stretches where the
/// implement is lifted.
pub fn worked_lines(path: &Path) -> Vec<Vec<Coord>> {
    path.segments
        .iter()
        .flat_map(|s| s.worked_stretches())
        .collect()
}

/// The tally's cells, those in the field and off its obstacles marked [`IN_FIELD`].
fn field_cells(grid: &Grid, boundary: &Polygon, obstacles: &[Polygon]) -> Vec<Cell> {
    let empty = Cell {
        last: NO_LINE,
        count: 0,
        flags: 0,
    };
    let mut cells = vec![empty; grid.len()];
    grid.fill_polygon(boundary, &mut |range| {
        cells[range].iter_mut().for_each(|c| c.flags |= IN_FIELD);
    });
    for o in obstacles {
        grid.fill_polygon(o, &mut |range| {
            cells[range].iter_mut().for_each(|c| c.flags &= !IN_FIELD);
        });
    }
    cells
}

/// The angle (radians, unsigned) the line turns at `b` on its way from `a` to `c`.
fn turn_angle(a: Coord, b: Coord, c: Coord) -> f64 {
    let (u, v) = (b - a, c - b);
    let cross = u.x * v.y - u.y * v.x;
    let dot = u.x * v.x + u.y * v.y;
    cross.abs().atan2(dot)
}

/// Where the centre line of a strip `width` wide may run: the field `boundary` less all its
/// `obstacles` (overlapping ones as their union), inset by half the width.
///
/// ```
/// use furrow::coverage::strip_centres;
/// use geo::{polygon, Area};
///
/// // A 30 x 100 m field worked 6 m wide: centre lines 3 m in from every side.
/// let field = polygon![(x: 0., y: 0.), (x: 30., y: 0.), (x: 30., y: 100.), (x: 0., y: 100.)];
/// let centres = strip_centres(&field, &[], 6.0);
/// assert!((centres.unsigned_area() - 24.0 * 94.0).abs() < 1e-6);
/// ```
pub fn strip_centres(boundary: &Polygon, obstacles: &[Polygon], width: f64) -> MultiPolygon {
    let mut region = MultiPolygon::new(vec![boundary.clone()]);
    if !obstacles.is_empty() {
        region = region.difference_overlapping(&MultiPolygon::new(obstacles.to_vec()));
    }
    inset(&region, width / 2.0)
}

/// Marks [`IN_REACH`] the cells of the field a strip of half-width `radius` can reach: those of
/// the field opened by a disc of that radius (a plan reaches whatever it works besides). The
/// opening is the field inset by the radius (`centres`, the [`strip_centres`]) swept round by
/// the disc again: the inset's inside and the sweep along its outline are drawn on the grid
/// rather than offset outwards as polygons, which costs a buffer of every arc the inset has.
fn mark_reach(grid: &Grid, centres: &MultiPolygon, cells: &mut [Cell], radius: f64) {
    let mut mark = |range: Range<usize>| {
        for c in &mut cells[range] {
            if c.in_field() {
                c.flags |= IN_REACH;
            }
        }
    };
    for polygon in &centres.0 {
        grid.fill_polygon(polygon, &mut mark);
        for ring in std::iter::once(polygon.exterior()).chain(polygon.interiors()) {
            let mut line = ring.0.clone();
            // Round the ring's first corner too: the line closed on its second point.
            if let Some(&second) = ring.0.get(1) {
                line.push(second);
            }
            sweep_round(grid, &line, radius, &mut mark);
        }
    }
}

/// Calls `mark` with every cell the implement, a bar of half-width `half` square to its heading,
/// sweeps along `line`: the strip of each edge and, where the line turns, the sectors it swings
/// through round the point between them.
fn sweep(grid: &Grid, line: &[Coord], half: f64, mark: &mut dyn FnMut(Range<usize>)) {
    for (n, w) in line.windows(2).enumerate() {
        grid.fill_strip(w[0], w[1], half, mark);
        if let Some(&next) = line.get(n + 2) {
            grid.fill_swing(w[0], w[1], next, half, mark);
        }
    }
}

/// Calls `mark` with every cell of `line` swept round by a disc of `radius`, its ends cut square:
/// the strip of each edge and, where the line turns, the disc round the point between them (at a
/// slight turn the sectors either side, within a hair of the disc's part outside the strips).
fn sweep_round(grid: &Grid, line: &[Coord], radius: f64, mark: &mut dyn FnMut(Range<usize>)) {
    for (n, w) in line.windows(2).enumerate() {
        grid.fill_strip(w[0], w[1], radius, mark);
        if let Some(&next) = line.get(n + 2) {
            if turn_angle(w[0], w[1], next) > ROUND_ANGLE {
                grid.fill_disc(w[1], radius, mark);
            } else {
                grid.fill_swing(w[0], w[1], next, radius, mark);
            }
        }
    }
}

/// The figures of a tally's `cells` of which `counts` were kept.
fn figures(grid: &Grid, cells: &[Cell], counts: &Counts, width: f64) -> Coverage {
    let Counts {
        field: in_field,
        covered,
        twice,
        ..
    } = *counts;
    let reached = counts.reach + counts.covered_beyond_reach;
    let a = grid.cell_area();
    let field_area = in_field as f64 * a;
    let ratio = |cells: usize| {
        if field_area > 0.0 {
            (cells as f64 * a / field_area).clamp(0.0, 1.0)
        } else {
            0.0
        }
    };
    // Of the crop left standing (no line over it), what is in reach is what the opening holds.
    let uncovered = standing_parts(grid, cells, &standing_cells(cells), width);
    let covered_area = covered as f64 * a;
    Coverage {
        field_area_m2: field_area,
        covered_area_m2: covered_area,
        coverage_ratio: ratio(covered),
        reachable_ratio: ratio(reached),
        overlap_ratio: ratio(twice),
        uncovered_area_m2: (field_area - covered_area).greater(0.0),
        outside_area_m2: counts.outside as f64 * a,
        resolution_m: grid.cell,
        uncovered,
    }
}

/// The cells of the crop left standing (in the field, no line over them), ascending: found a
/// block of cells at a time, most blocks having none.
fn standing_cells(cells: &[Cell]) -> Vec<usize> {
    const BLOCK: usize = 64;
    let standing = |c: &Cell| c.in_field() & (c.count == 0);
    let mut out = Vec::new();
    for (n, block) in cells.chunks(BLOCK).enumerate() {
        if block.iter().fold(false, |any, c| any | standing(c)) {
            let cells = block.iter().enumerate().filter(|(_, c)| standing(c));
            out.extend(cells.map(|(i, _)| n * BLOCK + i));
        }
    }
    out
}

/// The parts of the field left standing larger than a quarter of a working width squared, with
/// their outlines, largest first: `standing` holds their cells, ascending.
fn standing_parts(grid: &Grid, cells: &[Cell], standing: &[usize], width: f64) -> Vec<Uncovered> {
    let a = grid.cell_area();
    let least = (width * width / 4.0).greater(a * 4.0);
    let in_set = |i: usize| cells[i].in_field() && cells[i].count == 0;
    let mut out: Vec<Uncovered> =
        outline::parts_from(grid.columns, grid.rows, standing.iter().copied(), in_set)
            .into_iter()
            .filter(|p| p.cells.len() as f64 * a >= least)
            .filter_map(|p| {
                let reachable = p.cells.iter().filter(|&&i| cells[i].flags & IN_REACH != 0);
                let reachable_m2 = reachable.count() as f64 * a;
                let polygon = outline::outline(grid, &p, grid.cell * 0.75)?;
                Some(Uncovered {
                    polygon,
                    area_m2: p.cells.len() as f64 * a,
                    reachable_m2,
                })
            })
            .collect();
    out.shared_sort_by(|x, y| y.area_m2.total_cmp(&x.area_m2));
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{coord, polygon, Distance, Euclidean};

    /// The counts of a tally's cells, counted afresh.
    fn recounted(tally: &Tally) -> Counts {
        let mut c = Counts::default();
        for cell in &tally.cells {
            let (field, reach) = (cell.in_field(), cell.flags & IN_REACH != 0);
            c.field += usize::from(field);
            c.reach += usize::from(reach);
            c.covered += usize::from(cell.count > 0);
            c.twice += usize::from(cell.count > 1);
            c.covered_beyond_reach += usize::from(cell.count > 0 && !reach);
            c.outside += usize::from(cell.flags & SWEPT_OFF_FIELD != 0);
        }
        c
    }

    #[test]
    fn the_counts_kept_as_lines_are_added_are_the_cells_counts() {
        // A field with a notch and a pond, worked by crossing lines, some past the boundary.
        let field = polygon![
            (x: 0., y: 0.), (x: 80., y: 0.), (x: 80., y: 60.), (x: 45., y: 60.),
            (x: 40., y: 20.), (x: 35., y: 60.), (x: 0., y: 60.)
        ];
        let pond = polygon![(x: 10., y: 10.), (x: 20., y: 12.), (x: 12., y: 25.)];
        let mut tally = Tally::new(&field, &[pond], 6.0).expect("a tally");
        let lines: Vec<Vec<Coord>> = (0..12)
            .map(|i| {
                let x = i as f64 * 7.5;
                vec![
                    coord! { x: x, y: -5.0 },
                    coord! { x: 80.0 - x, y: 65.0 },
                    coord! { x: x + 3.0, y: 30.0 },
                ]
            })
            .collect();
        for line in &lines {
            tally.work(std::slice::from_ref(line));
            assert_eq!(tally.counts, recounted(&tally));
        }
        let c = tally.coverage();
        assert!(c.overlap_ratio > 0.0 && c.outside_area_m2 > 0.0 && c.reachable_ratio < 1.0);
        tally.forget();
        assert_eq!(tally.counts, recounted(&tally));
        assert_eq!(tally.counts.covered, 0);
    }

    #[test]
    fn a_line_counts_once_per_cell_after_the_line_numbers_run_out() {
        // A line driven up and back over itself works its strip once, also after more lines
        // than the cells' numbers hold: the tally after 70,000 short lines is that of two.
        let field = polygon![(x: 0., y: 0.), (x: 12., y: 0.), (x: 12., y: 100.), (x: 0., y: 100.)];
        let short = vec![coord! { x: 9.0, y: 50.0 }, coord! { x: 9.0, y: 51.0 }];
        let up_and_back = vec![
            coord! { x: 3.0, y: 0.0 },
            coord! { x: 3.0, y: 100.0 },
            coord! { x: 3.0, y: 0.0 },
        ];
        let mut many = Tally::new(&field, &[], 6.0).expect("a tally");
        for _ in 0..70_000 {
            many.work(std::slice::from_ref(&short));
        }
        many.work(std::slice::from_ref(&up_and_back));
        let mut two = Tally::new(&field, &[], 6.0).expect("a tally");
        two.work(&[short.clone(), short, up_and_back]);
        let (many, two) = (many.coverage(), two.coverage());
        assert_eq!(many, two);
        assert!(
            two.overlap_ratio > 0.0 && two.overlap_ratio < 0.01,
            "{}",
            two.overlap_ratio
        );
    }

    #[test]
    fn a_round_drawn_as_many_short_edges_is_worked_in_full() {
        // A circle of radius 50 m as 400 edges (each turning 0.016 rad),
        // worked 12 m wide: the annulus from 44 to 56 m, π (56² - 44²) = 3,770 m². The strips
        // of the chords alone leave the wedges on the outside of every turn, 113 m² in all.
        let ring: Vec<Coord> = (0..=400)
            .map(|i| {
                let t = i as f64 * std::f64::consts::TAU / 400.0;
                coord! { x: 50.0 * t.cos(), y: 50.0 * t.sin() }
            })
            .collect();
        let field = polygon![(x: -100., y: -100.), (x: 100., y: -100.), (x: 100., y: 100.), (x: -100., y: 100.)];
        let c = measure(&field, &[], &[ring], 12.0);
        let annulus = std::f64::consts::PI * (56.0f64.powi(2) - 44.0f64.powi(2));
        assert!(
            (c.covered_area_m2 - annulus).abs() < 0.01 * annulus,
            "{} m² worked of {annulus}",
            c.covered_area_m2
        );
    }

    #[test]
    fn a_curve_is_worked_to_its_ends_and_no_farther() {
        // A quarter circle of radius 20 m as 30 edges (each turning 3 degrees), worked 24 m wide:
        // the bar across the heading sweeps the quarter annulus from 8 to 32 m, π/4 (32² - 8²)
        // = 754 m², its ends cut square. A disc of the implement's width at each point would
        // reach 12 m past both ends.
        let arc: Vec<Coord> = (0..=30)
            .map(|i| {
                let t = (3.0 * i as f64).to_radians();
                coord! { x: 20.0 * t.cos(), y: 20.0 * t.sin() }
            })
            .collect();
        let field =
            polygon![(x: -60., y: -60.), (x: 60., y: -60.), (x: 60., y: 60.), (x: -60., y: 60.)];
        let c = measure(&field, &[], &[arc], 24.0);
        let quarter = std::f64::consts::FRAC_PI_4 * (32.0f64.powi(2) - 8.0f64.powi(2));
        assert!(
            (c.covered_area_m2 - quarter).abs() < 0.02 * quarter,
            "{} m² worked of {quarter}",
            c.covered_area_m2
        );
    }

    #[test]
    fn the_reach_drawn_on_the_grid_is_the_opened_polygon() {
        // A field with a notch and a pond with a sharp corner, opened by 4 m: the cells the
        // inset swept round on the grid marks are those inside the opening computed as polygons
        // (inset and outset by i_overlay), but for cells a hair from its outline.
        let field = polygon![
            (x: 0., y: 0.), (x: 120., y: 0.), (x: 120., y: 80.), (x: 70., y: 80.),
            (x: 60., y: 30.), (x: 50., y: 80.), (x: 0., y: 80.)
        ];
        let pond = polygon![(x: 20., y: 20.), (x: 40., y: 25.), (x: 22., y: 50.)];
        let grid = Grid::over(field.bounding_rect().unwrap(), 0.5, 1_000_000);
        let mut marked = field_cells(&grid, &field, std::slice::from_ref(&pond));
        let centres = strip_centres(&field, std::slice::from_ref(&pond), 8.0);
        mark_reach(&grid, &centres, &mut marked, 4.0);
        let cells: Vec<bool> = marked.iter().map(|c| c.in_field()).collect();
        let drawn: Vec<bool> = marked.iter().map(|c| c.flags & IN_REACH != 0).collect();
        let region = field.difference(&MultiPolygon::new(vec![pond]));
        let opening = crate::headland::offset::open(&region, 4.0);
        let mut by_polygons = vec![false; grid.len()];
        for p in &opening.0 {
            grid.fill_polygon(p, &mut |r| {
                for i in r {
                    by_polygons[i] = cells[i];
                }
            });
        }
        let outline = geo::MultiLineString::new(
            opening
                .0
                .iter()
                .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
                .cloned()
                .collect(),
        );
        let mut inside = 0;
        for i in 0..grid.len() {
            inside += usize::from(by_polygons[i]);
            if drawn[i] != by_polygons[i] {
                let d = Euclidean.distance(&geo::Point::from(grid.centre(i)), &outline);
                assert!(d < 0.02, "cell {i} at {d} m from the opening's outline");
            }
        }
        assert!(inside > 10_000, "{inside}");
    }

    #[test]
    fn a_neck_narrower_than_the_implement_is_out_of_reach() {
        // A 200 m square with a 2 m wide, 100 m long arm: at 6 m the arm is out of reach, and
        // the square's corners lose (1 - π/4) 9 m² each.
        let field = polygon![
            (x: 0., y: 0.), (x: 200., y: 0.), (x: 200., y: 99.), (x: 300., y: 99.),
            (x: 300., y: 101.), (x: 200., y: 101.), (x: 200., y: 200.), (x: 0., y: 200.)
        ];
        let c = measure(&field, &[], &[], 6.0);
        assert_eq!(c.coverage_ratio, 0.0);
        let corners = 4.0 * (1.0 - std::f64::consts::FRAC_PI_4) * 9.0;
        let expected = (40_000.0 - corners) / 40_200.0;
        assert!(
            (c.reachable_ratio - expected).abs() < 0.002,
            "{}",
            c.reachable_ratio
        );
        assert_eq!(c.uncovered.len(), 1);
        assert!(c.uncovered[0].reachable_m2 < c.uncovered[0].area_m2 - 150.0);
    }

    #[test]
    fn a_forgotten_tally_counts_as_a_new_one() {
        let field = polygon![(x: 0., y: 0.), (x: 12., y: 0.), (x: 12., y: 100.), (x: 0., y: 100.)];
        let first = vec![vec![
            coord! { x: 11.0, y: 0.0 },
            coord! { x: 11.0, y: 100.0 },
        ]];
        let second = vec![vec![coord! { x: 3.0, y: 0.0 }, coord! { x: 3.0, y: 60.0 }]];
        let mut tally = Tally::new(&field, &[], 6.0).expect("a tally");
        tally.work(&first);
        tally.forget();
        tally.work(&second);
        let again = tally.coverage();
        let fresh = measure(&field, &[], &second, 6.0);
        assert_eq!(again.covered_area_m2, fresh.covered_area_m2);
        assert_eq!(again.overlap_ratio, fresh.overlap_ratio);
        assert_eq!(again.outside_area_m2, fresh.outside_area_m2);
        assert!((fresh.covered_area_m2 - 360.0).abs() < 20.0, "{fresh:?}");
    }

    #[test]
    fn a_strip_past_the_boundary_or_over_an_obstacle_is_worked_outside() {
        // A 12 x 100 m field: one swath at x = 3 inside, one at x = 11 whose strip reaches 2 m
        // past the east side (200 m²), and a 2 x 10 m obstacle under the first one's strip.
        let field = polygon![(x: 0., y: 0.), (x: 12., y: 0.), (x: 12., y: 100.), (x: 0., y: 100.)];
        let pole = polygon![(x: 1., y: 40.), (x: 3., y: 40.), (x: 3., y: 50.), (x: 1., y: 50.)];
        let worked = vec![
            vec![coord! { x: 3.0, y: 0.0 }, coord! { x: 3.0, y: 100.0 }],
            vec![coord! { x: 11.0, y: 0.0 }, coord! { x: 11.0, y: 100.0 }],
        ];
        let c = measure(&field, &[pole], &worked, 6.0);
        // Exact to a row of cells round each part.
        let slack = c.resolution_m * 2.0 * (100.0 + 2.0 + 10.0 + 2.0);
        assert!(
            (c.outside_area_m2 - 220.0).abs() <= slack,
            "{}",
            c.outside_area_m2
        );
        // Inside alone: nothing outside.
        let inside = measure(&field, &[], &worked[..1], 6.0);
        assert_eq!(inside.outside_area_m2, 0.0);
    }

    #[test]
    fn overlap_counts_area_worked_twice_but_not_a_line_over_itself() {
        let field = polygon![(x: 0., y: 0.), (x: 12., y: 0.), (x: 12., y: 100.), (x: 0., y: 100.)];
        // Two swaths 4 m apart (2 m of overlap), one of them driven there and back.
        let worked = vec![
            vec![
                coord! { x: 3.0, y: 0.0 },
                coord! { x: 3.0, y: 100.0 },
                coord! { x: 3.0, y: 0.0 },
            ],
            vec![coord! { x: 7.0, y: 0.0 }, coord! { x: 7.0, y: 100.0 }],
        ];
        let c = measure(&field, &[], &worked, 6.0);
        // Exact to a column of cells either way.
        let column = c.resolution_m * 100.0 / 1200.0;
        assert!(
            (c.overlap_ratio - 200.0 / 1200.0).abs() <= column,
            "{}",
            c.overlap_ratio
        );
        assert!((c.coverage_ratio - 1000.0 / 1200.0).abs() <= column);
    }
}
