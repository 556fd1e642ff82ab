//! The JavaScript API of the WebAssembly package. All wasm-bindgen code lives here; the planner
//! itself knows nothing of JavaScript. The package has four modules, each built from this crate
//! with one feature, so that a page that only plans never loads the tracks' or the readers' code:
//!
//! - `planner-api` ([`plan`]): `plan`, `defaultOptions`, `version` (the package's `furrow` entry);
//! - `pool-api` ([`plan`]): the same and `planShare`, `finishShare`, for the workers of the
//!   package's `furrow/pool` entry (`js/pool.js`);
//! - `tracks-api` ([`tracks`]): `TrackGraph`, `shortestPath` (its `furrow/tracks` entry);
//! - `formats-api` ([`formats`]): `readFieldFile`, `readShapefile` (its `furrow/formats` entry).
//!
//! ```js
//! import init, { plan } from "furrow";
//! await init();
//! const result = plan(fieldGeoJson, { width: 6, headlandPasses: 2 });
//! ```
//!
//! Errors are thrown as `Error` objects with `name` `"FurrowError"` and a stable `code`, plus
//! `feature`, `ring`, `vertex` and `coordinate` where the problem has a place in the input.

#[cfg(feature = "formats-api")]
pub mod formats;
#[cfg(feature = "planner-api")]
pub mod plan;
#[cfg(feature = "tracks-api")]
pub mod tracks;

use crate::error::PlanError;
use wasm_bindgen::prelude::*;

/// Installs the panic hook, so that a bug shows its message in the console.
#[wasm_bindgen(start, skip_typescript)]
fn start() {
    console_error_panic_hook::set_once();
}

/// A JavaScript value as JSON text (the planner's and the tracks' inputs).
#[cfg(any(feature = "planner-api", feature = "tracks-api"))]
fn json_text(value: &JsValue) -> Result<String, PlanError> {
    js_sys::JSON::stringify(value)
        .ok()
        .and_then(|s| s.as_string())
        .ok_or_else(|| {
            PlanError::new(
                crate::error::ErrorCode::InvalidOption,
                "expected plain values (numbers, arrays, objects)",
            )
        })
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
