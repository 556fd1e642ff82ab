//! The exact solvers: dynamic programming over subsets of blocks ([`solve_exact`], Held-Karp),
//! and every permutation ([`exhaustive`]), the yardstick it is checked against.

use super::ant_colony::solve_heuristic;
use super::compiled::{Compiled, DENSE_MAX_NODES};
use super::{empty_sequence, AntColony, Sequence, SequenceMethod, SequenceProblem};

/// [`solve`] is exact up to this many blocks (with ways).
///
/// [`solve`]: super::solve
pub const EXACT_MAX_BLOCKS: usize = 12;

/// The most steps (`2^blocks x ways^2`, about twice the additions its table takes) for which
/// [`solve`] takes the exact answer rather than the heuristic: 11 blocks of four ways each
/// (`2048 x 44^2`, 4 million) are exact, 12 (`4096 x 48^2`, 9.4 million) are not. In
/// WebAssembly those 12 took about 10 ms exactly, 25 with eight ways (blocks that may also end
/// by driving back along their last swath), the ant colony under 2; on the corpus the colony
/// found the exact cost wherever the limit changed the solver.
///
/// [`solve`]: super::solve
pub const EXACT_MAX_WORK: usize = 5_000_000;

/// [`exhaustive`] enumerates every permutation up to this many blocks.
pub const EXHAUSTIVE_MAX_BLOCKS: usize = 9;

/// The most dynamic-programming states (`2^blocks x ways`) [`solve_exact`] allocates: 32 MB.
const EXACT_MAX_STATES: usize = 1 << 22;

/// Whether the exact table fits: few enough blocks, and ways (nodes) for the transition matrix.
fn exact_fits(blocks: usize, nodes: usize) -> bool {
    blocks <= EXACT_MAX_BLOCKS
        && nodes <= DENSE_MAX_NODES
        && (1usize << blocks).saturating_mul(nodes) <= EXACT_MAX_STATES
}

/// Whether [`solve`] takes the exact answer: it fits, and its table costs at most
/// [`EXACT_MAX_WORK`] steps.
pub(super) fn exact_pays(blocks: usize, nodes: usize) -> bool {
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
            // Worked before the blocks not in `set`: what that costs where they should come first.
            let late = c.late(b, set);
            for to in c.ways(b) {
                row[to] = late
                    + if before == 0 {
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
                let cost = self.c.close(a, &self.layers[(depth - 1) * w..depth * w])
                    + self.c.precedence_cost(&self.path);
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

#[cfg(test)]
mod tests {
    use super::super::test_support::{check, irregular_problem, relative_gap};
    use super::super::*;
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
    fn exhaustive_hands_larger_problems_to_exact() {
        let problem = random_problem(10, 3);
        assert_eq!(exhaustive(&problem), solve_exact(&problem));
    }
}
