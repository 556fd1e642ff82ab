//! Local search on a block order: 2-opt and or-opt moves, each order costed with its best
//! ways, within a budget of work ([`LOCAL_SEARCH_WORK`]); and [`random_restarts`], the
//! yardstick of the heuristic.

use super::compiled::Compiled;
use super::{empty_sequence, Sequence, SequenceMethod, SequenceProblem};
use crate::rng::SplitMix64 as Rng;

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

/// `candidate` is better than `current` by more than rounding.
fn improves(candidate: f64, current: f64) -> bool {
    candidate < current - (1e-9 + 1e-10 * current.abs())
}

/// The most work [`keep_precedence`] does, in additions of layer steps as
/// [`LOCAL_SEARCH_WORK`]: each order it tries is costed afresh (`blocks x widest^2`).
const PRECEDENCE_WORK: usize = 20_000_000;

/// Moves blocks of `order` worked before blocks better worked first ([`Precedence`]) while
/// that lowers the cost of the order with its best ways and its precedence cost: of each pair
/// broken, the later block tried at every place before the earlier, and the earlier at every
/// place after the later; the best move taken, until none lowers the cost or the work reaches
/// [`PRECEDENCE_WORK`] (then the best move among those tried). Gives the order's cost. The local search weighs the driving only; this
/// weighs the rest.
///
/// [`Precedence`]: super::Precedence
pub(super) fn keep_precedence(c: &Compiled, order: &mut Vec<usize>) -> f64 {
    let mut cost = c.viterbi(order).1;
    if c.follows.is_empty() || order.len() < 2 {
        return cost;
    }
    let per_try = order.len() * c.widest * c.widest;
    let mut work = 0;
    while work < PRECEDENCE_WORK {
        let at = |b: usize| order.iter().position(|&k| k == b);
        let mut best: Option<(f64, Vec<usize>)> = None;
        'pairs: for &(first, then, _) in &c.follows {
            let (Some(f), Some(t)) = (at(first), at(then)) else {
                continue;
            };
            if t > f {
                continue;
            }
            // `then` moved to after `first` (which stands at f - 1 once `then` is out), or
            // `first` moved to before `then`.
            for (from, places) in [(t, f..order.len()), (f, 0..t + 1)] {
                for to in places {
                    if work >= PRECEDENCE_WORK {
                        break 'pairs;
                    }
                    let mut tried = order.clone();
                    let moved = tried.remove(from);
                    tried.insert(to, moved);
                    work += per_try;
                    let tried_cost = c.viterbi(&tried).1;
                    if improves(tried_cost, best.as_ref().map_or(cost, |b| b.0)) {
                        best = Some((tried_cost, tried));
                    }
                }
            }
        }
        match best {
            Some((lower, better)) => {
                cost = lower;
                *order = better;
            }
            None => break,
        }
    }
    cost
}

/// The best of `restarts` local searches (2-opt + or-opt as in [`solve_heuristic`]) each from a
/// random block order: the yardstick the heuristic is measured against. At least one restart
/// is made; the method reported is [`SequenceMethod::AntColony`] (a heuristic).
///
/// [`solve_heuristic`]: super::solve_heuristic
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

/// 2-opt and or-opt on a block order, each order costed with its best ways, kept as prefix
/// (`forward`) and suffix (`backward`) layers so that a move is costed by its changed part only.
///
/// Moves are tried only where they make a near connection (see `Compiled::near`), first
/// improvement, pass after pass until one finds no improving move or the search has done
/// [`LOCAL_SEARCH_WORK`].
pub(super) struct LocalSearch<'c, 'p> {
    c: &'c Compiled<'p>,
    pub(super) order: Vec<usize>,
    /// `forward[i * widest + w]`: the best cost of `order[..=i]` ending with way `w` of
    /// `order[i]`.
    forward: Vec<f64>,
    /// `backward[i * widest + w]`: the best cost from way `w` of `order[i]` (its own cost not
    /// included) through `order[i + 1..]` to the finish.
    backward: Vec<f64>,
    pub(super) cost: f64,
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
    pub(super) fn new(c: &'c Compiled<'p>, order: Vec<usize>) -> Self {
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
    pub(super) fn run(&mut self) {
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
    use super::super::test_support::relative_gap;
    use super::super::*;
    use super::*;
    use crate::rng::SplitMix64 as Rng;

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
}
