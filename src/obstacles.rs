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
use crate::geometry::BooleanOps;
use crate::geometry::{point_segment_distance, polygons_within, IndexedSegment, SweepFrame};
use crate::headland::offset::drop_slivers;
use crate::sort::SharedSort;
use geo::{BoundingRect, ConvexHull, Coord, MultiPolygon, Polygon};
use rstar::{Envelope, RTree, RTreeObject, AABB};
use serde::Serialize;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// The class of an obstacle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
pub enum ObstacleClass {
    /// Small across the driving direction: swaths and headland passes run past it with the implement lifted.
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

    let not_a: Vec<usize> = (0..n).filter(|&i| class[i] != ObstacleClass::A).collect();
    let groups = close_groups(field, &not_a, s.width);

    // The boundary's edges, indexed: an obstacle's headland reaches at most this far.
    let ring = &field.boundary.exterior().0;
    let most_edge_passes = s.edge_passes.iter().copied().max().unwrap_or(0);
    let farthest = (s.obstacle_passes + most_edge_passes) as f64 * s.width;
    let edges = RTree::bulk_load(
        ring.windows(2)
            .enumerate()
            .map(|(e, w)| IndexedSegment::new(w[0], w[1], 0, e))
            .collect(),
    );
    let mut hole_of = vec![None; n];
    let mut holes = Vec::with_capacity(groups.len());
    for (members, polygon) in groups {
        let shape = if members.len() > 1 {
            // The hull of obstacles in a concave field may reach outside it.
            drop_slivers(polygon.intersection(&field.boundary))
        } else {
            MultiPolygon::new(vec![polygon])
        };
        let near_boundary = shape.bounding_rect().is_some_and(|r| {
            edges
                .locate_in_envelope_intersecting(&grown_box(r, farthest))
                .any(|edge| {
                    let e = edge.index;
                    let reach = (s.obstacle_passes + s.edge_passes.get(e).copied().unwrap_or(0))
                        as f64
                        * s.width;
                    reach > 0.0 && distance_to_segment(&shape, edge.a, edge.b) < reach
                })
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

/// Groups of the obstacles `which` (not A) closer than `width`, merged into their convex hulls
/// until no two groups are that close: the first pair in order (the group of the lowest place
/// with a partner, and its first partner after it) merged first, the merged group in the
/// place of the first, as one would find by looking at every pair again after each merge.
///
/// The groups' boxes are in an R-tree (a merged group's box added anew), so that a group is
/// weighed only against those whose boxes come within `width` of its own: `polygons_within`
/// says no to all others. After a merge only the grown group can have new partners: it is
/// looked at again, and so is each group before it whose box its new hull comes near.
fn close_groups(field: &Field, which: &[usize], width: f64) -> Vec<(Vec<usize>, Polygon)> {
    let mut groups: Vec<Option<(Vec<usize>, Polygon)>> = which
        .iter()
        .map(|&i| Some((vec![i], field.obstacles[i].polygon.clone())))
        .collect();
    // The version of each group's box: a box in the tree of an older version is stale.
    let mut version = vec![0usize; groups.len()];
    let boxed = |g: usize, p: &Polygon, v: usize| {
        p.bounding_rect()
            .map(|r| IndexedSegment::new(r.min(), r.max(), g, v))
    };
    let mut tree = RTree::bulk_load(
        groups
            .iter()
            .enumerate()
            .filter_map(|(g, x)| x.as_ref().and_then(|(_, p)| boxed(g, p, 0)))
            .collect(),
    );
    // Boxes of merged groups since the tree was built: looked through one by one, and put in the
    // tree by building it anew once there are many (rstar's insertion would bring its own sorts
    // of nodes into the WebAssembly module).
    let mut added: Vec<IndexedSegment> = Vec::new();
    // The groups near a polygon (boxes within `width`, with a margin for rounding), in order.
    let near = |tree: &RTree<IndexedSegment>,
                added: &[IndexedSegment],
                groups: &[Option<(Vec<usize>, Polygon)>],
                version: &[usize],
                p: &Polygon| {
        let mut found: Vec<usize> = p.bounding_rect().map_or(Vec::new(), |r| {
            let envelope = grown_box(r, width * (1.0 + 1e-9) + 1e-9);
            tree.locate_in_envelope_intersecting(&envelope)
                .chain(added.iter().filter(|b| envelope.intersects(&b.envelope())))
                .filter(|b| groups[b.line].is_some() && version[b.line] == b.index)
                .map(|b| b.line)
                .collect()
        });
        found.shared_sort_unstable_by(Ord::cmp);
        found.dedup();
        found
    };
    let mut pending = Pending::all(groups.len());
    while let Some(a) = pending.pop_first() {
        let Some((_, polygon)) = &groups[a] else {
            continue;
        };
        let partner = near(&tree, &added, &groups, &version, polygon)
            .into_iter()
            .filter(|&b| b > a)
            .find(|&b| {
                groups[b]
                    .as_ref()
                    .is_some_and(|(_, q)| polygons_within(polygon, q, width))
            });
        let Some(b) = partner else {
            continue;
        };
        let Some((members_b, _)) = groups[b].take() else {
            continue;
        };
        pending.remove(b);
        let Some((members, _)) = &mut groups[a] else {
            continue;
        };
        members.extend(members_b);
        members.shared_sort_unstable_by(Ord::cmp);
        let hull = hull_of(field, members);
        version[a] += 1;
        if let Some(e) = boxed(a, &hull, version[a]) {
            added.push(e);
        }
        if added.len() > REBUILD_AFTER {
            let current =
                |b: &&IndexedSegment| groups[b.line].is_some() && version[b.line] == b.index;
            let boxes = tree
                .iter()
                .filter(current)
                .chain(added.iter().filter(current))
                .copied()
                .collect();
            tree = RTree::bulk_load(boxes);
            added.clear();
        }
        pending.insert(a);
        for c in near(&tree, &added, &groups, &version, &hull) {
            if c < a {
                pending.insert(c);
            }
        }
        if let Some((_, p)) = &mut groups[a] {
            *p = hull;
        }
    }
    groups.into_iter().flatten().collect()
}

/// The convex hull of a group of obstacles.
fn hull_of(field: &Field, members: &[usize]) -> Polygon {
    MultiPolygon::new(
        members
            .iter()
            .map(|&i| field.obstacles[i].polygon.clone())
            .collect(),
    )
    .convex_hull()
}

/// The groups still to be looked at, smallest index first: a min-heap of indices with a mark for
/// each, a removed index left in the heap and passed over when it comes up. (A `BTreeSet` does
/// the same, with 13 KB more of WebAssembly: its tree and the sort of its first collection.)
struct Pending {
    heap: BinaryHeap<Reverse<usize>>,
    marked: Vec<bool>,
}

impl Pending {
    /// Every index below `n`.
    fn all(n: usize) -> Self {
        Pending {
            heap: (0..n).map(Reverse).collect(),
            marked: vec![true; n],
        }
    }

    /// The smallest index still pending, taken out.
    fn pop_first(&mut self) -> Option<usize> {
        while let Some(Reverse(i)) = self.heap.pop() {
            if std::mem::take(&mut self.marked[i]) {
                return Some(i);
            }
        }
        None
    }

    fn insert(&mut self, i: usize) {
        if !self.marked[i] {
            self.marked[i] = true;
            self.heap.push(Reverse(i));
        }
    }

    fn remove(&mut self, i: usize) {
        self.marked[i] = false;
    }
}

/// How many merged groups' boxes are looked through one by one before the groups' R-tree is
/// built anew.
const REBUILD_AFTER: usize = 64;

/// A box grown by `d` on every side, as the R-trees' envelope.
fn grown_box(r: geo::Rect, d: f64) -> AABB<[f64; 2]> {
    AABB::from_corners(
        [r.min().x - d, r.min().y - d],
        [r.max().x + d, r.max().y + d],
    )
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

    #[test]
    fn pending_gives_the_smallest_index_still_pending_as_a_sorted_set_would() {
        let mut pending = Pending::all(6);
        let mut reference: std::collections::BTreeSet<usize> = (0..6).collect();
        // Pops, removals and insertions, some of indices removed before or already pending.
        let steps: [(char, usize); 12] = [
            ('p', 0),
            ('r', 3),
            ('i', 1),
            ('i', 1),
            ('p', 0),
            ('r', 1),
            ('i', 3),
            ('p', 0),
            ('i', 0),
            ('r', 5),
            ('p', 0),
            ('p', 0),
        ];
        for (step, i) in steps {
            match step {
                'p' => assert_eq!(pending.pop_first(), reference.pop_first()),
                'r' => {
                    pending.remove(i);
                    reference.remove(&i);
                }
                _ => {
                    pending.insert(i);
                    reference.insert(i);
                }
            }
        }
        while let Some(i) = reference.pop_first() {
            assert_eq!(pending.pop_first(), Some(i));
        }
        assert_eq!(pending.pop_first(), None);
    }

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

    /// The grouping as it was first written: every pair looked at again after each merge.
    fn close_groups_by_pairs(
        field: &Field,
        which: &[usize],
        width: f64,
    ) -> Vec<(Vec<usize>, Polygon)> {
        let mut groups: Vec<(Vec<usize>, Polygon)> = which
            .iter()
            .map(|&i| (vec![i], field.obstacles[i].polygon.clone()))
            .collect();
        'again: loop {
            for a in 0..groups.len() {
                for b in a + 1..groups.len() {
                    if polygons_within(&groups[a].1, &groups[b].1, width) {
                        let (members_b, _) = groups.remove(b);
                        let members = &mut groups[a].0;
                        members.extend(members_b);
                        members.sort_unstable();
                        groups[a].1 = hull_of(field, members);
                        continue 'again;
                    }
                }
            }
            return groups;
        }
    }

    #[test]
    fn groups_are_those_of_looking_at_every_pair_after_each_merge() {
        use crate::rng::SplitMix64 as Rng;
        // Obstacles of 2 to 12 m, thin bars among them (whose hulls reach past their
        // neighbours), strewn over the field: groups of one, chains, and hulls that take in
        // obstacles none of their members was near.
        // The last fields are crowded: more merges than the groups' R-tree takes before it is
        // built anew.
        let (mut chains, mut most_merges) = (0, 0);
        for seed in 0..20 {
            let mut rng = Rng::new(seed);
            let count = if seed < 17 { 60 } else { 240 };
            let obstacles: Vec<Polygon> = (0..count)
                .map(|_| {
                    let (x, y) = (20.0 + 400.0 * rng.unit(), 20.0 + 400.0 * rng.unit());
                    let (w, h) = if rng.below(4) == 0 {
                        (60.0 * rng.unit() + 2.0, 2.0)
                    } else {
                        let side = 2.0 + 10.0 * rng.unit();
                        (side, side)
                    };
                    polygon![(x: x, y: y), (x: x + w, y: y), (x: x + w, y: y + h), (x: x, y: y + h)]
                })
                .collect();
            let f = field(obstacles);
            let which: Vec<usize> = (0..f.obstacles.len()).filter(|i| i % 7 != 3).collect();
            let width = 5.0 + 25.0 * rng.unit();
            let expected = close_groups_by_pairs(&f, &which, width);
            let got = close_groups(&f, &which, width);
            assert_eq!(got.len(), expected.len(), "seed {seed}");
            for ((gm, gp), (em, ep)) in got.iter().zip(&expected) {
                assert_eq!(gm, em, "seed {seed}");
                assert_eq!(gp, ep, "seed {seed}");
            }
            chains += usize::from(expected.iter().any(|(m, _)| m.len() > 2));
            most_merges = most_merges.max(which.len() - got.len());
        }
        assert!(chains >= 10, "{chains} fields with groups of three or more");
        assert!(
            most_merges > REBUILD_AFTER,
            "at most {most_merges} merges in a field"
        );
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
