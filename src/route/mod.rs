//! The route: the order in which swaths, blocks and headland passes are worked, which way each
//! is driven, and the connections between them along the headland.
//!
//! Its parts, each in its own module:
//! - [`pattern`]: the order of the swaths inside a block (boustrophedon, snake, spiral, custom,
//!   or `auto`, the one whose turns cost least), and the four ways to start it.
//! - [`headland_graph`]: the lines along which the machine moves between blocks without crossing
//!   the crop: the headland passes round the field and the obstacles, joined where they meet.
//! - [`sequence`]: the order of the blocks and the way each is worked, as a travelling-salesman
//!   problem over the blocks' entry and exit points (Zhou et al. 2.4): exact by dynamic
//!   programming while its table is small (up to 11 blocks of four ways), by ant colony and
//!   local search beyond.
//! - [`nearest`]: the plain order for fields of many blocks (more than 1,024 ways, 256 blocks
//!   of four), whose connection table would take gigabytes: each next block the nearest.
//! - `ring`: the nearest point of a ring (a closed pass) to a position ([`nearest_on_ring`]).
//! - `on_the_way`: the blocks that fill what the field's blocks leave, sequenced after them,
//!   each moved to between two field blocks where it lies on the way.
//! - [`turns_onto`]: blocks whose swath ends lie against a neighbour's swaths, better worked
//!   after it (their turns then run over stubble): a precedence the block order weighs.
//!
//! The headland passes come last, as in seeding (Zhou et al. 2.1), from the innermost out, so the
//! machine finishes on the outermost pass at the field edge; or first, as in harvesting, from the
//! outermost in, opening up the field edge before the swaths (the passes round obstacles, islands
//! in the inner field, still come after them, reached along worked swaths rather than through
//! standing crop). Passes with the same index are
//! taken nearest-first; a closed pass is entered at its point nearest to the machine, an open one
//! at its nearer end. The route starts at the entrance when one is given (else wherever the work
//! starts best) and ends at the exit when one is given.

pub mod headland_graph;
pub mod nearest;
mod on_the_way;
pub mod pattern;
mod ring;
pub mod sequence;
mod turn_floor;
pub mod turns_onto;

pub use ring::nearest_on_ring;

use crate::decompose::Blocks;
use crate::geometry::PlanarHypot;
use crate::headland::{HeadlandOrder, HeadlandPass, PassAround};
use crate::objective::TurnLengths;
use crate::sort::SharedSort;
use crate::swath::Swaths;
use geo::{Coord, LineString, MultiPolygon};
use headland_graph::{HeadlandGraph, CROSSING_PENALTY_M};
use on_the_way::OnTheWay;
use pattern::{block_turning_m, ways, BlockWay, SwathOrder};
use sequence::{SequenceMethod, SequenceProblem, Way};
use turn_floor::{facing_out, turn_floor};

/// One step of a route.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RouteStep {
    /// Work a swath.
    Swath {
        /// Index into [`Swaths::swaths`].
        swath: usize,
        /// Driven from its end to its start (against the swath direction).
        reversed: bool,
        /// The block it belongs to.
        block: usize,
    },
    /// Work a headland pass: a closed one from the point of it nearest to the machine, an open
    /// one from its nearer end.
    HeadlandPass {
        /// Index into [`Headlands::passes`](crate::headland::Headlands::passes).
        pass: usize,
        /// An open pass driven from its last point to its first.
        reversed: bool,
    },
}

/// A move without working, between blocks or onto the headland passes: along the headland
/// graph, or straight where it offers no way.
#[derive(Debug, Clone, PartialEq)]
pub struct Connection {
    /// Its line, in driving order.
    pub line: LineString,
    /// Whether the headland offered no way, so that it runs straight, likely across crop.
    pub straight: bool,
}

/// How the order of the blocks was found.
#[derive(Debug, Clone, PartialEq)]
pub struct SequenceReport {
    /// Exact (dynamic programming) or the ant colony with local search.
    pub method: SequenceMethod,
    /// The cost minimised: turning inside the blocks by the turn model and connections between
    /// them (and from the entrance), metres; each connection the headland offers no way for
    /// counts [`CROSSING_PENALTY_M`] more. The field's blocks are sequenced first, then the
    /// blocks that fill what they leave, from where the field's end; a fill block is then
    /// moved between two blocks where it lies on the way: the sum of both.
    pub cost_m: f64,
    /// Of [`cost_m`](Self::cost_m), what the blocks that fill what the field's leave add.
    pub fill_cost_m: f64,
}

/// The order of work.
#[derive(Debug, Clone, PartialEq)]
pub struct Route {
    /// The steps in driving order.
    pub steps: Vec<RouteStep>,
    /// For each step, the connection that leads into it: `None` for a turn between swaths of a
    /// block, and for the first step when the route has no entrance.
    pub connections: Vec<Option<Connection>>,
    /// The connection from the end of the work to the exit, if one was given.
    pub finish: Option<Connection>,
    /// The blocks in the order they are worked.
    pub block_order: Vec<usize>,
    /// The swath order each block is worked in (`boustrophedon`, `snake-1`, ...), by block.
    pub block_patterns: Vec<String>,
    /// Length of the turns between swaths of a block by the turn model, metres.
    pub turning_m: f64,
    /// How the block order was found.
    pub sequence: SequenceReport,
}

impl Default for Route {
    fn default() -> Self {
        Route {
            steps: Vec::new(),
            connections: Vec::new(),
            finish: None,
            block_order: Vec::new(),
            block_patterns: Vec::new(),
            turning_m: 0.0,
            sequence: SequenceReport {
                method: SequenceMethod::Exact,
                cost_m: 0.0,
                fill_cost_m: 0.0,
            },
        }
    }
}

impl Route {
    /// The connections, in driving order (the finish last).
    pub fn all_connections(&self) -> impl Iterator<Item = &Connection> {
        self.connections.iter().flatten().chain(&self.finish)
    }

    /// The same route over the same swaths numbered otherwise: each swath step's index `i`
    /// becomes `new_index[i]`. `None` if a step's swath has no new index.
    ///
    /// ```
    /// use furrow::route::{Route, RouteStep};
    ///
    /// let route = Route {
    ///     steps: vec![RouteStep::Swath { swath: 1, reversed: false, block: 0 }],
    ///     ..Route::default()
    /// };
    /// let renumbered = route.with_swaths_renumbered(&[Some(1), Some(0)]);
    /// assert_eq!(
    ///     renumbered.map(|r| r.steps),
    ///     Some(vec![RouteStep::Swath { swath: 0, reversed: false, block: 0 }])
    /// );
    /// assert!(route.with_swaths_renumbered(&[Some(0)]).is_none());
    /// ```
    pub fn with_swaths_renumbered(&self, new_index: &[Option<usize>]) -> Option<Route> {
        let mut route = self.clone();
        for step in &mut route.steps {
            if let RouteStep::Swath { swath, .. } = step {
                *swath = new_index.get(*swath).copied().flatten()?;
            }
        }
        Some(route)
    }
}

/// The settings of the route stage.
#[derive(Debug, Clone, PartialEq)]
pub struct RouteSettings {
    /// The swath orders to choose from for each block (the one whose turns cost least is used).
    pub orders: Vec<SwathOrder>,
    /// Headland passes before or after the swaths.
    pub headland_order: HeadlandOrder,
    /// Working width, metres.
    pub width: f64,
    /// Turning radius, metres.
    pub turn_radius: f64,
    /// Whether the machine may reverse: each block's pattern is chosen with close swaths
    /// joined by three-point turns where they cost less than loops
    /// ([`TurnLengths::of_machine`]).
    pub reverse: bool,
    /// The headland's depth where the swaths end, metres: each block's pattern is chosen with
    /// turns that do not fit it weighed more ([`TurnLengths::between`]). Infinite: no limit.
    pub headland_m: f64,
    /// Where the route starts (local metres).
    pub entrance: Option<Coord>,
    /// Where the route ends (local metres).
    pub exit: Option<Coord>,
    /// Seed of the ant colony (for block orders too large to solve exactly).
    pub seed: u64,
    /// The crop standing while the machine moves between blocks (the inner field): the headland
    /// graph's hops do not cross it ([`HeadlandGraph::with_crop`]). `None`: hops anywhere.
    pub crop: Option<MultiPolygon>,
}

impl Default for RouteSettings {
    fn default() -> Self {
        RouteSettings {
            orders: vec![SwathOrder::Boustrophedon],
            headland_order: HeadlandOrder::Last,
            width: 6.0,
            turn_radius: 8.0,
            reverse: false,
            headland_m: f64::INFINITY,
            entrance: None,
            exit: None,
            seed: 1,
            crop: None,
        }
    }
}

/// Routes a plan: the swath order of each block, the block sequence, the headland passes before
/// or after, and the connections between them along the headland.
///
/// ```
/// use furrow::{decompose::cluster_swaths, route::{plan_route, RouteSettings, RouteStep}, swath::generate};
/// use geo::{polygon, MultiPolygon};
///
/// let field = polygon![(x: 0., y: 0.), (x: 30., y: 0.), (x: 30., y: 100.), (x: 0., y: 100.)];
/// let swaths = generate(&MultiPolygon::new(vec![field]), 0.0, 6.0, 6.0)?;
/// let blocks = cluster_swaths(&swaths);
/// let route = plan_route(&swaths, &blocks, &[], &RouteSettings::default());
/// let reversed: Vec<bool> = route.steps.iter().map(|s| match s {
///     RouteStep::Swath { reversed, .. } => *reversed,
///     _ => unreachable!(),
/// }).collect();
/// assert_eq!(reversed.len(), 5);
/// // Each swath is driven the other way from the one before.
/// assert!(reversed.windows(2).all(|w| w[0] != w[1]));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn plan_route(
    swaths: &Swaths,
    blocks: &Blocks,
    passes: &[HeadlandPass],
    settings: &RouteSettings,
) -> Route {
    plan_route_on(
        &headland_graph(passes, settings),
        swaths,
        blocks,
        passes,
        settings,
    )
}

/// The headland graph of `passes` for these settings: their width, and their crop if any.
pub fn headland_graph(passes: &[HeadlandPass], settings: &RouteSettings) -> HeadlandGraph {
    let graph = HeadlandGraph::new(passes, settings.width);
    match &settings.crop {
        Some(crop) => graph.with_crop(crop),
        None => graph,
    }
}

/// [`plan_route`] along a headland graph built by the caller, [`headland_graph`]`(passes,
/// settings)`: plans that differ only in their swaths share it (the same route as
/// [`plan_route`]'s).
pub fn plan_route_on(
    graph: &HeadlandGraph,
    swaths: &Swaths,
    blocks: &Blocks,
    passes: &[HeadlandPass],
    settings: &RouteSettings,
) -> Route {
    let s = &swaths.swaths;
    let mut route = Route::default();

    // Headland first: the passes from the entrance, and the blocks from where they end.
    let mut position = settings.entrance;
    let mut pass_steps = Vec::new();
    if settings.headland_order == HeadlandOrder::First {
        position =
            append_headland_passes(&mut pass_steps, passes, graph, position, true, not_island);
    }

    let (names, block_ways) = cheapest_ways(swaths, blocks, settings);
    route.block_patterns = names;
    // With passes (or an exit) after the blocks, the last block should end where the headland
    // reaches.
    let finish_on_headland = finishes_on_headland(graph, passes, settings);
    // The field's blocks first, then the blocks that fill what they leave (reached once the
    // crop round them is worked).
    let fill_from = swaths.first_fill_swath();
    let (field_blocks, fill_blocks): (Vec<usize>, Vec<usize>) = (0..blocks.blocks.len())
        .partition(|&b| blocks.blocks[b].swaths.iter().any(|&i| i < fill_from));
    // Once the field's swaths are worked, the machine may also drive along their tracks.
    let field_tracks = || {
        let tracks: Vec<LineString> = s[..fill_from.min(s.len())]
            .iter()
            .map(|w| LineString::new(vec![w.centre.start, w.centre.end]))
            .collect();
        HeadlandGraph::with_tracks(passes, &tracks, settings.width)
    };
    let mut tracks_graph: Option<HeadlandGraph> = None;
    let mut order: Vec<(usize, usize, bool)> = Vec::new(); // (block, way, returns)
    let mut fill_at = 0; // where the fill's blocks start in `order`
    let mut reports: Vec<(SequenceMethod, f64, bool)> = Vec::new();
    for (group, fill) in [(field_blocks, false), (fill_blocks, true)] {
        if group.is_empty() {
            continue;
        }
        let group_ways: Vec<Vec<BlockWay>> = group.iter().map(|&b| block_ways[b].clone()).collect();
        // The entrance (or where the passes first end) joins the graph however far it is.
        let unlimited: Vec<usize> = if position.is_some() && order.is_empty() {
            vec![0]
        } else {
            vec![]
        };
        let (on, finish_on_headland) = if fill && !order.is_empty() {
            (
                &*tracks_graph.get_or_insert_with(field_tracks),
                fill_finishes_on_headland(passes, settings),
            )
        } else {
            (graph, finish_on_headland)
        };
        let between = Between {
            graph: on,
            unlimited: &unlimited,
            finish_on_headland,
            settings,
        };
        let (solution, chosen_ways) = sequence_blocks(&group_ways, s, position, &between);
        if fill {
            fill_at = order.len();
        }
        for &(g, wi) in &solution.order {
            let Some(&(wi, returns)) = chosen_ways.get(g).and_then(|w| w.get(wi)) else {
                continue;
            };
            let (Some(&b), Some(w)) = (group.get(g), group_ways.get(g).and_then(|w| w.get(wi)))
            else {
                continue;
            };
            order.push((b, wi, returns));
            // A block that ends by driving back along its last swath leaves the machine at
            // that swath's other end.
            let end = if returns {
                w.exit(s).and_then(|e| {
                    let last = s.get(*w.swaths.last()?)?;
                    Some(if e == last.centre.end {
                        last.centre.start
                    } else {
                        last.centre.end
                    })
                })
            } else {
                w.exit(s)
            };
            position = end.or(position);
        }
        reports.push((solution.method, solution.cost, fill));
    }
    // Fill blocks worked where they lie on the way between the field's blocks.
    let mut saved = 0.0;
    if let Some(after_field) = tracks_graph.as_ref().filter(|_| fill_at > 0) {
        let improver = OnTheWay {
            block_ways: &block_ways,
            swaths: s,
            graph,
            after_field,
        };
        saved = improver.improve(&mut order, &mut fill_at);
    }
    if let Some(&(method, _, _)) = reports.first() {
        route.sequence = SequenceReport {
            method,
            cost_m: reports.iter().map(|r| r.1).sum::<f64>() - saved,
            fill_cost_m: reports.iter().filter(|r| r.2).map(|r| r.1).sum::<f64>() - saved,
        };
    }

    // The steps: headland passes first, the blocks, headland passes last.
    let mut steps = pass_steps;
    let mut returns_after: Vec<usize> = Vec::new(); // steps after which the machine drives back
    for &(b, wi, returns) in &order {
        let Some(w) = block_ways.get(b).and_then(|w| w.get(wi)) else {
            continue;
        };
        route.block_order.push(b);
        route.turning_m += w.turning_m;
        let mut reversed = w.first_reversed;
        for &id in &w.swaths {
            steps.push(RouteStep::Swath {
                swath: id,
                reversed,
                block: b,
            });
            position = Some(if reversed {
                s[id].centre.start
            } else {
                s[id].centre.end
            });
            reversed = !reversed;
        }
        if returns {
            returns_after.push(steps.len() - 1);
        }
    }
    match settings.headland_order {
        HeadlandOrder::Last => {
            append_headland_passes(&mut steps, passes, graph, position, false, |_| true);
        }
        HeadlandOrder::First => {
            append_headland_passes(&mut steps, passes, graph, position, false, |p| {
                !not_island(p)
            });
        }
    }

    // The connections into each step that starts a block or a pass, and to the exit.
    let mut moves: Vec<(usize, Coord, Coord)> = Vec::new(); // (step, from, to)
    let mut backs: Vec<Option<Coord>> = Vec::new(); // where a drive back along a swath began
    let mut at = settings.entrance;
    let mut back: Option<Coord> = None;
    let mut last_block: Option<usize> = None;
    for (k, step) in steps.iter().enumerate() {
        let (start, end, block) = step_ends(step, s, passes, at);
        if let (Some(from), Some(start)) = (at, start) {
            let same_block = block.is_some() && block == last_block;
            if !same_block {
                moves.push((k, from, start));
                backs.push(back.take());
            }
        }
        at = end.or(at);
        last_block = block;
        if returns_after.contains(&k) {
            // Back along the swath just worked: the next connection starts at its other end.
            back = at;
            at = start;
        }
    }
    let finish = match (at, settings.exit) {
        (Some(from), Some(to)) => Some((steps.len(), from, to)),
        _ => None,
    };
    let pairs: Vec<Coord> = moves
        .iter()
        .chain(&finish)
        .flat_map(|&(_, a, b)| [a, b])
        .collect();
    let mut ends_free: Vec<usize> = Vec::new();
    if let (Some(e), Some(&(k, from, _))) = (settings.entrance, moves.first()) {
        if k == 0 && from == e {
            ends_free.push(0);
        }
    }
    if finish.is_some() {
        ends_free.push(pairs.len() - 1);
    }
    let joined = graph.connect_with(&pairs, &ends_free);
    // Once every swath is worked, the machine may also drive along their tracks: the way to an
    // obstacle's passes, an island in the inner field.
    let last_swath = steps
        .iter()
        .rposition(|st| matches!(st, RouteStep::Swath { swath, .. } if *swath < fill_from));
    let after_swaths = |k: usize| last_swath.is_none_or(|l| k > l);
    // One search per connection: the lines through the headland graph.
    let lines: Vec<Option<LineString>> = (0..moves.len() + finish.iter().count())
        .map(|i| joined.line(2 * i, 2 * i + 1))
        .collect();
    let needs_tracks = moves
        .iter()
        .chain(&finish)
        .zip(&lines)
        .any(|(&(k, _, _), line)| after_swaths(k) && line.is_none());
    if tracks_graph.is_none() && needs_tracks && last_swath.is_some() {
        tracks_graph = Some(field_tracks());
    }
    let along_tracks = tracks_graph
        .as_ref()
        .map(|g| g.connect_with(&pairs, &ends_free));
    route.connections = vec![None; steps.len()];
    for (i, &(k, from, to)) in moves.iter().chain(&finish).enumerate() {
        if (to - from).x.planar_hypot((to - from).y) < 1e-6 {
            continue;
        }
        let found = lines[i].clone().or_else(|| {
            along_tracks
                .as_ref()
                .filter(|_| after_swaths(k))
                .and_then(|t| t.line(2 * i, 2 * i + 1))
        });
        let found = match (found, backs.get(i).copied().flatten()) {
            (Some(line), Some(b)) => {
                let mut pts = vec![b];
                pts.extend(line.0);
                Some(LineString::new(pts))
            }
            (found, _) => found,
        };
        let c = match found {
            Some(line) => Connection {
                line,
                straight: false,
            },
            None => Connection {
                line: LineString::new(vec![from, to]),
                straight: true,
            },
        };
        if k < steps.len() {
            route.connections[k] = Some(c);
        } else {
            route.finish = Some(c);
        }
    }
    route.steps = steps;
    route
}

/// The block order and the way of each block, and for each block and way of the order the way
/// in `block_ways` it stands for and whether it ends by driving back along its last swath.
///
/// Up to [`nearest::MAX_SEQUENCED_WAYS`] ways in all, and where their connections' searches
/// are within [`nearest::MAX_SEQUENCE_SEARCH_WORK`], the order is sequenced
/// ([`sequence::solve`]) over the connections along the headland graph; beyond, it is the plain
/// [`nearest::nearest_order`].
fn sequence_blocks(
    block_ways: &[Vec<BlockWay>],
    s: &[crate::swath::Swath],
    position: Option<Coord>,
    between: &Between<'_>,
) -> (sequence::Sequence, Vec<Vec<(usize, bool)>>) {
    let seed = between.settings.seed;
    let ways: usize = block_ways.iter().map(Vec::len).sum();
    let plain = (ways <= nearest::MAX_SEQUENCED_WAYS)
        .then(|| build_problem(block_ways, s, position, between, false))
        .flatten();
    let Some(plain) = plain else {
        let own = block_ways
            .iter()
            .map(|w| (0..w.len()).map(|wi| (wi, false)).collect())
            .collect();
        return (nearest::nearest_order(block_ways, s, position), own);
    };
    let solution = sequence::solve(&plain.problem, seed);
    if solution.cost < CROSSING_PENALTY_M {
        return (solution, plain.ways);
    }
    // Some block leaves the machine where the headland offers no way on: let a block also end
    // by driving back along its last swath, worked by then, to its other end.
    let second = build_problem(block_ways, s, position, between, true)
        .map(|returning| (sequence::solve(&returning.problem, seed), returning.ways));
    match second {
        Some((second, ways)) if second.cost < solution.cost => (second, ways),
        _ => (solution, plain.ways),
    }
}

/// Each block's pattern (the cheapest of `settings.orders` by the mean turning of its four
/// ways, turns that do not fit the headland weighed more; the first on a tie) and its ways in
/// that pattern, with their turns' lengths by the turn model.
fn cheapest_ways(
    swaths: &Swaths,
    blocks: &Blocks,
    settings: &RouteSettings,
) -> (Vec<String>, Vec<Vec<BlockWay>>) {
    let turns = TurnLengths::of_machine(settings.turn_radius, settings.reverse);
    let weighed = turns.within(settings.headland_m);
    let mut names = Vec::with_capacity(blocks.blocks.len());
    let mut block_ways = Vec::with_capacity(blocks.blocks.len());
    for block in &blocks.blocks {
        let mut best: Option<(f64, &SwathOrder)> = None;
        for order in &settings.orders {
            let one = std::slice::from_ref(order);
            let mean = block_turning_m(&block.swaths, &swaths.swaths, one, weighed);
            if best.is_none_or(|b| mean < b.0 - 1e-9) {
                best = Some((mean, order));
            }
        }
        let (name, w) = best.map_or((String::new(), Vec::new()), |(_, order)| {
            (
                order.name(),
                ways(&block.swaths, &swaths.swaths, order, turns),
            )
        });
        names.push(name);
        block_ways.push(w);
    }
    (names, block_ways)
}

/// The block sequence problem [`plan_route`] solves first: the field's blocks (those that fill
/// what they leave are sequenced after them), each block's four ways in its pattern, connections along the headland from where the work starts (the entrance, or where
/// the headland passes end when they come first). For checking the sequence against an
/// exhaustive search. `None` where its connections' searches would exceed
/// [`nearest::MAX_SEQUENCE_SEARCH_WORK`] (the route then orders the blocks by nearest entry).
pub fn block_sequence_problem(
    swaths: &Swaths,
    blocks: &Blocks,
    passes: &[HeadlandPass],
    settings: &RouteSettings,
) -> Option<SequenceProblem> {
    let graph = headland_graph(passes, settings);
    let mut position = settings.entrance;
    if settings.headland_order == HeadlandOrder::First {
        position =
            append_headland_passes(&mut Vec::new(), passes, &graph, position, true, not_island);
    }
    let (_, mut block_ways) = cheapest_ways(swaths, blocks, settings);
    // The field's blocks come first in `blocks` (see `cluster_swaths`).
    let fill_from = swaths.first_fill_swath();
    block_ways.truncate(
        blocks
            .blocks
            .iter()
            .take_while(|b| b.swaths.iter().any(|&i| i < fill_from))
            .count(),
    );
    let unlimited: Vec<usize> = if position.is_some() { vec![0] } else { vec![] };
    let finish_on_headland = finishes_on_headland(&graph, passes, settings);
    let between = Between {
        graph: &graph,
        unlimited: &unlimited,
        finish_on_headland,
        settings,
    };
    build_problem(&block_ways, &swaths.swaths, position, &between, false).map(|p| p.problem)
}

/// What the connections of the block sequence problem go by: the headland graph, the points
/// that join it from anywhere (of index in `unlimited`), whether the work finishes on the
/// headland, and the route's settings (the machine's turns between near blocks).
#[derive(Clone, Copy)]
struct Between<'a> {
    graph: &'a HeadlandGraph,
    unlimited: &'a [usize],
    finish_on_headland: bool,
    settings: &'a RouteSettings,
}

/// The block sequence problem, and for each block and way of the problem the way of the block
/// it stands for and whether it ends by driving back along its last swath.
struct Problem {
    problem: SequenceProblem,
    ways: Vec<Vec<(usize, bool)>>,
}

/// Builds the block sequence problem: the points (where the work starts from, then each way's
/// entry and exit), the ways, and the connection costs through the headland graph, straight at
/// [`CROSSING_PENALTY_M`] where it offers no way. With `returning`, each way also comes in a
/// variant that drives back along its last swath and leaves from its other end. `None` where
/// the searches for the costs could take more than [`nearest::MAX_SEQUENCE_SEARCH_WORK`].
fn build_problem(
    block_ways: &[Vec<BlockWay>],
    s: &[crate::swath::Swath],
    position: Option<Coord>,
    between: &Between<'_>,
    returning: bool,
) -> Option<Problem> {
    let Between {
        graph,
        unlimited,
        finish_on_headland,
        settings,
    } = *between;
    let mut points: Vec<Coord> = vec![position.unwrap_or_default()];
    let mut problem_ways: Vec<Vec<Way>> = Vec::with_capacity(block_ways.len());
    let mut ways: Vec<Vec<(usize, bool)>> = Vec::with_capacity(block_ways.len());
    for wlist in block_ways {
        let mut list = Vec::with_capacity(wlist.len());
        let mut which = Vec::with_capacity(wlist.len());
        for (wi, w) in wlist.iter().enumerate() {
            let (Some(entry), Some(exit), Some(last)) = (
                w.entry(s),
                w.exit(s),
                w.swaths.last().and_then(|&i| s.get(i)),
            ) else {
                continue;
            };
            let entry = point_id(&mut points, entry);
            let exit_id = point_id(&mut points, exit);
            list.push(Way {
                entry,
                exit: exit_id,
                cost: w.turning_m,
            });
            which.push((wi, false));
            if returning {
                let other = if exit == last.centre.end {
                    last.centre.start
                } else {
                    last.centre.end
                };
                list.push(Way {
                    entry,
                    exit: point_id(&mut points, other),
                    cost: w.turning_m + last.length(),
                });
                which.push((wi, true));
            }
        }
        problem_ways.push(list);
        ways.push(which);
    }
    let n = points.len();
    let connections = graph.connect_with(&points, unlimited);
    if n.saturating_mul(connections.node_count()) > nearest::MAX_SEQUENCE_SEARCH_WORK {
        return None;
    }
    // Connection costs from every exit (and the start) to every entry.
    let mut is_exit = vec![false; n];
    let mut is_entry = vec![false; n];
    for w in problem_ways.iter().flatten() {
        is_exit[w.exit] = true;
        is_entry[w.entry] = true;
    }
    let entries: Vec<usize> = (0..n).filter(|&i| is_entry[i]).collect();
    let facing = facing_out(&points, s);
    let mut connection = vec![CROSSING_PENALTY_M * 10.0; n * n];
    let mut from_start = vec![0.0; n];
    // Where the blocks end the machine drives on to the headland passes or the exit: an exit
    // point the headland does not reach costs a crossing.
    let to_finish: Vec<f64> = (0..n)
        .map(|i| {
            if !is_exit[i] || !finish_on_headland || connections.is_joined(i) {
                0.0
            } else {
                CROSSING_PENALTY_M
            }
        })
        .collect();
    for from in 0..n {
        let start = from == 0;
        if !(is_exit[from] || start && position.is_some()) {
            continue;
        }
        let d = connections.distances(from, &entries);
        for (&to, d) in entries.iter().zip(d) {
            let cost = match d {
                Some(d) if start => d,
                Some(d) => d.max(turn_floor(
                    (points[from], facing[from]),
                    (points[to], facing[to]),
                    d,
                    settings.turn_radius,
                )),
                None => {
                    let v = points[to] - points[from];
                    v.x.planar_hypot(v.y) + CROSSING_PENALTY_M
                }
            };
            if start {
                from_start[to] = cost;
            } else {
                connection[from * n + to] = cost;
            }
        }
    }
    Some(Problem {
        problem: SequenceProblem {
            ways: problem_ways,
            points: n,
            connection,
            from_start,
            to_finish,
            precedence: turns_onto::precedence(block_ways, s, settings.width, settings.turn_radius),
        },
        ways,
    })
}

/// The index of a point in `points`, added if new.
fn point_id(points: &mut Vec<Coord>, p: Coord) -> usize {
    match points.iter().skip(1).position(|&q| q == p) {
        Some(i) => i + 1,
        None => {
            points.push(p);
            points.len() - 1
        }
    }
}

/// Where a step starts and ends (a closed pass starts and ends at its point nearest to where
/// the machine is), and the block of a swath step.
fn step_ends(
    step: &RouteStep,
    s: &[crate::swath::Swath],
    passes: &[HeadlandPass],
    at: Option<Coord>,
) -> (Option<Coord>, Option<Coord>, Option<usize>) {
    match *step {
        RouteStep::Swath {
            swath,
            reversed,
            block,
        } => match s.get(swath) {
            Some(w) if reversed => (Some(w.centre.end), Some(w.centre.start), Some(block)),
            Some(w) => (Some(w.centre.start), Some(w.centre.end), Some(block)),
            None => (None, None, Some(block)),
        },
        RouteStep::HeadlandPass { pass, reversed } => match passes.get(pass) {
            Some(p) if p.closed => {
                let (_, q) = nearest_on_ring(&p.line, at);
                (q, q, None)
            }
            Some(p) => {
                let (first, last) = (p.line.0.first().copied(), p.line.0.last().copied());
                if reversed {
                    (last, first, None)
                } else {
                    (first, last, None)
                }
            }
            None => (None, None, None),
        },
    }
}

/// Whether a pass is reached from the field's headland: not one round an obstacle, an island in
/// the inner field. With the headland first, those come after the swaths all the same: the
/// machine reaches them along the swaths it has worked rather than through standing crop.
/// Whether the blocks should end where the headland graph reaches: when an exit or the passes
/// round obstacles come after them. (Passes round the field that come last are reached along
/// the worked swaths' tracks from wherever the blocks end.)
fn finishes_on_headland(
    graph: &HeadlandGraph,
    passes: &[HeadlandPass],
    settings: &RouteSettings,
) -> bool {
    !graph.is_empty() && (settings.exit.is_some() || passes.iter().any(|p| !not_island(p)))
}

/// Whether the blocks that fill what the field's leave should end where the graph along the
/// headland and the worked swaths' tracks reaches: when an exit or any passes come after them.
fn fill_finishes_on_headland(passes: &[HeadlandPass], settings: &RouteSettings) -> bool {
    let passes_after = match settings.headland_order {
        HeadlandOrder::Last => !passes.is_empty(),
        HeadlandOrder::First => passes.iter().any(|p| !not_island(p)),
    };
    settings.exit.is_some() || passes_after
}

fn not_island(p: &HeadlandPass) -> bool {
    p.around != PassAround::Obstacle
}

/// Appends the headland passes `which` selects, outermost or innermost first, each part
/// nearest-first, and returns where the machine ends up. `graph` is the headland graph of
/// `passes`, whose index of their segments finds the nearest passes.
fn append_headland_passes(
    steps: &mut Vec<RouteStep>,
    passes: &[HeadlandPass],
    graph: &HeadlandGraph,
    mut position: Option<Coord>,
    outermost_first: bool,
    which: impl Fn(&HeadlandPass) -> bool,
) -> Option<Coord> {
    let mut order: Vec<usize> = (0..passes.len()).filter(|&i| which(&passes[i])).collect();
    if outermost_first {
        order.shared_sort_by_key(|&i| passes[i].index);
    } else {
        order.shared_sort_by_key(|&i| std::cmp::Reverse(passes[i].index));
    }
    let mut k = 0;
    while k < order.len() {
        // Passes with the same index (parts split at necks): nearest first.
        let index = passes[order[k]].index;
        let mut end = k;
        while end < order.len() && passes[order[end]].index == index {
            end += 1;
        }
        let mut group = NearestFirst::new(&order[k..end], passes);
        while let Some((pass, reversed, end)) = group.next_from(position, graph) {
            steps.push(RouteStep::HeadlandPass { pass, reversed });
            position = end.or(position);
        }
        k = end;
    }
    position
}

/// The passes of one group (the same index) taken nearest-first: the next is the one of least
/// distance from the machine, the first in the group's order among equals (a closed pass by its
/// nearest point, an open one by its nearer end, that one first among equals).
struct NearestFirst<'a> {
    passes: &'a [HeadlandPass],
    /// The group's passes, in its order.
    members: &'a [usize],
    /// Each pass's place in the group, if it is in it.
    place: Vec<Option<usize>>,
    taken: Vec<bool>,
    left: usize,
    /// The pick at which each member was last looked at (so each is costed once a pick).
    seen: Vec<usize>,
    pick: usize,
    /// Members the graph does not hold (fewer than two points): looked at every pick.
    unindexed: Vec<usize>,
}

/// A candidate: its distance, place in the group and option, and the step it makes.
type Candidate = (f64, usize, usize, bool, Option<Coord>);

impl<'a> NearestFirst<'a> {
    fn new(members: &'a [usize], passes: &'a [HeadlandPass]) -> Self {
        let mut place = vec![None; passes.len()];
        for (g, &i) in members.iter().enumerate() {
            place[i] = Some(g);
        }
        let unindexed = (0..members.len())
            .filter(|&g| passes[members[g]].line.0.len() < 2)
            .collect();
        NearestFirst {
            passes,
            members,
            place,
            taken: vec![false; members.len()],
            left: members.len(),
            seen: vec![usize::MAX; members.len()],
            pick: 0,
            unindexed,
        }
    }

    /// The ways to enter member `g` from `position`: (distance, reversed, where it ends).
    fn options(&self, g: usize, position: Option<Coord>) -> Vec<(f64, bool, Option<Coord>)> {
        let p = &self.passes[self.members[g]];
        if p.closed {
            let (d, q) = nearest_on_ring(&p.line, position);
            vec![(d, false, q)]
        } else {
            let (Some(&first), Some(&last)) = (p.line.0.first(), p.line.0.last()) else {
                return Vec::new();
            };
            let d = |q: Coord| position.map_or(0.0, |p| distance(p, q));
            vec![(d(first), false, Some(last)), (d(last), true, Some(first))]
        }
    }

    /// Weighs member `g` against the best so far.
    fn weigh(&mut self, g: usize, position: Option<Coord>, best: &mut Option<Candidate>) {
        if self.taken[g] || self.seen[g] == self.pick {
            return;
        }
        self.seen[g] = self.pick;
        for (k, (d, reversed, end)) in self.options(g, position).into_iter().enumerate() {
            let better = best.is_none_or(|(bd, bg, bk, ..)| d < bd || d == bd && (g, k) < (bg, bk));
            if better {
                *best = Some((d, g, k, reversed, end));
            }
        }
    }

    /// The next pass from `position`: (pass, reversed, where it ends); `None` once all are taken.
    fn next_from(
        &mut self,
        position: Option<Coord>,
        graph: &HeadlandGraph,
    ) -> Option<(usize, bool, Option<Coord>)> {
        if self.left == 0 {
            return None;
        }
        self.pick += 1;
        let mut best: Option<Candidate> = None;
        for u in 0..self.unindexed.len() {
            self.weigh(self.unindexed[u], position, &mut best);
        }
        if let Some(p) = position {
            // Segments nearest first: once they are farther than the best pass (beyond rounding),
            // no pass nearer or as near is left unseen.
            for (pass, d) in graph.passes_by_distance(p) {
                if best.is_some_and(|(bd, ..)| d > bd + 1e-9 * bd.max(1.0)) {
                    break;
                }
                if let Some(g) = self.place.get(pass).copied().flatten() {
                    self.weigh(g, position, &mut best);
                }
            }
        }
        if best.is_none_or(|(d, ..)| d.is_nan()) || position.is_none() {
            // Without a position every pass is as near; and a graph of other passes than these
            // would leave some unseen: every pass is weighed.
            for g in 0..self.members.len() {
                self.weigh(g, position, &mut best);
            }
        }
        let (_, g, _, reversed, end) = best?;
        self.taken[g] = true;
        self.left -= 1;
        Some((self.members[g], reversed, end))
    }
}

#[inline]
fn distance(a: Coord, b: Coord) -> f64 {
    (a.x - b.x).planar_hypot(a.y - b.y)
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::decompose::cluster_swaths;
    use crate::headland::{HeadlandOrder, HeadlandPass};
    use crate::swath::generate;
    use geo::{polygon, LineString, MultiPolygon};

    fn boustrophedon(
        swaths: &Swaths,
        blocks: &Blocks,
        passes: &[HeadlandPass],
        order: HeadlandOrder,
        entrance: Option<Coord>,
    ) -> Route {
        let settings = RouteSettings {
            headland_order: order,
            entrance,
            ..RouteSettings::default()
        };
        plan_route(swaths, blocks, passes, &settings)
    }

    /// Asserts that the route works each of `count` swaths exactly once.
    fn assert_every_swath_once(route: &Route, count: usize) {
        let mut seen: Vec<usize> = route
            .steps
            .iter()
            .filter_map(|s| match s {
                RouteStep::Swath { swath, .. } => Some(*swath),
                _ => None,
            })
            .collect();
        seen.sort_unstable();
        assert_eq!(seen, (0..count).collect::<Vec<_>>());
    }

    #[test]
    fn every_swath_once_and_blocks_all_visited() {
        let field = polygon!(
            exterior: [(x: 0., y: 0.), (x: 60., y: 0.), (x: 60., y: 100.), (x: 0., y: 100.)],
            interiors: [[(x: 20., y: 40.), (x: 40., y: 40.), (x: 40., y: 60.), (x: 20., y: 60.)]],
        );
        let swaths = generate(&MultiPolygon::new(vec![field]), 0.0, 6.0, 6.0).unwrap();
        let blocks = cluster_swaths(&swaths);
        let route = boustrophedon(&swaths, &blocks, &[], HeadlandOrder::Last, None);
        assert_every_swath_once(&route, swaths.swaths.len());
        let mut order = route.block_order.clone();
        order.sort_unstable();
        assert_eq!(order, vec![0, 1, 2, 3]);
    }

    #[test]
    fn many_blocks_are_ordered_nearest_first() {
        // 300 separate strips of two swaths: 1,200 ways, too many to sequence.
        let strips: Vec<geo::Polygon> = (0..300)
            .map(|i| {
                let (x, y) = ((i % 20) as f64 * 30.0, (i / 20) as f64 * 60.0);
                polygon![(x: x, y: y), (x: x + 12., y: y), (x: x + 12., y: y + 40.), (x: x, y: y + 40.)]
            })
            .collect();
        let swaths = generate(&MultiPolygon::new(strips), 0.0, 6.0, 6.0).unwrap();
        let blocks = cluster_swaths(&swaths);
        assert_eq!(blocks.blocks.len(), 300);
        let route = boustrophedon(&swaths, &blocks, &[], HeadlandOrder::Last, None);
        assert_eq!(route.sequence.method, SequenceMethod::NearestNeighbour);
        assert_every_swath_once(&route, swaths.swaths.len());
        // Each block's two swaths one after the other, the second driven back.
        for pair in route.steps.chunks(2) {
            match pair {
                [RouteStep::Swath {
                    block: a,
                    reversed: x,
                    ..
                }, RouteStep::Swath {
                    block: b,
                    reversed: y,
                    ..
                }] => {
                    assert_eq!(a, b);
                    assert_ne!(x, y);
                }
                _ => panic!("two swaths a block"),
            }
        }
    }

    #[test]
    fn blocks_whose_connection_searches_are_too_large_are_ordered_nearest_first() {
        // Six strips of two swaths (four ways each, from and to their 24 corners: 25 points
        // with the start), among open headland pieces 1 m long on a 20 m grid, too far apart
        // to hop between: two nodes each.
        let strips: Vec<geo::Polygon> = (0..6)
            .map(|i| {
                let x = 100.0 + 40.0 * i as f64;
                polygon![(x: x, y: 100.), (x: x + 12., y: 100.), (x: x + 12., y: 140.), (x: x, y: 140.)]
            })
            .collect();
        let swaths = generate(&MultiPolygon::new(strips), 0.0, 6.0, 6.0).unwrap();
        let blocks = cluster_swaths(&swaths);
        let pieces = |count: usize| -> Vec<HeadlandPass> {
            (0..count)
                .map(|k| {
                    let (x, y) = ((k % 300) as f64 * 20.0, (k / 300) as f64 * 20.0 + 3.0);
                    HeadlandPass {
                        index: 1,
                        line: LineString::from(vec![(x, y), (x + 1.0, y)]),
                        closed: false,
                        around: crate::headland::PassAround::Field,
                    }
                })
                .collect()
        };
        // 25 points and 2,000 nodes: sequenced.
        let few = pieces(1_000);
        let route = boustrophedon(&swaths, &blocks, &few, HeadlandOrder::Last, None);
        assert_ne!(route.sequence.method, SequenceMethod::NearestNeighbour);
        // 25 points and 180,000 nodes: 4.5 million, beyond the searches' limit.
        let many = pieces(90_000);
        assert!(25 * 2 * many.len() > nearest::MAX_SEQUENCE_SEARCH_WORK);
        let route = boustrophedon(&swaths, &blocks, &many, HeadlandOrder::Last, None);
        assert_eq!(route.sequence.method, SequenceMethod::NearestNeighbour);
        assert_every_swath_once(&route, swaths.swaths.len());
    }

    #[test]
    fn open_passes_are_entered_at_the_nearer_end() {
        let passes = vec![HeadlandPass {
            index: 1,
            line: LineString::from(vec![(0.0, 3.0), (100.0, 3.0)]),
            closed: false,
            around: crate::headland::PassAround::Field,
        }];
        let inner = polygon![(x: 0., y: 6.), (x: 100., y: 6.), (x: 100., y: 50.), (x: 0., y: 50.)];
        let swaths = generate(&MultiPolygon::new(vec![inner]), 0.0, 6.0, 6.0).unwrap();
        let blocks = cluster_swaths(&swaths);
        // Starting near the eastern end, the pass is driven west.
        let route = boustrophedon(
            &swaths,
            &blocks,
            &passes,
            HeadlandOrder::First,
            Some(geo::coord! { x: 99.0, y: 0.0 }),
        );
        assert_eq!(
            route.steps[0],
            RouteStep::HeadlandPass {
                pass: 0,
                reversed: true
            }
        );
    }

    #[test]
    fn headland_passes_come_last_innermost_first() {
        let ring = |d: f64| {
            LineString::from(vec![
                (d, d),
                (100.0 - d, d),
                (100.0 - d, 100.0 - d),
                (d, 100.0 - d),
                (d, d),
            ])
        };
        let pass = |index: usize, line: LineString| HeadlandPass {
            index,
            line,
            closed: true,
            around: crate::headland::PassAround::Field,
        };
        let passes = vec![pass(1, ring(3.0)), pass(2, ring(9.0))];
        let inner =
            polygon![(x: 12., y: 12.), (x: 88., y: 12.), (x: 88., y: 88.), (x: 12., y: 88.)];
        let swaths = generate(&MultiPolygon::new(vec![inner]), 0.0, 6.0, 6.0).unwrap();
        let blocks = cluster_swaths(&swaths);
        let route = boustrophedon(&swaths, &blocks, &passes, HeadlandOrder::Last, None);
        let tail: Vec<_> = route.steps[route.steps.len() - 2..].to_vec();
        assert_eq!(
            tail,
            vec![
                RouteStep::HeadlandPass {
                    pass: 1,
                    reversed: false
                },
                RouteStep::HeadlandPass {
                    pass: 0,
                    reversed: false
                }
            ]
        );
        // Harvesting: outermost first, then the swaths.
        let route = boustrophedon(&swaths, &blocks, &passes, HeadlandOrder::First, None);
        assert_eq!(
            route.steps[..2].to_vec(),
            vec![
                RouteStep::HeadlandPass {
                    pass: 0,
                    reversed: false
                },
                RouteStep::HeadlandPass {
                    pass: 1,
                    reversed: false
                }
            ]
        );
        assert_eq!(route.steps.len(), 2 + swaths.swaths.len());
        assert!(matches!(route.steps[2], RouteStep::Swath { .. }));
    }
}
