//! Planning in shares: `auto`'s candidates split among several planners (Web Workers, threads)
//! that each plan a share of them, so that a plan takes about the time of its largest share
//! rather than of all.
//!
//! The work that plans apart is a *unit*: the single-direction decompositions (`none` and
//! boustrophedon), or split and merge from one of its seeds; each share works one or more
//! ([`Share::has`]). Each share begins the plan ([`Pending::start`]: the field read
//! and checked, its direction and headlands, its units worked) and tells the others what its
//! units gave ([`Pending::summaries`], a few numbers per candidate, [`encode`]d for sending).
//! Given every share's summaries, each share finds the same choice; the share that holds the
//! chosen candidate finishes the plan ([`Pending::finish`]: the fill, the coverage, the plans
//! again with fewer passes or by passes to the middle where planning alone would), the others
//! give `None`. The plan is the one [`crate::plan::plan`] gives.
//!
//! ```
//! use furrow::field::{Coordinates, Field};
//! use furrow::plan::share::{decode, encode, Pending, Share};
//! use furrow::PlanOptions;
//!
//! let text = r#"{"type": "Polygon", "coordinates": [[[0, 0], [300, 0], [300, 120], [120, 120], [120, 300], [0, 300], [0, 0]]]}"#;
//! let options = PlanOptions { width: 6.0, headland_passes: 1.into(), coordinates: Coordinates::Metric, ..Default::default() };
//! let (field, warnings) = Field::from_geojson_str_in(text, Coordinates::Metric)?;
//! // Two shares (in two workers; here one after the other), each sending its summaries.
//! let shares: Vec<Pending> = (0..2)
//!     .map(|index| Pending::start(field.clone(), &options, warnings.clone(), Share { index, of: 2 }))
//!     .collect::<Result<_, _>>()?;
//! let mut sent: Vec<f64> = Vec::new();
//! for share in &shares {
//!     sent.extend(encode(&share.summaries()));
//! }
//! let all = decode(&sent).ok_or("the summaries do not read back")?;
//! // One share finishes the plan, the others have nothing to give.
//! let mut plans: Vec<_> = shares.into_iter().filter_map(|s| s.finish(&all)).collect();
//! assert_eq!(plans.len(), 1);
//! let plan = plans.remove(0)?;
//! let alone = furrow::plan(field, &options)?;
//! assert_eq!(plan.summary.estimated_time_s, alone.summary.estimated_time_s);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use super::auto::{self, BlockSignature, Outcome};
use super::candidate::{fill_leftovers, Worked};
use super::{contour, covers_more, fewer_passes, finish, stage, Plan, Prepared};
use crate::coverage::Coverage;
use crate::decompose::Decomposition;
use crate::error::{ErrorCode, PlanError, Warning};
use crate::field::Field;
use crate::headland::passes::HeadlandPasses;
use crate::metrics::DecompositionCandidate;
use crate::metrics::StageTimes;
use crate::numbers::Shortest;
use crate::options::PlanOptions;

/// Which share of the units a planner works: those whose number modulo `of` is `index`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Share {
    /// This share, from 0.
    pub index: usize,
    /// How many shares there are.
    pub of: usize,
}

impl Share {
    /// All the units, in one planner.
    pub const WHOLE: Share = Share { index: 0, of: 1 };

    /// Whether the share works the unit at `place` (the single-direction decompositions 0,
    /// split and merge's greedy seed 1, its cells seeds 2 and 3). With fewer than four shares
    /// the two cells seeds share one, the last, so that it skips the second where its cells
    /// are the first's, as planning alone does: two shares work {0, 1} and {2, 3}, three {0},
    /// {1} and {2, 3}; four or more one unit each.
    pub(super) fn has(self, place: usize) -> bool {
        let share = match self.of {
            0 | 1 => 0,
            2 => place / 2,
            3 => place.min(2),
            _ => place,
        };
        share == self.index
    }

    /// Whether the share is the whole work.
    pub(super) fn whole(self) -> bool {
        self.of <= 1
    }
}

/// What one unit gave, as the choice among candidates needs it.
#[derive(Debug, Clone, PartialEq)]
pub struct UnitSummary {
    pub(super) unit: usize,
    /// The unit failed (its error decides the plan if no unit before it failed).
    pub(super) failed: bool,
    /// A cells seed's cells before they are improved.
    pub(super) start: Option<Vec<BlockSignature>>,
    /// A seed's blocks.
    pub(super) result: Option<Vec<BlockSignature>>,
    /// A seed's direction evaluations.
    pub(super) evaluations: usize,
    /// The unit's candidates, in order.
    pub(super) candidates: Vec<Scored>,
}

impl UnitSummary {
    pub(super) fn new(unit: usize) -> UnitSummary {
        UnitSummary {
            unit,
            failed: false,
            start: None,
            result: None,
            evaluations: 0,
            candidates: Vec::new(),
        }
    }
}

/// A candidate as the choice sees it: its compared time and its figures for the report.
#[derive(Debug, Clone, PartialEq)]
pub struct Scored {
    pub(super) compared_s: f64,
    pub(super) figures: DecompositionCandidate,
}

/// A plan begun in one share: what its units gave, and what it needs to finish the plan.
pub struct Pending {
    share: Share,
    /// The options, with the passes `auto` or `all` count.
    options: PlanOptions,
    /// `headlandPasses: "all"`: passes to the middle, no fallback.
    to_middle: bool,
    /// The field and its warnings, kept for planning again with fewer passes or by passes to
    /// the middle.
    again: Option<(Field, Vec<Warning>)>,
    /// Whether contour work is weighed ([`contour::weighed`]).
    contour: bool,
    /// The stages before the decomposition and the share's units, or the error that stopped
    /// them (the same in every share).
    begun: Result<(Prepared, Vec<Outcome>), PlanError>,
    /// The share's own best candidate, filled before the choice is known ([`Pending::fill_ahead`]).
    ahead: Option<Ahead>,
}

/// A share's own best candidate (its unit and place there), filled before the choice: where
/// every share's summaries choose it, the plan is finished without filling it again.
pub(super) struct Ahead {
    pub(super) unit: usize,
    pub(super) k: usize,
    pub(super) filled: Result<(Worked, Coverage), PlanError>,
    /// The stages' times with the fill.
    pub(super) times: StageTimes,
}

impl Pending {
    /// Begins planning `field` with `options` in `share`: the stages before the decomposition
    /// and the share's units. Options that are refused are refused here.
    pub fn start(
        field: Field,
        options: &PlanOptions,
        warnings: Vec<Warning>,
        share: Share,
    ) -> Result<Pending, PlanError> {
        options.validate()?;
        if share.of == 0 || share.index >= share.of {
            return Err(PlanError::new(
                ErrorCode::InvalidOption,
                format!("share {} of {} does not exist", share.index, share.of),
            ));
        }
        // `auto` passes are counted once, from the machine, and `all` from the field's size:
        // the plan reports the count laid.
        let to_middle = options.headland_passes == HeadlandPasses::All;
        let options = options
            .with_pass_count(&field.boundary)
            .unwrap_or_else(|| options.clone());
        // Kept for planning again with fewer passes (a copy of the outlines: far less than a
        // plan), or by passes to the middle where those may take less time.
        let again = (!to_middle && options.headland_pass_count() > 0)
            .then(|| (field.clone(), warnings.clone()));
        let contour = !to_middle && contour::weighed(&field, &options);
        let begun = stage(field, &options, warnings, to_middle).map(|mut prepared| {
            let outcomes = auto::work_units(&mut prepared, share);
            (prepared, outcomes)
        });
        Ok(Pending {
            share,
            options,
            to_middle,
            again,
            contour,
            begun,
            ahead: None,
        })
    }

    /// Fills the share's own best candidate ahead of the choice: a worker of a pool does it while
    /// the other shares work their units, so that where it is the one chosen the plan is
    /// finished sooner. (Where it is not, it was time the worker would have waited.)
    pub fn fill_ahead(&mut self) {
        let Ok((prepared, outcomes)) = &self.begun else {
            return;
        };
        let Some((unit, k, worked)) = auto::own_best(prepared, outcomes) else {
            return;
        };
        let mut times = prepared.times;
        let filled = fill_leftovers(prepared, worked, &mut times);
        self.ahead = Some(Ahead {
            unit,
            k,
            filled,
            times,
        });
    }

    /// What this share's units gave, for every share's [`Pending::finish`].
    pub fn summaries(&self) -> Vec<UnitSummary> {
        match &self.begun {
            Ok((_, outcomes)) => outcomes.iter().map(|o| o.summary.clone()).collect(),
            Err(_) => Vec::new(),
        }
    }

    /// The plan, given the summaries of every share: `None` where another share holds the
    /// chosen candidate (or, where the plan fails before its units, in all shares but the
    /// first).
    pub fn finish(self, summaries: &[UnitSummary]) -> Option<Result<Plan, PlanError>> {
        let first = self.share.index == 0;
        let planned = match self.begun {
            Err(e) => first.then_some(Err(e))?,
            Ok((prepared, mut outcomes)) => match auto::decide(summaries, &prepared.methods) {
                Err(e) => first.then_some(Err(e))?,
                Ok(decision) => {
                    let unit = decision.unit();
                    if !outcomes.iter().any(|o| o.summary.unit == unit) {
                        return None;
                    }
                    finish(prepared, decision, &mut outcomes, self.ahead)
                }
            },
        };
        Some(after(
            planned,
            &self.options,
            self.to_middle,
            self.again,
            self.contour,
        ))
    }
}

/// What follows the plan: `all` said as asked; where the passes leave no inner field, the plan
/// with fewer passes that works most ([`fewer_passes`]); else contour work where it is
/// weighed and pays ([`contour::kept`]).
fn after(
    planned: Result<Plan, PlanError>,
    options: &PlanOptions,
    to_middle: bool,
    again: Option<(Field, Vec<Warning>)>,
    weighed: bool,
) -> Result<Plan, PlanError> {
    if to_middle {
        return planned.map(|mut plan| {
            plan.options.headland_passes = HeadlandPasses::All;
            plan
        });
    }
    let no_inner_field = match &planned {
        // Swaths that only fill what the passes leave are no inner field.
        Ok(plan) => plan.summary.swath_count == plan.summary.fill_swath_count,
        Err(e) => e.code == ErrorCode::HeadlandConsumesField,
    };
    match again {
        Some((field, warnings)) if no_inner_field => {
            let fewer = fewer_passes(&field, options, &warnings);
            match (planned, fewer) {
                (Ok(plan), Some(fewer)) if covers_more(&fewer, &plan) => Ok(fewer),
                (Ok(plan), _) => Ok(plan),
                (Err(_), Some(fewer)) => Ok(fewer),
                (Err(e), None) => Err(PlanError {
                    message: format!(
                        "the field has no room for a pass of {} m, with or without headland passes: it is narrower than the working width nearly everywhere; use a narrower width",
                        Shortest(options.width)
                    ),
                    ..e
                }),
            }
        }
        Some((field, warnings)) if weighed => {
            planned.map(|plan| contour::kept(plan, field, options, warnings))
        }
        _ => planned,
    }
}

/// Most numbers [`decode`] reads: far beyond what any plan's summaries take (a few dozen per
/// candidate), so that a corrupt message cannot ask for gigabytes.
pub const MAX_ENCODED: usize = 1 << 20;

/// The summaries as numbers, to send between workers (exact: every figure is an `f64` or a
/// count well within its 53 bits). [`decode`] reads them back.
pub fn encode(summaries: &[UnitSummary]) -> Vec<f64> {
    let mut out = Vec::new();
    for s in summaries {
        out.push(s.unit as f64);
        out.push(f64::from(u8::from(s.failed)));
        out.push(s.evaluations as f64);
        for signatures in [&s.start, &s.result] {
            match signatures {
                None => out.push(-1.0),
                Some(list) => {
                    out.push(list.len() as f64);
                    for b in list {
                        out.extend([b.bearing, b.area_m2, b.centroid.x, b.centroid.y]);
                    }
                }
            }
        }
        out.push(s.candidates.len() as f64);
        for c in &s.candidates {
            let f = &c.figures;
            out.extend([
                c.compared_s,
                method_code(f.method),
                f.block_count as f64,
                f.swath_count as f64,
                f.turn_count as f64,
                f.block_headland_passes as f64,
                f.estimated_time_s,
                f.uncovered_area_m2,
                f.evaluations as f64,
                f.bearings_deg.len() as f64,
            ]);
            out.extend(&f.bearings_deg);
        }
    }
    out
}

/// The summaries [`encode`] wrote (several shares' one after another); `None` for numbers it
/// did not write.
pub fn decode(numbers: &[f64]) -> Option<Vec<UnitSummary>> {
    if numbers.len() > MAX_ENCODED {
        return None;
    }
    let mut r = Reader { numbers, at: 0 };
    let mut out = Vec::new();
    while r.at < numbers.len() {
        let mut s = UnitSummary::new(r.count()?);
        s.failed = r.count()? == 1;
        s.evaluations = r.count()?;
        s.start = r.signatures()?;
        s.result = r.signatures()?;
        for _ in 0..r.count()? {
            let compared_s = r.number()?;
            let method = method_of(r.number()?)?;
            let [block_count, swath_count, turn_count, block_headland_passes] =
                [r.count()?, r.count()?, r.count()?, r.count()?];
            let (estimated_time_s, uncovered_area_m2) = (r.number()?, r.number()?);
            let evaluations = r.count()?;
            let bearings_deg = (0..r.count()?)
                .map(|_| r.number())
                .collect::<Option<Vec<f64>>>()?;
            s.candidates.push(Scored {
                compared_s,
                figures: DecompositionCandidate {
                    method,
                    block_count,
                    bearings_deg,
                    swath_count,
                    turn_count,
                    block_headland_passes,
                    estimated_time_s,
                    uncovered_area_m2,
                    evaluations,
                },
            });
        }
        out.push(s);
    }
    Some(out)
}

/// Reads numbers in turn, each checked.
struct Reader<'a> {
    numbers: &'a [f64],
    at: usize,
}

impl Reader<'_> {
    fn number(&mut self) -> Option<f64> {
        let x = *self.numbers.get(self.at)?;
        self.at += 1;
        Some(x)
    }

    /// A whole number from 0 up to the numbers' count (no count or index here is larger).
    fn count(&mut self) -> Option<usize> {
        let x = self.number()?;
        (x >= 0.0 && x.fract() == 0.0 && x <= MAX_ENCODED as f64).then_some(x as usize)
    }

    fn signatures(&mut self) -> Option<Option<Vec<BlockSignature>>> {
        if self.numbers.get(self.at) == Some(&-1.0) {
            self.at += 1;
            return Some(None);
        }
        let n = self.count()?;
        let list = (0..n)
            .map(|_| {
                Some(BlockSignature {
                    bearing: self.number()?,
                    area_m2: self.number()?,
                    centroid: geo::Coord {
                        x: self.number()?,
                        y: self.number()?,
                    },
                })
            })
            .collect::<Option<Vec<_>>>()?;
        Some(Some(list))
    }
}

const METHODS: [Decomposition; 4] = [
    Decomposition::Auto,
    Decomposition::None,
    Decomposition::Boustrophedon,
    Decomposition::SplitMerge,
];

fn method_code(m: Decomposition) -> f64 {
    METHODS.iter().position(|&x| x == m).unwrap_or(0) as f64
}

fn method_of(code: f64) -> Option<Decomposition> {
    METHODS
        .iter()
        .enumerate()
        .find(|&(i, _)| i as f64 == code)
        .map(|(_, &m)| m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn summary() -> UnitSummary {
        let sig = |x: f64| BlockSignature {
            bearing: 0.1 * x,
            area_m2: 1e4 / 3.0 * x,
            centroid: geo::Coord { x, y: -x / 7.0 },
        };
        UnitSummary {
            unit: 3,
            failed: false,
            start: Some(vec![sig(1.0), sig(2.0)]),
            result: Some(vec![sig(3.0)]),
            evaluations: 41,
            candidates: vec![Scored {
                compared_s: 1_234.567_890_123,
                figures: DecompositionCandidate {
                    method: Decomposition::SplitMerge,
                    block_count: 3,
                    bearings_deg: vec![12.3, 101.1],
                    swath_count: 57,
                    turn_count: 54,
                    block_headland_passes: 2,
                    estimated_time_s: 1200.0 + 1.0 / 3.0,
                    uncovered_area_m2: 0.1,
                    evaluations: 41,
                },
            }],
        }
    }

    #[test]
    fn summaries_read_back_exactly() {
        let failed = UnitSummary {
            failed: true,
            ..UnitSummary::new(0)
        };
        let all = vec![failed, summary()];
        assert_eq!(decode(&encode(&all)), Some(all));
    }

    #[test]
    fn a_cut_or_altered_message_is_refused() {
        let numbers = encode(&[summary()]);
        for cut in 1..numbers.len() {
            assert_eq!(decode(&numbers[..cut]), None, "cut at {cut}");
        }
        let mut bad = numbers.clone();
        bad[0] = 0.5; // a unit number that is no whole number
        assert_eq!(decode(&bad), None);
        assert_eq!(decode(&vec![0.0; MAX_ENCODED + 1]), None);
    }

    proptest! {
        #[test]
        fn any_numbers_decode_without_panic(numbers in proptest::collection::vec(
            prop_oneof![Just(-1.0), Just(0.0), Just(1.0), 0.0..5.0f64, any::<f64>()], 0..80)) {
            let _ = decode(&numbers);
        }
    }
}
