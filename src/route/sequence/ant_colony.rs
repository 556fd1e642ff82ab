//! The heuristic for problems beyond the exact table: the ant colony of Zhou et al. over the
//! (block, way) nodes, its best orders then improved by local search ([`solve_heuristic`]).

use super::compiled::Compiled;
use super::local_search::{keep_precedence, LocalSearch};
use super::{empty_sequence, Sequence, SequenceMethod, SequenceProblem, LARGE_COST};
use crate::rng::SplitMix64 as Rng;
use std::cmp::Ordering;

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
///
/// [`best_ways`]: super::best_ways
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
    let mut best: Option<(f64, Vec<usize>)> = None;
    for start in starts {
        let mut search = LocalSearch::new(&c, start);
        search.run();
        let mut order = search.order;
        let cost = if c.follows.is_empty() {
            search.cost
        } else {
            keep_precedence(&c, &mut order)
        };
        if best.as_ref().is_none_or(|b| cost < b.0) {
            best = Some((cost, order));
        }
    }
    let order = best.map(|b| b.1).unwrap_or_default();
    c.sequence(&order, SequenceMethod::AntColony)
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
    let mut list: Vec<usize> = Vec::with_capacity(width + 1);
    for from in 0..nodes {
        // The `width` cheapest, kept in order as they come (ties by index): each next way
        // compared with the dearest kept, and only a cheaper one put in its place.
        list.clear();
        let key = |to: usize| (avoidable[from * nodes + to], to);
        let before = |a: usize, b: usize| {
            let (ka, kb) = (key(a), key(b));
            ka.0.total_cmp(&kb.0).then(ka.1.cmp(&kb.1)) == Ordering::Less
        };
        for to in (0..nodes).filter(|&to| block_of[to] != block_of[from]) {
            if list.len() == width && list.last().is_some_and(|&last| !before(to, last)) {
                continue;
            }
            let at = list.partition_point(|&kept| before(kept, to));
            list.insert(at, to);
            list.truncate(width);
        }
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

#[cfg(test)]
mod tests {
    use super::super::test_support::{check, irregular_problem};
    use super::super::*;

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
}
