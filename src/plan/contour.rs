//! Contour work chosen by the objective: a field narrow enough to be worked by a few passes
//! following its outline (`headlandPasses: "all"`) is planned that way too, and that plan kept
//! where it leaves no more crop standing and takes less time than the swaths, with the crop
//! each leaves counted as worked at working speed (as `auto` compares decompositions,
//! [`super::auto`]). A bent strip is then
//! driven along its length, round its bends, rather than in straight pieces cut short at each
//! bend with a turn at both ends of every one.

use super::plan_with_passes;
use super::Plan;
use crate::decompose::Decomposition;
use crate::error::Warning;
use crate::field::Field;
use crate::headland::passes::HeadlandPasses;
use crate::headland::HeadlandMode;
use crate::options::PlanOptions;

/// Most passes to the middle (by the field's bounding box, as `headlandPasses: "all"` counts them) for contour
/// work to be tried: beyond, the passes' inner rings are too short and too many for it to pay,
/// and planning the field twice would cost time on every edit.
pub const CONTOUR_MAX_PASSES: u32 = 12;

/// Swaths that work this share of what the implement can reach are kept without contour work
/// weighed (it must leave no more crop standing to be kept, and seldom can).
const WELL_COVERED: f64 = 0.99;

/// The decomposition report's reason where the passes to the middle are kept (its candidates
/// are then that plan's own, one).
pub const REASON: &str =
    "passes following the field's outline to its middle: less time than swaths, no more crop left";

/// A plan that loses by less than this share of its time keeps the swaths (the simpler plan).
const TIE: f64 = 1e-3;

/// Whether contour work is weighed for `field` with `options`: `auto` decomposition, a headland
/// all round (its passes follow the outline anyway), no directions forbidden and no prohibited
/// regions. Whether the field is narrow and bent enough, the swaths' plan tells ([`kept`]): its
/// blocks at more than one direction, which only split and merge gives, and it only where no
/// direction is asked for.
///
/// ```
/// use furrow::field::{Coordinates, Field};
/// use furrow::plan::contour::weighed;
/// use furrow::PlanOptions;
/// let options = PlanOptions { width: 6.0, headland_passes: 1.into(), coordinates: Coordinates::Metric, ..Default::default() };
/// let field = |text: &str| Field::from_geojson_str_in(text, Coordinates::Metric).map(|(f, _)| f);
/// // A strip 40 m wide bent at a right angle, its arms 500 m long: weighed.
/// let bent = field(r#"{"type": "Polygon", "coordinates": [[[0, 0], [500, 0], [500, 40], [40, 40], [40, 500], [0, 500], [0, 0]]]}"#)?;
/// assert!(weighed(&bent, &options));
/// // Not where swaths are asked for.
/// let swaths = PlanOptions { decomposition: furrow::decompose::Decomposition::SplitMerge, ..options.clone() };
/// assert!(!weighed(&bent, &swaths));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[inline(never)]
pub fn weighed(field: &Field, options: &PlanOptions) -> bool {
    options.decomposition == Decomposition::Auto
        && matches!(options.headland_passes, HeadlandPasses::Count(n) if n > 0)
        && options.headland_mode == HeadlandMode::Constant
        && options.edge_passes.is_empty()
        && options.forbidden_bearings_deg.is_empty()
        && field.prohibited.is_empty()
}

/// `swaths`, or the field planned by passes to its middle where that leaves no more crop
/// standing and takes less time (the crop each plan leaves counted as worked at working speed),
/// its report saying so. Tried only where the swaths' plan is bent (its blocks at more than one
/// direction) and leaves more than [`WELL_COVERED`] of what the implement can reach, on a field
/// of at most [`CONTOUR_MAX_PASSES`] to its middle.
#[inline(never)]
pub fn kept(swaths: Plan, field: Field, options: &PlanOptions, warnings: Vec<Warning>) -> Plan {
    // Where the swaths work nearly all the implement can reach, passes cannot leave less; and
    // a strip the swaths work in one direction is straight: they work it along its length.
    let coverage = &swaths.summary.coverage;
    let report = &swaths.summary.decomposition;
    let bent = report
        .candidates
        .iter()
        .find(|c| c.method == report.method)
        .is_some_and(|c| c.bearings_deg.len() > 1);
    if !bent || coverage.coverage_ratio >= WELL_COVERED * coverage.reachable_ratio {
        return swaths;
    }
    let mut all = options.clone();
    all.headland_passes = HeadlandPasses::All;
    all.decomposition = Decomposition::None;
    let Some(to_middle) = all
        .with_pass_count(&field.boundary)
        .filter(|o| o.headland_pass_count() <= CONTOUR_MAX_PASSES)
    else {
        return swaths;
    };
    let Ok(mut contour) = plan_with_passes(field, &to_middle, warnings, true) else {
        return swaths;
    };
    let (a, b) = (compared_s(&contour, options), compared_s(&swaths, options));
    let uncovered = |p: &Plan| p.summary.coverage.uncovered_area_m2;
    if a >= b - b * TIE || uncovered(&contour) > uncovered(&swaths) {
        return swaths;
    }
    let report = &mut contour.summary.decomposition;
    report.requested = Decomposition::Auto;
    report.reason = String::from(REASON);
    contour.options.headland_passes = options.headland_passes;
    contour
}

/// What whole plans are compared by: the estimated operation time, with the crop the plan
/// leaves uncovered counted as worked at working speed, seconds.
fn compared_s(plan: &Plan, options: &PlanOptions) -> f64 {
    plan.summary.estimated_time_s
        + plan.summary.coverage.uncovered_area_m2 * 3.6
            / (options.width * options.working_speed_kmh)
}
