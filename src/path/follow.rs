//! Driving along a line with corners (a headland pass, a connection along the headland): the
//! corners rounded at the vehicle's limits.
//!
//! Each corner of the polyline is rounded by the vehicle's fillet (an arc of the turning
//! radius, or a continuous-curvature turn), which starts a tangent length before the corner and
//! ends as far after it. Where consecutive roundings do not fit on the edge between them (the
//! polygonal arcs of a rounded headland corner: many short edges turning a little each), the
//! edges between are dropped and the corner of the edges either side is rounded as one: the
//! path stays within millimetres of an arc drawn at the turning radius, and cuts arcs drawn
//! tighter than the machine turns. A corner too sharp to round within the edges either side (a
//! cusp of a headland pass where a neck was cut, a spur onto a pass at right angles) gets a
//! manoeuvre instead: the vehicle's cheapest turn from the end of one edge to the start of the
//! next (a loop, or a three-point turn where it may reverse). [`follow_in`] reports those
//! manoeuvres, so that the path drives them as turns with the implement lifted, and chooses
//! each to stay inside the field where one of the machine's turns does. A rounding or bend that
//! would put the implement out of the field (round a concave corner tighter than the turning
//! radius) is reported too, as a manoeuvre of form `lifted`.
//!
//! A machine whose passes are exact ([`Vehicle::exact_passes`]: one that reverses, or any with
//! headland corners `manoeuvre`) works into a sharp corner where rounding it would leave crop:
//! on past the corner until the implement's bar meets the next side, a manoeuvre with the
//! implement lifted, and off along the next edge from as far before the corner, so that the two
//! strips cover the corner between them.
//!
//! ```
//! use furrow::path::curve;
//! use furrow::path::follow::follow;
//! use furrow::path::turn::Vehicle;
//! use geo::coord;
//!
//! let v = Vehicle { turn_radius: 5.0, ..Vehicle::default() };
//! // A square corner with 50 m edges: a quarter circle of 5 m replaces the corner.
//! let pts = [coord! { x: 0.0, y: 0.0 }, coord! { x: 50.0, y: 0.0 }, coord! { x: 50.0, y: 50.0 }];
//! let path = follow(&pts, &v);
//! let expected = 100.0 - 2.0 * 5.0 + 5.0 * std::f64::consts::FRAC_PI_2;
//! assert!((curve::length(&path) - expected).abs() < 1e-9);
//! let end = curve::end(&path).ok_or("no path")?;
//! assert!((end.x - 50.0).abs() < 1e-9 && (end.y - 50.0).abs() < 1e-9);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use super::curve::{wrap, Gear, Pose, Segment};
use super::turn::{Area, Turn, TurnForm, Vehicle};
use crate::geometry::PlanarHypot;
use crate::headland::HeadlandCorners;
use geo::Coord;
use std::ops::Range;

/// Most length of edges (in turning radii) a rounding may leave out between two others.
const MAX_SKIPPED_RADII: f64 = 3.0;

/// Points closer than this (metres) are one.
const SAME_POINT_M: f64 = 1e-6;

/// A manoeuvre at a corner too sharp to round: which pieces of the followed path it is, its
/// form, and whether it stays inside the area it was chosen in (true when none was given).
#[derive(Debug, Clone, PartialEq)]
pub struct Manoeuvre {
    /// Its pieces, as positions in the path.
    pub pieces: Range<usize>,
    /// Its form.
    pub form: TurnForm,
    /// Whether it stays inside the area.
    pub inside: bool,
}

/// The path along `points` at the vehicle's limits (see the module documentation): it starts at
/// the first point facing along the first edge and ends at the last point facing along the last
/// edge. Empty for fewer than two distinct points.
pub fn follow(points: &[Coord], v: &Vehicle) -> Vec<Segment> {
    follow_in(points, v, None).0
}

/// [`follow`], with the manoeuvres at corners too sharp to round: each the cheapest that stays in
/// `area` where one does (else the cheapest, `inside: false`), reported in driving order.
///
/// ```
/// use furrow::path::follow::follow_in;
/// use furrow::path::turn::{Area, Vehicle};
/// use geo::{coord, polygon};
///
/// let v = Vehicle { turn_radius: 8.0, reverse: true, ..Vehicle::default() };
/// // Up a strip 12 m wide and back: at its dead end the machine, which may reverse, works into
/// // both corners, backing round onto the next side at each, inside the strip.
/// let strip = polygon![(x: -10., y: -6.), (x: 100., y: -6.), (x: 100., y: 6.), (x: -10., y: 6.)];
/// let line = [coord! { x: 0., y: -3. }, coord! { x: 90., y: -3. }, coord! { x: 90., y: 3. },
///     coord! { x: 0., y: 3. }];
/// let (path, manoeuvres) = follow_in(&line, &v, Some(&Area::new(&strip, &[])));
/// assert_eq!(manoeuvres.len(), 2);
/// for m in &manoeuvres {
///     assert!(m.inside);
///     assert!(path[m.pieces.clone()].iter().any(|s| s.gear == furrow::path::curve::Gear::Reverse));
/// }
/// ```
pub fn follow_in(
    points: &[Coord],
    v: &Vehicle,
    area: Option<&Area>,
) -> (Vec<Segment>, Vec<Manoeuvre>) {
    let mut pts: Vec<Coord> = Vec::with_capacity(points.len());
    for &p in points {
        if !(p.x.is_finite() && p.y.is_finite()) {
            continue;
        }
        if pts
            .last()
            .is_none_or(|q: &Coord| (p.x - q.x).planar_hypot(p.y - q.y) > SAME_POINT_M)
        {
            pts.push(p);
        }
    }
    let mut manoeuvres: Vec<Manoeuvre> = Vec::new();
    if pts.len() < 2 {
        return (Vec::new(), manoeuvres);
    }
    let edges: Vec<Edge> = pts.windows(2).map(|w| Edge::new(w[0], w[1])).collect();
    let max_skip = MAX_SKIPPED_RADII * v.turn_radius;
    let mut out: Vec<Segment> = Vec::with_capacity(edges.len());
    // The edge being driven and how far along it the machine already is.
    let mut a = 0;
    let mut a_from = 0.0;
    let mut position = Pose::new(pts[0].x, pts[0].y, edges[0].heading);
    let mut j = 1;
    while j < edges.len() {
        let mut placed = false;
        let mut skipped = 0.0;
        // The turn from edge a to edge k, summed edge by edge (so that a run turning more
        // than half round is not taken for one turning the other way).
        let mut deflection = 0.0;
        let mut k = j;
        while k < edges.len() {
            if k > j {
                skipped += edges[k - 1].length;
                if skipped > max_skip {
                    break;
                }
            }
            deflection += wrap(edges[k].heading - edges[k - 1].heading);
            if deflection.abs() >= std::f64::consts::PI - 1e-6 {
                break;
            }
            let Some((s, t)) = edges[a].meet(&edges[k]) else {
                // Parallel: with nothing between them, one edge continues the other.
                if deflection.abs() < 1e-9 && k == j {
                    push_line(&mut out, &mut position, edges[a].length - a_from);
                    a = k;
                    a_from = edges[k].along(Coord {
                        x: position.x,
                        y: position.y,
                    });
                    j = k + 1;
                    placed = true;
                }
                break;
            };
            // A corner drawn as one vertex, or as a few within half a width of each other
            // (a chamfer the offset leaves), worked into as one: where the lines of the edges
            // either side meet within half a width of their ends.
            let near = v.width / 2.0;
            let corner =
                if skipped <= near && s >= a_from && s <= edges[a].length + near && t >= -near {
                    into_corner(&edges[a], s, &edges[k], t, deflection, v, area)
                } else {
                    None
                };
            if let Some((run, turn)) = corner {
                push_line(&mut out, &mut position, s + run - a_from);
                manoeuvres.push(Manoeuvre {
                    pieces: out.len()..out.len() + turn.segments.len(),
                    form: turn.form,
                    inside: turn.inside,
                });
                out.extend(turn.segments);
                let at = edges[k].from + edges[k].dir * (t - run);
                position = Pose::new(at.x, at.y, edges[k].heading);
                a = k;
                a_from = t - run;
                j = k + 1;
                placed = true;
                break;
            }
            let tangent = v.tangent_length(deflection);
            if !tangent.is_finite() {
                break;
            }
            let fits_before = s - tangent >= a_from - 1e-9;
            // Room on edge k for this rounding and the next corner's.
            let next = if k + 1 < edges.len() {
                v.tangent_length(wrap(edges[k + 1].heading - edges[k].heading))
                    .min(edges[k].length)
            } else {
                0.0
            };
            let fits_after = t + tangent <= edges[k].length - next + 1e-9;
            if fits_before && fits_after {
                push_line(&mut out, &mut position, s - tangent - a_from);
                let fillet = v.fillet(position, deflection);
                if !clear_for_work(&fillet, v, area) {
                    // Worked, the implement would reach out of the field: lifted over it (and
                    // where the machine itself would leave the field or run into an obstacle,
                    // said so).
                    manoeuvres.push(Manoeuvre {
                        pieces: out.len()..out.len() + fillet.len(),
                        form: TurnForm::Lifted,
                        inside: area.is_none_or(|a| a.contains(&fillet)),
                    });
                }
                for f in fillet {
                    position = f.end();
                    out.push(f);
                }
                // A machine that turns on the spot pivots at the corner.
                position.heading = edges[k].heading;
                a = k;
                a_from = t + tangent;
                j = k + 1;
                placed = true;
                break;
            }
            if !fits_before {
                break;
            }
            k += 1;
        }
        if !placed {
            let left: f64 = edges[j..].iter().map(|e| e.length).sum();
            if left <= max_skip && edges[j..].iter().all(|e| e.length < v.turn_radius) {
                // The line ends in short edges that cannot be rounded (the last chords of an
                // arc tighter than the machine turns): it stops at the end of this edge, at
                // most a few turning radii short, rather than looping to reach its very end.
                break;
            }
            // A corner too sharp to round from here: drive to the end of this edge and turn
            // onto the first edge ahead long enough to settle on (short edges in between, the
            // chords of an arc tighter than the machine turns, are cut), a little way along it.
            push_line(&mut out, &mut position, edges[a].length - a_from);
            let mut m = j;
            let mut skipped = 0.0;
            while m + 1 < edges.len()
                && edges[m].length < v.turn_radius
                && skipped + edges[m].length <= max_skip
            {
                skipped += edges[m].length;
                m += 1;
            }
            // Where along it: a bend the machine drives forward with the implement down where
            // one joins (a jog of the line: the join that drives least, the stretch it replaces
            // counted off), else a manoeuvre with the implement lifted (the one inside the area,
            // where one is, that costs least, the stretch it skips counted as driven again: its
            // crop is left standing).
            let room = if m + 1 < edges.len() {
                edges[m].length / 2.0
            } else {
                edges[m].length
            };
            let deflection = wrap(edges[m].heading - edges[a].heading).abs();
            // (rank: 0 a bend, 1 a manoeuvre inside, 2 one outside; cost; into; the join)
            let mut best: Option<(u8, f64, f64, Turn)> = None;
            for k in [0.0, 0.5, 1.0, 2.0, 3.0] {
                let into = (k * v.turn_radius).min(room);
                let at = edges[m].from + edges[m].dir * into;
                let onto = Pose::new(at.x, at.y, edges[m].heading);
                let turn = match area {
                    Some(area) => v.turn(position, onto, area),
                    None => v.shortest(position, onto),
                };
                let (rank, cost) =
                    if is_bend(&turn, deflection) && clear_for_work(&turn.segments, v, area) {
                        (0, turn.cost() - into)
                    } else {
                        (if turn.inside { 1 } else { 2 }, turn.cost() + into)
                    };
                if best
                    .as_ref()
                    .is_none_or(|b| rank < b.0 || (rank == b.0 && cost < b.1 - 1e-9))
                {
                    best = Some((rank, cost, into, turn));
                }
            }
            let first = out.len();
            let mut into = 0.0;
            if let Some((rank, _, at, turn)) = best {
                into = at;
                out.extend(turn.segments);
                if rank > 0 {
                    manoeuvres.push(Manoeuvre {
                        pieces: first..out.len(),
                        form: turn.form,
                        inside: turn.inside,
                    });
                }
            }
            if let Some(last) = out.last() {
                position = last.end();
            }
            position.heading = edges[m].heading;
            a = m;
            a_from = into;
            j = m + 1;
        }
    }
    push_line(&mut out, &mut position, edges[a].length - a_from);
    (out, manoeuvres)
}

/// The path all the way round a closed ring (its first point repeated last) at the vehicle's
/// limits, from its first point. [`follow`] ends a line where its last corners have no room to
/// round, up to a few turning radii short; round a ring the machine goes on onto the ring's
/// beginning, so the ring is followed with a stretch of its beginning again and the path cut
/// where it is back on the first edge, level with the start or past it (past the start corner's
/// rounding). A line that is not closed, or a ring whose path never comes back onto its first
/// edge (a manoeuvre at the start corner settles further on), is [`follow`]ed as it is.
///
/// ```
/// use furrow::path::curve;
/// use furrow::path::follow::{follow, follow_round};
/// use furrow::path::turn::Vehicle;
/// use geo::coord;
///
/// let v = Vehicle { turn_radius: 8.0, ..Vehicle::default() };
/// // A 60 x 40 m rectangle whose south-west corner is a quarter circle of 3 m (drawn as
/// // chords, tighter than the machine turns), started where that corner ends.
/// let mut ring = vec![coord! { x: 3., y: 0. }, coord! { x: 60., y: 0. }, coord! { x: 60., y: 40. },
///     coord! { x: 0., y: 40. }];
/// for i in 0..=8 {
///     let t = std::f64::consts::PI * (1.0 + i as f64 / 16.0);
///     ring.push(coord! { x: 3. + 3. * t.cos(), y: 3. + 3. * t.sin() });
/// }
/// // Followed as a line, the path stops where the chords begin, 3 m up the west side.
/// let end = curve::end(&follow(&ring, &v)).ok_or("no path")?;
/// assert!(end.x.abs() < 1e-6 && (end.y - 3.0).abs() < 1e-6);
/// // Round the ring, it rounds that corner at 8 m and stops back on the south side.
/// let end = curve::end(&follow_round(&ring, &v)).ok_or("no path")?;
/// assert!(end.y.abs() < 1e-6 && end.x > 3.0 && end.x < 9.0, "{end:?}");
/// assert!(end.heading.abs() < 1e-6);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn follow_round(ring: &[Coord], v: &Vehicle) -> Vec<Segment> {
    follow_round_in(ring, v, None).0
}

/// [`follow_round`], with its manoeuvres chosen and reported as [`follow_in`] does.
pub fn follow_round_in(
    ring: &[Coord],
    v: &Vehicle,
    area: Option<&Area>,
) -> (Vec<Segment>, Vec<Manoeuvre>) {
    let (Some(&first), Some(&last)) = (ring.first(), ring.last()) else {
        return (Vec::new(), Vec::new());
    };
    let closed =
        ring.len() >= 4 && (first.x - last.x).planar_hypot(first.y - last.y) <= SAME_POINT_M;
    let Some(second) = ring
        .iter()
        .copied()
        .find(|p| (p.x - first.x).planar_hypot(p.y - first.y) > SAME_POINT_M)
    else {
        return (Vec::new(), Vec::new());
    };
    if !closed {
        return follow_in(ring, v, area);
    }
    let edge = Edge::new(first, second);
    let ring_length: f64 = ring
        .windows(2)
        .map(|w| (w[1].x - w[0].x).planar_hypot(w[1].y - w[0].y))
        .sum();
    // The ring and its beginning again, as far as a rounding or a manoeuvre may reach.
    let extra = (MAX_SKIPPED_RADII + 3.0) * v.turn_radius + edge.length;
    let mut again = 0.0;
    let mut extended: Vec<Coord> = ring.to_vec();
    for w in ring.windows(2) {
        if again >= extra.min(ring_length) {
            break;
        }
        extended.push(w[1]);
        again += (w[1].x - w[0].x).planar_hypot(w[1].y - w[0].y);
    }
    let (path, mut manoeuvres) = follow_in(&extended, v, area);
    match back_on_first_edge(&path, &edge, ring_length / 2.0, v.turn_radius) {
        Some(cut) => {
            let path = cut_at(path, cut);
            // A manoeuvre the cut ends within is cut with it; one after it is dropped.
            manoeuvres.retain_mut(|m| {
                m.pieces.end = m.pieces.end.min(path.len());
                m.pieces.start < m.pieces.end
            });
            (path, manoeuvres)
        }
        None => follow_in(ring, v, area),
    }
}

/// Distance along `path` (past `from`) where it is first on the line of `edge` (within a
/// millimetre), heading along it, level with the edge's start or past it, and straight (a
/// clothoid easing onto the edge is followed to its end).
fn back_on_first_edge(path: &[Segment], edge: &Edge, from: f64, radius: f64) -> Option<f64> {
    // At most about 100,000 samples, however long the ring and small the radius.
    let step = (radius / 20.0).clamp(0.01, 0.5).max(from / 50_000.0);
    let on = |p: &Pose| {
        let at = Coord { x: p.x, y: p.y };
        let along = edge.along(at);
        let d = at - edge.from;
        let off = (d.x * edge.dir.y - d.y * edge.dir.x).abs();
        along >= -1e-6 && off <= 1e-3 && wrap(p.heading - edge.heading).abs() < 1e-3
    };
    let mut done = 0.0;
    for seg in path {
        if done + seg.length >= from {
            let poses = seg.poses();
            let mut s = (from - done).max(0.0);
            let mut before = s;
            while s <= seg.length {
                if on(&poses.at(s)) {
                    // Where, since the last sample that was not, it comes onto the edge.
                    let (mut lo, mut hi) = (before, s);
                    for _ in 0..40 {
                        let mid = (lo + hi) / 2.0;
                        if on(&poses.at(mid)) {
                            hi = mid;
                        } else {
                            lo = mid;
                        }
                    }
                    // Within a rounding's easing out (a clothoid coming onto the edge within
                    // the tolerances): at its end, where it is straight again.
                    if seg.curvature_at(hi).abs() > 1e-9 {
                        return Some(done + seg.length);
                    }
                    return Some(done + hi);
                }
                before = s;
                s += step;
            }
            if on(&seg.end()) {
                return Some(done + seg.length);
            }
        }
        done += seg.length;
    }
    None
}

/// Whether a join is a bend driven on with the implement down: inside the area, forward
/// throughout, making a `deflection` of at most three eighths of a turn (a corner cut), and
/// turning in all (either way) at most a sixth of a turn more than that. A sharper join (a dead
/// end, a cusp) is a manoeuvre.
fn is_bend(turn: &Turn, deflection: f64) -> bool {
    if deflection > 0.75 * std::f64::consts::PI + 1e-9 {
        return false;
    }
    let mut turned = 0.0;
    for s in &turn.segments {
        if s.gear != Gear::Forward {
            return false;
        }
        turned += (s.curvature.abs() + s.sharpness.abs() * s.length / 2.0) * s.length;
    }
    turn.inside && turned <= deflection + std::f64::consts::FRAC_PI_3 + 1e-9
}

/// Least crop (in working widths squared) the rounding of a corner must leave for a machine
/// whose passes are exact to work into the corner instead.
const CORNER_CROP_WIDTHS2: f64 = 0.25;

/// How a machine whose passes are exact ([`Vehicle::exact_passes`]) works into a sharp corner of
/// a pass (from the edge `from`, `s` along it, onto the edge `onto`, `t` along it) rather than
/// rounding it, where the rounding would leave at least [`CORNER_CROP_WIDTHS2`] of crop: it works
/// on past the corner as far as the implement's bar stays in the field (half a width past a
/// square corner), turns with the implement lifted, and sets off on the next edge as far before
/// the corner. The run past the corner and the turn, the cheapest that stays in `area` (with
/// headland corners `manoeuvre`, the cheapest of all where none does); `None` where none does
/// (`auto`), or where no area is given (a line that is not worked).
fn into_corner(
    from: &Edge,
    s: f64,
    onto: &Edge,
    t: f64,
    deflection: f64,
    v: &Vehicle,
    area: Option<&Area>,
) -> Option<(f64, Turn)> {
    let area = area.filter(|_| v.exact_passes() && !v.pivots())?;
    let half = v.width / 2.0;
    let d = deflection.abs() / 2.0;
    let rim = v.turn_radius + half;
    if rim * rim * (d.tan() - d) < CORNER_CROP_WIDTHS2 * v.width * v.width {
        return None;
    }
    // The bar past the corner reaches the next side's line (for the outermost pass, the field's
    // boundary) at tan(d) half widths, or its tip at an acute corner at cot(d). (Where another
    // side is nearer, the path's lifts take the implement out of work, see [`super::lift`].)
    let run = (half * d.tan().min(1.0 / d.tan()) - 0.01).max(0.0);
    let past = from.from + from.dir * (s + run);
    let before = onto.from + onto.dir * (t - run);
    let turn = v.turn(
        Pose::new(past.x, past.y, from.heading),
        Pose::new(before.x, before.y, onto.heading),
        area,
    );
    (turn.inside || v.corners == HeadlandCorners::Manoeuvre).then_some((run, turn))
}

/// Whether the implement working along `segments` stays in `area` (to a centimetre; true
/// without an area).
fn clear_for_work(segments: &[Segment], v: &Vehicle, area: Option<&Area>) -> bool {
    area.is_none_or(|area| area.keeps_clear(segments, (v.width / 2.0 - 0.01).max(0.0)))
}

/// `path` cut `at` metres from its start.
fn cut_at(path: Vec<Segment>, at: f64) -> Vec<Segment> {
    let mut out = Vec::with_capacity(path.len());
    let mut done = 0.0;
    for mut seg in path {
        if done + seg.length >= at {
            seg.length = (at - done).max(0.0);
            if seg.length > 1e-9 {
                out.push(seg);
            }
            break;
        }
        done += seg.length;
        out.push(seg);
    }
    out
}

/// Drives `length` metres straight on from `position` (nothing if under a micrometre).
fn push_line(out: &mut Vec<Segment>, position: &mut Pose, length: f64) {
    if length > 1e-6 {
        let line = Segment::line(*position, length, Gear::Forward);
        *position = line.end();
        out.push(line);
    }
}

/// An edge of the polyline.
#[derive(Debug, Clone, Copy)]
struct Edge {
    from: Coord,
    dir: Coord,
    length: f64,
    heading: f64,
}

impl Edge {
    fn new(from: Coord, to: Coord) -> Self {
        let d = to - from;
        let length = d.x.planar_hypot(d.y);
        Edge {
            from,
            dir: Coord {
                x: d.x / length,
                y: d.y / length,
            },
            length,
            heading: d.y.atan2(d.x),
        }
    }

    /// How far along the edge's line (from its start) `p` projects.
    fn along(&self, p: Coord) -> f64 {
        (p.x - self.from.x) * self.dir.x + (p.y - self.from.y) * self.dir.y
    }

    /// Where the lines of two edges meet: the distances along each from its start. `None` for
    /// parallel lines.
    fn meet(&self, o: &Edge) -> Option<(f64, f64)> {
        let cross = self.dir.x * o.dir.y - self.dir.y * o.dir.x;
        if cross.abs() < 1e-12 {
            return None;
        }
        let w = o.from - self.from;
        let s = (w.x * o.dir.y - w.y * o.dir.x) / cross;
        let t = (w.x * self.dir.y - w.y * self.dir.x) / cross;
        Some((s, t))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::path::curve;
    use geo::{coord, polygon};
    use std::f64::consts::PI;

    fn check_continuous(path: &[Segment], max_curvature: f64) {
        for w in path.windows(2) {
            let (e, s) = (w[0].end(), w[1].start);
            assert!(e.distance(&s) < 1e-6, "gap {e:?} {s:?}");
            assert!(e.heading_change(&s).abs() < 1e-6, "kink {e:?} {s:?}");
        }
        for s in path {
            assert!(s.max_curvature() <= max_curvature + 1e-9);
        }
    }

    #[test]
    fn a_polygonal_arc_at_the_turning_radius_is_driven_as_one_arc() {
        // A headland corner rounded at 8 m, drawn with chords 3 mm off the arc.
        let r = 8.0;
        let mut pts = vec![coord! { x: -50.0, y: 0.0 }];
        let n = 60;
        for i in 0..=n {
            let a = -PI / 2.0 + (PI / 2.0) * i as f64 / n as f64;
            pts.push(coord! { x: r * a.cos(), y: r + r * a.sin() });
        }
        pts.push(coord! { x: r, y: 60.0 });
        let v = Vehicle {
            turn_radius: r,
            ..Vehicle::default()
        };
        let path = follow(&pts, &v);
        check_continuous(&path, 1.0 / r);
        let length = curve::length(&path);
        let expect = 50.0 + r * PI / 2.0 + (60.0 - r);
        assert!((length - expect).abs() < 0.01, "{length} {expect}");
        // No manoeuvre: every piece forward, the turn one arc or a few.
        assert!(path.iter().all(|s| s.gear == Gear::Forward));
        let turned: f64 = path.iter().map(|s| s.curvature * s.length).sum();
        assert!((turned - PI / 2.0).abs() < 1e-6);
    }

    #[test]
    fn a_tight_corner_is_cut_and_a_cusp_gets_a_manoeuvre() {
        let v = Vehicle {
            turn_radius: 8.0,
            ..Vehicle::default()
        };
        // An arc of 3 m radius (tighter than the machine): cut at 8 m.
        let mut pts = vec![coord! { x: -40.0, y: 0.0 }];
        for i in 0..=20 {
            let a = -PI / 2.0 + (PI / 2.0) * i as f64 / 20.0;
            pts.push(coord! { x: 3.0 * a.cos(), y: 3.0 + 3.0 * a.sin() });
        }
        pts.push(coord! { x: 3.0, y: 40.0 });
        let path = follow(&pts, &v);
        check_continuous(&path, 1.0 / 8.0);
        let e = curve::end(&path).unwrap();
        assert!((e.x - 3.0).abs() < 1e-6 && (e.y - 40.0).abs() < 1e-6);
        // A cusp: out and straight back at 10 degrees: a manoeuvre, and still continuous.
        let pts = [
            coord! { x: 0.0, y: 0.0 },
            coord! { x: 30.0, y: 0.0 },
            coord! { x: 0.0, y: 30.0 * 10f64.to_radians().tan() },
        ];
        let path = follow(&pts, &v);
        check_continuous(&path, 1.0 / 8.0);
        let e = curve::end(&path).unwrap();
        assert!(
            e.distance(&Pose::new(pts[2].x, pts[2].y, 0.0)) < 1e-6,
            "{e:?}"
        );
    }

    #[test]
    fn a_jog_is_a_bend_worked_on_and_a_dead_end_a_manoeuvre() {
        let v = Vehicle {
            turn_radius: 8.0,
            ..Vehicle::default()
        };
        // A line that steps 1.5 m aside over a metre (a notch of an outline): too tight to round
        // corner by corner, it is an S-bend driven forward, not a manoeuvre.
        let jog = [
            coord! { x: 0.0, y: 0.0 },
            coord! { x: 50.0, y: 0.0 },
            coord! { x: 51.0, y: 1.5 },
            coord! { x: 100.0, y: 1.5 },
        ];
        let (path, manoeuvres) = follow_in(&jog, &v, None);
        check_continuous(&path, 1.0 / 8.0);
        assert!(manoeuvres.is_empty(), "{manoeuvres:?}");
        assert!(path.iter().all(|s| s.gear == Gear::Forward));
        // Up and back 6 m aside: a dead end, turned at with a manoeuvre (a loop, forward only)
        // that starts where the line turns back and ends on the way back.
        let dead_end = [
            coord! { x: 0.0, y: 0.0 },
            coord! { x: 60.0, y: 0.0 },
            coord! { x: 60.0, y: 6.0 },
            coord! { x: 0.0, y: 6.0 },
        ];
        let (path, manoeuvres) = follow_in(&dead_end, &v, None);
        check_continuous(&path, 1.0 / 8.0);
        assert_eq!(manoeuvres.len(), 1);
        let m = &manoeuvres[0];
        let start = path[m.pieces.start].start;
        assert!(
            (start.x - 60.0).abs() < 1e-6 && start.y.abs() < 1e-6,
            "{start:?}"
        );
        let end = path[m.pieces.end - 1].end();
        assert!(
            (end.y - 6.0).abs() < 1e-6 && end.x <= 60.0 + 1e-6,
            "{end:?}"
        );
        let turned: f64 = path[m.pieces.clone()]
            .iter()
            .map(|s| s.curvature.abs() * s.length)
            .sum();
        assert!(turned > PI, "a loop turns more than half round: {turned}");
    }

    #[test]
    fn a_rounding_the_implement_would_work_out_of_the_field_is_lifted() {
        // Round the inside of an L's concave corner at 8 m, a 6 m implement on a pass 3 m from
        // it would reach 2 m over the corner's vertex: that bend is driven lifted.
        let l = polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 100., y: 100.), (x: 50., y: 100.),
            (x: 50., y: 50.), (x: 0., y: 50.)];
        let area = Area::new(&l, &[]);
        let v = Vehicle {
            width: 6.0,
            turn_radius: 8.0,
            ..Vehicle::default()
        };
        let pass = [
            coord! { x: 10.0, y: 47.0 },
            coord! { x: 53.0, y: 47.0 },
            coord! { x: 53.0, y: 90.0 },
        ];
        let (path, manoeuvres) = follow_in(&pass, &v, Some(&area));
        check_continuous(&path, 1.0 / 8.0);
        assert_eq!(manoeuvres.len(), 1);
        assert_eq!(manoeuvres[0].form, TurnForm::Lifted);
        assert!(manoeuvres[0].inside);
        // A pass 1 m from the corner: the rounding takes the machine itself 1.3 m over the
        // corner's vertex, out of the field, and says so.
        let pass = [
            coord! { x: 10.0, y: 49.0 },
            coord! { x: 51.0, y: 49.0 },
            coord! { x: 51.0, y: 90.0 },
        ];
        let (_, out) = follow_in(&pass, &v, Some(&area));
        assert_eq!(out.len(), 1);
        assert_eq!(out[0].form, TurnForm::Lifted);
        assert!(!out[0].inside);
        // A convex corner is rounded inwards, away from the field's sides: worked.
        let square =
            polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 100., y: 100.), (x: 0., y: 100.)];
        let pass = [
            coord! { x: 20.0, y: 3.0 },
            coord! { x: 97.0, y: 3.0 },
            coord! { x: 97.0, y: 80.0 },
        ];
        let (_, none) = follow_in(&pass, &v, Some(&Area::new(&square, &[])));
        assert!(none.is_empty(), "{none:?}");
    }

    #[test]
    fn a_ring_round_continuous_curvature_corners_ends_straight() {
        // Started at a corner, the ring's path ends past that corner's rounding: where it is
        // straight on the first edge again, not within the clothoid easing onto it (whose end
        // comes within the tolerances of the edge's line and heading before it is straight).
        let v = Vehicle {
            turn_radius: 2.1,
            curvature_rate: Some(0.1),
            ..Vehicle::default()
        };
        let ring = [
            coord! { x: 0.0, y: 0.0 },
            coord! { x: 100.0, y: 0.0 },
            coord! { x: 100.0, y: 100.0 },
            coord! { x: 0.0, y: 100.0 },
            coord! { x: 0.0, y: 0.0 },
        ];
        let path = follow_round(&ring, &v);
        let last = path.last().expect("a path");
        assert!(last.curvature_at(last.length).abs() < 1e-9, "{last:?}");
        let end = last.end();
        assert!(end.y.abs() < 1e-6 && end.heading.abs() < 1e-9, "{end:?}");
    }

    #[test]
    fn continuous_curvature_corners_keep_curvature_and_its_rate() {
        let v = Vehicle {
            turn_radius: 6.0,
            curvature_rate: Some(0.1),
            ..Vehicle::default()
        };
        let pts = [
            coord! { x: 0.0, y: 0.0 },
            coord! { x: 60.0, y: 0.0 },
            coord! { x: 60.0, y: 60.0 },
            coord! { x: 0.0, y: 70.0 },
        ];
        let path = follow(&pts, &v);
        check_continuous(&path, 1.0 / 6.0);
        for w in path.windows(2) {
            let k0 = w[0].curvature_at(w[0].length);
            assert!((k0 - w[1].curvature).abs() < 1e-9, "curvature jumps");
        }
        assert!(path.iter().all(|s| s.sharpness.abs() <= 0.1 + 1e-12));
    }

    #[test]
    fn a_machine_that_reverses_works_into_square_corners_and_one_that_does_not_rounds_them() {
        // A pass 3 m inside a 100 x 60 m field, started along its south side.
        let field = polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 100., y: 60.), (x: 0., y: 60.)];
        let area = Area::new(&field, &[]);
        let ring = [
            coord! { x: 40., y: 3. },
            coord! { x: 97., y: 3. },
            coord! { x: 97., y: 57. },
            coord! { x: 3., y: 57. },
            coord! { x: 3., y: 3. },
            coord! { x: 40., y: 3. },
        ];
        let drill = Vehicle {
            width: 6.0,
            turn_radius: 8.0,
            ..Vehicle::default()
        };
        let (_, rounded) = follow_round_in(&ring, &drill, Some(&area));
        assert!(rounded.is_empty(), "{rounded:?}");
        let reversing = Vehicle {
            reverse: true,
            ..drill
        };
        let (path, corners) = follow_round_in(&ring, &reversing, Some(&area));
        assert_eq!(corners.len(), 4, "{corners:?}");
        for m in &corners {
            assert!(m.inside);
            let turn = &path[m.pieces.clone()];
            assert!(turn.iter().any(|s| s.gear == Gear::Reverse), "{turn:?}");
            // Worked on until the bar is a centimetre from the next side: half a width past
            // the corner of the pass.
            let at = path[m.pieces.start - 1].end();
            let to_side = (at.x.min(100.0 - at.x)).min(at.y.min(60.0 - at.y));
            assert!((to_side - 0.01).abs() < 1e-6, "{at:?}");
        }
        // All the way round: back on the south side, level with the start or past it.
        let end = path.last().map(Segment::end).expect("a path");
        assert!(
            (end.y - 3.0).abs() < 1e-6 && end.x >= 40.0 - 1e-6,
            "{end:?}"
        );
    }
}
