//! Fill passes along the outline of what is left standing: the narrow arms, necks and bent
//! strips that no straight piece works, driven as farmers drive them, round their outline one
//! half width in, up one side of an arm and back down the other.
//!
//! For each part left standing (see [`super::fill`]), the lanes where a strip's centre line may
//! run and still reach the part (the field inset by half a width, within half a width of the
//! part's core) are driven along their outline: the stretches of it whose strip reaches a
//! quarter width or more into the part's core are the passes; the rest of the outline runs over
//! crop already worked and is left out. A lane's outline that runs over the part all the way
//! round is a closed pass. A pass is laid only where the route can get to one of its ends
//! without crossing crop, and where it is at least as long as the plan's shortest swath.
//!
//! The path drives a pass as it drives a headland pass: its corners rounded at the turning
//! radius, and where its outline turns back on itself (the dead end of an arm narrower than
//! the machine turns in) a manoeuvre, a three-point turn where the machine may reverse.

use super::{lanes, Centres, FillSettings, Lanes, MIN_PART_WIDTHS};
use crate::coverage::Uncovered;
use crate::geometry::PlanarHypot;
use crate::headland::offset::outset;
use geo::{Coord, Intersects, LineString, MultiPolygon};

/// A fill pass: its centre line and whether it is a closed ring.
#[derive(Debug, Clone, PartialEq)]
pub struct FillPass {
    /// The centre line; a closed pass repeats its first point at the end.
    pub line: LineString,
    /// Whether the pass runs all the way round.
    pub closed: bool,
}

/// The passes along the outline of the parts of `uncovered` (see the module documentation).
/// `centres` is where a strip's centre line may run: the field less its obstacles, inset by
/// half a width.
///
/// ```
/// use furrow::coverage::measure;
/// use furrow::fill::{along::passes_along, FillSettings};
/// use furrow::headland::offset::inset;
/// use geo::{coord, polygon, MultiPolygon};
///
/// // An L of 6 m swaths along the south edge of a 100 x 100 m field, and a bent arm
/// // 12 m wide going north along the west edge that no straight 6 m swath set works.
/// let field = polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 100., y: 12.), (x: 12., y: 12.),
///     (x: 12., y: 100.), (x: 0., y: 100.)];
/// let worked = vec![
///     vec![coord! { x: 0.0, y: 3.0 }, coord! { x: 100.0, y: 3.0 }],
///     vec![coord! { x: 0.0, y: 9.0 }, coord! { x: 100.0, y: 9.0 }],
/// ];
/// let left = measure(&field, &[], &worked, 6.0).uncovered;
/// let centres = inset(&MultiPolygon::new(vec![field.clone()]), 3.0);
/// let settings = FillSettings {
///     width: 6.0,
///     bearing: std::f64::consts::FRAC_PI_2,
///     forbidden: &[],
///     regions: &[],
///     min_length: 6.0,
///     reachable: &|_| true,
///     slivers: &|_| false,
/// };
/// let passes = passes_along(&left, &centres, &settings);
/// // One pass up the arm and back down it.
/// assert_eq!(passes.len(), 1);
/// assert!(!passes[0].closed);
/// let mut all = worked.clone();
/// all.push(passes[0].line.0.clone());
/// let after = measure(&field, &[], &all, 6.0);
/// assert!(after.uncovered_area_m2 < 30.0, "{}", after.uncovered_area_m2);
/// ```
pub fn passes_along(
    uncovered: &[Uncovered],
    centres: &MultiPolygon,
    settings: &FillSettings,
) -> Vec<FillPass> {
    let w = settings.width;
    if centres.0.is_empty() || w.is_nan() || w <= 0.0 {
        return Vec::new();
    }
    let shortest = settings.min_length.max(w);
    let centres = Centres::new(centres);
    let mut out = Vec::new();
    for u in uncovered
        .iter()
        .filter(|u| u.reachable_m2 >= MIN_PART_WIDTHS * w * w)
    {
        let Some(Lanes { core, lanes, .. }) = lanes(&u.polygon, &centres, w, settings.slivers)
        else {
            continue;
        };
        let over = outset(&core, w / 4.0);
        let rings = lanes
            .0
            .iter()
            .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()));
        let step = sample_step(w);
        for ring in rings {
            let points = densified(ring, step);
            for stretch in stretches_over(&points, &over) {
                let pass = match stretch {
                    Stretch::Round => closed(&points),
                    Stretch::Run { from, to } => {
                        let (from, to) = joined(&points, from, to, step, w, settings.reachable);
                        open_run(&points, from, to)
                    }
                };
                let reached = pass.closed
                    || pass
                        .line
                        .0
                        .first()
                        .is_some_and(|&p| (settings.reachable)(p))
                    || pass.line.0.last().is_some_and(|&p| (settings.reachable)(p));
                if reached && length(&pass.line) >= shortest {
                    out.push(pass);
                }
            }
        }
    }
    out
}

/// How far apart a ring is sampled to find where it runs over a part, metres.
fn sample_step(w: f64) -> f64 {
    (w / 4.0).clamp(0.25, 2.0)
}

/// A stretch of a ring that runs over a part.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Stretch {
    /// The whole ring.
    Round,
    /// From point `from` to point `to` (counted on round the ring: `to` may be past the end).
    Run { from: usize, to: usize },
}

/// The stretches of the closed ring through `points` (without its closing repeat) that lie in
/// `over`.
fn stretches_over(points: &[Coord], over: &MultiPolygon) -> Vec<Stretch> {
    if points.len() < 3 {
        return Vec::new();
    }
    let inside: Vec<bool> = points.iter().map(|p| over.intersects(p)).collect();
    let Some(start) = inside.iter().position(|&i| !i) else {
        return vec![Stretch::Round];
    };
    let n = points.len();
    let mut out = Vec::new();
    let mut from: Option<usize> = None;
    for k in 1..=n {
        let i = start + k;
        match (inside[i % n], from) {
            (true, None) => from = Some(i),
            (false, Some(f)) => {
                if i - 1 > f {
                    out.push(Stretch::Run { from: f, to: i - 1 });
                }
                from = None;
            }
            _ => {}
        }
    }
    out
}

/// How far a pass may run on along its ring over worked crop to where the route gets to it,
/// in working widths.
const JOIN_WIDTHS: f64 = 4.0;

/// The run `from..=to` of the ring through `points`, each end run on along the ring (over
/// crop already worked, up to [`JOIN_WIDTHS`] widths, never round into the run's other end) to
/// the nearest point the route gets to, where the end itself is not such a point.
fn joined(
    points: &[Coord],
    from: usize,
    to: usize,
    step: f64,
    w: f64,
    reachable: &dyn Fn(Coord) -> bool,
) -> (usize, usize) {
    let n = points.len();
    let reach = (JOIN_WIDTHS * w / step).ceil() as usize;
    // The points off the run, which the two ends may take between them.
    let off = n.saturating_sub(to - from + 2);
    let at = |i: usize| points[i % n];
    let back = (0..=reach.min(off))
        .find(|&k| reachable(at(from + n - k)))
        .unwrap_or(0);
    let on = (0..=reach.min(off - back))
        .find(|&k| reachable(at(to + k)))
        .unwrap_or(0);
    (from + n - back, to + n + on)
}

/// The open pass along the ring through `points` from point `from` to `to` (indices taken
/// round the ring).
fn open_run(points: &[Coord], from: usize, to: usize) -> FillPass {
    let n = points.len();
    FillPass {
        line: LineString::new((from..=to).map(|i| points[i % n]).collect()),
        closed: false,
    }
}

/// The closed pass round the ring through `points`.
fn closed(points: &[Coord]) -> FillPass {
    let mut line = points.to_vec();
    if let Some(&first) = line.first() {
        line.push(first);
    }
    FillPass {
        line: LineString::new(line),
        closed: true,
    }
}

/// The ring's points without its closing repeat, with points added so that none is more than
/// `step` from the next.
fn densified(ring: &LineString, step: f64) -> Vec<Coord> {
    let pts = &ring.0;
    let open = match (pts.first(), pts.last()) {
        (Some(a), Some(b)) if a == b && pts.len() > 1 => &pts[..pts.len() - 1],
        _ => &pts[..],
    };
    let mut out = Vec::with_capacity(open.len() * 2);
    for (i, &a) in open.iter().enumerate() {
        let b = open[(i + 1) % open.len()];
        out.push(a);
        let d = (b.x - a.x).planar_hypot(b.y - a.y);
        let parts = (d / step).ceil();
        if parts.is_finite() && parts > 1.0 && parts < 1e6 {
            let k = parts as usize;
            for j in 1..k {
                let t = j as f64 / parts;
                out.push(Coord {
                    x: a.x + (b.x - a.x) * t,
                    y: a.y + (b.y - a.y) * t,
                });
            }
        }
    }
    out
}

fn length(line: &LineString) -> f64 {
    line.0
        .windows(2)
        .map(|s| (s[1].x - s[0].x).planar_hypot(s[1].y - s[0].y))
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::measure;
    use crate::headland::offset::inset;
    use geo::{coord, polygon, Coord};

    fn settings<'a>(reachable: &'a dyn Fn(Coord) -> bool) -> FillSettings<'a> {
        FillSettings {
            width: 6.0,
            bearing: 0.0,
            forbidden: &[],
            regions: &[],
            min_length: 6.0,
            reachable,
            slivers: &|_| false,
        }
    }

    #[test]
    fn a_ring_all_over_the_part_is_one_closed_pass() {
        let square = polygon![(x: 0., y: 0.), (x: 10., y: 0.), (x: 10., y: 10.), (x: 0., y: 10.)];
        let over = MultiPolygon::new(vec![square]);
        let ring = LineString::from(vec![(2., 2.), (8., 2.), (8., 8.), (2., 8.), (2., 2.)]);
        let points = densified(&ring, 1.0);
        assert_eq!(stretches_over(&points, &over), vec![Stretch::Round]);
        assert!((length(&closed(&points).line) - 24.0).abs() < 1e-9);
    }

    #[test]
    fn the_stretch_over_worked_crop_is_left_out() {
        // A ring half in the part: the half outside is dropped.
        let half = polygon![(x: 0., y: 0.), (x: 5., y: 0.), (x: 5., y: 10.), (x: 0., y: 10.)];
        let over = MultiPolygon::new(vec![half]);
        let ring = LineString::from(vec![(2., 2.), (8., 2.), (8., 8.), (2., 8.), (2., 2.)]);
        let points = densified(&ring, 1.0);
        let stretches = stretches_over(&points, &over);
        assert_eq!(stretches.len(), 1);
        let Stretch::Run { from, to } = stretches[0] else {
            panic!("{stretches:?}");
        };
        let pass = open_run(&points, from, to);
        assert!(pass.line.0.iter().all(|p| p.x <= 5.0));
        assert!(length(&pass.line) > 6.0 + 2.0 * 2.0);
        // Run on to where the route gets to it: the east side's south end, over worked crop.
        let east = |p: Coord| p.x > 7.9 && p.y < 3.5;
        let (from, to) = joined(&points, from, to, 1.0, 6.0, &east);
        let pass = open_run(&points, from, to);
        assert!(east(pass.line.0[0]) || east(pass.line.0[pass.line.0.len() - 1]));
    }

    #[test]
    fn an_unreachable_part_gets_no_pass() {
        let field = polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 100., y: 12.), (x: 12., y: 12.),
            (x: 12., y: 100.), (x: 0., y: 100.)];
        let worked = vec![
            vec![coord! { x: 0.0, y: 3.0 }, coord! { x: 100.0, y: 3.0 }],
            vec![coord! { x: 0.0, y: 9.0 }, coord! { x: 100.0, y: 9.0 }],
        ];
        let left = measure(&field, &[], &worked, 6.0).uncovered;
        let centres = inset(&MultiPolygon::new(vec![field]), 3.0);
        let nowhere = |_: Coord| false;
        assert!(passes_along(&left, &centres, &settings(&nowhere)).is_empty());
        // Reached from the worked strip only: the pass ends there.
        let south = |p: Coord| p.y < 20.0;
        let passes = passes_along(&left, &centres, &settings(&south));
        assert_eq!(passes.len(), 1);
        let line = &passes[0].line.0;
        assert!(south(line[0]) || south(line[line.len() - 1]));
        assert!(line.iter().any(|p| p.y > 90.0), "up to the arm's end");
    }
}
