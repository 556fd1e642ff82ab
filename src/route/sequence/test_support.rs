//! What the solvers' tests share: a problem of irregular ways, and the check that a sequence
//! is a valid one of its problem.

use super::{Sequence, SequenceProblem, Way};
use crate::rng::SplitMix64 as Rng;

pub(super) fn relative_gap(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1.0)
}

/// A problem with irregular ways: 0 to 4 ways per block at random points, random way costs,
/// an asymmetric random connection matrix with some penalties, random start and finish costs.
pub(super) fn irregular_problem(blocks: usize, seed: u64) -> SequenceProblem {
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
        precedence: Vec::new(),
    }
}

fn blocks_with_ways(problem: &SequenceProblem) -> Vec<usize> {
    (0..problem.ways.len())
        .filter(|&b| !problem.ways[b].is_empty())
        .collect()
}

/// The order is a permutation of the blocks with ways, each with a valid way, and its cost
/// is what it says.
pub(super) fn check(problem: &SequenceProblem, sequence: &Sequence) {
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
