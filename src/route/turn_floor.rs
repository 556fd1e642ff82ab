//! What a connection between two blocks costs at least where the next block is entered right
//! beside where the last one ended, facing back the way it left: the turn it takes, as between
//! two swaths of a block, not the few metres between the ends (see [`turn_floor`]).

use crate::objective::turn_length;
use crate::sort::SharedSort;
use crate::swath::Swath;
use geo::Coord;

/// How near (in turning radii along the headland) a block's exit and the next block's entry
/// are for the machine's turn between them to set the cost of the connection
/// ([`turn_floor`]): farther apart, it turns onto the headland and off it where it likes.
const NEAR_TURN_RADII: f64 = 6.0;

/// The cosine of the largest angle between the directions a block's exit and the next block's
/// entry face out of their swaths for the machine to turn between them as between two swaths
/// of a block (30 degrees).
const SAME_WAY_COS: f64 = 0.866;

/// The least the machine drives from a swath's end (`exit`, facing out of the swath) into the
/// start of another (`entry`, facing out of it, so entered the other way) that faces the same
/// way, where they lie within [`NEAR_TURN_RADII`] along the headland (`along`): the turn
/// model's length for their spacing, as between two swaths of a block ([`turn_length`]: a
/// loop where they lie nearer than twice the turning radius), and the stagger of their ends. A
/// connection between near ends that face each other the wrong way costs the loop it takes,
/// not the few metres between them, so that the block order and the ways the blocks are worked
/// avoid it. Farther apart, facing otherwise, or without a direction at either end, `along`.
pub(super) fn turn_floor(
    exit: (Coord, Option<Coord>),
    entry: (Coord, Option<Coord>),
    along: f64,
    r: f64,
) -> f64 {
    let ((a, Some(out_a)), (b, Some(out_b))) = (exit, entry) else {
        return along;
    };
    if along.is_nan()
        || along >= NEAR_TURN_RADII * r
        || out_a.x * out_b.x + out_a.y * out_b.y < SAME_WAY_COS
    {
        return along;
    }
    let gap = b - a;
    let across = gap.x * out_a.y - gap.y * out_a.x;
    let stagger = gap.x * out_a.x + gap.y * out_a.y;
    turn_length(across, r) + stagger.abs()
}

/// For each point that is the end of a swath, the direction out of the swath there (a unit
/// vector along it).
pub(super) fn facing_out(points: &[Coord], s: &[Swath]) -> Vec<Option<Coord>> {
    let key = |p: Coord| (p.x.to_bits(), p.y.to_bits());
    let mut out_of: Vec<((u64, u64), Coord)> = Vec::with_capacity(2 * s.len());
    for w in s {
        let length = w.length();
        if length > 0.0 {
            let d = (w.centre.end - w.centre.start) / length;
            out_of.push((key(w.centre.end), d));
            out_of.push((key(w.centre.start), -d));
        }
    }
    out_of.shared_sort_by(|x, y| x.0.cmp(&y.0));
    points
        .iter()
        .map(|&p| {
            let k = key(p);
            out_of
                .binary_search_by(|x| x.0.cmp(&k))
                .ok()
                .and_then(|i| out_of.get(i))
                .map(|x| x.1)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{polygon, MultiPolygon};

    #[test]
    fn a_connection_between_near_ends_facing_the_wrong_way_costs_its_loop() {
        let r = 8.0;
        let north = Some(Coord { x: 0.0, y: 1.0 });
        let south = Some(Coord { x: 0.0, y: -1.0 });
        let exit = (Coord { x: 0.0, y: 0.0 }, north);
        // The next swath starts 6 m east, entered heading south (its outward direction north):
        // a loop turn, far longer than the 6 m between the ends.
        let beside = (Coord { x: 6.0, y: 0.0 }, north);
        let floor = turn_floor(exit, beside, 6.0, r);
        assert!(
            (floor - turn_length(6.0, r)).abs() < 1e-9 && floor > 50.0,
            "{floor}"
        );
        // 4 m farther on: the stagger too.
        let staggered = (Coord { x: 6.0, y: 4.0 }, north);
        assert!((turn_floor(exit, staggered, 8.0, r) - floor - 4.0).abs() < 1e-9);
        // Entered heading north from 20 m ahead, the machine drives straight on.
        let ahead = (Coord { x: 0.0, y: 20.0 }, south);
        assert_eq!(turn_floor(exit, ahead, 20.0, r), 20.0);
        // Far apart along the headland, or without a direction, the headland's distance.
        assert_eq!(turn_floor(exit, beside, 60.0, r), 60.0);
        assert_eq!(turn_floor(exit, (beside.0, None), 6.0, r), 6.0);
    }

    #[test]
    fn the_ends_of_swaths_face_out_of_them() {
        let field = polygon![(x: 0., y: 0.), (x: 12., y: 0.), (x: 12., y: 100.), (x: 0., y: 100.)];
        let swaths = crate::swath::generate(&MultiPolygon::new(vec![field]), 0.0, 6.0, 6.0)
            .unwrap_or_else(|e| panic!("{e}"));
        let points = [
            Coord { x: 3.0, y: 0.0 },
            Coord { x: 3.0, y: 100.0 },
            Coord { x: 5.0, y: 50.0 },
        ];
        let facing = facing_out(&points, &swaths.swaths);
        assert_eq!(facing[0], Some(Coord { x: 0.0, y: -1.0 }));
        assert_eq!(facing[1], Some(Coord { x: 0.0, y: 1.0 }));
        assert_eq!(facing[2], None);
    }
}
