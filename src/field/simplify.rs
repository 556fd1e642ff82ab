//! Simplifying dense outlines: a boundary recorded by a GNSS receiver driving round the field has
//! a vertex every metre or so, many of them noise, and every vertex costs planning time. Dense
//! outlines are thinned to about one vertex per two working widths of outline, within the least
//! tolerance that reaches it: from 2 cm up to a sixth of the working width, at most 1 m (as in
//! the field trials of Zhou et al. 2014, section 3). A clean outline loses next to nothing; a
//! noisy one loses up to the noise.
//!
//! The simplification is one-sided ([`crate::geometry::sleeve`]): the field's boundary only
//! moves inwards and an obstacle's or prohibited region's outline only outwards (to within the
//! millimetre by which cleaning may move an outline), so the planned field lies inside the
//! boundary as given and outside every obstacle as given.

use super::ring::{find_self_intersection, COLLINEAR_M};
use super::Field;
use crate::error::{Warning, WarningCode};
use crate::geometry::{sleeve_ring, Sleeve};
use crate::numbers::Decimals;
use geo::{Area, Euclidean, Length, LineString, Polygon};

/// The simplification's largest tolerance for a working width: a sixth of it, between 2 cm and
/// 1 m. A 6 m implement gets 1 m: about the noise of a DGPS-recorded boundary, and a sixth of a
/// swath at the field edge.
///
/// ```
/// use furrow::field::simplify::tolerance_for_width;
///
/// assert_eq!(tolerance_for_width(6.0), 1.0);
/// assert_eq!(tolerance_for_width(3.0), 0.5);
/// assert_eq!(tolerance_for_width(0.05), 0.02);
/// ```
pub fn tolerance_for_width(width: f64) -> f64 {
    (width / 6.0).clamp(MIN_TOLERANCE_M, 1.0)
}

/// The first tolerance tried, metres; each next one is twice the last, up to
/// [`tolerance_for_width`].
pub const MIN_TOLERANCE_M: f64 = 0.02;

/// An outline is dense when it has more than one vertex per this many working widths of its
/// length (and more than [`MIN_VERTICES`]); it is simplified until it has no more, or the
/// tolerance reaches its largest.
pub const WIDTHS_PER_VERTEX: f64 = 2.0;

/// Outlines of this many vertices or fewer are never simplified.
pub const MIN_VERTICES: usize = 32;

/// Vertices nearer than this many largest tolerances (a working width, between 12 cm and 6 m)
/// to both their neighbours are samples of a recorded outline, and may be simplified away;
/// farther apart they are the corners of a drawn one, and are kept.
pub const DENSE_GAPS: f64 = 6.0;

/// How far simplification may go for a working width.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Simplification {
    /// The largest tolerance, metres ([`tolerance_for_width`]).
    pub max_tolerance: f64,
    /// The outline length per vertex wanted, metres.
    pub spacing: f64,
}

impl Simplification {
    /// The simplification for a working width.
    ///
    /// ```
    /// use furrow::field::simplify::Simplification;
    ///
    /// let s = Simplification::for_width(6.0);
    /// assert_eq!((s.max_tolerance, s.spacing), (1.0, 12.0));
    /// ```
    pub fn for_width(width: f64) -> Self {
        Simplification {
            max_tolerance: tolerance_for_width(width),
            spacing: WIDTHS_PER_VERTEX * width,
        }
    }

    /// How many vertices an outline of this length may keep without simplification.
    fn budget(&self, length: f64) -> usize {
        let wanted = (length / self.spacing).ceil();
        if wanted.is_finite() && wanted < usize::MAX as f64 {
            (wanted as usize).max(MIN_VERTICES)
        } else {
            MIN_VERTICES
        }
    }
}

/// Which way an outline may move when it is simplified.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Keep {
    /// The simplified outline lies inside the given one (a field boundary).
    Inside,
    /// The simplified outline encloses the given one (an obstacle, a prohibited region).
    Enclosing,
}

/// A closed counter-clockwise ring simplified within `tolerance` metres, moving only as `keep`
/// says, or `None` when simplifying removes nothing or would make it cross itself or collapse
/// (the ring is then kept as it is). Only vertices nearer than `max_gap` to both neighbours are
/// removed.
///
/// Every vertex removed lies within `tolerance` of the new edge that replaces it, on the side
/// `keep` allows (or within [`COLLINEAR_M`] on the other); the new ring does not cross itself,
/// so it lies inside the given ring (or encloses it), to within that millimetre.
///
/// ```
/// use furrow::field::simplify::{simplify_ring, Keep};
/// use geo::{Area, BooleanOps, LineString, Polygon};
///
/// // A 100 m square whose southern edge was recorded every metre, wavering 5 cm either way.
/// let mut points: Vec<(f64, f64)> = (0..100).map(|i| (i as f64, 0.05 * (i as f64).sin())).collect();
/// points.extend([(100.0, 0.0), (100.0, 100.0), (0.0, 100.0), (0.0, 0.0)]);
/// let ring = LineString::from(points);
/// let inside = simplify_ring(&ring, 0.2, 2.0, Keep::Inside).ok_or("nothing removed")?;
/// assert!(inside.0.len() < 20);
/// let (given, simplified) = (Polygon::new(ring, vec![]), Polygon::new(inside, vec![]));
/// // Nothing outside the square as given (to within a millimetre along its southern edge).
/// assert!(simplified.difference(&given).unsigned_area() < 1e-3 * 100.0);
/// assert!(given.unsigned_area() - simplified.unsigned_area() < 0.2 * 100.0);
/// # Ok::<(), &str>(())
/// ```
pub fn simplify_ring(
    ring: &LineString,
    tolerance: f64,
    max_gap: f64,
    keep: Keep,
) -> Option<LineString> {
    let open = ring.0.get(..ring.0.len().saturating_sub(1))?;
    // Counter-clockwise: inside is left of every edge, so the vertices removed lie right of the
    // edges that replace them, or at most as far left as cleaning moves an outline (a parallel
    // of latitude is a curve a few millimetres deep on the local map: a millimetre keeps its
    // vertices from counting as corners).
    let (left, right) = match keep {
        Keep::Inside => (COLLINEAR_M, tolerance),
        Keep::Enclosing => (tolerance, COLLINEAR_M),
    };
    let mut simplified = sleeve_ring(
        open,
        Sleeve {
            left,
            right,
            max_gap,
        },
    );
    let n = simplified.len();
    if n >= open.len() || n < 3 || find_self_intersection(&simplified).is_some() {
        return None;
    }
    simplified.push(simplified[0]);
    Some(LineString::new(simplified))
}

/// A dense ring simplified within the least tolerance that brings it to its budget of vertices
/// (or the largest), and that tolerance; `None` when the ring is not dense or nothing can go.
///
/// ```
/// use furrow::field::simplify::{simplify_dense_ring, Keep, Simplification};
/// use geo::LineString;
///
/// // A 100 m disc recorded every 10 cm: 6,283 vertices where a 6 m implement wants about 53.
/// let ring: LineString = (0..=6283)
///     .map(|i| {
///         let t = i as f64 / 6283.0 * std::f64::consts::TAU;
///         (100.0 * t.cos(), 100.0 * t.sin())
///     })
///     .collect();
/// let (simplified, tolerance) =
///     simplify_dense_ring(&ring, &Simplification::for_width(6.0), Keep::Inside).ok_or("kept")?;
/// assert!(simplified.0.len() <= 54 && tolerance <= 0.32);
/// # Ok::<(), &str>(())
/// ```
pub fn simplify_dense_ring(
    ring: &LineString,
    simplification: &Simplification,
    keep: Keep,
) -> Option<(LineString, f64)> {
    let budget = simplification.budget(Euclidean.length(ring));
    if ring.0.len() <= budget + 1 {
        return None;
    }
    let max_gap = DENSE_GAPS * simplification.max_tolerance;
    let mut tolerance = MIN_TOLERANCE_M.min(simplification.max_tolerance);
    loop {
        let last = tolerance >= simplification.max_tolerance;
        let simplified = simplify_ring(ring, tolerance, max_gap, keep);
        match simplified {
            Some(r) if r.0.len() <= budget + 1 || last => return Some((r, tolerance)),
            None if last => return None,
            _ => tolerance = (2.0 * tolerance).min(simplification.max_tolerance),
        }
    }
}

impl Field {
    /// Simplifies the dense outlines of the boundary (inwards), obstacles and prohibited regions
    /// (outwards) for a working width, and says what changed.
    pub fn simplify(&mut self, width: f64) -> Vec<Warning> {
        let simplification = Simplification::for_width(width);
        let mut warnings = Vec::new();
        let subject = "the field boundary".to_string();
        let boundary = &mut self.boundary;
        if let Some(w) = simplify_polygon(boundary, &simplification, Keep::Inside, &subject) {
            warnings.push(w.at_feature(self.feature));
        }
        let polygons = self
            .obstacles
            .iter_mut()
            .map(|o| (o.subject(), &mut o.polygon, o.feature))
            .chain(
                self.prohibited
                    .iter_mut()
                    .map(|p| (p.subject(), &mut p.polygon, p.feature)),
            );
        for (subject, polygon, feature) in polygons {
            let keep = Keep::Enclosing;
            if let Some(w) = simplify_polygon(polygon, &simplification, keep, &subject) {
                warnings.push(w.at_feature(feature));
            }
        }
        warnings
    }
}

/// Simplifies a polygon's outer ring in place; the warning saying so, if it changed.
fn simplify_polygon(
    polygon: &mut Polygon,
    simplification: &Simplification,
    keep: Keep,
    subject: &str,
) -> Option<Warning> {
    let (ring, tolerance) = simplify_dense_ring(polygon.exterior(), simplification, keep)?;
    let (before, after) = (polygon.exterior().0.len() - 1, ring.0.len() - 1);
    let area_before = polygon.unsigned_area();
    polygon.exterior_mut(|r| *r = ring);
    let change = (polygon.unsigned_area() - area_before).abs();
    let (way, more_or_less) = match keep {
        Keep::Inside => ("inside", "less"),
        Keep::Enclosing => ("outside", "more"),
    };
    Some(Warning::new(
        WarningCode::OutlineSimplified,
        format!(
            "{subject} was simplified from {before} to {after} points, within {} m {way} the outline as given ({} m², {} %, {more_or_less})",
            Decimals(tolerance, 2),
            Decimals(change, 1),
            Decimals(100.0 * change / area_before.max(f64::MIN_POSITIVE), 3)
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{BooleanOps, Distance, Euclidean, Point};

    /// A 200 x 100 m rectangle recorded every metre with +-5 cm of noise.
    fn noisy_rectangle() -> LineString {
        let mut pts = Vec::new();
        let mut k = 0u32;
        let mut noise = || {
            k = k.wrapping_mul(1_103_515_245).wrapping_add(12_345);
            (f64::from(k % 1000) / 1000.0 - 0.5) * 0.1
        };
        for x in 0..200 {
            pts.push((x as f64, noise()));
        }
        for y in 0..100 {
            pts.push((200.0 + noise(), y as f64));
        }
        for x in (1..=200).rev() {
            pts.push((x as f64, 100.0 + noise()));
        }
        for y in (1..=100).rev() {
            pts.push((noise(), y as f64));
        }
        pts.push(pts[0]);
        LineString::from(pts)
    }

    #[test]
    fn noise_is_removed_and_the_shape_kept() {
        let ring = noisy_rectangle();
        for keep in [Keep::Inside, Keep::Enclosing] {
            let simple = simplify_ring(&ring, 0.3, 2.0, keep).unwrap();
            // 601 points, 10 cm of noise: one-sided edges end where the noise turns inwards.
            assert!(simple.0.len() <= 40, "{} vertices left", simple.0.len());
            for c in &ring.0 {
                let d = Euclidean.distance(&Point(*c), &simple);
                assert!(d <= 0.3 + 1e-9, "{d}");
            }
            let (given, simple) = (
                Polygon::new(ring.clone(), vec![]),
                Polygon::new(simple, vec![]),
            );
            let a = simple.unsigned_area();
            assert!((a - 20_000.0).abs() < 0.01 * 20_000.0);
            // Outside the outline as given by no more than cleaning moves it: a millimetre.
            let beyond = match keep {
                Keep::Inside => simple.difference(&given),
                Keep::Enclosing => given.difference(&simple),
            };
            assert!(
                beyond.unsigned_area() <= COLLINEAR_M * 600.0,
                "{}",
                beyond.unsigned_area()
            );
            let within = match keep {
                Keep::Inside => given.difference(&simple),
                Keep::Enclosing => simple.difference(&given),
            };
            assert!(
                within.unsigned_area() > 1.0,
                "{keep:?} moved the outline the wrong way"
            );
        }
    }

    #[test]
    fn a_clean_dense_outline_loses_next_to_nothing() {
        // A 4 ha disc as a register draws it, a vertex every 50 cm: simplified for a 6 m
        // implement to its budget of vertices, at the least tolerance that reaches it.
        let n = 1418;
        let ring: LineString = (0..=n)
            .map(|i| {
                let t = f64::from(i) / f64::from(n) * std::f64::consts::TAU;
                (112.8 * t.cos(), 112.8 * t.sin())
            })
            .collect();
        let simplification = Simplification::for_width(6.0);
        let (simple, tolerance) =
            simplify_dense_ring(&ring, &simplification, Keep::Inside).unwrap();
        assert!(simple.0.len() <= 61, "{} vertices", simple.0.len());
        assert!(tolerance < simplification.max_tolerance, "{tolerance}");
        let (a, b) = (
            Polygon::new(ring, vec![]).unsigned_area(),
            Polygon::new(simple, vec![]).unsigned_area(),
        );
        assert!(a - b < 2e-3 * a, "{} % lost", 100.0 * (a - b) / a);
    }

    #[test]
    fn a_sparse_outline_is_not_simplified() {
        let ring: LineString = (0..=20)
            .map(|i| {
                let t = f64::from(i) / 20.0 * std::f64::consts::TAU;
                (100.0 * t.cos(), 100.0 * t.sin())
            })
            .collect();
        let simplification = Simplification::for_width(6.0);
        assert!(simplify_dense_ring(&ring, &simplification, Keep::Inside).is_none());
    }

    #[test]
    fn a_clean_ring_is_left_alone() {
        let ring = LineString::from(vec![(0., 0.), (10., 0.), (10., 10.), (0., 10.), (0., 0.)]);
        assert!(simplify_ring(&ring, 0.3, 2.0, Keep::Inside).is_none());
    }
}
