//! The decompositions tried, and the choice among them: for `auto`, none and boustrophedon,
//! and split and merge where the direction was searched and the headland runs all around;
//! split and merge itself from several seeds. Each is worked to its estimated operation time
//! ([`work`]) and the fastest kept, near-ties going to the simpler.

use super::candidate::{work, Worked};
use super::share::{Scored, Share, UnitSummary};
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
use crate::route::pattern::SwathOrder;
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

/// A part of auto's work that plans apart from the others (in a worker of its own, see
/// [`super::share`]): the single-direction decompositions together (boustrophedon takes the
/// route of `none` where their blocks agree), or split and merge from one seed.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Unit {
    Single,
    Seed(Seed),
}

impl Unit {
    /// Its place among all units (the single-direction ones, then the seeds in order), which
    /// decides its share.
    fn place(self) -> usize {
        match self {
            Unit::Single => 0,
            Unit::Seed(seed) => {
                1 + SPLIT_MERGE_SEEDS
                    .iter()
                    .position(|&s| s == seed)
                    .unwrap_or(0)
            }
        }
    }
}

/// The units of `methods`, in the order their candidates are compared: the single-direction
/// decompositions first, then split and merge's seeds.
fn units(methods: &[Decomposition]) -> Vec<Unit> {
    let mut units = Vec::new();
    if methods.iter().any(|&m| m != Decomposition::SplitMerge) {
        units.push(Unit::Single);
    }
    if methods.contains(&Decomposition::SplitMerge) {
        units.extend(SPLIT_MERGE_SEEDS.map(Unit::Seed));
    }
    units
}

/// What one unit gave: its summary (what the choice needs, the same in every share) and the
/// plans of its candidates, or the error that stopped it.
pub(super) struct Outcome {
    pub(super) summary: UnitSummary,
    worked: Vec<Worked>,
    error: Option<PlanError>,
}

/// Works the units of `share`, in order, into candidate plans. Working alone, a seed whose
/// cells or blocks an earlier seed had is skipped (it would plan the same again); a share
/// works each of its seeds, and [`decide`] skips them alike. The first unit that fails ends
/// the work (no unit after it can matter).
pub(super) fn work_units(prep: &mut Prepared, share: Share) -> Vec<Outcome> {
    let mut times = prep.times;
    let outcomes = work_units_timed(prep, share, &mut times);
    prep.times = times;
    outcomes
}

/// [`work_units`], its stages' times added to `times`.
fn work_units_timed(prep: &Prepared, share: Share, times: &mut StageTimes) -> Vec<Outcome> {
    let mut outcomes = Vec::new();
    let mut seen = Seen {
        results_too: share.whole(),
        ..Seen::default()
    };
    for (u, unit) in units(&prep.methods).into_iter().enumerate() {
        if !share.has(unit.place()) {
            continue;
        }
        let outcome = match unit {
            Unit::Single => work_single(prep, times).map(|worked| Outcome {
                summary: UnitSummary {
                    candidates: worked.iter().map(Worked::scored).collect(),
                    ..UnitSummary::new(u)
                },
                worked,
                error: None,
            }),
            Unit::Seed(seed) => work_seed(prep, u, seed, &mut seen, times),
        };
        match outcome {
            Ok(o) => outcomes.push(o),
            Err(e) => {
                outcomes.push(Outcome {
                    summary: UnitSummary {
                        failed: true,
                        ..UnitSummary::new(u)
                    },
                    worked: Vec::new(),
                    error: Some(e),
                });
                break;
            }
        }
    }
    outcomes
}

/// The single-direction decompositions of `prep.methods`, each worked into a candidate.
fn work_single(prep: &Prepared, times: &mut StageTimes) -> Result<Vec<Worked>, PlanError> {
    let mut worked: Vec<Worked> = Vec::new();
    for &m in prep
        .methods
        .iter()
        .filter(|&&m| m != Decomposition::SplitMerge)
    {
        // Boustrophedon cells often cluster the swaths into the blocks of `none`, in the
        // same order, only numbered cell by cell: its route and path are then those of
        // `none`.
        let same_as = worked.iter().find(|c| c.method == Decomposition::None);
        let w = work(prep, m, None, same_as, times)?;
        worked.push(w);
    }
    Ok(worked)
}

/// The cells and blocks of the seeds worked so far, where a seed that repeats one is skipped.
/// A seed whose cells an earlier seed of the share had is skipped in every share: the cells
/// seeds share a share where there are fewer than four ([`Share::has`]), so the share has seen
/// every earlier one. Blocks are compared only working alone (`results_too`): a share has not
/// seen the blocks of the greedy seed, and [`decide`] skips a repeat of them.
#[derive(Default)]
struct Seen {
    starts: Vec<Vec<BlockSignature>>,
    results: Vec<Vec<BlockSignature>>,
    results_too: bool,
}

/// Split and merge from `seed` (unit `u`), worked into a candidate; skipped where its cells or
/// (working alone) its blocks are in `seen`.
fn work_seed(
    prep: &Prepared,
    u: usize,
    seed: Seed,
    seen: &mut Seen,
    times: &mut StageTimes,
) -> Result<Outcome, PlanError> {
    let mut clock = Instant::now();
    let orders = route_settings(&prep.options, &prep.field).orders;
    let settings = split_merge_settings(prep, &orders);
    let start = seed_cells(prep, seed, &settings);
    let start_signatures = start.as_ref().map(|(blocks, _)| signatures(blocks));
    let mut summary = UnitSummary {
        start: start_signatures.clone(),
        ..UnitSummary::new(u)
    };
    let skipped = |summary: UnitSummary| Outcome {
        summary,
        worked: Vec::new(),
        error: None,
    };
    if let Some(s) = start_signatures {
        if seen.starts.iter().any(|t| same_blocks(t, &s)) {
            times.lap(&mut clock, |t| &mut t.decomposition);
            return Ok(skipped(summary));
        }
        seen.starts.push(s);
    }
    let sm = improve_seed(prep, seed, start, &settings)?;
    times.lap(&mut clock, |t| &mut t.decomposition);
    let result = signatures(&sm.blocks);
    summary.evaluations = sm.evaluations;
    summary.result = Some(result.clone());
    if seen.results_too {
        if seen.results.iter().any(|r| same_blocks(r, &result)) {
            return Ok(skipped(summary));
        }
        seen.results.push(result);
    }
    let w = work(prep, Decomposition::SplitMerge, Some(sm), None, times)?;
    summary.candidates = vec![w.scored()];
    Ok(Outcome {
        summary,
        worked: vec![w],
        error: None,
    })
}

/// What [`decide`] found: the unit whose failure ends the plan, or the candidates compared (each
/// its unit and its place there), their figures and the one of lowest compared time.
pub(super) enum Decision {
    Failed(usize),
    Chosen {
        candidates: Vec<(usize, usize)>,
        figures: Vec<DecompositionCandidate>,
        best: usize,
        /// Split and merge's evaluations over its seeds.
        seed_evaluations: usize,
    },
}

impl Decision {
    /// The chosen candidate: its unit and its place there.
    pub(super) fn chosen(&self) -> Option<(usize, usize)> {
        match self {
            Decision::Failed(_) => None,
            Decision::Chosen {
                candidates, best, ..
            } => Some(candidates[*best]),
        }
    }

    /// The unit that holds the chosen candidate (or the failure).
    pub(super) fn unit(&self) -> usize {
        match self {
            Decision::Failed(u) => *u,
            Decision::Chosen {
                candidates, best, ..
            } => candidates[*best].0,
        }
    }
}

/// The choice among the units' candidates, from their `summaries` (of every share): the
/// candidates of the single-direction unit, then split and merge's best seed (a seed whose
/// cells or blocks an earlier seed had is skipped, and the first of equal times kept), and of
/// these the lowest compared time, near-ties going to the simpler. The first unit that failed
/// decides instead.
pub(super) fn decide(
    summaries: &[UnitSummary],
    methods: &[Decomposition],
) -> Result<Decision, PlanError> {
    decide_among(summaries, methods, false)
}

/// The candidate [`decide`] would choose among these units alone (the others left out): the
/// one a share fills ahead of the choice. `None` where a unit failed or none gave a plan.
pub(super) fn own_best(prep: &Prepared, outcomes: &[Outcome]) -> Option<(usize, usize, Worked)> {
    let summaries: Vec<UnitSummary> = outcomes.iter().map(|o| o.summary.clone()).collect();
    let Ok(Decision::Chosen {
        candidates, best, ..
    }) = decide_among(&summaries, &prep.methods, true)
    else {
        return None;
    };
    let (unit, k) = candidates[best];
    let outcome = outcomes.iter().find(|o| o.summary.unit == unit)?;
    let mut worked = outcome.worked.get(k)?.clone();
    if worked.shares_path {
        let none = outcome
            .worked
            .iter()
            .find(|c| c.method == Decomposition::None)?;
        worked.path = none.path.clone();
    }
    Some((unit, k, worked))
}

/// [`decide`], or with `partial` among the units in `summaries` alone.
fn decide_among(
    summaries: &[UnitSummary],
    methods: &[Decomposition],
    partial: bool,
) -> Result<Decision, PlanError> {
    let missing = || PlanError::new(ErrorCode::Internal, "a part of the plan's work is missing");
    let mut candidates: Vec<(usize, usize, f64, DecompositionCandidate)> = Vec::new();
    let mut seen = Seen::default();
    let mut best_seed: Option<(usize, &Scored)> = None;
    let mut seed_evaluations = 0;
    for (u, unit) in units(methods).into_iter().enumerate() {
        let Some(s) = summaries.iter().find(|s| s.unit == u) else {
            if partial {
                continue;
            }
            return Err(missing());
        };
        if s.failed {
            return Ok(Decision::Failed(u));
        }
        if unit == Unit::Single {
            for (k, c) in s.candidates.iter().enumerate() {
                candidates.push((u, k, c.compared_s, c.figures.clone()));
            }
            continue;
        }
        if let Some(start) = &s.start {
            if seen.starts.iter().any(|t| same_blocks(t, start)) {
                continue;
            }
            seen.starts.push(start.clone());
        }
        seed_evaluations += s.evaluations;
        let result = s.result.as_ref().ok_or_else(missing)?;
        if seen.results.iter().any(|r| same_blocks(r, result)) {
            continue;
        }
        seen.results.push(result.clone());
        let c = s.candidates.first().ok_or_else(missing)?;
        if best_seed.is_none_or(|(_, b)| c.compared_s < b.compared_s) {
            best_seed = Some((u, c));
        }
    }
    if let Some((u, c)) = best_seed {
        let figures = DecompositionCandidate {
            evaluations: seed_evaluations,
            ..c.figures.clone()
        };
        candidates.push((u, 0, c.compared_s, figures));
    }
    // `choose` picks among them: there must be one (split and merge always gives a plan from
    // its first seed, or an error).
    if candidates.is_empty() {
        return Err(PlanError::new(
            ErrorCode::Internal,
            "no decomposition gave a plan",
        ));
    }
    let times: Vec<f64> = candidates.iter().map(|c| c.2).collect();
    let best = fastest(&times);
    Ok(Decision::Chosen {
        best,
        seed_evaluations,
        figures: candidates.iter().map(|c| c.3.clone()).collect(),
        candidates: candidates.into_iter().map(|(u, k, _, _)| (u, k)).collect(),
    })
}

/// The candidate `decision` chose, taken from `outcomes` (which must hold its unit), with the
/// report of the choice; or the error of the unit that failed.
pub(super) fn choose(
    prep: &Prepared,
    decision: Decision,
    outcomes: &mut [Outcome],
) -> Result<(Worked, DecompositionReport), PlanError> {
    let unit = decision.unit();
    let outcome = outcomes
        .iter_mut()
        .find(|o| o.summary.unit == unit)
        .ok_or_else(|| PlanError::new(ErrorCode::Internal, "the chosen plan is elsewhere"))?;
    let Decision::Chosen {
        candidates,
        figures,
        best,
        seed_evaluations,
    } = decision
    else {
        return Err(outcome
            .error
            .take()
            .unwrap_or_else(|| PlanError::new(ErrorCode::Internal, "a part of the plan failed")));
    };
    let k = candidates[best].1;
    if k >= outcome.worked.len() {
        return Err(PlanError::new(
            ErrorCode::Internal,
            "the chosen plan is missing",
        ));
    }
    let shared = outcome.worked[k]
        .shares_path
        .then(|| {
            let none = outcome
                .worked
                .iter()
                .position(|c| c.method == Decomposition::None)?;
            Some(std::mem::take(&mut outcome.worked[none].path))
        })
        .flatten();
    let mut chosen = outcome.worked.swap_remove(k);
    if let Some(path) = shared {
        chosen.path = path;
    }
    if chosen.method == Decomposition::SplitMerge {
        chosen.decomposition_evaluations = seed_evaluations;
    }
    let reason = reason(chosen.method, &figures, prep.left_out.clone());
    let report = DecompositionReport {
        requested: prep.options.decomposition,
        method: chosen.method,
        reason,
        candidates: figures,
    };
    Ok((chosen, report))
}

/// The index of the lowest of the candidates' compared `times`; near-ties go to the simpler
/// decomposition (the candidates come simplest first).
fn fastest(times: &[f64]) -> usize {
    let mut best = 0;
    for (i, &t) in times.iter().enumerate() {
        let b = times[best];
        if t < b - (b * 1e-3).max(1.0) {
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

    /// What the choice needs of the candidate: its compared time and its figures.
    fn scored(&self) -> Scored {
        Scored {
            compared_s: self.compared_time(),
            figures: self.figures(),
        }
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

/// The settings split and merge works with.
fn split_merge_settings<'a>(
    prep: &'a Prepared,
    orders: &'a [SwathOrder],
) -> SplitMergeSettings<'a> {
    let (field, options) = (&prep.field, &prep.options);
    SplitMergeSettings {
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
        orders,
    }
}

/// The cells a cells seed starts from, at the field's direction, and the parts no swath works
/// (`None` for the greedy selection, which starts from the whole inner field).
fn seed_cells(
    prep: &Prepared,
    seed: Seed,
    settings: &SplitMergeSettings,
) -> Option<(Vec<BlockArea>, Vec<usize>)> {
    let rule = match seed {
        Seed::Greedy(_) => return None,
        Seed::Cells => MergeRule::Boustrophedon,
        Seed::OksanenCells => MergeRule::SplitMerge {
            min_end_angle: settings.min_end_angle,
        },
    };
    Some(cells_at(
        &prep.headlands.inner,
        prep.direction.bearing,
        rule,
        settings,
    ))
}

/// The split-and-merge decomposition of the inner field from `seed`: the greedy selection, or
/// the cells `start` improved.
fn improve_seed(
    prep: &Prepared,
    seed: Seed,
    start: Option<(Vec<BlockArea>, Vec<usize>)>,
    settings: &SplitMergeSettings,
) -> Result<SplitMerge, PlanError> {
    match (seed, start) {
        (_, Some((blocks, not_worked))) => {
            let (blocks, evaluations) = improve(blocks, settings)?;
            Ok(SplitMerge {
                blocks,
                evaluations,
                not_worked,
            })
        }
        (Seed::Greedy(substantial_share), None) => {
            let criterion = Criterion {
                substantial_share,
                ..Criterion::default()
            };
            split_merge(
                &prep.headlands.inner,
                &SplitMergeSettings {
                    criterion,
                    ..*settings
                },
            )
        }
        (_, None) => Err(PlanError::new(
            ErrorCode::Internal,
            "a cells seed without its cells",
        )),
    }
}

/// What tells blocks apart when seeds are compared: direction, area and centroid. Two
/// decompositions whose blocks agree in these (to rounding) are the same decomposition, with
/// their rings perhaps starting at other corners.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct BlockSignature {
    pub(super) bearing: f64,
    pub(super) area_m2: f64,
    pub(super) centroid: geo::Coord,
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
