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

use crate::geometry::PlanarHypot;
use crate::rng::SplitMix64 as Rng;
use crate::sort::SharedSort;
use std::ops::Range;

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

/// Settings of the ant colony.
///
/// The defaults are Zhou et al.'s `rho = 0.5, alpha = 1, beta = 5`; they use as many ants as
/// nodes (ways) and 200 iterations, here the ants are capped and the iterations fewer, since the
/// local search that follows does the fine work and the planner runs on every edit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AntColony {
    /// Evaporation rate of the pheromone per iteration, in `[0, 1]`.
    pub rho: f64,
    /// Weight of the pheromone in an ant's choice.
    pub alpha: f64,
    /// Weight of the heuristic value (`1 / cost` of the move) in an ant's choice.
    pub beta: f64,
    /// The most ants per iteration: the colony has as many ants as ways (nodes), as in the
    /// paper, but no more than this.
    pub ants: usize,
    /// Number of iterations (0: no colony, the local search starts from a nearest-next order).
    pub iterations: usize,
    /// Seed of the random choices.
    pub seed: u64,
}

impl Default for AntColony {
    fn default() -> Self {
        AntColony {
            rho: 0.5,
            alpha: 1.0,
            beta: 5.0,
            ants: 8,
            iterations: 20,
            seed: 0,
        }
    }
}

/// Every cost is clamped to `-LARGE_COST..=LARGE_COST`, and a missing one costs this.
pub const LARGE_COST: f64 = 1e12;

/// [`solve`] is exact up to this many blocks (with ways).
pub const EXACT_MAX_BLOCKS: usize = 12;

/// The most steps (`2^blocks x ways^2`, about twice the additions its table takes) for which
/// [`solve`] takes the exact answer rather than the heuristic: 11 blocks of four ways each
/// (`2048 x 44^2`, 4 million) are exact, 12 (`4096 x 48^2`, 9.4 million) are not. In
/// WebAssembly those 12 took about 10 ms exactly, 25 with eight ways (blocks that may also end
/// by driving back along their last swath), the ant colony under 2; on the corpus the colony
/// found the exact cost wherever the limit changed the solver.
pub const EXACT_MAX_WORK: usize = 5_000_000;

/// [`exhaustive`] enumerates every permutation up to this many blocks.
pub const EXHAUSTIVE_MAX_BLOCKS: usize = 9;

/// The most dynamic-programming states (`2^blocks x ways`) [`solve_exact`] allocates: 32 MB.
const EXACT_MAX_STATES: usize = 1 << 22;

/// The most ways for which the (way x way) transition matrix is kept (8 MB) and the colony
/// runs; above it costs are looked up as needed and the search starts nearest-next.
const DENSE_MAX_NODES: usize = 1024;

/// How many cheapest moves out of and into each block the local search tries (its neighbours).
const NEAR: usize = 8;

/// The most entries of the block-pair matrices kept (8 MB); above it costs are looked up.
const PAIRS_MAX: usize = 1 << 20;

/// The longest run of blocks or-opt moves.
const OR_OPT_MAX_RUN: usize = 3;

/// A safety bound on the passes of the local search (each pass that continues improves).
const MAX_PASSES: usize = 10_000;

/// The most work one local search does, in additions of layer steps: a step carries the best
/// cost per way of a partial order on by one block, `widest x widest` additions (see
/// `Compiled::step`, four times that where the costs are looked up rather than kept); a move
/// tried costs a step per block it re-walks, a move taken one per block of the order. At the
/// budget the search stops with the best order so far.
///
/// On the corpus a search takes at most 5.5 million (85,000 steps of eight ways a block, 6 ms
/// natively); at 50 million a search takes about 60 to 80 ms natively, so that the four searches
/// of a problem stay within a third of a second whatever its size.
pub const LOCAL_SEARCH_WORK: usize = 50_000_000;

fn clamp_cost(cost: f64) -> f64 {
    if cost.is_nan() {
        LARGE_COST
    } else {
        cost.clamp(-LARGE_COST, LARGE_COST)
    }
}

/// `candidate` is better than `current` by more than rounding.
fn improves(candidate: f64, current: f64) -> bool {
    candidate < current - (1e-9 + 1e-10 * current.abs())
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
    /// entry, each way's cost, each connection from an exit to the next entry, and from the last
    /// exit to the finish. Pairs that name no way are skipped; an empty order costs 0.
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
        total
    }
}

/// The problem as the solvers see it: the blocks with ways numbered `0..blocks`, their ways
/// flattened into nodes, and the way cost folded into the cost of arriving at a node.
struct Compiled<'p> {
    problem: &'p SequenceProblem,
    /// The problem's index of each block with ways.
    blocks: Vec<usize>,
    /// The nodes of block `k` are `offset[k]..offset[k + 1]`, in the order of its ways.
    offset: Vec<usize>,
    entry: Vec<usize>,
    exit: Vec<usize>,
    way_cost: Vec<f64>,
    /// From the start to the node's entry, plus its way cost.
    start: Vec<f64>,
    /// From the node's exit to the finish.
    finish: Vec<f64>,
    /// `nodes x nodes`: connection from one node's exit to the other's entry, plus the other's
    /// way cost; empty when not dense.
    transition: Vec<f64>,
    dense: bool,
    /// The most ways of a block.
    widest: usize,
    /// `blocks x widest`: the start layer of each block, its `start` padded with infinity.
    start_layer: Vec<f64>,
    /// `blocks x widest`: the finish layer of each block, its `finish` padded with infinity.
    finish_layer: Vec<f64>,
    /// `blocks x blocks` matrices of `widest x widest` (see `pair`), when dense and not too big.
    pairs: Vec<f64>,
    /// `near[a * blocks + b]`: going on from block `a` to block `b` is among the cheapest
    /// moves out of `a` or into `b`; empty when every pair counts as near.
    near: Vec<bool>,
}

impl<'p> Compiled<'p> {
    fn new(problem: &'p SequenceProblem, dense: bool) -> Self {
        let mut blocks = Vec::new();
        let mut offset = vec![0];
        let mut entry = Vec::new();
        let mut exit = Vec::new();
        let mut way_cost = Vec::new();
        let mut widest = 0;
        for (block, ways) in problem.ways.iter().enumerate() {
            if ways.is_empty() {
                continue;
            }
            blocks.push(block);
            for way in ways {
                entry.push(way.entry);
                exit.push(way.exit);
                way_cost.push(clamp_cost(way.cost));
            }
            offset.push(entry.len());
            widest = widest.max(ways.len());
        }
        let nodes = entry.len();
        let start = (0..nodes)
            .map(|m| problem.start_cost(entry[m]) + way_cost[m])
            .collect();
        let finish = exit.iter().map(|&e| problem.finish_cost(e)).collect();
        let mut compiled = Compiled {
            problem,
            blocks,
            offset,
            entry,
            exit,
            way_cost,
            start,
            finish,
            transition: Vec::new(),
            dense: false,
            widest,
            start_layer: Vec::new(),
            finish_layer: Vec::new(),
            pairs: Vec::new(),
            near: Vec::new(),
        };
        let count = compiled.block_count();
        let mut start_layer = vec![f64::INFINITY; count * widest];
        let mut finish_layer = vec![f64::INFINITY; count * widest];
        for k in 0..count {
            for (v, m) in compiled.ways(k).enumerate() {
                start_layer[k * widest + v] = compiled.start[m];
                finish_layer[k * widest + v] = compiled.finish[m];
            }
        }
        compiled.start_layer = start_layer;
        compiled.finish_layer = finish_layer;
        if dense && nodes <= DENSE_MAX_NODES {
            let mut transition = Vec::with_capacity(nodes * nodes);
            for from in 0..nodes {
                for to in 0..nodes {
                    transition.push(compiled.lookup(from, to));
                }
            }
            compiled.transition = transition;
            compiled.dense = true;
            let size = count.saturating_mul(count).saturating_mul(widest * widest);
            if size <= PAIRS_MAX {
                let mut pairs = vec![f64::INFINITY; size];
                for a in 0..count {
                    for b in 0..count {
                        let base = (a * count + b) * widest * widest;
                        for (v, from) in compiled.ways(a).enumerate() {
                            for (w, to) in compiled.ways(b).enumerate() {
                                pairs[base + v * widest + w] = compiled.transition(from, to);
                            }
                        }
                    }
                }
                compiled.pairs = pairs;
            }
            compiled.near = compiled.neighbours();
        }
        compiled
    }

    /// The near pairs of blocks (see `near`), or none when every pair is near anyway.
    fn neighbours(&self) -> Vec<bool> {
        let blocks = self.block_count();
        if blocks <= NEAR + 1 {
            return Vec::new();
        }
        let cheapest: Vec<f64> = (0..blocks)
            .map(|k| {
                self.ways(k)
                    .map(|m| self.way_cost[m])
                    .fold(f64::INFINITY, f64::min)
            })
            .collect();
        // gap[a * blocks + b]: the cheapest avoidable cost of going on from block a to block b.
        let mut gap = vec![f64::INFINITY; blocks * blocks];
        for a in 0..blocks {
            for b in (0..blocks).filter(|&b| b != a) {
                let mut least = f64::INFINITY;
                for from in self.ways(a) {
                    for to in self.ways(b) {
                        least = least.min(self.transition(from, to));
                    }
                }
                gap[a * blocks + b] = least - cheapest[b];
            }
        }
        let mut near = vec![false; blocks * blocks];
        let mut others: Vec<usize> = Vec::with_capacity(blocks);
        for a in 0..blocks {
            for outgoing in [true, false] {
                let key = |b: usize| {
                    if outgoing {
                        gap[a * blocks + b]
                    } else {
                        gap[b * blocks + a]
                    }
                };
                others.clear();
                others.extend((0..blocks).filter(|&b| b != a));
                others.shared_sort_by(|&x, &y| key(x).total_cmp(&key(y)).then(x.cmp(&y)));
                for &b in others.iter().take(NEAR) {
                    if outgoing {
                        near[a * blocks + b] = true;
                    } else {
                        near[b * blocks + a] = true;
                    }
                }
            }
        }
        near
    }

    /// Going on from block `a` to block `b` is worth trying in the local search.
    fn is_near(&self, a: usize, b: usize) -> bool {
        self.near.is_empty() || self.near.get(a * self.block_count() + b) == Some(&true)
    }

    fn nodes(&self) -> usize {
        self.entry.len()
    }

    fn block_count(&self) -> usize {
        self.blocks.len()
    }

    fn ways(&self, block: usize) -> Range<usize> {
        self.offset[block]..self.offset[block + 1]
    }

    fn lookup(&self, from: usize, to: usize) -> f64 {
        self.problem
            .connection_cost(self.exit[from], self.entry[to])
            + self.way_cost[to]
    }

    /// The cost of going on from node `from` to node `to`, including `to`'s way cost.
    #[inline]
    fn transition(&self, from: usize, to: usize) -> f64 {
        if self.dense {
            self.transition[from * self.nodes() + to]
        } else {
            self.lookup(from, to)
        }
    }

    /// The `widest x widest` matrix of going on from block `a` to block `b`, `[v * widest + w]`
    /// from way `v` of `a` to way `w` of `b` (infinite in the padding), when kept.
    #[inline]
    fn pair(&self, a: usize, b: usize) -> Option<&[f64]> {
        let size = self.widest * self.widest;
        let base = (a * self.block_count() + b) * size;
        self.pairs.get(base..base + size)
    }

    /// One entry of the pair matrix of `a` to `b`, looked up.
    fn pair_entry(&self, a: usize, b: usize, v: usize, w: usize) -> f64 {
        let (from, to) = (self.ways(a), self.ways(b));
        if v < from.len() && w < to.len() {
            self.transition(from.start + v, to.start + w)
        } else {
            f64::INFINITY
        }
    }

    /// `out`: the layer of starting with block `b`, the cost of each of its ways.
    fn enter(&self, b: usize, out: &mut [f64]) {
        let w = self.widest;
        out[..w].copy_from_slice(&self.start_layer[b * w..(b + 1) * w]);
    }

    /// `out`: the layer of finishing with block `b`, the cost from each of its ways.
    fn last(&self, b: usize, out: &mut [f64]) {
        let w = self.widest;
        out[..w].copy_from_slice(&self.finish_layer[b * w..(b + 1) * w]);
    }

    /// `out[w]`: the best cost of standing at way `w` of block `b` after block `a`, given `cur[v]`
    /// the best cost of standing at way `v` of block `a`.
    fn step(&self, a: usize, cur: &[f64], b: usize, out: &mut [f64]) {
        match self.pair(a, b) {
            Some(m) => with_width(self.widest, |w| step_kernel(w, m, cur, out)),
            None => {
                for (t, o) in out.iter_mut().enumerate().take(self.widest) {
                    *o = (0..self.widest)
                        .map(|v| cur[v] + self.pair_entry(a, b, v, t))
                        .fold(f64::INFINITY, least);
                }
            }
        }
    }

    /// `out[v]`: the best cost from way `v` of block `a` to the finish through block `b`, given
    /// `after[w]` the best cost from way `w` of block `b` to the finish (excluding what leads in).
    fn pull(&self, a: usize, b: usize, after: &[f64], out: &mut [f64]) {
        match self.pair(a, b) {
            Some(m) => with_width(self.widest, |w| pull_kernel(w, m, after, out)),
            None => {
                for (v, o) in out.iter_mut().enumerate().take(self.widest) {
                    *o = (0..self.widest)
                        .map(|t| self.pair_entry(a, b, v, t) + after[t])
                        .fold(f64::INFINITY, least);
                }
            }
        }
    }

    /// The best total of a prefix standing at block `a` (`cur`) and a suffix starting at block
    /// `b` (`after`).
    fn join(&self, a: usize, cur: &[f64], b: usize, after: &[f64]) -> f64 {
        match self.pair(a, b) {
            Some(m) => with_width(self.widest, |w| join_kernel(w, m, cur, after)),
            None => (0..self.widest)
                .flat_map(|v| (0..self.widest).map(move |t| (v, t)))
                .map(|(v, t)| cur[v] + self.pair_entry(a, b, v, t) + after[t])
                .fold(f64::INFINITY, least),
        }
    }

    /// The best total of a prefix standing at block `a` that finishes there.
    fn close(&self, a: usize, cur: &[f64]) -> f64 {
        let w = self.widest;
        let finish = &self.finish_layer[a * w..(a + 1) * w];
        cur.iter()
            .zip(finish)
            .map(|(&c, &f)| c + f)
            .fold(f64::INFINITY, least)
    }

    /// The best total of a suffix starting at block `b` that is the whole sequence.
    fn open(&self, b: usize, after: &[f64]) -> f64 {
        let w = self.widest;
        let start = &self.start_layer[b * w..(b + 1) * w];
        start
            .iter()
            .zip(after)
            .map(|(&s, &r)| s + r)
            .fold(f64::INFINITY, least)
    }

    /// The best way (index within its block) of each block of `order` and the total cost:
    /// Viterbi through the layers of ways.
    fn viterbi(&self, order: &[usize]) -> (Vec<usize>, f64) {
        let Some(&first) = order.first() else {
            return (Vec::new(), 0.0);
        };
        let w = self.widest;
        let mut cost = vec![f64::INFINITY; order.len() * w];
        let mut back = vec![0usize; order.len() * w];
        self.enter(first, &mut cost[..w]);
        for (i, pair) in order.windows(2).enumerate() {
            let (a, b) = (pair[0], pair[1]);
            let matrix = self.pair(a, b);
            let (done, next) = cost.split_at_mut((i + 1) * w);
            let cur = &done[i * w..];
            for t in 0..w {
                let mut best = f64::INFINITY;
                let mut arg = 0;
                for (v, &base) in cur.iter().enumerate() {
                    let step = match matrix {
                        Some(m) => m[v * w + t],
                        None => self.pair_entry(a, b, v, t),
                    };
                    if base + step < best {
                        best = base + step;
                        arg = v;
                    }
                }
                next[t] = best;
                back[(i + 1) * w + t] = arg;
            }
        }
        let end = order.len() - 1;
        let finish = &self.finish_layer[order[end] * w..(order[end] + 1) * w];
        let mut total = f64::INFINITY;
        let mut way = 0;
        for (v, (&base, &f)) in cost[end * w..].iter().zip(finish).enumerate() {
            if base + f < total {
                total = base + f;
                way = v;
            }
        }
        let mut ways = vec![0; order.len()];
        for i in (0..order.len()).rev() {
            ways[i] = way;
            way = back[i * w + way];
        }
        (ways, total)
    }

    /// The sequence of the given order (of compiled blocks), with its best ways.
    fn sequence(&self, order: &[usize], method: SequenceMethod) -> Sequence {
        let (ways, cost) = self.viterbi(order);
        Sequence {
            order: order
                .iter()
                .zip(ways)
                .map(|(&k, w)| (self.blocks[k], w))
                .collect(),
            cost,
            method,
        }
    }

    /// Nearest-next: the cheapest start, then always the cheapest way of a block not yet worked.
    fn nearest_next(&self) -> Vec<usize> {
        let blocks = self.block_count();
        let Some(mut at) =
            (0..self.nodes()).min_by(|&a, &b| self.start[a].total_cmp(&self.start[b]))
        else {
            return Vec::new();
        };
        let block_of = |node: usize| self.offset.partition_point(|&o| o <= node) - 1;
        let mut done = vec![false; blocks];
        let mut order = Vec::with_capacity(blocks);
        loop {
            let k = block_of(at);
            done[k] = true;
            order.push(k);
            let mut best: Option<(f64, usize)> = None;
            for b in (0..blocks).filter(|&b| !done[b]) {
                for m in self.ways(b) {
                    let c = self.transition(at, m);
                    if best.is_none_or(|(bc, _)| c < bc) {
                        best = Some((c, m));
                    }
                }
            }
            match best {
                Some((_, m)) => at = m,
                None => return order,
            }
        }
    }
}

/// The lesser of two costs.
#[inline(always)]
fn least(a: f64, b: f64) -> f64 {
    if b < a {
        b
    } else {
        a
    }
}

/// Calls `f` with `width`, as a constant for the common widths so that it inlines unrolled.
#[inline(always)]
fn with_width<R>(width: usize, f: impl FnOnce(usize) -> R) -> R {
    match width {
        1 => f(1),
        2 => f(2),
        3 => f(3),
        4 => f(4),
        _ => f(width),
    }
}

/// `out[t] = min over v of cur[v] + m[v * w + t]`.
#[inline(always)]
fn step_kernel(w: usize, m: &[f64], cur: &[f64], out: &mut [f64]) {
    let (m, cur, out) = (&m[..w * w], &cur[..w], &mut out[..w]);
    out.copy_from_slice(&m[..w]);
    for o in out.iter_mut() {
        *o += cur[0];
    }
    for v in 1..w {
        let row = &m[v * w..(v + 1) * w];
        for (o, &t) in out.iter_mut().zip(row) {
            *o = least(*o, cur[v] + t);
        }
    }
}

/// `out[v] = min over t of m[v * w + t] + after[t]`.
#[inline(always)]
fn pull_kernel(w: usize, m: &[f64], after: &[f64], out: &mut [f64]) {
    let (m, after, out) = (&m[..w * w], &after[..w], &mut out[..w]);
    for (o, row) in out.iter_mut().zip(m.chunks_exact(w)) {
        *o = row
            .iter()
            .zip(after)
            .map(|(&t, &r)| t + r)
            .fold(f64::INFINITY, least);
    }
}

/// `min over v, t of cur[v] + m[v * w + t] + after[t]`.
#[inline(always)]
fn join_kernel(w: usize, m: &[f64], cur: &[f64], after: &[f64]) -> f64 {
    let (m, cur, after) = (&m[..w * w], &cur[..w], &after[..w]);
    let mut best = f64::INFINITY;
    for (&c, row) in cur.iter().zip(m.chunks_exact(w)) {
        for (&t, &r) in row.iter().zip(after) {
            best = least(best, c + t + r);
        }
    }
    best
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

/// Whether the exact table fits: few enough blocks, and ways (nodes) for the transition matrix.
fn exact_fits(blocks: usize, nodes: usize) -> bool {
    blocks <= EXACT_MAX_BLOCKS
        && nodes <= DENSE_MAX_NODES
        && (1usize << blocks).saturating_mul(nodes) <= EXACT_MAX_STATES
}

/// Whether [`solve`] takes the exact answer: it fits, and its table costs at most
/// [`EXACT_MAX_WORK`] steps.
fn exact_pays(blocks: usize, nodes: usize) -> bool {
    exact_fits(blocks, nodes)
        && (1usize << blocks)
            .saturating_mul(nodes)
            .saturating_mul(nodes)
            <= EXACT_MAX_WORK
}

/// Dynamic programming over subsets of blocks and the way (hence exit point) of the last block
/// (Held-Karp): optimal.
///
/// With more than [`EXACT_MAX_BLOCKS`] blocks, more than 1024 ways in all, or so many that the
/// table would pass 32 MB, it returns [`solve_heuristic`] with default settings instead (method
/// [`SequenceMethod::AntColony`]).
pub fn solve_exact(problem: &SequenceProblem) -> Sequence {
    let c = Compiled::new(problem, true);
    let blocks = c.block_count();
    if blocks == 0 {
        return empty_sequence(SequenceMethod::Exact);
    }
    let nodes = c.nodes();
    if !exact_fits(blocks, nodes) {
        return solve_heuristic(problem, &AntColony::default());
    }
    let full = (1usize << blocks) - 1;
    // Rows padded to a multiple of 4 for the four-lane minimum below.
    let width = nodes.div_ceil(4) * 4;
    // into[to * width + from]: the transition from node `from` to node `to`.
    let mut into = vec![0.0; nodes * width];
    for (to, row) in into.chunks_exact_mut(width).enumerate() {
        for (from, t) in row.iter_mut().take(nodes).enumerate() {
            *t = c.transition(from, to);
        }
    }
    // best[set * width + node]: the least cost of working the blocks of `set`, ending with
    // `node`, a way of a block in `set` (infinite for the others).
    let mut best = vec![f64::INFINITY; (full + 1) * width];
    for set in 1..=full {
        let (done, rest) = best.split_at_mut(set * width);
        let row = &mut rest[..width];
        let mut inside = set;
        while inside != 0 {
            let b = inside.trailing_zeros() as usize;
            inside &= inside - 1;
            let before = set & !(1 << b);
            for to in c.ways(b) {
                row[to] = if before == 0 {
                    c.start[to]
                } else {
                    let previous = &done[before * width..(before + 1) * width];
                    let arriving = &into[to * width..(to + 1) * width];
                    // Only the ways of blocks in `before` are finite there.
                    let mut least = f64::INFINITY;
                    let mut blocks_before = before;
                    while blocks_before != 0 {
                        let k = blocks_before.trailing_zeros() as usize;
                        blocks_before &= blocks_before - 1;
                        let ways = c.ways(k);
                        // A comparison, not f64::min: in wasm that is a call (to keep NaNs).
                        let cost = min_plus(&previous[ways.clone()], &arriving[ways]);
                        if cost < least {
                            least = cost;
                        }
                    }
                    least
                };
            }
        }
    }
    // The best last node, then back through the sets.
    let row = full * width;
    let Some(mut at) = (0..nodes)
        .min_by(|&a, &b| (best[row + a] + c.finish[a]).total_cmp(&(best[row + b] + c.finish[b])))
    else {
        return empty_sequence(SequenceMethod::Exact);
    };
    let block_of = |node: usize| c.offset.partition_point(|&o| o <= node) - 1;
    let mut set = full;
    let mut order = Vec::with_capacity(blocks);
    loop {
        let k = block_of(at);
        order.push(k);
        let before = set & !(1 << k);
        if before == 0 {
            break;
        }
        let previous = &best[before * width..(before + 1) * width];
        let arriving = &into[at * width..(at + 1) * width];
        let mut from = None;
        let mut least = f64::INFINITY;
        for (node, (&p, &t)) in previous.iter().zip(arriving).take(nodes).enumerate() {
            let cost = p + t;
            if cost < least {
                least = cost;
                from = Some(node);
            }
        }
        match from {
            Some(node) => {
                set = before;
                at = node;
            }
            None => break,
        }
    }
    order.reverse();
    if order.len() != blocks {
        // Cannot happen (every set is reachable); keep the answer a permutation all the same.
        return solve_heuristic(problem, &AntColony::default());
    }
    c.sequence(&order, SequenceMethod::Exact)
}

/// `min over i of a[i] + b[i]` (equal lengths), in four lanes.
fn min_plus(a: &[f64], b: &[f64]) -> f64 {
    let mut lanes = [f64::INFINITY; 4];
    let (a4, b4) = (a.chunks_exact(4), b.chunks_exact(4));
    for (&x, &y) in a4.remainder().iter().zip(b4.remainder()) {
        let cost = x + y;
        lanes[0] = if cost < lanes[0] { cost } else { lanes[0] };
    }
    for (x, y) in a4.zip(b4) {
        for ((lane, &x), &y) in lanes.iter_mut().zip(x).zip(y) {
            let cost = x + y;
            *lane = if cost < *lane { cost } else { *lane };
        }
    }
    let [l0, l1, l2, l3] = lanes;
    let low = if l1 < l0 { l1 } else { l0 };
    let high = if l3 < l2 { l3 } else { l2 };
    if high < low {
        high
    } else {
        low
    }
}

/// Ant colony optimisation over (block, way) nodes (Zhou et al.), then 2-opt (segment reversal)
/// and or-opt (move one block / a short run) local search on the block order, each order
/// evaluated with its best ways by [`best_ways`].
///
/// The colony is Ant System with an elitist ant: each ant starts at a node drawn by its start
/// cost and goes on to a way of a block it has not worked yet, drawn in proportion to
/// `pheromone^alpha x (scale / (avoidable cost + small))^beta`, the avoidable cost being the
/// connection plus how much dearer the way is than its block's cheapest. After each iteration
/// the pheromone evaporates by `rho`, every ant lays some on its tour, more the nearer it is to
/// the best so far, and the best tour so far lays a full measure. An ant looks first at the 16
/// cheapest ways to go on to and at the rest only when those are all worked. The local search
/// then improves the four best distinct orders the colony found, and the best result is kept.
/// With more than 1024 ways, or no iterations, it starts from a nearest-next order instead.
pub fn solve_heuristic(problem: &SequenceProblem, settings: &AntColony) -> Sequence {
    let c = Compiled::new(problem, true);
    if c.block_count() == 0 {
        return empty_sequence(SequenceMethod::AntColony);
    }
    let mut rng = Rng::new(settings.seed);
    let mut starts = ant_colony(&c, settings, &mut rng);
    if starts.is_empty() {
        starts.push(c.nearest_next());
    }
    let mut best: Option<LocalSearch> = None;
    for start in starts {
        let mut search = LocalSearch::new(&c, start);
        search.run();
        if best.as_ref().is_none_or(|b| search.cost < b.cost) {
            best = Some(search);
        }
    }
    let order = best.map(|b| b.order).unwrap_or_default();
    c.sequence(&order, SequenceMethod::AntColony)
}

/// Given a block order, the best way of each block and the total cost: a shortest path through
/// the layered graph of ways (Viterbi), `O(blocks x ways^2)`.
///
/// The ways are indices into `ways[block]`, one for each entry of `blocks`. A block that is out
/// of range or has no ways is skipped: it adds nothing to the cost and its entry is 0. A block
/// may appear more than once. The cost is that of [`SequenceProblem::cost`].
pub fn best_ways(problem: &SequenceProblem, blocks: &[usize]) -> (Vec<usize>, f64) {
    let c = Compiled::new(problem, false);
    let mut compiled_index = vec![usize::MAX; problem.ways.len()];
    for (k, &block) in c.blocks.iter().enumerate() {
        compiled_index[block] = k;
    }
    let kept: Vec<usize> = blocks
        .iter()
        .filter_map(|&b| compiled_index.get(b).copied().filter(|&k| k != usize::MAX))
        .collect();
    let (ways, cost) = c.viterbi(&kept);
    let mut ways = ways.into_iter();
    let all = blocks
        .iter()
        .map(|&b| match compiled_index.get(b) {
            Some(&k) if k != usize::MAX => ways.next().unwrap_or(0),
            _ => 0,
        })
        .collect();
    (all, cost)
}

/// Every permutation of the blocks with its best ways: the exact answer for checking, up to
/// [`EXHAUSTIVE_MAX_BLOCKS`] (9) blocks, in time growing as `blocks! x ways^2`. With more blocks
/// it returns the result of [`solve_exact`] instead.
pub fn exhaustive(problem: &SequenceProblem) -> Sequence {
    let c = Compiled::new(problem, true);
    let blocks = c.block_count();
    if blocks == 0 {
        return empty_sequence(SequenceMethod::Exact);
    }
    if blocks > EXHAUSTIVE_MAX_BLOCKS {
        return solve_exact(problem);
    }
    let mut search = Permutations {
        c: &c,
        layers: vec![f64::INFINITY; blocks * c.widest],
        used: vec![false; blocks],
        path: Vec::with_capacity(blocks),
        best_cost: f64::INFINITY,
        best: Vec::new(),
    };
    search.extend(None);
    let best = search.best;
    c.sequence(&best, SequenceMethod::Exact)
}

/// Depth-first enumeration of block orders, each prefix carrying its best cost per way.
struct Permutations<'c, 'p> {
    c: &'c Compiled<'p>,
    layers: Vec<f64>,
    used: Vec<bool>,
    path: Vec<usize>,
    best_cost: f64,
    best: Vec<usize>,
}

impl Permutations<'_, '_> {
    fn extend(&mut self, last: Option<usize>) {
        let w = self.c.widest;
        let depth = self.path.len();
        let blocks = self.used.len();
        if depth == blocks {
            if let Some(a) = last {
                let cost = self.c.close(a, &self.layers[(depth - 1) * w..depth * w]);
                if cost < self.best_cost {
                    self.best_cost = cost;
                    self.best.clone_from(&self.path);
                }
            }
            return;
        }
        for k in 0..blocks {
            if self.used[k] {
                continue;
            }
            let (before, after) = self.layers.split_at_mut(depth * w);
            match last {
                None => self.c.enter(k, &mut after[..w]),
                Some(a) => self
                    .c
                    .step(a, &before[(depth - 1) * w..], k, &mut after[..w]),
            }
            self.used[k] = true;
            self.path.push(k);
            self.extend(Some(k));
            self.path.pop();
            self.used[k] = false;
        }
    }
}

/// The best of `restarts` local searches (2-opt + or-opt as in [`solve_heuristic`]) each from a
/// random block order: the yardstick the heuristic is measured against. At least one restart
/// is made; the method reported is [`SequenceMethod::AntColony`] (a heuristic).
pub fn random_restarts(problem: &SequenceProblem, restarts: usize, seed: u64) -> Sequence {
    let c = Compiled::new(problem, true);
    let blocks = c.block_count();
    if blocks == 0 {
        return empty_sequence(SequenceMethod::AntColony);
    }
    let mut rng = Rng::new(seed);
    let mut best: Option<(f64, Vec<usize>)> = None;
    for _ in 0..restarts.max(1) {
        let mut order: Vec<usize> = (0..blocks).collect();
        rng.shuffle(&mut order);
        let mut search = LocalSearch::new(&c, order);
        search.run();
        if best.as_ref().is_none_or(|(cost, _)| search.cost < *cost) {
            best = Some((search.cost, search.order));
        }
    }
    let order = best.map(|(_, order)| order).unwrap_or_default();
    c.sequence(&order, SequenceMethod::AntColony)
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
    }
}

/// How many of the colony's best distinct block orders the local search improves.
const POLISHED: usize = 4;

/// How many of the cheapest next ways an ant considers first (its candidate list).
const CANDIDATES: usize = 16;

/// The ant colony: the block orders of its best distinct tours (at most [`POLISHED`]),
/// cheapest first; none when it does not run.
fn ant_colony(c: &Compiled, settings: &AntColony, rng: &mut Rng) -> Vec<Vec<usize>> {
    // The best distinct block orders found, cheapest first.
    let mut pool: Vec<(f64, Vec<usize>)> = Vec::with_capacity(POLISHED + 1);
    let nodes = c.nodes();
    let blocks = c.block_count();
    if nodes == 0 || !c.dense || settings.iterations == 0 {
        return Vec::new();
    }
    let rho = if settings.rho.is_finite() {
        settings.rho.clamp(0.0, 1.0)
    } else {
        0.5
    };
    let alpha = if settings.alpha.is_finite() {
        settings.alpha.max(0.0)
    } else {
        1.0
    };
    let beta = if settings.beta.is_finite() {
        settings.beta.max(0.0)
    } else {
        5.0
    };
    let ants = settings.ants.clamp(1, nodes);
    let mut block_of = vec![0; nodes];
    let mut cheapest = vec![f64::INFINITY; blocks];
    for (k, least) in cheapest.iter_mut().enumerate() {
        for m in c.ways(k) {
            block_of[m] = k;
            *least = least.min(c.way_cost[m]);
        }
    }
    let unavoidable: f64 = cheapest.iter().sum();
    // The avoidable cost of each move: the connection and how much dearer the way is than its
    // block's cheapest (row `nodes` is the start). Then shifted to be non-negative.
    let mut avoidable = vec![f64::INFINITY; (nodes + 1) * nodes];
    let mut lowest = f64::INFINITY;
    let (mut sum, mut count) = (0.0, 0usize);
    for (from, row) in avoidable.chunks_exact_mut(nodes).enumerate() {
        for (to, d) in row.iter_mut().enumerate() {
            let base = if from == nodes {
                c.start[to]
            } else if block_of[from] == block_of[to] {
                continue;
            } else {
                c.transition(from, to)
            };
            *d = base - cheapest[block_of[to]];
            lowest = lowest.min(*d);
            if d.abs() < LARGE_COST / 10.0 {
                sum += d.abs();
                count += 1;
            }
        }
    }
    let lowest = if lowest.is_finite() { lowest } else { 0.0 };
    avoidable.iter_mut().for_each(|d| *d -= lowest);
    let scale = if count > 0 && sum > 0.0 {
        sum / count as f64
    } else {
        1.0
    };
    let small = 1e-3 * scale;
    // The heuristic value raised to beta (0 within a block: never a move).
    let integer_beta = (beta.fract() == 0.0 && beta <= 16.0).then_some(beta as i32);
    let visibility: Vec<f64> = avoidable
        .iter()
        .map(|&d| {
            let eta = scale / (d + small);
            match integer_beta {
                Some(b) => eta.powi(b),
                None => eta.powf(beta),
            }
        })
        .collect();
    // Each node's candidates: the ways of other blocks cheapest to go on to, cheapest first.
    let width = CANDIDATES.min(nodes);
    let mut candidates = Vec::with_capacity(nodes * width);
    let mut list: Vec<usize> = Vec::with_capacity(nodes);
    for from in 0..nodes {
        list.clear();
        list.extend((0..nodes).filter(|&to| block_of[to] != block_of[from]));
        let key = |&to: &usize| (avoidable[from * nodes + to], to);
        let by_key = |a: &usize, b: &usize| {
            let (ka, kb) = (key(a), key(b));
            ka.0.total_cmp(&kb.0).then(ka.1.cmp(&kb.1))
        };
        if list.len() > width {
            list.select_nth_unstable_by(width, by_key);
            list.truncate(width);
        }
        list.shared_sort_unstable_by(by_key);
        // Padded with `nodes` (no node) where there are fewer.
        candidates.extend(
            list.iter()
                .copied()
                .chain(std::iter::repeat(nodes))
                .take(width),
        );
    }
    let mut pheromone = vec![1.0; (nodes + 1) * nodes];
    let power = |tau: f64| if alpha == 1.0 { tau } else { tau.powf(alpha) };

    let mut best_cost = f64::INFINITY;
    let mut best_tour: Vec<usize> = Vec::new();
    let mut tours: Vec<(Vec<usize>, f64)> = Vec::with_capacity(ants);
    let mut done = vec![false; blocks];
    let mut weights: Vec<(usize, f64)> = Vec::with_capacity(nodes);
    for _ in 0..settings.iterations {
        tours.clear();
        for _ in 0..ants {
            done.fill(false);
            let mut tour = Vec::with_capacity(blocks);
            let mut at = nodes; // the start
            for _ in 0..blocks {
                let base = at * nodes;
                let weight = |to: usize| power(pheromone[base + to]) * visibility[base + to];
                // The candidate list first, then every way of the blocks not yet worked.
                weights.clear();
                if at < nodes {
                    let list = &candidates[at * width..(at + 1) * width];
                    weights.extend(
                        list.iter()
                            .filter(|&&to| to < nodes && !done[block_of[to]])
                            .map(|&to| (to, weight(to))),
                    );
                }
                let mut next = roulette(&weights, rng);
                if next.is_none() {
                    weights.clear();
                    weights.extend(
                        (0..nodes)
                            .filter(|&to| !done[block_of[to]])
                            .map(|to| (to, weight(to))),
                    );
                    next = roulette(&weights, rng).or_else(|| {
                        weights
                            .iter()
                            .map(|&(to, _)| to)
                            .min_by(|&a, &b| avoidable[base + a].total_cmp(&avoidable[base + b]))
                    });
                }
                let Some(to) = next else { break };
                done[block_of[to]] = true;
                tour.push(to);
                at = to;
            }
            let mut cost = 0.0;
            for (i, &node) in tour.iter().enumerate() {
                cost += if i == 0 {
                    c.start[node]
                } else {
                    c.transition(tour[i - 1], node)
                };
            }
            if let Some(&last) = tour.last() {
                cost += c.finish[last];
            }
            if tour.len() == blocks && cost < best_cost {
                best_cost = cost;
                best_tour.clone_from(&tour);
            }
            if tour.len() == blocks
                && (pool.len() < POLISHED || pool.last().is_some_and(|w| cost < w.0))
            {
                let order: Vec<usize> = tour.iter().map(|&m| block_of[m]).collect();
                if !pool.iter().any(|(_, o)| *o == order) {
                    let at = pool.partition_point(|(pc, _)| *pc <= cost);
                    pool.insert(at, (cost, order));
                    pool.truncate(POLISHED);
                }
            }
            tours.push((tour, cost));
        }
        // Evaporation, then each ant's deposit: a full measure at the best so far, half at twice
        // its avoidable cost; the best tour so far lays a full measure too (the elitist ant).
        let keep = 1.0 - rho;
        pheromone.iter_mut().for_each(|t| *t *= keep);
        let reference = (best_cost - unavoidable).abs().max(scale);
        let elitist = std::iter::once((&best_tour, best_cost));
        for (tour, cost) in tours.iter().map(|(t, c)| (t, *c)).chain(elitist) {
            let amount = reference / (reference + (cost - best_cost).max(0.0));
            let mut from = nodes;
            for &to in tour {
                pheromone[from * nodes + to] += amount;
                from = to;
            }
        }
    }
    pool.into_iter().map(|(_, o)| o).collect()
}

/// A draw in proportion to the weights; `None` when they do not make a distribution (none, all
/// zero, or overflowing).
fn roulette(weights: &[(usize, f64)], rng: &mut Rng) -> Option<usize> {
    let total: f64 = weights.iter().map(|&(_, w)| w).sum();
    if !(total.is_finite() && total > 0.0) {
        return None;
    }
    let mut left = rng.unit() * total;
    let mut last = None;
    for &(to, w) in weights {
        if w > 0.0 {
            last = Some(to);
            left -= w;
            if left < 0.0 {
                break;
            }
        }
    }
    last
}

/// 2-opt and or-opt on a block order, each order costed with its best ways, kept as prefix
/// (`forward`) and suffix (`backward`) layers so that a move is costed by its changed part only.
///
/// Moves are tried only where they make a near connection (see `Compiled::near`), first
/// improvement, pass after pass until one finds no improving move or the search has done
/// [`LOCAL_SEARCH_WORK`].
struct LocalSearch<'c, 'p> {
    c: &'c Compiled<'p>,
    order: Vec<usize>,
    /// `forward[i * widest + w]`: the best cost of `order[..=i]` ending with way `w` of
    /// `order[i]`.
    forward: Vec<f64>,
    /// `backward[i * widest + w]`: the best cost from way `w` of `order[i]` (its own cost not
    /// included) through `order[i + 1..]` to the finish.
    backward: Vec<f64>,
    cost: f64,
    /// Work done so far (see [`LOCAL_SEARCH_WORK`]), and the most it may do.
    work: usize,
    budget: usize,
    x: Vec<f64>,
    y: Vec<f64>,
    v: Vec<f64>,
    h: Vec<f64>,
    g: Vec<f64>,
}

impl<'c, 'p> LocalSearch<'c, 'p> {
    fn new(c: &'c Compiled<'p>, order: Vec<usize>) -> Self {
        let w = c.widest;
        let n = order.len();
        let mut search = LocalSearch {
            c,
            order,
            forward: vec![f64::INFINITY; n * w],
            backward: vec![f64::INFINITY; n * w],
            cost: 0.0,
            work: 0,
            budget: LOCAL_SEARCH_WORK,
            x: vec![0.0; w],
            y: vec![0.0; w],
            v: vec![0.0; w],
            h: vec![0.0; w],
            g: vec![0.0; w],
        };
        search.rebuild();
        search
    }

    fn rebuild(&mut self) {
        let c = self.c;
        let w = c.widest;
        let n = self.order.len();
        self.spend(2 * n);
        let Some(&first) = self.order.first() else {
            self.cost = 0.0;
            return;
        };
        c.enter(first, &mut self.forward[..w]);
        for i in 1..n {
            let (done, next) = self.forward.split_at_mut(i * w);
            c.step(
                self.order[i - 1],
                &done[(i - 1) * w..],
                self.order[i],
                &mut next[..w],
            );
        }
        c.last(self.order[n - 1], &mut self.backward[(n - 1) * w..]);
        for i in (0..n - 1).rev() {
            let (before, after) = self.backward.split_at_mut((i + 1) * w);
            c.pull(
                self.order[i],
                self.order[i + 1],
                &after[..w],
                &mut before[i * w..],
            );
        }
        self.cost = c.close(self.order[n - 1], &self.forward[(n - 1) * w..]);
    }

    /// Until no move improves, or the budget is spent.
    fn run(&mut self) {
        if self.order.len() < 2 {
            return;
        }
        for _ in 0..MAX_PASSES {
            let reversed = self.two_opt();
            let moved = self.or_opt();
            if !reversed && !moved || self.spent() {
                break;
            }
        }
    }

    /// Counts the work of `steps` layer steps about to be taken; whether the budget was spent
    /// before them.
    fn spend(&mut self, steps: usize) -> bool {
        let spent = self.spent();
        // A step whose pair matrix is not kept looks its costs up, some four times slower.
        let w = self.c.widest;
        let per_step = if self.c.pairs.is_empty() {
            4 * w * w
        } else {
            w * w
        };
        self.work = self.work.saturating_add(steps.saturating_mul(per_step));
        spent
    }

    fn spent(&self) -> bool {
        self.work >= self.budget
    }

    /// Every reversal of a run `order[i..=j]`, taken at once when it improves.
    fn two_opt(&mut self) -> bool {
        let n = self.order.len();
        let w = self.c.widest;
        let mut improved = false;
        for i in 0..n - 1 {
            for j in i + 1..n {
                // The new connections: order[i - 1] to order[j], order[i] to order[j + 1].
                let near = i == 0
                    || j + 1 == n
                    || self.c.is_near(self.order[i - 1], self.order[j])
                    || self.c.is_near(self.order[i], self.order[j + 1]);
                if !near {
                    continue;
                }
                if self.spend(j - i + 2) {
                    return improved;
                }
                let cost = {
                    let order = &self.order;
                    let last = prefix(self.c, order, &self.forward, i, &mut self.x);
                    let last = advance(
                        self.c,
                        last,
                        (i..=j).rev().map(|k| order[k]),
                        &mut self.x,
                        &mut self.y,
                    );
                    finish(self.c, order, &self.backward, w, last, &self.x, j + 1)
                };
                if improves(cost, self.cost) {
                    self.order[i..=j].reverse();
                    self.rebuild();
                    improved = true;
                }
            }
        }
        improved
    }

    /// Every move of a run of 1 to 3 blocks, either way round, to another place.
    fn or_opt(&mut self) -> bool {
        let n = self.order.len();
        let mut improved = false;
        for run in 1..=OR_OPT_MAX_RUN.min(n - 1) {
            for i in 0..=n - run {
                if self.spent() {
                    return improved;
                }
                if self.move_run(i, run) {
                    improved = true;
                }
            }
        }
        improved
    }

    /// Tries moving `order[i..i + run]` later and earlier; makes the first improving move.
    fn move_run(&mut self, i: usize, run: usize) -> bool {
        let c = self.c;
        let w = c.widest;
        let n = self.order.len();
        let orientations: &[bool] = if run == 1 { &[false] } else { &[false, true] };
        let (head, tail) = (self.order[i], self.order[i + run - 1]);
        let ends = |reversed: bool| if reversed { (tail, head) } else { (head, tail) };
        // Later: order[..i] ++ order[i + run..=p] ++ run ++ order[p + 1..].
        let mut at = prefix(c, &self.order, &self.forward, i, &mut self.v);
        for p in i + run..n {
            if self.spend(1) {
                return false;
            }
            at = advance(c, at, [self.order[p]].into_iter(), &mut self.v, &mut self.y);
            for &reversed in orientations {
                let (first, last) = ends(reversed);
                let near = p + 1 == n
                    || c.is_near(self.order[p], first)
                    || c.is_near(last, self.order[p + 1]);
                if !near {
                    continue;
                }
                if self.spend(run + 1) {
                    return false;
                }
                self.x.copy_from_slice(&self.v);
                let last = advance(
                    c,
                    at,
                    segment(&self.order, i, run, reversed),
                    &mut self.x,
                    &mut self.y,
                );
                let cost = finish(c, &self.order, &self.backward, w, last, &self.x, p + 1);
                if improves(cost, self.cost) {
                    let mut order = Vec::with_capacity(n);
                    order.extend_from_slice(&self.order[..i]);
                    order.extend_from_slice(&self.order[i + run..=p]);
                    order.extend(segment(&self.order, i, run, reversed));
                    order.extend_from_slice(&self.order[p + 1..]);
                    self.order = order;
                    self.rebuild();
                    return true;
                }
            }
        }
        // Earlier: order[..p] ++ run ++ order[p..i] ++ order[i + run..].
        for p in (0..i).rev() {
            if self.spend(1) {
                return false;
            }
            // h: from each way of order[p] through order[p + 1..i] and order[i + run..].
            if p + 1 == i {
                if i + run < n {
                    let after = &self.backward[(i + run) * w..(i + run + 1) * w];
                    c.pull(self.order[p], self.order[i + run], after, &mut self.h);
                } else {
                    c.last(self.order[p], &mut self.h);
                }
            } else {
                c.pull(self.order[p], self.order[p + 1], &self.h, &mut self.g);
                std::mem::swap(&mut self.h, &mut self.g);
            }
            for &reversed in orientations {
                let (first, last) = ends(reversed);
                let near =
                    p == 0 || c.is_near(self.order[p - 1], first) || c.is_near(last, self.order[p]);
                if !near {
                    continue;
                }
                if self.spend(run + 1) {
                    return false;
                }
                let start = prefix(c, &self.order, &self.forward, p, &mut self.x);
                let last = advance(
                    c,
                    start,
                    segment(&self.order, i, run, reversed),
                    &mut self.x,
                    &mut self.y,
                );
                let Some(a) = last else { continue };
                let cost = c.join(a, &self.x, self.order[p], &self.h);
                if improves(cost, self.cost) {
                    let mut order = Vec::with_capacity(n);
                    order.extend_from_slice(&self.order[..p]);
                    order.extend(segment(&self.order, i, run, reversed));
                    order.extend_from_slice(&self.order[p..i]);
                    order.extend_from_slice(&self.order[i + run..]);
                    self.order = order;
                    self.rebuild();
                    return true;
                }
            }
        }
        false
    }
}

/// The blocks of the run `order[i..i + run]`, in order or reversed.
fn segment(
    order: &[usize],
    i: usize,
    run: usize,
    reversed: bool,
) -> impl Iterator<Item = usize> + '_ {
    let blocks = &order[i..i + run];
    (0..run).map(move |t| {
        if reversed {
            blocks[run - 1 - t]
        } else {
            blocks[t]
        }
    })
}

/// Loads the layer of `order[..p]` (its last block's ways) into `x`; the block, if any.
fn prefix(
    c: &Compiled,
    order: &[usize],
    forward: &[f64],
    p: usize,
    x: &mut [f64],
) -> Option<usize> {
    if p == 0 {
        return None;
    }
    let w = c.widest;
    x.copy_from_slice(&forward[(p - 1) * w..p * w]);
    Some(order[p - 1])
}

/// Extends the layer in `x` (standing at block `last`, or at the start) through `blocks`.
fn advance(
    c: &Compiled,
    mut last: Option<usize>,
    blocks: impl Iterator<Item = usize>,
    x: &mut Vec<f64>,
    y: &mut Vec<f64>,
) -> Option<usize> {
    for b in blocks {
        match last {
            None => c.enter(b, x),
            Some(a) => {
                c.step(a, x, b, y);
                std::mem::swap(x, y);
            }
        }
        last = Some(b);
    }
    last
}

/// The total of a layer `x` standing at `last` followed by `order[s..]`.
fn finish(
    c: &Compiled,
    order: &[usize],
    backward: &[f64],
    w: usize,
    last: Option<usize>,
    x: &[f64],
    s: usize,
) -> f64 {
    let after = backward.get(s * w..(s + 1) * w);
    match (last, order.get(s), after) {
        (Some(a), Some(&b), Some(after)) => c.join(a, x, b, after),
        (Some(a), _, _) => c.close(a, x),
        (None, Some(&b), Some(after)) => c.open(b, after),
        (None, _, _) => 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_while_the_table_is_cheap() {
        assert!(exact_pays(11, 44), "11 blocks of four ways: exact");
        assert!(
            !exact_pays(12, 48),
            "12 blocks of four ways: the ant colony"
        );
        assert!(exact_pays(12, 12), "12 blocks of one way: exact");
        assert!(!exact_pays(EXACT_MAX_BLOCKS + 1, EXACT_MAX_BLOCKS + 1));
    }

    fn relative_gap(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs().max(1.0)
    }

    /// A problem with irregular ways: 0 to 4 ways per block at random points, random way costs,
    /// an asymmetric random connection matrix with some penalties, random start and finish costs.
    fn irregular_problem(blocks: usize, seed: u64) -> SequenceProblem {
        let mut rng = Rng::new(seed);
        let points = 3 * blocks + 1;
        let ways = (0..blocks)
            .map(|_| {
                let count = if rng.below(6) == 0 {
                    0
                } else {
                    1 + rng.below(4)
                };
                (0..count)
                    .map(|_| Way {
                        entry: rng.below(points),
                        exit: rng.below(points),
                        cost: 100.0 * rng.unit(),
                    })
                    .collect()
            })
            .collect();
        let connection = (0..points * points)
            .map(|_| {
                if rng.below(20) == 0 {
                    1e7
                } else {
                    100.0 * rng.unit()
                }
            })
            .collect();
        let from_start = (0..points).map(|_| 50.0 * rng.unit()).collect();
        let to_finish = (0..points).map(|_| 50.0 * rng.unit()).collect();
        SequenceProblem {
            ways,
            points,
            connection,
            from_start,
            to_finish,
        }
    }

    fn blocks_with_ways(problem: &SequenceProblem) -> Vec<usize> {
        (0..problem.ways.len())
            .filter(|&b| !problem.ways[b].is_empty())
            .collect()
    }

    /// The order is a permutation of the blocks with ways, each with a valid way, and its cost
    /// is what it says.
    fn check(problem: &SequenceProblem, sequence: &Sequence) {
        let mut blocks: Vec<usize> = sequence.order.iter().map(|&(b, _)| b).collect();
        blocks.sort_unstable();
        assert_eq!(blocks, blocks_with_ways(problem));
        for &(b, w) in &sequence.order {
            assert!(w < problem.ways[b].len());
        }
        let cost = problem.cost(&sequence.order);
        assert!(
            relative_gap(sequence.cost, cost) < 1e-9,
            "{} != {}",
            sequence.cost,
            cost
        );
    }

    #[test]
    fn best_ways_is_optimal() {
        for seed in 0..40 {
            let blocks = 1 + (seed as usize % 5);
            let problem = if seed % 2 == 0 {
                random_problem(blocks, seed)
            } else {
                irregular_problem(blocks, seed)
            };
            let mut rng = Rng::new(seed + 1000);
            // Any list of blocks: repeats, blocks without ways, out of range.
            let order: Vec<usize> = (0..blocks + 1).map(|_| rng.below(blocks + 1)).collect();
            let (ways, cost) = best_ways(&problem, &order);
            assert_eq!(ways.len(), order.len());
            let pairs: Vec<(usize, usize)> = order.iter().copied().zip(ways).collect();
            assert!(relative_gap(problem.cost(&pairs), cost) < 1e-9);
            // Brute force over every combination of ways.
            let counts: Vec<usize> = order
                .iter()
                .map(|&b| problem.ways.get(b).map_or(1, |w| w.len().max(1)))
                .collect();
            let combinations: usize = counts.iter().product();
            let mut least = f64::INFINITY;
            for mut code in 0..combinations {
                let pairs: Vec<(usize, usize)> = order
                    .iter()
                    .zip(&counts)
                    .map(|(&b, &n)| {
                        let w = code % n;
                        code /= n;
                        (b, w)
                    })
                    .collect();
                least = least.min(problem.cost(&pairs));
            }
            assert!(relative_gap(least, cost) < 1e-9, "{least} vs {cost}");
        }
    }

    #[test]
    fn exact_equals_exhaustive() {
        for blocks in 1..=8 {
            for seed in 0..4u64 {
                let problem = if seed % 2 == 0 {
                    random_problem(blocks, seed * 31 + blocks as u64)
                } else {
                    irregular_problem(blocks, seed * 31 + blocks as u64)
                };
                let exact = solve_exact(&problem);
                let all = exhaustive(&problem);
                assert_eq!(exact.method, SequenceMethod::Exact);
                assert_eq!(all.method, SequenceMethod::Exact);
                check(&problem, &exact);
                check(&problem, &all);
                assert!(
                    relative_gap(exact.cost, all.cost) < 1e-9,
                    "{blocks} blocks, seed {seed}: {} vs {}",
                    exact.cost,
                    all.cost
                );
                let order: Vec<usize> = exact.order.iter().map(|&(b, _)| b).collect();
                assert!(relative_gap(best_ways(&problem, &order).1, exact.cost) < 1e-9);
                // The heuristic cannot beat the optimum.
                let heuristic = solve_heuristic(&problem, &AntColony::default());
                check(&problem, &heuristic);
                assert!(heuristic.cost >= exact.cost - 1e-9 * exact.cost.abs());
            }
        }
    }

    #[test]
    fn heuristic_is_near_random_restarts() {
        for (blocks, seed) in [(13, 1), (13, 2), (20, 3), (20, 4), (30, 5), (30, 6)] {
            let problem = random_problem(blocks, seed);
            let heuristic = solve(&problem, seed);
            assert_eq!(heuristic.method, SequenceMethod::AntColony);
            check(&problem, &heuristic);
            let yardstick = random_restarts(&problem, 100, seed);
            check(&problem, &yardstick);
            assert!(
                heuristic.cost <= yardstick.cost * 1.02,
                "{blocks} blocks: {} vs {}",
                heuristic.cost,
                yardstick.cost
            );
        }
    }

    #[test]
    fn heuristic_is_near_exact() {
        for seed in 0..4 {
            let problem = irregular_problem(12, seed);
            let exact = solve_exact(&problem);
            let heuristic = solve_heuristic(&problem, &AntColony::default());
            check(&problem, &heuristic);
            assert!(heuristic.cost <= exact.cost * 1.02 + 1e-9);
        }
    }

    #[test]
    fn exhaustive_hands_larger_problems_to_exact() {
        let problem = random_problem(10, 3);
        assert_eq!(exhaustive(&problem), solve_exact(&problem));
    }

    #[test]
    fn many_ways_are_looked_up() {
        // 1050 ways: no transition matrix, no colony, no exact table; three blocks is still
        // within reach of one local search from any order.
        let mut rng = Rng::new(17);
        let points = 60;
        let problem = SequenceProblem {
            ways: (0..3)
                .map(|_| {
                    (0..350)
                        .map(|_| Way {
                            entry: rng.below(points),
                            exit: rng.below(points),
                            cost: 10.0 * rng.unit(),
                        })
                        .collect()
                })
                .collect(),
            points,
            connection: (0..points * points).map(|_| 100.0 * rng.unit()).collect(),
            from_start: vec![0.0; points],
            to_finish: vec![0.0; points],
        };
        let sequence = solve(&problem, 0);
        assert_eq!(sequence.method, SequenceMethod::AntColony);
        check(&problem, &sequence);
        let all = exhaustive(&problem);
        check(&problem, &all);
        assert!(relative_gap(sequence.cost, all.cost) < 1e-9);
        let order: Vec<usize> = all.order.iter().map(|&(b, _)| b).collect();
        assert!(relative_gap(best_ways(&problem, &order).1, all.cost) < 1e-9);
    }

    #[test]
    fn the_local_search_stops_at_its_budget() {
        // 250 blocks of four ways from a random order: far more work to a local optimum than
        // the budget given here.
        let problem = random_problem(250, 3);
        let c = Compiled::new(&problem, true);
        let mut start: Vec<usize> = (0..250).collect();
        Rng::new(5).shuffle(&mut start);
        let run = |budget: usize| {
            let mut search = LocalSearch::new(&c, start.clone());
            search.budget = budget;
            let before = search.cost;
            search.run();
            (search.work, search.cost, before, search.order)
        };
        let budget = 2_000_000;
        let (work, cost, before, order) = run(budget);
        // It stops at the budget, past it by at most the move it was trying and the rebuild
        // after it (a step per block each, 16 additions a step).
        assert!(work >= budget, "{work}");
        assert!(work <= budget + 3 * (250 + 2) * 16, "{work}");
        // With the best order so far: every block once, its cost what it says, and better than
        // where it started.
        let mut blocks = order.clone();
        blocks.sort_unstable();
        assert_eq!(blocks, (0..250).collect::<Vec<_>>());
        assert!(relative_gap(c.viterbi(&order).1, cost) < 1e-9);
        assert!(cost < before);
        // The same again: the budget counts work, not time.
        assert_eq!(run(budget).3, order);
        // Twice the budget goes further.
        assert!(run(2 * budget).1 < cost);
    }

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

    #[test]
    fn empty_problem() {
        let empty = SequenceProblem {
            ways: Vec::new(),
            points: 0,
            connection: Vec::new(),
            from_start: Vec::new(),
            to_finish: Vec::new(),
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
