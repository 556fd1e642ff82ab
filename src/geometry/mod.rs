//! Small geometric helpers shared by the pipeline stages: boolean operations and buffers of
//! polygons, compass bearings, point-to-segment distance, the planar `hypot`, `min`, `max` and
//! `round` of the hot loops, Douglas-Peucker simplification and sleeve fitting, whether two
//! polygons come within a distance, segments for R-trees, sets of parallel lines clipped by
//! polygons (the core of swath generation; one such line limited to a segment), and the union,
//! intersection and difference of the pieces of a line.

pub mod bearing;
pub mod bearing_range;
pub mod distance;
pub mod intervals;
pub mod overlay;
pub mod parallel_lines;
pub mod polygon_distance;
pub mod round;
pub mod segment_tree;
pub mod simplify;
pub mod sleeve;

pub use bearing::{bearing_of, deg_to_bearing, swath_direction, unit_vector};
pub use bearing_range::{forbids_every_direction, BearingRange};
pub use distance::{point_segment_distance, segment_foot, Extremes, PlanarHypot};
pub use overlay::{buffer_line, buffer_region, BooleanOps};
pub use parallel_lines::{clip_segment, SweepFrame};
pub use polygon_distance::polygons_within;
pub use round::round_half_away;
pub use segment_tree::IndexedSegment;
pub use simplify::PlanarSimplify;
pub use sleeve::{sleeve_ring, Sleeve};
