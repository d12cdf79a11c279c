#!/usr/bin/env python3
"""Writes the team's own urban RoadEditor waypoint files (docs/maps.md): a street grid with
a 4-way intersection, a T junction, a one-way loop around a block, two-way streets, a
two-lane approach, turns with 8-12 m radii, routes that share their first or last stretch,
branch, merge, overlap in the middle, cross, close on themselves and pass a place twice.

Routes are drawn the way RoadEditor users draw them: points 0.5-1 m apart, and routes meant
to be "the same lane" a few centimetres apart (a fixed offset plus seeded noise).

Usage: scripts/urban_waypoints.py map OUT_DIR        writes urban.waypoint.json (sumo_nets/urban)
       scripts/urban_waypoints.py fixtures OUT_DIR   writes the single-pattern files the tests
              use: crossing.waypoint.json, branch_merge.waypoint.json, loop.waypoint.json
Deterministic: the same script writes the same bytes."""
import json
import math
import random
import sys
from pathlib import Path

LANE = 3.5      # m lane width; lane centres lie LANE/2 beside a two-way street's axis
R_TURN = 10.0   # m, left turns
R_RIGHT = 8.0   # m, right turns (tighter: they stay in the near lanes)


def fillet_path(corners, radius, spacing):
    """Points along the polyline through `corners`, each interior corner rounded with an arc
    of `radius` (per corner: a number or a list), sampled every `spacing` metres."""
    radii = radius if isinstance(radius, list) else [radius] * len(corners)
    pieces = []  # ("line", a, b) or ("arc", centre, r, a0, sweep)
    start = corners[0]
    for i in range(1, len(corners) - 1):
        a, b, c = corners[i - 1], corners[i], corners[i + 1]
        d1 = unit(sub(b, a))
        d2 = unit(sub(c, b))
        turn = math.atan2(cross(d1, d2), dot(d1, d2))
        r = radii[i]
        if abs(turn) < 1e-9 or r <= 0:
            continue
        cut = r * math.tan(abs(turn) / 2)
        t1 = sub(b, scale(d1, cut))
        t2 = add(b, scale(d2, cut))
        pieces.append(("line", start, t1))
        side = 1 if turn > 0 else -1  # left turn: centre on the left
        centre = add(t1, scale((-d1[1] * side, d1[0] * side), r))
        a0 = math.atan2(t1[1] - centre[1], t1[0] - centre[0])
        pieces.append(("arc", centre, r, a0, turn))
        start = t2
    pieces.append(("line", start, corners[-1]))
    points = []
    carry = 0.0
    for piece in pieces:
        length = dist(piece[1], piece[2]) if piece[0] == "line" else piece[2] * abs(piece[4])
        s = carry
        while s < length - 1e-9:
            points.append(point_on(piece, s / length if length > 0 else 0))
            s += spacing
        carry = s - length
    points.append(corners[-1] if pieces[-1][0] == "line" else point_on(pieces[-1], 1.0))
    return points


def point_on(piece, f):
    if piece[0] == "line":
        return add(piece[1], scale(sub(piece[2], piece[1]), f))
    _, centre, r, a0, sweep = piece
    a = a0 + f * sweep
    return (centre[0] + r * math.cos(a), centre[1] + r * math.sin(a))


def sub(a, b): return (a[0] - b[0], a[1] - b[1])
def add(a, b): return (a[0] + b[0], a[1] + b[1])
def scale(a, k): return (a[0] * k, a[1] * k)
def dot(a, b): return a[0] * b[0] + a[1] * b[1]
def cross(a, b): return a[0] * b[1] - a[1] * b[0]
def dist(a, b): return math.hypot(a[0] - b[0], a[1] - b[1])
def unit(a):
    n = math.hypot(*a)
    return (a[0] / n, a[1] / n)


def route(rid, corners, speed_kmh, spacing=1.0, radius=R_TURN, offset=0.0, noise=0.0, seed=0):
    """A route through `corners` (map frame), drawn `offset` m left of them with `noise` m of
    seeded jitter per point, as RoadEditor writes it (x = map x, z = -map y, y = height)."""
    pts = fillet_path(corners, radius, spacing)
    rng = random.Random(seed)
    out = []
    for i, p in enumerate(pts):
        j = min(i + 1, len(pts) - 1)
        k = max(i - 1, 0)
        d = unit(sub(pts[j], pts[k])) if pts[j] != pts[k] else (1.0, 0.0)
        n = (-d[1], d[0])
        lat = offset + (rng.uniform(-noise, noise) if noise else 0.0)
        x, y = p[0] + n[0] * lat, p[1] + n[1] * lat
        out.append({"x": round(x, 4), "y": 0, "z": round(-y, 4), "v": speed_kmh})
    if corners[0] == corners[-1]:
        out[-1] = dict(out[0])  # a closed loop ends exactly on its first point
    return {"id": rid, "points": out}


# The street grid (right-hand traffic). Main street along y = 0 (x -150..250), cross street
# along x = 0 (y -150..200), side street along x = 120 (y 0..150), a one-way north street
# along y = 150 (x 120 -> 0, westbound, single lane).
H = LANE / 2
EB = -H           # eastbound lane (the left one of the two-lane approach west of x = 0)
EB_RIGHT = -3 * H  # eastbound right-turn lane of the approach
WB = H
NB = H            # northbound lane x
SB = -H           # southbound lane x
SIDE_NB = 120 + H
SIDE_SB = 120 - H
NORTH = 150.0     # the one-way north street (its single lane's centre)


def urban_routes():
    r = []
    # Main street, both directions; the eastbound left-turn route branches off the straight
    # one at the 4-way (drawn 3 cm beside it, with noise).
    r.append(route("EB_straight", [(-150, EB), (250, EB)], 50, spacing=1.0))
    r.append(route("EB_left", [(-150, EB), (NB, EB), (NB, 200)], 50,
                   spacing=0.7, offset=0.03, noise=0.02, seed=1))
    # The right-turn lane of the two-lane approach: a lane of its own from the start.
    r.append(route("EB_right", [(-150, EB_RIGHT), (SB, EB_RIGHT), (SB, -150)], 40, spacing=0.8,
                   radius=R_RIGHT))
    r.append(route("WB_straight", [(250, WB), (-150, WB)], 50, spacing=1.0))
    # Left turn across oncoming traffic: westbound into the southbound lane.
    r.append(route("WB_left", [(250, WB), (SB, WB), (SB, -150)], 40, spacing=0.6, offset=-0.02,
                   noise=0.015, seed=2))
    r.append(route("NB_straight", [(NB, -150), (NB, 200)], 50, spacing=1.0))
    # Right turn into the eastbound lane: merges with EB_straight after the 4-way.
    r.append(route("NB_right", [(NB, -150), (NB, EB), (250, EB)], 40, spacing=0.9, radius=R_RIGHT))
    r.append(route("SB_straight", [(SB, 200), (SB, -150)], 50, spacing=1.0))
    # Left turn southbound -> eastbound: merges too.
    r.append(route("SB_left", [(SB, 200), (SB, EB), (250, EB)], 40, spacing=0.5, offset=0.02,
                   noise=0.02, seed=3))
    # The side street (T junction at x = 120): in by a left turn, out by a right turn.
    r.append(route("T_in", [(-150, EB), (SIDE_NB, EB), (SIDE_NB, NORTH - 20)], 40, spacing=1.0))
    r.append(route("T_out", [(SIDE_SB, NORTH - 20), (SIDE_SB, WB), (-150, WB)], 40, spacing=0.8,
                   radius=R_RIGHT))
    # The loop around the block, counter-clockwise, closed on itself: east on the main
    # street, north up the side street, west along the one-way north street, south down the
    # cross street through the 4-way, left into the main street again.
    loop = [(60, EB), (SIDE_NB, EB), (SIDE_NB, NORTH), (SB, NORTH), (SB, EB), (60, EB)]
    r.append(route("LOOP", loop, 40, spacing=1.0))
    # Once around the loop and on east past the T junction: the same place twice.
    twice = loop[:-1] + [(60, EB), (250, EB)]
    r.append(route("LOOP_then_east", twice, 40, spacing=0.9, offset=-0.025, noise=0.015, seed=4))
    return r


def crossing_routes():
    """Only the 4-way: straight crossings of two two-way streets, no turns."""
    return [route("EB", [(-100, EB), (100, EB)], 50), route("WB", [(100, WB), (-100, WB)], 50),
            route("NB", [(NB, -100), (NB, 100)], 50), route("SB", [(SB, 100), (SB, -100)], 50)]


def branch_merge_routes():
    """One lane splitting into straight and right turn, and a lane merging into it."""
    return [route("main", [(-100, EB), (100, EB)], 50),
            route("exit", [(-100, EB), (SB, EB), (SB, -100)], 40, radius=R_RIGHT, offset=0.03),
            route("entry", [(NB, -100), (NB, EB), (100, EB)], 40, radius=R_RIGHT, spacing=0.6)]


def loop_routes():
    """A closed loop alone (a ring road with rounded corners)."""
    return [route("ring", [(40, 0), (80, 0), (80, 60), (0, 60), (0, 0), (40, 0)], 40, radius=12)]


def write(path, map_id, routes):
    doc = {"id": "WayPoint_" + map_id, "mapId": map_id, "waypoints": routes,
           "properties": [{"id": "ego_startPoint", "name": "ego start", "index": 0,
                           "waypointId": routes[0]["id"]}]}
    path.write_text(json.dumps(doc, indent=1) + "\n")


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in ("map", "fixtures"):
        sys.exit(__doc__)
    out = Path(sys.argv[2])
    out.mkdir(parents=True, exist_ok=True)
    if sys.argv[1] == "map":
        write(out / "urban.waypoint.json", "Urban.Grid", urban_routes())
    else:
        write(out / "crossing.waypoint.json", "Crossing", crossing_routes())
        write(out / "branch_merge.waypoint.json", "BranchMerge", branch_merge_routes())
        write(out / "loop.waypoint.json", "Loop", loop_routes())


if __name__ == "__main__":
    main()
