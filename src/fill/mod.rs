//! Filling what the swaths and headland passes leave standing: the corners their rounding
//! leaves, the strips between swath ends and the passes, narrow parts no swath reaches.
//!
//! Each part left standing that is at least half a width across and that a strip of the
//! implement's width can reach gets working pieces of its own: short swaths, a width apart,
//! along the part's own narrowest direction (the direction of a side of its convex hull) or the
//! field's, whichever works it with fewer pieces. A line's centre keeps half a width from the
//! boundary and the obstacles (the whole strip stays in the field) and runs as far as its strip
//! reaches the middle of the part's wide stretches; slivers narrower than half a width are left
//! (a full strip over them would mostly work again what is worked), but for those a quarter of a
//! width across outside the inner field: the middle of an arm or a strip its passes work round,
//! which no swath works. A piece is laid only where
//! the route can get to one of its ends without crossing crop (near a headland pass or a
//! swath's track): a part with no such piece is left, to be measured as standing.
//!
//! The fill's swaths are blocks of the plan, worked after the field's blocks (the route reaches
//! them along the headland and the worked swaths' tracks, see [`crate::route`]); the overlap
//! with the work around them is the price, and is reported.

pub mod along;

use crate::coverage::Uncovered;
use crate::field::ProhibitedRegion;
use crate::geometry::sleeve::{sleeve_ring, Sleeve};
use crate::geometry::{bearing_of, swath_direction, BearingRange, BooleanOps, SweepFrame};
use crate::headland::offset::{inset, outset};
use crate::swath::{on_lines, SwathArea, Swaths};
use geo::orient::{Direction, Orient};
use geo::{Area, BoundingRect, ConvexHull, Coord, Intersects, MultiPolygon, Polygon, Rect};

/// What the fill needs besides the parts left standing.
#[derive(Clone, Copy)]
pub struct FillSettings<'a> {
    /// Working width, metres.
    pub width: f64,
    /// The field's swath direction, compass radians.
    pub bearing: f64,
    /// Driving directions forbidden everywhere.
    pub forbidden: &'a [BearingRange],
    /// Regions with directions of their own forbidden.
    pub regions: &'a [ProhibitedRegion],
    /// The shortest piece laid, metres (the plan's minimum swath length).
    pub min_length: f64,
    /// Whether the machine gets to a point without crossing crop once the field's swaths are
    /// worked (near a headland pass or a swath's track): a piece is laid only where one of its
    /// ends is such a point, so that the route reaches it and leaves it (driving back along it
    /// from a dead end).
    pub reachable: &'a dyn Fn(Coord) -> bool,
    /// Whether a sliver (a part nowhere half a width across, a quarter somewhere) is filled: the
    /// middle of an arm or a strip that its passes work round, not a sliver among the swaths,
    /// where a strip over it would mostly work again what they work.
    pub slivers: &'a dyn Fn(&Polygon) -> bool,
}

impl std::fmt::Debug for FillSettings<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FillSettings")
            .field("width", &self.width)
            .field("bearing", &self.bearing)
            .field("forbidden", &self.forbidden)
            .field("regions", &self.regions)
            .field("min_length", &self.min_length)
            .finish_non_exhaustive()
    }
}

/// The least area (in working widths squared) a strip must be able to reach of a part for it to
/// be filled; and a part must be half a width across somewhere, or a quarter for a sliver
/// [`FillSettings::slivers`] lets be filled.
pub(crate) const MIN_PART_WIDTHS: f64 = 0.5;

/// The least area (in working widths squared) of a sliver the plan fills (see
/// [`FillSettings::slivers`]): a strip over a sliver mostly works again what is worked, worth
/// driving to where the sliver is long.
pub(crate) const MIN_SLIVER_WIDTHS: f64 = 4.0;

/// The swaths that work the parts of `uncovered`, one set per part that gets any (each at its
/// own direction). `centres` is where a strip's centre line may run: the field less its
/// obstacles, inset by half a width.
///
/// ```
/// use furrow::coverage::measure;
/// use furrow::fill::{fill, FillSettings};
/// use furrow::headland::offset::inset;
/// use geo::{coord, polygon, MultiPolygon};
///
/// // A 30 x 100 m field worked by four 6 m swaths: the last 6 m strip is filled by one more.
/// let field = polygon![(x: 0., y: 0.), (x: 30., y: 0.), (x: 30., y: 100.), (x: 0., y: 100.)];
/// let worked: Vec<Vec<_>> = [3.0, 9.0, 15.0, 21.0]
///     .iter()
///     .map(|&x| vec![coord! { x: x, y: 0.0 }, coord! { x: x, y: 100.0 }])
///     .collect();
/// let left = measure(&field, &[], &worked, 6.0).uncovered;
/// let centres = inset(&MultiPolygon::new(vec![field]), 3.0);
/// let settings = FillSettings {
///     width: 6.0,
///     bearing: 0.0,
///     forbidden: &[],
///     regions: &[],
///     min_length: 6.0,
///     reachable: &|_| true,
///     slivers: &|_| false,
/// };
/// let pieces = fill(&left, &centres, &settings);
/// assert_eq!(pieces.len(), 1);
/// assert_eq!(pieces[0].swaths.len(), 1);
/// assert!((pieces[0].swaths[0].across.abs() - 27.0).abs() < 0.6);
/// assert!(pieces[0].swaths[0].length() > 90.0);
/// ```
pub fn fill(
    uncovered: &[Uncovered],
    centres: &MultiPolygon,
    settings: &FillSettings,
) -> Vec<Swaths> {
    let w = settings.width;
    if centres.0.is_empty() || w.is_nan() || w <= 0.0 {
        return Vec::new();
    }
    let centres = Centres::new(centres);
    uncovered
        .iter()
        .filter(|u| u.reachable_m2 >= MIN_PART_WIDTHS * w * w)
        .filter_map(|u| fill_part(&u.polygon, &centres, settings))
        .collect()
}

/// Where a strip's centre line may run, with the bounding boxes of its polygons and their holes
/// worked out once for all the parts ([`lanes`] takes the holes near a part: a field of 2,000
/// ponds is one polygon with 2,000 holes, and the parts left between their passes thousands).
pub(crate) struct Centres<'a> {
    region: &'a MultiPolygon,
    boxes: Vec<(Option<Rect>, Vec<Option<Rect>>)>,
}

impl<'a> Centres<'a> {
    pub(crate) fn new(region: &'a MultiPolygon) -> Self {
        let boxes = region
            .0
            .iter()
            .map(|p| {
                let holes = p.interiors().iter().map(|h| h.bounding_rect()).collect();
                (p.bounding_rect(), holes)
            })
            .collect();
        Centres { region, boxes }
    }

    /// The polygons whose boxes meet `area`, with only their holes whose boxes meet it.
    fn near(&self, area: &Rect) -> MultiPolygon {
        let meets = |b: &Option<Rect>| b.is_some_and(|b| b.intersects(area));
        let polygons = self
            .region
            .0
            .iter()
            .zip(&self.boxes)
            .filter(|(_, (outer, _))| meets(outer))
            .map(|(p, (_, holes))| {
                let holes = p
                    .interiors()
                    .iter()
                    .zip(holes)
                    .filter(|(_, b)| meets(b))
                    .map(|(h, _)| h.clone())
                    .collect();
                Polygon::new(p.exterior().clone(), holes)
            })
            .collect();
        MultiPolygon::new(polygons)
    }
}

/// The swaths of one part, at the direction that works it with the fewest pieces.
fn fill_part(part: &Polygon, centres: &Centres, settings: &FillSettings) -> Option<Swaths> {
    let w = settings.width;
    let part = lanes(part, centres, w, settings.slivers)?;
    let reached = |s: &crate::swath::Swath| {
        (settings.reachable)(s.centre.start) || (settings.reachable)(s.centre.end)
    };
    let mut best: Option<Swaths> = None;
    // Where no direction reaches all its pieces, the one whose reachable pieces are longest.
    let mut partly: Option<Swaths> = None;
    for bearing in directions(&part.core, &part.near, settings) {
        let Some(swaths) = pieces_at(&part, bearing, w, settings.min_length) else {
            continue;
        };
        if !swaths.swaths.iter().all(reached) {
            if best.is_none() {
                let mut some = swaths;
                some.retain(reached);
                let longer = partly
                    .as_ref()
                    .is_none_or(|p| length(&some) > length(p) + 1e-6);
                if !some.swaths.is_empty() && longer {
                    partly = Some(some);
                }
            }
            continue;
        }
        let better = best.as_ref().is_none_or(|b| {
            swaths.swaths.len() < b.swaths.len()
                || (swaths.swaths.len() == b.swaths.len() && length(&swaths) > length(b) + 1e-6)
        });
        if better {
            best = Some(swaths);
        }
    }
    let mut swaths = best.or(partly)?;
    let area = strips(&swaths, w);
    swaths.areas.push(SwathArea {
        swaths: 0..swaths.swaths.len(),
        bearing: swaths.bearing,
        region: None,
        area,
        fill: true,
    });
    Some(swaths)
}

/// Where pieces working a part may run.
pub(crate) struct Lanes {
    /// The part where it is at least half a width across (inset by a quarter width), or a
    /// sliver's where it is a quarter width across (inset by an eighth).
    pub core: MultiPolygon,
    /// How far the core lies inside the part, metres.
    pub core_inset: f64,
    /// Within how far a centre line's strip reaches the core (half a width round it).
    pub near: MultiPolygon,
    /// Where a centre line may run to work the core: in `near`, its strip in the field.
    pub lanes: MultiPolygon,
}

/// The lanes of `part` among `centres` (where a strip's centre line may run), for an implement
/// `w` wide; `None` where the part is nowhere half a width across (a quarter where `sliver`
/// says so) or no lane reaches it.
pub(crate) fn lanes(
    part: &Polygon,
    centres: &Centres,
    w: f64,
    sliver: &dyn Fn(&Polygon) -> bool,
) -> Option<Lanes> {
    let whole = part;
    let part = MultiPolygon::new(vec![part.clone()]);
    let mut core_inset = w / 4.0;
    let mut core = inset(&part, core_inset);
    if core.unsigned_area() <= 0.0 && sliver(whole) {
        core_inset = w / 8.0;
        core = inset(&part, core_inset);
    }
    if core.unsigned_area() <= 0.0 {
        return None;
    }
    let near = outset(
        &bulges_cut(&core, REACH_SLACK_M / 2.0),
        w / 2.0 - REACH_SLACK_M,
    );
    let box_of = near.bounding_rect()?;
    // Only the holes near the part matter.
    let lanes = centres.near(&box_of).intersection(&near);
    (lanes.unsigned_area() > 0.0).then_some(Lanes {
        core,
        core_inset,
        near,
        lanes,
    })
}

/// `region` with the stretches of its outline that bulge into it cut by chords within
/// `tolerance` metres (the region grows by as much, never shrinks): a core inset from a part has
/// an arc bulging into it at each of the part's inner corners, and the outset of an arc of many
/// points has a loop of the outline at each point to resolve (a field of 2,000 obstacles spent
/// most of its planning there).
fn bulges_cut(region: &MultiPolygon, tolerance: f64) -> MultiPolygon {
    // Left of the outline, walked with the region on its left, is inside: vertices there may go.
    let sleeve = Sleeve {
        left: tolerance,
        right: 0.0,
        max_gap: f64::INFINITY,
    };
    let thin = |ring: &geo::LineString| {
        let open = ring.0.split_last().map_or(&[][..], |(_, open)| open);
        let mut kept = sleeve_ring(open, sleeve);
        kept.extend(kept.first().copied());
        geo::LineString::new(kept)
    };
    let oriented = region.orient(Direction::Default);
    let polygons = oriented
        .0
        .iter()
        .map(|p| Polygon::new(thin(p.exterior()), p.interiors().iter().map(thin).collect()))
        .collect();
    MultiPolygon::new(polygons)
}

/// The area the implement works along `swaths`: their strips, `width` wide, as one region.
fn strips(swaths: &Swaths, width: f64) -> MultiPolygon {
    let half = width / 2.0;
    let mut area = MultiPolygon::new(Vec::new());
    for s in &swaths.swaths {
        let f = s.frame;
        let corners = [
            f.point(s.across - half, s.along.0),
            f.point(s.across + half, s.along.0),
            f.point(s.across + half, s.along.1),
            f.point(s.across - half, s.along.1),
        ];
        let mut ring = corners.to_vec();
        ring.push(corners[0]);
        let strip = Polygon::new(geo::LineString::new(ring), vec![]);
        area = area.union(&strip);
    }
    area
}

/// How much short of half a width the lanes reach out from a part, metres: a strip that only
/// touches a part's edge is not a piece.
const REACH_SLACK_M: f64 = 0.05;

fn length(s: &Swaths) -> f64 {
    s.swaths.iter().map(|s| s.length()).sum()
}

/// The directions tried for a part that no forbidden range rules out where its pieces may run
/// (`reach`, the part's core and half a width round it): the narrowest across its convex hull,
/// and the field's.
fn directions(part: &MultiPolygon, reach: &MultiPolygon, settings: &FillSettings) -> Vec<f64> {
    let mut out = Vec::with_capacity(2);
    if let Some(b) = narrowest(part) {
        out.push(b);
    }
    out.push(swath_direction(settings.bearing));
    let allowed = |b: f64| {
        !settings.forbidden.iter().any(|r| r.forbids(b))
            && !settings
                .regions
                .iter()
                .filter(|r| r.polygon.intersects(reach))
                .any(|r| r.forbidden.iter().any(|f| f.forbids(b)))
    };
    out.retain(|&b| allowed(b));
    out.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    out
}

/// The direction of the side of `part`'s convex hull across which it is narrowest (rotating
/// calipers), compass radians in `[0, π)`.
fn narrowest(part: &MultiPolygon) -> Option<f64> {
    let hull = part.convex_hull();
    let ring = &hull.exterior().0;
    let mut best: Option<(f64, f64)> = None;
    for edge in ring.windows(2) {
        let (a, b) = (edge[0], edge[1]);
        if a == b {
            continue;
        }
        let bearing = swath_direction(bearing_of(a, b));
        let (lo, hi) = SweepFrame::new(bearing).across_extent(part)?;
        if best.is_none_or(|(w, _)| hi - lo < w - 1e-9) {
            best = Some((hi - lo, bearing));
        }
    }
    best.map(|(_, b)| b)
}

/// The pieces of lines at `bearing` that work the part whose lanes are given: as few lines a
/// width apart as span the part's wide extent across (its core's, grown back by the core's
/// inset), spread evenly over it, each moved into the lanes' extent and cut to the lanes.
fn pieces_at(part: &Lanes, bearing: f64, w: f64, min_length: f64) -> Option<Swaths> {
    let Lanes {
        core,
        core_inset,
        lanes,
        ..
    } = part;
    let frame = SweepFrame::new(bearing);
    let (lo, hi) = frame.across_extent(core)?;
    let (lo, hi) = (lo - core_inset, hi + core_inset);
    let (lane_lo, lane_hi) = frame.across_extent(lanes)?;
    let count = (((hi - lo) / w) - 1e-6).ceil().max(1.0) as usize;
    let mut offsets: Vec<f64> = if count == 1 {
        vec![(lo + hi) / 2.0]
    } else {
        let step = (hi - lo - w) / (count - 1) as f64;
        (0..count).map(|k| lo + w / 2.0 + k as f64 * step).collect()
    };
    // Lanes narrower than twice the margin hold one line, in their middle.
    let (inside_lo, inside_hi) = if lane_hi - lane_lo > 2.0 * LANE_INSIDE_M {
        (lane_lo + LANE_INSIDE_M, lane_hi - LANE_INSIDE_M)
    } else {
        let mid = (lane_lo + lane_hi) / 2.0;
        (mid, mid)
    };
    // `inside_lo <= inside_hi` by construction; max and min rather than `clamp`, whose check
    // would bring the float formatting of its panic message into the module.
    for c in &mut offsets {
        *c = c.max(inside_lo).min(inside_hi);
    }
    offsets.dedup_by(|a, b| (*a - *b).abs() < w / 2.0);
    let swaths = on_lines(lanes, bearing, w, &offsets, min_length.max(1.0));
    (!swaths.swaths.is_empty()).then_some(swaths)
}

/// How far inside the lanes' extent a line is kept, metres: a line on the extent itself would
/// touch the lanes at a point.
const LANE_INSIDE_M: f64 = 0.01;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::measure;
    use crate::headland::offset::{inset, outset};
    use geo::{coord, polygon, Coord};

    #[test]
    fn cutting_the_bulges_grows_a_core_by_at_most_the_tolerance() {
        // An L with a pond: its core a width in has an arc bulging into it at the L's inner
        // corner and all round the pond.
        let part = polygon!(
            exterior: [(x: 0., y: 0.), (x: 60., y: 0.), (x: 60., y: 20.), (x: 20., y: 20.), (x: 20., y: 60.), (x: 0., y: 60.)],
            interiors: [[(x: 40., y: 8.), (x: 44., y: 8.), (x: 44., y: 12.), (x: 40., y: 12.)]],
        );
        let core = inset(&MultiPolygon::new(vec![part]), 1.5);
        let cut = bulges_cut(&core, 0.025);
        let points = |m: &MultiPolygon| geo::CoordsIter::coords_count(m);
        assert!(
            points(&cut) * 5 < points(&core) * 3,
            "{} of {}",
            points(&cut),
            points(&core)
        );
        // Nothing of the core lost, and nothing added beyond the tolerance.
        assert!(core.difference(&cut).unsigned_area() < 1e-6);
        let within = outset(&core, 0.025 + 1e-3);
        assert!(cut.difference(&within).unsigned_area() < 1e-6);
        assert!(cut.unsigned_area() > core.unsigned_area());
    }

    fn settings(bearing: f64) -> FillSettings<'static> {
        FillSettings {
            width: 6.0,
            bearing,
            forbidden: &[],
            regions: &[],
            min_length: 3.0,
            reachable: &anywhere,
            slivers: &|_| false,
        }
    }

    fn anywhere(_: Coord) -> bool {
        true
    }

    /// The first `n` 6 m swaths of a field from x = 0, north from y = 0 to `to_y`.
    fn worked_from_west(n: usize, to_y: f64) -> Vec<Vec<Coord>> {
        (0..n)
            .map(|i| {
                let x = 3.0 + 6.0 * i as f64;
                vec![coord! { x: x, y: 0.0 }, coord! { x: x, y: to_y }]
            })
            .collect()
    }

    fn lines_of(s: &[Swaths]) -> Vec<Vec<Coord>> {
        s.iter()
            .flat_map(|s| s.swaths.iter().map(|x| vec![x.centre.start, x.centre.end]))
            .collect()
    }

    #[test]
    fn a_part_is_filled_only_where_the_route_can_get_to_a_piece() {
        // A 30 x 100 m field worked by four 6 m swaths: the last strip, x 24 to 30, is left.
        let field = polygon![(x: 0., y: 0.), (x: 30., y: 0.), (x: 30., y: 100.), (x: 0., y: 100.)];
        let worked = worked_from_west(4, 100.0);
        let left = measure(&field, &[], &worked, 6.0).uncovered;
        let centres = inset(&MultiPolygon::new(vec![field]), 3.0);
        // Nowhere to get to: nothing is laid.
        let nowhere = |_: Coord| false;
        let none = FillSettings {
            reachable: &nowhere,
            slivers: &|_| false,
            ..settings(0.0)
        };
        assert!(fill(&left, &centres, &none).is_empty());
        // Only the north end is reached (a headland pass along the north edge): the piece is
        // laid along the strip, one end there.
        let north = |p: Coord| p.y > 90.0;
        let from_north = FillSettings {
            reachable: &north,
            slivers: &|_| false,
            ..settings(0.0)
        };
        let pieces = fill(&left, &centres, &from_north);
        let lines = lines_of(&pieces);
        assert_eq!(lines.len(), 1);
        assert!(lines[0].iter().any(|p| north(*p)));
        assert!((lines[0][0].x - 27.0).abs() < 0.6);
    }

    #[test]
    fn where_no_direction_reaches_every_piece_the_reachable_ones_are_laid() {
        // A 60 x 100 m field worked west of x = 36: the strip left is 24 m wide, and the route
        // gets only to its north-eastern corner. Along the strip, two of its four pieces end
        // there; across it, only the northernmost.
        let field = polygon![(x: 0., y: 0.), (x: 60., y: 0.), (x: 60., y: 100.), (x: 0., y: 100.)];
        let worked = worked_from_west(6, 100.0);
        let before = measure(&field, &[], &worked, 6.0);
        let centres = inset(&MultiPolygon::new(vec![field.clone()]), 3.0);
        let corner = |p: Coord| p.x > 48.0 && p.y > 90.0;
        let from_corner = FillSettings {
            reachable: &corner,
            slivers: &|_| false,
            ..settings(0.0)
        };
        let pieces = fill(&before.uncovered, &centres, &from_corner);
        let lines = lines_of(&pieces);
        assert_eq!(lines.len(), 2, "{lines:?}");
        assert!(lines.iter().all(|l| l.iter().any(|p| corner(*p))));
        let numbered = |s: &Swaths| s.swaths.iter().enumerate().all(|(i, x)| x.index == i);
        assert!(pieces.iter().all(numbered));
        let mut all = worked.clone();
        all.extend(lines);
        let after = measure(&field, &[], &all, 6.0);
        assert!(
            after.uncovered_area_m2 < before.uncovered_area_m2 - 1000.0,
            "{} -> {}",
            before.uncovered_area_m2,
            after.uncovered_area_m2
        );
    }

    #[test]
    fn a_strip_across_the_swath_ends_is_worked_along_its_length() {
        // Swaths north-south end 6 m short of the north edge: the strip left is worked east-west.
        let field = polygon![(x: 0., y: 0.), (x: 60., y: 0.), (x: 60., y: 100.), (x: 0., y: 100.)];
        let worked = worked_from_west(10, 94.0);
        let before = measure(&field, &[], &worked, 6.0);
        assert!(before.coverage_ratio < 0.95);
        let centres = inset(&MultiPolygon::new(vec![field.clone()]), 3.0);
        let pieces = fill(&before.uncovered, &centres, &settings(0.0));
        assert_eq!(pieces.len(), 1);
        assert_eq!(pieces[0].swaths.len(), 1, "one piece along the strip");
        assert!((pieces[0].bearing - std::f64::consts::FRAC_PI_2).abs() < 1e-6);
        let mut all = worked.clone();
        all.extend(lines_of(&pieces));
        let after = measure(&field, &[], &all, 6.0);
        // Left: the strip's ends, half a width short of the sides (3 x 6 m each).
        assert!(
            after.uncovered_area_m2 < 40.0,
            "{}",
            after.uncovered_area_m2
        );
        assert!(
            before.uncovered_area_m2 > 300.0,
            "{}",
            before.uncovered_area_m2
        );
        assert!(after.outside_area_m2 < 1.0, "{}", after.outside_area_m2);
    }

    #[test]
    fn a_forbidden_direction_is_not_used() {
        let field = polygon![(x: 0., y: 0.), (x: 60., y: 0.), (x: 60., y: 100.), (x: 0., y: 100.)];
        let worked = worked_from_west(10, 94.0);
        let before = measure(&field, &[], &worked, 6.0);
        let centres = inset(&MultiPolygon::new(vec![field]), 3.0);
        let east_west = [BearingRange {
            from_deg: 80.0,
            to_deg: 100.0,
        }];
        let s = FillSettings {
            forbidden: &east_west,
            ..settings(0.0)
        };
        let pieces = fill(&before.uncovered, &centres, &s);
        assert!(pieces.iter().all(|p| p.bearing.abs() < 1e-6));
    }

    #[test]
    fn a_field_worked_all_over_gets_nothing() {
        let field = polygon![(x: 0., y: 0.), (x: 30., y: 0.), (x: 30., y: 100.), (x: 0., y: 100.)];
        let worked: Vec<Vec<Coord>> = (0..5)
            .map(|i| {
                let x = 3.0 + 6.0 * i as f64;
                vec![coord! { x: x, y: 0.0 }, coord! { x: x, y: 100.0 }]
            })
            .collect();
        let before = measure(&field, &[], &worked, 6.0);
        let centres = inset(&MultiPolygon::new(vec![field]), 3.0);
        assert!(fill(&before.uncovered, &centres, &settings(0.0)).is_empty());
    }

    #[test]
    fn a_corner_a_strip_cannot_reach_gets_nothing() {
        // The tip of a 20 degree wedge: left standing, but no 6 m strip reaches into it.
        let tip = polygon![(x: 0., y: 0.), (x: 10., y: 0.), (x: 10., y: 3.6)];
        let u = Uncovered {
            polygon: tip.clone(),
            area_m2: tip.unsigned_area(),
            reachable_m2: 0.0,
        };
        let centres = MultiPolygon::new(vec![
            polygon![(x: 20., y: 0.), (x: 40., y: 0.), (x: 40., y: 10.), (x: 20., y: 10.)],
        ]);
        assert!(fill(&[u], &centres, &settings(0.0)).is_empty());
    }
}
