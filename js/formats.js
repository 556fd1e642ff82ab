// furrow/formats: field files read into the GeoJSON the planner takes (zipped Shapefiles or
// their parts dropped together, KML, KMZ), a WebAssembly module of its own (furrow_formats_wasm.js)
// loaded with its own init, so that a page that only plans GeoJSON never loads the readers.
// Loading, errors and recovery as the planner's (load.js).
import * as core from "./furrow_formats_wasm.js";
import { loader } from "./load.js";

export { FurrowError } from "./load.js";

const formats = loader(core, {
  what: "furrow/formats",
  // Literal, so that bundlers find the .wasm and rewrite the URL to their copy.
  wasmUrl: () => new URL("furrow_formats_wasm_bg.wasm", import.meta.url),
  entry: "furrow/formats",
  initName: "initFormats",
});

/**
 * Loads the readers' module: in a browser or worker it fetches furrow_formats_wasm_bg.wasm
 * beside this file (or what `input` names); in Node it reads that file.
 */
export default formats.init;
/** Loads the readers' module synchronously (as the planner's initSync). */
export const initSync = formats.initSync;

const readText = formats.guarded("readFieldFileText");
const readPartsText = formats.guarded("readShapefileText");

/** The parcels of a field file (a zipped Shapefile, KML or KMZ): see formats.d.ts. */
export function readFieldFile(bytes, name = "") {
  return JSON.parse(readText(asBytes(bytes), String(name)));
}

/** The parcels of a Shapefile given as its files (.shp, .shx, .dbf, .prj): see formats.d.ts. */
export function readShapefile(files) {
  const list = Array.from(files ?? []);
  return JSON.parse(
    readPartsText(
      list.map((f) => String(f?.name ?? "")),
      list.map((f) => asBytes(f?.bytes)),
    ),
  );
}

const taskDataText = formats.guarded("taskDataText");
const taskDataZip = formats.guarded("taskDataZip");

/** A plan as ISOXML TaskData, zipped as TASKDATA/TASKDATA.XML: see formats.d.ts. */
export function exportTaskData(field, plan, options = {}) {
  return taskDataZip(...taskDataArguments(field, plan, options));
}

/** A plan as the text of TASKDATA.XML: see formats.d.ts. */
export function taskDataXml(field, plan, options = {}) {
  return taskDataText(...taskDataArguments(field, plan, options));
}

const planKmlText = formats.guarded("planKmlText");

/** A plan as KML, for Google Earth: see formats.d.ts. */
export function exportKml(field, plan) {
  const [fieldText, planText] = taskDataArguments(field, plan, {});
  return planKmlText(fieldText, planText);
}

function taskDataArguments(field, plan, options) {
  const fieldText = typeof field === "string" ? field : JSON.stringify(field);
  // The plan's features only: its samples (typed arrays) are not needed.
  const planText = typeof plan === "string" ? plan : JSON.stringify({ type: "FeatureCollection", features: plan?.features ?? [] });
  const { width = NaN, version = 4, curvesAsAb = false, name } = options ?? {};
  return [fieldText, planText, Number(width), Number(version), Boolean(curvesAsAb), name == null ? undefined : String(name)];
}

function asBytes(b) {
  if (b instanceof Uint8Array) return b;
  if (b instanceof ArrayBuffer) return new Uint8Array(b);
  if (ArrayBuffer.isView(b)) return new Uint8Array(b.buffer, b.byteOffset, b.byteLength);
  return new Uint8Array(0);
}
