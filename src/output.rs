//! The plan as GeoJSON: a FeatureCollection in the input's coordinates.
//!
//! This is the contract with apps and the viewer, so it only grows. Every feature has
//! `properties.kind`:
//!
//! | kind | geometry | properties |
//! |---|---|---|
//! | `block` | Polygon | `index`, `order` (position in the order blocks are worked), `swath_count`, `bearing_deg`, `region` (if it lies in a prohibited region worked in its own direction), `fill` (`true` for a block working what the others leave standing) |
//! | `obstacle` | Polygon | `index`, `feature` (index of the input feature), `name` (if it had one), `class` (`A`-`D`), `group` (for class C: the `obstacle_group` it was merged into) |
//! | `obstacle_group` | Polygon | `index`, `class` (`C`), `members` (indices of the obstacles merged) |
//! | `swath` | LineString | `sequence`, `index`, `block`, `line`, `length_m`, `bearing_deg` (driving direction), `lifted` (if any: `[from, to]` metres from the swath's first point where the implement is lifted over a class A obstacle), `overlap_m` (on a line working a leftover strip: its overlap with the neighbouring strip), `region` (in a prohibited region worked in its own direction), `fill` (`true` in a fill block) |
//! | `headland` | LineString | `sequence`, `pass` (1 = nearest the boundary or obstacle), `around` (`field`, `obstacle`, `block` or `fill`), `closed`, `length_m` |
//! | `turn` | LineString | `sequence`, `block`, `length_m`, `form`, `word`, `inside` |
//! | `connection` | LineString | `sequence`, `length_m`, `inside` |
//! | `uncovered` | Polygon | `index`, `area_m2`, `reachable_m2` (what a strip of the implement's width could reach of it): crop left standing, parts larger than a quarter of a working width squared, largest first |
//!
//! Every drivable feature also has `distance_m`, `time_s` (from the start of the path),
//! `duration_s`, `working`, and at each point of its line `heading_deg` and `curvature` (and
//! `reverse` where the machine reverses on it).
//!
//! Drivable features (`swath`, `headland`, `turn`, `connection`) carry `sequence`, their position
//! in driving order from 0, and follow each other in that order in `features`; each starts where
//! the one before it ends. Blocks, obstacles, obstacle groups and the parts left uncovered come first. The collection has two more members:
//! `summary` ([`Summary`]) and `warnings` (a list of `{code, message, feature?}`).

pub mod budget;
pub mod json;

use crate::error::Warning;
use crate::field::projection::OutputAlong;
use crate::field::Frame;
use crate::geometry::{bearing_of, round_half_away};
use crate::metrics::Summary;
use crate::obstacles::ObstacleClass;
use crate::path::curve::Gear;
use crate::path::sample::compass_deg;
use crate::path::turn::chord_poses_within;
use crate::path::{PathSegment, SegmentKind};
use crate::plan::Plan;
use crate::route::RouteStep;
use geo::{Coord, LineString, Polygon};
use serde::Serialize;

/// The plan as a GeoJSON FeatureCollection (serialise it with serde).
#[derive(Debug, Clone, Serialize)]
pub struct PlanGeoJson {
    #[serde(rename = "type")]
    kind: &'static str,
    /// The features: blocks and obstacles, then the drivable segments in driving order.
    pub features: Vec<Feature>,
    /// The plan's figures.
    pub summary: Summary,
    /// Repairs made to the input and things the user should know.
    pub warnings: Vec<Warning>,
}

/// One GeoJSON Feature of a plan.
#[derive(Debug, Clone, Serialize)]
pub struct Feature {
    #[serde(rename = "type")]
    kind: &'static str,
    /// What the feature is and its figures.
    pub properties: Properties,
    /// Its geometry in the input's coordinates.
    pub geometry: Geometry,
}

/// The properties of a plan feature; which are present depends on `kind`.
#[derive(Debug, Clone, Default, Serialize)]
pub struct Properties {
    /// `block`, `obstacle`, `obstacle_group`, `uncovered`, `swath`, `headland`, `turn` or
    /// `connection`.
    pub kind: &'static str,
    /// Position in driving order (drivable features).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sequence: Option<usize>,
    /// Index of the block, obstacle or swath.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub index: Option<usize>,
    /// Area of a part left standing, square metres.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub area_m2: Option<f64>,
    /// Of a part left standing, what a strip of the implement's width could reach, square
    /// metres.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reachable_m2: Option<f64>,
    /// Position of a block in the order blocks are worked.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub order: Option<usize>,
    /// The block a swath or turn belongs to.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub block: Option<usize>,
    /// The swath line a swath lies on, counted across the field.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub line: Option<usize>,
    /// Which headland pass, 1 = outermost.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pass: Option<usize>,
    /// Number of swaths of a block.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub swath_count: Option<usize>,
    /// Index of the input feature an obstacle came from.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub feature: Option<usize>,
    /// The input feature's `name`, for obstacles that had one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Length, metres.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub length_m: Option<f64>,
    /// Compass bearing, degrees: the driving direction of a swath, the swath direction of a block.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bearing_deg: Option<f64>,
    /// The class of an obstacle (`A`-`D`, Zhou et al.); `C` for an obstacle group.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub class: Option<&'static str>,
    /// The obstacle group a class-C obstacle was merged into.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub group: Option<usize>,
    /// The obstacles merged into an obstacle group.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub members: Option<Vec<usize>>,
    /// What a headland pass runs around: `field`, `obstacle`, `block` or `fill`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub around: Option<&'static str>,
    /// Whether a headland pass is a closed path.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub closed: Option<bool>,
    /// Where along a swath or headland pass the implement is lifted (over small obstacles, and
    /// wherever it would reach out of the field or over an obstacle): `[from, to]` metres from
    /// its first point.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lifted: Option<Vec<[f64; 2]>>,
    /// For a swath on a line placed to work a leftover strip: how far (metres) its strip
    /// overlaps its neighbour's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub overlap_m: Option<f64>,
    /// For a swath or block in a prohibited region worked in its own direction: the region.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub region: Option<usize>,
    /// `true` for a swath or block that works a part the others left standing.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fill: Option<bool>,
    /// Distance driven from the start of the path to the start of a drivable feature, metres.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub distance_m: Option<f64>,
    /// Time from the start of the path to the start of a drivable feature, seconds.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub time_s: Option<f64>,
    /// Time to drive a drivable feature, seconds.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub duration_s: Option<f64>,
    /// Whether the implement works along a drivable feature.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub working: Option<bool>,
    /// A turn's form: `u-turn`, `loop`, `three-point`, `reeds-shepp`, `cc-u-turn`, `cc-loop`,
    /// `on-the-spot`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub form: Option<&'static str>,
    /// A turn's word (`LSL`, `L+R-L+` …), where it has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub word: Option<String>,
    /// `false` on a turn or connection that leaves the field or crosses an obstacle (see the
    /// warnings); `true` on the others.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub inside: Option<bool>,
    /// `true` on a connection between blocks or a turn between swaths that drives over crop
    /// the plan works later (see the `connection_crosses_crop` and `turn_crosses_crop`
    /// warnings); absent on the others.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub crosses_crop: Option<bool>,
    /// The heading at each point of a drivable feature's line, compass degrees.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub heading_deg: Option<Vec<f64>>,
    /// The steering curvature at each point, 1/m, positive to the left.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub curvature: Option<Vec<f64>>,
    /// Whether the machine reverses at each point: only on features where it does.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reverse: Option<Vec<bool>>,
}

/// A GeoJSON geometry of a plan feature.
#[derive(Debug, Clone, Serialize)]
#[serde(tag = "type", content = "coordinates")]
pub enum Geometry {
    /// A line.
    LineString(Vec<[f64; 2]>),
    /// A polygon: outer ring, then holes.
    Polygon(Vec<Vec<[f64; 2]>>),
}

impl Plan {
    /// The plan as a GeoJSON FeatureCollection in the input's coordinates.
    pub fn to_geojson(&self) -> PlanGeoJson {
        let out = Output {
            frame: &self.field.frame,
        };
        let mut features = Vec::with_capacity(
            self.blocks.blocks.len() + self.field.obstacles.len() + self.path.segments.len(),
        );
        let order_of = |b: usize| self.route.block_order.iter().position(|&x| x == b);
        for block in &self.blocks.blocks {
            features.push(out.feature(
                Properties {
                    kind: "block",
                    index: Some(block.index),
                    order: order_of(block.index),
                    swath_count: Some(block.swaths.len()),
                    bearing_deg: Some(round(block.bearing.to_degrees(), 1e-6)),
                    region: block.swaths.first().and_then(|&s| self.region_of(s)),
                    fill: block.swaths.first().and_then(|&s| self.fill_of(s)),
                    ..Default::default()
                },
                out.polygon(&block.outline),
            ));
        }
        for (i, o) in self.field.obstacles.iter().enumerate() {
            let class = self.obstacles.class.get(i).copied();
            features.push(out.feature(
                Properties {
                    kind: "obstacle",
                    index: Some(i),
                    feature: Some(o.feature),
                    name: o.name.clone(),
                    class: class.map(|c| c.as_str()),
                    group: if class == Some(ObstacleClass::C) {
                        self.obstacles.hole_of.get(i).copied().flatten()
                    } else {
                        None
                    },
                    ..Default::default()
                },
                out.polygon(&o.polygon),
            ));
        }
        for (g, hole) in self.obstacles.holes.iter().enumerate() {
            if hole.members.len() < 2 {
                continue;
            }
            for part in &hole.shape.0 {
                features.push(out.feature(
                    Properties {
                        kind: "obstacle_group",
                        index: Some(g),
                        class: Some(ObstacleClass::C.as_str()),
                        members: Some(hole.members.clone()),
                        ..Default::default()
                    },
                    out.polygon(part),
                ));
            }
        }
        for (i, part) in self.summary.coverage.uncovered.iter().enumerate() {
            features.push(out.feature(
                Properties {
                    kind: "uncovered",
                    index: Some(i),
                    area_m2: Some(round(part.area_m2, 1e-2)),
                    reachable_m2: Some(round(part.reachable_m2, 1e-2)),
                    ..Default::default()
                },
                out.polygon(&part.polygon),
            ));
        }
        let vehicle = self.options.vehicle();
        let (mut distance, mut time) = (0.0, 0.0);
        // The path's points through the projection exact every few hundred metres and
        // quadratic in between (within 0.3 mm, as the samples), which spares a projection per
        // vertex of the densely drawn turns and connections; one conversion along the whole
        // path, as each segment starts where the one before ends. (The field's own outlines
        // keep the exact projection of every vertex.)
        let mut along = OutputAlong::new(&self.field.frame);
        // Chords within 5 mm of the curves, unless that makes too many points.
        let tolerance = budget::chord_tolerance(&self.path);
        for (sequence, seg) in self.path.segments.iter().enumerate() {
            let length = seg.length();
            let speed = if seg.is_working() {
                vehicle.working_speed
            } else {
                vehicle.turning_speed
            };
            let duration = if speed > 0.0 { length / speed } else { 0.0 };
            let (points, heading, curvature, reverse) = vertices(seg, tolerance);
            let mut p = Properties {
                kind: seg.kind.as_str(),
                sequence: Some(sequence),
                length_m: Some(round(length, 1e-3)),
                distance_m: Some(round(distance, 1e-3)),
                time_s: Some(round(time, 1e-3)),
                duration_s: Some(round(duration, 1e-3)),
                working: Some(seg.is_working()),
                heading_deg: Some(heading),
                curvature: Some(curvature),
                reverse: seg.reverses().then_some(reverse),
                lifted: lifted_mm(&seg.lifted, length),
                ..Default::default()
            };
            distance += length;
            time += duration;
            if let Some(t) = &seg.turn {
                p.form = Some(t.form.name());
                let word = t.form.word();
                p.word = (!word.is_empty()).then_some(word);
                p.inside = Some(t.inside);
                p.crosses_crop = seg.crosses_crop.then_some(true);
            }
            if seg.kind == SegmentKind::Connection {
                p.inside = Some(!seg.leaves_field);
                p.crosses_crop = seg.crosses_crop.then_some(true);
            }
            match seg.step.and_then(|k| self.route.steps.get(k)) {
                Some(&RouteStep::Swath { swath, block, .. }) => {
                    p.index = Some(swath);
                    p.block = Some(block);
                    p.line = self.swaths.swaths.get(swath).map(|s| s.line_index);
                    if let (Some(&a), Some(&b)) = (seg.line.0.first(), seg.line.0.last()) {
                        p.bearing_deg = Some(round(bearing_of(a, b).to_degrees(), 1e-6));
                    }
                    p.overlap_m = self
                        .swaths
                        .swaths
                        .get(swath)
                        .filter(|s| s.overlap_m > 0.0)
                        .map(|s| round(s.overlap_m, 1e-3));
                    p.region = self.region_of(swath);
                    p.fill = self.fill_of(swath);
                }
                Some(&RouteStep::HeadlandPass { pass, .. }) => {
                    if let Some(h) = self.headlands.passes.get(pass) {
                        p.pass = Some(h.index);
                        p.around = Some(h.around.as_str());
                        p.closed = Some(h.closed);
                    }
                }
                None => {}
            }
            if seg.kind == SegmentKind::Turn {
                p.block = self.block_before(sequence);
            }
            let line = if points.is_empty() {
                along.all(seg.line.0.iter().copied())
            } else {
                along.all(points.iter().copied())
            };
            features.push(out.feature(p, Geometry::LineString(line)));
        }
        PlanGeoJson {
            kind: "FeatureCollection",
            features,
            summary: self.summary.clone(),
            warnings: self.warnings.clone(),
        }
    }

    /// The plan as GeoJSON text (compact).
    pub fn to_geojson_string(&self) -> String {
        // ok: the output types hold only strings, integers and finite floats; serde_json cannot fail.
        json::to_json_string(&self.to_geojson()).unwrap_or_default()
    }

    /// The prohibited region whose own direction swath `i` follows, if any.
    fn region_of(&self, i: usize) -> Option<usize> {
        self.swaths
            .areas
            .iter()
            .find(|a| a.swaths.contains(&i))
            .and_then(|a| a.region)
    }

    /// `Some(true)` if swath `i` works a part the other swaths left standing.
    fn fill_of(&self, i: usize) -> Option<bool> {
        self.swaths
            .areas
            .iter()
            .any(|a| a.fill && a.swaths.contains(&i))
            .then_some(true)
    }

    /// The block of the swath driven just before path segment `k`.
    fn block_before(&self, k: usize) -> Option<usize> {
        // A turn's block is that of the swath it leaves (a manoeuvre on a headland pass has none).
        let before = k.checked_sub(1).and_then(|i| self.path.segments.get(i))?;
        match before.step.and_then(|i| self.route.steps.get(i)) {
            Some(&RouteStep::Swath { block, .. }) => Some(block),
            _ => None,
        }
    }
}

/// The stretches of a segment `length` metres long driven with the implement lifted, widened to
/// the millimetre (lifted a little early, lowered a little late), one that reaches its end
/// written to a millimetre past it: the line as written is a little longer or shorter than as
/// driven, and no crumb of it is to be read as worked.
fn lifted_mm(lifted: &[(f64, f64)], length: f64) -> Option<Vec<[f64; 2]>> {
    let end = ((length + 1e-3) * 1e3).ceil() / 1e3;
    let out: Vec<[f64; 2]> = lifted
        .iter()
        .map(|&(a, b)| {
            let b = if b >= length - 1e-3 {
                end
            } else {
                (b * 1e3).ceil() / 1e3
            };
            [(a * 1e3).floor() / 1e3 + 0.0, b]
        })
        .collect();
    (!out.is_empty()).then_some(out)
}

/// The points of a drivable segment's line (its pieces at chords within `tolerance` metres,
/// [`budget::chord_tolerance`]) with the heading (compass degrees), curvature and gear at each.
fn vertices(seg: &PathSegment, tolerance: f64) -> (Vec<Coord>, Vec<f64>, Vec<f64>, Vec<bool>) {
    let (mut pts, mut heading, mut curvature, mut reverse) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for (i, piece) in seg.pieces.iter().enumerate() {
        for (j, (pose, k)) in chord_poses_within(piece, tolerance).enumerate() {
            if i > 0 && j == 0 {
                continue;
            }
            pts.push(Coord {
                x: pose.x,
                y: pose.y,
            });
            heading.push(round(compass_deg(pose.heading), 1e-4));
            curvature.push(round(k, 1e-7));
            reverse.push(piece.gear == Gear::Reverse);
        }
    }
    (pts, heading, curvature, reverse)
}

/// Converts local metres to output coordinates.
struct Output<'a> {
    frame: &'a Frame,
}

impl Output<'_> {
    fn feature(&self, properties: Properties, geometry: Geometry) -> Feature {
        Feature {
            kind: "Feature",
            properties,
            geometry,
        }
    }

    fn line(&self, l: &LineString) -> Vec<[f64; 2]> {
        l.0.iter().map(|&c| self.frame.to_output(c)).collect()
    }

    fn polygon(&self, p: &Polygon) -> Geometry {
        let mut rings = Vec::with_capacity(1 + p.interiors().len());
        rings.push(self.line(p.exterior()));
        rings.extend(p.interiors().iter().map(|r| self.line(r)));
        Geometry::Polygon(rings)
    }
}

/// `v` rounded to a multiple of `step` (a negative power of ten). Dividing by the exact integer
/// `1 / step` gives the double nearest the decimal, so it prints short.
fn round(v: f64, step: f64) -> f64 {
    let scale = round_half_away(1.0 / step);
    round_half_away(v * scale) / scale
}
