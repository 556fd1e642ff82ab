//! # furrow
//!
//! Coverage path planning for farm machines: from a field boundary drawn or recorded in GeoJSON,
//! the headland passes, swaths, blocks, route and path a tractor drives to work the whole field.
//!
//! The pipeline, one module per stage:
//!
//! 1. [`field`]: read GeoJSON, project to local metres, repair and validate;
//! 2. [`direction`]: the driving direction of the swaths;
//! 3. [`obstacles`] and [`headland`]: obstacle classes A-D, headland passes around the boundary
//!    and the obstacles, and the inner field they leave;
//! 4. [`swath`]: parallel swaths one working width apart covering the inner field;
//! 5. [`decompose`]: blocks of swaths that can be worked one after the other;
//! 6. [`route`]: the order of blocks, swaths and headland passes;
//! 7. [`path`]: the continuous path, with turns and connections;
//! 8. [`metrics`]: distances, areas and counts, and [`coverage`]: the implement's footprint
//!    against the field, what it could reach, and the crop left standing;
//! 9. [`tracks`]: the lanes the plan leaves, for driving on existing tracks later.
//!
//! [`plan()`] runs them in order; [`output`] writes the result as GeoJSON in the input's
//! coordinates. Inside, all lengths are metres and all angles radians, with bearings measured
//! clockwise from north; the API speaks metres and compass degrees.
//!
//! ```
//! use furrow::{plan_geojson, PlanOptions};
//!
//! let field = r#"{"type": "Polygon", "coordinates": [[[24.05, 60.25], [24.056, 60.25],
//!     [24.056, 60.252], [24.05, 60.252], [24.05, 60.25]]]}"#;
//! let options = PlanOptions { width: 6.0, headland_passes: 2.into(), ..Default::default() };
//! let plan = plan_geojson(field, &options)?;
//! assert!(plan.summary.swath_count > 0);
//! let geojson: serde_json::Value = serde_json::from_str(&plan.to_geojson_string())?;
//! assert_eq!(geojson["type"], "FeatureCollection");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#![warn(missing_docs)]
// PlanError is a plain struct with its place in the input (feature, ring, vertex, coordinate,
// line, column) so that callers can read it directly; it travels only on the cold error path.
#![allow(clippy::result_large_err)]

pub mod coverage;
pub mod decompose;
pub mod direction;
pub mod error;
pub mod field;
pub mod fill;
#[cfg(feature = "formats")]
pub mod formats;
pub mod geometry;
pub mod headland;
pub mod metrics;
mod named;
pub mod numbers;
pub mod objective;
pub mod obstacles;
pub mod options;
pub mod output;
pub mod path;
pub mod plan;
pub mod prohibited;
pub mod rng;
pub mod route;
pub mod small_alloc;
pub mod sort;
pub mod swath;
pub mod tracks;

#[cfg(target_arch = "wasm32")]
pub mod bindings;

/// The npm package's allocator (feature `small-alloc`): small blocks reused in front of
/// dlmalloc, single-threaded, so only where wasm runs without threads.
#[cfg(all(
    feature = "small-alloc",
    target_arch = "wasm32",
    not(target_feature = "atomics")
))]
#[global_allocator]
// SAFETY: wasm32 without atomics runs one thread.
static ALLOCATOR: small_alloc::SmallBlocks<std::alloc::System> =
    unsafe { small_alloc::SmallBlocks::new(std::alloc::System) };

/// The fixed seed of the property tests, shared with the integration tests.
#[cfg(test)]
#[path = "../tests/common/seeded.rs"]
mod seeded;

pub use error::{ErrorCode, PlanError, Warning, WarningCode};
pub use options::PlanOptions;
pub use plan::{plan, plan_geojson, Plan};
