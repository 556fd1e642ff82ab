//! The problem as the solvers see it ([`Compiled`]): its blocks with ways, their ways as nodes,
//! the costs between them kept in matrices while they are small, and the layer steps with which
//! every solver costs a block order with its best ways (Viterbi, [`best_ways`]).

use super::{clamp_cost, Sequence, SequenceMethod, SequenceProblem};
use crate::sort::SharedSort;
use std::ops::Range;

/// The most ways for which the (way x way) transition matrix is kept (8 MB) and the colony
/// runs; above it costs are looked up as needed and the search starts nearest-next.
pub(super) const DENSE_MAX_NODES: usize = 1024;

/// How many cheapest moves out of and into each block the local search tries (its neighbours).
const NEAR: usize = 8;

/// The most entries of the block-pair matrices kept (8 MB); above it costs are looked up.
const PAIRS_MAX: usize = 1 << 20;

/// The problem as the solvers see it: the blocks with ways numbered `0..blocks`, their ways
/// flattened into nodes, and the way cost folded into the cost of arriving at a node.
pub(super) struct Compiled<'p> {
    problem: &'p SequenceProblem,
    /// The problem's index of each block with ways.
    pub(super) blocks: Vec<usize>,
    /// The nodes of block `k` are `offset[k]..offset[k + 1]`, in the order of its ways.
    pub(super) offset: Vec<usize>,
    entry: Vec<usize>,
    exit: Vec<usize>,
    pub(super) way_cost: Vec<f64>,
    /// From the start to the node's entry, plus its way cost.
    pub(super) start: Vec<f64>,
    /// From the node's exit to the finish.
    pub(super) finish: Vec<f64>,
    /// `nodes x nodes`: connection from one node's exit to the other's entry, plus the other's
    /// way cost; empty when not dense.
    transition: Vec<f64>,
    pub(super) dense: bool,
    /// The most ways of a block.
    pub(super) widest: usize,
    /// `blocks x widest`: the start layer of each block, its `start` padded with infinity.
    start_layer: Vec<f64>,
    /// `blocks x widest`: the finish layer of each block, its `finish` padded with infinity.
    finish_layer: Vec<f64>,
    /// `blocks x blocks` matrices of `widest x widest` (see `pair`), when dense and not too big.
    pub(super) pairs: Vec<f64>,
    /// `near[a * blocks + b]`: going on from block `a` to block `b` is among the cheapest
    /// moves out of `a` or into `b`; empty when every pair counts as near.
    near: Vec<bool>,
    /// The blocks better worked before others: (first, then, what working `then` first costs)
    /// ([`Precedence`](super::Precedence), in compiled indices).
    pub(super) follows: Vec<(usize, usize, f64)>,
}

impl<'p> Compiled<'p> {
    pub(super) fn new(problem: &'p SequenceProblem, dense: bool) -> Self {
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
            follows: Vec::new(),
        };
        let count = compiled.block_count();
        compiled.follows = compiled.compile_precedence();
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

    /// The problem's precedence in compiled blocks (see `follows`): pairs naming a block without
    /// ways, or one block twice, are left out.
    fn compile_precedence(&self) -> Vec<(usize, usize, f64)> {
        let index = |block: usize| self.blocks.binary_search(&block).ok();
        self.problem
            .precedence
            .iter()
            .filter_map(|p| match (index(p.first), index(p.then)) {
                (Some(first), Some(then)) if first != then => {
                    Some((first, then, clamp_cost(p.cost)))
                }
                _ => None,
            })
            .collect()
    }

    /// What block `k` adds for the blocks better worked before it that are not in `set` (a bit
    /// per compiled block): `k` joins the blocks of `set` worked before it, the others after.
    pub(super) fn late(&self, k: usize, set: usize) -> f64 {
        let outside = |b: usize| set.checked_shr(b as u32).is_none_or(|s| s & 1 == 0);
        self.follows
            .iter()
            .filter(|&&(first, then, _)| then == k && outside(first))
            .map(|&(_, _, cost)| cost)
            .sum()
    }

    /// What `order` (compiled blocks) costs for blocks worked before those better worked first.
    pub(super) fn precedence_cost(&self, order: &[usize]) -> f64 {
        let at = |b: usize| order.iter().position(|&k| k == b);
        self.follows
            .iter()
            .filter(
                |&&(first, then, _)| matches!((at(first), at(then)), (Some(f), Some(t)) if t < f),
            )
            .map(|&(_, _, cost)| cost)
            .sum()
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
    pub(super) fn is_near(&self, a: usize, b: usize) -> bool {
        self.near.is_empty() || self.near.get(a * self.block_count() + b) == Some(&true)
    }

    pub(super) fn nodes(&self) -> usize {
        self.entry.len()
    }

    pub(super) fn block_count(&self) -> usize {
        self.blocks.len()
    }

    pub(super) fn ways(&self, block: usize) -> Range<usize> {
        self.offset[block]..self.offset[block + 1]
    }

    fn lookup(&self, from: usize, to: usize) -> f64 {
        self.problem
            .connection_cost(self.exit[from], self.entry[to])
            + self.way_cost[to]
    }

    /// The cost of going on from node `from` to node `to`, including `to`'s way cost.
    #[inline]
    pub(super) fn transition(&self, from: usize, to: usize) -> f64 {
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
    pub(super) fn enter(&self, b: usize, out: &mut [f64]) {
        let w = self.widest;
        out[..w].copy_from_slice(&self.start_layer[b * w..(b + 1) * w]);
    }

    /// `out`: the layer of finishing with block `b`, the cost from each of its ways.
    pub(super) fn last(&self, b: usize, out: &mut [f64]) {
        let w = self.widest;
        out[..w].copy_from_slice(&self.finish_layer[b * w..(b + 1) * w]);
    }

    /// `out[w]`: the best cost of standing at way `w` of block `b` after block `a`, given `cur[v]`
    /// the best cost of standing at way `v` of block `a`.
    pub(super) fn step(&self, a: usize, cur: &[f64], b: usize, out: &mut [f64]) {
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
    pub(super) fn pull(&self, a: usize, b: usize, after: &[f64], out: &mut [f64]) {
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
    pub(super) fn join(&self, a: usize, cur: &[f64], b: usize, after: &[f64]) -> f64 {
        match self.pair(a, b) {
            Some(m) => with_width(self.widest, |w| join_kernel(w, m, cur, after)),
            None => (0..self.widest)
                .flat_map(|v| (0..self.widest).map(move |t| (v, t)))
                .map(|(v, t)| cur[v] + self.pair_entry(a, b, v, t) + after[t])
                .fold(f64::INFINITY, least),
        }
    }

    /// The best total of a prefix standing at block `a` that finishes there.
    pub(super) fn close(&self, a: usize, cur: &[f64]) -> f64 {
        let w = self.widest;
        let finish = &self.finish_layer[a * w..(a + 1) * w];
        cur.iter()
            .zip(finish)
            .map(|(&c, &f)| c + f)
            .fold(f64::INFINITY, least)
    }

    /// The best total of a suffix starting at block `b` that is the whole sequence.
    pub(super) fn open(&self, b: usize, after: &[f64]) -> f64 {
        let w = self.widest;
        let start = &self.start_layer[b * w..(b + 1) * w];
        start
            .iter()
            .zip(after)
            .map(|(&s, &r)| s + r)
            .fold(f64::INFINITY, least)
    }

    /// The best way (index within its block) of each block of `order` and the total cost:
    /// Viterbi through the layers of ways, and the order's precedence cost (which the ways do
    /// not change).
    pub(super) fn viterbi(&self, order: &[usize]) -> (Vec<usize>, f64) {
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
        (ways, total + self.precedence_cost(order))
    }

    /// The sequence of the given order (of compiled blocks), with its best ways.
    pub(super) fn sequence(&self, order: &[usize], method: SequenceMethod) -> Sequence {
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
    pub(super) fn nearest_next(&self) -> Vec<usize> {
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

#[cfg(test)]
mod tests {
    use super::super::test_support::{check, irregular_problem, relative_gap};
    use super::super::*;
    use crate::rng::SplitMix64 as Rng;

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
            precedence: Vec::new(),
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
}
