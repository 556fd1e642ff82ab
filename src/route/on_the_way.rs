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

/// A block in the order: its index, the way it is worked (into its ways) and whether it ends by
/// driving back along its last swath.
pub(super) type Placed = (usize, usize, bool);

/// The gaps nearest a fill block, by the straight distance from the block's entry to where the
/// gap starts, tried for it: a detour to a far block never pays.
const GAPS_TRIED: usize = 4;

/// Fill blocks beyond this many stay after the field's blocks: each is weighed against a few
/// dozen ways, and the ways' table is searched through.
const MAX_TAIL: usize = 128;

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
#[inline(never)]
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
    points: Vec<Coord>,
    on_headland: Connections<'g>,
    after_field: Connections<'g>,
    /// The ways searched.
    known: Vec<((usize, usize, bool), Option<f64>)>,
}

impl Table<'_> {
    fn id(&self, p: Coord) -> Option<usize> {
        self.points.iter().position(|&q| q == p)
    }

    /// The way from `a` to `b` along the headland passes (`after_field`: also along the
    /// field's tracks); `None` where there is none.
    #[inline(never)]
    fn way(&mut self, a: Coord, b: Coord, after_field: bool) -> Option<f64> {
        if (b - a).x.planar_hypot((b - a).y) < 1e-9 {
            return Some(0.0);
        }
        let key = (self.id(a)?, self.id(b)?, after_field);
        if let Some(&(_, d)) = self.known.iter().find(|k| k.0 == key) {
            return d;
        }
        let c = if after_field {
            &self.after_field
        } else {
            &self.on_headland
        };
        let d = c.distances(key.0, &[key.1]).first().copied().flatten();
        self.known.push((key, d));
        d
    }

    /// As [`way`](Self::way), with a straight crossing at its penalty where there is none.
    #[inline(never)]
    fn cost(&mut self, a: Coord, b: Coord, after_field: bool) -> f64 {
        self.way(a, b, after_field).unwrap_or_else(|| {
            let v = b - a;
            v.x.planar_hypot(v.y) + CROSSING_PENALTY_M
        })
    }
}

impl OnTheWay<'_> {
    /// Moves fill blocks from `order[fill_from..]` into the gaps between `order[..fill_from]`
    /// where that saves driving (see the module). Gives the saving, metres (never negative).
    pub(super) fn improve(&self, order: &mut Vec<Placed>, fill_from: &mut usize) -> f64 {
        if *fill_from == 0 || *fill_from >= order.len() || order.len() - *fill_from > MAX_TAIL {
            return 0.0;
        }
        let mut table = self.table(order, *fill_from);
        let mut saved = 0.0;
        // Each fill block once, in its order after the field's: the first of the tail is at
        // `fill_from` while it stays, after the blocks moved out before it.
        let mut from = *fill_from;
        while from < order.len() {
            match self.best_move(order, from, *fill_from, &mut table) {
                Some((to, placed, gain)) => {
                    order.remove(from);
                    order.insert(to, placed);
                    *fill_from += 1;
                    from += 1;
                    saved += gain;
                }
                None => from += 1,
            }
        }
        saved
    }

    /// Every entry and exit of the blocks placed and of every way of the fill's blocks (from
    /// `fill_from` on), joined to both graphs.
    fn table<'g>(&'g self, order: &[Placed], fill_from: usize) -> Table<'g> {
        let mut points: Vec<Coord> = Vec::new();
        let mut add = |p: Coord| {
            if !points.contains(&p) {
                points.push(p);
            }
        };
        for (k, &(b, wi, returns)) in order.iter().enumerate() {
            let mut all = if k >= fill_from {
                self.variants(b)
            } else {
                Vec::new()
            };
            all.push((b, wi, returns));
            for placed in all {
                if let Some((entry, exit)) = ends(self.block_ways, self.swaths, placed) {
                    add(entry);
                    add(exit);
                }
            }
        }
        let on_headland = self.graph.connect(&points);
        let after_field = self.after_field.connect(&points);
        Table {
            points,
            on_headland,
            after_field,
            known: Vec::new(),
        }
    }

    /// Every way block `b` may be worked: each of its ways, ending at its exit or driving back.
    fn variants(&self, b: usize) -> Vec<Placed> {
        let n = self.block_ways.get(b).map_or(0, Vec::len);
        let mut out = Vec::with_capacity(2 * n);
        for wi in 0..n {
            out.push((b, wi, false));
            out.push((b, wi, true));
        }
        out
    }

    /// The move of the fill block at `order[from]` (in the tail) into the gap among the blocks
    /// before the tail that saves most, if one saves: (its new place, how it is worked there, the
    /// saving).
    fn best_move(
        &self,
        order: &[Placed],
        from: usize,
        fill_from: usize,
        table: &mut Table,
    ) -> Option<(usize, Placed, f64)> {
        let ends_of = |p: Placed| ends(self.block_ways, self.swaths, p);
        let here = *order.get(from)?;
        let (entry, exit) = ends_of(here)?;
        // The tail follows the field's blocks: there is always a block before it.
        let before = ends_of(*order.get(from.checked_sub(1)?)?).map(|e| e.1);
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
        let mut best: Option<(usize, Placed, f64)> = None;
        for (to, placed, cost) in self.insertions(order, fill_from, here.0, table) {
            let gain = saving - cost;
            if gain > 1e-6 && best.as_ref().is_none_or(|b| gain > b.2) {
                best = Some((to, placed, gain));
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
        let Some((centre, _)) = ends_of((b, 0, false)) else {
            return Vec::new();
        };
        // Gap g lies between order[g - 1] and order[g].
        let gaps = (1..fill_from).filter_map(|g| {
            let a = ends_of(order[g - 1])?.1;
            let c = ends_of(order[g])?.0;
            let v = a - centre;
            Some((g, v.x.planar_hypot(v.y), a, c))
        });
        // The nearest few, nearest first (ties to the earlier gap).
        let mut nearest: Vec<(usize, f64, Coord, Coord)> = Vec::with_capacity(GAPS_TRIED + 1);
        for g in gaps {
            let at = nearest
                .iter()
                .position(|n| g.1 < n.1)
                .unwrap_or(nearest.len());
            if at < GAPS_TRIED {
                nearest.insert(at, g);
                nearest.truncate(GAPS_TRIED);
            }
        }
        let mut out = Vec::new();
        for (g, _, a, c) in nearest {
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
    fn a_fill_block_beside_a_block_is_worked_on_the_way() -> Result<(), crate::PlanError> {
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
        let mut swaths = generate(&inner, 0.0, 6.0, 6.0)?;
        swaths.areas.push(SwathArea {
            swaths: 0..swaths.swaths.len(),
            bearing: 0.0,
            region: None,
            area: inner,
            fill: false,
        });
        let strip =
            polygon![(x: 99., y: 12.), (x: 105., y: 12.), (x: 105., y: 88.), (x: 99., y: 88.)];
        let mut piece = generate(&MultiPolygon::new(vec![strip.clone()]), 0.0, 6.0, 6.0)?;
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
        Ok(())
    }
}
