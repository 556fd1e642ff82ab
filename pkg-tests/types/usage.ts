// A TypeScript user of the package: compiled with `tsc --strict --noEmit` by types.test.mjs
// against the built package (node_modules/furrow there), so that a type missing from the
// package's exports, or declarations that do not compile strictly, fail the test.
import init, {
  defaultOptions,
  FurrowError,
  initSync,
  plan,
  version,
  type Decomposition,
  type DirectionMode,
  type ErrorCode,
  type FieldInput,
  type FurrowErrorDetails,
  type ObjectiveName,
  type PathSamples,
  type Plan,
  type PlanFeature,
  type PlanOptions,
  type PlanSummary,
  type PlanWarning,
  type Position,
  type SearchMethod,
  type SwathPattern,
} from "furrow";
import initTracks, {
  FurrowError as TracksError,
  shortestPath,
  TrackGraph,
  type TrackPathFeature,
  type TrackPathOptions,
  type Turning,
} from "furrow/tracks";
import initFormats, { readFieldFile, readShapefile, type FieldFileGeoJson } from "furrow/formats";

export async function load(bytes?: Uint8Array): Promise<string> {
  if (bytes) initSync({ module: bytes });
  else await init();
  await initTracks();
  return version();
}

export function planned(field: FieldInput, decomposition: Decomposition, pattern: SwathPattern): Plan {
  const direction: DirectionMode = "search";
  const search: SearchMethod = "coarse-to-fine";
  const objective: ObjectiveName = "time";
  const options: PlanOptions = { ...defaultOptions(), width: 6, direction, search, objective, decomposition, pattern };
  return plan(field, options);
}

export function summary(result: Plan): [PlanSummary, PlanFeature[], PlanWarning[]] {
  const samples: PathSamples = result.samples;
  const x: Float64Array = samples.x;
  return [result.summary, result.features.filter((f) => x.length > 0 && f.properties.kind === "swath"), result.warnings];
}

export function wayOut(result: Plan, from: Position, to: Position): TrackPathFeature {
  const turning: Turning = "heading";
  const options: TrackPathOptions = { turning };
  const tracks = new TrackGraph(result);
  try {
    return tracks.shortestPath(from, 0, to, options);
  } finally {
    tracks.free();
  }
}

/** What went wrong, for the user: FurrowError is a class, checked with instanceof. */
export function describe(e: unknown): string {
  if (e instanceof FurrowError) {
    const code: ErrorCode = e.code;
    const details: FurrowErrorDetails = e;
    const where = e.coordinate ? ` at ${e.coordinate[0]}, ${e.coordinate[1]}` : "";
    return `${e.name} ${code}${where}: ${e.message} (feature ${details.feature ?? "-"})`;
  }
  return String(e);
}

export const refused: FurrowError = new TracksError("no way out", { code: "no_path" });
export const oneCall = (result: Plan, from: Position, to: Position[]): TrackPathFeature =>
  shortestPath(result, from, 90, to);

/** The first parcel of a zipped Shapefile, planned; or of its parts dropped together. */
export async function planFirstParcel(zip: Uint8Array, parts?: { name: string; bytes: Uint8Array }[]): Promise<Plan> {
  await initFormats();
  const file: FieldFileGeoJson = parts ? readShapefile(parts) : readFieldFile(zip, "fields.zip");
  const crs: string = file.source.crs;
  return plan(file.features[0], { width: 6, headlandPasses: crs.startsWith("EPSG") ? 2 : 1 });
}

// Planning in a pool of workers (furrow/pool).
import { MAX_WORKERS, PlannerPool, planInWorkers, FurrowError as PoolError } from "furrow/pool";

export async function planInPool(field: FieldInput, options: PlanOptions): Promise<[Plan, Plan, number]> {
  const pool = new PlannerPool({ workers: Math.min(2, MAX_WORKERS) });
  try {
    const a: Plan = await pool.plan(field, options);
    const b: Plan = await planInWorkers(field, options, { workers: pool.size });
    return [a, b, a.summary.swath_count];
  } catch (e) {
    if (e instanceof PoolError) throw new Error(e.code);
    throw e;
  } finally {
    pool.terminate();
  }
}
