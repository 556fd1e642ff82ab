//! Obstacle classes (Zhou et al. 2.2.2): how each obstacle shapes the plan.
//!
//! Relative to the driving direction, the working width `w`, the headland passes and a
//! threshold `r`:
//!
//! - **A**: the obstacle's extent across the driving direction (the side of its bounding box
//!   perpendicular to the swaths) is less than `r`: it is too small to split the field. Swaths
//!   run past it with the implement lifted over it ([`crate::swath::lifts`]).
//! - **C**: closer than `w` to another obstacle (not of class A): the strip between them is too
//!   narrow to work, so they are merged into their convex hull, which is then handled as one
//!   obstacle (class D, or B if it lies near the boundary).
//! - **B**: its headland would reach the inner boundary of the field: closer to a boundary edge
//!   than its own headland width plus that edge's. It is merged into the field's headland, which
//!   runs around it; the inner field is not split by it.
//! - **D**: every other obstacle: it gets its own headland passes and splits the field body.
//!
//! B, C (as merged groups) and D obstacles are holes in the region the headlands are measured
//! from ([`crate::headland::build`]); A obstacles are not.

use crate::field::Field;
use crate::geometry::{point_segment_distance, polygons_within, SweepFrame};
use crate::headland::offset::drop_slivers;
use crate::sort::SharedSort;
use geo::{BooleanOps, ConvexHull, Coord, MultiPolygon, Polygon};
use serde::Serialize;

/// The class of an obstacle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
pub enum ObstacleClass {
    /// Small across the driving direction: swaths run past it with the implement lifted.
    A,
    /// Near the boundary: merged into the field headland.
    B,
    /// Close to another obstacle: merged with it.
    C,
    /// Its own headland, splitting the field.
    D,
}

impl ObstacleClass {
    /// The class's letter, as in the plan output.
    pub fn as_str(self) -> &'static str {
        match self {
            ObstacleClass::A => "A",
            ObstacleClass::B => "B",
            ObstacleClass::C => "C",
            ObstacleClass::D => "D",
        }
    }
}

/// An obstacle, or a merged group of them, that the headland runs around.
#[derive(Debug, Clone)]
pub struct ObstacleHole {
    /// Its outline, clipped to the field (a merged group is their convex hull).
    pub shape: MultiPolygon,
    /// The obstacles it stands for (indices into [`Field::obstacles`]).
    pub members: Vec<usize>,
    /// How it is handled: B (merged into the field headland) or D (its own headland).
    pub handled_as: ObstacleClass,
}

/// The classes of a field's obstacles.
#[derive(Debug, Clone, Default)]
pub struct ObstacleClasses {
    /// The class of each obstacle of the field, in [`Field::obstacles`] order.
    pub class: Vec<ObstacleClass>,
    /// For each obstacle, the hole it belongs to (`None` for class A).
    pub hole_of: Vec<Option<usize>>,
    /// The holes the headland runs around.
    pub holes: Vec<ObstacleHole>,
}

impl ObstacleClasses {
    /// The outlines of the holes, as polygons.
    pub fn hole_polygons(&self) -> Vec<Polygon> {
        self.holes
            .iter()
            .flat_map(|h| h.shape.0.iter().cloned())
            .collect()
    }

    /// Number of obstacles of a class.
    pub fn count(&self, class: ObstacleClass) -> usize {
        self.class.iter().filter(|&&c| c == class).count()
    }
}

/// What the classification depends on.
#[derive(Debug, Clone, Copy)]
pub struct ClassSettings<'a> {
    /// The swath direction, compass radians.
    pub bearing: f64,
    /// Working width, metres.
    pub width: f64,
    /// Obstacles narrower than this across the driving direction are class A, metres.
    pub threshold: f64,
    /// Headland passes around an obstacle.
    pub obstacle_passes: u32,
    /// Headland passes along each edge of the boundary's outer ring.
    pub edge_passes: &'a [u32],
}

/// Classifies the obstacles of a field.
///
/// ```
/// use furrow::obstacles::{classify, ClassSettings, ObstacleClass};
/// use furrow::field::Field;
///
/// // A 400 x 300 m field (metric coordinates) with a 2 m pole and a 40 m pond.
/// let text = r#"{"type": "Polygon", "coordinates": [
///     [[0, 0], [400, 0], [400, 300], [0, 300], [0, 0]],
///     [[100, 100], [100, 102], [102, 102], [102, 100], [100, 100]],
///     [[200, 100], [200, 140], [240, 140], [240, 100], [200, 100]]]}"#;
/// let (field, _) = Field::from_geojson_str_in(text, furrow::field::Coordinates::Metric)?;
/// let settings = ClassSettings { bearing: 0.0, width: 6.0, threshold: 6.0, obstacle_passes: 2, edge_passes: &[2, 2, 2, 2] };
/// let classes = classify(&field, &settings);
/// assert_eq!(classes.class, vec![ObstacleClass::A, ObstacleClass::D]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn classify(field: &Field, s: &ClassSettings) -> ObstacleClasses {
    let n = field.obstacles.len();
    let frame = SweepFrame::new(s.bearing);
    let mut class = vec![ObstacleClass::D; n];
    for (i, o) in field.obstacles.iter().enumerate() {
        let mut range: Option<(f64, f64)> = None;
        for &c in &o.polygon.exterior().0 {
            let (x, _) = frame.project(c);
            range = Some(range.map_or((x, x), |(lo, hi)| (lo.min(x), hi.max(x))));
        }
        if range.is_some_and(|(lo, hi)| hi - lo < s.threshold) {
            class[i] = ObstacleClass::A;
        }
    }

    // Groups of obstacles (not A) closer than the width, merged into their hulls until no two
    // groups are that close.
    let mut groups: Vec<(Vec<usize>, Polygon)> = (0..n)
        .filter(|&i| class[i] != ObstacleClass::A)
        .map(|i| (vec![i], field.obstacles[i].polygon.clone()))
        .collect();
    loop {
        let mut merged = false;
        'pairs: for a in 0..groups.len() {
            for b in a + 1..groups.len() {
                if polygons_within(&groups[a].1, &groups[b].1, s.width) {
                    let (members_b, _) = groups.remove(b);
                    let members = &mut groups[a].0;
                    members.extend(members_b);
                    members.shared_sort_unstable_by(Ord::cmp);
                    let hull = MultiPolygon::new(
                        members
                            .iter()
                            .map(|&i| field.obstacles[i].polygon.clone())
                            .collect(),
                    )
                    .convex_hull();
                    groups[a].1 = hull;
                    merged = true;
                    break 'pairs;
                }
            }
        }
        if !merged {
            break;
        }
    }

    let ring = &field.boundary.exterior().0;
    let mut hole_of = vec![None; n];
    let mut holes = Vec::with_capacity(groups.len());
    for (members, polygon) in groups {
        let shape = if members.len() > 1 {
            // The hull of obstacles in a concave field may reach outside it.
            drop_slivers(polygon.intersection(&field.boundary))
        } else {
            MultiPolygon::new(vec![polygon])
        };
        let near_boundary = ring.windows(2).enumerate().any(|(e, edge)| {
            let reach =
                (s.obstacle_passes + s.edge_passes.get(e).copied().unwrap_or(0)) as f64 * s.width;
            reach > 0.0 && distance_to_segment(&shape, edge[0], edge[1]) < reach
        });
        let handled_as = if near_boundary {
            ObstacleClass::B
        } else {
            ObstacleClass::D
        };
        for &i in &members {
            hole_of[i] = Some(holes.len());
            class[i] = if members.len() > 1 {
                ObstacleClass::C
            } else {
                handled_as
            };
        }
        holes.push(ObstacleHole {
            shape,
            members,
            handled_as,
        });
    }
    ObstacleClasses {
        class,
        hole_of,
        holes,
    }
}

/// Distance from a shape inside the field to a boundary edge.
fn distance_to_segment(shape: &MultiPolygon, a: Coord, b: Coord) -> f64 {
    let mut best = f64::INFINITY;
    for p in &shape.0 {
        for s in p.exterior().0.windows(2) {
            best = best
                .min(point_segment_distance(s[0], a, b))
                .min(point_segment_distance(a, s[0], s[1]))
                .min(point_segment_distance(b, s[0], s[1]));
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::field::{Frame, Obstacle};
    use geo::polygon;

    fn square(x: f64, y: f64, side: f64) -> Polygon {
        polygon![(x: x, y: y), (x: x + side, y: y), (x: x + side, y: y + side), (x: x, y: y + side)]
    }

    fn field(obstacles: Vec<Polygon>) -> Field {
        Field {
            boundary: square(0.0, 0.0, 500.0),
            drawn_boundary: vec![],
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
            entrance: None,
            reference_line: None,
        }
    }

    fn settings(bearing: f64) -> ClassSettings<'static> {
        ClassSettings {
            bearing,
            width: 6.0,
            threshold: 6.0,
            obstacle_passes: 2,
            edge_passes: &[2, 2, 2, 2],
        }
    }

    #[test]
    fn one_of_each_class() {
        let f = field(vec![
            square(100.0, 100.0, 3.0),  // a pole
            square(470.0, 200.0, 20.0), // 10 m from the eastern edge
            square(200.0, 300.0, 30.0), // two ponds 4 m apart
            square(234.0, 300.0, 30.0),
            square(250.0, 100.0, 60.0), // a wood in the middle
        ]);
        let c = classify(&f, &settings(0.0));
        use ObstacleClass::*;
        assert_eq!(c.class, vec![A, B, C, C, D]);
        assert_eq!(c.holes.len(), 3);
        assert_eq!(c.hole_of[2], c.hole_of[3]);
        assert_eq!(c.hole_of[0], None);
        // The merged ponds are one 64 x 30 hole.
        let merged = &c.holes[c.hole_of[2].unwrap()];
        assert!((geo::Area::unsigned_area(&merged.shape) - 64.0 * 30.0).abs() < 1e-6);
        assert_eq!(merged.handled_as, D);
    }

    #[test]
    fn class_a_depends_on_the_driving_direction() {
        // A fence 2 m wide and 50 m long running north: small across a northward drive only.
        let f = field(vec![
            polygon![(x: 100., y: 100.), (x: 102., y: 100.), (x: 102., y: 150.), (x: 100., y: 150.)],
        ]);
        assert_eq!(classify(&f, &settings(0.0)).class, vec![ObstacleClass::A]);
        assert_eq!(
            classify(&f, &settings(90f64.to_radians())).class,
            vec![ObstacleClass::D]
        );
    }

    #[test]
    fn without_headland_nothing_is_class_b() {
        let f = field(vec![square(470.0, 200.0, 20.0)]);
        let s = ClassSettings {
            obstacle_passes: 0,
            edge_passes: &[0, 0, 0, 0],
            ..settings(0.0)
        };
        assert_eq!(classify(&f, &s).class, vec![ObstacleClass::D]);
    }
}
