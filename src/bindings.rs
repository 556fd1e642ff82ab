//! The JavaScript API of the WebAssembly package. All wasm-bindgen code lives here; the planner
//! itself knows nothing of JavaScript.
//!
//! ```js
//! import init, { plan } from "furrow";
//! await init();
//! const result = plan(fieldGeoJson, { width: 6, headlandPasses: 2 });
//! ```
//!
//! Errors are thrown as `Error` objects with `name` `"FurrowError"` and a stable `code`, plus
//! `feature`, `ring`, `vertex` and `coordinate` where the problem has a place in the input.

use crate::error::{ErrorCode, PlanError};
use crate::field::{geojson, validate};
use crate::options::PlanOptions;
use crate::output::json::to_json_string;
use crate::plan::plan_stages;
use crate::tracks::{PlanTracks, Turning};
use serde::Deserialize;
use wasm_bindgen::prelude::*;
use web_time::Instant;

#[wasm_bindgen(typescript_custom_section)]
const TYPESCRIPT: &'static str = include_str!("bindings.d.ts");

/// Installs the panic hook, so that a bug shows its message in the console.
#[wasm_bindgen(start, skip_typescript)]
fn start() {
    console_error_panic_hook::set_once();
}

/// Plans a field. `field` is GeoJSON (an object, or its text); `options` may be left out.
/// Returns the plan as a GeoJSON FeatureCollection with `summary` and `warnings`.
/// (Its TypeScript declaration, with `options` optional, is in `bindings.d.ts`.)
#[wasm_bindgen(js_name = plan, skip_typescript)]
pub fn plan_js(field: JsValue, options: JsValue) -> Result<JsValue, JsValue> {
    let started = Instant::now();
    let options = read_options(options).map_err(|e| to_js_error(&e))?;
    // An object is read as its JSON text: one string across the boundary rather than a call
    // per property, and one reader for both forms. NaN and Infinity become null there, which
    // the reader takes for a coordinate that is not a finite number.
    let (text, object) = match field.as_string() {
        Some(text) => (text, false),
        None => (
            json_text(&field).map_err(|_| {
                to_js_error(&PlanError::new(
                    ErrorCode::InvalidGeojson,
                    "the field must be GeoJSON: its text, or an object of plain values",
                ))
            })?,
            true,
        ),
    };
    let input = geojson::parse_str(&text)
        .map_err(|e| if object { without_text_place(e) } else { e })
        .map_err(|e| to_js_error(&e))?;
    let (field, warnings) =
        validate::field_from_input(input, options.coordinates).map_err(|e| to_js_error(&e))?;
    let read_ms = started.elapsed().as_secs_f64() * 1000.0;
    let mut plan = plan_stages(field, &options, warnings).map_err(|e| to_js_error(&e))?;
    plan.summary.planning_ms = started.elapsed().as_secs_f64() * 1000.0;
    plan.summary.stages_ms.validation += read_ms;
    // One string and the engine's JSON.parse are much cheaper than building the object
    // property by property across the boundary.
    let text = to_json_string(&plan.to_geojson()).map_err(|e| {
        to_js_error(&PlanError::new(
            ErrorCode::Internal,
            format!("the plan could not be written: {e}"),
        ))
    })?;
    let result = js_sys::JSON::parse(&text)?;
    // The text is JavaScript's now: its memory goes back before the samples take theirs (a plan
    // of 100,000 swaths has 80 MB of it).
    drop(text);
    let samples = plan.samples();
    let columns = js_sys::Object::new();
    let put =
        |key: &str, value: JsValue| js_sys::Reflect::set(&columns, &JsValue::from_str(key), &value);
    for (key, column) in [
        ("x", &samples.x),
        ("y", &samples.y),
        ("heading_deg", &samples.heading_deg),
        ("curvature", &samples.curvature),
        ("distance_m", &samples.distance_m),
        ("time_s", &samples.time_s),
    ] {
        put(key, js_sys::Float64Array::from(&column[..]).into())?;
    }
    for (key, column) in [
        ("kind", &samples.kind),
        ("reverse", &samples.reverse),
        ("working", &samples.working),
    ] {
        put(key, js_sys::Uint8Array::from(&column[..]).into())?;
    }
    put(
        "segment",
        js_sys::Uint32Array::from(&samples.segment[..]).into(),
    )?;
    js_sys::Reflect::set(&result, &JsValue::from_str("samples"), &columns)?;
    Ok(result)
}

/// The tracks of a plan, for shortest paths along them (declared in `bindings.d.ts`): build it
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

fn json_text(value: &JsValue) -> Result<String, PlanError> {
    js_sys::JSON::stringify(value)
        .ok()
        .and_then(|s| s.as_string())
        .ok_or_else(|| {
            PlanError::new(
                ErrorCode::InvalidOption,
                "expected plain values (numbers, arrays, objects)",
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

/// The default value of every option.
#[wasm_bindgen(js_name = defaultOptions, unchecked_return_type = "Required<PlanOptions>")]
pub fn default_options() -> Result<JsValue, JsValue> {
    let text =
        to_json_string(&PlanOptions::default()).map_err(|e| JsValue::from_str(&e.to_string()))?;
    js_sys::JSON::parse(&text)
}

/// The version of the planner.
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").to_string()
}

fn read_options(options: JsValue) -> Result<PlanOptions, PlanError> {
    if options.is_undefined() || options.is_null() {
        return Ok(PlanOptions::default());
    }
    // Through JSON text, so that unknown keys (typos) are refused exactly as on the command line.
    let text = js_sys::JSON::stringify(&options)
        .ok()
        .and_then(|s| s.as_string())
        .ok_or_else(|| {
            PlanError::new(
                ErrorCode::InvalidOption,
                "options must be an object of plain values",
            )
        })?;
    PlanOptions::from_json_str(&text)
}

/// An error in reading an object through its JSON text, without the place in that text (which
/// the caller never saw): its feature says where.
fn without_text_place(mut e: PlanError) -> PlanError {
    if let Some(at) = e.message.rfind(" at line ") {
        e.message.truncate(at);
    }
    e.line = None;
    e.column = None;
    e
}

/// A `PlanError` as a JavaScript `Error` with `code` and the location fields.
fn to_js_error(e: &PlanError) -> JsValue {
    let error = js_sys::Error::new(&e.message);
    error.set_name("FurrowError");
    let object: &JsValue = error.as_ref();
    let set = |key: &str, value: JsValue| {
        // ok to ignore: setting a property on a fresh Error object cannot fail.
        let _ = js_sys::Reflect::set(object, &JsValue::from_str(key), &value);
    };
    set("code", JsValue::from_str(e.code.as_str()));
    if let Some(f) = e.feature {
        set("feature", JsValue::from(f as u32));
    }
    if let Some(r) = e.ring {
        set("ring", JsValue::from(r as u32));
    }
    if let Some(v) = e.vertex {
        set("vertex", JsValue::from(v as u32));
    }
    if let Some(l) = e.line {
        set("line", JsValue::from(l as u32));
    }
    if let Some(c) = e.column {
        set("column", JsValue::from(c as u32));
    }
    if let Some([x, y]) = e.coordinate {
        let array = js_sys::Array::of2(&JsValue::from(x), &JsValue::from(y));
        set("coordinate", array.into());
    }
    error.into()
}
