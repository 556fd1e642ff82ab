//! Each block at its own best direction.
//!
//! A block of a decomposition (a boustrophedon cell, or a split-and-merge block after pieces
//! were joined to it) is not always worked fastest at the direction it came with: a bay of a
//! field swept at the main direction is often worked faster along its own length. This step
//! searches each block's direction again, by the estimated time of the block on its own
//! ([`block_time`]), among the directions every prohibited region it reaches into allows,
//! trying the block's own direction and its longest edges first. A block changes direction
//! only when that saves time.

use super::join::{block_time, exact_block_time, rough};
use super::split_merge::SplitMergeSettings;
use super::BlockArea;
use crate::direction::{edge_directions, quick_search};
use crate::error::PlanError;
use crate::prohibited::constraints_in;

/// The share of a block's time a new direction must save.
const MIN_SAVING: f64 = 0.01;

/// Gives each block the direction at which it is worked fastest (see the module documentation);
/// returns the blocks and the number of directions evaluated.
///
/// ```
/// use furrow::decompose::redirect::redirect_blocks;
/// use furrow::decompose::split_merge::{Criterion, SplitMergeSettings};
/// use furrow::decompose::BlockArea;
/// use furrow::direction::SearchMethod;
/// use furrow::objective::Machine;
/// use geo::{polygon, MultiPolygon};
///
/// // A strip 300 m long running east, given to the block at north: it turns to east-west.
/// let strip = polygon![(x: 0., y: 0.), (x: 300., y: 0.), (x: 300., y: 60.), (x: 0., y: 60.)];
/// let s = SplitMergeSettings {
///     width: 6.0, min_length: 6.0,
///     machine: Machine { width: 6.0, turn_radius: 8.0, working_speed: 2.2, turning_speed: 1.4 },
///     method: SearchMethod::CoarseToFine, step_deg: 1.0, forbidden: &[], regions: &[],
///     criterion: Criterion::default(), min_end_angle: 20f64.to_radians(), tolerance: 3.0, orders: &[],
/// };
/// let (blocks, evaluations) =
///     redirect_blocks(vec![BlockArea { area: MultiPolygon::new(vec![strip]), bearing: 0.0 }], &s)?;
/// assert!((blocks[0].bearing.to_degrees() - 90.0).abs() < 1e-6);
/// assert!(evaluations > 10);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn redirect_blocks(
    blocks: Vec<BlockArea>,
    s: &SplitMergeSettings,
) -> Result<(Vec<BlockArea>, usize), PlanError> {
    let all = vec![true; blocks.len()];
    redirect_some(blocks, &all, s)
}

/// [`redirect_blocks`] for the blocks marked in `which` only (the others keep their direction).
pub fn redirect_some(
    blocks: Vec<BlockArea>,
    which: &[bool],
    s: &SplitMergeSettings,
) -> Result<(Vec<BlockArea>, usize), PlanError> {
    let min_area = s.width * s.width * 1e-2;
    let mut evaluations = 0;
    let mut out = Vec::with_capacity(blocks.len());
    for (k, mut b) in blocks.into_iter().enumerate() {
        if !which.get(k).copied().unwrap_or(true) {
            out.push(b);
            continue;
        }
        let allowed = constraints_in(&b.area, s.regions, s.forbidden, min_area);
        let estimate = rough(&b.area, s);
        let current = if allowed.iter().any(|r| r.forbids(b.bearing)) {
            f64::INFINITY
        } else {
            block_time(&estimate, b.bearing, s)?
        };
        let mut seeds = vec![b.bearing];
        seeds.extend(edge_directions(
            b.area.0.iter().map(|p| p.exterior()),
            s.width / 2.0,
        ));
        let mut error = None;
        let found = quick_search(
            s.method,
            s.step_deg,
            &allowed,
            &seeds,
            |bearing| match block_time(&estimate, bearing, s) {
                Ok(t) => t,
                Err(e) => {
                    error.get_or_insert(e);
                    f64::INFINITY
                }
            },
        );
        if let Some(e) = error {
            return Err(e);
        }
        // A block whose regions leave no direction keeps its own (the planner warns of those).
        if let Ok(r) = found {
            evaluations += r.evaluations;
            // The estimate takes strips reaching over the edge for crop worked: the exact
            // coverage has the last word.
            let forbidden_now = allowed.iter().any(|x| x.forbids(b.bearing));
            // A block changes direction for a real saving only: a degree or two off the edge it
            // was cut along looks wrong to a driver, and saves next to nothing.
            if forbidden_now
                || (r.cost < current * (1.0 - MIN_SAVING)
                    && exact_block_time(&b.area, r.bearing, s)?
                        < exact_block_time(&b.area, b.bearing, s)? * (1.0 - MIN_SAVING))
            {
                b.bearing = r.bearing;
            }
        }
        out.push(b);
    }
    Ok((out, evaluations))
}
