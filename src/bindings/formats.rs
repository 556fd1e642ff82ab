//! The field files' entry point (`furrow/formats`): zipped Shapefiles (or their parts dropped
//! together), KML and KMZ read into the field's GeoJSON, in a module of its own so that a page that only
//! plans GeoJSON never loads the readers and projections.
//!
//! ```js
//! import initFormats, { readFieldFile } from "furrow/formats";
//! await initFormats();
//! const field = readFieldFile(new Uint8Array(await file.arrayBuffer()), file.name);
//! ```

use super::to_js_error;
use crate::error::{ErrorCode, PlanError};
use crate::formats::isoxml::{taskdata_xml, taskdata_zip, TaskDataSettings, TaskDataVersion};
use crate::formats::plan_kml::plan_kml;
use crate::formats::{read_field_file, read_shapefile_files};
use wasm_bindgen::prelude::*;

#[wasm_bindgen(typescript_custom_section)]
const TYPESCRIPT: &'static str = include_str!("formats.d.ts");

/// The parcels of a field file (its bytes and name), as GeoJSON text: see `formats.d.ts`.
#[wasm_bindgen(js_name = readFieldFileText, skip_typescript)]
pub fn read_field_file_text(bytes: &[u8], name: &str) -> Result<String, JsValue> {
    read_field_file(bytes, name)
        .map(|f| f.to_geojson_string())
        .map_err(|e| to_js_error(&e))
}

/// The parcels of a Shapefile given as its files (`names[i]` and `contents[i]`, each a
/// `Uint8Array`), as GeoJSON text.
#[wasm_bindgen(js_name = readShapefileText, skip_typescript)]
pub fn read_shapefile_text(names: Vec<String>, contents: js_sys::Array) -> Result<String, JsValue> {
    let bytes: Vec<Vec<u8>> = contents
        .iter()
        .map(|c| js_sys::Uint8Array::new(&c).to_vec())
        .collect();
    if bytes.len() != names.len() {
        let e = PlanError::new(
            ErrorCode::InvalidFile,
            "each file needs its name and its bytes",
        );
        return Err(to_js_error(&e));
    }
    let files: Vec<(&str, &[u8])> = names
        .iter()
        .map(String::as_str)
        .zip(bytes.iter().map(Vec::as_slice))
        .collect();
    read_shapefile_files(&files)
        .map(|f| f.to_geojson_string())
        .map_err(|e| to_js_error(&e))
}

/// How a plan is written as TaskData, from what JavaScript passes.
fn taskdata_settings(
    width: f64,
    version: u32,
    curves_as_ab: bool,
    name: Option<String>,
) -> Result<TaskDataSettings, JsValue> {
    let version = match version {
        3 => TaskDataVersion::V3,
        4 => TaskDataVersion::V4,
        v => {
            let e = PlanError::new(
                ErrorCode::InvalidOption,
                format!("option `version` is {v}: ISOXML TaskData is written in version 4, or 3 for older terminals"),
            );
            return Err(to_js_error(&e));
        }
    };
    Ok(TaskDataSettings {
        width_m: width,
        version,
        curves_as_ab,
        name,
    })
}

/// A plan (its GeoJSON text) of a field (its GeoJSON text) as the text of `TASKDATA.XML`.
#[wasm_bindgen(js_name = taskDataText, skip_typescript)]
pub fn task_data_text(
    field: &str,
    plan: &str,
    width: f64,
    version: u32,
    curves_as_ab: bool,
    name: Option<String>,
) -> Result<String, JsValue> {
    let settings = taskdata_settings(width, version, curves_as_ab, name)?;
    taskdata_xml(field, plan, &settings).map_err(|e| to_js_error(&e))
}

/// The same zipped as `TASKDATA/TASKDATA.XML`.
#[wasm_bindgen(js_name = taskDataZip, skip_typescript)]
pub fn task_data_zip(
    field: &str,
    plan: &str,
    width: f64,
    version: u32,
    curves_as_ab: bool,
    name: Option<String>,
) -> Result<Vec<u8>, JsValue> {
    let settings = taskdata_settings(width, version, curves_as_ab, name)?;
    taskdata_zip(field, plan, &settings).map_err(|e| to_js_error(&e))
}

/// A plan (its GeoJSON text) of a field (its GeoJSON text) as KML text.
#[wasm_bindgen(js_name = planKmlText, skip_typescript)]
pub fn plan_kml_text(field: &str, plan: &str) -> Result<String, JsValue> {
    plan_kml(field, plan).map_err(|e| to_js_error(&e))
}
