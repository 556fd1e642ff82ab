//! Fill worked on the way: a block that fills what the field's blocks leave (a corner, the
//! strip between swath ends and the passes) lies beside the block that left it. Sequenced after
//! all the field's blocks, the machine would come back for each; worked between two field
//! blocks where it lies on the way, it costs a short detour along the headland.
//!
//! After the field's blocks and then the fill's are sequenced, each fill block is moved, while
//! that saves driving, from its place after the field's blocks to the gap between two blocks
//! where it costs least. Only ways along the headland passes count there (the field's swath
//! tracks are crop still standing then); after the field's blocks, the worked swaths' tracks
//! also count, as when the fill was sequenced.

use super::headland_graph::{Connections, HeadlandGraph, CROSSING_PENALTY_M};
use super::pattern::BlockWay;
use crate::geometry::PlanarHypot;
use crate::swath::Swath;
use geo::Coord;
use std::collections::HashMap;

/// A block in the order: its index, the way it is worked (into its ways) and whether it ends by
/// driving back along its last swath.
pub(super) type Placed = (usize, usize, bool);

/// The gaps nearest a fill block, by the straight distance from the block's entry to where the
/// gap starts, tried for it: a detour to a far block never pays.
const GAPS_TRIED: usize = 4;

/// The order and the graphs it is driven on.
pub(super) struct OnTheWay<'a> {
    /// Each block's ways.
    pub block_ways: &'a [Vec<BlockWay>],
    /// The swaths.
    pub swaths: &'a [Swath],
    /// The headland passes: the ways between the field's blocks.
    pub graph: &'a HeadlandGraph,
    /// The passes and the field's swath tracks: the ways once the field's blocks are worked.
    pub after_field: &'a HeadlandGraph,
}

/// Where a placed block is entered and left (after driving back, where it does).
fn ends(ways: &[Vec<BlockWay>], s: &[Swath], (b, wi, returns): Placed) -> Option<(Coord, Coord)> {
    let w = ways.get(b)?.get(wi)?;
    let (entry, exit) = (w.entry(s)?, w.exit(s)?);
    if !returns {
        return Some((entry, exit));
    }
    let last = s.get(*w.swaths.last()?)?;
    let back = if exit == last.centre.end {
        last.centre.start
    } else {
        last.centre.end
    };
    Some((entry, back))
}

/// A placed block's own cost: its turns, and the drive back along its last swath where it
/// returns.
fn own_cost(ways: &[Vec<BlockWay>], s: &[Swath], (b, wi, returns): Placed) -> f64 {
    let Some(w) = ways.get(b).and_then(|w| w.get(wi)) else {
        return 0.0;
    };
    let back = if returns {
        w.swaths
            .last()
            .and_then(|&i| s.get(i))
            .map_or(0.0, Swath::length)
    } else {
        0.0
    };
    w.turning_m + back
}

/// Distances between the points of the order, each searched once.
struct Table<'g> {
    ids: HashMap<(u64, u64), usize>,
    on_headland: Connections<'g>,
    after_field: Connections<'g>,
    known: HashMap<(usize, usize, bool), Option<f64>>,
}

impl Table<'_> {
    fn id(&self, p: Coord) -> Option<usize> {
        self.ids.get(&(p.x.to_bits(), p.y.to_bits())).copied()
    }

    /// The way from `a` to `b` along the headland passes (`after_field`: also along the
    /// field's tracks); `None` where there is none.
    fn way(&mut self, a: Coord, b: Coord, after_field: bool) -> Option<f64> {
        if (b - a).x.planar_hypot((b - a).y) < 1e-9 {
            return Some(0.0);
        }
        let (i, j) = (self.id(a)?, self.id(b)?);
        if let Some(&d) = self.known.get(&(i, j, after_field)) {
            return d;
        }
        let c = if after_field {
            &self.after_field
        } else {
            &self.on_headland
        };
        let d = c.distances(i, &[j]).first().copied().flatten();
        self.known.insert((i, j, after_field), d);
        d
    }

    /// As [`way`](Self::way), with a straight crossing at its penalty where there is none.
    fn cost(&mut self, a: Coord, b: Coord, after_field: bool) -> f64 {
        self.way(a, b, after_field).unwrap_or_else(|| {
            let v = b - a;
            v.x.planar_hypot(v.y) + CROSSING_PENALTY_M
        })
    }
}

impl OnTheWay<'_> {
    /// Moves fill blocks from `order[fill_from..]` into the gaps between `order[..fill_from]`
    /// where that saves driving (see the module). `start` is where the machine is before the
    /// first block. Gives the saving, metres (never negative).
    pub(super) fn improve(
        &self,
        order: &mut Vec<Placed>,
        fill_from: &mut usize,
        start: Option<Coord>,
    ) -> f64 {
        if *fill_from == 0 || *fill_from >= order.len() {
            return 0.0;
        }
        let mut table = self.table(order);
        let mut saved = 0.0;
        // Each move takes one block out of the tail: at most as many rounds as blocks there.
        for _ in *fill_from..order.len() {
            let Some((from, to, placed, gain)) =
                self.best_move(order, *fill_from, start, &mut table)
            else {
                break;
            };
            order.remove(from);
            order.insert(to, placed);
            *fill_from += 1;
            saved += gain;
        }
        saved
    }

    /// Every entry and exit of the blocks placed and of every way of the fill's blocks, joined
    /// to both graphs.
    fn table<'g>(&'g self, order: &[Placed]) -> Table<'g> {
        let mut points = Vec::new();
        let mut ids = HashMap::new();
        let mut add = |p: Coord| {
            ids.entry((p.x.to_bits(), p.y.to_bits()))
                .or_insert_with(|| {
                    points.push(p);
                    points.len() - 1
                });
        };
        for &(b, wi, returns) in order {
            for placed in self.variants(b).chain([(b, wi, returns)]) {
                if let Some((entry, exit)) = ends(self.block_ways, self.swaths, placed) {
                    add(entry);
                    add(exit);
                }
            }
        }
        let on_headland = self.graph.connect(&points);
        let after_field = self.after_field.connect(&points);
        Table {
            ids,
            on_headland,
            after_field,
            known: HashMap::new(),
        }
    }

    /// Every way block `b` may be worked: each of its ways, ending at its exit or driving back.
    fn variants(&self, b: usize) -> impl Iterator<Item = Placed> {
        let n = self.block_ways.get(b).map_or(0, Vec::len);
        (0..n).flat_map(move |wi| [(b, wi, false), (b, wi, true)])
    }

    /// The move of one fill block from the tail into a gap among the blocks before it that
    /// saves most: (its place now, its new place, how it is worked there, the saving).
    fn best_move(
        &self,
        order: &[Placed],
        fill_from: usize,
        start: Option<Coord>,
        table: &mut Table,
    ) -> Option<(usize, usize, Placed, f64)> {
        let ends_of = |p: Placed| ends(self.block_ways, self.swaths, p);
        let mut best: Option<(usize, usize, Placed, f64)> = None;
        for from in fill_from..order.len() {
            let here = order[from];
            let Some((entry, exit)) = ends_of(here) else {
                continue;
            };
            let before = if from == 0 {
                start
            } else {
                ends_of(order[from - 1]).map(|e| e.1)
            };
            let after = order.get(from + 1).and_then(|&p| ends_of(p)).map(|e| e.0);
            // What leaving it out of the tail saves.
            let mut saving = own_cost(self.block_ways, self.swaths, here);
            if let Some(a) = before {
                saving += table.cost(a, entry, true);
                if let Some(c) = after {
                    saving += table.cost(exit, c, true) - table.cost(a, c, true);
                }
            } else if let Some(c) = after {
                saving += table.cost(exit, c, true);
            }
            for (to, placed, cost) in self.insertions(order, fill_from, here.0, table) {
                let gain = saving - cost;
                if gain > 1e-6 && best.as_ref().is_none_or(|b| gain > b.3) {
                    best = Some((from, to, placed, gain));
                }
            }
        }
        best
    }

    /// The cheapest ways to work fill block `b` in each of the gaps nearest it among
    /// `order[..fill_from]`: (the place it would take, how it is worked, the cost it adds).
    /// A gap is open only where both ways to and from the block run along the headland.
    fn insertions(
        &self,
        order: &[Placed],
        fill_from: usize,
        b: usize,
        table: &mut Table,
    ) -> Vec<(usize, Placed, f64)> {
        let ends_of = |p: Placed| ends(self.block_ways, self.swaths, p);
        let Some(centre) = self
            .variants(b)
            .next()
            .and_then(ends_of)
            .map(|(entry, _)| entry)
        else {
            return Vec::new();
        };
        // Gap g lies between order[g - 1] and order[g].
        let mut gaps: Vec<(usize, f64, Coord, Coord)> = (1..fill_from)
            .filter_map(|g| {
                let a = ends_of(order[g - 1])?.1;
                let c = ends_of(order[g])?.0;
                let v = a - centre;
                Some((g, v.x.planar_hypot(v.y), a, c))
            })
            .collect();
        gaps.sort_by(|x, y| x.1.total_cmp(&y.1).then(x.0.cmp(&y.0)));
        gaps.truncate(GAPS_TRIED);
        let mut out = Vec::new();
        for (g, _, a, c) in gaps {
            let direct = table.cost(a, c, false);
            let mut cheapest: Option<(Placed, f64)> = None;
            for placed in self.variants(b) {
                let Some((entry, exit)) = ends_of(placed) else {
                    continue;
                };
                let (Some(to), Some(on)) = (table.way(a, entry, false), table.way(exit, c, false))
                else {
                    continue;
                };
                let cost = to + on - direct + own_cost(self.block_ways, self.swaths, placed);
                if cheapest.as_ref().is_none_or(|x| cost < x.1 - 1e-9) {
                    cheapest = Some((placed, cost));
                }
            }
            if let Some((placed, cost)) = cheapest {
                out.push((g, placed, cost));
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use crate::decompose::cluster_swaths;
    use crate::headland::{HeadlandOrder, HeadlandPass, PassAround};
    use crate::route::{plan_route, RouteSettings};
    use crate::swath::{generate, SwathArea};
    use geo::{coord, polygon, LineString, MultiPolygon};

    /// Two blocks 200 m apart along a 400 m field, and a strip left beside the western one:
    /// worked between the two, not after the eastern one (which would take the machine 200 m
    /// back and forth along the headland).
    #[test]
    fn a_fill_block_beside_a_block_is_worked_on_the_way() {
        let ring = LineString::from(vec![
            (3.0, 3.0),
            (397.0, 3.0),
            (397.0, 97.0),
            (3.0, 97.0),
            (3.0, 3.0),
        ]);
        let passes = vec![HeadlandPass {
            index: 1,
            line: ring,
            closed: true,
            around: PassAround::Field,
        }];
        let west = polygon![(x: 12., y: 12.), (x: 96., y: 12.), (x: 96., y: 88.), (x: 12., y: 88.)];
        let east =
            polygon![(x: 300., y: 12.), (x: 384., y: 12.), (x: 384., y: 88.), (x: 300., y: 88.)];
        let inner = MultiPolygon::new(vec![west, east]);
        let mut swaths = generate(&inner, 0.0, 6.0, 6.0).unwrap();
        swaths.areas.push(SwathArea {
            swaths: 0..swaths.swaths.len(),
            bearing: 0.0,
            region: None,
            area: inner,
            fill: false,
        });
        let strip =
            polygon![(x: 99., y: 12.), (x: 105., y: 12.), (x: 105., y: 88.), (x: 99., y: 88.)];
        let mut piece = generate(&MultiPolygon::new(vec![strip.clone()]), 0.0, 6.0, 6.0).unwrap();
        assert_eq!(piece.swaths.len(), 1);
        piece.areas.push(SwathArea {
            swaths: 0..1,
            bearing: 0.0,
            region: None,
            area: MultiPolygon::new(vec![strip]),
            fill: true,
        });
        swaths.append(piece);
        let blocks = cluster_swaths(&swaths);
        assert_eq!(blocks.blocks.len(), 3);
        let settings = RouteSettings {
            headland_order: HeadlandOrder::Last,
            entrance: Some(coord! { x: 0.0, y: 0.0 }),
            ..RouteSettings::default()
        };
        let route = plan_route(&swaths, &blocks, &passes, &settings);
        assert_eq!(route.block_order, vec![0, 2, 1], "{:?}", route.sequence);
        // The detour: up or down the strip and on to the eastern block, less the way there.
        assert!(
            route.sequence.fill_cost_m < 100.0,
            "the strip adds {} m",
            route.sequence.fill_cost_m
        );
        assert!(route.connections.iter().flatten().all(|c| !c.straight));
    }
}
