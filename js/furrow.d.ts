// Types of the furrow package: the planner's types and functions from the wasm-bindgen module,
// re-exported by furrow.js, which adds recovery from a trapped instance.
export type {
  GeoJsonObject,
  FieldInput,
  PlanOptions,
  PlanFeatureKind,
  PlanFeatureProperties,
  Position,
  PlanFeature,
  PlanSummary,
  PlanWarning,
  Plan,
  ErrorCode,
  FurrowError,
  InitInput,
  InitOutput,
  SyncInitInput,
} from "./furrow_wasm.js";
export { plan, defaultOptions, version, initSync, default } from "./furrow_wasm.js";
