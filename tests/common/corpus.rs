//! The benchmark fields kept in `tests/fields` (a copy of the workplace's shared corpus), with the
//! machine settings their README suggests. Shared by the integration tests and the benchmarks.
#![allow(dead_code)]

use furrow::PlanOptions;
use std::path::{Path, PathBuf};

/// Where the fields are.
pub fn fields_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fields")
}

/// One valid corpus field and its suggested settings.
#[derive(Debug, Clone)]
pub struct CorpusField {
    /// File name without `.geojson`.
    pub name: String,
    pub path: PathBuf,
    pub area_ha: f64,
    pub obstacles: usize,
    pub options: PlanOptions,
}

impl CorpusField {
    pub fn text(&self) -> String {
        std::fs::read_to_string(&self.path).expect("corpus field readable")
    }
}

/// The valid fields, with the width, headland passes and turning radius from the README's table.
pub fn valid_fields() -> Vec<CorpusField> {
    let readme = std::fs::read_to_string(fields_dir().join("README.md")).expect("fields README");
    let mut out = Vec::new();
    for line in readme.lines() {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        // | file | area ha | vertices | obstacles | prohibited | width m | headland passes | turn radius m | note |
        if cells.len() < 10 || !cells[1].ends_with(".geojson") {
            continue;
        }
        let num = |i: usize| -> f64 { cells[i].parse().expect("number in fields README") };
        let name = cells[1].trim_end_matches(".geojson").to_string();
        out.push(CorpusField {
            path: fields_dir().join(cells[1]),
            name,
            area_ha: num(2),
            obstacles: num(4) as usize,
            options: PlanOptions {
                width: num(6),
                headland_passes: (num(7) as u32).into(),
                turn_radius: num(8),
                ..PlanOptions::default()
            },
        });
    }
    assert!(
        out.len() >= 20,
        "fields README table not found or changed shape"
    );
    out
}

/// The valid field `name` (file name without `.geojson`), with its suggested settings.
pub fn valid_field(name: &str) -> CorpusField {
    valid_fields()
        .into_iter()
        .find(|f| f.name == name)
        .unwrap_or_else(|| panic!("no corpus field {name}"))
}

/// The invalid inputs and the error code each must give.
pub fn invalid_fields() -> Vec<(PathBuf, &'static str)> {
    let expected = [
        ("hole-crossing-boundary", "hole_crossing_boundary"),
        ("lat-lon-swapped", "coordinates_swapped"),
        ("latitude-out-of-range", "coordinate_out_of_range"),
        ("nan-coordinates", "invalid_json"),
        ("not-geojson", "invalid_json"),
        ("obstacle-outside-field", "obstacle_outside_field"),
        ("self-intersecting-bowtie", "self_intersection"),
        ("too-few-points", "too_few_points"),
        ("zero-area", "zero_area"),
    ];
    expected
        .iter()
        .map(|(name, code)| (fields_dir().join(format!("invalid/{name}.geojson")), *code))
        .collect()
}

/// Every feature of the real-parcel samples as its own GeoJSON Feature text, with its file and index.
pub fn real_parcels() -> Vec<(String, usize, String)> {
    let mut out = Vec::new();
    for file in ["dk_marker_2026_sample", "nl_brp_2023_sample"] {
        let path = fields_dir().join(format!("real/{file}.geojson"));
        let text = std::fs::read_to_string(&path).expect("real parcels readable");
        let v: serde_json::Value = serde_json::from_str(&text).expect("real parcels are JSON");
        for (i, f) in v["features"]
            .as_array()
            .expect("features")
            .iter()
            .enumerate()
        {
            out.push((file.to_string(), i, f.to_string()));
        }
    }
    out
}

/// How many headland passes a plan's path drives (a pass with manoeuvres is several segments
/// of one route step, with turns between).
pub fn passes_driven(plan: &furrow::Plan) -> usize {
    let mut steps: Vec<usize> = plan
        .path
        .segments
        .iter()
        .filter(|s| s.kind == furrow::path::SegmentKind::HeadlandPass)
        .filter_map(|s| s.step)
        .collect();
    steps.dedup();
    steps.len()
}

/// How far (metres) a swath's strip reaches out of the region its plan measures the headland
/// from (the field less the obstacles with headlands): the farthest of the strip's four corners,
/// a millimetre in from its sides; 0 where all four are inside.
pub fn strip_out_of_region(plan: &furrow::Plan, s: &furrow::swath::Swath) -> f64 {
    use geo::{Contains, Distance, Euclidean, Point};
    let half = plan.options.width / 2.0 - 1e-3;
    let region = &plan.headlands.region;
    [
        (-half, s.along.0),
        (half, s.along.0),
        (-half, s.along.1),
        (half, s.along.1),
    ]
    .into_iter()
    .map(|(c, a)| Point(s.frame.point(s.across + c, a)))
    .map(|p| {
        if region.contains(&p) {
            0.0
        } else {
            Euclidean.distance(&p, region)
        }
    })
    .fold(0.0, f64::max)
}
