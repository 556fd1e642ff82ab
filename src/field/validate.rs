//! From parsed GeoJSON to a [`Field`]: choose the boundary, check every coordinate, project to
//! metres, repair rings, and refuse what cannot be planned with an error that says where.

use super::geojson::{InputFeatures, InputPolygon, Role};
use super::landmask::land_within;
use super::place::{place_problem, MAX_PLACE_DISTANCE_M};
use super::projection::{Frame, TransverseMercator};
use super::ring::{clean_ring, find_self_intersection, signed_area2, RingRepairs};
use super::{BearingRange, Coordinates, Field, Obstacle, ProhibitedRegion};
use crate::error::{ErrorCode, PlanError, Warning, WarningCode};
use crate::geometry::forbids_every_direction;
use crate::geometry::{BooleanOps, PlanarHypot};
use crate::numbers::{Decimals, Position, Shortest};
use geo::{Area, BoundingRect, Contains, Coord, Intersects, LineString, MultiPolygon, Polygon};

/// Inputs with more vertices than this (all rings together) are refused.
pub const MAX_VERTICES: usize = 200_000;
/// A field boundary enclosing less than this (square metres) cannot be planned.
pub const MIN_FIELD_AREA_M2: f64 = 1.0;
/// An obstacle or prohibited region enclosing less than this (square metres) is degenerate.
pub const MIN_REGION_AREA_M2: f64 = 1e-4;
/// Latitudes beyond this (degrees) are refused: no field is planned that near a pole.
pub const MAX_ABS_LATITUDE_DEG: f64 = 89.0;
/// Metric coordinates beyond this (metres) from the origin are refused.
pub const MAX_ABS_METRIC_M: f64 = 1e7;
/// Fields larger than this across (metres, the diagonal of the bounding box) are refused: no farm
/// field is, and the local projection is only exact to a millimetre within 20 km of the centre.
pub const MAX_FIELD_EXTENT_M: f64 = 40_000.0;

/// Builds a [`Field`] from parsed input, repairing what can be repaired.
pub fn field_from_input(
    input: InputFeatures,
    coordinates: Coordinates,
) -> Result<(Field, Vec<Warning>), PlanError> {
    let mut warnings = Vec::new();
    for (feature, why) in &input.ignored {
        warnings.push(
            Warning::new(
                WarningCode::IgnoredFeature,
                format!("feature {feature} was ignored: {why}"),
            )
            .at_feature(*feature),
        );
    }
    let vertices: usize = input
        .polygons
        .iter()
        .flat_map(|p| p.rings.iter())
        .map(Vec::len)
        .sum();
    if vertices > MAX_VERTICES {
        return Err(PlanError::new(
            ErrorCode::InputTooLarge,
            format!("the input has {vertices} points; the planner accepts up to {MAX_VERTICES}: simplify the outlines"),
        ));
    }
    let (entrance, reference_line) = (input.entrance, input.reference_line);
    let entrance_feature = input.entrance_feature;
    let (mut boundary_in, others) = choose_boundary(input.polygons, &mut warnings)?;
    boundary_in.role = Role::Boundary;
    for p in std::iter::once(&boundary_in).chain(&others) {
        check_coordinates(p, coordinates)?;
    }
    let frame = match coordinates {
        Coordinates::Wgs84 => {
            let (lon, lat) = centre_lon_lat(&boundary_in.rings[0]);
            check_location(lon, lat, boundary_in.feature, &mut warnings)?;
            Frame::Wgs84(TransverseMercator::centred_at(lon, lat))
        }
        Coordinates::Metric => Frame::Metric,
    };

    let exterior = local_ring(&boundary_in, 0, &frame, &mut warnings)?;
    let boundary = Polygon::new(exterior, vec![]);
    if boundary.unsigned_area() < MIN_FIELD_AREA_M2 {
        return Err(zero_area(&boundary_in, 0, MIN_FIELD_AREA_M2));
    }
    if let Some(rect) = boundary.bounding_rect() {
        let extent = rect.width().planar_hypot(rect.height());
        if extent > MAX_FIELD_EXTENT_M {
            return Err(PlanError::new(
                ErrorCode::FieldTooLarge,
                format!(
                    "the field is {} km across; the planner plans fields up to {} km across",
                    Decimals(extent / 1000.0, 1),
                    Shortest(MAX_FIELD_EXTENT_M / 1000.0)
                ),
            )
            .at_feature(boundary_in.feature));
        }
    }
    if let (Some(p), Some(i)) = (entrance, entrance_feature) {
        if let Some(problem) = place_problem(p, coordinates, &boundary, &frame) {
            return Err(PlanError::new(
                ErrorCode::CoordinateOutOfRange,
                format!(
                    "the field's entrance (feature {i}) is {}: {problem}; move it to where the machine enters the field, within {} km of its boundary",
                    Position(p),
                    Shortest(MAX_PLACE_DISTANCE_M / 1000.0)
                ),
            )
            .at_feature(i)
            .at_coordinate(p));
        }
    }

    let mut obstacles = Vec::new();
    // Holes of the boundary are obstacles; they must lie inside the exterior.
    for r in 1..boundary_in.rings.len() {
        let ring = local_ring(&boundary_in, r, &frame, &mut warnings)?;
        let hole = Polygon::new(ring, vec![]);
        if let Some(p) = ring_crossing(&hole, &boundary) {
            return Err(PlanError::new(
                ErrorCode::HoleCrossingBoundary,
                format!(
                    "{} crosses the boundary's outer ring",
                    boundary_in.subject(r)
                ),
            )
            .at_feature(boundary_in.feature)
            .at_ring(r)
            .at_coordinate(frame.to_output(p)));
        }
        if !boundary.contains(&hole.exterior().0[0]) {
            return Err(PlanError::new(
                ErrorCode::HoleCrossingBoundary,
                format!(
                    "{} lies outside the boundary's outer ring",
                    boundary_in.subject(r)
                ),
            )
            .at_feature(boundary_in.feature)
            .at_ring(r));
        }
        obstacles.push(Obstacle {
            polygon: hole,
            feature: boundary_in.feature,
            name: None,
        });
    }

    let mut prohibited = Vec::new();
    for p in &others {
        let ring = local_ring(p, 0, &frame, &mut warnings)?;
        let polygon = Polygon::new(ring, vec![]);
        if polygon.unsigned_area() < MIN_REGION_AREA_M2 {
            return Err(zero_area(p, 0, MIN_REGION_AREA_M2));
        }
        if p.rings.len() > 1 {
            warnings.push(
                Warning::new(
                    WarningCode::IgnoredFeature,
                    format!("the holes of {} were ignored", p.subject(0)),
                )
                .at_feature(p.feature),
            );
        }
        let inside = clip_to_field(p, polygon, &boundary, &frame)?;
        match p.role {
            Role::Obstacle => {
                for polygon in inside.parts {
                    obstacles.push(Obstacle {
                        polygon,
                        feature: p.feature,
                        name: p.name.clone(),
                    });
                }
                if inside.clipped {
                    warnings.push(
                        Warning::new(
                            WarningCode::ObstacleClipped,
                            format!(
                                "{} reaches over the field boundary; only its part inside the field is kept",
                                p.subject(0)
                            ),
                        )
                        .at_feature(p.feature),
                    );
                }
            }
            Role::Prohibited => {
                let forbidden = bearing_ranges(p)?;
                for polygon in inside.parts {
                    prohibited.push(ProhibitedRegion {
                        polygon,
                        forbidden: forbidden.clone(),
                        feature: p.feature,
                        name: p.name.clone(),
                    });
                }
                if inside.clipped {
                    warnings.push(
                        Warning::new(
                            WarningCode::ProhibitedClipped,
                            format!(
                                "{} reaches over the field boundary; only its part inside the field is kept",
                                p.subject(0)
                            ),
                        )
                        .at_feature(p.feature),
                    );
                }
            }
            Role::Boundary | Role::Unspecified => {}
        }
    }
    let obstacles = merge_overlapping(obstacles, &mut warnings);

    let drawn_boundary = boundary_in.rings[0]
        .iter()
        .map(|&q| frame.to_local(q))
        .collect();
    let field = Field {
        boundary,
        drawn_boundary,
        obstacles,
        prohibited,
        name: boundary_in.name.clone(),
        feature: boundary_in.feature,
        frame,
        entrance,
        reference_line,
    };
    Ok((field, warnings))
}

/// Picks the boundary polygon; returns it and the obstacles and prohibited regions.
fn choose_boundary(
    polygons: Vec<InputPolygon>,
    warnings: &mut Vec<Warning>,
) -> Result<(InputPolygon, Vec<InputPolygon>), PlanError> {
    let explicit = polygons.iter().any(|p| p.role == Role::Boundary);
    let wanted = if explicit {
        Role::Boundary
    } else {
        Role::Unspecified
    };
    let (mut candidates, rest): (Vec<_>, Vec<_>) =
        polygons.into_iter().partition(|p| p.role == wanted);
    let mut others = Vec::with_capacity(rest.len());
    for p in rest {
        if p.role == Role::Unspecified {
            warnings.push(
                Warning::new(
                    WarningCode::IgnoredFeature,
                    format!(
                        "feature {} has no role and was ignored; give it `role: \"obstacle\"` to plan around it",
                        p.feature
                    ),
                )
                .at_feature(p.feature),
            );
        } else {
            others.push(p);
        }
    }
    match candidates.len() {
        0 => Err(PlanError::new(
            ErrorCode::NoBoundary,
            "the input has no field boundary: give one Polygon, or mark it with `properties.role = \"boundary\"`",
        )),
        1 => Ok((candidates.remove(0), others)),
        n => {
            let first = &candidates[0];
            let same_feature = candidates.iter().all(|c| c.feature == first.feature);
            let message = if same_feature {
                format!(
                    "feature {} is a MultiPolygon of {n} parts; plan each part as its own field",
                    first.feature
                )
            } else if explicit {
                format!("{n} polygons have `role: \"boundary\"`; a plan has one boundary")
            } else {
                format!(
                    "{n} polygons and none marked as the field: set `properties.role` to \"boundary\" on the field and \"obstacle\" on obstacles"
                )
            };
            Err(PlanError::new(ErrorCode::AmbiguousBoundary, message).at_feature(candidates[1].feature))
        }
    }
}

/// Checks that every position is a finite number in range for the coordinate system.
fn check_coordinates(p: &InputPolygon, coordinates: Coordinates) -> Result<(), PlanError> {
    for (r, ring) in p.rings.iter().enumerate() {
        for (v, &[x, y]) in ring.iter().enumerate() {
            let at = |e: PlanError| e.at_feature(p.feature).at_ring(r).at_vertex(v);
            if !x.is_finite() || !y.is_finite() {
                return Err(at(PlanError::new(
                    ErrorCode::NonFiniteCoordinate,
                    format!("point {v} of {} is not a finite number", p.subject(r)),
                )));
            }
            let problem = match coordinates {
                Coordinates::Wgs84 if !(-180.0..=180.0).contains(&x) => Some(format!(
                    "longitude {} is out of range -180..180",
                    Shortest(x)
                )),
                Coordinates::Wgs84 if y.abs() > 90.0 => {
                    Some(format!("latitude {} is out of range -90..90", Shortest(y)))
                }
                Coordinates::Metric if x.abs().max(y.abs()) > MAX_ABS_METRIC_M => Some(format!(
                    "({}, {}) is more than {} km from the origin of the metric frame",
                    Shortest(x),
                    Shortest(y),
                    Shortest(MAX_ABS_METRIC_M / 1000.0)
                )),
                _ => None,
            };
            if let Some(what) = problem {
                return Err(at(PlanError::new(
                    ErrorCode::CoordinateOutOfRange,
                    format!("point {v} of {}: {what}", p.subject(r)),
                ))
                .at_coordinate([x, y]));
            }
            if coordinates == Coordinates::Wgs84 && y.abs() > MAX_ABS_LATITUDE_DEG {
                return Err(at(PlanError::new(
                    ErrorCode::CoordinateOutOfRange,
                    format!(
                        "point {v} of {} is at latitude {}, too near a pole to plan (the limit is {})",
                        p.subject(r),
                        Shortest(y),
                        Shortest(MAX_ABS_LATITUDE_DEG)
                    ),
                ))
                .at_coordinate([x, y]));
            }
        }
    }
    Ok(())
}

/// A field far out at sea (no land within about 50 km) was not drawn there: when swapping its
/// longitude and latitude puts it on land, the input is [latitude, longitude] and is refused;
/// otherwise the plan goes ahead with a warning.
fn check_location(
    lon: f64,
    lat: f64,
    feature: usize,
    warnings: &mut Vec<Warning>,
) -> Result<(), PlanError> {
    if land_within(lon, lat, 1) {
        return Ok(());
    }
    let place = |lon: f64, lat: f64| {
        format!(
            "{}° {}, {}° {}",
            Decimals(lat.abs(), 4),
            if lat >= 0.0 { 'N' } else { 'S' },
            Decimals(lon.abs(), 4),
            if lon >= 0.0 { 'E' } else { 'W' }
        )
    };
    if lon.abs() <= 90.0 && land_within(lat, lon, 1) {
        return Err(PlanError::new(
            ErrorCode::CoordinatesSwapped,
            format!(
                "the field lies in the sea at {}; with longitude and latitude swapped it would be on land at {}: GeoJSON positions are [longitude, latitude]",
                place(lon, lat),
                place(lat, lon)
            ),
        )
        .at_feature(feature)
        .at_coordinate([round9(lon), round9(lat)]));
    }
    warnings.push(
        Warning::new(
            WarningCode::FieldAtSea,
            format!(
                "the field lies in the sea at {}, far from land: check its coordinates (GeoJSON positions are [longitude, latitude])",
                place(lon, lat)
            ),
        )
        .at_feature(feature),
    );
    Ok(())
}

/// Degrees rounded to 1e-9 (0.1 mm), as the plan's coordinates are.
fn round9(deg: f64) -> f64 {
    (deg * 1e9).round() / 1e9
}

/// Centre of a ring's bounding box in longitude and latitude, across the antimeridian too.
fn centre_lon_lat(ring: &[[f64; 2]]) -> (f64, f64) {
    let (mut lat_min, mut lat_max) = (f64::INFINITY, f64::NEG_INFINITY);
    // Longitudes are compared both as given and shifted to 0..360, and the narrower span is used.
    let (mut a_min, mut a_max) = (f64::INFINITY, f64::NEG_INFINITY);
    let (mut b_min, mut b_max) = (f64::INFINITY, f64::NEG_INFINITY);
    for &[lon, lat] in ring {
        lat_min = lat_min.min(lat);
        lat_max = lat_max.max(lat);
        a_min = a_min.min(lon);
        a_max = a_max.max(lon);
        let shifted = lon.rem_euclid(360.0);
        b_min = b_min.min(shifted);
        b_max = b_max.max(shifted);
    }
    let lon = if b_max - b_min < a_max - a_min {
        let c = (b_min + b_max) / 2.0;
        if c > 180.0 {
            c - 360.0
        } else {
            c
        }
    } else {
        (a_min + a_max) / 2.0
    };
    (lon, (lat_min + lat_max) / 2.0)
}

/// Projects, cleans and checks ring `r` of a polygon, and orients it counter-clockwise.
fn local_ring(
    p: &InputPolygon,
    r: usize,
    frame: &Frame,
    warnings: &mut Vec<Warning>,
) -> Result<LineString, PlanError> {
    let what = p.subject(r);
    let input = &p.rings[r];
    let projected: Vec<Coord> = input.iter().map(|&q| frame.to_local(q)).collect();
    let (mut ring, repairs) = clean_ring(&projected);
    report_repairs(&what, p.feature, repairs, warnings);
    if ring.len() < 3 && repairs.distinct >= 3 {
        return Err(PlanError::new(
            ErrorCode::ZeroArea,
            format!("{what} encloses no area: all its points lie on one line"),
        )
        .at_feature(p.feature)
        .at_ring(r));
    }
    if ring.len() < 3 {
        return Err(PlanError::new(
            ErrorCode::TooFewPoints,
            format!("{what} has fewer than 3 distinct points"),
        )
        .at_feature(p.feature)
        .at_ring(r));
    }
    if let Some((c, _, _)) = find_self_intersection(&ring) {
        return Err(PlanError::new(
            ErrorCode::SelfIntersection,
            format!("{what} crosses itself: move its points so that the outline does not cross"),
        )
        .at_feature(p.feature)
        .at_ring(r)
        .at_coordinate(frame.to_output(c)));
    }
    let area2 = signed_area2(&ring);
    if area2.abs() / 2.0 < MIN_REGION_AREA_M2 {
        return Err(zero_area(p, r, MIN_REGION_AREA_M2));
    }
    // RFC 7946: outer rings run counter-clockwise, holes clockwise. Every ring is stored
    // counter-clockwise, because a hole of the boundary becomes an obstacle's outer ring.
    let is_ccw = area2 > 0.0;
    let outer = r == 0;
    if is_ccw != outer {
        warnings.push(
            Warning::new(
                WarningCode::RingReoriented,
                format!(
                    "{what} ran {}; it was turned round",
                    if outer {
                        "clockwise, but GeoJSON's outer rings run counter-clockwise"
                    } else {
                        "counter-clockwise, but GeoJSON's holes run clockwise"
                    }
                ),
            )
            .at_feature(p.feature),
        );
    }
    if !is_ccw {
        ring.reverse();
    }
    let mut coords = ring;
    if let Some(&first) = coords.first() {
        coords.push(first);
    }
    Ok(LineString::new(coords))
}

fn report_repairs(what: &str, feature: usize, r: RingRepairs, warnings: &mut Vec<Warning>) {
    let mut warn = |code, message: String| {
        warnings.push(Warning::new(code, message).at_feature(feature));
    };
    if r.was_open {
        warn(
            WarningCode::RingClosed,
            format!("{what} was open (its last point did not repeat its first); it was closed"),
        );
    }
    if r.repeated > 0 {
        warn(
            WarningCode::RepeatedVertices,
            format!(
                "{} of {what} removed",
                count(r.repeated, "repeated point", "repeated points")
            ),
        );
    }
    if r.collinear > 0 {
        warn(
            WarningCode::CollinearVertices,
            format!(
                "{} on straight edges of {what} removed",
                count(r.collinear, "point", "points")
            ),
        );
    }
    if r.spikes > 0 {
        warn(
            WarningCode::SpikesRemoved,
            format!(
                "{} of {what} removed (the outline went out and straight back)",
                count(r.spikes, "spike", "spikes")
            ),
        );
    }
}

/// "1 spike", "3 spikes".
fn count(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

fn zero_area(p: &InputPolygon, r: usize, min_m2: f64) -> PlanError {
    PlanError::new(
        ErrorCode::ZeroArea,
        format!(
            "{} encloses almost no area (less than {} m²)",
            p.subject(r),
            Shortest(min_m2)
        ),
    )
    .at_feature(p.feature)
    .at_ring(r)
}

/// A point where the outer rings of two polygons cross, if they do.
fn ring_crossing(a: &Polygon, b: &Polygon) -> Option<Coord> {
    use geo::algorithm::line_intersection::line_intersection;
    let (ra, rb) = (a.bounding_rect()?, b.bounding_rect()?);
    if !ra.intersects(&rb) {
        return None;
    }
    for la in a.exterior().lines() {
        for lb in b.exterior().lines() {
            if let Some(hit) = line_intersection(la, lb) {
                return Some(match hit {
                    geo::LineIntersection::SinglePoint { intersection, .. } => intersection,
                    geo::LineIntersection::Collinear { intersection } => intersection.start,
                });
            }
        }
    }
    None
}

struct Clipped {
    parts: Vec<Polygon>,
    clipped: bool,
}

/// The part of a region inside the field; an error if there is none.
fn clip_to_field(
    p: &InputPolygon,
    region: Polygon,
    boundary: &Polygon,
    frame: &Frame,
) -> Result<Clipped, PlanError> {
    let crosses = ring_crossing(&region, boundary).is_some();
    if !crosses {
        if boundary.contains(&region.exterior().0[0]) {
            return Ok(Clipped {
                parts: vec![region],
                clipped: false,
            });
        }
        let outside = region.contains(&boundary.exterior().0[0]);
        return Err(outside_error(p, frame, &region, outside));
    }
    let inside: MultiPolygon = region.intersection(boundary);
    let parts: Vec<Polygon> = inside
        .0
        .into_iter()
        .filter(|q| q.unsigned_area() >= MIN_REGION_AREA_M2)
        .map(|q| Polygon::new(q.exterior().clone(), vec![]))
        .collect();
    if parts.is_empty() {
        return Err(outside_error(p, frame, &region, false));
    }
    Ok(Clipped {
        parts,
        clipped: true,
    })
}

fn outside_error(p: &InputPolygon, frame: &Frame, region: &Polygon, covers: bool) -> PlanError {
    let message = if covers {
        format!("{} covers the whole field", p.subject(0))
    } else {
        format!("{} lies outside the field boundary", p.subject(0))
    };
    PlanError::new(ErrorCode::ObstacleOutsideField, message)
        .at_feature(p.feature)
        .at_ring(0)
        .at_coordinate(frame.to_output(region.exterior().0[0]))
}

fn bearing_ranges(p: &InputPolygon) -> Result<Vec<BearingRange>, PlanError> {
    let ranges: Vec<BearingRange> = p
        .forbidden_bearings_deg
        .iter()
        .map(|&pair| BearingRange::from(pair))
        .collect();
    if ranges.iter().any(|r| !r.is_finite()) {
        return Err(PlanError::new(
            ErrorCode::InvalidGeojson,
            format!(
                "the forbidden bearings of {} must be finite numbers",
                p.subject(0)
            ),
        )
        .at_feature(p.feature));
    }
    if forbids_every_direction(&ranges) {
        return Err(PlanError::new(
            ErrorCode::NoAllowedDirection,
            format!(
                "{} forbids every driving direction; if nothing may be driven there, make it an obstacle",
                p.subject(0)
            ),
        )
        .at_feature(p.feature));
    }
    Ok(ranges)
}

/// Merges obstacles that overlap or touch into one, keeping the first one's feature index.
fn merge_overlapping(obstacles: Vec<Obstacle>, warnings: &mut Vec<Warning>) -> Vec<Obstacle> {
    let n = obstacles.len();
    if n < 2 {
        return obstacles;
    }
    // Union-find over overlapping pairs; pairs are pre-filtered by bounding box.
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(parent: &mut [usize], i: usize) -> usize {
        let mut r = i;
        while parent[r] != r {
            r = parent[r];
        }
        parent[i] = r;
        r
    }
    let rects: Vec<_> = obstacles
        .iter()
        .map(|o| o.polygon.bounding_rect())
        .collect();
    let mut any = false;
    for i in 0..n {
        for j in i + 1..n {
            let (Some(a), Some(b)) = (rects[i], rects[j]) else {
                continue;
            };
            if a.intersects(&b) && obstacles[i].polygon.intersects(&obstacles[j].polygon) {
                let (ri, rj) = (find(&mut parent, i), find(&mut parent, j));
                if ri != rj {
                    parent[ri.max(rj)] = ri.min(rj);
                    any = true;
                }
            }
        }
    }
    if !any {
        return obstacles;
    }
    let mut groups: Vec<Vec<usize>> = vec![Vec::new(); n];
    for i in 0..n {
        let r = find(&mut parent, i);
        groups[r].push(i);
    }
    let mut out = Vec::with_capacity(n);
    for group in groups.into_iter().filter(|g| !g.is_empty()) {
        if group.len() == 1 {
            out.push(obstacles[group[0]].clone());
            continue;
        }
        let feature = obstacles[group[0]].feature;
        let name = obstacles[group[0]].name.clone();
        // One warning on each obstacle merged, naming the others.
        for &i in &group {
            let others: Vec<String> = group
                .iter()
                .filter(|&&j| j != i)
                .map(|&j| obstacles[j].subject())
                .collect();
            warnings.push(
                Warning::new(
                    WarningCode::ObstaclesMerged,
                    format!(
                        "{} overlaps {}; they were merged into one obstacle",
                        obstacles[i].subject(),
                        others.join(" and ")
                    ),
                )
                .at_feature(obstacles[i].feature),
            );
        }
        let mut union = MultiPolygon::new(vec![obstacles[group[0]].polygon.clone()]);
        for &i in &group[1..] {
            union = union.union(&obstacles[i].polygon);
        }
        for polygon in union.0 {
            out.push(Obstacle {
                polygon: Polygon::new(polygon.exterior().clone(), vec![]),
                feature,
                name: name.clone(),
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::field::geojson::parse_str;

    fn field(text: &str) -> Result<(Field, Vec<Warning>), PlanError> {
        field_from_input(parse_str(text)?, Coordinates::Wgs84)
    }

    const SQUARE: &str =
        "[[24.05,60.25],[24.052,60.25],[24.052,60.251],[24.05,60.251],[24.05,60.25]]";

    #[test]
    fn a_bare_polygon_is_the_boundary() {
        let (f, w) = field(&format!(r#"{{"type":"Polygon","coordinates":[{SQUARE}]}}"#)).unwrap();
        assert!(w.is_empty(), "{w:?}");
        assert!(f.boundary.exterior().is_closed());
        // 0.002 degrees of longitude (110.76 m) by 0.001 of latitude (111.41 m) at 60.25 N.
        assert!(
            (f.area_m2() - 110.76 * 111.41).abs() < 5.0,
            "{}",
            f.area_m2()
        );
    }

    #[test]
    fn holes_become_obstacles_and_clockwise_rings_are_turned() {
        let text = r#"{"type":"Polygon","coordinates":[
            [[24.05,60.25],[24.05,60.251],[24.052,60.251],[24.052,60.25],[24.05,60.25]],
            [[24.0505,60.2502],[24.0506,60.2502],[24.0506,60.2503],[24.0505,60.2503],[24.0505,60.2502]]]}"#;
        let (f, w) = field(text).unwrap();
        assert_eq!(f.obstacles.len(), 1);
        assert!(w.iter().any(|w| w.code == WarningCode::RingReoriented));
        assert!(signed_area2(&f.boundary.exterior().0[..4]) > 0.0);
        assert!(signed_area2(&f.obstacles[0].polygon.exterior().0[..4]) > 0.0);
    }

    #[test]
    fn several_unmarked_polygons_are_ambiguous() {
        let text = format!(
            r#"{{"type":"FeatureCollection","features":[
            {{"type":"Feature","properties":{{}},"geometry":{{"type":"Polygon","coordinates":[{SQUARE}]}}}},
            {{"type":"Feature","properties":{{}},"geometry":{{"type":"Polygon","coordinates":[{SQUARE}]}}}}]}}"#
        );
        assert_eq!(field(&text).unwrap_err().code, ErrorCode::AmbiguousBoundary);
        assert_eq!(
            field(r#"{"type":"FeatureCollection","features":[]}"#)
                .unwrap_err()
                .code,
            ErrorCode::NoBoundary
        );
    }

    #[test]
    fn obstacle_over_the_boundary_is_clipped_and_one_outside_is_refused() {
        let over = r#"[[24.0515,60.2505],[24.053,60.2505],[24.053,60.2507],[24.0515,60.2507],[24.0515,60.2505]]"#;
        let out = r#"[[24.06,60.26],[24.061,60.26],[24.061,60.261],[24.06,60.26]]"#;
        let fc = |obstacle: &str| {
            format!(
                r#"{{"type":"FeatureCollection","features":[
                {{"type":"Feature","properties":{{"role":"boundary"}},"geometry":{{"type":"Polygon","coordinates":[{SQUARE}]}}}},
                {{"type":"Feature","properties":{{"role":"obstacle"}},"geometry":{{"type":"Polygon","coordinates":[{obstacle}]}}}}]}}"#
            )
        };
        let (f, w) = field(&fc(over)).unwrap();
        assert_eq!(f.obstacles.len(), 1);
        assert!(w.iter().any(|w| w.code == WarningCode::ObstacleClipped));
        assert!(f
            .boundary
            .contains(&f.obstacles[0].polygon.interior_point_or_first()));
        let e = field(&fc(out)).unwrap_err();
        assert_eq!(e.code, ErrorCode::ObstacleOutsideField);
        assert_eq!(e.feature, Some(1));
    }

    #[test]
    fn overlapping_obstacles_are_merged() {
        let a = r#"[[24.0505,60.2502],[24.0508,60.2502],[24.0508,60.2504],[24.0505,60.2504],[24.0505,60.2502]]"#;
        let b = r#"[[24.0507,60.2503],[24.0510,60.2503],[24.0510,60.2505],[24.0507,60.2505],[24.0507,60.2503]]"#;
        let text = format!(
            r#"{{"type":"FeatureCollection","features":[
            {{"type":"Feature","properties":{{"role":"boundary"}},"geometry":{{"type":"Polygon","coordinates":[{SQUARE}]}}}},
            {{"type":"Feature","properties":{{"role":"obstacle"}},"geometry":{{"type":"Polygon","coordinates":[{a}]}}}},
            {{"type":"Feature","properties":{{"role":"obstacle"}},"geometry":{{"type":"Polygon","coordinates":[{b}]}}}}]}}"#
        );
        let (f, w) = field(&text).unwrap();
        assert_eq!(f.obstacles.len(), 1);
        assert!(w.iter().any(|w| w.code == WarningCode::ObstaclesMerged));
    }

    #[test]
    fn too_many_vertices_are_refused() {
        let n = MAX_VERTICES + 1;
        let ring: Vec<String> = (0..n)
            .map(|i| {
                let t = i as f64 / n as f64 * std::f64::consts::TAU;
                format!("[{},{}]", 24.0 + 0.01 * t.cos(), 60.0 + 0.005 * t.sin())
            })
            .collect();
        let text = format!(
            r#"{{"type":"Polygon","coordinates":[[{}]]}}"#,
            ring.join(",")
        );
        assert_eq!(field(&text).unwrap_err().code, ErrorCode::InputTooLarge);
    }

    #[test]
    fn a_prohibited_region_forbidding_every_direction_is_refused() {
        let region = r#"[[24.0505,60.2502],[24.0508,60.2502],[24.0508,60.2504],[24.0505,60.2504],[24.0505,60.2502]]"#;
        let fc = |ranges: &str| {
            format!(
                r#"{{"type":"FeatureCollection","features":[
                {{"type":"Feature","properties":{{"role":"boundary"}},"geometry":{{"type":"Polygon","coordinates":[{SQUARE}]}}}},
                {{"type":"Feature","properties":{{"role":"prohibited","forbidden_bearings_deg":{ranges}}},"geometry":{{"type":"Polygon","coordinates":[{region}]}}}}]}}"#
            )
        };
        let (f, _) = field(&fc("[[0, 90]]")).unwrap();
        assert_eq!(f.prohibited.len(), 1);
        for all in ["[[0, 180]]", "[[0, 360]]", "[[-180, 180]]"] {
            let e = field(&fc(all)).unwrap_err();
            assert_eq!(e.code, ErrorCode::NoAllowedDirection, "{all}");
            assert_eq!(e.feature, Some(1));
        }
    }

    #[test]
    fn an_entrance_far_from_the_field_is_refused() {
        let fc = |entrance: &str| {
            format!(
                r#"{{"type":"FeatureCollection","features":[
                {{"type":"Feature","properties":{{"role":"boundary"}},"geometry":{{"type":"Polygon","coordinates":[{SQUARE}]}}}},
                {{"type":"Feature","properties":{{"role":"entrance"}},"geometry":{{"type":"Point","coordinates":{entrance}}}}}]}}"#
            )
        };
        let (f, _) = field(&fc("[24.052, 60.2505]")).unwrap();
        assert_eq!(f.entrance, Some([24.052, 60.2505]));
        // 0.2 degrees of latitude north: 22 km.
        for far in [
            "[24.05, 60.45]",
            "[1e300, 1e300]",
            "[-155.95, -60.25]",
            "[24.05, 89.5]",
        ] {
            let e = field(&fc(far)).unwrap_err();
            assert_eq!(e.code, ErrorCode::CoordinateOutOfRange, "{far}");
            assert_eq!(e.feature, Some(1), "{far}");
            assert!(e.message.contains("entrance"), "{}", e.message);
        }
    }

    #[test]
    fn a_field_more_than_40_km_across_is_refused() {
        let text = r#"{"type":"Polygon","coordinates":[[[24,60],[25,60],[25,60.3],[24,60]]]}"#;
        assert_eq!(field(text).unwrap_err().code, ErrorCode::FieldTooLarge);
    }

    #[test]
    fn antimeridian_centre() {
        let (lon, lat) = centre_lon_lat(&[[179.9, 1.0], [-179.9, 1.0], [-179.9, 2.0]]);
        assert!((lon.abs() - 180.0).abs() < 1e-9, "{lon}");
        assert!((lat - 1.5).abs() < 1e-12);
    }

    trait InteriorPointOrFirst {
        fn interior_point_or_first(&self) -> Coord;
    }
    impl InteriorPointOrFirst for Polygon {
        fn interior_point_or_first(&self) -> Coord {
            use geo::InteriorPoint;
            self.interior_point()
                .map(|p| p.0)
                .unwrap_or(self.exterior().0[0])
        }
    }
}
