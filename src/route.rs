//! The route: the order in which swaths and headland passes are worked, and which way each is
//! driven.
//!
//! Inside a block the swaths are worked boustrophedon: line after line, turning back at each end.
//! A block can be entered at either end of its first or its last swath; blocks are taken in
//! nearest-first order from where the machine is, choosing the nearest of those four entries.
//! The headland passes come last, as in seeding (Zhou et al. 2.1), from the innermost out, so
//! the machine finishes on the outermost pass at the field edge; or first, as in harvesting,
//! from the outermost in, opening up the field edge before the swaths. Passes with the same
//! index are taken nearest-first; a closed pass is entered at its point nearest to the machine,
//! an open one at its nearer end.

use crate::decompose::Blocks;
use crate::headland::{HeadlandOrder, HeadlandPass};
use crate::swath::Swaths;
use geo::{Closest, ClosestPoint, Coord, Point};

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

/// The order of work.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Route {
    /// The steps in driving order.
    pub steps: Vec<RouteStep>,
    /// The blocks in the order they are worked.
    pub block_order: Vec<usize>,
}

/// Orders the blocks nearest-first and their swaths boustrophedon, and the headland passes
/// before or after them.
///
/// ```
/// use furrow::{decompose::cluster_swaths, headland::HeadlandOrder, route::{boustrophedon, RouteStep}, swath::generate};
/// use geo::{polygon, MultiPolygon};
///
/// let field = polygon![(x: 0., y: 0.), (x: 30., y: 0.), (x: 30., y: 100.), (x: 0., y: 100.)];
/// let swaths = generate(&MultiPolygon::new(vec![field]), 0.0, 6.0, 6.0)?;
/// let blocks = cluster_swaths(&swaths);
/// let route = boustrophedon(&swaths, &blocks, &[], HeadlandOrder::Last, None);
/// let reversed: Vec<bool> = route.steps.iter().map(|s| match s {
///     RouteStep::Swath { reversed, .. } => *reversed,
///     _ => unreachable!(),
/// }).collect();
/// assert_eq!(reversed, vec![false, true, false, true, false]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn boustrophedon(
    swaths: &Swaths,
    blocks: &Blocks,
    passes: &[HeadlandPass],
    order: HeadlandOrder,
    start: Option<Coord>,
) -> Route {
    let mut route = Route::default();
    let s = &swaths.swaths;
    let mut position = start;
    if order == HeadlandOrder::First {
        position = append_headland_passes(&mut route, passes, position, true);
    }
    let mut position = position.or_else(|| s.first().map(|w| w.centre.start));
    let mut done = vec![false; blocks.blocks.len()];
    for _ in 0..blocks.blocks.len() {
        // The nearest entry of any block not yet worked.
        let mut best: Option<(f64, usize, bool, bool)> = None; // (distance, block, from_last, reversed)
        for (b, block) in blocks.blocks.iter().enumerate() {
            if done[b] {
                continue;
            }
            let (Some(&first), Some(&last)) = (block.swaths.first(), block.swaths.last()) else {
                continue;
            };
            for (from_last, id) in [(false, first), (true, last)] {
                for reversed in [false, true] {
                    let entry = if reversed {
                        s[id].centre.end
                    } else {
                        s[id].centre.start
                    };
                    let d = position.map_or(0.0, |p| distance(p, entry));
                    if best.is_none_or(|(bd, ..)| d < bd) {
                        best = Some((d, b, from_last, reversed));
                    }
                }
            }
        }
        let Some((_, b, from_last, mut reversed)) = best else {
            break;
        };
        done[b] = true;
        route.block_order.push(b);
        let ids = &blocks.blocks[b].swaths;
        let order: Box<dyn Iterator<Item = &usize>> = if from_last {
            Box::new(ids.iter().rev())
        } else {
            Box::new(ids.iter())
        };
        for &id in order {
            route.steps.push(RouteStep::Swath {
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
    }
    if order == HeadlandOrder::Last {
        append_headland_passes(&mut route, passes, position, false);
    }
    route
}

/// Appends the headland passes, outermost or innermost first, each part nearest-first, and
/// returns where the machine ends up.
fn append_headland_passes(
    route: &mut Route,
    passes: &[HeadlandPass],
    mut position: Option<Coord>,
    outermost_first: bool,
) -> Option<Coord> {
    let mut order: Vec<usize> = (0..passes.len()).collect();
    if outermost_first {
        order.sort_by_key(|&i| passes[i].index);
    } else {
        order.sort_by_key(|&i| std::cmp::Reverse(passes[i].index));
    }
    let mut k = 0;
    while k < order.len() {
        // Passes with the same index (parts split at necks): nearest first.
        let index = passes[order[k]].index;
        let mut end = k;
        while end < order.len() && passes[order[end]].index == index {
            end += 1;
        }
        let mut group: Vec<usize> = order[k..end].to_vec();
        while !group.is_empty() {
            // (distance, position in group, reversed, where the pass ends)
            let mut best: Option<(f64, usize, bool, Option<Coord>)> = None;
            for (g, &i) in group.iter().enumerate() {
                let p = &passes[i];
                let options = if p.closed {
                    let (d, q) = nearest_on_ring(&p.line, position);
                    vec![(d, false, q)]
                } else {
                    let (Some(&first), Some(&last)) = (p.line.0.first(), p.line.0.last()) else {
                        continue;
                    };
                    let d = |q: Coord| position.map_or(0.0, |p| distance(p, q));
                    vec![(d(first), false, Some(last)), (d(last), true, Some(first))]
                };
                for (d, reversed, end) in options {
                    if best.is_none_or(|(bd, ..)| d < bd) {
                        best = Some((d, g, reversed, end));
                    }
                }
            }
            let (g, reversed, end) = best.map_or((0, false, None), |(_, g, r, e)| (g, r, e));
            let pass = group.remove(g);
            route.steps.push(RouteStep::HeadlandPass { pass, reversed });
            position = end.or(position);
        }
        k = end;
    }
    position
}

/// Distance to and the nearest point of a ring from a position (0 and `None` without one).
pub fn nearest_on_ring(ring: &geo::LineString, position: Option<Coord>) -> (f64, Option<Coord>) {
    let Some(p) = position else {
        return (0.0, ring.0.first().copied());
    };
    match ring.closest_point(&Point(p)) {
        Closest::Intersection(q) | Closest::SinglePoint(q) => (distance(p, q.0), Some(q.0)),
        Closest::Indeterminate => (f64::INFINITY, None),
    }
}

#[inline]
fn distance(a: Coord, b: Coord) -> f64 {
    (a.x - b.x).hypot(a.y - b.y)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::decompose::cluster_swaths;
    use crate::headland::{HeadlandOrder, HeadlandPass};
    use crate::swath::generate;
    use geo::{polygon, LineString, MultiPolygon};

    #[test]
    fn every_swath_once_and_blocks_all_visited() {
        let field = polygon!(
            exterior: [(x: 0., y: 0.), (x: 60., y: 0.), (x: 60., y: 100.), (x: 0., y: 100.)],
            interiors: [[(x: 20., y: 40.), (x: 40., y: 40.), (x: 40., y: 60.), (x: 20., y: 60.)]],
        );
        let swaths = generate(&MultiPolygon::new(vec![field]), 0.0, 6.0, 6.0).unwrap();
        let blocks = cluster_swaths(&swaths);
        let route = boustrophedon(&swaths, &blocks, &[], HeadlandOrder::Last, None);
        let mut seen: Vec<usize> = route
            .steps
            .iter()
            .filter_map(|s| match s {
                RouteStep::Swath { swath, .. } => Some(*swath),
                _ => None,
            })
            .collect();
        seen.sort_unstable();
        assert_eq!(seen, (0..swaths.swaths.len()).collect::<Vec<_>>());
        let mut order = route.block_order.clone();
        order.sort_unstable();
        assert_eq!(order, vec![0, 1, 2, 3]);
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
