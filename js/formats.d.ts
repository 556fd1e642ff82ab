// Types of the package's "furrow/formats" entry: field files read into the GeoJSON the planner
// takes, from the wasm-bindgen module furrow_formats_wasm.js, wrapped by formats.js (which adds
// loading in Node, FurrowError and recovery from a trapped instance, as the planner's entry).
import type { InitInput, InitOutput, SyncInitInput } from "./furrow_formats_wasm.js";
import type { FieldFileGeoJson } from "./furrow_formats_wasm.js";

export type { FieldFileGeoJson, InitInput, InitOutput, SyncInitInput } from "./furrow_formats_wasm.js";
/** The same class as the planner's: `instanceof` holds for errors of every entry. */
export { FurrowError } from "./furrow.js";

/**
 * The parcels of a field file: a zipped Shapefile (`.zip` holding `.shp`, `.shx`, `.dbf` and
 * `.prj`), converted to WGS84 from the system its `.prj` names (WGS 84 and ETRS89, UTM on
 * either, RD New with its datum shift, ETRS-TM35FIN); KML or KMZ (every placemark's polygons,
 * their inner boundaries as holes, the placemark's name and extended data as properties); or
 * ISOXML TaskData, `TASKDATA.XML` or its zip (each partfield's boundary with its obstacles as
 * holes, its guidance lines as `guidance` and its first AB line as `reference_line`). Each polygon is a Feature: give the
 * collection to `plan` where it holds one, or one of its features where it holds several.
 * Throws a `FurrowError`: `invalid_file` (damaged, incomplete, not a format it reads), `unknown_crs` (a
 * system it does not convert from, named), `input_too_large` (over 64 MB, or unpacking to more
 * than 256 MB), `unsupported_geometry` (no polygons).
 */
export function readFieldFile(bytes: Uint8Array | ArrayBuffer, name?: string): FieldFileGeoJson;

/**
 * The parcels of a Shapefile given as its files, as dropped together: `.shp` (required),
 * `.shx`, `.dbf` and `.prj`, each with its name. As `readFieldFile` otherwise.
 */
export function readShapefile(files: Iterable<{ name: string; bytes: Uint8Array | ArrayBuffer }>): FieldFileGeoJson;

/** How a plan is written as ISOXML TaskData. */
export interface TaskDataOptions {
  /** The implement's working width, metres (the plan's `width`): the guidance lines' swath width. */
  width: number;
  /** 4 (the default: guidance groups and patterns, the headland polygon) or 3 for older terminals. */
  version?: 3 | 4;
  /** The headland passes as AB segments, for terminals that take no curves. */
  curvesAsAb?: boolean;
  /** The partfield's name (at most 32 plain characters are kept); the field's own name by default. */
  name?: string;
}

/**
 * A plan as ISO 11783-10 TaskData for an ISOBUS terminal, zipped as `TASKDATA/TASKDATA.XML`:
 * a partfield with the field's boundary and obstacles (and, in version 4, the headland's inner
 * edge), a guidance group per block with an AB
 * line along its swaths, and the headland passes as curves (version 3: the same lines as
 * guidance line strings of the partfield). `field` is the field's GeoJSON as planned (WGS84), `plan` the result of `plan` (or
 * its GeoJSON text).
 */
export function exportTaskData(field: unknown, plan: { features: unknown[] } | string, options: TaskDataOptions): Uint8Array;

/** The same as the text of TASKDATA.XML. */
export function taskDataXml(field: unknown, plan: { features: unknown[] } | string, options: TaskDataOptions): string;

/**
 * A plan as KML for Google Earth: folders of the field (boundary, obstacles), the blocks, the
 * swaths and headland passes (numbered in driving order), the turns and the connections.
 */
export function exportKml(field: unknown, plan: { features: unknown[] } | string): string;

/**
 * Loads the readers' module, once, before any other call of this entry (the planner's `init`
 * does not load it). In a browser or worker it fetches furrow_formats_wasm_bg.wasm beside
 * formats.js (where a bundler put it), or what `module_or_path` names; in Node it reads that
 * file. Throws a `FurrowError` with code `not_initialised` if it cannot.
 */
export default function initFormats(
  module_or_path?: { module_or_path: InitInput | Promise<InitInput> } | InitInput | Promise<InitInput>,
): Promise<InitOutput>;

/**
 * Loads the readers' module synchronously from the bytes of furrow_formats_wasm_bg.wasm or a
 * compiled `WebAssembly.Module` (`{ module }`); in Node 20.16 or later it may be left out.
 */
export function initSync(module?: { module: SyncInitInput } | SyncInitInput): InitOutput;
