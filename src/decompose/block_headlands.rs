//! Headlands between blocks, only where they are needed (Oksanen & Visala 2.7).
//!
//! Where two blocks of a decomposition meet, the machine working one of them turns at the end
//! of its swaths on the other block. That needs no headland of its own when the border runs
//! along the other block's swaths (one block's end lies along the other's parallel side: the
//! turns are made on the neighbour's first or last swath, worked before or after), nor when
//! it runs nearly along the block's own swaths (an end within [`END_TOLERANCE_DEG`] of the
//! swath direction, where the swath lines are bent along it instead). Split and merge
//! chooses blocks so that almost every border is of the first kind; the others (typically
//! the border of a prohibited region, where the block outside it ends and the block inside
//! ends too) get `passes` headland passes along the border, cut from one of the two blocks:
//! the one in which driving along the border is allowed, the later one when both allow it.

use super::BlockArea;
use crate::field::ProhibitedRegion;
use crate::geometry::BooleanOps;
use crate::geometry::{bearing_of, clip_segment, swath_direction, BearingRange};
use crate::geometry::{Extremes, PlanarHypot};
use crate::headland::{HeadlandPass, PassAround};
use geo::{Area, BoundingRect, Coord, Intersects, LineString, MultiPolygon, Polygon};
use std::f64::consts::PI;

/// A block end within this many degrees of its swath direction needs no headland (Oksanen &
/// Visala: "e.g. below 15 degrees").
pub const END_TOLERANCE_DEG: f64 = 15.0;

/// Points closer than this (metres) to a line lie on it.
const ON_EDGE_M: f64 = 1e-3;

/// The blocks with the headland bands between them cut out, and the passes in those bands.
#[derive(Debug, Clone)]
pub struct BlockHeadlands {
    /// The blocks, less the bands.
    pub blocks: Vec<BlockArea>,
    /// The passes along the borders that need them, open lines.
    pub passes: Vec<HeadlandPass>,
    /// The bands cut out of the blocks, where the passes run.
    pub bands: MultiPolygon,
}

/// A stretch of border two blocks share.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Border {
    /// The earlier block (index).
    pub first: usize,
    /// The later block.
    pub second: usize,
    /// Its ends.
    pub from: Coord,
    /// Its ends.
    pub to: Coord,
}

impl Border {
    /// Its swath direction (compass radians in `[0, π)`).
    pub fn bearing(&self) -> f64 {
        swath_direction(bearing_of(self.from, self.to))
    }

    /// Its length, metres.
    pub fn length(&self) -> f64 {
        (self.to.x - self.from.x).planar_hypot(self.to.y - self.from.y)
    }
}

/// The angle (radians, in `[0, π/2]`) between two swath directions.
fn angle_between(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(PI);
    d.min(PI - d)
}

/// The stretches of border the blocks share, each straight, between pairs of blocks that share
/// at least `min_length` metres in all.
pub fn borders(blocks: &[BlockArea], min_length: f64) -> Vec<Border> {
    // Each edge with its box grown by twice the tolerance: edges that share a stretch of border
    // lie within the tolerance of each other, so their grown boxes meet.
    let reach = 2.0 * ON_EDGE_M;
    let edges: Vec<Vec<(Coord, Coord, [f64; 4])>> = blocks
        .iter()
        .map(|b| {
            b.area
                .0
                .iter()
                .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
                .flat_map(|r| r.lines().map(|l| (l.start, l.end)))
                .map(|(a, b)| {
                    let grown = [
                        a.x.lesser(b.x) - reach,
                        a.y.lesser(b.y) - reach,
                        a.x.greater(b.x) + reach,
                        a.y.greater(b.y) + reach,
                    ];
                    (a, b, grown)
                })
                .collect()
        })
        .collect();
    let apart =
        |x: &[f64; 4], y: &[f64; 4]| x[0] > y[2] || y[0] > x[2] || x[1] > y[3] || y[1] > x[3];
    let boxes: Vec<_> = blocks.iter().map(|b| b.area.bounding_rect()).collect();
    let mut out = Vec::new();
    // The edges of each of a pair of blocks that reach into the other's box, in ring order.
    let (mut near_i, mut near_j) = (Vec::new(), Vec::new());
    let within = |edges: &[(Coord, Coord, [f64; 4])], other: geo::Rect, near: &mut Vec<_>| {
        let grown = [
            other.min().x - reach,
            other.min().y - reach,
            other.max().x + reach,
            other.max().y + reach,
        ];
        near.clear();
        near.extend(edges.iter().filter(|e| !apart(&e.2, &grown)).copied());
    };
    for j in 0..blocks.len() {
        for i in 0..j {
            let (Some(box_i), Some(box_j)) = (boxes[i], boxes[j]) else {
                continue;
            };
            if !box_i.intersects(&box_j) {
                continue;
            }
            within(&edges[i], box_j, &mut near_i);
            within(&edges[j], box_i, &mut near_j);
            let first = out.len();
            for &(a, b, a_box) in &near_j {
                let d = b - a;
                let len = d.x.planar_hypot(d.y);
                if len < ON_EDGE_M {
                    continue;
                }
                let u = d / len;
                for &(p, q, p_box) in &near_i {
                    if apart(&a_box, &p_box) {
                        continue;
                    }
                    if let Some((from, to)) = shared_stretch(a, u, len, p, q) {
                        out.push(Border {
                            first: i,
                            second: j,
                            from,
                            to,
                        });
                    }
                }
            }
            let shared: f64 = out[first..].iter().map(Border::length).sum();
            if shared < min_length {
                out.truncate(first);
            }
        }
    }
    out
}

/// The stretch of the edge from `a` (unit direction `u`, `len` metres long) that the edge
/// `p`-`q` lies along: both of its ends within the tolerance of the edge's line, and overlapping
/// it by at least the tolerance.
fn shared_stretch(a: Coord, u: Coord, len: f64, p: Coord, q: Coord) -> Option<(Coord, Coord)> {
    let off = |x: Coord| ((x - a).x * u.y - (x - a).y * u.x).abs();
    if off(p) > ON_EDGE_M || off(q) > ON_EDGE_M {
        return None;
    }
    let t = |x: Coord| (x - a).x * u.x + (x - a).y * u.y;
    let (t0, t1) = (t(p).min(t(q)).max(0.0), t(p).max(t(q)).min(len));
    (t1 - t0 >= ON_EDGE_M).then(|| (a + u * t0, a + u * t1))
}

/// Whether a border needs a headland: neither block's swaths run along it (within the
/// tolerance, radians).
pub fn needs_headland(border: &Border, blocks: &[BlockArea], tolerance: f64) -> bool {
    let b = border.bearing();
    let along = |k: usize| {
        blocks
            .get(k)
            .is_none_or(|x| angle_between(x.bearing, b) < tolerance)
    };
    !(along(border.first) || along(border.second))
}

/// Cuts a band of `passes` passes of `width` along every border that needs one (see the module
/// documentation), from one of its blocks; `forbidden` and `regions` say where driving along
/// the border is allowed.
///
/// ```
/// use furrow::decompose::block_headlands::cut_block_headlands;
/// use furrow::decompose::BlockArea;
/// use geo::{polygon, Area, MultiPolygon};
///
/// // Two blocks side by side, both worked east-west: both end at the border x = 100.
/// let west = polygon![(x: 0., y: 0.), (x: 100., y: 0.), (x: 100., y: 60.), (x: 0., y: 60.)];
/// let east = polygon![(x: 100., y: 0.), (x: 200., y: 0.), (x: 200., y: 60.), (x: 100., y: 60.)];
/// let east_west = std::f64::consts::FRAC_PI_2;
/// let blocks = vec![
///     BlockArea { area: MultiPolygon::new(vec![west]), bearing: east_west },
///     BlockArea { area: MultiPolygon::new(vec![east]), bearing: east_west + 0.5 },
/// ];
/// let h = cut_block_headlands(&blocks, 6.0, 2, &[], &[]);
/// assert_eq!(h.passes.len(), 2);
/// // A 12 m band cut from the later block.
/// assert!((h.blocks[1].area.unsigned_area() - 88.0 * 60.0).abs() < 1e-6);
/// assert!((h.bands.unsigned_area() - 12.0 * 60.0).abs() < 1e-6);
/// ```
pub fn cut_block_headlands(
    blocks: &[BlockArea],
    width: f64,
    passes: u32,
    forbidden: &[BearingRange],
    regions: &[ProhibitedRegion],
) -> BlockHeadlands {
    let mut out = BlockHeadlands {
        blocks: blocks.to_vec(),
        passes: Vec::new(),
        bands: MultiPolygon::new(vec![]),
    };
    if passes == 0 || blocks.len() < 2 {
        return out;
    }
    let tolerance = END_TOLERANCE_DEG.to_radians();
    let depth = passes as f64 * width;
    let mut pieces: Vec<Polygon> = Vec::new();
    for border in borders(blocks, width) {
        if border.length() < width || !needs_headland(&border, blocks, tolerance) {
            continue;
        }
        let b = border.bearing();
        let d = border.to - border.from;
        let len = border.length();
        if len <= 0.0 {
            continue;
        }
        let normal = Coord {
            x: -d.y / len,
            y: d.x / len,
        };
        let slab = |k: f64| {
            let o = normal * (k * depth);
            Polygon::new(
                LineString::new(vec![
                    border.from - o,
                    border.to - o,
                    border.to + o,
                    border.from + o,
                    border.from - o,
                ]),
                vec![],
            )
        };
        let strip = MultiPolygon::new(vec![slab(1.0)]);
        let allowed_in = |k: usize| -> bool {
            let band = out.blocks[k].area.intersection(&strip);
            if forbidden.iter().any(|r| r.forbids(b)) {
                return false;
            }
            !regions.iter().any(|r| {
                r.forbidden.iter().any(|f| f.forbids(b))
                    && band
                        .intersection(&MultiPolygon::new(vec![r.polygon.clone()]))
                        .unsigned_area()
                        > width
            })
        };
        let side = if !allowed_in(border.second) && allowed_in(border.first) {
            border.first
        } else {
            border.second
        };
        // Slivers where the strip grazes the block are not headland.
        let band = MultiPolygon::new(
            out.blocks[side]
                .area
                .intersection(&strip)
                .0
                .into_iter()
                .filter(|p| p.unsigned_area() >= width * width / 2.0)
                .collect(),
        );
        if band.0.is_empty() {
            continue;
        }
        out.blocks[side].area = out.blocks[side].area.difference(&band);
        for k in 1..=passes {
            // The pass k - 1/2 widths from the border, on the side the band lies.
            let shift = (k as f64 - 0.5) * width;
            for sign in [1.0, -1.0] {
                let o = normal * (sign * shift);
                for (p, q) in clip_segment(&band, border.from + o, border.to + o) {
                    if (q - p).x.planar_hypot((q - p).y) > width {
                        out.passes.push(HeadlandPass {
                            index: k as usize,
                            line: LineString::new(vec![p, q]),
                            closed: false,
                            around: PassAround::Block,
                        });
                    }
                }
            }
        }
        pieces.extend(band.0);
    }
    if !pieces.is_empty() {
        out.bands = MultiPolygon::new(pieces.clone()).union(&MultiPolygon::new(vec![]));
        if out.bands.0.is_empty() {
            out.bands = MultiPolygon::new(pieces);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::BearingRange;
    use geo::polygon;
    use std::f64::consts::FRAC_PI_2;

    /// [`borders`] without the boxes: every edge of one block against every edge of the other.
    fn borders_edge_by_edge(blocks: &[BlockArea], min_length: f64) -> Vec<Border> {
        let edges: Vec<Vec<(Coord, Coord)>> = blocks
            .iter()
            .map(|b| {
                b.area
                    .0
                    .iter()
                    .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
                    .flat_map(|r| r.lines().map(|l| (l.start, l.end)))
                    .collect()
            })
            .collect();
        let mut out = Vec::new();
        for j in 0..blocks.len() {
            for i in 0..j {
                let first = out.len();
                for &(a, b) in &edges[j] {
                    let d = b - a;
                    let len = d.x.planar_hypot(d.y);
                    if len < ON_EDGE_M {
                        continue;
                    }
                    let u = d / len;
                    for &(p, q) in &edges[i] {
                        if let Some((from, to)) = shared_stretch(a, u, len, p, q) {
                            out.push(Border {
                                first: i,
                                second: j,
                                from,
                                to,
                            });
                        }
                    }
                }
                let shared: f64 = out[first..].iter().map(Border::length).sum();
                if shared < min_length {
                    out.truncate(first);
                }
            }
        }
        out
    }

    #[test]
    fn the_boxes_find_the_borders_every_edge_pair_finds() {
        use crate::decompose::cells::MergeRule;
        use crate::decompose::split_merge::cells_at;
        // A field with a bay and two obstacles, its corners rounded as headlands leave them,
        // cut into cells at many directions: borders along slab lines and along oblique edges.
        let mut exterior: Vec<(f64, f64)> = vec![(0., 0.), (300., 0.), (300., 200.), (180., 200.)];
        for k in 0..=12 {
            let a = std::f64::consts::PI * k as f64 / 12.0;
            exterior.push((150.0 - 30.0 * a.cos(), 200.0 - 60.0 * a.sin()));
        }
        exterior.extend([(120., 200.), (0., 200.)]);
        let holes = vec![
            LineString::from(vec![(50., 50.), (90., 40.), (80., 90.), (50., 50.)]),
            LineString::from(vec![
                (200., 60.),
                (240., 60.),
                (240., 120.),
                (200., 120.),
                (200., 60.),
            ]),
        ];
        let field = MultiPolygon::new(vec![Polygon::new(LineString::from(exterior), holes)]);
        let s = crate::decompose::split_merge::tests::settings(&[]);
        let mut found = 0;
        for k in 0..36 {
            let bearing = (k as f64 * 5.0 + if k % 2 == 0 { 0.0 } else { 0.7 }).to_radians();
            for rule in [
                MergeRule::Boustrophedon,
                MergeRule::SplitMerge {
                    min_end_angle: 0.35,
                },
            ] {
                let (blocks, _) = cells_at(&field, bearing, rule, &s);
                for min_length in [0.0, 6.0] {
                    let fast = borders(&blocks, min_length);
                    assert_eq!(
                        fast,
                        borders_edge_by_edge(&blocks, min_length),
                        "{k} {rule:?}"
                    );
                    found += fast.len();
                }
            }
        }
        assert!(found > 200, "{found} borders");
    }

    fn block(x0: f64, x1: f64, bearing: f64) -> BlockArea {
        BlockArea {
            area: MultiPolygon::new(vec![
                polygon![(x: x0, y: 0.), (x: x1, y: 0.), (x: x1, y: 60.), (x: x0, y: 60.)],
            ]),
            bearing,
        }
    }

    #[test]
    fn a_border_along_either_blocks_swaths_needs_no_headland() {
        // East-west swaths ending on the side of a block worked north-south.
        let blocks = [block(0.0, 100.0, 0.0), block(100.0, 200.0, FRAC_PI_2)];
        let b = borders(&blocks, 6.0);
        assert_eq!(b.len(), 1);
        assert!(!needs_headland(
            &b[0],
            &blocks,
            END_TOLERANCE_DEG.to_radians()
        ));
        let h = cut_block_headlands(&blocks, 6.0, 2, &[], &[]);
        assert!(h.passes.is_empty() && h.bands.0.is_empty());
    }

    #[test]
    fn the_band_goes_where_driving_along_the_border_is_allowed() {
        // Both blocks end on the border x = 100 (running north); the later block lies in a
        // region where north-south driving is forbidden, so the band is cut from the earlier.
        let blocks = [block(0.0, 100.0, FRAC_PI_2), block(100.0, 200.0, 1.2)];
        let region = ProhibitedRegion {
            polygon: polygon![(x: 100., y: 0.), (x: 200., y: 0.), (x: 200., y: 60.), (x: 100., y: 60.)],
            forbidden: vec![BearingRange {
                from_deg: 350.0,
                to_deg: 10.0,
            }],
            feature: 1,
            name: None,
        };
        let h = cut_block_headlands(&blocks, 6.0, 1, &[], &[region]);
        assert_eq!(h.passes.len(), 1);
        assert!((h.blocks[0].area.unsigned_area() - 94.0 * 60.0).abs() < 1e-6);
        assert!((h.blocks[1].area.unsigned_area() - 100.0 * 60.0).abs() < 1e-6);
        // The pass half a width from the border, inside the earlier block.
        assert!(h.passes[0].line.0.iter().all(|c| (c.x - 97.0).abs() < 1e-6));
    }
}
