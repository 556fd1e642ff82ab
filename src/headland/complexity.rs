//! Whether offsetting an outline stays cheap, found before it is tried.
//!
//! An inset (geo's buffer, i_overlay's outline) replaces each edge of a ring by its *section*:
//! the rectangle the edge sweeps moving the offset distance into the region (plus a round join
//! at each vertex where the offset turns away from the region); then it unites all sections
//! with one overlay. The overlay splits every section edge where it crosses another and keeps
//! every piece: its time and memory grow with the number of crossings. Two sections of a smooth
//! outline meet only where their edges do (neighbours along a ring) as long as the outline
//! curves no tighter than about half the offset distance; on a jagged outline (a noisy trace at
//! a fine working width, a boundary of many small teeth) each section crosses those of every
//! edge within the distance, and a 199,000-vertex noisy outline inset by 8 m has hundreds of
//! millions of crossings: gigabytes, and an abort where the allocation fails.
//!
//! [`overlapping_sections`] counts the pairs of sections, other than neighbours along a ring,
//! that overlap: each such pair is at least one crossing of the overlay (two, usually), so the
//! count is a lower bound of the overlay's work, and the work on the neighbours and joins adds
//! a few times the number of vertices. It is found with an R-tree of the sections' boxes and an
//! exact test of each pair whose boxes meet, and stops at a cap, so it costs at most a few
//! tens of milliseconds however complex the outline.

use super::offset::round_step;
use crate::error::{ErrorCode, PlanError};
use crate::geometry::IndexedSegment;
use crate::numbers::{Decimals, Shortest};
use geo::{Coord, Polygon};
use rstar::{RTree, AABB};

/// The most offset work planning takes on: each inset of the headland stage (one per pass, and
/// one for the inner field) counts the region's edges, the points of its round joins and the
/// pairs of its sections that overlap, at the deepest inset. Measured natively: an inset of a
/// noisy 20,000-point outline by 8 m (20,000 edges, 192,000 overlapping pairs) took 1.2 s and
/// 150 MB, one of 1.4 million pairs 6.5 s and 580 MB, one of 16 million ten minutes and 11.5 GB;
/// the three insets of a field with 2,000 square obstacles (8,000 edges, 336,000 join points,
/// 1.04 million in all) 1.4 s. At this budget the insets of a plan take two seconds or so and a
/// few hundred MB. The corpus needs at most 9,300.
pub const MAX_OFFSET_WORK: usize = 1_500_000;

/// The count of [`overlapping_sections`], and whether it stopped at a cap before the end.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SectionOverlaps {
    /// Pairs of overlapping sections found (at most the cap plus one).
    pub pairs: usize,
    /// Whether the count stopped early: at the cap of pairs, or after examining as many pairs
    /// of sections with meeting boxes as the work allowed.
    pub stopped: bool,
}

/// One section: the rectangle edge `a`-`b` sweeps moving by `normal` (its length the offset
/// distance), with the ring it comes from and its place in it.
#[derive(Debug, Clone, Copy)]
struct Section {
    a: Coord,
    b: Coord,
    normal: Coord,
    ring: usize,
    index: usize,
}

impl Section {
    fn corners(&self) -> [Coord; 4] {
        [self.a, self.b, self.b + self.normal, self.a + self.normal]
    }

    fn envelope(&self) -> AABB<[f64; 2]> {
        let c = self.corners();
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in c {
            lo = [lo[0].min(p.x), lo[1].min(p.y)];
            hi = [hi[0].max(p.x), hi[1].max(p.y)];
        }
        AABB::from_corners(lo, hi)
    }

    /// Whether the two rectangles overlap (or touch): no axis of either separates them.
    fn overlaps(&self, other: &Section) -> bool {
        let (p, q) = (self.corners(), other.corners());
        let axes = [
            self.b - self.a,
            self.normal,
            other.b - other.a,
            other.normal,
        ];
        axes.iter().all(|axis| {
            let project = |c: &[Coord; 4]| {
                c.iter()
                    .map(|v| v.x * axis.x + v.y * axis.y)
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), t| {
                        (lo.min(t), hi.max(t))
                    })
            };
            let ((p_lo, p_hi), (q_lo, q_hi)) = (project(&p), project(&q));
            p_hi >= q_lo && q_hi >= p_lo
        })
    }
}

/// The pairs of sections of the region's rings (the outer ring of `boundary`, and `holes`,
/// whose insides are outside the region) that overlap when the region is inset by `distance`,
/// neighbours along a ring not counted (see the module documentation). Counting stops once it
/// passes `cap` pairs, or after examining `8 x cap + 64 x sections` pairs of sections whose boxes
/// meet. (A simplified outline has few: where it is smooth its vertices lie at least
/// `sqrt(8 x radius x tolerance)` apart, and the sections of a bend of radius under half the
/// distance overlap; more, and it is jagged.)
///
/// ```
/// use furrow::headland::complexity::overlapping_sections;
/// use geo::{polygon, Polygon, LineString};
///
/// // A square's sections overlap only where neighbours meet, until the inset passes its middle.
/// let square = polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 100., y: 100.), (x: 0., y: 100.)];
/// assert_eq!(overlapping_sections(&square, &[], 10.0, 1000).pairs, 0);
/// assert_eq!(overlapping_sections(&square, &[], 60.0, 1000).pairs, 2); // the opposite sides
/// // A saw-toothed edge, teeth 1 m deep and 2 m apart: inset by 5 m each tooth's sections reach
/// // across those of the teeth beside it.
/// let mut teeth: Vec<(f64, f64)> = (0..=100).map(|i| (i as f64, if i % 2 == 0 { 0.0 } else { 1.0 })).collect();
/// teeth.extend([(100.0, 50.0), (0.0, 50.0)]);
/// let saw = Polygon::new(LineString::from(teeth), vec![]);
/// assert!(overlapping_sections(&saw, &[], 5.0, 100_000).pairs > 200);
/// ```
pub fn overlapping_sections(
    boundary: &Polygon,
    holes: &[&Polygon],
    distance: f64,
    cap: usize,
) -> SectionOverlaps {
    let mut sections: Vec<Section> = Vec::new();
    let rings = std::iter::once((boundary.exterior(), false))
        .chain(holes.iter().map(|h| (h.exterior(), true)));
    for (ring, (line, hole)) in rings.enumerate() {
        let pts = &line.0;
        // Twice the signed area: positive for a counter-clockwise ring, whose inside is to the
        // left of each edge.
        let twice_area: f64 = pts
            .windows(2)
            .map(|w| w[0].x * w[1].y - w[1].x * w[0].y)
            .sum();
        // The region lies inside the outer ring and outside each hole.
        let left = (twice_area > 0.0) != hole;
        for (index, w) in pts.windows(2).enumerate() {
            let d = w[1] - w[0];
            let length = d.x.hypot(d.y);
            if length == 0.0 || !length.is_finite() {
                continue;
            }
            let side = if left { 1.0 } else { -1.0 };
            let normal = Coord {
                x: -d.y * side * distance / length,
                y: d.x * side * distance / length,
            };
            sections.push(Section {
                a: w[0],
                b: w[1],
                normal,
                ring,
                index,
            });
        }
    }
    // The ring lengths in edges, for telling neighbours apart.
    let mut edges_in: Vec<usize> = Vec::new();
    for s in &sections {
        if s.ring >= edges_in.len() {
            edges_in.resize(s.ring + 1, 0);
        }
        edges_in[s.ring] = edges_in[s.ring].max(s.index + 1);
    }
    let neighbours = |x: &Section, y: &Section| {
        x.ring == y.ring && {
            let n = edges_in[x.ring];
            let gap = x.index.abs_diff(y.index);
            gap <= 1 || gap + 1 == n
        }
    };
    // Each section's box, as the element type the planner's R-trees share: a segment from the
    // box's lower corner to its upper one has the box for envelope.
    let boxes: Vec<IndexedSegment> = sections
        .iter()
        .enumerate()
        .map(|(k, s)| {
            let e = s.envelope();
            let (lo, hi) = (e.lower(), e.upper());
            IndexedSegment::new(
                Coord { x: lo[0], y: lo[1] },
                Coord { x: hi[0], y: hi[1] },
                k,
                0,
            )
        })
        .collect();
    let tree = RTree::bulk_load(boxes);
    let examine_cap = cap
        .saturating_mul(8)
        .saturating_add(sections.len().saturating_mul(64));
    let (mut pairs, mut examined) = (0usize, 0usize);
    for (k, s) in sections.iter().enumerate() {
        for other in tree.locate_in_envelope_intersecting(&s.envelope()) {
            let j = other.line;
            if j <= k {
                continue;
            }
            examined += 1;
            let t = &sections[j];
            if !neighbours(s, t) && s.overlaps(t) {
                pairs += 1;
            }
            if pairs > cap || examined > examine_cap {
                return SectionOverlaps {
                    pairs,
                    stopped: true,
                };
            }
        }
    }
    SectionOverlaps {
        pairs,
        stopped: false,
    }
}

/// The points of the round joins an inset of the region by `distance` adds: where a ring turns
/// away from the region (a reflex corner of the field, any corner of an obstacle) the sections
/// of its two edges part, and an arc of the turning angle, in chords of
/// [`round_step`]`(distance)`, fills the gap.
///
/// ```
/// use furrow::headland::complexity::join_points;
/// use furrow::headland::offset::round_step;
/// use geo::polygon;
///
/// // A square field has no reflex corner; a square obstacle turns a full circle of them.
/// let field = polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 100., y: 100.), (x: 0., y: 100.)];
/// let pond = polygon![(x: 40., y: 40.), (x: 50., y: 40.), (x: 50., y: 50.), (x: 40., y: 50.)];
/// assert_eq!(join_points(&field, &[], 10.0), 0);
/// let quarter = (std::f64::consts::FRAC_PI_2 / round_step(10.0)).ceil() as usize;
/// assert_eq!(join_points(&field, &[&pond], 10.0), 4 * quarter);
/// ```
pub fn join_points(boundary: &Polygon, holes: &[&Polygon], distance: f64) -> usize {
    let step = round_step(distance);
    let rings = std::iter::once((boundary.exterior(), false))
        .chain(holes.iter().map(|h| (h.exterior(), true)));
    let mut points = 0;
    for (line, hole) in rings {
        let pts = line.0.get(..line.0.len().saturating_sub(1)).unwrap_or(&[]);
        let n = pts.len();
        let twice_area: f64 = line
            .0
            .windows(2)
            .map(|w| w[0].x * w[1].y - w[1].x * w[0].y)
            .sum();
        // The region lies left of each edge where this is positive.
        let side = if (twice_area > 0.0) != hole {
            1.0
        } else {
            -1.0
        };
        for i in 0..n {
            let (a, v, b) = (pts[(i + n - 1) % n], pts[i], pts[(i + 1) % n]);
            let (d1, d2) = (v - a, b - v);
            let cross = d1.x * d2.y - d1.y * d2.x;
            if cross * side < 0.0 {
                let turn = cross.abs().atan2(d1.x * d2.x + d1.y * d2.y);
                points += (turn / step).ceil() as usize;
            }
        }
    }
    points
}

/// Refuses, with [`ErrorCode::FieldTooComplex`], a region whose headland insets would cost more
/// than [`MAX_OFFSET_WORK`]: `passes` passes (the most along any edge or round any obstacle) of
/// `width` rounded to `turn_radius`, `passes + 1` insets (one a pass, and the inner field's),
/// each counted at the deepest, `(passes - 1/2) x width + turn_radius` (or `passes x width`):
/// its edges, its joins' points ([`join_points`]) and its overlapping sections
/// ([`overlapping_sections`]). `holes` are the obstacles that may get headlands (which do is
/// decided later).
///
/// ```
/// use furrow::headland::complexity::check_offsets;
/// use furrow::ErrorCode;
/// use geo::{LineString, Polygon};
///
/// // A 200 m disc traced with 20,000 points, each up to half a metre off: at a 6 m width the
/// // planner simplifies the noise away first, but at 0.1 m it is kept, and inset by 8 m its
/// // sections cross tens of thousands of times.
/// let points: Vec<(f64, f64)> = (0..20_000)
///     .map(|k| {
///         let t = k as f64 / 20_000.0 * std::f64::consts::TAU;
///         let r = 200.0 + 0.5 * ((k * 7919) % 13) as f64 / 6.0 - 0.5;
///         (r * t.cos(), r * t.sin())
///     })
///     .collect();
/// let noisy = Polygon::new(LineString::from(points), vec![]);
/// let err = check_offsets(&noisy, &[], 0.1, 2, 8.0).unwrap_err();
/// assert_eq!(err.code, ErrorCode::FieldTooComplex);
/// // Without headland passes nothing is offset.
/// assert!(check_offsets(&noisy, &[], 0.1, 0, 8.0).is_ok());
/// ```
pub fn check_offsets(
    boundary: &Polygon,
    holes: &[&Polygon],
    width: f64,
    passes: u32,
    turn_radius: f64,
) -> Result<(), PlanError> {
    if passes == 0 {
        return Ok(());
    }
    let insets = passes as usize + 1;
    let deepest = ((passes as f64 - 0.5) * width + turn_radius).max(passes as f64 * width);
    let edges: usize = std::iter::once(boundary)
        .chain(holes.iter().copied())
        .map(|p| p.exterior().0.len().saturating_sub(1))
        .sum();
    let joins = join_points(boundary, holes, deepest);
    let outline = edges.saturating_add(joins);
    // The overlapping pairs each inset may have besides its edges and joins.
    let allowed = (MAX_OFFSET_WORK / insets).saturating_sub(outline);
    let overlaps = if outline.saturating_mul(insets) <= MAX_OFFSET_WORK {
        overlapping_sections(boundary, holes, deepest, allowed)
    } else {
        SectionOverlaps {
            pairs: 0,
            stopped: true,
        }
    };
    if !overlaps.stopped {
        return Ok(());
    }
    let crossing = if overlaps.pairs > 0 {
        format!(
            ", overlapping each other more than {} times",
            overlaps.pairs.min(allowed)
        )
    } else {
        String::new()
    };
    Err(PlanError::new(
        ErrorCode::FieldTooComplex,
        format!(
            "the outlines are too detailed for headland passes at {} m: their {edges} edges and {joins} points of rounded corners, inset by up to {} m{crossing}, {insets} times over, are more than the planner takes on ({MAX_OFFSET_WORK} in all); simplify the outlines or use fewer obstacles, or a wider working width, fewer headland passes or a smaller turning radius",
            Shortest(width),
            Decimals(deepest, 1)
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64 as Rng;
    use geo::{Intersects, LineString};

    /// A star of `n` points of radius about `r`, each moved in or out by up to `noise`.
    fn noisy_star(n: usize, r: f64, noise: f64, seed: u64) -> Polygon {
        let mut rng = Rng::new(seed);
        let points: Vec<(f64, f64)> = (0..n)
            .map(|k| {
                let t = k as f64 / n as f64 * std::f64::consts::TAU;
                let radius = r * (1.0 + 0.3 * (5.0 * t).sin()) + noise * (2.0 * rng.unit() - 1.0);
                (radius * t.cos(), radius * t.sin())
            })
            .collect();
        Polygon::new(LineString::from(points), vec![])
    }

    /// The sections as polygons, and the pairs that intersect by geo, neighbours left out.
    fn by_geo(rings: &[(&LineString, bool)], distance: f64) -> usize {
        let mut sections: Vec<(usize, usize, usize, Polygon)> = Vec::new();
        for (ring, &(line, hole)) in rings.iter().enumerate() {
            let twice_area: f64 = line
                .0
                .windows(2)
                .map(|w| w[0].x * w[1].y - w[1].x * w[0].y)
                .sum();
            let left = (twice_area > 0.0) != hole;
            let n = line.0.len() - 1;
            for (index, w) in line.0.windows(2).enumerate() {
                let d = w[1] - w[0];
                let l = d.x.hypot(d.y);
                let s = if left { 1.0 } else { -1.0 };
                let v = Coord {
                    x: -d.y * s * distance / l,
                    y: d.x * s * distance / l,
                };
                let quad = LineString::new(vec![w[0], w[1], w[1] + v, w[0] + v, w[0]]);
                sections.push((ring, index, n, Polygon::new(quad, vec![])));
            }
        }
        let mut pairs = 0;
        for (i, a) in sections.iter().enumerate() {
            for b in &sections[i + 1..] {
                let gap = a.1.abs_diff(b.1);
                let neighbours = a.0 == b.0 && (gap <= 1 || gap + 1 == a.2);
                if !neighbours && a.3.intersects(&b.3) {
                    pairs += 1;
                }
            }
        }
        pairs
    }

    #[test]
    fn overlapping_sections_are_those_geo_finds() {
        for (seed, noise, distance) in [(1, 0.5, 1.0), (2, 2.0, 3.0), (3, 0.0, 20.0), (4, 1.0, 8.0)]
        {
            let star = noisy_star(300, 60.0, noise, seed);
            // A hole: a smaller star inside, running the other way round.
            let hole = {
                let mut h = noisy_star(100, 15.0, noise, seed + 10);
                h.exterior_mut(|r| r.0.reverse());
                h
            };
            let rings = [(star.exterior(), false), (hole.exterior(), true)];
            let expected = by_geo(&rings, distance);
            let got = overlapping_sections(&star, &[&hole], distance, usize::MAX / 16);
            assert_eq!(got.pairs, expected, "seed {seed}");
            assert!(!got.stopped);
        }
    }

    #[test]
    fn counting_stops_at_the_cap() {
        let star = noisy_star(2000, 100.0, 1.0, 5);
        let all = overlapping_sections(&star, &[], 8.0, usize::MAX / 16);
        assert!(all.pairs > 10_000, "{}", all.pairs);
        let capped = overlapping_sections(&star, &[], 8.0, 1000);
        assert!(capped.stopped);
        assert_eq!(capped.pairs, 1001);
    }

    #[test]
    fn smooth_or_wide_outlines_pass_and_jagged_fine_ones_are_refused() {
        // The same noisy trace: at a 6 m width the planner simplifies it first, at 0.1 m the
        // noise stays, and the insets by 8 m (the turning radius) cross it all over.
        let trace = noisy_star(20_000, 200.0, 0.5, 6);
        let err = check_offsets(&trace, &[], 0.1, 2, 8.0).unwrap_err();
        assert_eq!(err.code, ErrorCode::FieldTooComplex);
        assert!(
            err.message.contains("wider working width"),
            "{}",
            err.message
        );
        // Without the turning radius the insets are a few centimetres deep.
        assert!(check_offsets(&trace, &[], 0.1, 2, 0.0).is_ok());
        // A disc of as many points passes...
        let disc = |n: usize| {
            let points: Vec<(f64, f64)> = (0..n)
                .map(|k| {
                    let t = k as f64 / n as f64 * std::f64::consts::TAU;
                    (200.0 * t.cos(), 200.0 * t.sin())
                })
                .collect();
            Polygon::new(LineString::from(points), vec![])
        };
        assert!(check_offsets(&disc(20_000), &[], 0.1, 2, 8.0).is_ok());
        // ... and one as the planner simplifies it at a 6 m width (within 1 m: a point every
        // 40 m, here every 6) at any depth up to its middle...
        assert!(check_offsets(&disc(200), &[], 6.0, 10, 8.0).is_ok());
        // ... but each pass is an inset of every edge: 80 insets of 20,000 edges spend the
        // budget.
        assert!(check_offsets(&disc(20_000), &[], 0.1, 79, 0.0).is_err());
        // The concave bays of a smooth star, as densely drawn, turn tighter than 65 m: the
        // sections of each bay cross by the hundred thousand.
        let star = noisy_star(20_000, 200.0, 0.0, 7);
        assert!(check_offsets(&star, &[], 6.0, 10, 8.0).is_err());
    }
}
