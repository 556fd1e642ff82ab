//! The decompositions tried, and the choice among them: for `auto`, none and boustrophedon,
//! and split and merge where the direction was searched and the headland runs all around;
//! split and merge itself from several seeds. Each is worked to its estimated operation time
//! ([`work`]) and the fastest kept, near-ties going to the simpler.

use super::candidate::{work, Worked};
use super::{route_settings, Prepared, DECOMPOSITION_TOLERANCE};
use crate::decompose::boustrophedon::within_limits as boustrophedon_within_limits;
use crate::decompose::cells::MergeRule;
use crate::decompose::split_merge::{
    cells_at, improve, split_merge, within_limits as split_merge_within_limits, Criterion,
    SplitMerge, SplitMergeSettings,
};
use crate::decompose::{BlockArea, Decomposition};
use crate::direction::DirectionMode;
use crate::error::{ErrorCode, PlanError};
use crate::geometry::PlanarHypot;
use crate::metrics::{DecompositionCandidate, DecompositionReport, StageTimes};
use crate::numbers::Shortest;
use geo::{Area, Centroid};
use web_time::Instant;

/// Split and merge joins trapezoids whose ends are at least this steep to the direction
/// (Oksanen & Visala 2.4).
const MIN_END_ANGLE_DEG: f64 = 20.0;

/// Where split and merge starts: Oksanen & Visala's greedy selection, and the boustrophedon
/// cells of the field's direction; each is improved, and the faster kept. (The greedy selection
/// with blocks counting as substantial from half or a quarter of the area left, see
/// [`Criterion::substantial_share`], won on 2 of the 21 corpus fields, by under 2 %, at the
/// cost of a greedy run each.)
const SPLIT_MERGE_SEEDS: [Seed; 3] = [Seed::Greedy(1.0), Seed::Cells, Seed::OksanenCells];

/// Where a split-and-merge decomposition starts.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Seed {
    /// Oksanen & Visala's greedy selection, with this substantial share.
    Greedy(f64),
    /// The boustrophedon cells of the field's direction.
    Cells,
    /// The cells of the field's direction merged by Oksanen & Visala's rule (ends at least 20
    /// degrees to the direction), so that bays with oblique sides are cells of their own.
    OksanenCells,
}

/// The decompositions to try, simplest first: the one asked for, or for `auto` none and
/// boustrophedon, and split and merge too where the direction was searched and the field's
/// headland runs all around. Split and merge asked for without the headland all around is
/// refused.
pub(super) fn decompositions(
    asked: Decomposition,
    mode: DirectionMode,
    all_around: bool,
) -> Result<Vec<Decomposition>, PlanError> {
    // Split and merge gives blocks their own directions, so their swaths may end on any edge:
    // it needs the field headland all around. (Only where needed, the headland follows the
    // field's one direction.)
    if asked == Decomposition::SplitMerge && !all_around {
        return Err(PlanError::new(
            ErrorCode::InvalidOption,
            "option `decomposition` is `split-merge`, whose blocks each have their own direction and may end on any edge; it needs the headland all around the field (`headlandMode: constant`, no `edgePasses` with fewer passes)",
        ));
    }
    Ok(match asked {
        Decomposition::Auto if mode == DirectionMode::Search && all_around => vec![
            Decomposition::None,
            Decomposition::Boustrophedon,
            Decomposition::SplitMerge,
        ],
        Decomposition::Auto => vec![Decomposition::None, Decomposition::Boustrophedon],
        m => vec![m],
    })
}

/// The decompositions to try within their limits: split and merge's work grows with the cells
/// and vertices of the inner field, boustrophedon's with the trapezoids its sweep cuts the inner
/// field into, so beyond them `auto` leaves them out (and says why, as a clause for the report)
/// and asking for one is refused.
pub(super) fn within_limits(
    mut methods: Vec<Decomposition>,
    prep: &Prepared,
) -> Result<(Vec<Decomposition>, Option<String>), PlanError> {
    let width = prep.options.width;
    let tolerance = width * DECOMPOSITION_TOLERANCE;
    let bearing = prep.direction.bearing;
    let mut left_out: Vec<String> = Vec::new();
    for (method, name, alternatives) in [
        (
            Decomposition::SplitMerge,
            "split and merge",
            "boustrophedon or none",
        ),
        (Decomposition::Boustrophedon, "boustrophedon cells", "none"),
    ] {
        if !methods.contains(&method) {
            continue;
        }
        let limits = match method {
            Decomposition::SplitMerge => {
                split_merge_within_limits(&prep.headlands.inner, bearing, tolerance)
            }
            _ => match &prep.single {
                Some(single) => boustrophedon_within_limits(&single.main_area, bearing, tolerance),
                None => Ok(()),
            },
        };
        let Err(why) = limits else { continue };
        if prep.options.decomposition != Decomposition::Auto {
            return Err(PlanError::new(
                ErrorCode::FieldTooComplex,
                format!(
                    "the field is too complex for {name} at {} m: {why}; use decomposition {alternatives}, or a wider working width",
                    Shortest(width)
                ),
            ));
        }
        methods.retain(|&m| m != method);
        left_out.push(format!("{} was not tried: {why}", method.as_str()));
    }
    Ok((methods, (!left_out.is_empty()).then(|| left_out.join("; "))))
}

/// Works each decomposition of `methods` into a candidate plan, in their order.
pub(super) fn work_candidates(
    prep: &Prepared,
    methods: &[Decomposition],
    times: &mut StageTimes,
) -> Result<Vec<Worked>, PlanError> {
    let mut candidates: Vec<Worked> = Vec::with_capacity(methods.len());
    for &m in methods {
        if m == Decomposition::SplitMerge {
            if let Some(best) = best_split_merge(prep, times)? {
                candidates.push(best);
            }
        } else {
            // Boustrophedon cells often cluster the swaths into the blocks of `none`, in the
            // same order, only numbered cell by cell: its route and path are then those of
            // `none`.
            let same_as = candidates.iter().find(|c| c.method == Decomposition::None);
            candidates.push(work(prep, m, None, same_as, times)?);
        }
    }
    // `choose` picks among them: there must be one (split and merge always gives a plan from
    // its first seed, or an error).
    if candidates.is_empty() {
        return Err(PlanError::new(
            ErrorCode::Internal,
            "no decomposition gave a plan",
        ));
    }
    Ok(candidates)
}

/// Split and merge from each of its seeds, the plan of lowest estimated time.
///
/// The greedy selection cannot see what a block leaves behind: it is started several ways and
/// the plan of lowest estimated time kept. A start (or a result) equal to an earlier seed's
/// would plan the same again: it is skipped.
fn best_split_merge(prep: &Prepared, times: &mut StageTimes) -> Result<Option<Worked>, PlanError> {
    let mut best: Option<Worked> = None;
    let mut evaluations = 0;
    let mut starts: Vec<Vec<BlockSignature>> = Vec::new();
    let mut results: Vec<Vec<BlockSignature>> = Vec::new();
    for seed in SPLIT_MERGE_SEEDS {
        let mut clock = Instant::now();
        let sm = decompose_seed(prep, seed, &mut starts)?;
        times.lap(&mut clock, |t| &mut t.decomposition);
        let Some(sm) = sm else { continue };
        evaluations += sm.evaluations;
        let result = signatures(&sm.blocks);
        if results.iter().any(|r| same_blocks(r, &result)) {
            continue;
        }
        results.push(result);
        let w = work(prep, Decomposition::SplitMerge, Some(sm), None, times)?;
        if best
            .as_ref()
            .is_none_or(|b| w.compared_time() < b.compared_time())
        {
            best = Some(w);
        }
    }
    Ok(best.map(|mut b| {
        b.decomposition_evaluations = evaluations;
        b
    }))
}

/// The candidate of lowest compared time (see [`Worked::compared_time`]), with the report of
/// the choice: `methods` are the decompositions the candidates were worked from, `left_out`
/// why split and merge was not.
pub(super) fn choose(
    mut candidates: Vec<Worked>,
    requested: Decomposition,
    methods: &[Decomposition],
    left_out: Option<String>,
) -> (Worked, DecompositionReport) {
    let best = fastest(&candidates);
    let figures: Vec<DecompositionCandidate> = candidates.iter().map(Worked::figures).collect();
    let shared = candidates[best]
        .shares_path
        .then(|| {
            let none = candidates
                .iter()
                .position(|c| c.method == Decomposition::None)?;
            Some(std::mem::take(&mut candidates[none].path))
        })
        .flatten();
    let mut chosen = candidates.swap_remove(best);
    if let Some(path) = shared {
        chosen.path = path;
    }
    let reason = reason(chosen.method, &figures, left_out);
    let report = DecompositionReport {
        requested,
        method: methods[best],
        reason,
        candidates: figures,
    };
    (chosen, report)
}

/// The index of the candidate of lowest compared time; near-ties go to the simpler
/// decomposition (the candidates come simplest first).
fn fastest(candidates: &[Worked]) -> usize {
    let mut best = 0;
    for (i, c) in candidates.iter().enumerate() {
        let b = candidates[best].compared_time();
        if c.compared_time() < b - (b * 1e-3).max(1.0) {
            best = i;
        }
    }
    best
}

/// Why `chosen` was: as asked, or the lowest estimated time of these candidates.
fn reason(
    chosen: Decomposition,
    figures: &[DecompositionCandidate],
    left_out: Option<String>,
) -> String {
    let mut reason = if figures.len() == 1 && left_out.is_none() {
        format!("{} as asked", chosen.as_str())
    } else if figures.len() == 1 {
        format!(
            "{}, the only decomposition within its limits",
            chosen.as_str()
        )
    } else {
        let times: Vec<String> = figures
            .iter()
            .map(|f| format!("{} {}", f.method.as_str(), minutes(f.estimated_time_s)))
            .collect();
        format!(
            "{} has the lowest estimated operation time before the fill ({}; crop left uncovered counted as worked at working speed, a connection straight across the crop as worse than any time; within 0.1 % the simpler wins)",
            chosen.as_str(),
            times.join(", ")
        )
    };
    if let Some(why) = left_out {
        reason.push_str(&format!("; {why}"));
    }
    reason
}

impl Worked {
    /// Inner field area the swaths leave uncovered, square metres.
    fn uncovered_m2(&self) -> f64 {
        (self.summary.inner_field_area_m2 - self.summary.objectives.covered_area_m2).max(0.0)
    }

    /// What decompositions are compared by: the estimated operation time, with the crop the
    /// swaths leave uncovered counted as if worked at working speed (else a plan would look
    /// faster for leaving crop standing).
    fn compared_time(&self) -> f64 {
        let m = &self.machine;
        // A connection straight across the crop damages it: a plan with one loses to any plan
        // without, whatever the time.
        let crossings = self.summary.route.straight_connections as f64;
        self.summary.estimated_time_s
            + self.uncovered_m2() / (m.width * m.working_speed)
            + crossings * CROSSING_PENALTY_S
    }

    /// The candidate's figures in the decomposition report: its blocks and their directions,
    /// swaths, turns, time and the crop it leaves.
    fn figures(&self) -> DecompositionCandidate {
        // Each direction once: within a degree (a bearing of 179.6 and one of 0.3 are one).
        let mut bearings_deg: Vec<f64> = Vec::new();
        for b in &self.blocks.blocks {
            let deg = ((b.bearing.to_degrees() * 10.0).round() / 10.0).rem_euclid(180.0);
            let near = |d: &f64| {
                let x = (deg - d).rem_euclid(180.0);
                x.min(180.0 - x) < 1.0
            };
            if !bearings_deg.iter().any(near) {
                bearings_deg.push(deg);
            }
        }
        DecompositionCandidate {
            method: self.method,
            block_count: self.blocks.blocks.len(),
            bearings_deg,
            swath_count: self.summary.swath_count,
            turn_count: self.summary.turn_count,
            block_headland_passes: self.block_headland_passes,
            estimated_time_s: self.summary.estimated_time_s,
            uncovered_area_m2: self.uncovered_m2(),
            evaluations: self.decomposition_evaluations,
        }
    }
}

/// What a connection straight across the crop adds to a candidate's time when decompositions
/// are compared, seconds: more than any field takes to work.
const CROSSING_PENALTY_S: f64 = 1e7;

/// "12 min" or "1 h 05 min".
fn minutes(seconds: f64) -> String {
    let m = (seconds / 60.0).round() as i64;
    if m >= 60 {
        format!("{} h {:02} min", m / 60, m % 60)
    } else {
        format!("{m} min")
    }
}

/// The split-and-merge decomposition of the inner field from `seed`; `None` when the seed's
/// cells are those of a seed in `starts` (improving them again would give the same blocks).
/// Cells seeds add their cells' signatures to `starts`.
fn decompose_seed(
    prep: &Prepared,
    seed: Seed,
    starts: &mut Vec<Vec<BlockSignature>>,
) -> Result<Option<SplitMerge>, PlanError> {
    let (field, options) = (prep.field, prep.options);
    let orders = route_settings(options, field).orders;
    let settings = SplitMergeSettings {
        width: options.width,
        min_length: options.min_swath_length_m(),
        machine: options.machine(),
        method: options.search,
        step_deg: options.search_step_deg,
        forbidden: &options.forbidden_bearings_deg,
        regions: &field.prohibited,
        criterion: Criterion::default(),
        min_end_angle: MIN_END_ANGLE_DEG.to_radians(),
        tolerance: options.width * DECOMPOSITION_TOLERANCE,
        orders: &orders,
    };
    let inner = &prep.headlands.inner;
    let rule = match seed {
        Seed::Greedy(substantial_share) => {
            let criterion = Criterion {
                substantial_share,
                ..Criterion::default()
            };
            return split_merge(
                inner,
                &SplitMergeSettings {
                    criterion,
                    ..settings
                },
            )
            .map(Some);
        }
        Seed::Cells => MergeRule::Boustrophedon,
        Seed::OksanenCells => MergeRule::SplitMerge {
            min_end_angle: settings.min_end_angle,
        },
    };
    let (blocks, not_worked) = cells_at(inner, prep.direction.bearing, rule, &settings);
    let start = signatures(&blocks);
    if starts.iter().any(|s| same_blocks(s, &start)) {
        return Ok(None);
    }
    starts.push(start);
    let (blocks, evaluations) = improve(blocks, &settings)?;
    Ok(Some(SplitMerge {
        blocks,
        evaluations,
        not_worked,
    }))
}

/// What tells blocks apart when seeds are compared: direction, area and centroid. Two
/// decompositions whose blocks agree in these (to rounding) are the same decomposition, with
/// their rings perhaps starting at other corners.
#[derive(Debug, Clone, Copy)]
struct BlockSignature {
    bearing: f64,
    area_m2: f64,
    centroid: geo::Coord,
}

fn signatures(blocks: &[BlockArea]) -> Vec<BlockSignature> {
    blocks
        .iter()
        .map(|b| BlockSignature {
            bearing: b.bearing,
            area_m2: b.area.unsigned_area(),
            centroid: b.area.centroid().map_or(geo::Coord::zero(), |p| p.0),
        })
        .collect()
}

/// Whether two decompositions have the same blocks, in any order: bearings within a
/// microradian, areas within a millionth, centroids within a tenth of a millimetre.
fn same_blocks(a: &[BlockSignature], b: &[BlockSignature]) -> bool {
    if a.len() != b.len() {
        return false;
    }
    let same = |x: &BlockSignature, y: &BlockSignature| {
        let turn = (x.bearing - y.bearing).rem_euclid(std::f64::consts::PI);
        turn.min(std::f64::consts::PI - turn) < 1e-6
            && (x.area_m2 - y.area_m2).abs() <= 1e-6 * x.area_m2.max(1.0)
            && (x.centroid.x - y.centroid.x).planar_hypot(x.centroid.y - y.centroid.y) < 1e-4
    };
    let mut taken = vec![false; b.len()];
    a.iter().all(|x| {
        let found = (0..b.len()).find(|&k| !taken[k] && same(x, &b[k]));
        found.inspect(|&k| taken[k] = true).is_some()
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::MultiPolygon;
    use std::f64::consts::PI;

    fn block(ring: &[(f64, f64)], bearing: f64) -> BlockArea {
        let exterior: Vec<geo::Coord> = ring.iter().map(|&(x, y)| geo::Coord { x, y }).collect();
        BlockArea {
            area: MultiPolygon::new(vec![geo::Polygon::new(exterior.into(), vec![])]),
            bearing,
        }
    }

    #[test]
    fn seeds_with_the_same_blocks_are_the_same_decomposition() {
        let west = [
            (0.0, 0.0),
            (50.0, 0.0),
            (50.0, 80.0),
            (0.0, 80.0),
            (0.0, 0.0),
        ];
        // The same square, its ring starting at another corner.
        let west_again = [
            (50.0, 80.0),
            (0.0, 80.0),
            (0.0, 0.0),
            (50.0, 0.0),
            (50.0, 80.0),
        ];
        let east = [
            (50.0, 0.0),
            (90.0, 0.0),
            (90.0, 80.0),
            (50.0, 80.0),
            (50.0, 0.0),
        ];
        let a = signatures(&[block(&west, 0.3), block(&east, 1.2)]);
        // In the other order, a bearing and its reverse alike.
        let b = signatures(&[block(&east, 1.2), block(&west_again, 0.3 + PI)]);
        assert!(same_blocks(&a, &b));
        // Another direction, another area, or another number of blocks: not the same.
        assert!(!same_blocks(
            &a,
            &signatures(&[block(&west, 0.3), block(&east, 1.25)])
        ));
        let shifted = [
            (50.0, 0.0),
            (91.0, 0.0),
            (91.0, 80.0),
            (50.0, 80.0),
            (50.0, 0.0),
        ];
        assert!(!same_blocks(
            &a,
            &signatures(&[block(&west, 0.3), block(&shifted, 1.2)])
        ));
        assert!(!same_blocks(&a, &signatures(&[block(&west, 0.3)])));
        // Two copies of one block do not match one block and another.
        let twice = signatures(&[block(&west, 0.3), block(&west, 0.3)]);
        assert!(!same_blocks(&a, &twice));
    }
}
