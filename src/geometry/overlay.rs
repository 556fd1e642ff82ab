//! Boolean operations and offsets of polygons: union, intersection and difference, and buffers
//! of polygons and lines with round joins.
//!
//! They are i_overlay's, called directly at its current version rather than through geo's
//! `BooleanOps` and `Buffer` (geo 0.33 holds i_overlay at 4.5, whose hole binding fails an index
//! on some results where two parts touch at a point; the fix came in i_overlay 7). The
//! conventions are geo's: even-odd filling, results in the OGC form (exteriors counter-clockwise,
//! holes clockwise, parts touching at a point kept apart), rings closed.

use geo::{Coord, LineString, MultiPolygon, Orient, Polygon};
use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::core::solver::Solver;
use i_overlay::float::overlay::{FloatOverlay, OverlayOptions};
use i_overlay::mesh::outline::offset::OutlineOffset;
use i_overlay::mesh::stroke::offset::StrokeOffset;
use i_overlay::mesh::style::{LineCap, LineJoin, OutlineStyle, StrokeStyle};

type Point = [f64; 2];
type Shapes = Vec<Vec<Vec<Point>>>;

/// Polygons given to the boolean operations as rings.
pub trait Rings {
    /// The rings as i_overlay's contours (open: the closing point left out).
    fn contours(&self) -> Vec<Vec<Point>>;
}

impl Rings for Polygon {
    fn contours(&self) -> Vec<Vec<Point>> {
        std::iter::once(self.exterior())
            .chain(self.interiors())
            .map(contour)
            .collect()
    }
}

impl Rings for MultiPolygon {
    fn contours(&self) -> Vec<Vec<Point>> {
        self.0.iter().flat_map(|p| p.contours()).collect()
    }
}

/// Union, intersection and difference of polygons (the names and results of geo's
/// `BooleanOps`).
///
/// ```
/// use furrow::geometry::BooleanOps;
/// use geo::{polygon, Area};
///
/// let a = polygon![(x: 0., y: 0.), (x: 10., y: 0.), (x: 10., y: 10.), (x: 0., y: 10.)];
/// let b = polygon![(x: 5., y: 5.), (x: 15., y: 5.), (x: 15., y: 15.), (x: 5., y: 15.)];
/// assert!((a.union(&b).unsigned_area() - 175.0).abs() < 1e-9);
/// assert!((a.intersection(&b).unsigned_area() - 25.0).abs() < 1e-9);
/// assert!((a.difference(&b).unsigned_area() - 75.0).abs() < 1e-9);
/// ```
pub trait BooleanOps: Rings {
    /// The area in both.
    fn intersection(&self, other: &impl Rings) -> MultiPolygon {
        overlay(self, other, OverlayRule::Intersect, FillRule::EvenOdd)
    }
    /// The area in either.
    fn union(&self, other: &impl Rings) -> MultiPolygon {
        overlay(self, other, OverlayRule::Union, FillRule::EvenOdd)
    }
    /// The area in `self` and not in `other`.
    fn difference(&self, other: &impl Rings) -> MultiPolygon {
        overlay(self, other, OverlayRule::Difference, FillRule::EvenOdd)
    }
    /// The area in `self` and in none of the parts of `other`, which may overlap one another
    /// (read by the non-zero rule: as their union, not where an even number of them overlap).
    fn difference_overlapping(&self, other: &impl Rings) -> MultiPolygon {
        overlay(self, other, OverlayRule::Difference, FillRule::NonZero)
    }
}

impl BooleanOps for Polygon {}
impl BooleanOps for MultiPolygon {}

fn overlay(
    subject: &(impl Rings + ?Sized),
    clip: &impl Rings,
    rule: OverlayRule,
    fill: FillRule,
) -> MultiPolygon {
    let (subject, clip) = (subject.contours(), clip.contours());
    let shapes = FloatOverlay::with_subj_and_clip_custom(
        &subject,
        &clip,
        OverlayOptions::ogc(),
        Solver::default(),
    )
    .overlay(rule, fill);
    multi_polygon(shapes)
}

/// `region` grown by `distance` metres (shrunk where it is negative), corners joined by arcs of
/// chords `join_step` radians apart.
///
/// ```
/// use furrow::geometry::buffer_region;
/// use geo::{polygon, Area, MultiPolygon};
///
/// let square = MultiPolygon::new(vec![polygon![(x: 0., y: 0.), (x: 10., y: 0.), (x: 10., y: 10.), (x: 0., y: 10.)]]);
/// assert!((buffer_region(&square, -2.0, 0.1).unsigned_area() - 36.0).abs() < 1e-9);
/// ```
pub fn buffer_region(region: &MultiPolygon, distance: f64, join_step: f64) -> MultiPolygon {
    let subject = region.orient(geo::orient::Direction::Default).contours();
    let style = OutlineStyle::new(distance).line_join(LineJoin::Round(join_step));
    multi_polygon(subject.outline(&style))
}

/// The points within `distance` metres of `line`, with round joins and ends of chords `step`
/// radians apart. A line of a single point is its disc; an empty line or a distance not above
/// zero gives nothing.
///
/// ```
/// use furrow::geometry::buffer_line;
/// use geo::{line_string, Area};
///
/// let band = buffer_line(&line_string![(x: 0., y: 0.), (x: 10., y: 0.)], 1.0, 0.05);
/// let expected = 20.0 + std::f64::consts::PI;
/// assert!((band.unsigned_area() - expected).abs() < 0.01);
/// ```
pub fn buffer_line(line: &LineString, distance: f64, step: f64) -> MultiPolygon {
    if distance.is_nan() || distance <= 0.0 {
        return MultiPolygon::new(vec![]);
    }
    let mut path: Vec<Point> = line.0.iter().map(|c| [c.x, c.y]).collect();
    path.dedup();
    match path.as_slice() {
        [] => MultiPolygon::new(vec![]),
        [c] => MultiPolygon::new(vec![disc(*c, distance, step)]),
        _ => {
            let style = StrokeStyle::new(2.0 * distance)
                .line_join(LineJoin::Round(step))
                .start_cap(LineCap::Round(step))
                .end_cap(LineCap::Round(step));
            multi_polygon(path.stroke(style, false))
        }
    }
}

/// A disc as a polygon of chords `step` radians apart.
fn disc(c: Point, radius: f64, step: f64) -> Polygon {
    let n = (std::f64::consts::TAU / step.max(0.01)).ceil().max(8.0) as usize;
    let ring = (0..=n)
        .map(|i| {
            let a = std::f64::consts::TAU * (i % n) as f64 / n as f64;
            Coord {
                x: c[0] + radius * a.cos(),
                y: c[1] + radius * a.sin(),
            }
        })
        .collect();
    Polygon::new(LineString::new(ring), vec![])
}

/// A ring as an open contour.
fn contour(ring: &LineString) -> Vec<Point> {
    let pts = match ring.0.split_last() {
        Some((last, rest)) if rest.first() == Some(last) => rest,
        _ => &ring.0[..],
    };
    pts.iter().map(|c| [c.x, c.y]).collect()
}

/// i_overlay's shapes (outer contour first, then holes; open) as polygons with closed rings.
fn multi_polygon(shapes: Shapes) -> MultiPolygon {
    let ring = |path: Vec<Point>| {
        let mut r = LineString::new(path.into_iter().map(|[x, y]| Coord { x, y }).collect());
        r.close();
        r
    };
    MultiPolygon::new(
        shapes
            .into_iter()
            .filter_map(|shape| {
                let mut rings = shape.into_iter().map(ring);
                let exterior = rings.next()?;
                Some(Polygon::new(exterior, rings.collect()))
            })
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{polygon, Area, Winding};

    fn square(x: f64, y: f64, side: f64) -> Polygon {
        polygon![(x: x, y: y), (x: x + side, y: y), (x: x + side, y: y + side), (x: x, y: y + side)]
    }

    #[test]
    fn results_are_in_the_ogc_form() {
        let ring = square(0.0, 0.0, 10.0).difference(&square(3.0, 3.0, 4.0));
        assert_eq!(ring.0.len(), 1);
        let p = &ring.0[0];
        assert!(p.exterior().is_ccw() && p.exterior().is_closed());
        assert!(p.interiors().len() == 1 && p.interiors()[0].is_cw());
        assert!((ring.unsigned_area() - 84.0).abs() < 1e-9);
    }

    #[test]
    fn parts_touching_at_a_point_stay_apart() {
        let two = MultiPolygon::new(vec![square(0.0, 0.0, 10.0), square(10.0, 10.0, 10.0)]);
        let u = two.union(&MultiPolygon::new(vec![]));
        assert_eq!(u.0.len(), 2);
        assert!((u.unsigned_area() - 200.0).abs() < 1e-9);
    }

    #[test]
    fn an_empty_operand_is_nothing() {
        let none = MultiPolygon::new(vec![]);
        assert!(square(0.0, 0.0, 1.0).intersection(&none).0.is_empty());
        assert!(none.difference(&square(0.0, 0.0, 1.0)).0.is_empty());
        assert!(none.union(&none).0.is_empty());
        assert!(buffer_region(&none, -1.0, 0.1).0.is_empty());
        assert!(buffer_region(&none, 1.0, 0.1).0.is_empty());
    }

    #[test]
    fn a_clockwise_region_is_buffered_as_its_area() {
        let cw = MultiPolygon::new(vec![polygon![
            (x: 0., y: 0.), (x: 0., y: 10.), (x: 10., y: 10.), (x: 10., y: 0.)
        ]]);
        assert!((buffer_region(&cw, -2.0, 0.1).unsigned_area() - 36.0).abs() < 1e-9);
        let grown = buffer_region(&cw, 1.0, 0.01).unsigned_area();
        assert!((grown - (100.0 + 40.0 + std::f64::consts::PI)).abs() < 0.01);
    }

    #[test]
    fn a_line_of_one_point_is_a_disc() {
        let band = buffer_line(&LineString::from(vec![(1.0, 1.0), (1.0, 1.0)]), 2.0, 0.05);
        assert!((band.unsigned_area() - 4.0 * std::f64::consts::PI).abs() < 0.02);
        assert!(buffer_line(&LineString::new(vec![]), 2.0, 0.05)
            .0
            .is_empty());
        assert!(
            buffer_line(&LineString::from(vec![(0.0, 0.0), (1.0, 0.0)]), 0.0, 0.05)
                .0
                .is_empty()
        );
    }

    /// The rest of a star-shaped field (parts touching at a point) less a block whose outline
    /// passes twice through that point: i_overlay 4.5 failed an index binding the result's holes.
    #[test]
    fn a_block_through_the_point_where_two_parts_touch_is_subtracted() {
        let rest = MultiPolygon::new(vec![
            polygon![
                (x: -1002.066082763713, y: 814.6288373125717),
                (x: -3230.372006225627, y: 682.9182736529037),
                (x: -1682.5447814941817, y: -333.4849093304947),
                (x: -1824.051823425334, y: -1261.440048490651),
                (x: -1074.876240539592, y: -1743.5678332196549),
                (x: -1418.4330032349044, y: -1522.4737856732681),
                (x: -1496.044468689006, y: -1472.5273592816666),
            ],
            polygon![
                (x: -592.4314010620528, y: 2711.2674939287826),
                (x: -1625.6982162475997, y: 2532.1080929888412),
                (x: -1002.066082763713, y: 814.6288373125717),
            ],
            polygon![
                (x: 1431.864680480916, y: 2359.57222720515),
                (x: 361.19076080318155, y: -2597.726585661061),
                (x: 511.50270385738077, y: -2575.605087553151),
                (x: 729.6351806640214, y: -891.8018954144791),
                (x: 3232.150515747029, y: -2660.505264555104),
                (x: 1264.4796249389237, y: -354.3109286176041),
                (x: 1874.0962936400956, y: 30.209426607005298),
                (x: 1155.9649612426347, y: 372.5445859087631),
                (x: 1280.603579711873, y: 949.4258114947006),
                (x: 1432.392916870076, y: 2360.010734285228),
            ],
        ]);
        let block = polygon![
            (x: -592.4314010620526, y: 2711.2674939287826),
            (x: -1090.108601281906, y: 2624.974633515139),
            (x: -1625.6982162475992, y: 2532.1080929888412),
            (x: -1611.8511459947406, y: 2493.973342333323),
            (x: -1531.1473721607317, y: 2271.715620236197),
            (x: -1213.5658059012342, y: 1397.0978403780666),
            (x: -1002.066082763713, y: 814.6288373125717),
            (x: -1632.0824815694036, y: 777.3898684044724),
            (x: -3129.1091141061347, y: 688.9037141879919),
            (x: -1307.3131432480977, y: -598.6874651230214),
            (x: -1092.4782892676046, y: 396.0136827936295),
            (x: -1002.066082763713, y: 814.6288373125717),
            (x: -920.9343654073865, y: 1190.2746463452618),
            (x: -799.1094405842396, y: 1754.3329941372726),
            (x: -768.1513113197757, y: 1897.6714059523815),
            (x: -762.839547439888, y: 1922.2652627702714),
            (x: -674.5091838163038, y: 2331.2413326321257),
        ];
        let left = rest.difference(&block);
        let expected = rest.unsigned_area() - rest.intersection(&block).unsigned_area();
        assert!((left.unsigned_area() - expected).abs() < 1e-3 * expected);
        // shapely: 56,094.2 + 356,095.4 + 2,029,357.1 square metres
        assert!((left.unsigned_area() - 2_441_546.75).abs() < 1.0);
    }
}
