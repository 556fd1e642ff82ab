//! WGS84 longitude/latitude to a local metric frame centred on the field, and back.
//!
//! The frame is a transverse Mercator projection of the WGS84 ellipsoid whose central meridian
//! runs through the field's centre, with scale 1 on that meridian and the centre at (0, 0):
//! `x` points east and `y` north, in metres. It uses Krüger's series to sixth order in the third
//! flattening (Karney, "Transverse Mercator with an accuracy of a few nanometers", 2011), so a
//! round trip is exact to well under a micrometre anywhere a field can be, and lengths and areas
//! are within a few parts per million of the geodesic ones within 20 km of the centre.
//!
//! Grid north and true north agree on the central meridian; 1 km east or west of it they differ by
//! about `0.009° · sin(latitude)`, so compass bearings can be used in the frame unchanged.

use crate::geometry::round_half_away;
use geo::Coord;

/// WGS84 semi-major axis in metres.
const WGS84_A: f64 = 6_378_137.0;
/// WGS84 flattening.
const WGS84_F: f64 = 1.0 / 298.257_223_563;

/// A transverse Mercator projection centred on a point, in metres.
///
/// ```
/// use furrow::field::TransverseMercator;
///
/// let tm = TransverseMercator::centred_at(24.05, 60.25);
/// let p = tm.forward(24.06, 60.26);
/// assert!((p.x - 553.6).abs() < 0.1 && (p.y - 1114.2).abs() < 0.1);
/// let (lon, lat) = tm.inverse(p);
/// assert!((lon - 24.06).abs() < 1e-11 && (lat - 60.26).abs() < 1e-11);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct TransverseMercator {
    /// Longitude of the central meridian, degrees.
    lon0_deg: f64,
    /// Northing of the centre on the unshifted projection, metres (subtracted so the centre is y = 0).
    y0: f64,
    /// Rectifying radius `A` (Karney eq. 14), metres.
    rectifying_radius: f64,
    /// First eccentricity.
    e: f64,
    /// Krüger coefficients of the forward series (alpha_1..alpha_6).
    alpha: [f64; 6],
    /// Krüger coefficients of the inverse series (beta_1..beta_6).
    beta: [f64; 6],
    /// Coefficients of the series from conformal to geographic latitude (delta_1..delta_6).
    delta: [f64; 6],
}

impl TransverseMercator {
    /// The projection whose origin (0, 0) is at the given longitude and latitude (degrees).
    pub fn centred_at(lon0_deg: f64, lat0_deg: f64) -> Self {
        let f = WGS84_F;
        let n = f / (2.0 - f);
        let e = (f * (2.0 - f)).sqrt();
        let (n2, n3) = (n * n, n * n * n);
        let (n4, n5, n6) = (n2 * n2, n2 * n3, n3 * n3);
        let rectifying_radius = WGS84_A / (1.0 + n) * (1.0 + n2 / 4.0 + n4 / 64.0 + n6 / 256.0);
        let alpha = [
            n / 2.0 - 2.0 * n2 / 3.0 + 5.0 * n3 / 16.0 + 41.0 * n4 / 180.0 - 127.0 * n5 / 288.0
                + 7891.0 * n6 / 37800.0,
            13.0 * n2 / 48.0 - 3.0 * n3 / 5.0 + 557.0 * n4 / 1440.0 + 281.0 * n5 / 630.0
                - 1983433.0 * n6 / 1935360.0,
            61.0 * n3 / 240.0 - 103.0 * n4 / 140.0
                + 15061.0 * n5 / 26880.0
                + 167603.0 * n6 / 181440.0,
            49561.0 * n4 / 161280.0 - 179.0 * n5 / 168.0 + 6601661.0 * n6 / 7257600.0,
            34729.0 * n5 / 80640.0 - 3418889.0 * n6 / 1995840.0,
            212378941.0 * n6 / 319334400.0,
        ];
        let beta = [
            n / 2.0 - 2.0 * n2 / 3.0 + 37.0 * n3 / 96.0 - n4 / 360.0 - 81.0 * n5 / 512.0
                + 96199.0 * n6 / 604800.0,
            n2 / 48.0 + n3 / 15.0 - 437.0 * n4 / 1440.0 + 46.0 * n5 / 105.0
                - 1118711.0 * n6 / 3870720.0,
            17.0 * n3 / 480.0 - 37.0 * n4 / 840.0 - 209.0 * n5 / 4480.0 + 5569.0 * n6 / 90720.0,
            4397.0 * n4 / 161280.0 - 11.0 * n5 / 504.0 - 830251.0 * n6 / 7257600.0,
            4583.0 * n5 / 161280.0 - 108847.0 * n6 / 3991680.0,
            20648693.0 * n6 / 638668800.0,
        ];
        let delta = [
            2.0 * n - 2.0 * n2 / 3.0 - 2.0 * n3 + 116.0 * n4 / 45.0 + 26.0 * n5 / 45.0
                - 2854.0 * n6 / 675.0,
            7.0 * n2 / 3.0 - 8.0 * n3 / 5.0 - 227.0 * n4 / 45.0
                + 2704.0 * n5 / 315.0
                + 2323.0 * n6 / 945.0,
            56.0 * n3 / 15.0 - 136.0 * n4 / 35.0 - 1262.0 * n5 / 105.0 + 73814.0 * n6 / 2835.0,
            4279.0 * n4 / 630.0 - 332.0 * n5 / 35.0 - 399572.0 * n6 / 14175.0,
            4174.0 * n5 / 315.0 - 144838.0 * n6 / 6237.0,
            601676.0 * n6 / 22275.0,
        ];
        let mut tm = TransverseMercator {
            lon0_deg,
            y0: 0.0,
            rectifying_radius,
            e,
            alpha,
            beta,
            delta,
        };
        tm.y0 = tm.forward(lon0_deg, lat0_deg).y;
        tm
    }

    /// Longitude of the central meridian, degrees.
    pub fn central_meridian_deg(&self) -> f64 {
        self.lon0_deg
    }

    /// Projects longitude and latitude (degrees) to metres east and north of the centre.
    pub fn forward(&self, lon_deg: f64, lat_deg: f64) -> Coord {
        let lambda = wrap_deg(lon_deg - self.lon0_deg).to_radians();
        let phi = lat_deg.to_radians();
        let tau = phi.tan();
        let tau_prime = self.conformal_tan(tau);
        let (sin_l, cos_l) = lambda.sin_cos();
        let xi_p = tau_prime.atan2(cos_l);
        let eta_p = (sin_l / tau_prime.hypot(cos_l)).asinh();
        let (xi, eta) = clenshaw(&self.alpha, xi_p, eta_p, 1.0);
        Coord {
            x: self.rectifying_radius * eta,
            y: self.rectifying_radius * xi - self.y0,
        }
    }

    /// Inverse of [`forward`](Self::forward): metres east and north of the centre to (longitude,
    /// latitude) in degrees.
    pub fn inverse(&self, p: Coord) -> (f64, f64) {
        let xi = (p.y + self.y0) / self.rectifying_radius;
        let eta = p.x / self.rectifying_radius;
        let (xi_p, eta_p) = clenshaw(&self.beta, xi, eta, -1.0);
        let sinh_eta = eta_p.sinh();
        let (sin_xi, cos_xi) = xi_p.sin_cos();
        let tau_prime = sin_xi / sinh_eta.hypot(cos_xi);
        let lambda = sinh_eta.atan2(cos_xi);
        // Conformal latitude to geographic latitude by its series in n (Karney 2011, eq. 37):
        // one sine and cosine instead of Newton's method on the conformal tangent.
        let chi = tau_prime.atan();
        let lat = (chi + real_clenshaw(&self.delta, chi)).to_degrees();
        let lon = wrap_deg(self.lon0_deg + lambda.to_degrees());
        (lon, lat)
    }

    /// tan of the conformal latitude from tan of the geographic latitude (Karney eq. 7).
    fn conformal_tan(&self, tau: f64) -> f64 {
        let e = self.e;
        let sigma = (e * (e * tau / tau.hypot(1.0)).atanh()).sinh();
        tau * sigma.hypot(1.0) - sigma * tau.hypot(1.0)
    }
}

/// `ζ + sign · Σ c_j sin(2jζ)` for the complex `ζ = ξ + iη`, by Clenshaw's recurrence: one
/// sine, cosine and exponential per point instead of six of each (Karney 2011, section 5).
#[inline]
fn clenshaw(c: &[f64; 6], xi: f64, eta: f64, sign: f64) -> (f64, f64) {
    let (s2, c2) = (2.0 * xi).sin_cos();
    let e2 = (2.0 * eta).exp();
    let (sh2, ch2) = ((e2 - 1.0 / e2) / 2.0, (e2 + 1.0 / e2) / 2.0);
    // a = 2 cos(2ζ), complex.
    let (ar, ai) = (2.0 * c2 * ch2, -2.0 * s2 * sh2);
    // b_j = c_j + a b_{j+1} - b_{j+2}, from j = 6 down to 1.
    let (mut yr, mut yi) = (0.0, 0.0);
    let (mut zr, mut zi) = (0.0, 0.0);
    for &cj in c.iter().rev() {
        let (tr, ti) = (cj + ar * yr - ai * yi - zr, ai * yr + ar * yi - zi);
        (zr, zi) = (yr, yi);
        (yr, yi) = (tr, ti);
    }
    // Σ = sin(2ζ) b_1, with sin(2ζ) = sin 2ξ cosh 2η + i cos 2ξ sinh 2η.
    let (sr, si) = (s2 * ch2, c2 * sh2);
    (
        xi + sign * (sr * yr - si * yi),
        eta + sign * (sr * yi + si * yr),
    )
}

/// `Σ c_j sin(2jx)` for real `x`, by Clenshaw's recurrence.
#[inline]
fn real_clenshaw(c: &[f64; 6], x: f64) -> f64 {
    let (s2, c2) = (2.0 * x).sin_cos();
    let a = 2.0 * c2;
    let (mut y, mut z) = (0.0, 0.0);
    for &cj in c.iter().rev() {
        (z, y) = (y, cj + a * y - z);
    }
    s2 * y
}

/// Wraps a longitude difference into [-180, 180).
fn wrap_deg(d: f64) -> f64 {
    if (-180.0..180.0).contains(&d) {
        d
    } else {
        (d + 180.0).rem_euclid(360.0) - 180.0
    }
}

/// The coordinate system a field came in, and the way between it and the planner's metres.
#[derive(Debug, Clone, PartialEq)]
pub enum Frame {
    /// WGS84 longitude and latitude in degrees (GeoJSON's RFC 7946 coordinates).
    Wgs84(TransverseMercator),
    /// Already metres in a local frame, x east and y north: coordinates pass through unchanged.
    Metric,
}

impl Frame {
    /// Input coordinates to the planner's metres.
    #[inline]
    pub fn to_local(&self, p: [f64; 2]) -> Coord {
        match self {
            Frame::Wgs84(tm) => tm.forward(p[0], p[1]),
            Frame::Metric => Coord { x: p[0], y: p[1] },
        }
    }

    /// The planner's metres back to input coordinates.
    #[inline]
    pub fn to_input(&self, p: Coord) -> [f64; 2] {
        match self {
            Frame::Wgs84(tm) => {
                let (lon, lat) = tm.inverse(p);
                [lon, lat]
            }
            Frame::Metric => [p.x, p.y],
        }
    }

    /// The planner's metres back to input coordinates, rounded for output: degrees to 1e-9
    /// (about 0.1 mm), metres to 0.1 mm. Rounding makes the output shorter and loses nothing
    /// that matters in a field.
    #[inline]
    pub fn to_output(&self, p: Coord) -> [f64; 2] {
        let [x, y] = self.to_input(p);
        let scale = match self {
            Frame::Wgs84(_) => 1e9,
            Frame::Metric => 1e4,
        };
        // Dividing by the exact integer scale gives the double nearest the decimal: it prints short.
        [
            round_half_away(x * scale) / scale,
            round_half_away(y * scale) / scale,
        ]
    }

    /// The map to output coordinates near `p` as a quadratic map of local metres (exact at `p`,
    /// its first and second derivatives by central differences over [`NEAR_STEP_M`]): for
    /// converting many points close together, such as a path sampled every half metre, at the
    /// cost of nine projections. Within [`NEAR_M`] of `p` it is within 0.3 mm of the exact
    /// conversion (the output rounds to 0.1 mm); the terms it leaves out grow with the cube of
    /// the distance over the earth's radius.
    pub fn output_near(&self, p: Coord) -> NearOutput {
        let scale = match self {
            Frame::Wgs84(_) => 1e9,
            Frame::Metric => 1e4,
        };
        let at = self.to_input(p);
        let h = NEAR_STEP_M;
        // East, west, north, south, north-east, north-west, south-east, south-west of `p`, each
        // as a difference from `at`: longitudes across the antimeridian stay continuous. (One
        // loop: the projection's code once in the module, not eight times.)
        let steps = [
            (h, 0.0),
            (-h, 0.0),
            (0.0, h),
            (0.0, -h),
            (h, h),
            (-h, h),
            (h, -h),
            (-h, -h),
        ];
        let mut around = [[0.0; 2]; 8];
        for (d, &(dx, dy)) in around.iter_mut().zip(&steps) {
            let q = self.to_input(Coord {
                x: p.x + dx,
                y: p.y + dy,
            });
            *d = match self {
                Frame::Wgs84(_) => [wrap_deg(q[0] - at[0]), q[1] - at[1]],
                Frame::Metric => [q[0] - at[0], q[1] - at[1]],
            };
        }
        let [e, w, n, s, ne, nw, se, sw] = around;
        let per = |f: fn(&[f64; 2]) -> f64| NearTerms {
            dx: (f(&e) - f(&w)) / (2.0 * h),
            dy: (f(&n) - f(&s)) / (2.0 * h),
            dxx: (f(&e) + f(&w)) / (2.0 * h * h),
            dyy: (f(&n) + f(&s)) / (2.0 * h * h),
            dxy: (f(&ne) - f(&nw) - f(&se) + f(&sw)) / (4.0 * h * h),
        };
        NearOutput {
            origin: p,
            at,
            terms: [per(|q| q[0]), per(|q| q[1])],
            wraps: matches!(self, Frame::Wgs84(_)),
            scale,
        }
    }
}

/// How far from its origin (metres) a [`NearOutput`] is used.
pub const NEAR_M: f64 = 200.0;

/// The step (metres) of the central differences that give a [`NearOutput`] its derivatives:
/// long enough that the doubles' rounding stays far below the output's, short enough that the
/// differences' own error does too.
const NEAR_STEP_M: f64 = 10.0;

/// One output coordinate's terms in a [`NearOutput`]: its first derivatives, and half its
/// second derivatives along x and y (the cross derivative whole), per metre.
#[derive(Debug, Clone, Copy, PartialEq)]
struct NearTerms {
    dx: f64,
    dy: f64,
    dxx: f64,
    dyy: f64,
    dxy: f64,
}

impl NearTerms {
    #[inline]
    fn at(&self, u: f64, v: f64) -> f64 {
        u * (self.dx + u * self.dxx + v * self.dxy) + v * (self.dy + v * self.dyy)
    }
}

/// The conversion to output coordinates near a point, as a quadratic map (see
/// [`Frame::output_near`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NearOutput {
    /// Where it is exact, local metres.
    pub origin: Coord,
    at: [f64; 2],
    terms: [NearTerms; 2],
    /// Whether the first coordinate is a longitude, wrapped into [-180, 180).
    wraps: bool,
    scale: f64,
}

impl NearOutput {
    /// Output coordinates of `q` (rounded as [`Frame::to_output`] rounds).
    #[inline]
    pub fn apply(&self, q: Coord) -> [f64; 2] {
        let (u, v) = (q.x - self.origin.x, q.y - self.origin.y);
        let mut x = self.at[0] + self.terms[0].at(u, v);
        let y = self.at[1] + self.terms[1].at(u, v);
        if self.wraps {
            x = wrap_deg(x);
        }
        [
            round_half_away(x * self.scale) / self.scale,
            round_half_away(y * self.scale) / self.scale,
        ]
    }
}

/// Output coordinates of many points in a row, each near the one before (a sampled path, the
/// vertices of a turn): a [`NearOutput`] from the last exact point while within [`NEAR_M`] of
/// it, a new one (nine projections) beyond.
#[derive(Debug, Clone)]
pub struct OutputAlong<'a> {
    frame: &'a Frame,
    near: Option<NearOutput>,
}

impl<'a> OutputAlong<'a> {
    /// Conversions in `frame`, starting afresh.
    pub fn new(frame: &'a Frame) -> Self {
        OutputAlong { frame, near: None }
    }

    /// Output coordinates of `q`, within 0.3 mm of [`Frame::to_output`].
    pub fn convert(&mut self, q: Coord) -> [f64; 2] {
        let map = match self.near {
            Some(n)
                if (q.x - n.origin.x).powi(2) + (q.y - n.origin.y).powi(2) < NEAR_M * NEAR_M =>
            {
                n
            }
            _ => {
                let n = self.frame.output_near(q);
                self.near = Some(n);
                n
            }
        };
        map.apply(q)
    }

    /// Output coordinates of `points`, in a row.
    pub fn all(&mut self, points: impl Iterator<Item = Coord>) -> Vec<[f64; 2]> {
        points.map(|q| self.convert(q)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{Area, GeodesicArea, Polygon};

    #[test]
    fn the_map_near_a_point_matches_the_projection_to_the_output_rounding() {
        // From the equator to 85 degrees, and across the antimeridian.
        for (lon0, lat0) in [
            (24.05, 60.25),
            (5.3, 0.0),
            (-60.0, -35.0),
            (10.0, 85.0),
            (179.999, 0.5),
        ] {
            let frame = Frame::Wgs84(TransverseMercator::centred_at(lon0, lat0));
            for (px, py) in [(0.0, 0.0), (5000.0, -3000.0), (-15000.0, 12000.0)] {
                let p = Coord { x: px, y: py };
                let near = frame.output_near(p);
                for k in 0..64 {
                    // Out to the map's reach, every way round.
                    let angle = k as f64 * 0.1;
                    let r = NEAR_M * (k % 8 + 1) as f64 / 8.0;
                    let q = Coord {
                        x: px + r * angle.cos(),
                        y: py + r * angle.sin(),
                    };
                    let (a, b) = (near.apply(q), frame.to_output(q));
                    // Within 3e-9 degrees (0.3 mm): the rounding's 1e-9 and the terms the map
                    // leaves out.
                    let dlon = (a[0] - b[0]).abs();
                    assert!(
                        dlon.min(360.0 - dlon) <= 3e-9 && (a[1] - b[1]).abs() <= 3e-9,
                        "({lon0}, {lat0}) {p:?} -> {q:?}: {a:?} {b:?}"
                    );
                    assert!((-180.0..180.0).contains(&a[0]), "{a:?}");
                }
            }
        }
    }

    #[test]
    fn the_map_near_a_point_is_exact_in_metres() {
        let near = Frame::Metric.output_near(Coord { x: 12.5, y: -40.0 });
        for (x, y) in [(12.5, -40.0), (100.25, 3.5), (-150.0, -200.0)] {
            assert_eq!(
                near.apply(Coord { x, y }),
                Frame::Metric.to_output(Coord { x, y })
            );
        }
    }

    #[test]
    fn points_in_a_row_convert_within_the_output_rounding_and_exactly_where_a_map_starts() {
        let frame = Frame::Wgs84(TransverseMercator::centred_at(24.05, 60.25));
        let mut along = OutputAlong::new(&frame);
        // Five kilometres of path every half metre, then a jump far away.
        let mut points: Vec<Coord> = (0..10_000)
            .map(|i| Coord {
                x: 300.0 + 0.3 * i as f64,
                y: -200.0 + 0.4 * i as f64,
            })
            .collect();
        points.push(Coord {
            x: 9000.0,
            y: 7000.0,
        });
        for (i, &q) in points.iter().enumerate() {
            let (a, b) = (along.convert(q), frame.to_output(q));
            assert!(
                (a[0] - b[0]).abs() <= 3e-9 && (a[1] - b[1]).abs() <= 3e-9,
                "{i}: {a:?} {b:?}"
            );
            if i == 0 || i == points.len() - 1 {
                assert_eq!(a, b, "a new map is exact at its origin");
            }
        }
    }

    #[test]
    fn centre_maps_to_origin() {
        let tm = TransverseMercator::centred_at(24.05, 60.25);
        let p = tm.forward(24.05, 60.25);
        assert!(p.x.abs() < 1e-9 && p.y.abs() < 1e-6, "{p:?}");
    }

    #[test]
    fn round_trip_within_20_km_is_under_a_millimetre() {
        for &(lon0, lat0) in &[
            (24.05, 60.25),
            (5.3, 52.1),
            (-60.0, -35.0),
            (179.9, 0.5),
            (10.0, 85.0),
        ] {
            let tm = TransverseMercator::centred_at(lon0, lat0);
            for i in -10..=10 {
                for j in -10..=10 {
                    let p = Coord {
                        x: i as f64 * 2000.0,
                        y: j as f64 * 2000.0,
                    };
                    let (lon, lat) = tm.inverse(p);
                    let q = tm.forward(lon, lat);
                    assert!((p.x - q.x).hypot(p.y - q.y) < 1e-6, "{p:?} -> {q:?}");
                }
            }
        }
    }

    #[test]
    fn a_metre_north_is_a_metre() {
        // One degree of latitude at 60 N is 111 412.3 m on WGS84.
        let tm = TransverseMercator::centred_at(10.0, 60.0);
        let a = tm.forward(10.0, 59.5);
        let b = tm.forward(10.0, 60.5);
        assert!((b.y - a.y - 111_412.3).abs() < 1.0, "{}", b.y - a.y);
    }

    #[test]
    fn area_matches_geodesic_area() {
        // A 3 km by 2 km quadrilateral in Finland, away from the central meridian.
        let ring = vec![
            (24.00, 60.20),
            (24.06, 60.20),
            (24.07, 60.22),
            (24.01, 60.225),
            (24.00, 60.20),
        ];
        let geographic = Polygon::new(ring.clone().into(), vec![]);
        let tm = TransverseMercator::centred_at(24.035, 60.21);
        let local = Polygon::new(
            ring.iter()
                .map(|&(lon, lat)| tm.forward(lon, lat))
                .collect::<Vec<_>>()
                .into(),
            vec![],
        );
        let geodesic = geographic.geodesic_area_unsigned();
        let planar = local.unsigned_area();
        assert!(((planar - geodesic) / geodesic).abs() < 5e-4 / 10.0);
    }

    #[test]
    fn longitudes_wrap_at_the_antimeridian() {
        let tm = TransverseMercator::centred_at(179.99, -17.0);
        let east = tm.forward(-179.99, -17.0);
        assert!(east.x > 2000.0 && east.x < 2200.0, "{east:?}");
        let (lon, _) = tm.inverse(east);
        assert!((lon + 179.99).abs() < 1e-10);
    }

    #[test]
    fn metric_frame_is_identity() {
        let f = Frame::Metric;
        assert_eq!(f.to_local([3.0, 4.0]), Coord { x: 3.0, y: 4.0 });
        assert_eq!(f.to_input(Coord { x: 3.0, y: 4.0 }), [3.0, 4.0]);
    }
}
