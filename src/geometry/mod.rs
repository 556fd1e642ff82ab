//! Small geometric helpers shared by the pipeline stages: compass bearings, and sets of parallel
//! lines clipped by polygons (the core of swath generation).

pub mod bearing;
pub mod parallel_lines;

pub use bearing::{bearing_of, deg_to_bearing, swath_direction, unit_vector};
pub use parallel_lines::SweepFrame;
