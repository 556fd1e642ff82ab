//! Where the machine enters and leaves the field (the entrance and the exit): a place must be a
//! position of the input's coordinates and lie near the field, within
//! [`MAX_PLACE_DISTANCE_M`] of its boundary. A place far off is a mistake (a typo, a position
//! of another field, numbers such as 1e300): planned, it would make a first connection of
//! thousands of kilometres.

use super::validate::{MAX_ABS_LATITUDE_DEG, MAX_ABS_METRIC_M};
use super::{Coordinates, Frame};
use crate::geometry::distance::point_segment_distance;
use crate::numbers::{Decimals, Shortest};
use geo::{Contains, Coord, Polygon};

/// The farthest an entrance or exit may lie from the field boundary, metres: a gate across a
/// farm road, or a yard down a track, is nearer than this.
pub const MAX_PLACE_DISTANCE_M: f64 = 10_000.0;

/// Mean radius of the Earth (IUGG), metres: for distances too far for the field's projection.
const EARTH_RADIUS_M: f64 = 6_371_008.8;

/// Places farther than this from the field's centre (metres, along the sphere) are not
/// projected: they are far beyond [`MAX_PLACE_DISTANCE_M`] of any field (at most 40 km across),
/// and the projection is only meant for the field's surroundings.
const PROJECTED_WITHIN_M: f64 = 100_000.0;

/// What is wrong with position `p` as a position of `coordinates`, if anything: a number that
/// is not finite, a longitude or latitude out of range (or too near a pole to farm), metres
/// beyond [`MAX_ABS_METRIC_M`] of the origin.
///
/// ```
/// use furrow::field::{place::range_problem, Coordinates};
///
/// assert_eq!(range_problem([24.05, 60.25], Coordinates::Wgs84), None);
/// assert!(range_problem([1e300, 1e300], Coordinates::Wgs84).is_some());
/// assert!(range_problem([60.25, 124.05], Coordinates::Wgs84).is_some());
/// assert_eq!(range_problem([1e6, -2e6], Coordinates::Metric), None);
/// ```
pub fn range_problem([x, y]: [f64; 2], coordinates: Coordinates) -> Option<String> {
    if !(x.is_finite() && y.is_finite()) {
        return Some("its coordinates must be finite numbers".into());
    }
    match coordinates {
        Coordinates::Wgs84 if !(-180.0..=180.0).contains(&x) => Some(format!(
            "its longitude {} is out of range -180..180",
            Shortest(x)
        )),
        Coordinates::Wgs84 if y.abs() > MAX_ABS_LATITUDE_DEG => Some(format!(
            "its latitude {} is out of range -{}..{}",
            Shortest(y),
            Shortest(MAX_ABS_LATITUDE_DEG),
            Shortest(MAX_ABS_LATITUDE_DEG)
        )),
        Coordinates::Metric if x.abs().max(y.abs()) > MAX_ABS_METRIC_M => Some(format!(
            "it is more than {} km from the origin of the metric frame",
            Shortest(MAX_ABS_METRIC_M / 1000.0)
        )),
        _ => None,
    }
}

/// How far position `p` (input coordinates) lies from the field `boundary` (local metres, as
/// `frame` projects), metres; 0 inside it. A place more than 100 km from the field's centre is
/// not projected: its distance is then the great-circle distance to the centre.
///
/// ```
/// use furrow::field::{place::distance_from_field_m, Frame};
/// use geo::polygon;
///
/// let square = polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 100., y: 100.), (x: 0., y: 100.)];
/// assert_eq!(distance_from_field_m([50., 50.], &square, &Frame::Metric), 0.0);
/// assert_eq!(distance_from_field_m([130., 140.], &square, &Frame::Metric), 50.0);
/// ```
pub fn distance_from_field_m(p: [f64; 2], boundary: &Polygon, frame: &Frame) -> f64 {
    if let Frame::Wgs84(_) = frame {
        let centre = frame.to_input(Coord { x: 0.0, y: 0.0 });
        let far = great_circle_m(centre, p);
        if far > PROJECTED_WITHIN_M {
            return far;
        }
    }
    let q = frame.to_local(p);
    if boundary.contains(&q) {
        return 0.0;
    }
    boundary
        .exterior()
        .lines()
        .map(|l| point_segment_distance(q, l.start, l.end))
        .fold(f64::INFINITY, f64::min)
}

/// What is wrong with position `p` as an entrance or exit of the field, if anything: it is no
/// position of `coordinates` ([`range_problem`]), or it lies more than
/// [`MAX_PLACE_DISTANCE_M`] from the boundary (the phrase says how far, not the limit).
pub fn place_problem(
    p: [f64; 2],
    coordinates: Coordinates,
    boundary: &Polygon,
    frame: &Frame,
) -> Option<String> {
    if let Some(problem) = range_problem(p, coordinates) {
        return Some(problem);
    }
    let distance = distance_from_field_m(p, boundary, frame);
    (distance > MAX_PLACE_DISTANCE_M).then(|| {
        format!(
            "it lies {} km from the field boundary",
            Decimals(distance / 1000.0, 1)
        )
    })
}

/// Great-circle distance between two positions in longitude and latitude (degrees), metres,
/// on a sphere of the Earth's mean radius (haversine).
fn great_circle_m(a: [f64; 2], b: [f64; 2]) -> f64 {
    let (phi_a, phi_b) = (a[1].to_radians(), b[1].to_radians());
    let half_dphi = (phi_b - phi_a) / 2.0;
    let half_dlambda = (b[0] - a[0]).to_radians() / 2.0;
    let h = half_dphi.sin().powi(2) + phi_a.cos() * phi_b.cos() * half_dlambda.sin().powi(2);
    2.0 * EARTH_RADIUS_M * h.sqrt().min(1.0).asin()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::field::TransverseMercator;
    use geo::polygon;

    #[test]
    fn great_circle_distances() {
        // A quarter of the equator, and a degree of latitude (about 111.2 km on the sphere).
        let quarter = great_circle_m([0.0, 0.0], [90.0, 0.0]);
        assert!((quarter - EARTH_RADIUS_M * std::f64::consts::FRAC_PI_2).abs() < 1e-6);
        let degree = great_circle_m([24.0, 60.0], [24.0, 61.0]);
        assert!(
            (degree - EARTH_RADIUS_M.to_radians()).abs() < 1e-6,
            "{degree}"
        );
        // Across the antimeridian the short way.
        assert!(great_circle_m([179.5, 0.0], [-179.5, 0.0]) < 112_000.0);
    }

    #[test]
    fn places_near_the_field_are_measured_in_its_frame() {
        let frame = Frame::Wgs84(TransverseMercator::centred_at(24.05, 60.25));
        // A 200 m square round the centre.
        let square = polygon![(x: -100., y: -100.), (x: 100., y: -100.), (x: 100., y: 100.), (x: -100., y: 100.)];
        assert_eq!(distance_from_field_m([24.05, 60.25], &square, &frame), 0.0);
        // 0.05 degrees of latitude north of the centre: 5571 m on the ellipsoid there, less 100 m.
        let north = distance_from_field_m([24.05, 60.30], &square, &frame);
        assert!((north - 5471.0).abs() < 5.0, "{north}");
        assert_eq!(
            place_problem([24.05, 60.30], Coordinates::Wgs84, &square, &frame),
            None
        );
        // 0.1 degrees: 11.1 km, too far.
        let problem = place_problem([24.05, 60.35], Coordinates::Wgs84, &square, &frame);
        assert!(problem.is_some_and(|p| p.contains("11.0 km")));
        // The other side of the Earth: the great-circle distance, not a projection.
        let antipode = distance_from_field_m([-155.95, -60.25], &square, &frame);
        assert!((antipode - EARTH_RADIUS_M * std::f64::consts::PI).abs() < 1.0);
    }
}
