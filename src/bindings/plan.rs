//! The planner's entry point (`furrow`): plan a field, the default options, the version.
//!
//! ```js
//! import init, { plan } from "furrow";
//! await init();
//! const result = plan(fieldGeoJson, { width: 6, headlandPasses: 2 });
//! ```

use super::{json_text, to_js_error};
use crate::error::{ErrorCode, PlanError};
use crate::field::{geojson, validate};
use crate::options::{PlanOptions, DEFAULT_OPTIONS_JSON};
use crate::output::json::to_json_string;
use crate::plan::plan_stages;
#[cfg(feature = "pool-api")]
use crate::plan::share::{decode, encode, Pending, Share};
#[cfg(feature = "pool-api")]
use std::cell::Cell;
use wasm_bindgen::prelude::*;
use web_time::Instant;

#[wasm_bindgen(typescript_custom_section)]
const TYPESCRIPT: &'static str = include_str!("plan.d.ts");

/// Plans a field. `field` is GeoJSON (an object, or its text); `options` may be left out.
/// Returns the plan as a GeoJSON FeatureCollection with `summary` and `warnings`.
/// (Its TypeScript declaration, with `options` optional, is in `plan.d.ts`.)
#[wasm_bindgen(js_name = plan, skip_typescript)]
pub fn plan_js(field: JsValue, options: JsValue) -> Result<JsValue, JsValue> {
    let started = Instant::now();
    let options = read_options(options).map_err(|e| to_js_error(&e))?;
    let (field, warnings) = read_field(field, &options).map_err(|e| to_js_error(&e))?;
    let read_ms = started.elapsed().as_secs_f64() * 1000.0;
    let plan = plan_stages(field, &options, warnings).map_err(|e| to_js_error(&e))?;
    plan_result(plan, started, read_ms, false)
}

/// A plan begun by [`plan_share`], with when its reading began and how long it took.
#[cfg(feature = "pool-api")]
type Begun = Box<(Pending, Instant, f64)>;

#[cfg(feature = "pool-api")]
thread_local! {
    /// The plan [`plan_share`] began, until [`finish_share`] takes it.
    static PENDING: Cell<Option<Begun>> = const { Cell::new(None) };
}

/// Begins share `index` of `of` of a plan (the package's worker pool, `furrow/pool`): reads
/// and checks the field, lays its headlands and works this share's candidates. Returns their
/// summaries as numbers, for every share's [`finish_share`]. A plan begun before and not
/// finished is dropped.
#[cfg(feature = "pool-api")]
#[wasm_bindgen(js_name = planShare, skip_typescript)]
pub fn plan_share(
    field: JsValue,
    options: JsValue,
    index: u32,
    of: u32,
) -> Result<js_sys::Float64Array, JsValue> {
    PENDING.with(Cell::take);
    let started = Instant::now();
    let options = read_options(options).map_err(|e| to_js_error(&e))?;
    let (field, warnings) = read_field(field, &options).map_err(|e| to_js_error(&e))?;
    let read_ms = started.elapsed().as_secs_f64() * 1000.0;
    let share = Share {
        index: index as usize,
        of: of as usize,
    };
    let pending = Pending::start(field, &options, warnings, share).map_err(|e| to_js_error(&e))?;
    let numbers = encode(&pending.summaries());
    PENDING.with(|p| p.set(Some(Box::new((pending, started, read_ms)))));
    Ok(js_sys::Float64Array::from(&numbers[..]))
}

/// Fills this share's own best candidate ahead of the choice (see
/// [`Pending::fill_ahead`]): the pool's worker calls it after sending its summaries, while the
/// other shares finish their units.
#[cfg(feature = "pool-api")]
#[wasm_bindgen(js_name = fillAhead, skip_typescript)]
pub fn fill_ahead() {
    PENDING.with(|p| {
        let mut begun = p.take();
        if let Some(b) = begun.as_mut() {
            b.0.fill_ahead();
        }
        p.set(begun);
    });
}

/// Finishes the plan [`plan_share`] began, given every share's summaries (one after another):
/// where this share holds the candidate chosen, the plan as [`plan_js`] gives it but with its
/// GeoJSON as text in `json` beside `samples` (a string crosses to the page's thread far
/// cheaper than the object, which the page then parses); else `null`.
#[cfg(feature = "pool-api")]
#[wasm_bindgen(js_name = finishShare, skip_typescript)]
pub fn finish_share(summaries: &[f64]) -> Result<JsValue, JsValue> {
    let internal = |m: &str| to_js_error(&PlanError::new(ErrorCode::Internal, m));
    let (pending, started, read_ms) = *PENDING
        .with(Cell::take)
        .ok_or_else(|| internal("no plan was begun in this share"))?;
    let summaries =
        decode(summaries).ok_or_else(|| internal("the shares' summaries are unreadable"))?;
    match pending.finish(&summaries) {
        None => Ok(JsValue::NULL),
        Some(plan) => plan_result(plan.map_err(|e| to_js_error(&e))?, started, read_ms, true),
    }
}

/// Reads a field given as GeoJSON text or as an object. An object is read as its JSON text:
/// one string across the boundary rather than a call per property, and one reader for both
/// forms. NaN and Infinity become null there, which the reader takes for a coordinate that is
/// not a finite number.
fn read_field(
    field: JsValue,
    options: &PlanOptions,
) -> Result<(crate::field::Field, Vec<crate::error::Warning>), PlanError> {
    let (text, object) = match field.as_string() {
        Some(text) => (text, false),
        None => (
            json_text(&field).map_err(|_| {
                PlanError::new(
                    ErrorCode::InvalidGeojson,
                    "the field must be GeoJSON: its text, or an object of plain values",
                )
            })?,
            true,
        ),
    };
    let input =
        geojson::parse_str(&text).map_err(|e| if object { without_text_place(e) } else { e })?;
    validate::field_from_input(input, options.coordinates)
}

/// The plan as JavaScript: its GeoJSON with `summary` and `warnings` (or, `as_text`, the
/// GeoJSON's text as `json`), and the sampled path's columns as typed arrays in `samples`.
/// `read_ms` (reading the input) counts to the validation stage.
fn plan_result(
    mut plan: crate::plan::Plan,
    started: Instant,
    read_ms: f64,
    as_text: bool,
) -> Result<JsValue, JsValue> {
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
    let result = if as_text {
        let object = js_sys::Object::new();
        js_sys::Reflect::set(
            &object,
            &JsValue::from_str("json"),
            &JsValue::from_str(&text),
        )?;
        object.into()
    } else {
        js_sys::JSON::parse(&text)?
    };
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

/// The default value of every option.
#[wasm_bindgen(js_name = defaultOptions, unchecked_return_type = "Required<PlanOptions>")]
pub fn default_options() -> Result<JsValue, JsValue> {
    js_sys::JSON::parse(DEFAULT_OPTIONS_JSON)
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
