//! Prohibited regions (Oksanen & Visala 2.8): parts of the field where some driving directions
//! may not be used, such as an escarpment that must not be driven straight up and down, or
//! drainage laterals that must not be followed.
//!
//! Where the field's direction is one a region forbids, the region is cut out of the field's
//! area, as an obstacle for that direction, and worked in a direction of its own. Regions may
//! overlap: a region's area is what is left of it after the regions before it, and its direction
//! must also be allowed by every other region its area reaches into.

use crate::field::ProhibitedRegion;
use crate::geometry::BearingRange;
use crate::geometry::BooleanOps;
use geo::{Area, BoundingRect, Intersects, MultiPolygon};

/// Area (square metres) under which an overlap of a region with another is taken for a touch.
const TOUCH_AREA_M2: f64 = 1e-2;

/// The part of a prohibited region worked in its own direction.
#[derive(Debug, Clone, PartialEq)]
pub struct RegionArea {
    /// Index of the region (into the field's prohibited regions).
    pub region: usize,
    /// Its area: the region inside the given area, less the regions cut out before it.
    pub area: MultiPolygon,
    /// The directions its swaths may not take: the global ranges, its own, and those of other
    /// regions its area reaches into.
    pub forbidden: Vec<BearingRange>,
}

/// The regions (indices) whose forbidden ranges include the swath direction `bearing`.
pub fn forbidding(regions: &[ProhibitedRegion], bearing: f64) -> Vec<usize> {
    regions
        .iter()
        .enumerate()
        .filter(|(_, r)| r.forbidden.iter().any(|f| f.forbids(bearing)))
        .map(|(i, _)| i)
        .collect()
}

/// The forbidden ranges that hold anywhere in `area`: the `global` ones and those of every
/// region it reaches into by more than `min_area` square metres.
///
/// ```
/// use furrow::field::ProhibitedRegion;
/// use furrow::geometry::BearingRange;
/// use furrow::prohibited::constraints_in;
/// use geo::{polygon, MultiPolygon};
///
/// let slope = ProhibitedRegion {
///     polygon: polygon![(x: 0., y: 0.), (x: 40., y: 0.), (x: 40., y: 40.), (x: 0., y: 40.)],
///     forbidden: vec![BearingRange { from_deg: 350.0, to_deg: 10.0 }],
///     feature: 1,
///     name: None,
/// };
/// let inside = MultiPolygon::new(vec![polygon![(x: 10., y: 10.), (x: 60., y: 10.), (x: 60., y: 20.), (x: 10., y: 20.)]]);
/// let outside = MultiPolygon::new(vec![polygon![(x: 50., y: 50.), (x: 60., y: 50.), (x: 60., y: 60.)]]);
/// assert_eq!(constraints_in(&inside, &[slope.clone()], &[], 1.0).len(), 1);
/// assert!(constraints_in(&outside, &[slope], &[], 1.0).is_empty());
/// ```
pub fn constraints_in(
    area: &MultiPolygon,
    regions: &[ProhibitedRegion],
    global: &[BearingRange],
    min_area: f64,
) -> Vec<BearingRange> {
    let mut all = global.to_vec();
    let bounds = area.bounding_rect();
    for r in regions {
        let near = match (bounds, r.polygon.bounding_rect()) {
            (Some(a), Some(b)) => a.intersects(&b),
            _ => false,
        };
        if near
            && area
                .intersection(&MultiPolygon::new(vec![r.polygon.clone()]))
                .unsigned_area()
                > min_area
        {
            all.extend(r.forbidden.iter().copied());
        }
    }
    all
}

/// Splits `area` into the part worked at the field's direction and the parts of the regions
/// `cut` (indices, ascending) worked at their own.
///
/// ```
/// use furrow::field::ProhibitedRegion;
/// use furrow::geometry::BearingRange;
/// use furrow::prohibited::split;
/// use geo::{polygon, Area, MultiPolygon};
///
/// let field = MultiPolygon::new(vec![polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 100., y: 100.), (x: 0., y: 100.)]]);
/// let slope = ProhibitedRegion {
///     polygon: polygon![(x: 0., y: 0.), (x: 40., y: 0.), (x: 40., y: 40.), (x: 0., y: 40.)],
///     forbidden: vec![BearingRange { from_deg: 350.0, to_deg: 10.0 }],
///     feature: 1,
///     name: None,
/// };
/// let (main, parts) = split(&field, &[slope], &[0], &[]);
/// assert!((main.unsigned_area() - 8400.0).abs() < 1e-6);
/// assert!((parts[0].area.unsigned_area() - 1600.0).abs() < 1e-6);
/// assert_eq!(parts[0].forbidden.len(), 1);
/// ```
pub fn split(
    area: &MultiPolygon,
    regions: &[ProhibitedRegion],
    cut: &[usize],
    global: &[BearingRange],
) -> (MultiPolygon, Vec<RegionArea>) {
    let mut main = area.clone();
    let mut parts = Vec::new();
    let mut taken = MultiPolygon::new(vec![]);
    for &k in cut {
        let Some(region) = regions.get(k) else {
            continue;
        };
        let shape = MultiPolygon::new(vec![region.polygon.clone()]);
        let mut part = area.intersection(&shape);
        if !taken.0.is_empty() {
            part = part.difference(&taken);
        }
        main = main.difference(&shape);
        taken = taken.union(&shape);
        if part.unsigned_area() < TOUCH_AREA_M2 {
            continue;
        }
        // Its own ranges, and those of every other region it reaches into.
        let mut forbidden = constraints_in(&part, regions, global, TOUCH_AREA_M2);
        if !region.forbidden.iter().all(|f| forbidden.contains(f)) {
            forbidden.extend(region.forbidden.iter().copied());
        }
        parts.push(RegionArea {
            region: k,
            area: part,
            forbidden,
        });
    }
    (main, parts)
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::polygon;

    fn region(x0: f64, x1: f64, from: f64, to: f64) -> ProhibitedRegion {
        ProhibitedRegion {
            polygon: polygon![(x: x0, y: 0.), (x: x1, y: 0.), (x: x1, y: 50.), (x: x0, y: 50.)],
            forbidden: vec![BearingRange {
                from_deg: from,
                to_deg: to,
            }],
            feature: 1,
            name: None,
        }
    }

    #[test]
    fn overlapping_regions_share_their_overlap_once_and_its_constraints() {
        let field = MultiPolygon::new(vec![
            polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 100., y: 50.), (x: 0., y: 50.)],
        ]);
        let regions = [
            region(10.0, 50.0, 0.0, 10.0),
            region(40.0, 80.0, 80.0, 100.0),
        ];
        assert_eq!(forbidding(&regions, 5f64.to_radians()), vec![0]);
        let (main, parts) = split(&field, &regions, &[0, 1], &[]);
        assert!((main.unsigned_area() - 1500.0).abs() < 1e-6);
        assert!((parts[0].area.unsigned_area() - 2000.0).abs() < 1e-6);
        assert!((parts[1].area.unsigned_area() - 1500.0).abs() < 1e-6);
        // The first region reaches into the second: it must avoid both ranges.
        assert_eq!(parts[0].forbidden.len(), 2);
        // The second's part no longer reaches into the first.
        assert_eq!(parts[1].forbidden.len(), 1);
    }
}
