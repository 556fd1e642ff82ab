//! Exact passes, rounded by the turning circle only where the machine cannot drive them.
//!
//! A pass is first the exact offset of the field, its convex corners sharp and its arms and
//! strips kept however narrow. The same offset *opened* by a disc of the turning radius
//! ([`super::offset::open`]) is what the machine can drive forward without ever lifting: it
//! runs along the exact pass, leaving it only to round a corner or to cut across the mouth of an
//! arm or a strip too narrow to turn in. Each such shortcut of the opened pass replaces the
//! stretch of the exact pass it cuts off only where the caller says that stretch cannot be
//! driven (a manoeuvre it needs would leave the field, say): elsewhere the exact stretch is
//! kept, its corner worked into and its arm worked up and back.
//!
//! ```
//! use furrow::headland::splice::splice;
//! use geo::{coord, LineString};
//!
//! // A square pass 20 m across and its opening by a 5 m disc, whose south-east corner is an
//! // arc (here a single chord from (15, 0) to (20, 5)).
//! let exact = LineString::from(vec![(0., 0.), (20., 0.), (20., 20.), (0., 20.), (0., 0.)]);
//! let opened = LineString::from(vec![(0., 0.), (15., 0.), (20., 5.), (20., 20.), (0., 20.), (0., 0.)]);
//! // Where the corner can be driven, the exact pass stays as it is.
//! let kept = splice(&exact, &[&opened], &|_, _| true);
//! assert_eq!(kept, vec![exact.clone()]);
//! // Where it cannot, the shortcut replaces it.
//! let cut = &splice(&exact, &[&opened], &|_, _| false)[0];
//! assert!(cut.0.contains(&coord! { x: 15., y: 0. }) && !cut.0.contains(&coord! { x: 20., y: 0. }));
//! ```

use crate::geometry::{IndexedSegment, PlanarHypot};
use geo::{Coord, Intersects, Line, LineString};
use rstar::{RTree, AABB};

/// How far before and after the stretch a shortcut cuts off (metres, at most a quarter of the
/// ring) the machine is asked to drive it: a shortcut starts where the turning circle's arc
/// leaves the exact pass, just where a rounding at the same radius would start.
const RUN_UP_M: f64 = 1.0;

/// A point of the opened pass within this distance (metres) of the exact pass lies on it. The
/// opening's straight stretches are offsets of the exact pass's edges (within 1e-8 m); its arcs'
/// first chord points lie a millimetre or more inside.
const ON_PASS_M: f64 = 1e-4;

/// A run of an opened ring's edges off the exact ring: from its point `start` to its point
/// `end` (both on the exact ring, at `from` and `to` metres along it).
struct Shortcut {
    start: usize,
    end: usize,
    from: f64,
    to: f64,
}

/// An opened ring as it runs along the exact one: its points (the last not repeated) and its
/// shortcuts.
struct Opened<'q> {
    points: &'q [Coord],
    shortcuts: Vec<Shortcut>,
}

/// A closed ring (first point repeated last) with the distance along it of each point.
struct Ring<'a> {
    points: &'a [Coord],
    at: Vec<f64>,
    length: f64,
    tree: RTree<IndexedSegment>,
}

impl<'a> Ring<'a> {
    fn new(points: &'a [Coord]) -> Self {
        let mut at = Vec::with_capacity(points.len());
        let mut length = 0.0;
        let mut segments = Vec::with_capacity(points.len());
        for (i, w) in points.windows(2).enumerate() {
            at.push(length);
            length += (w[1].x - w[0].x).planar_hypot(w[1].y - w[0].y);
            segments.push(IndexedSegment::new(w[0], w[1], 0, i));
        }
        at.push(length);
        Ring {
            points,
            at,
            length,
            tree: RTree::bulk_load(segments),
        }
    }

    /// Where `p` lies on the ring (metres along it), if within [`ON_PASS_M`].
    fn locate(&self, p: Coord) -> Option<f64> {
        let (segment, d2) = self
            .tree
            .nearest_neighbor_iter_with_distance_2(&[p.x, p.y])
            .next()?;
        if d2 > ON_PASS_M * ON_PASS_M {
            return None;
        }
        let (a, b) = (segment.a, segment.b);
        let d = b - a;
        let len2 = d.x * d.x + d.y * d.y;
        let t = if len2 > 0.0 {
            (((p.x - a.x) * d.x + (p.y - a.y) * d.y) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        Some(self.at[segment.index] + t * len2.sqrt())
    }

    /// Metres forwards along the ring from `from` to `to`.
    fn ahead(&self, from: f64, to: f64) -> f64 {
        (to - from).rem_euclid(self.length)
    }

    /// The point `s` metres along the ring.
    fn point_at(&self, s: f64) -> Coord {
        let s = s.rem_euclid(self.length);
        let i = self.at.partition_point(|&a| a <= s).saturating_sub(1);
        let i = i.min(self.points.len() - 2);
        let (a, b) = (self.points[i], self.points[i + 1]);
        let len = self.at[i + 1] - self.at[i];
        let t = if len > 0.0 {
            (s - self.at[i]) / len
        } else {
            0.0
        };
        a + (b - a) * t.clamp(0.0, 1.0)
    }

    /// The ring's points from `from` to `to` metres along it, forwards: both ends and every
    /// vertex between.
    fn stretch(&self, from: f64, to: f64) -> Vec<Coord> {
        let span = self.ahead(from, to);
        let start = from.rem_euclid(self.length);
        let n = self.points.len() - 1;
        let mut out = vec![self.point_at(start)];
        // The first vertex after the start (the last, `n`, is the first again).
        let mut i = self.at.partition_point(|&a| a <= start).min(n);
        let mut done = self.at[i] - start;
        while done < span - 1e-12 {
            out.push(self.points[i]);
            if i == n {
                i = 0;
            }
            done += self.at[i + 1] - self.at[i];
            i += 1;
        }
        out.push(self.point_at(to));
        out
    }
}

/// How an opened ring `q` runs along the exact `ring`: `None` where it never does.
fn opened<'q>(ring: &Ring, q: &'q [Coord]) -> Option<Opened<'q>> {
    let m = q.len().saturating_sub(1);
    if m < 3 {
        return None;
    }
    let at: Vec<Option<f64>> = q[..m].iter().map(|&p| ring.locate(p)).collect();
    // Edge i (from point i to i + 1) runs along the ring where both ends are on it and the
    // ring goes as far between them as the edge.
    let along: Vec<bool> = (0..m)
        .map(|i| match (at[i], at[(i + 1) % m]) {
            (Some(a), Some(b)) => {
                let chord = (q[i + 1].x - q[i].x).planar_hypot(q[i + 1].y - q[i].y);
                (ring.ahead(a, b) - chord).abs() <= 1e-6 * (1.0 + chord)
            }
            _ => false,
        })
        .collect();
    let first = along.iter().position(|&b| b)?;
    let mut shortcuts = Vec::new();
    let mut run: Option<usize> = None;
    for step in 1..=m {
        let i = (first + step) % m;
        match (along[i], run) {
            (false, None) => run = Some(i),
            (true, Some(start)) => {
                if let (Some(from), Some(to)) = (at[start], at[i]) {
                    shortcuts.push(Shortcut {
                        start,
                        end: i,
                        from,
                        to,
                    });
                }
                run = None;
            }
            _ => {}
        }
    }
    Some(Opened {
        points: &q[..m],
        shortcuts,
    })
}

/// The opened ring `o` with each of its shortcuts that `detour` accepts replaced by the stretch
/// of the exact `ring` it cuts off: a closed ring.
fn rebuild(ring: &Ring, o: &Opened, detour: &dyn Fn(&Shortcut) -> bool) -> LineString {
    let m = o.points.len();
    let mut out: Vec<Coord> = Vec::with_capacity(m + 8);
    // From the end of a shortcut (or the first point where there is none), once round.
    let origin = o.shortcuts.first().map_or(0, |s| s.end);
    let mut i = origin;
    let mut done = 0;
    while done < m {
        match o.shortcuts.iter().find(|s| s.start == i) {
            Some(s) if detour(s) => {
                out.extend(ring.stretch(s.from, s.to));
                out.pop();
                done += (s.end + m - s.start) % m;
                i = s.end;
            }
            _ => {
                out.push(o.points[i]);
                done += 1;
                i = (i + 1) % m;
            }
        }
    }
    if let Some(&first) = out.first() {
        out.push(first);
    }
    out.dedup_by(|a, b| (a.x - b.x).planar_hypot(a.y - b.y) < 1e-9);
    LineString::new(out)
}

/// The rings of the exact pass `exact` (a closed ring) as the machine drives it, given the same
/// pass opened by the turning disc (`opened`, its rings near `exact`) and whether the machine
/// is to drive a stretch of the exact pass rather than the shortcut across it (`drivable`, the
/// stretch and the shortcut as polylines from a metre before the shortcut's start to a metre
/// after its end): the exact ring where every stretch the opening cuts off is
/// drivable or the opening leaves nothing of it; else, where the opening leaves one ring, that
/// ring with its shortcuts replaced by the exact stretches that are drivable (an arm kept, a
/// corner worked into); where it leaves several (a neck it cuts), those rings. See the module
/// documentation.
pub fn splice(
    exact: &LineString,
    opened: &[&LineString],
    drivable: &dyn Fn(&[Coord], &[Coord]) -> bool,
) -> Vec<LineString> {
    let points = &exact.0;
    if points.len() < 4 {
        return vec![exact.clone()];
    }
    let ring = Ring::new(points);
    if ring.length <= 0.0 {
        return vec![exact.clone()];
    }
    let runs: Vec<Opened> = opened
        .iter()
        .filter_map(|q| self::opened(&ring, &q.0))
        .collect();
    if runs.is_empty() {
        return vec![exact.clone()];
    }
    let cut_off = |s: &Shortcut| {
        let span = ring.ahead(s.from, s.to);
        span > 1e-6 && span < ring.length - 1e-6
    };
    let lead = RUN_UP_M.min(ring.length / 4.0);
    let verdicts: Vec<Vec<bool>> = runs
        .iter()
        .map(|o| {
            o.shortcuts
                .iter()
                .map(|s| {
                    if !cut_off(s) {
                        return true;
                    }
                    let mut shortcut = vec![ring.point_at(s.from - lead)];
                    let m = o.points.len();
                    let mut k = s.start;
                    while k != s.end {
                        shortcut.push(o.points[k]);
                        k = (k + 1) % m;
                    }
                    shortcut.push(o.points[s.end]);
                    shortcut.push(ring.point_at(s.to + lead));
                    drivable(&ring.stretch(s.from - lead, s.to + lead), &shortcut)
                })
                .collect()
        })
        .collect();
    if verdicts.iter().flatten().all(|&v| v) {
        return vec![exact.clone()];
    }
    if let [only] = &runs[..] {
        let verdict = &verdicts[0];
        let detour = |s: &Shortcut| {
            let n = only.shortcuts.iter().position(|t| std::ptr::eq(t, s));
            cut_off(s) && n.is_some_and(|n| verdict[n])
        };
        return vec![rebuild(&ring, only, &detour)];
    }
    // Several parts (a neck the opening cuts): each as the opening leaves it.
    opened
        .iter()
        .filter(|q| {
            runs.iter()
                .any(|o| std::ptr::eq(o.points.as_ptr(), q.0.as_ptr()))
        })
        .map(|q| (*q).clone())
        .collect()
}

/// [`splice`] for every ring of the exact pass at one depth (`exact`, each with what it runs
/// around), given every ring of the opened pass: each exact ring is spliced with the opened
/// rings that run along it alone. An opened ring that runs along several exact rings (holes the
/// opening merges: obstacles whose passes the turning circle cannot drive between) replaces
/// them all, once; one that runs along none lies within an exact ring kept and is dropped.
pub fn splice_all<T: Copy>(
    exact: &[(LineString, T)],
    opened: &[&LineString],
    drivable: &dyn Fn(&[Coord], &[Coord]) -> bool,
) -> Vec<(LineString, T)> {
    let rings: Vec<Option<Ring>> = exact
        .iter()
        .map(|(r, _)| (r.0.len() >= 4).then(|| Ring::new(&r.0)))
        .collect();
    // For each opened ring, the exact rings it runs along.
    let touches: Vec<Vec<usize>> = opened
        .iter()
        .map(|q| {
            rings
                .iter()
                .enumerate()
                .filter(|(_, r)| {
                    r.as_ref()
                        .is_some_and(|r| r.length > 0.0 && self::opened(r, &q.0).is_some())
                })
                .map(|(i, _)| i)
                .collect()
        })
        .collect();
    let shared = |i: usize| touches.iter().any(|t| t.len() > 1 && t.contains(&i));
    let mut out = Vec::with_capacity(exact.len());
    for (i, (ring, around)) in exact.iter().enumerate() {
        if shared(i) {
            continue;
        }
        let own: Vec<&LineString> = opened
            .iter()
            .zip(&touches)
            .filter(|(_, t)| t[..] == [i])
            .map(|(q, _)| *q)
            .collect();
        out.extend(
            splice(ring, &own, drivable)
                .into_iter()
                .map(|r| (r, *around)),
        );
    }
    for (q, t) in opened.iter().zip(&touches) {
        if let [first, _, ..] = t[..] {
            out.push(((*q).clone(), exact[first].1));
        }
    }
    out
}

/// The passes laid one width further out, against which a stretch of the next pass is checked:
/// a stretch kept exact where the pass outside it takes a shortcut would cross it.
pub struct Outside {
    tree: RTree<IndexedSegment>,
}

impl Outside {
    /// The segments of `lines`.
    pub fn new<'a>(lines: impl Iterator<Item = &'a LineString>) -> Self {
        let segments = lines
            .flat_map(|l| {
                l.0.windows(2)
                    .map(|w| IndexedSegment::new(w[0], w[1], 0, 0))
            })
            .collect();
        Outside {
            tree: RTree::bulk_load(segments),
        }
    }

    /// Whether the polyline `stretch` meets any of the lines.
    pub fn crosses(&self, stretch: &[Coord]) -> bool {
        stretch.windows(2).any(|w| {
            let line = Line::new(w[0], w[1]);
            let envelope = AABB::from_corners(
                [w[0].x.min(w[1].x), w[0].y.min(w[1].y)],
                [w[0].x.max(w[1].x), w[0].y.max(w[1].y)],
            );
            self.tree
                .locate_in_envelope_intersecting(&envelope)
                .any(|s| s.as_line().intersects(&line))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::coord;

    fn ring(points: &[(f64, f64)]) -> LineString {
        let mut v: Vec<Coord> = points.iter().map(|&(x, y)| coord! { x: x, y: y }).collect();
        v.push(v[0]);
        LineString::new(v)
    }

    fn length(l: &LineString) -> f64 {
        l.0.windows(2)
            .map(|w| (w[1].x - w[0].x).planar_hypot(w[1].y - w[0].y))
            .sum()
    }

    #[test]
    fn an_arm_is_cut_off_only_where_it_cannot_be_driven() {
        // A 100 m square pass with an arm 4 m wide and 30 m long up from its north side; the
        // opened pass runs straight across the arm's mouth.
        let exact = ring(&[
            (0., 0.),
            (100., 0.),
            (100., 100.),
            (52., 100.),
            (52., 130.),
            (48., 130.),
            (48., 100.),
            (0., 100.),
        ]);
        let opened = ring(&[(0., 0.), (100., 0.), (100., 100.), (0., 100.)]);
        assert_eq!(
            splice(&exact, &[&opened], &|_, _| true),
            vec![exact.clone()]
        );
        let asked = std::cell::RefCell::new(Vec::new());
        let cut = splice(&exact, &[&opened], &|s, _| {
            asked.borrow_mut().push(s.to_vec());
            false
        });
        // The stretch asked about runs from the arm's mouth up the arm and back
        let asked = asked.into_inner();
        assert_eq!(asked.len(), 1);
        // (from a metre before the mouth to a metre after it)
        assert_eq!(asked[0].first(), Some(&coord! { x: 100., y: 99. }));
        assert!(asked[0].contains(&coord! { x: 52., y: 130. }));
        assert_eq!(asked[0].last(), Some(&coord! { x: 0., y: 99. }));
        // The pass without the arm: the square.
        assert_eq!(cut.len(), 1);
        assert!(cut[0].is_closed());
        assert!(cut[0].0.iter().all(|p| p.y <= 100.0));
        assert!((length(&cut[0]) - 400.0).abs() < 1e-9);
    }

    #[test]
    fn a_shortcut_over_the_ring_start_wraps() {
        let exact = ring(&[(0., 0.), (20., 0.), (20., 20.), (0., 20.)]);
        // The opened pass rounds the corner at the ring's start (0, 0).
        let opened = ring(&[
            (5., 0.),
            (20., 0.),
            (20., 20.),
            (0., 20.),
            (0., 5.),
            (1.5, 1.5),
        ]);
        let cut = splice(&exact, &[&opened], &|_, _| false);
        assert_eq!(cut.len(), 1);
        assert!(cut[0].is_closed());
        assert!(!cut[0].0.contains(&coord! { x: 0., y: 0. }));
        assert!(cut[0].0.contains(&coord! { x: 1.5, y: 1.5 }));
        assert_eq!(cut[0].0.len(), 7);
    }

    #[test]
    fn a_ring_the_opening_leaves_nothing_of_stays_exact() {
        let strip = ring(&[(0., 0.), (100., 0.), (100., 4.), (0., 4.)]);
        assert_eq!(splice(&strip, &[], &|_, _| false), vec![strip.clone()]);
    }

    #[test]
    fn a_stretch_crossing_the_pass_outside_is_seen() {
        let outside = LineString::from(vec![(0., 10.), (100., 10.)]);
        let outside = Outside::new(std::iter::once(&outside));
        assert!(outside.crosses(&[coord! { x: 50., y: 0. }, coord! { x: 50., y: 20. }]));
        assert!(!outside.crosses(&[coord! { x: 0., y: 0. }, coord! { x: 100., y: 4. }]));
    }

    #[test]
    fn a_neck_that_cannot_be_driven_leaves_two_rings() {
        // Two 40 m squares joined by a neck 4 m wide and 20 m long; opened, two squares.
        let exact = LineString::from(vec![
            (0., 0.),
            (40., 0.),
            (40., 18.),
            (60., 18.),
            (60., 0.),
            (100., 0.),
            (100., 40.),
            (60., 40.),
            (60., 22.),
            (40., 22.),
            (40., 40.),
            (0., 40.),
            (0., 0.),
        ]);
        let west = LineString::from(vec![(0., 0.), (40., 0.), (40., 40.), (0., 40.), (0., 0.)]);
        let east = LineString::from(vec![
            (60., 0.),
            (100., 0.),
            (100., 40.),
            (60., 40.),
            (60., 0.),
        ]);
        let both = splice(&exact, &[&west, &east], &|_, _| true);
        assert_eq!(both, vec![exact.clone()]);
        let apart = splice(&exact, &[&west, &east], &|_, _| false);
        assert_eq!(apart.len(), 2);
        for (ring, x) in apart.iter().zip([(0.0, 40.0), (60.0, 100.0)]) {
            assert!(ring.is_closed());
            assert!(ring.0.iter().all(|p| p.x >= x.0 && p.x <= x.1), "{ring:?}");
        }
    }
}
