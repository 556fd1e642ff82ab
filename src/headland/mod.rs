//! Headlands: the passes driven around the field boundary and around obstacles, where the
//! machine turns at the ends of the swaths, and the inner field they leave for the swaths.
//!
//! The passes are measured from the *region*: the field less the obstacles that get headlands
//! (classes B, C and D, see [`crate::obstacles`]). Pass `k` (1 = outermost) of width `w` has its
//! centre line `(k - 1/2)·w` inside the region's boundary, so around an obstacle it runs
//! `(k - 1/2)·w` outside it; the inner field starts `h·w` inside (Zhou et al. 2.2.1, 2.2.2).
//!
//! Each pass is made drivable: the set of points at least `(k - 1/2)·w` inside is *opened* by a
//! disc of the turning radius ([`offset::open`]), which rounds every convex corner sharper than
//! the turning radius allows to an arc of that radius and cuts necks too narrow to turn in. The
//! crop this leaves at the corners is measured ([`Headlands::uncovered_area_m2`]). An opening
//! never moves a pass outwards, so passes stay `w` or more apart and never cross each other, the
//! boundary or an obstacle. At concave corners (and round obstacles) the passes are arcs of
//! radius `(k - 1/2)·w` around the corner; where that is less than the turning radius the
//! machine needs a manoeuvre there, which the turn stage plans.
//!
//! Where a narrow neck closes up an offset, the pass splits into several closed parts; passes
//! that find no room vanish. Along edges without headland (only-where-needed mode, or edges the
//! user set to 0 passes, see [`edges`]) the passes are open lines that end where the swaths
//! along those edges begin.

pub mod complexity;
pub mod edges;
pub mod offset;
pub mod passes;

pub use edges::{EdgePasses, HeadlandMode};

use crate::error::{ErrorCode, PlanError};
use crate::field::Field;
use crate::geometry::point_segment_distance;
use crate::geometry::BooleanOps;
use crate::geometry::PlanarHypot;
use crate::numbers::Shortest;
use geo::{Area, Coord, Euclidean, Length, LineString, MultiPolygon, Polygon};
use offset::{drop_slivers, inset, line_band, open, outset, outset_fine};
use serde::Serialize;

/// When the headland passes are worked.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum HeadlandOrder {
    /// Before the swaths, from the outermost pass in: the machine opens up the field edge first,
    /// as in harvesting (Zhou et al. 2.1).
    First,
    /// After the swaths, from the innermost pass out, finishing at the field edge, as in seeding:
    /// the turns on the headland are worked over last.
    #[default]
    Last,
}

crate::named::named!(HeadlandOrder { "first" => First, "last" => Last });

/// How the sharp corners of the headland passes are driven.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum HeadlandCorners {
    /// Worked into where a manoeuvre inside the field does it, by a machine that reverses (its
    /// passes exact); rounded at the turning radius otherwise, their crop left standing.
    #[default]
    Auto,
    /// Every pass rounded at the turning radius.
    Round,
    /// Every pass exact, every sharp corner worked into: by the cheapest manoeuvre inside the
    /// field, or, where none is (most corners of a machine that does not reverse), one that
    /// leaves it, warned of.
    Manoeuvre,
}

crate::named::named!(HeadlandCorners { "auto" => Auto, "round" => Round, "manoeuvre" => Manoeuvre });

/// What a headland pass runs around.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PassAround {
    /// The field boundary (and obstacles merged into it).
    Field,
    /// An obstacle (or a group of obstacles) inside the field.
    Obstacle,
    /// The border between two blocks of different directions whose swaths both end there: the
    /// pass runs along it, inside one of them.
    Block,
    /// Crop the passes and swaths leave standing (a narrow arm, a neck): the pass runs along
    /// the outline of what is left, half a width in ([`crate::fill::along`]).
    Fill,
}

impl PassAround {
    /// The name in the plan output.
    pub fn as_str(self) -> &'static str {
        match self {
            PassAround::Field => "field",
            PassAround::Obstacle => "obstacle",
            PassAround::Block => "block",
            PassAround::Fill => "fill",
        }
    }
}

/// One headland pass: a closed path around the field, an obstacle or one part of either at a
/// constant distance from it; or, where some edges have no headland, an open line along the
/// edges that have one.
#[derive(Debug, Clone, PartialEq)]
pub struct HeadlandPass {
    /// Which pass this is, counted from the boundary (or obstacle) outwards: 1 is the one
    /// nearest to it.
    pub index: usize,
    /// Its centre line; a closed pass repeats its first point at the end and runs
    /// counter-clockwise round the field (clockwise round an obstacle).
    pub line: LineString,
    /// Whether the pass is a closed path.
    pub closed: bool,
    /// What it runs around.
    pub around: PassAround,
}

impl HeadlandPass {
    /// Length of the pass, metres.
    pub fn length(&self) -> f64 {
        Euclidean.length(&self.line)
    }
}

/// The headland passes of a field and the inner field they leave.
#[derive(Debug, Clone)]
pub struct Headlands {
    /// The passes, nearest to the boundary first; a pass that splits at a neck gives several
    /// entries with the same index.
    pub passes: Vec<HeadlandPass>,
    /// The inner field: where the swaths go. Possibly several parts; empty where the passes
    /// take up the whole field (a strip a few widths wide worked by its passes alone).
    pub inner: MultiPolygon,
    /// The field less the obstacles that have headlands: what the passes are measured from.
    pub region: MultiPolygon,
    /// Passes along each edge of the field boundary's outer ring (edge `i` from point `i`).
    pub edge_passes: Vec<u32>,
    /// Area between the region's boundary and the inner field, square metres.
    pub area_m2: f64,
    /// Area of the headland no pass covers, square metres: corners rounded to the turning
    /// radius, and necks too narrow to turn in. Estimated as the headland area less the width
    /// times the length of the passes.
    pub uncovered_area_m2: f64,
}

/// The settings of the headland stage.
#[derive(Debug, Clone, Copy)]
pub struct HeadlandSettings<'a> {
    /// Working width, metres: the width of a pass.
    pub width: f64,
    /// Turning radius, metres: passes are rounded to it at convex corners.
    pub turn_radius: f64,
    /// Whether the passes are the exact offsets, not rounded: for a machine that reverses, which
    /// works into their corners (see [`crate::path::follow`]).
    pub exact: bool,
    /// Passes around each obstacle that has a headland.
    pub obstacle_passes: u32,
    /// Passes along each edge of the boundary's outer ring (edge `i` from point `i`).
    pub edge_passes: &'a [u32],
    /// Whether the passes go on to the middle of the field (`headlandPasses: "all"`): after the
    /// last that finds room, one more goes round what is left narrower than a pass, a quarter
    /// width into it, and no inner field is left for swaths. Where some edges have fewer passes
    /// than others (edge passes, or a headland only where swaths end), passes are laid along
    /// the others until they find no room, and the inner field is what they leave.
    pub to_middle: bool,
}

/// Cuts `passes` headland passes of `width` all around the field and its obstacles, with sharp
/// corners (turning radius 0): Fields2Cover's constant-width headland.
///
/// ```
/// use furrow::field::Field;
/// use furrow::headland::constant_width;
///
/// // A rectangle of about 333 m by 112 m.
/// let text = r#"{"type": "Polygon", "coordinates": [[[24.05, 60.25], [24.056, 60.25],
///     [24.056, 60.251], [24.05, 60.251], [24.05, 60.25]]]}"#;
/// let (field, _) = Field::from_geojson_str(text)?;
/// let headlands = constant_width(&field, 6.0, 2)?;
/// assert_eq!(headlands.passes.len(), 2);
/// // The headland is a 12 m wide band around the field.
/// let perimeter = 2.0 * (333.0 + 111.5);
/// assert!((headlands.area_m2 / (12.0 * perimeter) - 1.0).abs() < 0.06);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn constant_width(field: &Field, width: f64, passes: u32) -> Result<Headlands, PlanError> {
    let holes: Vec<Polygon> = field.obstacles.iter().map(|o| o.polygon.clone()).collect();
    let edges = vec![passes; field.boundary.exterior().0.len().saturating_sub(1)];
    build(
        &field.boundary,
        &holes,
        &HeadlandSettings {
            width,
            turn_radius: 0.0,
            exact: true,
            obstacle_passes: passes,
            edge_passes: &edges,
            to_middle: false,
        },
    )
    .map_err(|e| e.at_feature(field.feature))
}

/// Builds the headland passes and the inner field of a boundary with holes (the obstacles that
/// get headlands). Passes that leave no inner field are still laid (the field is worked by
/// them alone); a field no pass fits into is the error `headland_consumes_field`.
///
/// ```
/// use furrow::headland::{build, HeadlandSettings};
/// use geo::{polygon, Area};
///
/// // A 200 x 100 m field with headland along its short (east and west) edges only.
/// let field = polygon![(x: 0., y: 0.), (x: 200., y: 0.), (x: 200., y: 100.), (x: 0., y: 100.)];
/// let settings = HeadlandSettings {
///     width: 6.0,
///     turn_radius: 8.0,
///     exact: false,
///     obstacle_passes: 2,
///     edge_passes: &[0, 2, 0, 2],
///     to_middle: false,
/// };
/// let h = build(&field, &[], &settings)?;
/// assert!((h.inner.unsigned_area() - 176.0 * 100.0).abs() < 1e-6);
/// assert_eq!(h.passes.len(), 4); // two open passes at each end
/// assert!(h.passes.iter().all(|p| !p.closed));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn build(
    boundary: &Polygon,
    holes: &[Polygon],
    settings: &HeadlandSettings,
) -> Result<Headlands, PlanError> {
    let w = settings.width;
    let h = settings.obstacle_passes;
    let region = if holes.is_empty() {
        MultiPolygon::new(vec![boundary.clone()])
    } else {
        drop_slivers(boundary.difference(&MultiPolygon::new(holes.to_vec())))
    };
    let ring = &boundary.exterior().0;
    let edge_count = ring.len().saturating_sub(1);
    let edge_passes: Vec<u32> = (0..edge_count)
        .map(|i| settings.edge_passes.get(i).copied().unwrap_or(h))
        .collect();
    let first = edge_passes.first().copied().unwrap_or(h);
    let uniform = edge_passes.iter().all(|&n| n == first) && (holes.is_empty() || first == h);
    let most = edge_passes
        .iter()
        .copied()
        .chain((!holes.is_empty()).then_some(h))
        .max()
        .unwrap_or(0);

    let mut passes = Vec::new();
    for k in 1..=most.saturating_add(u32::from(settings.to_middle)) {
        let d = (k as f64 - 0.5) * w;
        let constraints = if uniform {
            Vec::new()
        } else {
            constraints(ring, holes, &edge_passes, h, |n| {
                if n >= k {
                    (d, true)
                } else {
                    ((n as f64 + 0.5) * w, false)
                }
            })
        };
        // The opening of the pass's room by the turning disc; where the disc fits nowhere, the
        // room itself: the pass is laid exact and the path drives its corners with manoeuvres
        // (lifted where one would work outside), rather than dropped.
        let mut drivable = if settings.exact {
            if uniform {
                inset(&region, d)
            } else {
                keep_clear(&region, &constraints)
            }
        } else if uniform {
            // The opening of the inset by d is the outset of the inset by d + r.
            let opened = outset(
                &inset(&region, d + settings.turn_radius),
                settings.turn_radius,
            );
            if opened.0.is_empty() {
                inset(&region, d)
            } else {
                opened
            }
        } else {
            let room = keep_clear(&region, &constraints);
            let opened = open(&room, settings.turn_radius);
            if opened.0.is_empty() {
                room
            } else {
                opened
            }
        };
        let middle = drivable.0.is_empty() && settings.to_middle && uniform;
        if middle {
            // What the last pass leaves, narrower than a pass: one more round it, a quarter
            // width into it, works it from both sides.
            drivable = inset(&region, (k as f64 - 0.75) * w);
        }
        if drivable.0.is_empty() {
            // No room for this pass, nor for any deeper one.
            break;
        }
        for polygon in &drivable.0 {
            let rings = std::iter::once((polygon.exterior(), PassAround::Field)).chain(
                polygon
                    .interiors()
                    .iter()
                    .map(|r| (r, PassAround::Obstacle)),
            );
            for (r, around) in rings {
                // Slivers that boolean operations leave are not passes.
                let r = without_crumbs(r);
                if r.0.len() < 4
                    || Polygon::new(r.clone(), vec![]).unsigned_area() < offset::MIN_PART_AREA_M2
                {
                    continue;
                }
                if uniform {
                    passes.push(HeadlandPass {
                        index: k as usize,
                        line: r,
                        closed: true,
                        around,
                    });
                } else {
                    for (line, closed) in pass_lines(&r, &constraints, w / 2.0) {
                        passes.push(HeadlandPass {
                            index: k as usize,
                            line,
                            closed,
                            around,
                        });
                    }
                }
            }
        }
        if middle {
            break;
        }
    }

    let inner = if settings.to_middle && uniform {
        MultiPolygon::new(Vec::new())
    } else if uniform {
        inset(&region, first as f64 * w)
    } else {
        let cs = constraints(ring, holes, &edge_passes, h, |n| (n as f64 * w, n > 0));
        let blocking: Vec<Constraint> = cs.into_iter().filter(|c| c.high).collect();
        keep_clear(&region, &blocking)
    };
    if inner.0.is_empty() && passes.is_empty() {
        return Err(PlanError::new(
            ErrorCode::HeadlandConsumesField,
            format!(
                "no headland pass of {} m fits into the field with turns of {} m radius; use a narrower width or a smaller turning radius",
                Shortest(w),
                Shortest(settings.turn_radius)
            ),
        ));
    }
    let inner_area = inner.unsigned_area();
    let area_m2 = (region.unsigned_area() - inner_area).max(0.0);
    // A pass of length L covers w·L of crop (the tube formula: exact where the strip along it
    // does not overlap itself, i.e. where it curves no tighter than w/2, which the rounding to
    // the turning radius and the arcs of at least w/2 at concave corners ensure).
    let worked: f64 = passes.iter().map(|p| p.length() * w).sum();
    let uncovered_area_m2 = (area_m2 - worked).max(0.0);
    Ok(Headlands {
        passes,
        inner,
        region,
        edge_passes,
        area_m2,
        uncovered_area_m2,
    })
}

/// Points closer together than this (metres) are one point of a pass.
const CRUMB_M: f64 = 1e-3;

/// A ring without the crumbs boolean operations leave: points within [`CRUMB_M`] of the one
/// before.
fn without_crumbs(ring: &LineString) -> LineString {
    let mut out: Vec<Coord> = Vec::with_capacity(ring.0.len());
    for &p in &ring.0 {
        if out
            .last()
            .is_none_or(|q: &Coord| (p.x - q.x).planar_hypot(p.y - q.y) >= CRUMB_M)
        {
            out.push(p);
        }
    }
    // Keep the ring closed on its first point.
    if let (Some(&first), Some(last)) = (ring.0.first(), out.last_mut()) {
        *last = first;
    }
    LineString::new(out)
}

/// A stretch of boundary (a run of edges) or an obstacle that passes keep a distance from.
#[derive(Debug, Clone)]
struct Constraint {
    shape: Shape,
    /// The distance to keep, metres.
    distance: f64,
    /// Whether the pass being built runs along it (rather than just keeping clear of it).
    high: bool,
}

#[derive(Debug, Clone)]
enum Shape {
    Run(LineString),
    Hole(Polygon),
}

impl Constraint {
    /// How much further than its distance a point is from it.
    fn excess(&self, p: Coord) -> f64 {
        let ring = match &self.shape {
            Shape::Run(line) => line,
            Shape::Hole(polygon) => polygon.exterior(),
        };
        let d = ring
            .0
            .windows(2)
            .map(|s| point_segment_distance(p, s[0], s[1]))
            .fold(f64::INFINITY, f64::min);
        d - self.distance
    }

    fn band(&self) -> MultiPolygon {
        match &self.shape {
            Shape::Run(line) => line_band(line, self.distance),
            Shape::Hole(polygon) => {
                outset_fine(&MultiPolygon::new(vec![polygon.clone()]), self.distance)
            }
        }
    }
}

/// The constraints of one pass: runs of boundary edges with equal (distance, high) from `rule`
/// applied to each edge's pass count, and the holes with `rule` applied to `hole_passes`.
fn constraints(
    ring: &[Coord],
    holes: &[Polygon],
    edge_passes: &[u32],
    hole_passes: u32,
    rule: impl Fn(u32) -> (f64, bool),
) -> Vec<Constraint> {
    let mut out = Vec::new();
    let n = edge_passes.len();
    if n > 0 && ring.len() == n + 1 {
        let key = |i: usize| rule(edge_passes[i % n]);
        // Start at an edge whose key differs from the one before it, so that no run wraps.
        let start = (0..n).find(|&i| key(i) != key((i + n - 1) % n));
        match start {
            None => {
                let (distance, high) = key(0);
                out.push(Constraint {
                    shape: Shape::Run(LineString::new(ring.to_vec())),
                    distance,
                    high,
                });
            }
            Some(s) => {
                let mut i = s;
                while i < s + n {
                    let k = key(i);
                    let mut j = i + 1;
                    while j < s + n && key(j) == k {
                        j += 1;
                    }
                    let points: Vec<Coord> = (i..=j).map(|v| ring[v % n]).collect();
                    out.push(Constraint {
                        shape: Shape::Run(LineString::new(points)),
                        distance: k.0,
                        high: k.1,
                    });
                    i = j;
                }
            }
        }
    }
    let (distance, high) = rule(hole_passes);
    for hole in holes {
        out.push(Constraint {
            shape: Shape::Hole(hole.clone()),
            distance,
            high,
        });
    }
    out
}

/// The part of `region` farther from every constraint than its distance.
fn keep_clear(region: &MultiPolygon, constraints: &[Constraint]) -> MultiPolygon {
    let bands: Vec<Polygon> = constraints
        .iter()
        .filter(|c| c.distance > 0.0)
        .flat_map(|c| c.band().0)
        .collect();
    if bands.is_empty() {
        return region.clone();
    }
    drop_slivers(region.difference_overlapping(&MultiPolygon::new(bands)))
}

/// Tolerance (metres) within which two constraints bind equally.
const BINDING_TOLERANCE_M: f64 = 1e-6;

/// The pieces of a ring of the room left for a pass that run along the constraints the pass
/// follows: the whole ring if it is all such, else open lines. A stretch of the ring is on the
/// pass where a followed constraint is the nearest (in excess of its distance) at both of its
/// ends and its middle; the middle matters at corners, where the two ends of a stretch along an
/// edge without headland touch the edges beside it. Pieces shorter than `min_length` are
/// dropped.
fn pass_lines(
    ring: &LineString,
    constraints: &[Constraint],
    min_length: f64,
) -> Vec<(LineString, bool)> {
    let pts = &ring.0;
    let m = pts.len().saturating_sub(1);
    if m < 2 {
        return Vec::new();
    }
    let follows = |p: Coord| {
        let mut best = (f64::INFINITY, false);
        for c in constraints {
            let e = c.excess(p);
            // Prefer the constraint being followed where two bind equally.
            if e < best.0 - BINDING_TOLERANCE_M
                || (e <= best.0 + BINDING_TOLERANCE_M && c.high && !best.1)
            {
                best = (e.min(best.0), c.high);
            }
        }
        best.1
    };
    let at_vertex: Vec<bool> = pts[..m].iter().map(|&p| follows(p)).collect();
    // Segment i runs from point i to point i + 1.
    let on_pass: Vec<bool> = (0..m)
        .map(|i| {
            let (a, b) = (pts[i], pts[i + 1]);
            at_vertex[i]
                && at_vertex[(i + 1) % m]
                && follows(Coord {
                    x: (a.x + b.x) / 2.0,
                    y: (a.y + b.y) / 2.0,
                })
        })
        .collect();
    if on_pass.iter().all(|&b| b) {
        return vec![(ring.clone(), true)];
    }
    let Some(start) = on_pass.iter().position(|&b| !b) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    let mut current: Vec<Coord> = Vec::new();
    for step in 1..=m {
        let i = (start + step) % m;
        if on_pass[i] {
            if current.is_empty() {
                current.push(pts[i]);
            }
            current.push(pts[i + 1]);
        } else if !current.is_empty() {
            out.push(std::mem::take(&mut current));
        }
    }
    if !current.is_empty() {
        out.push(current);
    }
    out.into_iter()
        .map(LineString::new)
        .filter(|l| Euclidean.length(l) >= min_length)
        .map(|l| (l, false))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::field::{Frame, Obstacle};
    use geo::{coord, polygon, Distance, Euclidean, Point};

    fn field(boundary: Polygon, obstacles: Vec<Polygon>) -> Field {
        Field {
            boundary,
            drawn_boundary: vec![],
            obstacles: obstacles
                .into_iter()
                .map(|polygon| Obstacle {
                    polygon,
                    feature: 1,
                    name: None,
                })
                .collect(),
            prohibited: vec![],
            name: None,
            feature: 0,
            frame: Frame::Metric,
            entrance: None,
            reference_line: None,
        }
    }

    fn rectangle(w: f64, h: f64) -> Polygon {
        polygon![(x: 0., y: 0.), (x: w, y: 0.), (x: w, y: h), (x: 0., y: h)]
    }

    #[test]
    fn pass_centre_lines_are_at_half_widths() {
        let f = field(rectangle(200.0, 100.0), vec![]);
        let h = constant_width(&f, 6.0, 3).unwrap();
        assert_eq!(h.passes.len(), 3);
        let boundary = f.boundary.exterior();
        for pass in &h.passes {
            let expected = (pass.index as f64 - 0.5) * 6.0;
            for &c in &pass.line.0 {
                let d = Euclidean.distance(&Point(c), boundary);
                assert!((d - expected).abs() < 1e-6, "pass {} at {d}", pass.index);
            }
        }
        // Inner field: 200 - 36 by 100 - 36.
        assert!((h.inner.unsigned_area() - 164.0 * 64.0).abs() < 1e-6);
        assert!((h.area_m2 - (200.0 * 100.0 - 164.0 * 64.0)).abs() < 1e-6);
    }

    #[test]
    fn no_passes_leaves_the_whole_field() {
        let f = field(rectangle(50.0, 50.0), vec![]);
        let h = constant_width(&f, 6.0, 0).unwrap();
        assert!(h.passes.is_empty());
        assert_eq!(h.area_m2, 0.0);
        assert!((h.inner.unsigned_area() - 2500.0).abs() < 1e-9);
    }

    #[test]
    fn obstacles_are_cut_out_of_the_inner_field() {
        let obstacle =
            polygon![(x: 40., y: 40.), (x: 60., y: 40.), (x: 60., y: 60.), (x: 40., y: 60.)];
        let f = field(rectangle(100.0, 100.0), vec![obstacle]);
        let h = constant_width(&f, 5.0, 1).unwrap();
        // The obstacle gets its pass too: the inner field keeps 5 m from it, round its corners.
        let around = 400.0 + 4.0 * 20.0 * 5.0 + std::f64::consts::PI * 25.0;
        assert!((h.inner.unsigned_area() - (90.0 * 90.0 - around)).abs() < 0.2);
        assert_eq!(h.passes.len(), 2);
        assert_eq!(
            h.passes
                .iter()
                .filter(|p| p.around == PassAround::Obstacle)
                .count(),
            1
        );
    }

    #[test]
    fn passes_that_leave_no_inner_field_are_laid_and_a_field_no_pass_fits_is_refused() {
        // 30 x 20 m at 6 m: passes at 3 and 9 m in, the inner field 12 m in is empty.
        let f = field(rectangle(30.0, 20.0), vec![]);
        let h = constant_width(&f, 6.0, 2).unwrap();
        assert!(h.inner.0.is_empty());
        assert_eq!(h.passes.len(), 2);
        assert!((h.area_m2 - 600.0).abs() < 1e-6);
        // A third pass 15 m in does not fit: two are laid.
        assert_eq!(constant_width(&f, 6.0, 3).unwrap().passes.len(), 2);
        // A 5 m strip at 6 m: not even the first pass, 3 m in, fits.
        let e = constant_width(&field(rectangle(100.0, 5.0), vec![]), 6.0, 1).unwrap_err();
        assert_eq!(e.code, ErrorCode::HeadlandConsumesField);
    }

    #[test]
    fn passes_stop_where_the_field_has_no_room_and_to_the_middle_one_goes_round_the_rest() {
        // 40 m across at 6 m: passes 3, 9 and 15 m in; a fourth, 21 m in, has no room.
        let settings = |to_middle| HeadlandSettings {
            width: 6.0,
            turn_radius: 0.0,
            exact: true,
            obstacle_passes: 50,
            edge_passes: &[50, 50, 50, 50],
            to_middle,
        };
        let asked = build(&rectangle(150.0, 40.0), &[], &settings(false)).unwrap();
        let indices: Vec<usize> = asked.passes.iter().map(|p| p.index).collect();
        assert_eq!(indices, [1, 2, 3]);
        assert!(asked.inner.0.is_empty());
        // To the middle: a fourth round the 4 m left, a quarter width (19.5 m) in, so that its
        // strip covers the rest from both sides; no inner field.
        let middle = build(&rectangle(150.0, 40.0), &[], &settings(true)).unwrap();
        assert_eq!(middle.passes.len(), 4);
        let last = &middle.passes[3];
        assert_eq!(last.index, 4);
        let ys: Vec<f64> = last.line.0.iter().map(|c| c.y).collect();
        let (lo, hi) = ys
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &y| {
                (a.min(y), b.max(y))
            });
        assert!(
            (lo - 19.5).abs() < 1e-6 && (hi - 20.5).abs() < 1e-6,
            "{lo} {hi}"
        );
        assert!(middle.inner.0.is_empty());
    }

    #[test]
    fn a_pass_the_turning_disc_fits_nowhere_is_laid_exact() {
        // 40 m wide at 24 m with turns of 9 m: the first pass's room (12 m in, 16 m wide) holds
        // no 18 m disc. Its exact offset is the pass: straight sides 16 m apart, sharp corners.
        let settings = HeadlandSettings {
            width: 24.0,
            turn_radius: 9.0,
            exact: false,
            obstacle_passes: 1,
            edge_passes: &[1, 1, 1, 1],
            to_middle: false,
        };
        let h = build(&rectangle(150.0, 40.0), &[], &settings).unwrap();
        assert_eq!(h.passes.len(), 1);
        let ring = &h.passes[0].line;
        let xs: Vec<f64> = ring.0.iter().map(|c| c.x).collect();
        let ys: Vec<f64> = ring.0.iter().map(|c| c.y).collect();
        let lo = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = |v: &[f64]| v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        assert!(
            (lo(&xs) - 12.0).abs() < 1e-6 && (hi(&xs) - 138.0).abs() < 1e-6,
            "{xs:?}"
        );
        assert!(
            (lo(&ys) - 12.0).abs() < 1e-6 && (hi(&ys) - 28.0).abs() < 1e-6,
            "{ys:?}"
        );
        assert_eq!(ring.0.len(), 5, "four sharp corners");
    }

    #[test]
    fn exact_passes_keep_their_corners_where_opened_ones_round_them() {
        let settings = |exact| HeadlandSettings {
            width: 6.0,
            turn_radius: 8.0,
            exact,
            obstacle_passes: 2,
            edge_passes: &[2, 2, 2, 2],
            to_middle: false,
        };
        let field = rectangle(100.0, 60.0);
        let exact = build(&field, &[], &settings(true)).unwrap();
        let opened = build(&field, &[], &settings(false)).unwrap();
        for (e, o) in exact.passes.iter().zip(&opened.passes) {
            assert_eq!(e.line.0.len(), 5, "four sharp corners: {:?}", e.line);
            assert!(o.line.0.len() > 5, "rounded corners: {:?}", o.line);
            assert!(e.length() > o.length());
        }
        assert!((exact.inner.unsigned_area() - opened.inner.unsigned_area()).abs() < 1e-6);
    }

    #[test]
    fn a_narrow_neck_splits_the_inner_field() {
        // Two 60 m squares joined by a 10 m wide neck: 2 passes of 4 m close the neck.
        let dumbbell = Polygon::new(
            LineString::from(vec![
                coord! { x: 0., y: 0. },
                coord! { x: 60., y: 0. },
                coord! { x: 60., y: 25. },
                coord! { x: 80., y: 25. },
                coord! { x: 80., y: 0. },
                coord! { x: 140., y: 0. },
                coord! { x: 140., y: 60. },
                coord! { x: 80., y: 60. },
                coord! { x: 80., y: 35. },
                coord! { x: 60., y: 35. },
                coord! { x: 60., y: 60. },
                coord! { x: 0., y: 60. },
            ]),
            vec![],
        );
        let f = field(dumbbell, vec![]);
        let h = constant_width(&f, 4.0, 2).unwrap();
        assert_eq!(h.inner.0.len(), 2);
        // Pass 1 (2 m in) still goes through the neck; pass 2 (6 m in) does not.
        assert_eq!(h.passes.iter().filter(|p| p.index == 1).count(), 1);
        assert_eq!(h.passes.iter().filter(|p| p.index == 2).count(), 2);
    }
}
