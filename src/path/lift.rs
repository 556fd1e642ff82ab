//! Where a worked line would put the implement outside the field or over an obstacle: the
//! stretches it is driven with the implement lifted.
//!
//! The implement is a bar `width` wide square to the line. Along each straight piece (chord) of
//! a worked line the bar sweeps a rectangle; wherever an edge of the field or of an obstacle
//! reaches into that rectangle (more than [`LIFT_TOLERANCE_M`] in from its long sides), the bar
//! would be partly outside there, and wherever the line itself runs outside, all of it would.
//! A headland pass running over an obstacle too small for a headland of its own (class A), the
//! slanted ends of swaths laid without headland, and the sides of the outer swaths of such a
//! field are lifted so; a line the bar keeps inside is left whole.

use super::turn::{Area, BOUNDARY_EDGE};
use super::PathSegment;
use crate::geometry::intervals::{union, Intervals};
use crate::geometry::{IndexedSegment, PlanarHypot};
use crate::route::{Route, RouteStep};
use crate::sort::SharedSort;
use crate::swath::Swaths;
use geo::Coord;
use rstar::AABB;

/// How far an edge may reach into the implement's strip from its side before the implement is
/// lifted there, metres: the bar of an outer headland pass runs along the boundary, and its
/// line is drawn with chords within 5 mm ([`super::turn::CHORD_TOLERANCE_M`]) of passes whose
/// arcs are held within 3 mm ([`crate::headland::offset::ARC_TOLERANCE_M`]); a millimetre short
/// of the centimetre the property test allows.
pub const LIFT_TOLERANCE_M: f64 = 0.009;

impl Area {
    /// The stretches of `line` (metres along it from its first point, sorted and disjoint)
    /// where a bar `2 * half` wide square to it reaches outside the area: an edge is within
    /// `half` (less [`LIFT_TOLERANCE_M`]) of the line there, or the line runs outside.
    ///
    /// ```
    /// use furrow::path::turn::Area;
    /// use geo::{coord, polygon};
    ///
    /// // A 100 x 40 m field with a 2 m pole at x = 49..51, y = 19..21.
    /// let field = polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 100., y: 40.), (x: 0., y: 40.)];
    /// let pole = polygon![(x: 49., y: 19.), (x: 51., y: 19.), (x: 51., y: 21.), (x: 49., y: 21.)];
    /// let area = Area::new(&field, &[&pole]);
    /// // A 6 m implement along y = 17 reaches the pole between x = 49 and 51.
    /// let line = [coord! { x: 10., y: 17. }, coord! { x: 90., y: 17. }];
    /// assert_eq!(area.reaches_out(&line, 3.0), vec![(39.0, 41.0)]);
    /// // Along y = 3 it runs along the boundary, 3 m off it: nothing is lifted.
    /// let line = [coord! { x: 10., y: 3. }, coord! { x: 90., y: 3. }];
    /// assert!(area.reaches_out(&line, 3.0).is_empty());
    /// ```
    pub fn reaches_out(&self, line: &[Coord], half: f64) -> Intervals {
        let (out, along) = self.edges_reaching_in(line, half, &|_| true);
        // Between the stretches where an edge reaches into the strip, the whole bar is on one
        // side of every edge: outside where the line is.
        let mut gaps = Vec::new();
        let mut from = 0.0;
        for &(a, b) in out.iter().chain(std::iter::once(&(along, along))) {
            let middle = super::polyline_pose(line, (from + a) / 2.0);
            if a > from && middle.is_some_and(|p| !self.contains_point(Coord { x: p.x, y: p.y })) {
                gaps.push((from, a));
            }
            from = b;
        }
        close_crumbs(&union(&out, &gaps), along)
    }

    /// How far along `line` an edge of the field's boundary (not of an obstacle) reaches into
    /// the strip of a bar `2 * half` wide square to it, metres: where the bar would reach past
    /// the boundary beside it, crop a headland pass along that edge would work.
    pub fn reach_past_boundary_m(&self, line: &[Coord], half: f64) -> f64 {
        let (hits, _) = self.edges_reaching_in(line, half, &|e| e.line == BOUNDARY_EDGE);
        hits.iter().map(|(a, b)| b - a).sum()
    }

    /// The stretches of `line` (metres along it, merged) where an edge that `keep` keeps
    /// reaches into the strip `half` (less [`LIFT_TOLERANCE_M`]) either side of it, and the
    /// line's length.
    fn edges_reaching_in(
        &self,
        line: &[Coord],
        half: f64,
        keep: &dyn Fn(&IndexedSegment) -> bool,
    ) -> (Intervals, f64) {
        let reach = (half - LIFT_TOLERANCE_M).max(0.0);
        let mut hits: Intervals = Vec::new();
        let mut along = 0.0;
        for w in line.windows(2) {
            let length = {
                let d = w[1] - w[0];
                d.x.planar_hypot(d.y)
            };
            if length > 0.0 {
                let on_chord = self.edges_in_strip(w[0], w[1], length, reach, keep);
                hits.extend(on_chord.iter().map(|h| (along + h.0, along + h.1)));
            }
            along += length;
        }
        hits.shared_sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        (union(&[], &hits), along)
    }

    /// Where along the chord `a`-`b` (of `length`, metres from `a`) an edge that `keep` keeps
    /// reaches into the strip `reach` either side of it.
    fn edges_in_strip(
        &self,
        a: Coord,
        b: Coord,
        length: f64,
        reach: f64,
        keep: &dyn Fn(&IndexedSegment) -> bool,
    ) -> Intervals {
        let u = (b - a) / length;
        let local = |p: Coord| {
            let d = p - a;
            (d.x * u.x + d.y * u.y, d.y * u.x - d.x * u.y)
        };
        let envelope = AABB::from_corners(
            [a.x.min(b.x) - reach, a.y.min(b.y) - reach],
            [a.x.max(b.x) + reach, a.y.max(b.y) + reach],
        );
        self.edges
            .locate_in_envelope_intersecting(&envelope)
            .filter(|e| keep(e))
            .filter_map(|e| clip_to_strip(local(e.a), local(e.b), length, reach))
            .collect()
    }

    /// Whether `p` is inside the area (an odd number of edges crosses the ray east of it).
    fn contains_point(&self, p: Coord) -> bool {
        let east = self.edges.root().envelope().upper()[0];
        // (Written so that a NaN point is outside.)
        if east.partial_cmp(&p.x) != Some(std::cmp::Ordering::Greater) {
            return false;
        }
        let ray = AABB::from_corners([p.x, p.y], [east, p.y]);
        let crossings = self
            .edges
            .locate_in_envelope_intersecting(&ray)
            .filter(|e| {
                (e.a.y > p.y) != (e.b.y > p.y)
                    && e.a.x + (p.y - e.a.y) / (e.b.y - e.a.y) * (e.b.x - e.a.x) > p.x
            })
            .count();
        crossings % 2 == 1
    }
}

/// Worked stretches shorter than this between lifts, or before the first or after the last,
/// are lifted too, metres: the implement is not lowered for a few millimetres.
const CRUMB_M: f64 = 0.01;

/// How far the worked segments of a path are lifted because the implement would reach past
/// the field's boundary (not over an obstacle: a pole in the headland is no edge a pass would
/// work), metres; only the segments lifted somewhere are measured.
pub fn lifted_at_edges_m(path: &super::Path, area: &Area, half: f64) -> f64 {
    path.segments
        .iter()
        .filter(|s| !s.lifted.is_empty())
        .map(|s| area.reach_past_boundary_m(&s.line.0, half))
        .sum()
}

/// `lifted` (within `0..total`) with the worked stretches shorter than [`CRUMB_M`] between its
/// stretches and at the ends closed, and the stretches of no length (under a micrometre: an
/// edge the bar only touches, as the boundary square across a swath's end) left out.
fn close_crumbs(lifted: &[(f64, f64)], total: f64) -> Intervals {
    let mut out: Intervals = Vec::with_capacity(lifted.len());
    for &(a, b) in lifted.iter().filter(|(a, b)| b - a > 1e-6) {
        let a = if a < CRUMB_M { 0.0 } else { a };
        let b = if b > total - CRUMB_M { total } else { b };
        match out.last_mut() {
            Some(last) if a - last.1 < CRUMB_M => last.1 = last.1.max(b),
            _ => out.push((a, b)),
        }
    }
    out
}

/// Marks the stretches of the worked segments driven with the implement lifted: where their
/// swaths pass over obstacles too small for a headland ([`Swaths::lifts`]), and where a bar
/// `2 * half` wide would reach out of `area` ([`Area::reaches_out`]).
pub(super) fn lift_where_needed(
    segments: &mut [PathSegment],
    route: &Route,
    swaths: &Swaths,
    half: f64,
    area: Option<&Area>,
) {
    for seg in segments.iter_mut().filter(|s| s.is_working()) {
        let mut lifted = match seg.step.and_then(|k| route.steps.get(k)) {
            Some(&RouteStep::Swath {
                swath, reversed, ..
            }) => over_small_obstacles(swaths, swath, reversed),
            _ => Vec::new(),
        };
        if let Some(area) = area {
            lifted = union(&lifted, &area.reaches_out(&seg.line.0, half));
        }
        seg.lifted = lifted;
    }
}

/// Where swath `i`, driven `reversed` or not, passes over small obstacles: metres from its
/// first point as driven.
fn over_small_obstacles(swaths: &Swaths, i: usize, reversed: bool) -> Intervals {
    let Some(s) = swaths.swaths.get(i) else {
        return Vec::new();
    };
    let start = swaths.lifts.partition_point(|l| l.swath < i);
    let mut out: Intervals = swaths.lifts[start..]
        .iter()
        .take_while(|l| l.swath == i)
        .map(|l| {
            if reversed {
                (s.along.1 - l.along.1, s.along.1 - l.along.0)
            } else {
                (l.along.0 - s.along.0, l.along.1 - s.along.0)
            }
        })
        .collect();
    out.shared_sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
    union(&[], &out)
}

/// The range of `t` over which the segment `p`-`q` (in a chord's frame: `t` along it, `s`
/// across) lies within `0 <= t <= length`, `|s| <= reach` (Liang-Barsky), if it does anywhere.
fn clip_to_strip(p: (f64, f64), q: (f64, f64), length: f64, reach: f64) -> Option<(f64, f64)> {
    let (dt, ds) = (q.0 - p.0, q.1 - p.1);
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    // Each side as `k * lambda <= m`.
    for (k, m) in [
        (-dt, p.0),
        (dt, length - p.0),
        (-ds, p.1 + reach),
        (ds, reach - p.1),
    ] {
        if k == 0.0 {
            if m < 0.0 {
                return None;
            }
        } else if k > 0.0 {
            hi = hi.min(m / k);
        } else {
            lo = lo.max(m / k);
        }
    }
    (lo <= hi).then(|| {
        let (t0, t1) = (p.0 + lo * dt, p.0 + hi * dt);
        (t0.min(t1), t0.max(t1))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{coord, polygon};

    fn square() -> geo::Polygon {
        polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 100., y: 100.), (x: 0., y: 100.)]
    }

    #[test]
    fn a_line_leaving_the_field_is_lifted_from_where_the_bar_reaches_the_boundary() {
        let area = Area::new(&square(), &[]);
        let line = [coord! { x: 50., y: 50. }, coord! { x: 150., y: 50. }];
        let lifted = area.reaches_out(&line, 3.0);
        assert_eq!(lifted.len(), 1);
        assert!((lifted[0].0 - 50.0).abs() < 1e-9 && (lifted[0].1 - 100.0).abs() < 1e-9);
    }

    #[test]
    fn a_bar_wholly_inside_an_obstacle_is_lifted_across_it() {
        // A 40 m pond: the 6 m bar is inside it from x = 33 to 67, off its edges.
        let pond = polygon![(x: 30., y: 30.), (x: 70., y: 30.), (x: 70., y: 70.), (x: 30., y: 70.)];
        let area = Area::new(&square(), &[&pond]);
        let line = [
            coord! { x: 10., y: 50. },
            coord! { x: 40., y: 50. },
            coord! { x: 90., y: 50. },
        ];
        assert_eq!(area.reaches_out(&line, 3.0), vec![(20.0, 60.0)]);
    }

    #[test]
    fn a_line_ending_on_the_boundary_square_across_it_lifts_nothing() {
        // The bar at the line's end lies along the east side: it touches it, no more.
        let area = Area::new(&square(), &[]);
        let line = [coord! { x: 10., y: 50. }, coord! { x: 100., y: 50. }];
        assert!(area.reaches_out(&line, 3.0).is_empty());
    }

    #[test]
    fn only_the_boundary_counts_as_reached_past() {
        let pond = polygon![(x: 30., y: 30.), (x: 70., y: 30.), (x: 70., y: 70.), (x: 30., y: 70.)];
        let area = Area::new(&square(), &[&pond]);
        let through_pond = [coord! { x: 10., y: 50. }, coord! { x: 90., y: 50. }];
        assert_eq!(area.reach_past_boundary_m(&through_pond, 3.0), 0.0);
        // Along y = 1.5 the bar (y = -1.5..4.5) reaches past the south side all its length.
        let along_south = [coord! { x: 10., y: 1.5 }, coord! { x: 90., y: 1.5 }];
        assert!((area.reach_past_boundary_m(&along_south, 3.0) - 80.0).abs() < 1e-9);
    }

    #[test]
    fn a_slanted_end_is_lifted_where_the_strip_crosses_it() {
        // The east side runs from (100, 0) to (80, 100): at y = 55 it is at x = 89. A 10 m bar
        // along y = 50 (y = 45..55) meets it from x = 89 on, 79 m along the line.
        let field = polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 80., y: 100.), (x: 0., y: 100.)];
        let area = Area::new(&field, &[]);
        let line = [coord! { x: 10., y: 50. }, coord! { x: 90., y: 50. }];
        let lifted = area.reaches_out(&line, 5.0);
        assert_eq!(lifted.len(), 1);
        assert!((lifted[0].0 - 79.0).abs() < 0.01, "{lifted:?}");
        assert!((lifted[0].1 - 80.0).abs() < 1e-9, "{lifted:?}");
    }
}
