//! The tracks' entry point (`furrow/tracks`): shortest paths along a plan's tracks.
//!
//! ```js
//! import initTracks, { shortestPath } from "furrow/tracks";
//! await initTracks();
//! const way = shortestPath(plan, [lon, lat], headingDeg, [targetLon, targetLat]);
//! ```

use super::{json_text, to_js_error};
use crate::error::{ErrorCode, PlanError};
use crate::output::json::to_json_string;
use crate::tracks::{PlanTracks, Turning};
use serde::Deserialize;
use wasm_bindgen::prelude::*;

#[wasm_bindgen(typescript_custom_section)]
const TYPESCRIPT: &'static str = include_str!("tracks.d.ts");

/// The tracks of a plan, for shortest paths along them (declared in `tracks.d.ts`): build it
/// once per plan, ask it many times.
#[wasm_bindgen(js_name = TrackGraph, skip_typescript)]
pub struct TrackGraphJs {
    inner: PlanTracks,
}

#[wasm_bindgen(js_class = TrackGraph)]
impl TrackGraphJs {
    /// The tracks of `plan` (the result of `plan`, or its GeoJSON); `options.coordinates` is the
    /// plan's (`wgs84` by default).
    #[wasm_bindgen(constructor)]
    pub fn new(plan: JsValue, options: JsValue) -> Result<TrackGraphJs, JsValue> {
        let options = read_path_options(&options).map_err(|e| to_js_error(&e))?;
        let inner = plan_tracks(&plan, &options).map_err(|e| to_js_error(&e))?;
        Ok(TrackGraphJs { inner })
    }

    /// The shortest path along the tracks: see `shortestPath`.
    #[wasm_bindgen(js_name = shortestPath)]
    pub fn shortest_path(
        &self,
        position: JsValue,
        heading: f64,
        target: JsValue,
        options: JsValue,
    ) -> Result<JsValue, JsValue> {
        let options = read_path_options(&options).map_err(|e| to_js_error(&e))?;
        answer(&self.inner, &position, heading, &target, &options).map_err(|e| to_js_error(&e))
    }

    /// Number of tracks.
    #[wasm_bindgen(getter, js_name = trackCount)]
    pub fn track_count(&self) -> u32 {
        self.inner.graph.tracks().len() as u32
    }

    /// Number of junctions.
    #[wasm_bindgen(getter, js_name = junctionCount)]
    pub fn junction_count(&self) -> u32 {
        self.inner.graph.junctions().len() as u32
    }
}

/// The shortest path along the plan's tracks from `position` (facing `heading`, compass
/// degrees) to `target` (a position, or several: the nearest wins), as a GeoJSON Feature.
#[wasm_bindgen(js_name = shortestPath, skip_typescript)]
pub fn shortest_path_js(
    plan: JsValue,
    position: JsValue,
    heading: f64,
    target: JsValue,
    options: JsValue,
) -> Result<JsValue, JsValue> {
    let options = read_path_options(&options).map_err(|e| to_js_error(&e))?;
    let tracks = plan_tracks(&plan, &options).map_err(|e| to_js_error(&e))?;
    answer(&tracks, &position, heading, &target, &options).map_err(|e| to_js_error(&e))
}

/// The options of a shortest path.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields, rename_all = "camelCase")]
struct PathOptions {
    #[serde(default)]
    turning: Option<String>,
    #[serde(default)]
    coordinates: Option<crate::field::Coordinates>,
}

fn read_path_options(options: &JsValue) -> Result<PathOptions, PlanError> {
    if options.is_undefined() || options.is_null() {
        return Ok(PathOptions::default());
    }
    let text = json_text(options)?;
    serde_json::from_str(&text).map_err(|e| {
        PlanError::new(
            ErrorCode::InvalidOption,
            format!("invalid shortest-path option: {e}"),
        )
    })
}

/// The tracks of a plan given from JavaScript: only its `features` are read (not the typed
/// arrays of samples).
fn plan_tracks(plan: &JsValue, options: &PathOptions) -> Result<PlanTracks, PlanError> {
    let coordinates = options.coordinates.unwrap_or_default();
    if let Some(text) = plan.as_string() {
        return PlanTracks::from_geojson(&text, coordinates);
    }
    let features = js_sys::Reflect::get(plan, &JsValue::from_str("features"))
        .ok()
        .filter(js_sys::Array::is_array)
        .ok_or_else(|| {
            PlanError::new(
                ErrorCode::InvalidGeojson,
                "a plan is a FeatureCollection: it has no `features`",
            )
        })?;
    let text = json_text(&features)?;
    PlanTracks::from_geojson(&format!("{{\"features\":{text}}}"), coordinates)
}

fn answer(
    tracks: &PlanTracks,
    position: &JsValue,
    heading: f64,
    target: &JsValue,
    options: &PathOptions,
) -> Result<JsValue, PlanError> {
    let turning = match options.turning.as_deref() {
        None => Turning::default(),
        Some(name) => Turning::parse(name).ok_or_else(|| {
            PlanError::new(
                ErrorCode::InvalidOption,
                format!("turning \"{name}\": expected \"tracks\", \"heading\" or \"on-the-spot\""),
            )
        })?,
    };
    let position: [f64; 2] = serde_json::from_str(&json_text(position)?).map_err(|_| {
        PlanError::new(
            ErrorCode::InvalidOption,
            "position must be [x, y] (longitude, latitude)",
        )
    })?;
    // One position, or a list of them.
    let target_text = json_text(target)?;
    let targets: Vec<[f64; 2]> = serde_json::from_str::<[f64; 2]>(&target_text)
        .map(|t| vec![t])
        .or_else(|_| serde_json::from_str::<Vec<[f64; 2]>>(&target_text))
        .map_err(|_| {
            PlanError::new(
                ErrorCode::InvalidOption,
                "target must be a position [x, y] or a list of positions",
            )
        })?;
    let path = tracks.shortest_path(position, heading, &targets, turning)?;
    let text = to_json_string(&tracks.to_feature(&path, turning)).map_err(|e| {
        PlanError::new(
            ErrorCode::Internal,
            format!("the path could not be written: {e}"),
        )
    })?;
    js_sys::JSON::parse(&text)
        .map_err(|_| PlanError::new(ErrorCode::Internal, "the path could not be read"))
}
