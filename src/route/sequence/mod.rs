//! The block sequence: the order in which the blocks are worked, and the way each is worked
//! (Zhou, Bochtis et al. 2014, section 2.4).
//!
//! # The formulation
//!
//! After decomposition the field is a set of blocks, each a sub-field of parallel swaths worked
//! boustrophedon. Zhou et al. start the work of a block at one of its two outermost swaths, so a
//! block has four entry nodes: the two ends of its first swath and the two ends of its last. The
//! exit follows from the entry and the parity of the swath count: entered at one end of the first
//! swath, a block with an odd number of swaths is left at the far end of its last swath, one with
//! an even number at the near end. Here each such choice is a [`Way`]: an entry point, an exit
//! point and the cost of the driving inside the block that way. A block may have any number of
//! ways (one, two, Zhou's four, or more), and a block with none is left out.
//!
//! A [`Sequence`] takes every block with ways once, in some order and each in one of its ways. Its
//! cost is
//!
//! ```text
//! from_start[entry of the first] + sum of the ways' costs
//!     + sum of connection[exit of a block][entry of the next] + to_finish[exit of the last]
//!     + the cost of each [`Precedence`] the order breaks
//! ```
//!
//! which is Zhou's Hamiltonian path through the graph of entry/exit nodes, with the internal
//! costs (their zero and large `L` entries between a block's own nodes) folded into the ways. The
//! connection matrix may be asymmetric and may carry large penalties (Zhou's `L`, say `1e7`) for
//! connections that cross the main field; every cost is clamped to ±[`LARGE_COST`] (NaN to
//! `LARGE_COST`) so that sums stay finite and ordered, and a missing entry or an out-of-range
//! point index costs `LARGE_COST`.
//!
//! # The solvers
//!
//! - [`solve_exact`]: dynamic programming over subsets of blocks and the way of the last block
//!   (Held-Karp). The best cost of a partial sequence depends only on the set of blocks it has
//!   worked and on where it stands, the exit of its last way: every completion of it costs the
//!   same whatever order came before. So `best[set][way]`, filled for the sets in increasing
//!   order, each from the sets one block smaller, is exact, in `O(2^blocks x blocks^2 x ways^2)`
//!   time and `O(2^blocks x blocks x ways)` memory: about 3 ms at 12 blocks of four ways natively
//!   (release), about 10 ms in WebAssembly.
//! - [`solve_heuristic`]: above that, the ant colony of Zhou et al. (Ant System, Dorigo 1996) over
//!   the (block, way) nodes, with their parameters `rho = 0.5, alpha = 1, beta = 5` and as many
//!   ants as nodes (capped, see [`AntColony`]); each ant walks from node to node through blocks
//!   it has not worked yet, choosing the next in proportion to `pheromone^alpha x
//!   (1 / cost)^beta`; the pheromone evaporates by `rho` each iteration and each ant lays more on
//!   the cheaper tours. The colony's best few orders are then improved by local search on the
//!   block order: 2-opt (reverse a run of blocks) and or-opt (move one block or a run of two or
//!   three, either way round, elsewhere), tried where they make a connection to one of a
//!   block's eight cheapest neighbours, until no such move improves or the search has done
//!   [`LOCAL_SEARCH_WORK`] (it then keeps the best order so far).
//! - [`best_ways`]: for a fixed block order the best way of each block is a shortest path through
//!   the layered graph of ways (Viterbi), `O(blocks x ways^2)`. The local search evaluates each
//!   candidate order with its best ways, kept incrementally as prefix and suffix layers, so a
//!   move that only changes the order may also change every way; a move costs only the layers
//!   it changes.
//! - [`exhaustive`] and [`random_restarts`]: yardsticks for the two above, as the exhaustive
//!   search of Zhou et al. 3.2.
//!
//! [`solve`] takes the exact answer up to [`EXACT_MAX_BLOCKS`] blocks (while its table costs at
//! most [`EXACT_MAX_WORK`] steps) and the heuristic above.
//! Every solver is deterministic: the same problem and seed give the same sequence.

/// The ant colony and the heuristic it starts ([`solve_heuristic`]).
mod ant_colony;
/// The problem as the solvers see it, and the layer steps that cost a block order
/// ([`best_ways`]).
mod compiled;
/// Dynamic programming ([`solve_exact`]) and every permutation ([`exhaustive`]).
mod exact;
/// 2-opt and or-opt on a block order within a budget of work, and [`random_restarts`].
mod local_search;
/// The problems and checks the solvers' tests share.
#[cfg(test)]
mod test_support;

pub use ant_colony::{solve_heuristic, AntColony};
pub use compiled::best_ways;
pub use exact::{exhaustive, solve_exact, EXACT_MAX_BLOCKS, EXACT_MAX_WORK, EXHAUSTIVE_MAX_BLOCKS};
pub use local_search::{random_restarts, LOCAL_SEARCH_WORK};

use crate::geometry::PlanarHypot;
use crate::rng::SplitMix64 as Rng;
use exact::exact_pays;

/// One way to work a block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Way {
    /// The point where the block is entered.
    pub entry: usize,
    /// The point where the block is left.
    pub exit: usize,
    /// The cost of working the block this way (its internal driving).
    pub cost: f64,
}

/// A block sequencing problem: blocks, their ways, and the costs between points.
#[derive(Debug, Clone, PartialEq)]
pub struct SequenceProblem {
    /// For each block, its ways (a block with no ways is left out of the sequence).
    pub ways: Vec<Vec<Way>>,
    /// Number of points; entry and exit are indices below it.
    pub points: usize,
    /// `points x points`, row-major: the cost from point `i` (an exit) to point `j` (an entry).
    /// May be asymmetric and may hold large penalties (`1e7` and up) for connections to avoid;
    /// values are clamped to ±[`LARGE_COST`] (NaN to `LARGE_COST`), missing entries cost
    /// `LARGE_COST`.
    pub connection: Vec<f64>,
    /// The cost from the start to each point (all zero: the route may start anywhere).
    pub from_start: Vec<f64>,
    /// The cost from each point to the finish (all zero: the route may end anywhere).
    pub to_finish: Vec<f64>,
    /// Blocks better worked before others: each costs its `cost` where its `then` block comes
    /// before its `first` (none: every order costs its driving alone).
    pub precedence: Vec<Precedence>,
}

/// Block `first` is better worked before block `then`: working `then` first costs `cost` more
/// (its turns run over the crop of `first` while it still stands).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Precedence {
    /// The block to work first (index into [`SequenceProblem::ways`]).
    pub first: usize,
    /// The block to work after it.
    pub then: usize,
    /// What working `then` before `first` costs, in the units of the connections.
    pub cost: f64,
}

/// How a [`Sequence`] was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SequenceMethod {
    /// Proven optimal: dynamic programming ([`solve_exact`]) or enumeration ([`exhaustive`]).
    Exact,
    /// A heuristic, good but not proven optimal: the ant colony and local search
    /// ([`solve_heuristic`]), also reported by the local-search yardstick [`random_restarts`].
    AntColony,
    /// A plain order for many blocks: each next block the nearest not yet worked
    /// ([`nearest_order`](super::nearest::nearest_order)).
    NearestNeighbour,
}

impl SequenceMethod {
    /// The method's name: `"exact"`, `"ant-colony"` or `"nearest-neighbour"`.
    pub fn as_str(self) -> &'static str {
        match self {
            SequenceMethod::Exact => "exact",
            SequenceMethod::AntColony => "ant-colony",
            SequenceMethod::NearestNeighbour => "nearest-neighbour",
        }
    }
}

/// A block sequence: the blocks in working order, each with its way.
#[derive(Debug, Clone, PartialEq)]
pub struct Sequence {
    /// (block, way index into `ways[block]`) in working order.
    pub order: Vec<(usize, usize)>,
    /// The total cost, as [`SequenceProblem::cost`] of `order`.
    pub cost: f64,
    /// How it was found.
    pub method: SequenceMethod,
}

/// Every cost is clamped to `-LARGE_COST..=LARGE_COST`, and a missing one costs this.
pub const LARGE_COST: f64 = 1e12;

fn clamp_cost(cost: f64) -> f64 {
    if cost.is_nan() {
        LARGE_COST
    } else {
        cost.clamp(-LARGE_COST, LARGE_COST)
    }
}

impl SequenceProblem {
    /// The cost of the connection from point `exit` to point `entry` (clamped; `LARGE_COST`
    /// when either is out of range or the matrix has no such entry).
    pub fn connection_cost(&self, exit: usize, entry: usize) -> f64 {
        if exit >= self.points || entry >= self.points {
            return LARGE_COST;
        }
        exit.checked_mul(self.points)
            .and_then(|i| i.checked_add(entry))
            .and_then(|i| self.connection.get(i))
            .map_or(LARGE_COST, |&c| clamp_cost(c))
    }

    /// The cost from the start to `point` (clamped; `LARGE_COST` when missing).
    pub fn start_cost(&self, point: usize) -> f64 {
        if point >= self.points {
            return LARGE_COST;
        }
        self.from_start
            .get(point)
            .map_or(LARGE_COST, |&c| clamp_cost(c))
    }

    /// The cost from `point` to the finish (clamped; `LARGE_COST` when missing).
    pub fn finish_cost(&self, point: usize) -> f64 {
        if point >= self.points {
            return LARGE_COST;
        }
        self.to_finish
            .get(point)
            .map_or(LARGE_COST, |&c| clamp_cost(c))
    }

    /// The cost of working the blocks in this order with these ways: from the start to the first
    /// entry, each way's cost, each connection from an exit to the next entry, from the last
    /// exit to the finish, and the [`precedence_cost`](Self::precedence_cost). Pairs that name
    /// no way are skipped; an empty order costs 0.
    pub fn cost(&self, order: &[(usize, usize)]) -> f64 {
        let mut total = 0.0;
        let mut last: Option<&Way> = None;
        for &(block, way) in order {
            let Some(way) = self.ways.get(block).and_then(|ways| ways.get(way)) else {
                continue;
            };
            total += match last {
                None => self.start_cost(way.entry),
                Some(previous) => self.connection_cost(previous.exit, way.entry),
            };
            total += clamp_cost(way.cost);
            last = Some(way);
        }
        if let Some(way) = last {
            total += self.finish_cost(way.exit);
        }
        total + self.precedence_cost(order)
    }

    /// What the order costs for blocks worked before those they should follow ([`Precedence`]):
    /// each whose `then` block comes before its `first`, both in the order.
    pub fn precedence_cost(&self, order: &[(usize, usize)]) -> f64 {
        let at = |block: usize| order.iter().position(|&(b, _)| b == block);
        self.precedence
            .iter()
            .filter(|p| matches!((at(p.first), at(p.then)), (Some(f), Some(t)) if t < f))
            .map(|p| clamp_cost(p.cost))
            .sum()
    }
}

/// The result for no blocks.
fn empty_sequence(method: SequenceMethod) -> Sequence {
    Sequence {
        order: Vec::new(),
        cost: 0.0,
        method,
    }
}

/// Exact for up to [`EXACT_MAX_BLOCKS`] blocks (and [`EXACT_MAX_WORK`] steps), else the ant
/// colony improved by local search (default [`AntColony`] settings with this seed).
///
/// ```
/// use furrow::route::sequence::{solve, SequenceMethod, SequenceProblem, Way};
///
/// // Two blocks of one swath each: block 0 from point 0 to point 1 or back, block 1 from
/// // point 2 to point 3 or back. The points lie on a line at x = 0, 100, 110 and 210.
/// let one_swath = |a, b| {
///     vec![Way { entry: a, exit: b, cost: 100.0 }, Way { entry: b, exit: a, cost: 100.0 }]
/// };
/// let x = [0.0, 100.0, 110.0, 210.0];
/// let problem = SequenceProblem {
///     ways: vec![one_swath(0, 1), one_swath(2, 3)],
///     points: 4,
///     connection: x.iter().flat_map(|a| x.iter().map(move |b| f64::abs(a - b))).collect(),
///     from_start: vec![0.0; 4],
///     to_finish: vec![0.0; 4],
///     precedence: Vec::new(),
/// };
/// let sequence = solve(&problem, 0);
/// assert_eq!(sequence.method, SequenceMethod::Exact);
/// assert_eq!(sequence.cost, 210.0); // 100 + 10 + 100: straight along the line, either way
/// assert!(sequence.order == [(0, 0), (1, 0)] || sequence.order == [(1, 1), (0, 1)]);
/// ```
pub fn solve(problem: &SequenceProblem, seed: u64) -> Sequence {
    let blocks = problem.ways.iter().filter(|w| !w.is_empty()).count();
    let ways: usize = problem.ways.iter().map(Vec::len).sum();
    if exact_pays(blocks, ways) {
        solve_exact(problem)
    } else {
        solve_heuristic(
            problem,
            &AntColony {
                seed,
                ..AntColony::default()
            },
        )
    }
}

/// A random problem for tests and benchmarks.
///
/// `blocks` rectangles of parallel swaths, each 50 to 400 m long, 3 to 12 m apart, 1 to 30 of
/// them, at a random angle and a random place in a 2 km square. Points `4k..4k + 4` of block
/// `k` are the start and end of its first swath, then the start and end of its last. Its four
/// ways enter at each of them and leave at the far swath's end on the side the parity gives
/// (odd: the other side, even: the same side as the entry). A way's cost is the block's driving:
/// its swaths plus a turn of twice the spacing between each two. A connection is the straight
/// distance times a random detour factor in `[1, 1.5)`, drawn for each ordered pair (so it is
/// asymmetric and not quite metric); from a point to itself it is 0. From start and to finish
/// are zero.
pub fn random_problem(blocks: usize, seed: u64) -> SequenceProblem {
    let mut rng = Rng::new(seed);
    let points = blocks * 4;
    let mut xy: Vec<(f64, f64)> = Vec::with_capacity(points);
    let mut ways = Vec::with_capacity(blocks);
    for k in 0..blocks {
        let swaths = 1 + rng.below(30);
        let spacing = 3.0 + 9.0 * rng.unit();
        let length = 50.0 + 350.0 * rng.unit();
        let angle = std::f64::consts::PI * rng.unit();
        let (cx, cy) = (2000.0 * rng.unit(), 2000.0 * rng.unit());
        let (ux, uy) = (angle.cos(), angle.sin());
        let (vx, vy) = (-uy, ux);
        let half_across = 0.5 * spacing * (swaths - 1) as f64;
        let half_along = 0.5 * length;
        for across in [-half_across, half_across] {
            for along in [-half_along, half_along] {
                xy.push((cx + ux * along + vx * across, cy + uy * along + vy * across));
            }
        }
        let cost = swaths as f64 * length + (swaths - 1) as f64 * 2.0 * spacing;
        let odd = swaths % 2 == 1;
        let base = 4 * k;
        // Entered at an end of the first swath, left at the last swath, and the other way round.
        let exits = if odd { [3, 2, 1, 0] } else { [2, 3, 0, 1] };
        ways.push(
            (0..4)
                .map(|e| Way {
                    entry: base + e,
                    exit: base + exits[e],
                    cost,
                })
                .collect(),
        );
    }
    let mut connection = Vec::with_capacity(points * points);
    for (i, &(xi, yi)) in xy.iter().enumerate() {
        for (j, &(xj, yj)) in xy.iter().enumerate() {
            let detour = 1.0 + 0.5 * rng.unit();
            connection.push(if i == j {
                0.0
            } else {
                (xi - xj).planar_hypot(yi - yj) * detour
            });
        }
    }
    SequenceProblem {
        ways,
        points,
        connection,
        from_start: vec![0.0; points],
        to_finish: vec![0.0; points],
        precedence: Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::test_support::{check, irregular_problem};
    use super::*;

    #[test]
    fn blocks_without_ways_are_skipped() {
        let mut problem = random_problem(5, 7);
        problem.ways[1].clear();
        problem.ways[3].clear();
        problem.ways.push(Vec::new());
        for sequence in [
            solve(&problem, 0),
            solve_exact(&problem),
            solve_heuristic(&problem, &AntColony::default()),
            exhaustive(&problem),
            random_restarts(&problem, 3, 0),
        ] {
            check(&problem, &sequence);
            assert_eq!(sequence.order.len(), 3);
        }
    }

    /// Random pairs of blocks better worked one before the other, each costing up to about a
    /// connection across the problem's square.
    fn with_precedence(mut problem: SequenceProblem, seed: u64) -> SequenceProblem {
        let mut rng = Rng::new(seed);
        let blocks = problem.ways.len();
        for _ in 0..blocks {
            let (first, then) = (rng.below(blocks), rng.below(blocks));
            if first != then {
                let cost = 2000.0 * rng.unit();
                problem.precedence.push(Precedence { first, then, cost });
            }
        }
        problem
    }

    #[test]
    fn precedence_is_weighed_exactly_and_by_the_heuristic() {
        for blocks in 2..=7 {
            for seed in 0..4u64 {
                let problem = with_precedence(random_problem(blocks, seed + 40), seed);
                let exact = solve_exact(&problem);
                let all = exhaustive(&problem);
                check(&problem, &exact);
                check(&problem, &all);
                assert!(
                    (exact.cost - all.cost).abs() <= 1e-9 * all.cost,
                    "{blocks} blocks, seed {seed}: {} vs {}",
                    exact.cost,
                    all.cost
                );
                let order: Vec<usize> = exact.order.iter().map(|&(b, _)| b).collect();
                assert!((best_ways(&problem, &order).1 - exact.cost).abs() <= 1e-9 * exact.cost);
                let heuristic = solve_heuristic(&problem, &AntColony::default());
                check(&problem, &heuristic);
                assert!(heuristic.cost >= exact.cost * (1.0 - 1e-9));
            }
        }
    }

    #[test]
    fn a_block_better_worked_first_comes_first_where_that_outweighs_the_driving() {
        // Exact (6 blocks) and the heuristic (30): the blocks that end and start the best order
        // by driving alone, then with the last better worked before the first.
        for blocks in [6, 30] {
            let mut problem = random_problem(blocks, 5);
            let driving = solve(&problem, 0);
            let (Some(&(start, _)), Some(&(end, _))) =
                (driving.order.first(), driving.order.last())
            else {
                panic!("no order");
            };
            problem.precedence.push(Precedence {
                first: end,
                then: start,
                cost: 1e6,
            });
            let kept = solve(&problem, 0);
            check(&problem, &kept);
            let at = |b: usize| kept.order.iter().position(|&(k, _)| k == b);
            assert!(at(end) < at(start), "{blocks} blocks: {:?}", kept.order);
            assert!(kept.cost < driving.cost + 1e6, "{blocks} blocks");
        }
    }

    #[test]
    fn empty_problem() {
        let empty = SequenceProblem {
            ways: Vec::new(),
            points: 0,
            connection: Vec::new(),
            from_start: Vec::new(),
            to_finish: Vec::new(),
            precedence: Vec::new(),
        };
        let no_ways = SequenceProblem {
            ways: vec![Vec::new(); 3],
            ..empty.clone()
        };
        for problem in [&empty, &no_ways] {
            for sequence in [
                solve(problem, 0),
                solve_exact(problem),
                solve_heuristic(problem, &AntColony::default()),
                exhaustive(problem),
                random_restarts(problem, 10, 0),
            ] {
                assert!(sequence.order.is_empty());
                assert_eq!(sequence.cost, 0.0);
            }
            assert_eq!(best_ways(problem, &[0, 1, 5]), (vec![0, 0, 0], 0.0));
        }
        assert_eq!(random_problem(0, 1).ways.len(), 0);
    }

    #[test]
    fn start_and_finish_costs_are_respected() {
        for blocks in [6, 16] {
            let mut problem = random_problem(blocks, 11);
            // Only entry 2 of block 4 is free to start at, only exit of way 1 of block 5 to end.
            problem.from_start.fill(1e6);
            problem.from_start[problem.ways[4][2].entry] = 0.0;
            problem.to_finish.fill(1e6);
            problem.to_finish[problem.ways[5][1].exit] = 0.0;
            for sequence in [
                solve(&problem, 3),
                solve_heuristic(&problem, &AntColony::default()),
            ] {
                check(&problem, &sequence);
                assert_eq!(sequence.order.first(), Some(&(4, 2)));
                assert_eq!(sequence.order.last(), Some(&(5, 1)));
                assert!(sequence.cost < 1e6);
            }
        }
    }

    #[test]
    fn penalised_connections_are_avoided() {
        for blocks in [6, 15] {
            let mut problem = random_problem(blocks, 5);
            let first = solve(&problem, 1);
            // Forbid the first connection the best sequence makes.
            let (a, wa) = first.order[0];
            let (b, wb) = first.order[1];
            let exit = problem.ways[a][wa].exit;
            let entry = problem.ways[b][wb].entry;
            problem.connection[exit * problem.points + entry] = 1e7;
            for sequence in [
                solve(&problem, 1),
                solve_heuristic(&problem, &AntColony::default()),
            ] {
                check(&problem, &sequence);
                assert!(sequence.cost < 1e7);
                assert!(sequence.order.windows(2).all(|p| (
                    problem.ways[p[0].0][p[0].1].exit,
                    problem.ways[p[1].0][p[1].1].entry
                ) != (exit, entry)));
            }
        }
    }

    #[test]
    fn odd_input_does_not_panic() {
        let mut problem = irregular_problem(14, 9);
        problem.connection.truncate(10);
        problem.from_start.clear();
        problem.to_finish.push(f64::NAN);
        problem.ways[0].push(Way {
            entry: usize::MAX,
            exit: 1_000_000,
            cost: f64::INFINITY,
        });
        problem.ways[1].push(Way {
            entry: 0,
            exit: 0,
            cost: f64::NEG_INFINITY,
        });
        problem.points = usize::MAX;
        for sequence in [
            solve(&problem, 0),
            solve_exact(&problem),
            solve_heuristic(&problem, &AntColony::default()),
            random_restarts(&problem, 2, 0),
        ] {
            assert!(sequence.cost.is_finite());
            check(&problem, &sequence);
        }
        let strange = AntColony {
            rho: f64::NAN,
            alpha: -1.0,
            beta: f64::INFINITY,
            ants: 0,
            iterations: 3,
            seed: 1,
        };
        let problem = random_problem(15, 2);
        check(&problem, &solve_heuristic(&problem, &strange));
        let huge_beta = AntColony {
            beta: 1000.0,
            ..AntColony::default()
        };
        check(&problem, &solve_heuristic(&problem, &huge_beta));
        let none = AntColony {
            iterations: 0,
            ..AntColony::default()
        };
        check(&problem, &solve_heuristic(&problem, &none));
        // Too many blocks for the exact table: solve_exact falls back rather than allocating.
        let big = random_problem(25, 4);
        let sequence = solve_exact(&big);
        assert_eq!(sequence.method, SequenceMethod::AntColony);
        check(&big, &sequence);
        // Infinite connections are clamped and sums stay ordered.
        let mut problem = random_problem(4, 8);
        problem.connection.fill(f64::INFINITY);
        let sequence = solve(&problem, 0);
        check(&problem, &sequence);
        assert!(sequence.cost.is_finite());
    }

    #[test]
    fn deterministic() {
        let problem = random_problem(20, 6);
        assert_eq!(solve(&problem, 42), solve(&problem, 42));
        assert_eq!(
            random_restarts(&problem, 5, 1),
            random_restarts(&problem, 5, 1)
        );
        assert_eq!(random_problem(7, 3), random_problem(7, 3));
        let small = random_problem(9, 6);
        assert_eq!(solve(&small, 1), solve(&small, 2));
    }

    #[test]
    fn random_problem_parity() {
        let problem = random_problem(10, 12);
        assert_eq!(problem.points, 40);
        assert_eq!(problem.connection.len(), 1600);
        for (k, ways) in problem.ways.iter().enumerate() {
            assert_eq!(ways.len(), 4);
            for (e, way) in ways.iter().enumerate() {
                assert_eq!(way.entry, 4 * k + e);
                // The exit is at the other swath, first <-> last.
                assert_eq!((way.exit - 4 * k) / 2, 1 - e / 2);
                assert!(way.cost > 0.0);
            }
        }
        assert_eq!(SequenceMethod::Exact.as_str(), "exact");
        assert_eq!(SequenceMethod::AntColony.as_str(), "ant-colony");
    }
}
