//! Shortest paths along a plan's tracks on every corpus field: 1,000 random queries per plan (a
//! third for each way of turning), each from a random place and heading on the tracks to a
//! random exit on the boundary lane. Every path is checked:
//!
//! - it runs along tracks only, stretch after stretch, each starting where the last ended;
//! - every change of track is at a junction of the two, with a change of heading the turning
//!   allows (and the first stretch follows the heading unless the machine may turn on the spot);
//! - its length is the sum of its stretches, and no exhaustive search over the same states
//!   (every state settled, no straight-line bound) finds a shorter one.

mod common;

use common::corpus::valid_fields;
use furrow::rng::SplitMix64;
use furrow::tracks::{
    from_plan, may_turn, shortest_path, shortest_path_exhaustive, TrackGraph, TrackPath,
    TrackQuery, Turning,
};
use furrow::{plan_geojson, ErrorCode, PlanOptions};
use geo::Coord;

const QUERIES_PER_PLAN: usize = 1000;

/// A random place on the tracks (chosen in proportion to length) and a heading along its track
/// either way, or anywhere for a third of the queries.
fn random_query(g: &TrackGraph, rng: &mut SplitMix64, turning: Turning) -> TrackQuery {
    let total: f64 = g.tracks().iter().map(|t| t.length()).sum();
    let mut pick = rng.unit() * total;
    let mut track = 0;
    for (i, t) in g.tracks().iter().enumerate() {
        if pick <= t.length() {
            track = i;
            break;
        }
        pick -= t.length();
    }
    let t = &g.tracks()[track];
    let at = pick.clamp(0.0, t.length());
    let from = t.point_at(at);
    let h = t.heading_at(at, rng.unit() < 0.5, true);
    let heading = if rng.unit() < 0.33 {
        rng.range(-std::f64::consts::PI, std::f64::consts::PI)
    } else {
        h.y.atan2(h.x)
    };
    let boundary: Vec<usize> = (0..g.tracks().len())
        .filter(|&i| g.tracks()[i].boundary)
        .collect();
    let pool = if boundary.is_empty() {
        (0..g.tracks().len()).collect()
    } else {
        boundary
    };
    let targets = (0..1 + rng.below(2))
        .map(|_| {
            let b = &g.tracks()[pool[rng.below(pool.len())]];
            b.point_at(rng.unit() * b.length())
        })
        .collect();
    TrackQuery {
        from,
        heading,
        targets,
        turning,
        ..TrackQuery::default()
    }
}

fn close(a: Coord, b: Coord, tol: f64) -> bool {
    (a.x - b.x).hypot(a.y - b.y) <= tol
}

/// Checks that `path` answers `query` over `g` as the module comment says.
fn check_path(g: &TrackGraph, query: &TrackQuery, path: &TrackPath, name: &str) {
    let tracks = g.tracks();
    let mut length = 0.0;
    let first = path.stretches.first().expect("a stretch");
    assert!(
        close(
            tracks[first.track].point_at(wrapped(g, first.track, first.from)),
            path.start,
            1e-6
        ),
        "{name}: starts at the placed start"
    );
    if query.turning != Turning::OnTheSpot && (first.to - first.from).abs() > 1e-9 {
        let forward = first.to > first.from;
        let h = tracks[first.track].heading_at(wrapped(g, first.track, first.from), forward, true);
        let face = Coord {
            x: query.heading.cos(),
            y: query.heading.sin(),
        };
        assert!(
            h.x * face.x + h.y * face.y >= -1e-9,
            "{name}: the first move follows the heading"
        );
    }
    for (k, s) in path.stretches.iter().enumerate() {
        length += (s.to - s.from).abs();
        if k == 0 {
            continue;
        }
        let prev = path.stretches[k - 1];
        let a = tracks[prev.track].point_at(wrapped(g, prev.track, prev.to));
        let b = tracks[s.track].point_at(wrapped(g, s.track, s.from));
        assert!(
            close(a, b, 0.2),
            "{name}: stretch {k} starts where the last ended ({a:?} vs {b:?})"
        );
        length += (a.x - b.x).hypot(a.y - b.y); // the step across a junction
                                                // At a junction of the two tracks.
        let node_at = |t: usize, at: f64| {
            g.nodes_on(t).iter().copied().find(|&n| {
                let d = (g.nodes()[n].at - wrapped(g, t, at)).abs();
                d < 1e-6 || (tracks[t].closed && (d - tracks[t].length()).abs() < 1e-6)
            })
        };
        let (Some(na), Some(nb)) = (node_at(prev.track, prev.to), node_at(s.track, s.from)) else {
            panic!("{name}: stretch {k} changes track away from a node");
        };
        assert_eq!(
            g.nodes()[na].junction,
            g.nodes()[nb].junction,
            "{name}: at one junction"
        );
        let arrive = tracks[prev.track].heading_at(
            wrapped(g, prev.track, prev.to),
            prev.to >= prev.from,
            false,
        );
        let leave = tracks[s.track].heading_at(wrapped(g, s.track, s.from), s.to >= s.from, true);
        let same = prev.track == s.track && (prev.to >= prev.from) == (s.to >= s.from);
        assert!(
            same || may_turn(query.turning, arrive, leave),
            "{name}: stretch {k} turns as allowed"
        );
    }
    assert!(
        (length - path.length).abs() < 1e-6,
        "{name}: length {length} vs {}: {:?}",
        path.length,
        path.stretches
            .iter()
            .map(|s| (
                s.track,
                s.from,
                s.to,
                tracks[s.track].closed,
                tracks[s.track].length()
            ))
            .collect::<Vec<_>>()
    );
    let end = path.points.last().expect("points");
    let target = query.targets[path.target];
    let (t, at, _) = g.nearest(target, |t| t.boundary).expect("a boundary");
    assert!(
        close(*end, tracks[t].point_at(at), 0.2),
        "{name}: ends at the target"
    );
}

fn wrapped(g: &TrackGraph, t: usize, at: f64) -> f64 {
    let track = &g.tracks()[t];
    if track.closed {
        at.rem_euclid(track.length())
    } else {
        at
    }
}

#[test]
fn random_queries_on_every_corpus_plan() {
    let mut rng = SplitMix64::new(20_261_201);
    let mut report = Vec::new();
    for field in valid_fields() {
        let plan = plan_geojson(&field.text(), &field.options)
            .unwrap_or_else(|e| panic!("{}: {e}", field.name));
        let g = from_plan(&plan);
        assert!(
            g.tracks().iter().any(|t| t.boundary),
            "{}: a boundary lane",
            field.name
        );
        let mut stats = [(0usize, 0usize, 0.0f64); 3];
        for q in 0..QUERIES_PER_PLAN {
            let (k, turning) = [
                (0, Turning::OnTheSpot),
                (1, Turning::Heading),
                (2, Turning::Tracks),
            ][q % 3];
            let query = random_query(&g, &mut rng, turning);
            let name = format!("{} query {q} ({})", field.name, turning.as_str());
            let fast = shortest_path(&g, &query);
            let full = shortest_path_exhaustive(&g, &query);
            match (&fast, &full) {
                (Ok(p), Ok(e)) => {
                    check_path(&g, &query, p, &name);
                    assert!(
                        p.length <= e.length + 1e-6,
                        "{name}: {} longer than the exhaustive {}",
                        p.length,
                        e.length
                    );
                    assert!(
                        e.length <= p.length + 1e-6,
                        "{name}: the exhaustive search is no better either"
                    );
                    stats[k].0 += 1;
                    stats[k].1 += p.expanded;
                    stats[k].2 += p.length;
                }
                (Err(a), Err(b)) => {
                    assert_eq!(a.code, ErrorCode::NoPath, "{name}: {a}");
                    assert_eq!(b.code, ErrorCode::NoPath, "{name}: {b}");
                }
                _ => panic!("{name}: the searches disagree: {fast:?} vs {full:?}"),
            }
        }
        // With turning on the spot there is always a way (the tracks are one connected path).
        assert_eq!(
            stats[0].0,
            QUERIES_PER_PLAN.div_ceil(3),
            "{}: every on-the-spot query has a path",
            field.name
        );
        report.push(format!(
            "{:<28} {:>5} tracks {:>5} junctions  found {:>3}/{:>3}/{:>3}  mean length {:>6.0}/{:>6.0}/{:>6.0} m  mean expanded {:>5.0}/{:>5.0}/{:>5.0}",
            field.name,
            g.tracks().len(),
            g.junctions().len(),
            stats[0].0,
            stats[1].0,
            stats[2].0,
            stats[0].2 / stats[0].0.max(1) as f64,
            stats[1].2 / stats[1].0.max(1) as f64,
            stats[2].2 / stats[2].0.max(1) as f64,
            stats[0].1 as f64 / stats[0].0.max(1) as f64,
            stats[1].1 as f64 / stats[1].0.max(1) as f64,
            stats[2].1 as f64 / stats[2].0.max(1) as f64,
        ));
    }
    println!("on the spot / heading / tracks:\n{}", report.join("\n"));
}

#[test]
fn stricter_turning_is_never_shorter() {
    let mut rng = SplitMix64::new(7);
    for field in valid_fields()
        .into_iter()
        .filter(|f| ["h-shape", "obstacles-2", "underdrain"].contains(&f.name.as_str()))
    {
        let plan = plan_geojson(&field.text(), &field.options).expect("plans");
        let g = from_plan(&plan);
        for _ in 0..100 {
            let q = random_query(&g, &mut rng, Turning::Tracks);
            let len = |turning| {
                shortest_path(
                    &g,
                    &TrackQuery {
                        turning,
                        ..q.clone()
                    },
                )
                .map(|p| p.length)
                .unwrap_or(f64::INFINITY)
            };
            let (a, b, c) = (
                len(Turning::OnTheSpot),
                len(Turning::Heading),
                len(Turning::Tracks),
            );
            assert!(
                a <= b + 1e-6 && b <= c + 1e-6,
                "{}: {a} <= {b} <= {c}",
                field.name
            );
        }
    }
}

#[test]
fn errors_are_typed() {
    let field = &valid_fields()[0];
    let plan = plan_geojson(&field.text(), &field.options).expect("plans");
    let g = from_plan(&plan);
    let t = &g.tracks()[0];
    let on = t.point_at(t.length() / 2.0);
    let far = Coord {
        x: on.x + 1000.0,
        y: on.y,
    };
    let q = TrackQuery {
        from: far,
        targets: vec![on],
        ..TrackQuery::default()
    };
    assert_eq!(
        shortest_path(&g, &q).map(|_| ()).unwrap_err().code,
        ErrorCode::OffTracks
    );
    let q = TrackQuery {
        from: on,
        targets: vec![],
        ..TrackQuery::default()
    };
    assert_eq!(
        shortest_path(&g, &q).map(|_| ()).unwrap_err().code,
        ErrorCode::InvalidOption
    );
    let q = TrackQuery {
        from: on,
        heading: f64::NAN,
        targets: vec![on],
        ..TrackQuery::default()
    };
    assert_eq!(
        shortest_path(&g, &q).map(|_| ()).unwrap_err().code,
        ErrorCode::InvalidOption
    );
    let _ = PlanOptions::default();
}
