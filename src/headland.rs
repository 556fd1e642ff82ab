//! Headlands: the passes driven around the field boundary, where the machine turns at the ends
//! of the swaths, and the inner field they leave for the swaths.
//!
//! Pass `k` (1 = outermost) of `h` passes of width `w` has its centre line `(k - 1/2)·w` inside
//! the boundary; the inner field starts `h·w` inside (Fields2Cover's constant-width headland,
//! Zhou et al. 2.2.1). The offsets are geo's inward buffer with round joins, so where the
//! boundary has a reflex corner the passes round it instead of crossing themselves, and where a
//! narrow neck closes up an offset splits into several parts (each its own closed pass).

use crate::error::{ErrorCode, PlanError};
use crate::field::Field;
use geo::algorithm::buffer::{BufferStyle, LineJoin};
use geo::{Area, BooleanOps, Buffer, LineString, MultiPolygon, Polygon};

/// Offset parts smaller than this (square metres) are slivers of the buffer and are dropped.
const MIN_PART_AREA_M2: f64 = 1e-2;

/// One headland pass: a closed path around the field (or one part of it) at a constant distance
/// inside the boundary.
#[derive(Debug, Clone, PartialEq)]
pub struct HeadlandPass {
    /// Which pass this is, counted from the boundary inwards: 1 is the outermost.
    pub index: usize,
    /// Its centre line, closed (first point repeated at the end) and counter-clockwise.
    pub ring: LineString,
}

/// The headland passes of a field and the inner field they leave.
#[derive(Debug, Clone)]
pub struct Headlands {
    /// The passes, outermost first; a pass that splits at a neck gives several entries with the
    /// same index.
    pub passes: Vec<HeadlandPass>,
    /// The inner field: the area inside the innermost headland and outside the obstacles, where
    /// the swaths go. Possibly several parts.
    pub inner: MultiPolygon,
    /// Area between the boundary and the inner boundary, square metres.
    pub area_m2: f64,
}

/// Cuts `passes` headland passes of width `width` (metres) off the field.
///
/// ```
/// use furrow::field::Field;
/// use furrow::headland::constant_width;
///
/// // A rectangle of about 333 m by 112 m.
/// let text = r#"{"type": "Polygon", "coordinates": [[[24.05, 60.25], [24.056, 60.25],
///     [24.056, 60.251], [24.05, 60.251], [24.05, 60.25]]]}"#;
/// let (field, _) = Field::from_geojson_str(text)?;
/// let headlands = constant_width(&field, 6.0, 2)?;
/// assert_eq!(headlands.passes.len(), 2);
/// // The headland is a 12 m wide band around the field.
/// let perimeter = 2.0 * (333.0 + 111.5);
/// assert!((headlands.area_m2 / (12.0 * perimeter) - 1.0).abs() < 0.06);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn constant_width(field: &Field, width: f64, passes: u32) -> Result<Headlands, PlanError> {
    let boundary = &field.boundary;
    let mut out = Vec::with_capacity(passes as usize);
    for k in 1..=passes as usize {
        let offset = (k as f64 - 0.5) * width;
        for part in inset(boundary, offset).0 {
            out.push(HeadlandPass {
                index: k,
                ring: part.exterior().clone(),
            });
        }
    }
    let inset_field = if passes == 0 {
        MultiPolygon::new(vec![boundary.clone()])
    } else {
        inset(boundary, passes as f64 * width)
    };
    if inset_field.0.is_empty() {
        return Err(PlanError::new(
            ErrorCode::HeadlandConsumesField,
            format!(
                "{passes} headland passes of {width} m take up the whole field; use fewer passes or a narrower width"
            ),
        )
        .at_feature(field.feature));
    }
    let area_m2 = (boundary.unsigned_area() - inset_field.unsigned_area()).max(0.0);
    let inner = if field.obstacles.is_empty() {
        inset_field
    } else {
        let obstacles =
            MultiPolygon::new(field.obstacles.iter().map(|o| o.polygon.clone()).collect());
        drop_slivers(inset_field.difference(&obstacles))
    };
    if inner.0.is_empty() {
        return Err(PlanError::new(
            ErrorCode::HeadlandConsumesField,
            "the obstacles cover the whole field inside the headland",
        )
        .at_feature(field.feature));
    }
    Ok(Headlands {
        passes: out,
        inner,
        area_m2,
    })
}

/// The largest gap (metres) between a rounded corner of an offset and the true circular arc.
const ARC_TOLERANCE_M: f64 = 1e-3;

/// The part of a polygon at least `distance` metres inside its boundary.
///
/// Round joins are approximated by chords; their step is chosen so that no chord comes closer
/// than [`ARC_TOLERANCE_M`] to the arc (geo's default step leaves 4.5 cm at 9 m).
fn inset(polygon: &Polygon, distance: f64) -> MultiPolygon {
    // A chord of angle a on radius r falls short of the arc by r (1 - cos(a / 2)).
    let step = 2.0 * (1.0 - ARC_TOLERANCE_M / distance.max(ARC_TOLERANCE_M)).acos();
    let style = BufferStyle::new(-distance).line_join(LineJoin::Round(step.clamp(0.01, 0.2)));
    drop_slivers(polygon.buffer_with_style(style))
}

fn drop_slivers(m: MultiPolygon) -> MultiPolygon {
    MultiPolygon::new(
        m.0.into_iter()
            .filter(|p| p.unsigned_area() >= MIN_PART_AREA_M2)
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::field::{Frame, Obstacle};
    use geo::{coord, polygon, Distance, Euclidean, Point};

    fn field(boundary: Polygon, obstacles: Vec<Polygon>) -> Field {
        Field {
            boundary,
            obstacles: obstacles
                .into_iter()
                .map(|polygon| Obstacle {
                    polygon,
                    feature: 1,
                    name: None,
                })
                .collect(),
            prohibited: vec![],
            name: None,
            feature: 0,
            frame: Frame::Metric,
        }
    }

    fn rectangle(w: f64, h: f64) -> Polygon {
        polygon![(x: 0., y: 0.), (x: w, y: 0.), (x: w, y: h), (x: 0., y: h)]
    }

    #[test]
    fn pass_centre_lines_are_at_half_widths() {
        let f = field(rectangle(200.0, 100.0), vec![]);
        let h = constant_width(&f, 6.0, 3).unwrap();
        assert_eq!(h.passes.len(), 3);
        let boundary = f.boundary.exterior();
        for pass in &h.passes {
            let expected = (pass.index as f64 - 0.5) * 6.0;
            for &c in &pass.ring.0 {
                let d = Euclidean.distance(&Point(c), boundary);
                assert!((d - expected).abs() < 1e-6, "pass {} at {d}", pass.index);
            }
        }
        // Inner field: 200 - 36 by 100 - 36.
        assert!((h.inner.unsigned_area() - 164.0 * 64.0).abs() < 1e-6);
        assert!((h.area_m2 - (200.0 * 100.0 - 164.0 * 64.0)).abs() < 1e-6);
    }

    #[test]
    fn no_passes_leaves_the_whole_field() {
        let f = field(rectangle(50.0, 50.0), vec![]);
        let h = constant_width(&f, 6.0, 0).unwrap();
        assert!(h.passes.is_empty());
        assert_eq!(h.area_m2, 0.0);
        assert!((h.inner.unsigned_area() - 2500.0).abs() < 1e-9);
    }

    #[test]
    fn obstacles_are_cut_out_of_the_inner_field() {
        let obstacle =
            polygon![(x: 40., y: 40.), (x: 60., y: 40.), (x: 60., y: 60.), (x: 40., y: 60.)];
        let f = field(rectangle(100.0, 100.0), vec![obstacle]);
        let h = constant_width(&f, 5.0, 1).unwrap();
        assert!((h.inner.unsigned_area() - (90.0 * 90.0 - 400.0)).abs() < 1e-6);
    }

    #[test]
    fn too_many_passes_consume_the_field() {
        let f = field(rectangle(30.0, 20.0), vec![]);
        let e = constant_width(&f, 6.0, 2).unwrap_err();
        assert_eq!(e.code, ErrorCode::HeadlandConsumesField);
    }

    #[test]
    fn a_narrow_neck_splits_the_inner_field() {
        // Two 60 m squares joined by a 10 m wide neck: 2 passes of 4 m close the neck.
        let dumbbell = Polygon::new(
            LineString::from(vec![
                coord! { x: 0., y: 0. },
                coord! { x: 60., y: 0. },
                coord! { x: 60., y: 25. },
                coord! { x: 80., y: 25. },
                coord! { x: 80., y: 0. },
                coord! { x: 140., y: 0. },
                coord! { x: 140., y: 60. },
                coord! { x: 80., y: 60. },
                coord! { x: 80., y: 35. },
                coord! { x: 60., y: 35. },
                coord! { x: 60., y: 60. },
                coord! { x: 0., y: 60. },
            ]),
            vec![],
        );
        let f = field(dumbbell, vec![]);
        let h = constant_width(&f, 4.0, 2).unwrap();
        assert_eq!(h.inner.0.len(), 2);
        // Pass 1 (2 m in) still goes through the neck; pass 2 (6 m in) does not.
        assert_eq!(h.passes.iter().filter(|p| p.index == 1).count(), 1);
        assert_eq!(h.passes.iter().filter(|p| p.index == 2).count(), 2);
    }
}
