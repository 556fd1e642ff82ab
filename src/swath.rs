//! Swaths: the straight strips the machine works, one working width wide, parallel to the driving
//! direction, covering the inner field.
//!
//! Centre lines are placed a working width apart across the inner field, the first half a width
//! from its edge (Zhou et al. 2.2.3). The strip left at the far side when the field's width is
//! not a whole number of working widths is still worked: the last line is moved back so that its
//! strip ends at the edge, overlapping its neighbour, rather than dropped (which leaves crop
//! standing, a known complaint about Fields2Cover). Lines are cut where they leave the inner field
//! or cross an obstacle; pieces shorter than a minimum length are left to the headland passes.
//! Where a headland is given, a swath may run on into it at a slanted end, as far as its strip
//! still works the inner field well ([`generate_reaching`]).

use crate::error::{ErrorCode, PlanError};
use crate::geometry::intervals::{difference, intersection, union, Intervals};
use crate::geometry::{Extremes, SweepFrame};
use crate::numbers::{Decimals, Shortest};
use crate::sort::SharedSort;
use geo::{Coord, Line, MultiPolygon};

/// Swath-line spacing below this fraction of the width is not worth an extra, overlapping line.
const LEFTOVER_TOLERANCE: f64 = 1e-3;
/// Pieces of one line closer than this (metres) are one swath: they meet where two parts of the
/// area touch.
const MERGE_GAP_M: f64 = 1e-3;

/// Where the swath lines lie across the field.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum LinePlacement {
    /// The first line half a width inside the area's edge (Zhou et al. 2.2.3), the following ones
    /// a width apart; a leftover strip at the far side gets one more, overlapping line.
    #[default]
    FromEdge,
    /// On a grid a width apart through `across` (a reference line: last year's AB line, or a
    /// line half a width inside a boundary edge); leftover strips at either side get one more,
    /// overlapping line each.
    Aligned {
        /// The `across` coordinate (in the sweep frame of the bearing) of one grid line.
        across: f64,
    },
}

/// What [`generate_with`] needs besides the area.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SwathSettings {
    /// Swath direction, compass radians.
    pub bearing: f64,
    /// Working width, metres.
    pub width: f64,
    /// Pieces shorter than this (metres) are dropped.
    pub min_length: f64,
    /// Where the lines lie across the area.
    pub placement: LinePlacement,
}
/// Most swath lines a field may need at one bearing (a 40 km field at 0.4 m, a 2 km field at
/// 2 cm); beyond that the width is a mistake, and the plan would take seconds and gigabytes.
pub const MAX_SWATH_LINES: usize = 100_000;

/// One swath: a straight piece of a swath line working the inner field.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Swath {
    /// Index among all swaths of the plan, ordered across the field, then along each line.
    pub index: usize,
    /// Its swath direction, compass radians in `[0, π)`: the field's direction, or that of the
    /// prohibited region it lies in.
    pub bearing: f64,
    /// The frame of its direction, in which `across` and `along` are measured.
    pub frame: SweepFrame,
    /// How far (metres, across) its strip overlaps the strip of the neighbouring line: zero
    /// except on a line placed to work the strip left over at the side of the field, which is
    /// narrower than a working width.
    pub overlap_m: f64,
    /// Index of the swath line it lies on, counted across the field (0 = leftmost looking along
    /// the driving direction).
    pub line_index: usize,
    /// Its centre line, from the end with the smaller to the end with the larger `along`
    /// coordinate, i.e. pointing in the swath direction. Driving may go either way.
    pub centre: Line,
    /// Offset of its line across the field, metres (the sweep frame's `across` coordinate).
    pub across: f64,
    /// Start and end along the line, metres (the sweep frame's `along` coordinates).
    pub along: (f64, f64),
}

impl Swath {
    /// Length of the swath, metres.
    pub fn length(&self) -> f64 {
        self.along.1 - self.along.0
    }
}

/// The swaths of a field: at the field's driving direction, and at their own directions in the
/// prohibited regions that forbid it.
#[derive(Debug, Clone)]
pub struct Swaths {
    /// The field's swath direction, compass radians in `[0, π)`.
    pub bearing: f64,
    /// The working width, metres.
    pub width: f64,
    /// The frame of the field's direction, in which its swath lines are `across = const`.
    pub frame: SweepFrame,
    /// The swaths, ordered by line, then along the line.
    pub swaths: Vec<Swath>,
    /// Pieces dropped because they were shorter than the minimum swath length.
    pub dropped: usize,
    /// Where the implement is lifted over small (class A) obstacles, ordered by swath.
    pub lifts: Vec<Lift>,
    /// The areas the swaths cover, each at one direction: the inner field (less the prohibited
    /// regions that forbid the field's direction), then those regions. Empty until the planner
    /// fills it.
    pub areas: Vec<SwathArea>,
}

/// An area worked at one direction, and its swaths.
#[derive(Debug, Clone, PartialEq)]
pub struct SwathArea {
    /// Its swaths, a range of indices into [`Swaths::swaths`].
    pub swaths: std::ops::Range<usize>,
    /// Their swath direction, compass radians in `[0, π)`.
    pub bearing: f64,
    /// The prohibited region (index into the field's) it is part of, if it is one.
    pub region: Option<usize>,
    /// The area.
    pub area: MultiPolygon,
    /// Whether it is a part the other areas' swaths and the headland passes left standing,
    /// worked afterwards ([`crate::fill`]).
    pub fill: bool,
}

/// A stretch of a swath where the implement is lifted over a small obstacle (class A) that the
/// swath runs past.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lift {
    /// Index of the swath.
    pub swath: usize,
    /// Index of the obstacle (into the field's obstacles).
    pub obstacle: usize,
    /// Start and end along the swath line, metres (the sweep frame's `along` coordinates).
    pub along: (f64, f64),
}

/// The stretches where swaths pass over the given obstacles (index and outline): wherever an
/// obstacle reaches into a swath's strip, the implement is lifted over the obstacle's length
/// along the swath.
///
/// ```
/// use furrow::swath::{generate, lifts};
/// use geo::{polygon, MultiPolygon};
///
/// let strip = polygon![(x: 0., y: 0.), (x: 30., y: 0.), (x: 30., y: 100.), (x: 0., y: 100.)];
/// let swaths = generate(&MultiPolygon::new(vec![strip]), 0.0, 6.0, 6.0)?;
/// // A 2 m pole at x = 11..13, y = 50..52: in the strip of the swath at x = 9 and the one at x = 15.
/// let pole = polygon![(x: 11., y: 50.), (x: 13., y: 50.), (x: 13., y: 52.), (x: 11., y: 52.)];
/// let l = lifts(&swaths, &[(0, &pole)]);
/// assert_eq!(l.iter().map(|l| l.swath).collect::<Vec<_>>(), vec![1, 2]);
/// assert_eq!(l[0].along, (50.0, 52.0));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn lifts(swaths: &Swaths, obstacles: &[(usize, &geo::Polygon)]) -> Vec<Lift> {
    let half = swaths.width / 2.0;
    let mut out = Vec::new();
    for &(index, polygon) in obstacles {
        let extent = |frame: &SweepFrame| {
            let mut c = (f64::INFINITY, f64::NEG_INFINITY);
            let mut a = (f64::INFINITY, f64::NEG_INFINITY);
            for &p in &polygon.exterior().0 {
                let (x, y) = frame.project(p);
                c = (c.0.lesser(x), c.1.greater(x));
                a = (a.0.lesser(y), a.1.greater(y));
            }
            (c, a)
        };
        let main = extent(&swaths.frame);
        for s in &swaths.swaths {
            let (c, a) = if s.frame == swaths.frame {
                main
            } else {
                extent(&s.frame)
            };
            if s.across + half <= c.0 || s.across - half >= c.1 {
                continue;
            }
            let from = a.0.greater(s.along.0);
            let to = a.1.lesser(s.along.1);
            if from < to {
                out.push(Lift {
                    swath: s.index,
                    obstacle: index,
                    along: (from, to),
                });
            }
        }
    }
    sort_lifts(&mut out);
    out
}

/// Puts lifts in the order [`Swaths::lifts`] keeps them: by swath, then along it.
pub fn sort_lifts(lifts: &mut [Lift]) {
    lifts.shared_sort_by(|x, y| {
        (x.swath, x.along.0)
            .partial_cmp(&(y.swath, y.along.0))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
}

/// Offsets (across the field) of the swath lines covering `[lo, hi]` with strips of `width`.
///
/// The first line is `width / 2` inside `lo`; lines follow `width` apart; if a strip narrower
/// than `width` remains at `hi`, one more line is placed `width / 2` inside `hi`.
///
/// ```
/// use furrow::swath::line_offsets;
///
/// assert_eq!(line_offsets(0.0, 12.0, 6.0), vec![3.0, 9.0]);
/// assert_eq!(line_offsets(0.0, 14.0, 6.0), vec![3.0, 9.0, 11.0]);
/// assert_eq!(line_offsets(0.0, 4.0, 6.0), vec![2.0]);
/// ```
pub fn line_offsets(lo: f64, hi: f64, width: f64) -> Vec<f64> {
    let extent = hi - lo;
    if extent.is_nan() || width.is_nan() || extent <= 0.0 || width <= 0.0 {
        return Vec::new();
    }
    if extent <= width {
        return vec![(lo + hi) / 2.0];
    }
    let full = (extent / width + LEFTOVER_TOLERANCE).floor() as usize;
    let mut offsets: Vec<f64> = Vec::with_capacity(full + 1);
    offsets.extend((0..full).map(|i| lo + (i as f64 + 0.5) * width));
    if extent - full as f64 * width > LEFTOVER_TOLERANCE * width {
        offsets.push(hi - width / 2.0);
    }
    offsets
}

/// Offsets of swath lines on the grid `origin + k·width` covering `[lo, hi]`, each marked `true`
/// where it is an extra line for a leftover strip (off the grid, overlapping its neighbour).
///
/// ```
/// use furrow::swath::aligned_offsets;
///
/// // Grid through 0 at 6 m over [-1, 13]: lines at 6 (strip 3..9) and two leftover lines for
/// // the strips -1..3 and 9..13.
/// assert_eq!(aligned_offsets(-1.0, 13.0, 6.0, 0.0), vec![(2.0, true), (6.0, false), (10.0, true)]);
/// ```
pub fn aligned_offsets(lo: f64, hi: f64, width: f64, origin: f64) -> Vec<(f64, bool)> {
    let extent = hi - lo;
    if !(extent > 0.0 && width > 0.0 && origin.is_finite()) {
        return Vec::new();
    }
    if extent <= width {
        return vec![((lo + hi) / 2.0, true)];
    }
    let tol = LEFTOVER_TOLERANCE * width;
    let k0 = ((lo + width / 2.0 - origin - tol) / width).ceil();
    let k1 = ((hi - width / 2.0 - origin + tol) / width).floor();
    let mut out: Vec<(f64, bool)> = Vec::new();
    if k1 >= k0 {
        out.extend((0..=(k1 - k0) as usize).map(|i| (origin + (k0 + i as f64) * width, false)));
    }
    let first_edge = out.first().map_or(hi, |l| l.0 - width / 2.0);
    if first_edge - lo > tol {
        out.insert(0, (lo + width / 2.0, true));
    }
    let last_edge = out.last().map_or(lo, |l| l.0 + width / 2.0);
    if hi - last_edge > tol {
        out.push((hi - width / 2.0, true));
    }
    out
}

/// Generates the swaths covering `inner` at swath direction `bearing` (compass radians), the
/// first line half a width inside the edge ([`LinePlacement::FromEdge`]).
///
/// ```
/// use furrow::swath::generate;
/// use geo::{polygon, MultiPolygon};
///
/// // A 30 m wide, 100 m long strip running north, worked 6 m wide: 5 swaths of 100 m.
/// let strip = polygon![(x: 0., y: 0.), (x: 30., y: 0.), (x: 30., y: 100.), (x: 0., y: 100.)];
/// let swaths = generate(&MultiPolygon::new(vec![strip]), 0.0, 6.0, 6.0)?;
/// assert_eq!(swaths.swaths.len(), 5);
/// assert!((swaths.swaths[0].centre.start.x - 3.0).abs() < 1e-9);
/// assert!((swaths.swaths[0].length() - 100.0).abs() < 1e-9);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn generate(
    inner: &MultiPolygon,
    bearing: f64,
    width: f64,
    min_length: f64,
) -> Result<Swaths, PlanError> {
    generate_with(
        inner,
        &SwathSettings {
            bearing,
            width,
            min_length,
            placement: LinePlacement::FromEdge,
        },
    )
}

/// Generates the swaths covering `area` with the given direction, width, minimum length and
/// line placement.
///
/// ```
/// use furrow::swath::{generate_with, LinePlacement, SwathSettings};
/// use geo::{polygon, MultiPolygon};
///
/// // Last year's lines ran north through x = 1: this year's follow them, 6 m apart.
/// let strip = polygon![(x: 0., y: 0.), (x: 30., y: 0.), (x: 30., y: 100.), (x: 0., y: 100.)];
/// let settings = SwathSettings {
///     bearing: 0.0, width: 6.0, min_length: 6.0, placement: LinePlacement::Aligned { across: 1.0 },
/// };
/// let swaths = generate_with(&MultiPolygon::new(vec![strip]), &settings)?;
/// let lines: Vec<f64> = swaths.swaths.iter().map(|s| s.across).collect();
/// // 3 (leftover strip 0..6 against the grid's 1 - 3 = -2), then 7, 13, 19, 25, and 27 for 28..30.
/// assert_eq!(lines, vec![3.0, 7.0, 13.0, 19.0, 25.0, 27.0]);
/// assert_eq!(swaths.swaths[0].overlap_m, 2.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn generate_with(area: &MultiPolygon, settings: &SwathSettings) -> Result<Swaths, PlanError> {
    generate_lines(area, settings, Ends::Centre)
}

/// [`generate_with`], each swath ending where its whole strip (the implement's width, not only
/// its centre line) is still inside `area`: for a field with no headland, whose swaths end at
/// the boundary itself, so that a wide implement does not work past a slanted end. Each end is
/// moved in to where both edges of the strip (1 mm in from its sides) are inside, if they come
/// inside within a width of it; along its length the strip is not tested, so a side that is
/// not parallel to the swaths, or a notch between the edges, may still be reached into (as by
/// the outer swaths of any field worked without headland); and a piece the trimming would leave
/// shorter than `min_length` is kept whole.
///
/// ```
/// use furrow::swath::{generate_with, generate_within, LinePlacement, SwathSettings};
/// use geo::{polygon, MultiPolygon};
///
/// // A 24 m strip whose north end slants up 1 m for every metre east, worked 12 m wide.
/// let field = polygon![(x: 0., y: 0.), (x: 24., y: 0.), (x: 24., y: 124.), (x: 0., y: 100.)];
/// let area = MultiPolygon::new(vec![field]);
/// let settings = SwathSettings {
///     bearing: 0.0, width: 12.0, min_length: 6.0, placement: LinePlacement::FromEdge,
/// };
/// // The first swath's centre line (x = 6) reaches y = 106; its strip (x = 0..12) fits to y = 100.
/// assert!((generate_with(&area, &settings)?.swaths[0].along.1 - 106.0).abs() < 1e-9);
/// assert!((generate_within(&area, &settings)?.swaths[0].along.1 - 100.0).abs() < 2e-3);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn generate_within(area: &MultiPolygon, settings: &SwathSettings) -> Result<Swaths, PlanError> {
    generate_lines(area, settings, Ends::StripInside)
}

/// Where the strips of an area's swaths may reach beyond it: the headland round it.
#[derive(Debug, Clone, Copy)]
pub struct Reach<'a> {
    /// Where a strip may be: the field less the obstacles that have headlands.
    pub region: &'a MultiPolygon,
    /// Every area swaths are laid in (the inner field): a strip stays out of the others.
    pub inner: &'a MultiPolygon,
    /// Where no strip of the swaths' direction may be: the prohibited regions that forbid it.
    pub avoid: Option<&'a MultiPolygon>,
}

/// [`generate_with`], each swath running on along its line as long as its strip still works
/// `area` well (a line a quarter of a width to one side of its centre is inside,
/// [`REACH_SIDE_WIDTHS`]) and the whole strip stays in the headland round it ([`Reach`]): an end
/// the area's edge cuts at a slant works most of the triangle beside it, and a line leaving the
/// area across an edge nearly parallel to it runs on along most of the wedge between its
/// neighbour and the headland. Only a piece long enough to be a swath runs on, and never into
/// the next piece of its line: where the headland crosses a line (round an obstacle, or a bay),
/// the line stays cut.
///
/// ```
/// use furrow::swath::{generate_reaching, generate_with, LinePlacement, Reach, SwathSettings};
/// use geo::{polygon, MultiPolygon};
///
/// // A 24 m strip whose north end slants up 1 m for every metre east, in a 12 m headland.
/// let inner = MultiPolygon::new(vec![polygon![(x: 0., y: 0.), (x: 24., y: 0.), (x: 24., y: 124.), (x: 0., y: 100.)]]);
/// let region = MultiPolygon::new(vec![polygon![(x: -12., y: -12.), (x: 36., y: -12.), (x: 36., y: 153.), (x: -12., y: 105.)]]);
/// let settings = SwathSettings {
///     bearing: 0.0, width: 6.0, min_length: 6.0, placement: LinePlacement::FromEdge,
/// };
/// // The first swath's centre line (x = 3) leaves the inner field at y = 103; the line a
/// // quarter width to its right (x = 4.5) at y = 104.5.
/// assert!((generate_with(&inner, &settings)?.swaths[0].along.1 - 103.0).abs() < 1e-9);
/// let reaching = generate_reaching(&inner, &settings, Reach { region: &region, inner: &inner, avoid: None })?;
/// assert!((reaching.swaths[0].along.1 - 104.5).abs() < 1e-9);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn generate_reaching(
    area: &MultiPolygon,
    settings: &SwathSettings,
    reach: Reach<'_>,
) -> Result<Swaths, PlanError> {
    generate_lines(area, settings, Ends::Reaching(reach))
}

/// Swaths on the lines at `offsets` (across, in the sweep frame of `bearing`, in increasing
/// order) cut to `area`: each piece at least `min_length` long is a swath, its line numbered by
/// its place in `offsets`. For lines placed by other means than a field's grid (the fill of
/// what the swaths leave, see [`crate::fill`]).
///
/// ```
/// use furrow::swath::on_lines;
/// use geo::{polygon, MultiPolygon};
///
/// let square = MultiPolygon::new(vec![polygon![(x: 0., y: 0.), (x: 10., y: 0.), (x: 10., y: 10.), (x: 0., y: 10.)]]);
/// let s = on_lines(&square, 0.0, 4.0, &[2.0, 8.0], 1.0);
/// assert_eq!(s.swaths.len(), 2);
/// assert!((s.swaths[1].centre.start.x - 8.0).abs() < 1e-9);
/// assert!((s.swaths[1].length() - 10.0).abs() < 1e-9);
/// ```
pub fn on_lines(
    area: &MultiPolygon,
    bearing: f64,
    width: f64,
    offsets: &[f64],
    min_length: f64,
) -> Swaths {
    let frame = SweepFrame::new(bearing);
    let mut swaths = Vec::new();
    let mut dropped = 0;
    let mut merged: Vec<(f64, f64)> = Vec::new();
    frame.clip_each(area, offsets, |line_index, line| {
        let Some(&across) = offsets.get(line_index) else {
            return;
        };
        merge_touching(line, &mut merged);
        for &(a0, a1) in &merged {
            if a1 - a0 < min_length.max(1e-6) {
                dropped += 1;
                continue;
            }
            swaths.push(Swath {
                index: swaths.len(),
                bearing,
                frame,
                overlap_m: 0.0,
                line_index,
                centre: Line::new(frame.point(across, a0), frame.point(across, a1)),
                across,
                along: (a0, a1),
            });
        }
    });
    Swaths {
        bearing,
        width,
        frame,
        swaths,
        dropped,
        lifts: Vec::new(),
        areas: Vec::new(),
    }
}

/// How far (in widths) from the centre line the line lies whose being in the area carries a
/// swath on into the headland ([`generate_reaching`]): a quarter of a width, halfway to the
/// strip's side. At the side itself, a swath would run on where its strip barely touches the
/// area, working mostly the headland again (on the register parcels, a 6 m drill's overlap
/// 4.0 % at a quarter width, 5.2 % at the side, for 1.59 against 1.45 % of the reachable crop
/// left standing).
const REACH_SIDE_WIDTHS: f64 = 0.25;

/// How far in from the strip's edges [`generate_within`] tests it, metres.
const STRIP_EDGE_IN_M: f64 = 1e-3;

/// Where the swaths of an area end.
#[derive(Clone, Copy)]
enum Ends<'a> {
    /// Where the centre line leaves the area.
    Centre,
    /// Where the whole strip is still inside ([`generate_within`]).
    StripInside,
    /// As far as one side of the strip works the area ([`generate_reaching`]).
    Reaching(Reach<'a>),
}

/// The swaths of `area`, ending as `ends` says.
fn generate_lines(
    area: &MultiPolygon,
    settings: &SwathSettings,
    ends: Ends<'_>,
) -> Result<Swaths, PlanError> {
    let SwathSettings {
        bearing,
        width,
        min_length,
        placement,
    } = *settings;
    let frame = SweepFrame::new(bearing);
    let mut swaths = Vec::new();
    let mut dropped = 0;
    if let Some((lo, hi)) = frame.across_extent(area) {
        let lines = (hi - lo) / width;
        if lines.is_nan() || lines > MAX_SWATH_LINES as f64 {
            return Err(PlanError::new(
                ErrorCode::FieldTooLarge,
                format!(
                    "at {} m working width the field needs {} swaths; the planner plans up to {MAX_SWATH_LINES}",
                    Shortest(width),
                    Decimals(lines, 0)
                ),
            ));
        }
        let placed: Vec<(f64, bool)> = match placement {
            LinePlacement::FromEdge => {
                let offsets = line_offsets(lo, hi, width);
                let n = offsets.len();
                let leftover =
                    n >= 2 && offsets[n - 1] - offsets[n - 2] < width * (1.0 - LEFTOVER_TOLERANCE);
                offsets
                    .into_iter()
                    .enumerate()
                    .map(|(i, c)| (c, (leftover && i + 1 == n) || n == 1))
                    .collect()
            }
            LinePlacement::Aligned { across } => aligned_offsets(lo, hi, width, across),
        };
        let offsets: Vec<f64> = placed.iter().map(|l| l.0).collect();
        let half = (width / 2.0 - STRIP_EDGE_IN_M).max(0.0);
        let own = match ends {
            Ends::Centre => None,
            Ends::StripInside | Ends::Reaching(_) => {
                Some(strip_lines(&frame, area, &offsets, half))
            }
        };
        let reach = match ends {
            Ends::Reaching(r) => Some((
                strip_lines(&frame, area, &offsets, width * REACH_SIDE_WIDTHS),
                strip_lines(&frame, r.region, &offsets, half),
                strip_lines(&frame, r.inner, &offsets, half),
                r.avoid
                    .map(|avoid| strip_lines(&frame, avoid, &offsets, half)),
            )),
            _ => None,
        };
        // Most lines give one swath.
        swaths.reserve(offsets.len());
        let mut merged: Vec<(f64, f64)> = Vec::new();
        let mut within: Vec<(f64, f64)> = Vec::new();
        frame.clip_each(area, &offsets, |line_index, line| {
            let Some(&(across, leftover)) = placed.get(line_index) else {
                return;
            };
            // A leftover line's strip overlaps the strip of the line beside it.
            let overlap_m = if leftover {
                let gap = |j: Option<&(f64, bool)>| j.map_or(width, |n| (n.0 - across).abs());
                let next_gap = gap(placed.get(line_index + 1));
                let prev_gap = gap(line_index.checked_sub(1).and_then(|p| placed.get(p)));
                (width - next_gap.min(prev_gap)).max(0.0)
            } else {
                0.0
            };
            let line = match (&own, &reach) {
                (Some(own), Some((sides, region, inner, avoid))) => {
                    let i = line_index;
                    let avoid = avoid.as_ref().and_then(|a| a.get(i));
                    let reach = reaching(&sides[i], &own[i], &region[i], &inner[i], avoid);
                    within = reaching_pieces(line, &reach, min_length);
                    &within[..]
                }
                (Some(own), None) => {
                    let [left, _, right] = &own[line_index];
                    within.clear();
                    // A piece the trimming would leave too short to work stays whole: a field
                    // whose every swath that would be is still worked.
                    within.extend(line.iter().map(|&piece| {
                        trim_ends(piece, left, right, width)
                            .filter(|t| t.1 - t.0 >= min_length)
                            .unwrap_or(piece)
                    }));
                    &within[..]
                }
                (None, _) => line,
            };
            merge_touching(line, &mut merged);
            for &(a0, a1) in &merged {
                if a1 - a0 < min_length.max(1e-6) {
                    dropped += 1;
                    continue;
                }
                swaths.push(Swath {
                    index: swaths.len(),
                    bearing,
                    frame,
                    overlap_m,
                    line_index,
                    centre: Line::new(frame.point(across, a0), frame.point(across, a1)),
                    across,
                    along: (a0, a1),
                });
            }
        });
    }
    Ok(Swaths {
        bearing,
        width,
        frame,
        swaths,
        dropped,
        lifts: Vec::new(),
        areas: Vec::new(),
    })
}

/// The pieces inside `area` of the left edge, the centre line and the right edge of each line's
/// strip (each edge [`STRIP_EDGE_IN_M`] in from the strip's side), by line.
fn strip_lines(
    frame: &SweepFrame,
    area: &MultiPolygon,
    offsets: &[f64],
    half: f64,
) -> Vec<[Intervals; 3]> {
    // Every line's three, in the increasing order the sweep needs (the edges of a leftover line
    // and its neighbour interleave).
    let mut lines: Vec<(f64, usize)> = offsets
        .iter()
        .enumerate()
        .flat_map(|(i, &c)| [(c - half, 3 * i), (c, 3 * i + 1), (c + half, 3 * i + 2)])
        .collect();
    lines.shared_sort_by(|a, b| a.0.total_cmp(&b.0));
    let sorted: Vec<f64> = lines.iter().map(|s| s.0).collect();
    let mut pieces = vec![Vec::new(); 3 * offsets.len()];
    frame.clip_each(area, &sorted, |k, line| {
        if let Some(&(_, which)) = lines.get(k) {
            pieces[which] = line.to_vec();
        }
    });
    let mut out = Vec::with_capacity(offsets.len());
    let mut it = pieces.into_iter();
    while let (Some(left), Some(centre), Some(right)) = (it.next(), it.next(), it.next()) {
        out.push([left, centre, right]);
    }
    out
}

/// Where along a line its strip reaches into the area from the headland: the pieces where one
/// of the lines `sides` is in the area and the whole strip in the region, out of the other
/// areas and out of `avoid` (the strip's edges and centre in `own`, `region`, `inner` and
/// `avoid`).
fn reaching(
    sides: &[Intervals; 3],
    own: &[Intervals; 3],
    region: &[Intervals; 3],
    inner: &[Intervals; 3],
    avoid: Option<&[Intervals; 3]>,
) -> Intervals {
    let [left, _, right] = sides;
    let mut pieces = union(left, right);
    for s in 0..3 {
        let mut allowed = difference(&region[s], &difference(&inner[s], &own[s]));
        if let Some(avoid) = avoid {
            allowed = difference(&allowed, &avoid[s]);
        }
        pieces = intersection(&pieces, &allowed);
    }
    pieces
}

/// The pieces of a line's centre inside the area (`centre`) with the stretches where its strip
/// reaches the area from the headland (`reach`, see [`reaching`]) added at their ends. Only a
/// piece long enough to be a swath (`min_length`) runs on, and never into the next: a line
/// stays cut where it crosses the headland (round an obstacle, or a bay), and a stub too short
/// to work stays dropped, so the blocks of the decompositions stay as they are.
fn reaching_pieces(centre: &[(f64, f64)], reach: &[(f64, f64)], min_length: f64) -> Intervals {
    let bridges: Intervals = centre
        .windows(2)
        .map(|w| (w[0].1, w[1].0))
        .filter(|g| g.1 - g.0 >= MERGE_GAP_M && reach.iter().any(|e| e.0 <= g.0 && g.1 <= e.1))
        .collect();
    let mut pieces = difference(&union(centre, reach), &bridges);
    pieces.retain(|p| {
        centre
            .iter()
            .any(|c| c.1 - c.0 >= min_length && c.0 <= p.1 && p.0 <= c.1)
    });
    pieces
}

/// A piece of a swath's centre line shortened at each end to where both edges of its strip
/// are inside, where the end is slanted: an edge whose point level with the end is outside the
/// area, and whose piece inside ends within `reach` of it, moves the end back to there. An edge
/// outside for longer runs along a side that is not parallel to the swath, not across its end,
/// and leaves the end as it is. `None` where nothing is left.
fn trim_ends(
    piece: (f64, f64),
    left: &[(f64, f64)],
    right: &[(f64, f64)],
    reach: f64,
) -> Option<(f64, f64)> {
    let (mut a0, mut a1) = piece;
    let inside = |side: &[(f64, f64)], a: f64| side.iter().any(|e| e.0 <= a && a <= e.1);
    for side in [left, right] {
        if !inside(side, piece.1) {
            let back = side
                .iter()
                .map(|e| e.1)
                .filter(|&e| e < piece.1 && e >= piece.1 - reach && e > piece.0)
                .fold(f64::NEG_INFINITY, f64::max);
            if back.is_finite() {
                a1 = a1.min(back);
            }
        }
        if !inside(side, piece.0) {
            let on = side
                .iter()
                .map(|e| e.0)
                .filter(|&e| e > piece.0 && e <= piece.0 + reach && e < piece.1)
                .fold(f64::INFINITY, f64::min);
            if on.is_finite() {
                a0 = a0.max(on);
            }
        }
    }
    (a1 > a0).then_some((a0, a1))
}

/// Pieces of one line with the gaps under [`MERGE_GAP_M`] closed, into `out` (cleared first).
fn merge_touching(pieces: &[(f64, f64)], out: &mut Vec<(f64, f64)>) {
    out.clear();
    for &(a0, a1) in pieces {
        match out.last_mut() {
            Some(last) if a0 - last.1 < MERGE_GAP_M => last.1 = last.1.max(a1),
            _ => out.push((a0, a1)),
        }
    }
}

impl Swaths {
    /// The index of the first swath that fills what the others leave ([`SwathArea::fill`]):
    /// they come after the field's swaths. The number of swaths when there is none.
    ///
    /// ```
    /// use furrow::swath::generate;
    /// use geo::{polygon, MultiPolygon};
    /// let field = polygon![(x: 0., y: 0.), (x: 60., y: 0.), (x: 60., y: 100.), (x: 0., y: 100.)];
    /// let swaths = generate(&MultiPolygon::new(vec![field]), 0.0, 6.0, 6.0)?;
    /// assert_eq!(swaths.first_fill_swath(), swaths.swaths.len());
    /// # Ok::<(), furrow::PlanError>(())
    /// ```
    pub fn first_fill_swath(&self) -> usize {
        self.areas
            .iter()
            .filter(|a| a.fill)
            .map(|a| a.swaths.start)
            .min()
            .unwrap_or(self.swaths.len())
            .min(self.swaths.len())
    }

    /// Keeps the swaths `keep` accepts, in order, numbered again from 0: their indices, the
    /// lifts over obstacles (those of swaths dropped go) and the areas' ranges follow.
    ///
    /// ```
    /// use furrow::swath::generate;
    /// use geo::{polygon, MultiPolygon};
    /// let field = polygon![(x: 0., y: 0.), (x: 60., y: 0.), (x: 60., y: 100.), (x: 0., y: 100.)];
    /// let mut swaths = generate(&MultiPolygon::new(vec![field]), 0.0, 6.0, 6.0)?;
    /// swaths.retain(|s| s.index % 2 == 1);
    /// assert_eq!(swaths.swaths.len(), 5);
    /// assert!(swaths.swaths.iter().enumerate().all(|(i, s)| s.index == i));
    /// # Ok::<(), furrow::PlanError>(())
    /// ```
    pub fn retain(&mut self, mut keep: impl FnMut(&Swath) -> bool) {
        // new_index[i]: how many swaths before i are kept (one more entry, for range ends).
        let mut new_index = Vec::with_capacity(self.swaths.len() + 1);
        let mut kept = Vec::with_capacity(self.swaths.len());
        let mut next = 0;
        for s in self.swaths.drain(..) {
            new_index.push(next);
            if keep(&s) {
                kept.push(Swath { index: next, ..s });
                next += 1;
            }
        }
        new_index.push(next);
        let is_kept = |i: usize| matches!((new_index.get(i), new_index.get(i + 1)), (Some(a), Some(b)) if b > a);
        self.lifts.retain(|l| is_kept(l.swath));
        for l in &mut self.lifts {
            if let Some(&n) = new_index.get(l.swath) {
                l.swath = n;
            }
        }
        for a in &mut self.areas {
            let at = |i: usize| new_index.get(i).copied().unwrap_or(next);
            a.swaths = at(a.swaths.start)..at(a.swaths.end);
        }
        self.swaths = kept;
    }

    /// Appends the swaths of another area (a prohibited region worked in its own direction):
    /// their indices follow on, and their lines are numbered apart from this set's so that no
    /// block joins swaths of the two.
    pub fn append(&mut self, other: Swaths) {
        let first = self.swaths.len();
        let line_base = self.swaths.last().map_or(0, |s| s.line_index + 2);
        self.swaths.extend(other.swaths.into_iter().map(|mut s| {
            s.index += first;
            s.line_index += line_base;
            s
        }));
        self.dropped += other.dropped;
        self.lifts.extend(other.lifts.into_iter().map(|mut l| {
            l.swath += first;
            l
        }));
        self.areas.extend(other.areas.into_iter().map(|mut a| {
            a.swaths = a.swaths.start + first..a.swaths.end + first;
            a
        }));
    }

    /// The end of swath `i` at its start (`at_end == false`) or end.
    pub fn end_point(&self, i: usize, at_end: bool) -> Option<Coord> {
        self.swaths
            .get(i)
            .map(|s| if at_end { s.centre.end } else { s.centre.start })
    }

    /// Total length of all swaths, metres.
    pub fn total_length(&self) -> f64 {
        self.swaths.iter().map(Swath::length).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{polygon, Contains, Point};
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn retain_renumbers_lifts_and_areas() {
        let field = polygon![(x: 0., y: 0.), (x: 60., y: 0.), (x: 60., y: 100.), (x: 0., y: 100.)];
        let mut swaths = generate(&MultiPolygon::new(vec![field]), 0.0, 6.0, 6.0)
            .unwrap_or_else(|e| panic!("{e}"));
        let lift = |swath| Lift {
            swath,
            obstacle: 0,
            along: (10.0, 20.0),
        };
        swaths.lifts = vec![lift(1), lift(4), lift(7)];
        let area = |r: std::ops::Range<usize>, fill| SwathArea {
            swaths: r,
            bearing: 0.0,
            region: None,
            area: MultiPolygon::new(vec![]),
            fill,
        };
        swaths.areas = vec![area(0..6, false), area(6..10, true)];
        let across: Vec<f64> = swaths.swaths.iter().map(|s| s.across).collect();
        // Drop swaths 0, 3 and 7.
        swaths.retain(|s| ![0, 3, 7].contains(&s.index));
        assert_eq!(swaths.swaths.len(), 7);
        let kept: Vec<f64> = swaths.swaths.iter().map(|s| s.across).collect();
        let expected: Vec<f64> = [1, 2, 4, 5, 6, 8, 9].iter().map(|&i| across[i]).collect();
        assert_eq!(kept, expected);
        assert!(swaths.swaths.iter().enumerate().all(|(i, s)| s.index == i));
        // Old 1 and 4 are now 0 and 2; the lift of the dropped 7 goes.
        let lifted: Vec<usize> = swaths.lifts.iter().map(|l| l.swath).collect();
        assert_eq!(lifted, vec![0, 2]);
        assert_eq!(swaths.areas[0].swaths, 0..4);
        assert_eq!(swaths.areas[1].swaths, 4..7);
        assert_eq!(swaths.first_fill_swath(), 4);
    }

    fn north(width: f64) -> SwathSettings {
        SwathSettings {
            bearing: 0.0,
            width,
            min_length: width,
            placement: LinePlacement::FromEdge,
        }
    }

    #[test]
    fn strips_within_end_where_a_slanted_end_lets_both_edges_in() {
        // A 36 m strip, its south end slanting down 1 m per 2 m east: y = -x/2 along it.
        let field =
            polygon![(x: 0., y: 0.), (x: 36., y: -18.), (x: 36., y: 200.), (x: 0., y: 200.)];
        let area = MultiPolygon::new(vec![field.clone()]);
        let within = generate_within(&area, &north(12.0)).unwrap();
        let plain = generate_with(&area, &north(12.0)).unwrap();
        assert_eq!(within.swaths.len(), plain.swaths.len());
        for (w, p) in within.swaths.iter().zip(&plain.swaths) {
            // The centre line starts at y = -c/2, the strip's east edge at -(c + 6)/2 and its
            // west edge at -(c - 6)/2: the strip fits from the west edge's y on.
            let c = w.across;
            assert!((p.along.0 + c / 2.0).abs() < 1e-9, "{c}: {:?}", p.along);
            assert!(
                (w.along.0 + (c - 6.0) / 2.0).abs() < 1e-2,
                "{c}: {:?}",
                w.along
            );
            assert_eq!(w.along.1, p.along.1);
            // Both corners of the strip's south end are in the field (1 mm in).
            for side in [-5.999, 5.999] {
                let corner = w.frame.point(c + side, w.along.0 + 1e-6);
                assert!(field.contains(&Point::from(corner)), "{c}{side:+}");
            }
        }
    }

    #[test]
    fn strips_within_keep_their_length_beside_a_side_not_parallel_to_them() {
        // A strip 36 m wide at its foot and 37 m at its head: the outer swaths' edges leave the
        // field along the east side, not across the ends, which are square.
        let field = polygon![(x: 0., y: 0.), (x: 36., y: 0.), (x: 37., y: 200.), (x: 0., y: 200.)];
        let area = MultiPolygon::new(vec![field]);
        let within = generate_within(&area, &north(12.0)).unwrap();
        let plain = generate_with(&area, &north(12.0)).unwrap();
        let along = |s: &Swaths| s.swaths.iter().map(|w| w.along).collect::<Vec<_>>();
        assert_eq!(along(&within), along(&plain));
    }

    #[test]
    fn a_piece_the_trimming_would_leave_too_short_stays_whole() {
        let piece = (0.0, 10.0);
        // The west edge is inside only over 8..10 near the end: trimmed to 8..10, shorter
        // than a minimum of 6 m, so generate_within keeps the piece whole (trim_ends says 8..10).
        assert_eq!(
            trim_ends(piece, &[(8.0, 10.0)], &[(0.0, 10.0)], 12.0),
            Some((8.0, 10.0))
        );
        // Both edges inside at both ends: untouched.
        assert_eq!(
            trim_ends(piece, &[(0.0, 10.0)], &[(-1.0, 11.0)], 12.0),
            Some(piece)
        );
        // An edge inside only far from both ends (beyond the reach): untouched.
        assert_eq!(
            trim_ends((0.0, 100.0), &[(40.0, 50.0)], &[(0.0, 100.0)], 12.0),
            Some((0.0, 100.0))
        );
        // Edges that leave nothing between them.
        assert_eq!(trim_ends(piece, &[(0.0, 3.0)], &[(7.0, 10.0)], 12.0), None);
    }

    #[test]
    fn leftover_strip_gets_an_overlapping_swath() {
        // 32 m across at 6 m: five full strips and a 2 m strip, worked by a sixth line at 29 m.
        let offsets = line_offsets(0.0, 32.0, 6.0);
        assert_eq!(offsets, vec![3.0, 9.0, 15.0, 21.0, 27.0, 29.0]);
    }

    #[test]
    fn swaths_split_at_holes_and_stay_inside() {
        let field = polygon!(
            exterior: [(x: 0., y: 0.), (x: 100., y: 0.), (x: 100., y: 60.), (x: 0., y: 60.)],
            interiors: [[(x: 40., y: 20.), (x: 60., y: 20.), (x: 60., y: 40.), (x: 40., y: 40.)]],
        );
        let inner = MultiPolygon::new(vec![field.clone()]);
        // Swaths running east (bearing 90 degrees): ten lines at y = 57, 51, ..., 3.
        let s = generate(&inner, FRAC_PI_2, 6.0, 6.0).unwrap();
        let through_hole = s
            .swaths
            .iter()
            .filter(|w| (20.0..=40.0).contains(&w.centre.start.y));
        assert_eq!(through_hole.count(), 8); // lines at y = 21, 27, 33, 39, each in two
        for w in &s.swaths {
            let mid = Point((w.centre.start + w.centre.end) / 2.0);
            assert!(field.contains(&mid));
            assert!(w.centre.start.x < w.centre.end.x, "swaths point east");
        }
        assert_eq!(s.swaths.len(), 6 + 4 * 2);
    }

    #[test]
    fn short_pieces_are_dropped() {
        // A triangle: the lines near its tip are short.
        let tri = polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 0., y: 50.)];
        let s = generate(&MultiPolygon::new(vec![tri]), 0.0, 6.0, 10.0).unwrap();
        assert!(s.dropped > 0);
        assert!(s.swaths.iter().all(|w| w.length() >= 10.0));
    }

    /// Swaths 6 m wide running north, the first line half a width in.
    const NORTH_6M: SwathSettings = SwathSettings {
        bearing: 0.0,
        width: 6.0,
        min_length: 6.0,
        placement: LinePlacement::FromEdge,
    };

    /// [`NORTH_6M`]'s swaths of `inner` reaching into the headland of `region`.
    fn reaching_into(inner: &MultiPolygon, region: &MultiPolygon) -> Swaths {
        let reach = Reach {
            region,
            inner,
            avoid: None,
        };
        generate_reaching(inner, &NORTH_6M, reach).unwrap_or_else(|e| panic!("{e}"))
    }

    /// The share of `area` (sampled on a 0.25 m grid) that no swath's strip of `width` covers.
    fn left_standing(area: &geo::Polygon, swaths: &Swaths, width: f64) -> f64 {
        let (mut inside, mut left) = (0usize, 0usize);
        let rect = geo::BoundingRect::bounding_rect(area).unwrap_or_else(|| panic!("a rectangle"));
        let steps = |lo: f64, hi: f64| ((hi - lo) / 0.25) as usize;
        for i in 0..steps(rect.min().x, rect.max().x) {
            for j in 0..steps(rect.min().y, rect.max().y) {
                let p = Point::new(
                    rect.min().x + 0.125 + 0.25 * i as f64,
                    rect.min().y + 0.125 + 0.25 * j as f64,
                );
                if !area.contains(&p) {
                    continue;
                }
                inside += 1;
                let (c, a) = swaths.frame.project(p.0);
                let worked = swaths.swaths.iter().any(|s| {
                    (c - s.across).abs() <= width / 2.0 && s.along.0 <= a && a <= s.along.1
                });
                left += usize::from(!worked);
            }
        }
        left as f64 / inside as f64
    }

    #[test]
    fn swaths_reaching_into_the_headland_work_the_slivers_their_ends_and_sides_leave() {
        // An inner field with a slanted north end and an east side leaning 3 degrees off the
        // swaths, inside a 12 m headland (the region: the inner field grown by 12 m).
        let inner_ring =
            polygon![(x: 0., y: 0.), (x: 40., y: 0.), (x: 50., y: 200.), (x: 0., y: 160.)];
        let inner = MultiPolygon::new(vec![inner_ring.clone()]);
        let region = crate::headland::offset::outset(&inner, 12.0);
        let cut = generate_with(&inner, &NORTH_6M).unwrap_or_else(|e| panic!("{e}"));
        let reaching = reaching_into(&inner, &region);
        let (before, after) = (
            left_standing(&inner_ring, &cut, 6.0),
            left_standing(&inner_ring, &reaching, 6.0),
        );
        assert!(before > 0.01, "the cut swaths leave {before}");
        assert!(
            after < before / 3.0,
            "reaching leaves {after} against {before}"
        );
        // Every strip stays in the region: its four corners (1 mm in) are inside.
        for s in &reaching.swaths {
            for (c, a) in [
                (-2.999, s.along.0),
                (2.999, s.along.0),
                (-2.999, s.along.1),
                (2.999, s.along.1),
            ] {
                let corner = Point::from(s.frame.point(s.across + c, a));
                assert!(
                    region.contains(&corner),
                    "swath {} reaches out at {corner:?}",
                    s.index
                );
            }
        }
    }

    #[test]
    fn a_line_the_headland_crosses_stays_cut() {
        // A 60 m square inner field with a hole 20 m across (an obstacle's headland): the line
        // past the hole's side, whose strip reaches round it, is not joined across it.
        let inner_ring = polygon!(
            exterior: [(x: 0., y: 0.), (x: 60., y: 0.), (x: 60., y: 100.), (x: 0., y: 100.)],
            interiors: [[(x: 20., y: 40.), (x: 40., y: 40.), (x: 40., y: 60.), (x: 20., y: 60.)]],
        );
        let inner = MultiPolygon::new(vec![inner_ring]);
        let region = MultiPolygon::new(vec![
            polygon![(x: -12., y: -12.), (x: 72., y: -12.), (x: 72., y: 112.), (x: -12., y: 112.)],
        ]);
        let reaching = reaching_into(&inner, &region);
        // The line at x = 21 runs 1 m into the hole: cut there, its pieces run on into it as far
        // as the line at x = 19.5 is in the inner field (not at all: the hole's side is at 20).
        let pieces: Vec<(f64, f64)> = reaching
            .swaths
            .iter()
            .filter(|s| s.across == 21.0)
            .map(|s| s.along)
            .collect();
        assert_eq!(pieces, vec![(0.0, 40.0), (60.0, 100.0)]);
    }
}
