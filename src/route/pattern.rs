//! The order of the swaths inside a block: Fields2Cover's route patterns (boustrophedon, snake,
//! spiral, custom), and `auto`, which takes for each block the pattern whose turns cost the
//! machine least.
//!
//! Every pattern drives each swath the other way from the one before, so a block worked from
//! one of its outer swaths ends on the side its swath count's parity says (Zhou et al. 2.4.1),
//! and it can be started in four ways: from either outer swath, in either direction. Turns are
//! costed by the turn model ([`turn_length`]) for the spacing between the two swaths, plus the
//! stagger between their ends: with spacing under twice the turning radius, neighbouring swaths
//! need a loop turn, which is why skipping swaths often wins (Fields2Cover's results).
//!
//! ```
//! use furrow::route::pattern::SwathOrder;
//!
//! assert_eq!(SwathOrder::Boustrophedon.positions(5), vec![0, 1, 2, 3, 4]);
//! // Fields2Cover's snake: out on every other swath, back on the ones skipped.
//! assert_eq!(SwathOrder::Snake { skip: 1 }.positions(6), vec![0, 2, 4, 5, 3, 1]);
//! // Its spiral, in groups of 6 from the outside in.
//! assert_eq!(SwathOrder::Spiral { size: 6 }.positions(8), vec![0, 5, 1, 4, 2, 3, 6, 7]);
//! ```

use crate::objective::{turn_length, TurnLengths};
use crate::swath::Swath;
use serde::Serialize;

/// The pattern option: how the swaths of each block are ordered.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SwathPattern {
    /// Swath after swath across the block, turning into the next one.
    Boustrophedon,
    /// Out on every (k + 1)-th swath, back on the ones skipped (`snakeSkip` = k).
    Snake,
    /// Groups of `spiralSize` swaths, each worked from its outside in.
    Spiral,
    /// The order `customOrder` gives, repeated over groups of its length.
    Custom,
    /// The pattern whose turns cost least, block by block.
    #[default]
    Auto,
}

crate::named::named!(SwathPattern { "boustrophedon" => Boustrophedon, "snake" => Snake, "spiral" => Spiral, "custom" => Custom, "auto" => Auto });

impl SwathPattern {
    /// The option's name.
    pub fn as_str(self) -> &'static str {
        match self {
            SwathPattern::Boustrophedon => "boustrophedon",
            SwathPattern::Snake => "snake",
            SwathPattern::Spiral => "spiral",
            SwathPattern::Custom => "custom",
            SwathPattern::Auto => "auto",
        }
    }
}

/// A swath order with its parameters.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SwathOrder {
    /// 0, 1, 2, ...
    Boustrophedon,
    /// Each turn skips `skip` swaths: the swaths fall into `skip + 1` interleaved sets, worked
    /// one after another, alternately out and back, taking the sets from the two sides in
    /// turn (0, k, 1, k - 1, ...) so that the turns between sets are wide too. Skip 1 is
    /// Fields2Cover's snake.
    Snake {
        /// Swaths skipped at each turn.
        skip: usize,
    },
    /// Groups of `size` swaths, each worked from its outside in (first, last, second, second
    /// last, ...): Fields2Cover's spiral.
    Spiral {
        /// Swaths in a group.
        size: usize,
    },
    /// A permutation of `0..m` applied to each group of `m` swaths (the last group, if shorter,
    /// keeps the permutation's order of the positions it has).
    Custom(Vec<usize>),
}

impl SwathOrder {
    /// The name as the plan output spells it (`snake-2`, `spiral-6`).
    pub fn name(&self) -> String {
        match self {
            SwathOrder::Boustrophedon => "boustrophedon".into(),
            SwathOrder::Snake { skip } => format!("snake-{skip}"),
            SwathOrder::Spiral { size } => format!("spiral-{size}"),
            SwathOrder::Custom(_) => "custom".into(),
        }
    }

    /// The positions (0 = the first swath across the block) in working order: a permutation of
    /// `0..n`.
    pub fn positions(&self, n: usize) -> Vec<usize> {
        let mut out = Vec::with_capacity(n);
        self.positions_into(n, &mut out);
        out
    }

    /// [`SwathOrder::positions`] into `out` (cleared first).
    pub fn positions_into(&self, n: usize, out: &mut Vec<usize>) {
        out.clear();
        match self {
            SwathOrder::Boustrophedon => out.extend(0..n),
            SwathOrder::Snake { skip } => {
                let step = skip.saturating_add(1).max(1);
                let sets = step.min(n.max(1));
                // Sets taken from the two sides in turn: 0, k, 1, k - 1, ...
                let (mut lo, mut hi) = (0usize, sets - 1);
                let mut outward = true;
                let mut from_low = true;
                while lo <= hi {
                    let set = if from_low { lo } else { hi };
                    let members = (set..n).step_by(step);
                    if outward {
                        out.extend(members);
                    } else {
                        out.extend(members.rev());
                    }
                    outward = !outward;
                    if from_low {
                        lo += 1;
                    } else if hi == 0 {
                        break;
                    } else {
                        hi -= 1;
                    }
                    from_low = !from_low;
                }
            }
            SwathOrder::Spiral { size } => {
                let size = (*size).max(1);
                let mut start = 0;
                while start < n {
                    let m = size.min(n - start);
                    let (mut lo, mut hi) = (0, m - 1);
                    let mut low = true;
                    while lo <= hi {
                        if low {
                            out.push(start + lo);
                            lo += 1;
                        } else {
                            out.push(start + hi);
                            if hi == 0 {
                                break;
                            }
                            hi -= 1;
                        }
                        low = !low;
                    }
                    start += m;
                }
            }
            SwathOrder::Custom(order) => {
                let m = order.len();
                if m == 0 {
                    out.extend(0..n);
                    return;
                }
                let mut start = 0;
                while start < n {
                    let left = m.min(n - start);
                    out.extend(order.iter().filter(|&&p| p < left).map(|&p| start + p));
                    start += m;
                }
            }
        }
    }
}

/// The orders `pattern` allows for a machine: one, or for `auto` the candidates compared on
/// each block: boustrophedon, snake skipping one, snake skipping as few as make every turn a
/// plain U-turn (spacing at least twice the turning radius), and spiral.
pub fn candidates(
    pattern: SwathPattern,
    snake_skip: usize,
    spiral_size: usize,
    custom_order: &[usize],
    width: f64,
    turn_radius: f64,
) -> Vec<SwathOrder> {
    match pattern {
        SwathPattern::Boustrophedon => vec![SwathOrder::Boustrophedon],
        SwathPattern::Snake => vec![SwathOrder::Snake { skip: snake_skip }],
        SwathPattern::Spiral => vec![SwathOrder::Spiral { size: spiral_size }],
        SwathPattern::Custom => vec![SwathOrder::Custom(custom_order.to_vec())],
        SwathPattern::Auto => {
            let mut out = vec![SwathOrder::Boustrophedon, SwathOrder::Snake { skip: 1 }];
            // The fewest skipped swaths for which (skip + 1)·w >= 2r.
            let u_turn = if width > 0.0 {
                ((2.0 * turn_radius / width).ceil() as usize).saturating_sub(1)
            } else {
                1
            };
            if (2..=MAX_AUTO_SKIP).contains(&u_turn) {
                out.push(SwathOrder::Snake { skip: u_turn });
            }
            out.push(SwathOrder::Spiral { size: spiral_size });
            out
        }
    }
}

/// The widest skip `auto` tries.
const MAX_AUTO_SKIP: usize = 8;

/// One way to work a block: its swaths in working order, and which way the first is driven.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockWay {
    /// Swath indices (into [`Swaths::swaths`](crate::swath::Swaths::swaths)) in working order.
    pub swaths: Vec<usize>,
    /// Whether the first swath is driven against the swath direction; each next one is driven
    /// the other way from the one before.
    pub first_reversed: bool,
    /// Length of its turns by the turn model, metres.
    pub turning_m: f64,
}

impl BlockWay {
    /// Where the way starts: the start of its first swath as driven (`None` without swaths, or
    /// with an index outside `swaths`).
    pub fn entry(&self, swaths: &[Swath]) -> Option<geo::Coord> {
        let first = swaths.get(*self.swaths.first()?)?;
        Some(if self.first_reversed {
            first.centre.end
        } else {
            first.centre.start
        })
    }

    /// Where the way ends: the end of its last swath as driven.
    pub fn exit(&self, swaths: &[Swath]) -> Option<geo::Coord> {
        let last = swaths.get(*self.swaths.last()?)?;
        // Each swath is driven the other way from the one before.
        let reversed = self.first_reversed ^ self.swaths.len().is_multiple_of(2);
        Some(if reversed {
            last.centre.start
        } else {
            last.centre.end
        })
    }
}

/// The four ways to work a block in `order`: from its first or its last swath across (the order
/// mirrored), each driven either way first. `ids` are the block's swaths in line order.
pub fn ways(
    ids: &[usize],
    swaths: &[Swath],
    order: &SwathOrder,
    turns: TurnLengths,
) -> Vec<BlockWay> {
    let (mut positions, mut forward, mut mirrored) = (Vec::new(), Vec::new(), Vec::new());
    sequences(ids, order, [&mut positions, &mut forward, &mut mirrored]);
    let mut out = Vec::with_capacity(4);
    for sequence in [forward, mirrored] {
        for first_reversed in [false, true] {
            let turning_m = turning_of(&sequence, first_reversed, swaths, turns);
            out.push(BlockWay {
                swaths: sequence.clone(),
                first_reversed,
                turning_m,
            });
        }
    }
    out
}

/// The turn model's length of the turns of a block worked in the cheapest of `orders`, metres:
/// the pattern the route picks for it (the one whose four ways turn least on average, see
/// [`ways`]). `ids` are the block's swaths in line order; no orders give boustrophedon.
///
/// ```
/// use furrow::objective::TurnLengths;
/// use furrow::route::pattern::{block_turning_m, SwathOrder};
/// use furrow::swath::{generate_with, LinePlacement, SwathSettings};
/// use geo::{polygon, MultiPolygon};
///
/// // A block 18 m wide, 3 m swaths, a machine turning at 6 m: a snake skipping three swaths
/// // turns in plain U-turns, where boustrophedon needs a loop at every end.
/// let block = polygon![(x: 0., y: 0.), (x: 18., y: 0.), (x: 18., y: 100.), (x: 0., y: 100.)];
/// let settings = SwathSettings {
///     bearing: 0.0, width: 3.0, min_length: 3.0, placement: LinePlacement::FromEdge,
/// };
/// let swaths = generate_with(&MultiPolygon::new(vec![block]), &settings)?.swaths;
/// let ids: Vec<usize> = (0..swaths.len()).collect();
/// let turns = TurnLengths::new(6.0);
/// let bous = block_turning_m(&ids, &swaths, &[SwathOrder::Boustrophedon], turns);
/// let auto = [SwathOrder::Boustrophedon, SwathOrder::Snake { skip: 3 }];
/// assert!(block_turning_m(&ids, &swaths, &auto, turns) < bous);
/// # Ok::<(), furrow::error::PlanError>(())
/// ```
pub fn block_turning_m(
    ids: &[usize],
    swaths: &[Swath],
    orders: &[SwathOrder],
    turns: TurnLengths,
) -> f64 {
    let boustrophedon = [SwathOrder::Boustrophedon];
    let orders = if orders.is_empty() {
        &boustrophedon[..]
    } else {
        orders
    };
    // The mean over the four ways of `ways`, without building them: planning asks this for
    // every block of every direction a decomposition tries.
    let mut positions: Vec<usize> = Vec::with_capacity(ids.len());
    let mut forward: Vec<usize> = Vec::with_capacity(ids.len());
    let mut mirrored: Vec<usize> = Vec::with_capacity(ids.len());
    let mut lengths = turns;
    let mut least = f64::INFINITY;
    for order in orders {
        sequences(ids, order, [&mut positions, &mut forward, &mut mirrored]);
        let mut total = 0.0;
        for sequence in [&forward, &mirrored] {
            // Driven either way first: the same turns, the staggers at the other ends.
            let [ahead, reversed] = turning_both_ways(sequence, swaths, &mut lengths);
            total += ahead;
            total += reversed;
        }
        let mean = total / 4.0;
        if mean < least {
            least = mean;
        }
    }
    least
}

/// The swaths of a block (`ids`, in line order) in `order` from its first line across
/// (`forward`) and from its last (`mirrored`), into the two lists (cleared first; `positions`
/// is room for the order's positions).
fn sequences(
    ids: &[usize],
    order: &SwathOrder,
    [positions, forward, mirrored]: [&mut Vec<usize>; 3],
) {
    let n = ids.len();
    order.positions_into(n, positions);
    forward.clear();
    forward.extend(positions.iter().filter_map(|&p| ids.get(p).copied()));
    mirrored.clear();
    mirrored.extend(
        positions
            .iter()
            .filter_map(|&p| n.checked_sub(1 + p).and_then(|k| ids.get(k).copied())),
    );
}

/// The turn model's length of the turns of swaths worked in this sequence, metres (`turns`:
/// the turn lengths of the machine).
pub fn turning_of(
    sequence: &[usize],
    first_reversed: bool,
    swaths: &[Swath],
    turns: TurnLengths,
) -> f64 {
    let mut reversed = first_reversed;
    let mut total = 0.0;
    let mut lengths = turns;
    for w in sequence.windows(2) {
        if let (Some(a), Some(b)) = (swaths.get(w[0]), swaths.get(w[1])) {
            total += lengths.between(a.across - b.across, stagger(a, reversed, b));
        }
        reversed = !reversed;
    }
    total
}

/// The turn model's length from the end of swath `a` (driven against its direction if
/// `a_reversed`) into swath `b`, driven the other way: a turn for the spacing between them,
/// and the stagger between the ends.
pub fn turn_between(a: &Swath, a_reversed: bool, b: &Swath, radius: f64) -> f64 {
    turn_length(a.across - b.across, radius) + stagger(a, a_reversed, b)
}

/// [`turning_of`] the sequence with its first swath driven along the swath direction and
/// against it, in one pass (the same numbers).
fn turning_both_ways(sequence: &[usize], swaths: &[Swath], lengths: &mut TurnLengths) -> [f64; 2] {
    let mut reversed = false;
    let mut totals = [0.0; 2];
    for w in sequence.windows(2) {
        if let (Some(a), Some(b)) = (swaths.get(w[0]), swaths.get(w[1])) {
            let spacing = a.across - b.across;
            totals[0] += lengths.between(spacing, stagger(a, reversed, b));
            totals[1] += lengths.between(spacing, stagger(a, !reversed, b));
        }
        reversed = !reversed;
    }
    totals
}

/// How far apart the ends of `a` and `b` lie along the swaths at the end the turn from `a`
/// (driven against its direction if `a_reversed`) is made.
fn stagger(a: &Swath, a_reversed: bool, b: &Swath) -> f64 {
    if a_reversed {
        (a.along.0 - b.along.0).abs()
    } else {
        (a.along.1 - b.along.1).abs()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn is_permutation(mut p: Vec<usize>, n: usize) -> bool {
        p.sort_unstable();
        p == (0..n).collect::<Vec<_>>()
    }

    #[test]
    fn every_order_is_a_permutation() {
        let orders = [
            SwathOrder::Boustrophedon,
            SwathOrder::Snake { skip: 1 },
            SwathOrder::Snake { skip: 2 },
            SwathOrder::Snake { skip: 5 },
            SwathOrder::Spiral { size: 1 },
            SwathOrder::Spiral { size: 4 },
            SwathOrder::Spiral { size: 6 },
            SwathOrder::Custom(vec![2, 0, 3, 1]),
            SwathOrder::Custom(vec![]),
        ];
        for order in &orders {
            for n in 0..40 {
                assert!(is_permutation(order.positions(n), n), "{order:?} {n}");
            }
        }
    }

    #[test]
    fn snake_skips_and_comes_back() {
        let s = SwathOrder::Snake { skip: 1 };
        assert_eq!(s.positions(5), vec![0, 2, 4, 3, 1]);
        assert_eq!(s.positions(1), vec![0]);
        // Skipping two: out on 0, 3, 6, back on 8, 5, 2 (the set from the other side), then 1, 4, 7.
        let s = SwathOrder::Snake { skip: 2 };
        assert_eq!(s.positions(9), vec![0, 3, 6, 8, 5, 2, 1, 4, 7]);
        // Every turn but the ones between sets skips two swaths.
        let p = s.positions(30);
        let narrow = p.windows(2).filter(|w| w[0].abs_diff(w[1]) < 3).count();
        assert!(narrow <= 2, "{p:?}");
    }

    #[test]
    fn spiral_and_custom_work_in_groups() {
        assert_eq!(
            SwathOrder::Spiral { size: 4 }.positions(10),
            vec![0, 3, 1, 2, 4, 7, 5, 6, 8, 9]
        );
        let c = SwathOrder::Custom(vec![1, 3, 0, 2]);
        assert_eq!(c.positions(7), vec![1, 3, 0, 2, 5, 4, 6]);
    }

    #[test]
    fn auto_tries_the_skip_that_makes_every_turn_a_u_turn() {
        // 3 m width, 8 m radius: skipping 5 gives 18 m >= 16 m.
        let c = candidates(SwathPattern::Auto, 1, 6, &[], 3.0, 8.0);
        assert!(c.contains(&SwathOrder::Snake { skip: 5 }), "{c:?}");
        assert_eq!(c[0], SwathOrder::Boustrophedon);
        let c = candidates(SwathPattern::Snake, 3, 6, &[], 3.0, 8.0);
        assert_eq!(c, vec![SwathOrder::Snake { skip: 3 }]);
    }

    #[test]
    fn skipping_saves_turning_when_swaths_are_closer_than_twice_the_radius() {
        use crate::swath::generate;
        use geo::{polygon, MultiPolygon};
        let field =
            polygon![(x: 0., y: 0.), (x: 120., y: 0.), (x: 120., y: 200.), (x: 0., y: 200.)];
        let swaths = generate(&MultiPolygon::new(vec![field]), 0.0, 4.0, 4.0).unwrap();
        let ids: Vec<usize> = (0..swaths.swaths.len()).collect();
        let cost =
            |o: &SwathOrder| ways(&ids, &swaths.swaths, o, TurnLengths::new(8.0))[0].turning_m;
        let bous = cost(&SwathOrder::Boustrophedon);
        let snake = cost(&SwathOrder::Snake { skip: 3 });
        assert!(snake < 0.8 * bous, "snake {snake} boustrophedon {bous}");
        // The four ways visit every swath.
        for w in ways(
            &ids,
            &swaths.swaths,
            &SwathOrder::Snake { skip: 1 },
            TurnLengths::new(8.0),
        ) {
            assert!(is_permutation(w.swaths.clone(), ids.len()));
        }
    }
}
