#!/usr/bin/env python3
"""Seeded generator of city-like RoadEditor waypoint files, the test input of the map
builder's property test (docs/maps.md, "Generated maps").

Draws a map the way RoadEditor users draw one: a street grid with random block sizes
(30-200 m), one- and two-way streets with 1-3 lanes per direction (each lane drawn as its
own routes), a diagonal street making a 5-way junction, side streets ending at T junctions,
staggered side streets whose junctions lie closer together than a car length; routes of
3-15 streets that turn with radii of 5-25 m, share stretches with other routes (same lane
drawn a few centimetres apart, opposite directions side by side), start and end mid-block,
cross, loop around a block and pass a junction twice. Points lie 0.3-2 m apart with
centimetre noise; now and then a route has a repeated point, a zero-length segment, a
180-degree spike, or bulges towards its neighbouring lane at a shallow angle.

The output matches RoadEditor's "Export Waypoint" files byte for byte in form (tabs,
"}]" closers, no final newline, x = map x, z = -map y, y = height, v in km/h).

Usage: scripts/city_waypoints.py --seed N --out FILE [--scale K]
  --scale K   K times as many streets and routes in each direction of the grid (default 1)
Deterministic: the same seed and scale write the same bytes."""
import argparse
import math
import random
from pathlib import Path

LANE = 3.5          # m between neighbouring lane centres
MIN_BLOCK, MAX_BLOCK = 30.0, 200.0
MIN_RADIUS, MAX_RADIUS = 5.0, 25.0
END_CLEAR = 14.0    # m a route's own start or end keeps from any junction centre


# ---- small vector helpers (tuples) ----
def add(a, b): return (a[0] + b[0], a[1] + b[1])
def sub(a, b): return (a[0] - b[0], a[1] - b[1])
def mul(a, k): return (a[0] * k, a[1] * k)
def dot(a, b): return a[0] * b[0] + a[1] * b[1]
def cross(a, b): return a[0] * b[1] - a[1] * b[0]
def norm(a): return math.hypot(a[0], a[1])
def unit(a):
    n = norm(a)
    return (a[0] / n, a[1] / n)
def right_of(d): return (d[1], -d[0])


class Street:
    """A straight street from a to b. One-way streets run a -> b."""

    def __init__(self, sid, a, b, oneway, lanes_fwd, lanes_bwd):
        self.id, self.a, self.b = sid, a, b
        self.oneway = oneway
        self.lanes = {+1: lanes_fwd, -1: 0 if oneway else lanes_bwd}
        self.dir = unit(sub(b, a))
        self.length = norm(sub(b, a))
        self.nodes = []  # (t along the street, node id), sorted

    def lane_offset(self, sense, k):
        """Metres to the right of the street's axis (seen in driving direction `sense`) of
        lane k (0 = next to the centre line / the left edge of a one-way street)."""
        if self.oneway:
            n = self.lanes[+1]
            return (k - (n - 1) / 2) * LANE
        return (k + 0.5) * LANE

    def lane_line(self, sense, k):
        """(point, direction) of lane k's centre line in driving direction `sense`."""
        d = self.dir if sense > 0 else mul(self.dir, -1)
        return add(self.a, mul(right_of(d), self.lane_offset(sense, k))), d

    def point(self, t):
        return add(self.a, mul(self.dir, t))


def intersect(p, d, q, e):
    """Intersection of lines p + s d and q + u e (None when parallel)."""
    c = cross(d, e)
    if abs(c) < 1e-9:
        return None
    s = cross(sub(q, p), e) / c
    return add(p, mul(d, s))


class City:
    def __init__(self, rng, scale):
        self.rng = rng
        self.streets = []
        self.node_pos = []
        self.make_grid(scale)
        self.find_nodes()

    def make_grid(self, scale):
        rng = self.rng
        nx = rng.randint(3, 4) * scale
        ny = rng.randint(3, 4) * scale
        xs = [0.0]
        for _ in range(nx - 1):
            xs.append(xs[-1] + rng.uniform(MIN_BLOCK, MAX_BLOCK if rng.random() < 0.3 else 120.0))
        ys = [0.0]
        for _ in range(ny - 1):
            ys.append(ys[-1] + rng.uniform(MIN_BLOCK, MAX_BLOCK if rng.random() < 0.3 else 120.0))
        margin = 60.0

        def street_props():
            oneway = rng.random() < 0.3
            fwd = rng.choice([1, 1, 1, 2, 2, 3])
            bwd = rng.choice([1, 1, 1, 2, 2, 3])
            return oneway, fwd, bwd

        for i, x in enumerate(xs):
            lo, hi = ys[0] - margin, ys[-1] + margin
            # Some streets stop at a cross street: T junctions there.
            if rng.random() < 0.25 and 0 < i < len(xs) - 1:
                lo = ys[1]
            elif rng.random() < 0.2 and 0 < i < len(xs) - 1:
                hi = ys[-2]
            oneway, fwd, bwd = street_props()
            a, b = (x, lo), (x, hi)
            if rng.random() < 0.5:
                a, b = b, a
            self.streets.append(Street(f"v{i}", a, b, oneway, fwd, bwd))
        for j, y in enumerate(ys):
            lo, hi = xs[0] - margin, xs[-1] + margin
            oneway, fwd, bwd = street_props()
            a, b = (lo, y), (hi, y)
            if rng.random() < 0.5:
                a, b = b, a
            self.streets.append(Street(f"h{j}", a, b, oneway, fwd, bwd))
        # A diagonal street out of an inner grid node: a 5-way junction there.
        ci, cj = rng.randrange(len(xs)), rng.randrange(1, len(ys))
        ang = math.radians(rng.choice([35, 45, 55, 125, 135, 145]))
        start = (xs[ci], ys[cj])
        end = add(start, (math.cos(ang) * rng.uniform(70, 110), math.sin(ang) * rng.uniform(70, 110)))
        self.streets.append(Street("d0", end, start, False, 1, 1))
        # Staggered side streets off a horizontal street: two T junctions closer together
        # than a car length (4-6 m between their near lane edges).
        j = rng.randrange(1, len(ys))
        gap_x = [(xs[k], xs[k + 1]) for k in range(len(xs) - 1) if xs[k + 1] - xs[k] > 70]
        if gap_x:
            x0, x1 = rng.choice(gap_x)
            xm = (x0 + x1) / 2
            off = 2 * LANE + rng.uniform(4.0, 6.0)
            below = ys[j - 1] if j > 0 else ys[j] - 60
            len_down = min(50.0, (ys[j] - below) * 0.6)
            self.streets.append(Street("s0", (xm, ys[j] + rng.uniform(40, 60)), (xm, ys[j]), False, 1, 1))
            self.streets.append(Street("s1", (xm + off, ys[j]), (xm + off, ys[j] - len_down), False, 1, 1))

    def find_nodes(self):
        """Where streets meet: every pairwise intersection of their segments (ends included)."""
        for i, s in enumerate(self.streets):
            for t_ in self.streets[i + 1:]:
                p = intersect(s.a, s.dir, t_.a, t_.dir)
                if p is None:
                    continue
                ts = dot(sub(p, s.a), s.dir)
                tt = dot(sub(p, t_.a), t_.dir)
                if -0.5 <= ts <= s.length + 0.5 and -0.5 <= tt <= t_.length + 0.5:
                    nid = None
                    for k, q in enumerate(self.node_pos):
                        if norm(sub(q, p)) < 1.0:
                            nid = k
                    if nid is None:
                        nid = len(self.node_pos)
                        self.node_pos.append(p)
                    for st, tv in ((s, ts), (t_, tt)):
                        if all(n != nid for _, n in st.nodes):
                            st.nodes.append((min(max(tv, 0.0), st.length), nid))
        for s in self.streets:
            s.nodes.sort()

    def streets_at(self, nid):
        return [(s, t) for s in self.streets for t, n in s.nodes if n == nid]


class Leg:
    """One street of a route: street, sense (+1 along a->b), lane, t0 -> t1 along the street."""

    def __init__(self, street, sense, lane, t0, t1):
        self.street, self.sense, self.lane, self.t0, self.t1 = street, sense, lane, t0, t1


def random_walk(city, rng, legs_wanted, start=None):
    """A route as legs over the street graph: no U-turns, one-way streets their way only."""
    if start is None:
        cands = [(s, sense) for s in city.streets for sense in (+1, -1) if s.lanes[sense] > 0 and s.nodes]
        s, sense = rng.choice(cands)
        nodes = s.nodes if sense > 0 else [(s.length - t, n) for t, n in reversed(s.nodes)]
        # Start at the street's own end or mid-block before one of its nodes.
        k = rng.randrange(len(nodes))
        prev_t = nodes[k - 1][0] if k > 0 else 0.0
        room = nodes[k][0] - prev_t
        # A start leaves the first turn the room its curve may take (half the block).
        if k == 0 and nodes[0][0] > END_CLEAR + 5:
            t0 = rng.uniform(0, nodes[0][0] - max(END_CLEAR, room / 2)) if rng.random() < 0.5 else 0.0
        elif room > 2 * END_CLEAR + 2:
            t0 = rng.uniform(prev_t + END_CLEAR, nodes[k][0] - max(END_CLEAR, room / 2))
        else:
            return None
        lane = rng.randrange(s.lanes[sense])
        start = (s, sense, lane, t0)
    s, sense, lane, t0 = start
    legs = []
    visited_twice = False
    seen = set()
    while True:
        nodes = s.nodes if sense > 0 else [(s.length - t, n) for t, n in reversed(s.nodes)]
        ahead = [(t, n) for t, n in nodes if t > t0 + END_CLEAR]
        if len(legs) + 1 >= legs_wanted or not ahead:
            # End mid-block in the first gap between nodes (or after the last) with room.
            marks = [t0] + [t for t, _ in ahead] + [s.length]
            for lo, hi in zip(marks, marks[1:]):
                lo_clear = lo + (max(END_CLEAR, (hi - lo) / 2) if lo > t0 else 10.0)
                hi_clear = hi - (END_CLEAR if hi < s.length else 0.0)
                if hi_clear > lo_clear + 1:
                    legs.append(Leg(s, sense, lane, t0, rng.uniform(lo_clear, hi_clear)))
                    return legs
            return None
        # Go through some nodes straight, then turn at one.
        options = []
        for t, n in ahead:
            for s2, t2 in city.streets_at(n):
                if s2 is s:
                    continue
                for sense2 in (+1, -1):
                    if s2.lanes[sense2] == 0:
                        continue
                    t2s = t2 if sense2 > 0 else s2.length - t2
                    d1 = s.dir if sense > 0 else mul(s.dir, -1)
                    d2 = s2.dir if sense2 > 0 else mul(s2.dir, -1)
                    if dot(d1, d2) < -0.9:
                        continue  # a U-turn
                    if s2.length - t2s < END_CLEAR + 2:
                        continue  # nothing to drive onto
                    options.append((t, n, s2, sense2, t2s, cross(d1, d2)))
            if options and rng.random() < 0.6:
                break
        if not options:
            legs_wanted = len(legs) + 1
            continue
        t, n, s2, sense2, t2s, turn = rng.choice(options)
        if n in seen:
            visited_twice = True
        seen.add(n)
        legs.append(Leg(s, sense, lane, t0, t))
        nl = s2.lanes[sense2]
        # Turning drivers keep to the near lanes mostly: right turns to the right lane.
        if turn < 0:
            lane2 = nl - 1 if rng.random() < 0.7 else rng.randrange(nl)
        else:
            lane2 = 0 if rng.random() < 0.7 else rng.randrange(nl)
        s, sense, lane, t0 = s2, sense2, lane2, t2s
        if len(legs) > 20 or (visited_twice and rng.random() < 0.3 and len(legs) >= 3):
            legs_wanted = len(legs) + 1


def leg_corners(legs):
    """The polyline corners of a route: its start, each turn's lane-line intersection, its end."""
    pts = []
    first = legs[0]
    p, d = first.street.lane_line(first.sense, first.lane)
    base = first.street.point(first.t0 if first.sense > 0 else first.street.length - first.t0)
    pts.append(add(project_on(base, p, d), (0, 0)))
    for a, b in zip(legs, legs[1:]):
        pa, da = a.street.lane_line(a.sense, a.lane)
        pb, db = b.street.lane_line(b.sense, b.lane)
        c = intersect(pa, da, pb, db)
        if c is None:
            return None
        pts.append(c)
    last = legs[-1]
    p, d = last.street.lane_line(last.sense, last.lane)
    base = last.street.point(last.t1 if last.sense > 0 else last.street.length - last.t1)
    pts.append(project_on(base, p, d))
    return pts


def project_on(q, p, d):
    return add(p, mul(d, dot(sub(q, p), d)))


def fillet(corners, radii, spacing):
    """Points every `spacing` m along the corners' polyline, each interior corner rounded
    with an arc of its radius (shrunk to fit between its neighbours)."""
    pieces = []
    start = corners[0]
    for i in range(1, len(corners) - 1):
        a, b, c = corners[i - 1], corners[i], corners[i + 1]
        if norm(sub(b, a)) < 1e-6 or norm(sub(c, b)) < 1e-6:
            continue
        d1, d2 = unit(sub(b, a)), unit(sub(c, b))
        turn = math.atan2(cross(d1, d2), dot(d1, d2))
        if abs(turn) < 1e-6:
            continue
        # The arc may use the straight before it (what the previous arc left) and half of
        # the one after it (all of it before the route's end).
        room = min(norm(sub(b, start)), norm(sub(c, b)) / (1 if i == len(corners) - 2 else 2))
        r = min(radii[i], room / math.tan(abs(turn) / 2))
        cut = r * math.tan(abs(turn) / 2)
        t1, t2 = sub(b, mul(d1, cut)), add(b, mul(d2, cut))
        pieces.append(("line", start, t1))
        side = 1 if turn > 0 else -1
        centre = add(t1, mul((-d1[1] * side, d1[0] * side), r))
        a0 = math.atan2(t1[1] - centre[1], t1[0] - centre[0])
        pieces.append(("arc", centre, r, a0, turn))
        start = t2
    pieces.append(("line", start, corners[-1]))
    pts, carry = [], 0.0
    for pc in pieces:
        length = norm(sub(pc[2], pc[1])) if pc[0] == "line" else pc[2] * abs(pc[4])
        s = carry
        while s < length - 1e-9:
            pts.append(point_on(pc, s / length))
            s += spacing
        carry = s - length
    pts.append(corners[-1])
    return pts


def point_on(pc, f):
    if pc[0] == "line":
        return add(pc[1], mul(sub(pc[2], pc[1]), f))
    _, centre, r, a0, sweep = pc
    a = a0 + f * sweep
    return (centre[0] + r * math.cos(a), centre[1] + r * math.sin(a))


def draw(rng, corners, radii, closed=False):
    """Waypoints along `corners` as a user draws them: spacing, noise, now and then a flaw.
    radii[i]: the turn radius at corners[i] (the same for every route making that turn from
    that lane into that lane, as RoadEditor users trace one curve: SUMO has one connection
    per pair of lanes)."""
    spacing = rng.choice([rng.uniform(0.3, 0.8), rng.uniform(0.8, 2.0), 1.0])
    if closed:  # start mid-side so that the closing point is on a straight
        corners = corners[:-1]
        mid = mul(add(corners[0], corners[1]), 0.5)
        corners = [mid] + corners[1:] + [corners[0], mid]
        radii = [0] + radii[1:len(corners) - 1] + [0]
    pts = fillet(corners, radii, spacing)
    noise = rng.choice([0.0, 0.01, 0.02, 0.03])
    out = []
    for i, p in enumerate(pts):
        j, k = min(i + 1, len(pts) - 1), max(i - 1, 0)
        d = sub(pts[j], pts[k])
        n = right_of(unit(d)) if norm(d) > 1e-9 else (0.0, 0.0)
        out.append(add(p, mul(n, rng.uniform(-noise, noise))))
    if closed:
        out[-1] = out[0]
        return out
    flaw = rng.random()
    if len(out) > 40:
        i = rng.randrange(10, len(out) - 10)
        if flaw < 0.06:      # a repeated point
            out.insert(i, out[i])
        elif flaw < 0.12:    # a zero-length segment (a point drawn twice, 0.1 mm apart)
            out.insert(i, add(out[i], (0.0001, 0.0)))
        elif flaw < 0.17:    # a 180-degree spike: one point overshoots and the line comes back
            out.insert(i + 1, add(out[i + 1], mul(sub(out[i + 1], out[i]), 0.8)))
    return out


def bulge(rng, pts, towards_left):
    """A shallow-angle touch: the route leans ~2.6 m towards its neighbouring lane over 40 m
    mid-way along its longest straight stretch, and back."""
    n = len(pts)
    if n < 100:
        return pts
    mid = n // 2
    out = list(pts)
    span = 40.0
    s_acc = [0.0]
    for a, b in zip(pts, pts[1:]):
        s_acc.append(s_acc[-1] + norm(sub(b, a)))
    s_mid = s_acc[mid]
    for i in range(1, n - 1):
        x = (s_acc[i] - s_mid) / (span / 2)
        if abs(x) >= 1:
            continue
        d = unit(sub(pts[i + 1], pts[i - 1])) if norm(sub(pts[i + 1], pts[i - 1])) > 1e-9 else (1.0, 0.0)
        side = (-d[1], d[0]) if towards_left else right_of(d)
        out[i] = add(pts[i], mul(side, 2.6 * (0.5 + 0.5 * math.cos(math.pi * x))))
    return out


def loop_route(city, rng):
    """Around one block (counter-clockwise: left turns), if the block's streets allow it."""
    blocks = []
    for s in city.streets:
        for (ta, na), (tb, nb) in zip(s.nodes, s.nodes[1:]):
            blocks.append((s, na, nb))
    rng.shuffle(blocks)
    for s, na, nb in blocks:
        for sense in (+1, -1):
            if s.lanes[sense] == 0:
                continue
            legs, ok = [], True
            cur_s, cur_sense, from_node, to_node = s, sense, na if sense > 0 else nb, nb if sense > 0 else na
            for _ in range(4):
                nxt = None
                for s2, t2 in city.streets_at(to_node):
                    if s2 is cur_s:
                        continue
                    for sense2 in (+1, -1):
                        if s2.lanes[sense2] == 0:
                            continue
                        d1 = cur_s.dir if cur_sense > 0 else mul(cur_s.dir, -1)
                        d2 = s2.dir if sense2 > 0 else mul(s2.dir, -1)
                        if cross(d1, d2) > 0.9:  # a left turn of about 90 degrees
                            nodes = s2.nodes if sense2 > 0 else [(s2.length - t, n) for t, n in reversed(s2.nodes)]
                            t2s = t2 if sense2 > 0 else s2.length - t2
                            after = [n for t, n in nodes if t > t2s + 1]
                            if after:
                                nxt = (s2, sense2, to_node, after[0])
                if nxt is None:
                    ok = False
                    break
                legs.append((cur_s, cur_sense))
                cur_s, cur_sense, from_node, to_node = nxt
            if ok and cur_s is s and cur_sense == sense:
                corners = []
                ring = legs + [legs[0]]
                for (sa, ea), (sb, eb) in zip(ring, ring[1:]):
                    pa, da = sa.lane_line(ea, sa.lanes[ea] - 1 if sa.oneway else 0)
                    pb, db = sb.lane_line(eb, sb.lanes[eb] - 1 if sb.oneway else 0)
                    c = intersect(pa, da, pb, db)
                    if c is None:
                        break
                    corners.append(c)
                else:
                    if len(corners) == 4:
                        sides = [(sa, ea, sa.lanes[ea] - 1 if sa.oneway else 0) for sa, ea in legs]
                        return corners + [corners[0]], sides
    return None


def block_beside(street, sense, p, before):
    """Length of the block of `street` just before (or after) point p in driving direction
    `sense`: to the neighbouring node or the street's end."""
    t = dot(sub(p, street.a), street.dir)
    ts = [0.0] + [tn for tn, _ in street.nodes] + [street.length]
    if sense < 0:
        before = not before
    if before:
        return t - max([x for x in ts if x < t - 0.5], default=0.0)
    return min([x for x in ts if x > t + 0.5], default=street.length) - t


def generate(seed, scale=1):
    rng = random.Random(seed)
    city = City(rng, scale)
    routes = []
    speed = {s.id: rng.choice([30, 40, 50, 60]) for s in city.streets}

    turn_radius = {}

    def radius(a, b):
        """One radius per turn from a lane into a lane, small enough for the shortest
        block beside the turn: every route making that turn draws the same curve."""
        key = (a[0].id, a[1], a[2], b[0].id, b[1], b[2])
        if key not in turn_radius:
            da = a[0].dir if a[1] > 0 else mul(a[0].dir, -1)
            db = b[0].dir if b[1] > 0 else mul(b[0].dir, -1)
            turn = abs(math.atan2(cross(da, db), dot(da, db)))
            node = intersect(a[0].a, a[0].dir, b[0].a, b[0].dir)
            gaps = [block_beside(a[0], a[1], node, before=True), block_beside(b[0], b[1], node, before=False)]
            limit = (min(gaps) / 2 - 1) / math.tan(turn / 2) if turn > 1e-6 and node else MAX_RADIUS
            turn_radius[key] = max(1.0, min(rng.uniform(MIN_RADIUS, MAX_RADIUS), limit))
        return turn_radius[key]

    def add_route(rid, legs):
        corners = leg_corners(legs)
        if corners is None or len(corners) < 2 or norm(sub(corners[-1], corners[0])) < 1:
            return False
        radii = [0] + [radius((a.street, a.sense, a.lane), (b.street, b.sense, b.lane)) for a, b in zip(legs, legs[1:])] + [0]
        pts = draw(rng, corners, radii)
        if rng.random() < 0.05:
            pts = bulge(rng, pts, rng.random() < 0.5)
        routes.append((rid, pts, speed[legs[0].street.id]))
        return True

    # Multi-lane streets: each lane drawn as its own route along the whole street.
    for s in city.streets:
        for sense in (+1, -1):
            if s.lanes[sense] >= 2 and rng.random() < 0.5:
                for k in range(s.lanes[sense]):
                    add_route(f"Waypoint{len(routes) + 1:02d}", [Leg(s, sense, k, 0.0, s.length)])
    # Routes over the grid: 3-15 streets each.
    target = rng.randint(10, 14) * scale
    tries = 0
    while len(routes) < target + 0 and tries < 400:
        tries += 1
        legs = random_walk(city, rng, rng.randint(3, 15))
        if not legs or len(legs) < 3:
            continue
        name = f"Waypoint{len(routes) + 1:02d}" if rng.random() < 0.85 else f"EmergencyWaypoint{len(routes) + 1:02d}"
        add_route(name, legs)
        # Now and then a second route along the first stretch of this one, then its own way.
        if rng.random() < 0.3:
            first = legs[0]
            more = random_walk(city, rng, rng.randint(3, 8), (first.street, first.sense, first.lane, first.t0))
            if more and len(more) >= 2:
                add_route(f"Waypoint{len(routes) + 1:02d}", more)
    loop = loop_route(city, rng)
    if loop:
        corners, sides = loop
        # corners[i] turns from side i to side i + 1; draw() starts mid-way along side 0.
        radii = [0] + [radius(sides[i], sides[(i + 1) % 4]) for i in (1, 2, 3, 0)]
        pts = draw(rng, corners, radii, closed=True)
        routes.append((f"Loop{len(routes) + 1:02d}", pts, 30))
    return routes


# ---- RoadEditor's own text form ----
def num(v):
    if abs(v - round(v)) < 5e-7:
        r = int(round(v))
        return "0" if r == 0 else str(r)
    text = f"{v:.6f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "0") else text


def roadeditor_text(map_id, routes):
    out = ["{", f'\t"id": "WayPoint_{map_id}",', f'\t"mapId": "{map_id}",', '\t"waypoints": [']
    for ri, (rid, pts, v) in enumerate(routes):
        out += ["\t\t{", f'\t\t\t"id": "{rid}",', '\t\t\t"points": [']
        for pi, (x, y) in enumerate(pts):
            out += ["\t\t\t\t{", f'\t\t\t\t\t"x": {num(x)},', '\t\t\t\t\t"y": 0,', f'\t\t\t\t\t"z": {num(-y)},',
                    f'\t\t\t\t\t"v": {v}', "\t\t\t\t}" + ("]" if pi == len(pts) - 1 else ",")]
        out.append("\t\t}" + ("]," if ri == len(routes) - 1 else ","))
    first = routes[0]
    out += ['\t"properties": [', "\t\t{", '\t\t\t"id": "ego_startPoint",', '\t\t\t"name": "自車の開始地点",',
            '\t\t\t"index": 0,', f'\t\t\t"waypointId": "{first[0]}"', "\t\t},", "\t\t{",
            '\t\t\t"id": "ego_endPoint",', '\t\t\t"name": "自車の終了地点",',
            f'\t\t\t"index": {len(first[1]) - 1},', f'\t\t\t"waypointId": "{first[0]}"', "\t\t}]", "}"]
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seed", type=int, required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--scale", type=int, default=1)
    a = ap.parse_args()
    map_id = f"City.{a.seed}" + (f".x{a.scale}" if a.scale != 1 else "")
    Path(a.out).write_bytes(roadeditor_text(map_id, generate(a.seed, a.scale)).encode("utf-8"))


if __name__ == "__main__":
    main()
