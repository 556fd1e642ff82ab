#!/usr/bin/env python3
"""Coverage of plans on the register parcels of tests/fields/real/, measured independently of the
planner's own figure: from the CLI's GeoJSON output with shapely, the footprint of every working
feature (a strip of the width along it, flat ends, lifted stretches left out) against the parcel,
in a transverse Mercator projection about the parcel (pyproj). Four machines, as in the table of
docs/performance.md. The last two columns count plans with a connection (of them those with no
connection_crosses_crop warning) and plans with a turn between swaths (of them without the
turn_crosses_crop warning) that drives through at
least 1 m of crop the plan works later (not on the headland, not on a strip already worked: see
crop_crossed); the column before them counts plans whose route (a turn or a connection) runs
more than 1 m out of the field, and of them those with no warning naming it. Needs `pip install
shapely pyproj numpy`.

usage: python3 scripts/coverage-table.py BINARY [--parcels DIR] [--json OUT]
  BINARY   the CLI, e.g. target/release/examples/plan (cargo build --release --example plan)
  --parcels a directory of one-parcel GeoJSON files (default: each feature of
           tests/fields/real/*.geojson, written to a temporary directory)
  --json   every parcel's figures, for comparing two binaries

A second table estimates, for the forward-only machines, what any plan could reach without its
path leaving the field: the parcel less half a width, opened by the turning disc (a path bent
no tighter than the turning radius comes no nearer a convex corner), and half a width round
that. It misses what a path driving straight through a neck narrower than the disc reaches, so
it errs low there."""
import json, subprocess, glob, sys, os, math, tempfile
from concurrent.futures import ThreadPoolExecutor
from shapely.geometry import shape, LineString, Polygon, MultiPolygon, Point
from shapely.ops import unary_union, substring
from shapely import transform as stransform
from pyproj import Transformer

binary = sys.argv[1]
pdir = None
out_json = None
if '--parcels' in sys.argv: pdir = sys.argv[sys.argv.index('--parcels') + 1]
if '--json' in sys.argv: out_json = sys.argv[sys.argv.index('--json') + 1]
if pdir is None:
    pdir = tempfile.mkdtemp(prefix='furrow-parcels-')
    real = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'tests', 'fields', 'real')
    for path in sorted(glob.glob(os.path.join(real, '*.geojson'))):
        stem = os.path.basename(path)[:-len('.geojson')]
        for i, feature in enumerate(json.load(open(path))['features']):
            with open(os.path.join(pdir, f'{stem}_{i:03d}.geojson'), 'w') as f:
                json.dump(feature, f)
MACHINES = [
    ('mower 3 m, 2 passes, r 5', ['--width', '3', '--headland-passes', '2', '--turn-radius', '5'], 3.0),
    ('drill 6 m, 2 passes, r 8', ['--width', '6', '--headland-passes', '2', '--turn-radius', '8'], 6.0),
    ('drill 6 m reversing', ['--width', '6', '--headland-passes', '2', '--turn-radius', '8', '--reverse', 'true'], 6.0),
    ('sprayer 24 m, 1 pass, r 9', ['--width', '24', '--headland-passes', '1', '--turn-radius', '9'], 24.0),
]
if os.environ.get('EXTRA'): MACHINES = [(m[0], m[1] + os.environ['EXTRA'].split(), m[2]) for m in MACHINES]

def local_tf(g):
    c = g.centroid
    t = Transformer.from_crs('EPSG:4326', f'+proj=tmerc +lon_0={c.x} +lat_0={c.y} +ellps=WGS84', always_xy=True)
    return lambda geom: stransform(geom, lambda xy: __import__('numpy').column_stack(t.transform(xy[:, 0], xy[:, 1])))

def evaluate(path, args, w):
    d = json.load(open(path)); g = shape(d['geometry'])
    tf = local_tf(g)
    field = tf(g).buffer(0)
    reach = field.buffer(-w / 2, join_style=1).buffer(w / 2, join_style=1)
    res = {'area': field.area, 'reach': reach.area}
    if '--reverse' not in args:
        # What a path bent no tighter than the turning radius reaches without leaving the field:
        # the field less half a width, opened by the turning disc, and the implement's half
        # width round that (exact at convex corners; a neck driven straight through is missed).
        r = float(args[args.index('--turn-radius') + 1])
        centre = field.buffer(-w / 2, join_style=1).buffer(-r, join_style=1).buffer(r, join_style=1)
        res['forward_reach'] = centre.buffer(w / 2, join_style=1).intersection(reach).area
    p = subprocess.run([binary, path] + args, capture_output=True, text=True)
    if p.returncode != 0:
        try: res['error'] = json.loads(p.stderr.strip().splitlines()[-1])['code']
        except Exception: res['error'] = p.stderr[:80]
        return res
    plan = json.loads(p.stdout)
    feet = []; outside = 0.0; turns_out = 0
    worked_at = []  # (sequence, footprint) of every working feature, for the crop crossed
    headland_feet = []
    connections = []
    turns = []
    out_depth = {'turn': 0.0, 'connection': 0.0}
    for f in plan['features']:
        k = f['properties']['kind']
        if f['geometry']['type'] != 'LineString': continue
        if k in out_depth:
            out_depth[k] = max(out_depth[k], depth_outside(field, tf(shape(f['geometry']))))
        if k in ('connection', 'turn'):
            (connections if k == 'connection' else turns).append(
                (f['properties'].get('sequence', 0), tf(shape(f['geometry']))))
        if not f['properties'].get('working', k in ('swath', 'headland', 'fill')): 
            continue
        line = tf(shape(f['geometry']))
        pieces = [line]
        lifted = f['properties'].get('lifted')
        if lifted:
            pieces = []; pos = 0.0
            for a, b in (lifted if isinstance(lifted[0], list) else [lifted]):
                if a > pos: pieces.append(substring(line, pos, a))
                pos = b
            if pos < line.length: pieces.append(substring(line, pos, line.length))
        for pc in pieces:
            if pc.length > 0:
                foot = pc.buffer(w / 2, cap_style=2, join_style=1)
                feet.append(foot)
                worked_at.append((f['properties'].get('sequence', 0), foot))
                if k == 'headland': headland_feet.append(foot)
    union = unary_union(feet) if feet else Polygon()
    covered = union.intersection(field).area
    total = sum(f.intersection(field).area for f in feet)
    res.update(covered=covered, overlap=max(0.0, total - covered), outside=union.difference(field.buffer(0.05)).area,
               summary_cov=plan['summary'].get('coverage'), turns_outside=plan['summary'].get('turns_outside_field', 0),
               through_crop=crop_crossed(field, headland_feet, worked_at, connections),
               turns_through_crop=crop_crossed(field, headland_feet, worked_at, turns),
               turn_out_m=out_depth['turn'], connection_out_m=out_depth['connection'],
               warnings=[w['code'] for w in plan.get('warnings', [])])
    return res

def depth_outside(field, line):
    """How far (metres) the line runs out of the field (or into a hole of it) at its worst."""
    out = line.difference(field)
    if out.is_empty: return 0.0
    return max(field.boundary.distance(Point(c)) for g in getattr(out, 'geoms', [out]) for c in g.coords)

def unwarned_outside(r):
    """Whether a turn or connection runs more than 1 m out of the field with no warning naming it."""
    return (r['turn_out_m'] > 1.0 and 'turn_leaves_field' not in r['warnings']) or \
        (r['connection_out_m'] > 1.0 and 'connection_leaves_field' not in r['warnings'])

def crop_crossed(field, headland_feet, worked_at, connections):
    """The longest stretch (metres) of a connection through crop still standing when it is driven
    and worked later: the field less the headland (driven on by design), taken in a metre from
    its edges (a connection along a worked strip's edge crosses no crop), less every strip worked
    earlier in the plan's sequence, within a strip worked later (crop the plan never works, such
    as a corner left standing, is not counted)."""
    if not connections: return 0.0
    crop = field.difference(unary_union(headland_feet)) if headland_feet else field
    crop = crop.buffer(-1.0)
    worst = 0.0
    for seq, line in connections:
        inside = line.intersection(crop)
        if inside.is_empty: continue
        earlier = [foot for s, foot in worked_at if s < seq and foot.intersects(inside)]
        left = inside.difference(unary_union(earlier)) if earlier else inside
        later = [foot for s, foot in worked_at if s > seq and foot.intersects(left)]
        if later: worst = max(worst, left.intersection(unary_union(later)).length)
    return worst

def run_machine(m):
    name, args, w = m
    files = sorted(glob.glob(pdir + '/*.geojson'))
    with ThreadPoolExecutor(2) as ex:
        results = list(ex.map(lambda f: (os.path.basename(f), evaluate(f, args, w)), files))
    return name, results

table = []
allres = {}
for m in MACHINES:
    name, results = run_machine(m)
    allres[name] = results
    refused = [r for _, r in results if 'error' in r]
    refused_reach = [r for r in refused if r['reach'] >= 0.5 * r['area']]
    ok = [r for _, r in results if 'error' not in r]
    A = sum(r['area'] for _, r in results)
    cov = sum(r.get('covered', 0) for _, r in results) / A
    reach = sum(r['reach'] for _, r in results) / A
    ge97 = sum(1 for _, r in results if r.get('covered', 0) >= 0.97 * r['reach']) / len(results)
    lt90 = sum(1 for _, r in results if r.get('covered', 0) < 0.90 * r['area']) / len(results)
    ov = sum(r.get('overlap', 0) for r in ok) / sum(r['area'] for r in ok)
    outside = sum(1 for r in ok if r['outside'] > 1.0)
    tout = sum(1 for r in ok if r['turns_outside'] > 0)
    crossing = sum(1 for r in ok if r['through_crop'] >= 1.0)
    crossing_unwarned = sum(1 for r in ok if r['through_crop'] >= 1.0 and 'connection_crosses_crop' not in r['warnings'])
    turns_crossing = sum(1 for r in ok if r['turns_through_crop'] >= 1.0)
    turns_unwarned = sum(1 for r in ok if r['turns_through_crop'] >= 1.0 and 'turn_crosses_crop' not in r['warnings'])
    route_out = sum(1 for r in ok if max(r['turn_out_m'], r['connection_out_m']) > 1.0)
    unwarned = sum(1 for r in ok if unwarned_outside(r))
    table.append(f"| {name} | {len(refused)} ({len(refused_reach)}) | {100*cov:.1f} % | {100*reach:.2f} % | {100*cov/reach:.1f} % | {100*ge97:.0f} % | {100*lt90:.0f} % | {100*ov:.1f} % | {outside} | {tout} of {len(ok)} | {route_out} ({unwarned}) | {crossing} ({crossing_unwarned}) | {turns_crossing} ({turns_unwarned}) |")
print('| machine | refused (of them reachable >= 50 %) | coverage, area-weighted | reachable (limit) | coverage of reachable | parcels >= 97 % of their reachable | parcels < 90 % covered | overlap | plans working > 1 m² outside | plans with turns outside | plans with a turn or connection > 1 m outside (of them not warned of) | plans with a connection through >= 1 m of crop worked later (of them not warned of) | plans with a turn through >= 1 m of crop worked later (of them not warned of) |')
print('|---|---|---|---|---|---|---|---|---|---|---|---|---|')
print('\n'.join(table))
print()
print('| machine | forward-only estimate: coverage of reachable | parcels >= 97 % of their reachable |')
print('|---|---|---|')
for name, results in allres.items():
    est = [r for _, r in results if 'forward_reach' in r]
    if est:
        share = sum(r['forward_reach'] for r in est) / sum(r['reach'] for r in est)
        ge97 = sum(1 for r in est if r['forward_reach'] >= 0.97 * r['reach']) / len(est)
        print(f"| {name} | {100*share:.1f} % | {100*ge97:.0f} % |")
if out_json: json.dump(allres, open(out_json, 'w'))
