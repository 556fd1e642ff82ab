//! Objective functions: how good the swaths at one driving direction are.
//!
//! The direction search ([`crate::direction`]) measures the swaths of each candidate direction
//! once, as [`SwathStats`], and an [`Objective`] turns the measures into a cost (lower is
//! better). The objectives are Fields2Cover's (number of swaths, total swath length, field
//! coverage; Mier et al. 2023, II-B), the number of turns, the area worked twice, the estimated
//! operation time, and Oksanen & Visala's weighted criterion (2.5: efficiency 65 %, area 15 %,
//! distance 20 %). A caller may bring its own by implementing the trait.
//!
//! Field coverage is the area of the measured region inside the union of the swaths' strips.
//! Fields2Cover computes it with polygon unions and differences, its slowest objective (3.5 s for
//! 1 ha); here it is integrated across the strips in the same sweep that cuts the swaths: on a
//! line across the strip, the length covered is the overlap of the swath pieces with the
//! region's chord. That length is linear in the across coordinate between the region's vertices,
//! the swath lines (where the pieces were cut) and the edges of neighbouring strips, so the
//! midpoint rule between those breaks is exact.

use crate::decompose::block_members;
use crate::geometry::{Extremes, PlanarHypot};
use crate::sort::{sort_floats, SharedSort};
use crate::swath::{Swath, Swaths};
use geo::{Area, Coord, MultiPolygon};
use serde::Serialize;
use std::f64::consts::PI;
use std::ops::AddAssign;

/// The measures of a set of swaths from which every objective is computed. Measures of disjoint
/// areas add up (`+=`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct SwathStats {
    /// Number of swaths.
    pub swath_count: usize,
    /// Total length of the swaths, metres.
    pub swath_length_m: f64,
    /// Number of turns from one swath to the next: within blocks (worked boustrophedon) and from
    /// each block to the next, so that a direction cannot look better by breaking the field
    /// into more blocks.
    pub turn_count: usize,
    /// Length of those turns by the turn model ([`turn_length`] plus the run along the headland
    /// between the swaths' ends; between blocks, a turn and the way between their nearest
    /// corners), metres.
    pub turning_distance_m: f64,
    /// Of the turning distance, the moves from one block to the next (a turn and the way
    /// between the blocks' nearest corners), metres.
    pub block_change_m: f64,
    /// Area of the region the swaths are to cover, square metres.
    pub area_m2: f64,
    /// Of which covered by the swaths' strips, square metres.
    pub covered_area_m2: f64,
    /// Area of all strips, each a working width wide along its swath, square metres.
    pub strip_area_m2: f64,
}

impl AddAssign for SwathStats {
    fn add_assign(&mut self, o: SwathStats) {
        self.swath_count += o.swath_count;
        self.swath_length_m += o.swath_length_m;
        self.turn_count += o.turn_count;
        self.turning_distance_m += o.turning_distance_m;
        self.block_change_m += o.block_change_m;
        self.area_m2 += o.area_m2;
        self.covered_area_m2 += o.covered_area_m2;
        self.strip_area_m2 += o.strip_area_m2;
    }
}

impl SwathStats {
    /// Share of the region covered by the strips, in `[0, 1]`.
    pub fn coverage(&self) -> f64 {
        if self.area_m2 > 0.0 {
            (self.covered_area_m2 / self.area_m2).clamp(0.0, 1.0)
        } else {
            1.0
        }
    }

    /// Area worked more than once or outside the region (strips overlapping each other and
    /// reaching over the region's edge into the headland), square metres.
    pub fn overlap_m2(&self) -> f64 {
        (self.strip_area_m2 - self.covered_area_m2).max(0.0)
    }

    /// Estimated time to work the swaths and turn between them, seconds.
    pub fn time_s(&self, machine: &Machine) -> f64 {
        self.swath_length_m / machine.working_speed
            + self.turning_distance_m / machine.turning_speed
    }
}

/// The machine as the objectives see it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Machine {
    /// Working width, metres.
    pub width: f64,
    /// Minimum turning radius, metres.
    pub turn_radius: f64,
    /// Speed while working, metres per second.
    pub working_speed: f64,
    /// Speed while turning, metres per second.
    pub turning_speed: f64,
}

/// Length of the shortest forward turn (metres) from the end of one swath onto the next,
/// `spacing` metres beside it and driven the other way: a U-turn of two quarter circles and a
/// straight where the spacing is at least twice the radius, otherwise a loop (bulb) turn that
/// swings out and back, `r (π + 4 acos((d + 2r) / 4r))` (the Dubins CCC path).
///
/// ```
/// use furrow::objective::turn_length;
/// use std::f64::consts::PI;
///
/// assert!((turn_length(16.0, 8.0) - 8.0 * PI).abs() < 1e-9); // a half circle
/// assert!((turn_length(20.0, 8.0) - (8.0 * PI + 4.0)).abs() < 1e-9);
/// assert!((turn_length(0.0, 8.0) - 8.0 * 7.0 * PI / 3.0).abs() < 1e-9); // turning onto itself
/// ```
pub fn turn_length(spacing: f64, radius: f64) -> f64 {
    let d = spacing.abs();
    let r = radius.max(0.0);
    if d >= 2.0 * r {
        PI * r + (d - 2.0 * r)
    } else {
        let phi = ((d + 2.0 * r) / (4.0 * r)).clamp(-1.0, 1.0).acos();
        r * (PI + 4.0 * phi)
    }
}

/// What the three-point (fishtail) turn between swaths `spacing` apart costs, metres: a quarter
/// circle forward, straight back `2r − d`, a quarter circle forward, and a change of gear at
/// each end of the stretch back ([`crate::path::turn::CUSP_PENALTY_M`] each).
///
/// ```
/// use furrow::objective::three_point_length;
/// use std::f64::consts::PI;
///
/// assert!((three_point_length(6.0, 8.0) - (8.0 * PI + 10.0 + 10.0)).abs() < 1e-9);
/// ```
pub fn three_point_length(spacing: f64, radius: f64) -> f64 {
    let (d, r) = (spacing.abs(), radius.max(0.0));
    PI * r + (2.0 * r - d).max(0.0) + 2.0 * crate::path::turn::CUSP_PENALTY_M
}

/// [`turn_length`] at one turning radius, remembering the last few spacings: the turns of a
/// block are mostly between neighbouring swaths, one spacing apart (a snake that skips swaths
/// alternates between two or three), and the length is an arc cosine (a routine in software in
/// WebAssembly) that planning asks for every turn of every block at every direction tried. The
/// same numbers as [`turn_length`].
///
/// ```
/// use furrow::objective::{turn_length, TurnLengths};
///
/// let mut lengths = TurnLengths::new(8.0);
/// assert_eq!(lengths.of(6.0), turn_length(6.0, 8.0));
/// assert_eq!(lengths.of(-6.0), turn_length(6.0, 8.0));
/// assert_eq!(lengths.of(20.0), turn_length(20.0, 8.0));
/// assert_eq!(lengths.of(12.0), turn_length(12.0, 8.0));
/// assert_eq!(lengths.of(6.0), turn_length(6.0, 8.0));
/// ```
#[derive(Debug, Clone, Copy)]
pub struct TurnLengths {
    radius: f64,
    /// Whether the machine may reverse: close swaths are then joined by the three-point turn
    /// where it is cheaper than the loop.
    reverses: bool,
    /// The headland's depth, metres: a turn that does not fit it ([`TurnLengths::between`])
    /// weighs more. Infinite: any turn fits.
    headland_m: f64,
    /// Spacings (absolute) and their lengths, the most recent at `next - 1`; NaN where empty.
    recent: [(f64, f64); TURN_LENGTHS_KEPT],
    next: usize,
}

/// How many spacings [`TurnLengths`] remembers.
const TURN_LENGTHS_KEPT: usize = 4;

impl TurnLengths {
    /// Turn lengths at this turning radius.
    pub fn new(radius: f64) -> Self {
        TurnLengths::of_machine(radius, false)
    }

    /// Turn lengths at this turning radius for a machine that reverses or not: one that does
    /// joins swaths closer than twice the radius by the three-point turn where it costs less
    /// than the loop ([`three_point_length`]).
    ///
    /// ```
    /// use furrow::objective::{three_point_length, turn_length, TurnLengths};
    ///
    /// let mut reversing = TurnLengths::of_machine(8.0, true);
    /// assert_eq!(reversing.of(6.0), three_point_length(6.0, 8.0));
    /// assert_eq!(reversing.of(20.0), turn_length(20.0, 8.0));
    /// ```
    pub fn of_machine(radius: f64, reverses: bool) -> Self {
        TurnLengths {
            radius,
            reverses,
            headland_m: f64::INFINITY,
            recent: [(f64::NAN, f64::NAN); TURN_LENGTHS_KEPT],
            next: 0,
        }
    }

    /// [`turn_length`] of `spacing` (either sign) at the radius.
    #[inline]
    pub fn of(&mut self, spacing: f64) -> f64 {
        let d = spacing.abs();
        // NaN is equal to nothing: an empty place never matches.
        if let Some(&(_, length)) = self.recent.iter().find(|(at, _)| *at == d) {
            return length;
        }
        let mut length = turn_length(d, self.radius);
        if self.reverses && d < 2.0 * self.radius {
            length = length.min(three_point_length(d, self.radius));
        }
        self.recent[self.next] = (d, length);
        self.next = (self.next + 1) % TURN_LENGTHS_KEPT;
        length
    }

    /// These turn lengths where the turns must keep to a headland `depth` metres deep.
    pub fn within(self, depth: f64) -> Self {
        TurnLengths {
            headland_m: depth,
            ..self
        }
    }

    /// The turn model's cost from the end of one swath into the next, `spacing` apart across
    /// and their ends `stagger` apart along the swaths: the turn and the stagger, and
    /// [`MISFIT_TURN_FACTOR`] times that where the turn does not fit the headland. Between
    /// ends staggered along an oblique headland edge, the turn is made beyond the farther end:
    /// it reaches the stagger and the turn's own depth ([`forward_turn_depth`], or the radius
    /// for a three-point turn) beyond the nearer end, where the headland measured along the
    /// swaths is `depth · √(spacing² + stagger²) / spacing` deep.
    ///
    /// ```
    /// use furrow::objective::{turn_length, TurnLengths, MISFIT_TURN_FACTOR};
    ///
    /// // Two passes of 6 m: a U-turn 18 m across between level ends fits, a loop does not;
    /// // the U-turn between ends 36 m apart along an edge at 27° to the swaths does not either.
    /// let mut drill = TurnLengths::new(8.0).within(12.0);
    /// assert_eq!(drill.between(18.0, 0.0), turn_length(18.0, 8.0));
    /// assert_eq!(drill.between(6.0, 0.0), MISFIT_TURN_FACTOR * turn_length(6.0, 8.0));
    /// assert_eq!(drill.between(18.0, 36.0), MISFIT_TURN_FACTOR * (turn_length(18.0, 8.0) + 36.0));
    /// // A machine that reverses turns into the neighbour 6 m across, 12 m further on.
    /// let mut reversing = TurnLengths::of_machine(8.0, true).within(12.0);
    /// assert!(reversing.between(6.0, 12.0) < reversing.between(18.0, 36.0) / MISFIT_TURN_FACTOR);
    /// ```
    pub fn between(&mut self, spacing: f64, stagger: f64) -> f64 {
        let cost = self.of(spacing) + stagger.abs();
        if self.fits(spacing.abs(), stagger.abs()) {
            cost
        } else {
            cost * MISFIT_TURN_FACTOR
        }
    }

    /// Whether the turn between swaths `s` apart with ends `d` apart along them keeps to the
    /// headland (see [`TurnLengths::between`]).
    fn fits(&self, s: f64, d: f64) -> bool {
        if !self.headland_m.is_finite() || s <= 0.0 {
            return true;
        }
        let r = self.radius;
        let depth = if self.reverses && s < 2.0 * r {
            r
        } else {
            forward_turn_depth(s, r)
        };
        d + depth <= self.headland_m * s.hypot(d) / s
    }
}

/// How many times its cost a turn that does not fit the headland weighs in the choice of a
/// block's pattern ([`TurnLengths::between`]): it drives over crop or out of the field, so a
/// pattern whose turns fit is taken unless it drives much further.
pub const MISFIT_TURN_FACTOR: f64 = 3.0;

/// How far beyond the swath ends a forward turn between swaths `spacing` apart reaches,
/// metres: a U of the turning radius where they are two radii apart or more, else a loop
/// (three arcs of the radius, the middle one away from the swaths).
///
/// ```
/// use furrow::objective::forward_turn_depth;
///
/// assert_eq!(forward_turn_depth(20.0, 8.0), 8.0);
/// assert!((forward_turn_depth(12.0, 8.0) - (8.0 + 60f64.sqrt())).abs() < 1e-9);
/// ```
pub fn forward_turn_depth(spacing: f64, radius: f64) -> f64 {
    if spacing >= 2.0 * radius {
        return radius;
    }
    // The middle arc's centre: two radii from the centres of the end arcs, which lie a
    // radius beyond each swath's line, away from the other.
    let half = (spacing + 2.0 * radius) / 2.0;
    radius + ((2.0 * radius).powi(2) - half * half).max(0.0).sqrt()
}

/// A cost to minimise over driving directions.
pub trait Objective {
    /// The objective's name, as the options spell it.
    fn name(&self) -> &'static str;
    /// The cost of swaths with these measures (lower is better).
    fn cost(&self, stats: &SwathStats, machine: &Machine) -> f64;
}

/// Fewest swaths (Fields2Cover's `NSwath`).
#[derive(Debug, Clone, Copy, Default)]
pub struct SwathCount;
/// Shortest total swath length (Fields2Cover's `SwathLength`).
#[derive(Debug, Clone, Copy, Default)]
pub struct SwathLength;
/// Most of the region covered (Fields2Cover's `FieldCoverage`): cost is the uncovered share.
#[derive(Debug, Clone, Copy, Default)]
pub struct Coverage;
/// Least area worked twice or over the edge, square metres.
#[derive(Debug, Clone, Copy, Default)]
pub struct Overlap;
/// Fewest turns.
#[derive(Debug, Clone, Copy, Default)]
pub struct TurnCount;
/// Shortest estimated operation time: swaths at working speed, turns by the turn model at
/// turning speed, and the area the swaths leave uncovered as if worked at working speed (else a
/// direction could look faster by leaving crop standing).
#[derive(Debug, Clone, Copy, Default)]
pub struct OperationTime;
/// Oksanen & Visala's weighted criterion (2.5): efficiency (working time over all time), area
/// (covered share) and distance (swath length against the ideal `area / width`), each in
/// `[0, 1]`, weighted; the cost is one less the weighted score.
#[derive(Debug, Clone, Copy)]
pub struct OksanenWeighted {
    /// Weight of driving efficiency (0.65 in the paper).
    pub efficiency: f64,
    /// Weight of the area covered (0.15).
    pub area: f64,
    /// Weight of the working distance (0.20).
    pub distance: f64,
}

impl Default for OksanenWeighted {
    fn default() -> Self {
        OksanenWeighted {
            efficiency: 0.65,
            area: 0.15,
            distance: 0.20,
        }
    }
}

impl Objective for SwathCount {
    fn name(&self) -> &'static str {
        "swath-count"
    }
    fn cost(&self, s: &SwathStats, _: &Machine) -> f64 {
        s.swath_count as f64
    }
}

impl Objective for SwathLength {
    fn name(&self) -> &'static str {
        "swath-length"
    }
    fn cost(&self, s: &SwathStats, _: &Machine) -> f64 {
        s.swath_length_m
    }
}

impl Objective for Coverage {
    fn name(&self) -> &'static str {
        "coverage"
    }
    fn cost(&self, s: &SwathStats, _: &Machine) -> f64 {
        1.0 - s.coverage()
    }
}

impl Objective for Overlap {
    fn name(&self) -> &'static str {
        "overlap"
    }
    fn cost(&self, s: &SwathStats, _: &Machine) -> f64 {
        s.overlap_m2()
    }
}

impl Objective for TurnCount {
    fn name(&self) -> &'static str {
        "turn-count"
    }
    fn cost(&self, s: &SwathStats, _: &Machine) -> f64 {
        s.turn_count as f64
    }
}

impl Objective for OperationTime {
    fn name(&self) -> &'static str {
        "time"
    }
    fn cost(&self, s: &SwathStats, m: &Machine) -> f64 {
        let uncovered = (s.area_m2 - s.covered_area_m2).max(0.0);
        s.time_s(m) + uncovered / (m.width * m.working_speed)
    }
}

impl OksanenWeighted {
    /// The weighted score in `[0, 1]` (higher is better).
    pub fn score(&self, s: &SwathStats, m: &Machine) -> f64 {
        let working = s.swath_length_m / m.working_speed;
        let all = s.time_s(m);
        let efficiency = if all > 0.0 { working / all } else { 0.0 };
        let distance = if s.area_m2 > 0.0 {
            (s.swath_length_m * m.width / s.area_m2).min(1.0)
        } else {
            0.0
        };
        self.efficiency * efficiency + self.area * s.coverage() + self.distance * distance
    }
}

impl Objective for OksanenWeighted {
    fn name(&self) -> &'static str {
        "oksanen"
    }
    fn cost(&self, s: &SwathStats, m: &Machine) -> f64 {
        1.0 - self.score(s, m)
    }
}

/// The objectives by name, for the options.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ObjectiveKind {
    /// [`SwathCount`].
    SwathCount,
    /// [`SwathLength`].
    SwathLength,
    /// [`Coverage`].
    Coverage,
    /// [`Overlap`].
    Overlap,
    /// [`TurnCount`].
    TurnCount,
    /// [`OperationTime`] (the default).
    #[default]
    Time,
    /// [`OksanenWeighted`] with the paper's weights.
    Oksanen,
}

crate::named::named!(ObjectiveKind { "swath-count" => SwathCount, "swath-length" => SwathLength, "coverage" => Coverage, "overlap" => Overlap, "turn-count" => TurnCount, "time" => Time, "oksanen" => Oksanen });

impl ObjectiveKind {
    /// The objective.
    pub fn objective(self) -> Box<dyn Objective> {
        match self {
            ObjectiveKind::SwathCount => Box::new(SwathCount),
            ObjectiveKind::SwathLength => Box::new(SwathLength),
            ObjectiveKind::Coverage => Box::new(Coverage),
            ObjectiveKind::Overlap => Box::new(Overlap),
            ObjectiveKind::TurnCount => Box::new(TurnCount),
            ObjectiveKind::Time => Box::new(OperationTime),
            ObjectiveKind::Oksanen => Box::new(OksanenWeighted::default()),
        }
    }
}

/// The values of every objective for one set of swaths: what the plan summary reports for the
/// chosen direction.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ObjectiveValues {
    /// Number of swaths.
    pub swath_count: usize,
    /// Total swath length, metres.
    pub swath_length_m: f64,
    /// Share of the inner field covered by the swaths' strips.
    pub coverage: f64,
    /// Inner field area the strips cover, square metres.
    pub covered_area_m2: f64,
    /// Area worked twice or over the inner field's edge by the strips, square metres.
    pub overlap_m2: f64,
    /// Number of turns from one swath to the next, the moves between blocks included.
    pub turn_count: usize,
    /// Length of those turns by the turn model, metres.
    pub turning_distance_m: f64,
    /// Estimated time for the swaths and the turns between them, seconds.
    pub time_s: f64,
    /// Oksanen & Visala's weighted score, in `[0, 1]` (higher is better).
    pub oksanen_score: f64,
}

impl ObjectiveValues {
    /// Every objective's value for these measures.
    pub fn of(s: &SwathStats, m: &Machine) -> Self {
        ObjectiveValues {
            swath_count: s.swath_count,
            swath_length_m: s.swath_length_m,
            coverage: s.coverage(),
            covered_area_m2: s.covered_area_m2,
            overlap_m2: s.overlap_m2(),
            turn_count: s.turn_count,
            turning_distance_m: s.turning_distance_m,
            time_s: s.time_s(m),
            oksanen_score: OksanenWeighted::default().score(s, m),
        }
    }
}

/// Measures swaths covering `area` (all of one direction, as from
/// [`generate_with`](crate::swath::generate_with)).
///
/// ```
/// use furrow::objective::{measure, Machine};
/// use furrow::swath::generate;
/// use geo::{polygon, MultiPolygon};
///
/// let strip = MultiPolygon::new(vec![polygon![(x: 0., y: 0.), (x: 32., y: 0.), (x: 32., y: 100.), (x: 0., y: 100.)]]);
/// let swaths = generate(&strip, 0.0, 6.0, 6.0)?;
/// let m = Machine { width: 6.0, turn_radius: 3.0, working_speed: 2.0, turning_speed: 1.0 };
/// let s = measure(&swaths.swaths, 6.0, &strip, &m);
/// assert_eq!((s.swath_count, s.turn_count), (6, 5));
/// assert!((s.covered_area_m2 - 3200.0).abs() < 1e-6); // all of it, the last strip overlapping
/// assert!((s.overlap_m2() - 400.0).abs() < 1e-6);      // 4 m of the last strip, 100 m long
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn measure(swaths: &[Swath], width: f64, area: &MultiPolygon, m: &Machine) -> SwathStats {
    let mut stats = measure_turns(swaths, width, area.unsigned_area(), m);
    stats.covered_area_m2 = covered_area(swaths, width, area);
    stats
}

/// [`measure`] without the exact coverage, for estimates made many times over: the covered
/// area is taken as the strips' area, at most the area (`area_m2`, square metres).
pub fn measure_turns(swaths: &[Swath], width: f64, area_m2: f64, m: &Machine) -> SwathStats {
    measure_turns_in(swaths, &block_members(swaths), width, area_m2, m)
}

/// [`measure_turns`] of swaths whose blocks (their [`block_members`]) the caller has found.
pub fn measure_turns_in(
    swaths: &[Swath],
    blocks: &[Vec<usize>],
    width: f64,
    area_m2: f64,
    m: &Machine,
) -> SwathStats {
    let mut stats = SwathStats {
        swath_count: swaths.len(),
        swath_length_m: swaths.iter().map(Swath::length).sum(),
        area_m2,
        ..SwathStats::default()
    };
    stats.strip_area_m2 = stats.swath_length_m * width;
    let mut previous_corners: Option<[Coord; 4]> = None;
    let mut lengths = TurnLengths::new(m.turn_radius);
    for block in blocks {
        for (k, pair) in block.windows(2).enumerate() {
            let (a, b) = (&swaths[pair[0]], &swaths[pair[1]]);
            // Boustrophedon: the first swath driven forward, so turns alternate ends.
            let run = if k % 2 == 0 {
                (a.along.1 - b.along.1).abs()
            } else {
                (a.along.0 - b.along.0).abs()
            };
            stats.turn_count += 1;
            stats.turning_distance_m += lengths.of(b.across - a.across) + run;
        }
        // Moving on from the block before (blocks are found across the field, so neighbours
        // follow each other): a turn, and the way from its nearest corner to this block's.
        let (Some(&first), Some(&last)) = (block.first(), block.last()) else {
            continue;
        };
        let (f, l) = (&swaths[first].centre, &swaths[last].centre);
        let corners = [f.start, f.end, l.start, l.end];
        if let Some(before) = previous_corners {
            let gap = before
                .iter()
                .flat_map(|p| {
                    corners
                        .iter()
                        .map(move |q| (p.x - q.x).planar_hypot(p.y - q.y))
                })
                .fold(f64::INFINITY, f64::min);
            let change = turn_length(width, m.turn_radius) + gap;
            stats.turn_count += 1;
            stats.turning_distance_m += change;
            stats.block_change_m += change;
        }
        previous_corners = Some(corners);
    }
    stats.covered_area_m2 = stats.strip_area_m2.min(area_m2);
    stats
}

/// Area of `area` inside the union of the swaths' strips (see the module documentation).
fn covered_area(swaths: &[Swath], width: f64, area: &MultiPolygon) -> f64 {
    let Some(first) = swaths.first() else {
        return 0.0;
    };
    let frame = first.frame;
    let half = width / 2.0;
    // The pieces of each line, in line order.
    let mut lines: Vec<(f64, Vec<(f64, f64)>)> = Vec::new();
    for s in swaths {
        match lines.last_mut() {
            Some((c, pieces)) if *c == s.across => pieces.push(s.along),
            _ => lines.push((s.across, vec![s.along])),
        }
    }
    // The covered length changes slope only at the area's vertices, at the swath lines (where
    // the pieces were cut) and where a neighbour's strip begins: the breaks of the integral.
    let mut vertices: Vec<f64> = area
        .0
        .iter()
        .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
        .flat_map(|ring| ring.0.iter().map(|&v| frame.project(v).0))
        .collect();
    sort_floats(&mut vertices);
    // (sample offset, line, weight) at the middle of every interval between breaks.
    let mut samples: Vec<(f64, usize, f64)> = Vec::with_capacity(lines.len() * 4 + vertices.len());
    let mut breaks: Vec<f64> = Vec::new();
    for (i, &(c, _)) in lines.iter().enumerate() {
        let (lo, hi) = (c - half, c + half);
        breaks.clear();
        breaks.extend([lo, c, hi]);
        let from = vertices.partition_point(|&v| v <= lo);
        breaks.extend(vertices[from..].iter().take_while(|&&v| v < hi).copied());
        for j in [i.wrapping_sub(1), i + 1] {
            if let Some(&(n, _)) = lines.get(j) {
                breaks.extend(
                    [n - half, n, n + half]
                        .into_iter()
                        .filter(|&b| lo < b && b < hi),
                );
            }
        }
        sort_floats(&mut breaks);
        for pair in breaks.windows(2) {
            if pair[1] - pair[0] > 1e-9 {
                samples.push(((pair[0] + pair[1]) / 2.0, i, pair[1] - pair[0]));
            }
        }
    }
    samples.shared_sort_by_float_key(|s| s.0);
    let offsets: Vec<f64> = samples.iter().map(|s| s.0).collect();
    let mut covered = 0.0;
    frame.clip_each(area, &offsets, |k, chord| {
        let Some(&(c, i, weight)) = samples.get(k) else {
            return;
        };
        let own = &lines[i].1;
        let mut length = overlap_length(own, chord);
        // Where the previous line's strip also reaches, count only what it leaves.
        if let Some((pc, prev)) = i.checked_sub(1).map(|p| &lines[p]) {
            if (c - pc).abs() < half {
                length -= overlap3(own, prev, chord);
            }
        }
        covered += length * weight;
    });
    covered
}

/// Calls `f(lo, hi)` for every overlap of two sorted lists of disjoint intervals, in order.
fn for_each_overlap(a: &[(f64, f64)], b: &[(f64, f64)], mut f: impl FnMut(f64, f64)) {
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        let lo = a[i].0.greater(b[j].0);
        let hi = a[i].1.lesser(b[j].1);
        if hi > lo {
            f(lo, hi);
        }
        if a[i].1 < b[j].1 {
            i += 1;
        } else {
            j += 1;
        }
    }
}

/// Total length of the overlap of two sorted lists of disjoint intervals.
fn overlap_length(a: &[(f64, f64)], b: &[(f64, f64)]) -> f64 {
    let mut sum = 0.0;
    for_each_overlap(a, b, |lo, hi| sum += hi - lo);
    sum
}

/// Length of the overlap of three sorted lists of disjoint intervals.
fn overlap3(a: &[(f64, f64)], b: &[(f64, f64)], c: &[(f64, f64)]) -> f64 {
    let mut ab = Vec::new();
    for_each_overlap(a, b, |lo, hi| ab.push((lo, hi)));
    overlap_length(&ab, c)
}

/// Measures a plan's swaths area by area: the field's at its direction, and each prohibited
/// region's at its own.
pub fn measure_all(swaths: &Swaths, m: &Machine) -> SwathStats {
    let mut stats = SwathStats::default();
    for a in &swaths.areas {
        if let Some(s) = swaths.swaths.get(a.swaths.clone()) {
            stats += measure(s, swaths.width, &a.area, m);
        }
    }
    stats
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::swath::generate;
    use geo::{polygon, BooleanOps, Polygon};

    fn machine() -> Machine {
        Machine {
            width: 6.0,
            turn_radius: 8.0,
            working_speed: 8.0 / 3.6,
            turning_speed: 5.0 / 3.6,
        }
    }

    #[test]
    fn moves_between_blocks_are_counted_apart() {
        // Two 30 x 100 strips 100 m apart along the lines: two blocks of five swaths.
        let strips = MultiPolygon::new(vec![
            polygon![(x: 0., y: 0.), (x: 30., y: 0.), (x: 30., y: 100.), (x: 0., y: 100.)],
            polygon![(x: 0., y: 200.), (x: 30., y: 200.), (x: 30., y: 300.), (x: 0., y: 300.)],
        ]);
        let m = machine();
        let swaths = generate(&strips, 0.0, 6.0, 6.0).unwrap();
        let s = measure(&swaths.swaths, 6.0, &strips, &m);
        let turn = turn_length(6.0, m.turn_radius);
        assert_eq!(s.turn_count, 8 + 1);
        assert!((s.block_change_m - (turn + 100.0)).abs() < 1e-9);
        assert!((s.turning_distance_m - s.block_change_m - 8.0 * turn).abs() < 1e-9);
    }

    #[test]
    fn loop_turn_meets_u_turn_at_twice_the_radius() {
        let r = 8.0;
        assert!((turn_length(2.0 * r - 1e-9, r) - turn_length(2.0 * r, r)).abs() < 1e-3);
        // Shorter spacing needs a longer loop.
        assert!(turn_length(6.0, r) > turn_length(12.0, r));
    }

    /// Coverage by the integral equals the area of the union of the strips clipped to the
    /// region, computed with polygon booleans, on a field with slanted ends and a hole.
    #[test]
    fn coverage_matches_boolean_union() {
        let field = polygon!(
            exterior: [(x: 0., y: 0.), (x: 97., y: 13.), (x: 83., y: 71.), (x: 7., y: 60.)],
            interiors: [[(x: 30., y: 25.), (x: 52., y: 28.), (x: 45., y: 44.)]],
        );
        let area = MultiPolygon::new(vec![field]);
        for deg in [0.0f64, 17.0, 63.0, 90.0, 131.0] {
            let swaths = generate(&area, deg.to_radians(), 6.0, 6.0).unwrap();
            let stats = measure(&swaths.swaths, 6.0, &area, &machine());
            let mut union = MultiPolygon::new(vec![]);
            for s in &swaths.swaths {
                let f = &s.frame;
                let (c, (a0, a1)) = (s.across, s.along);
                let rect = Polygon::new(
                    vec![
                        f.point(c - 3.0, a0),
                        f.point(c + 3.0, a0),
                        f.point(c + 3.0, a1),
                        f.point(c - 3.0, a1),
                        f.point(c - 3.0, a0),
                    ]
                    .into(),
                    vec![],
                );
                union = union.union(&MultiPolygon::new(vec![rect]));
            }
            let exact = union.intersection(&area).unsigned_area();
            let rel = (stats.covered_area_m2 - exact).abs() / exact;
            // geo snaps its boolean results to a grid of about 1e-6 of the extent.
            assert!(rel < 1e-4, "{deg}: {} vs {exact}", stats.covered_area_m2);
        }
    }

    #[test]
    fn objectives_rank_a_long_strip_along_its_length() {
        // 30 x 300 m: along the length 5 swaths and 4 turns, across 50 and 49.
        let strip = MultiPolygon::new(vec![
            polygon![(x: 0., y: 0.), (x: 30., y: 0.), (x: 30., y: 300.), (x: 0., y: 300.)],
        ]);
        let m = machine();
        let along = measure(
            &generate(&strip, 0.0, 6.0, 6.0).unwrap().swaths,
            6.0,
            &strip,
            &m,
        );
        let across = measure(
            &generate(&strip, PI / 2.0, 6.0, 6.0).unwrap().swaths,
            6.0,
            &strip,
            &m,
        );
        for kind in [
            ObjectiveKind::SwathCount,
            ObjectiveKind::TurnCount,
            ObjectiveKind::Time,
            ObjectiveKind::Oksanen,
        ] {
            let o = kind.objective();
            assert!(o.cost(&along, &m) < o.cost(&across, &m), "{}", o.name());
        }
        assert!((along.coverage() - 1.0).abs() < 1e-9);
        let v = ObjectiveValues::of(&along, &m);
        assert_eq!(v.turn_count, 4);
        assert!(v.oksanen_score > 0.5 && v.oksanen_score <= 1.0);
    }

    #[test]
    fn names_match_the_options() {
        for kind in [
            ObjectiveKind::SwathCount,
            ObjectiveKind::SwathLength,
            ObjectiveKind::Coverage,
            ObjectiveKind::Overlap,
            ObjectiveKind::TurnCount,
            ObjectiveKind::Time,
            ObjectiveKind::Oksanen,
        ] {
            let json = serde_json::to_string(&kind).unwrap();
            assert_eq!(json, format!("\"{}\"", kind.objective().name()));
        }
    }
}
