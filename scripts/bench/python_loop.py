#!/usr/bin/python3
"""The benchmark's comparison: bench_scenario.json hand-written as a plain Python loop over
SUMO's own `traci` client (Debian package sumo-tools), the way a user writes one.

Per step it does the scenario's work: step SUMO, read the ego's and the scripted cars'
state, check the scene conditions and the collision stop condition, move the scripted cars
(moveToXY, setSpeed, blinkers), find the background vehicles within 75 m of an actor and
count the rest, and write a CSV trace row per actor and a count row.

--neighbours poll (default): every vehicle's position from getIDList (what most loops do);
--neighbours subscribe: context subscriptions around the actors, as the orchestrator does.

SUMO gets the orchestrator's exact command line (`sumo_args` in an orchestrator run's
result.json), so both simulate the same network, traffic, seed and step.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

sys.path.append(os.path.join(os.environ.get("SUMO_HOME", "/usr/share/sumo"), "tools"))
import traci  # noqa: E402
import traci.constants as tc  # noqa: E402

NEAR = 75.0
LENGTHS = {"ego": 4.51, "actor1": 4.61, "actor2": 4.79, "actor3": 3.71}
WIDTHS = {"ego": 2.01, "actor1": 2.24, "actor2": 2.16, "actor3": 1.79}


def start_sumo(cmd):
    """traci.start without its 1 s sleep between connection attempts, which would count
    against the loop in short runs."""
    port = traci.getFreeSocketPort()
    proc = subprocess.Popen(cmd + ["--remote-port", str(port)], stdout=subprocess.DEVNULL)
    for _ in range(3000):
        try:
            traci.init(port, numRetries=0, proc=proc)
            return
        except (traci.FatalTraCIError, traci.TraCIException, OSError):
            time.sleep(0.01)
    raise RuntimeError("sumo did not start")


def load_routes(waypoint_file):
    with open(waypoint_file) as f:
        doc = json.load(f)
    return {w["id"]: [(p["x"], -p["z"]) for p in w["points"]] for w in doc["waypoints"]}


def point_on(route, s):
    """Centre of a car s metres along a route (its points are 1 m apart on this map)."""
    i = max(0, min(int(s), len(route) - 2))
    (x0, y0), (x1, y1) = route[i], route[i + 1]
    f = s - i
    return x0 + f * (x1 - x0), y0 + f * (y1 - y0), math.atan2(y1 - y0, x1 - x0)


def add_car(vid, model_len, model_width, route, s, speed, scripted):
    x, y, _ = point_on(route, s)
    edge, pos, lane = traci.simulation.convertRoad(x + model_len / 2, y)
    edges = traci.simulation.findRoute(edge, SINK).edges
    traci.route.add("r_" + vid, edges)
    traci.vehicletype.copy("DEFAULT_VEHTYPE", "t_" + vid)
    traci.vehicletype.setLength("t_" + vid, model_len)
    traci.vehicletype.setWidth("t_" + vid, model_width)
    traci.vehicle.add(vid, "r_" + vid, typeID="t_" + vid, depart="now", departLane=str(lane),
                      departPos="%.3f" % pos, departSpeed="%.3f" % speed)
    traci.vehicle.setLaneChangeMode(vid, 0)
    if scripted:
        traci.vehicle.setSpeedMode(vid, 0)
    else:
        traci.vehicle.setMaxSpeed(vid, 80 / 3.6)


class Scripted:
    def __init__(self, vid, route, s, speed):
        self.vid, self.route, self.s, self.v = vid, route, s, speed
        self.target, self.rate = speed, None  # rate None: instant
        self.change = None  # (from_route, t0, duration)
        self.signals = 0

    def step(self, dt, t):
        if self.rate is None:
            self.v = self.target
        elif self.v < self.target:
            self.v = min(self.target, self.v + self.rate * dt)
        else:
            self.v = max(self.target, self.v - self.rate * dt)
        self.s += self.v * dt
        x, y, heading = point_on(self.route, self.s)
        if self.change:
            src, t0, dur = self.change
            u = min(1.0, (t - t0) / dur)
            w = 10 * u ** 3 - 15 * u ** 4 + 6 * u ** 5  # quintic lateral profile
            xs, ys, _ = point_on(src, self.s)
            x, y = xs + w * (x - xs), ys + w * (y - ys)
            if u >= 1:
                self.change = None
        L = LENGTHS[self.vid]
        angle = (90 - math.degrees(heading)) % 360
        traci.vehicle.moveToXY(self.vid, "", -1, x + L / 2 * math.cos(heading), y + L / 2 * math.sin(heading),
                               angle, keepRoute=2)
        traci.vehicle.setSpeed(self.vid, self.v)
        traci.vehicle.setSignals(self.vid, self.signals)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--result", required=True, help="result.json of an orchestrator run (its sumo_args)")
    ap.add_argument("--waypoints", required=True)
    ap.add_argument("--steps", type=int, required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--neighbours", choices=["poll", "subscribe"], default="poll")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)

    args = json.load(open(a.result))["sumo_args"]
    if "--log" in args:
        args[args.index("--log") + 1] = os.path.join(a.out, "sumo.log")
    step = float(args[args.index("--step-length") + 1])
    start_sumo(["sumo"] + args)
    global SINK
    SINK = "Waypoint03+Waypoint02+Waypoint01#40"

    routes = load_routes(a.waypoints)
    w1, w2, w3 = routes["Waypoint01"], routes["Waypoint02"], routes["Waypoint03"]
    add_car("ego", 4.51, 2.01, w2, 4000, 0.0, False)
    cars = {"actor1": Scripted("actor1", w2, 4060, 50 / 3.6), "actor2": Scripted("actor2", w1, 3990, 50 / 3.6),
            "actor3": Scripted("actor3", w3, 4030, 45 / 3.6)}
    for c in cars.values():
        add_car(c.vid, LENGTHS[c.vid], WIDTHS[c.vid], c.route, c.s, c.v, True)
    actors = ["ego"] + list(cars)
    subscribed = set()

    trace = open(os.path.join(a.out, "trace.csv"), "w")
    trace.write("time,scene_id,actor_id,x,y,heading,speed,lane,lane_pos\n")
    counts = open(os.path.join(a.out, "counts.csv"), "w")
    counts.write("time,background_vehicles,nearby_vehicles\n")
    scene, entered = 0, 0.0
    verdict = "max-time"
    for _ in range(a.steps):
        traci.simulationStep()
        t = traci.simulation.getTime()
        state = {}
        for vid in actors:
            if a.neighbours == "subscribe":
                if vid not in subscribed and vid in traci.simulation.getDepartedIDList():
                    traci.vehicle.subscribe(vid, [tc.VAR_POSITION, tc.VAR_SPEED, tc.VAR_ANGLE, tc.VAR_LANE_INDEX,
                                                  tc.VAR_LANEPOSITION])
                    traci.vehicle.subscribeContext(vid, tc.CMD_GET_VEHICLE_VARIABLE, NEAR, [tc.VAR_POSITION])
                    subscribed.add(vid)
                r = traci.vehicle.getSubscriptionResults(vid)
                if r:
                    state[vid] = (r[tc.VAR_POSITION], r[tc.VAR_SPEED], r[tc.VAR_ANGLE], r[tc.VAR_LANE_INDEX],
                                  r[tc.VAR_LANEPOSITION])
            else:
                try:
                    state[vid] = (traci.vehicle.getPosition(vid), traci.vehicle.getSpeed(vid),
                                  traci.vehicle.getAngle(vid), traci.vehicle.getLaneIndex(vid),
                                  traci.vehicle.getLanePosition(vid))
                except traci.TraCIException:
                    pass  # not inserted yet
        # Neighbours and counts.
        near = set()
        if a.neighbours == "subscribe":
            background = traci.vehicle.getIDCount() - len(state)
            for vid in state:
                near.update(v for v in traci.vehicle.getContextSubscriptionResults(vid) if v not in LENGTHS)
        else:
            ids = traci.vehicle.getIDList()
            background = len(ids) - len(state)
            for v in ids:
                if v in LENGTHS:
                    continue
                px, py = traci.vehicle.getPosition(v)
                if any(math.hypot(px - s[0][0], py - s[0][1]) <= NEAR for s in state.values()):
                    near.add(v)
        counts.write("%.3f,%d,%d\n" % (t, background, len(near)))
        for vid, (pos, v, ang, lane, lpos) in state.items():
            trace.write("%.3f,%d,%s,%.3f,%.3f,%.4f,%.3f,%d,%.3f\n" % (t, scene, vid, pos[0], pos[1],
                                                                       math.radians(90 - ang), v, lane, lpos))
        if "ego" not in state:
            continue
        ego_x, ego_v = state["ego"][0][0], state["ego"][1]
        # Stop conditions: a collision of the ego, or the ego at the end of the road.
        if any("ego" in (c.collider, c.victim) for c in traci.simulation.getCollisions()):
            verdict = "collision"
            break
        if ego_x >= 9900:
            verdict = "end of road"
            break
        # Scene transitions.
        since = t - entered
        nxt = None
        if scene == 0 and (ego_v >= 30 / 3.6 or t >= 5):
            nxt = 1
            cars["actor2"].target, cars["actor2"].rate = ego_v + 15 / 3.6, None
            cars["actor3"].target, cars["actor3"].rate = 55 / 3.6, 2.0
        elif scene == 1 and (cars["actor2"].s - (ego_x - 4.51 / 2) > 15 or t >= 12):
            nxt = 2
            cars["actor2"].signals = 1
        elif scene == 2 and since >= 2:
            nxt = 3
            cars["actor2"].change = (cars["actor2"].route, t, 4.0)
            cars["actor2"].route = w2
        elif scene in (3, 5) and since >= (4 if scene == 3 else 5):
            nxt = 4
            cars["actor2"].signals = 0
            cars["actor2"].target, cars["actor2"].rate = 55 / 3.6, 2.0
            cars["actor1"].target, cars["actor1"].rate = 40 / 3.6, 1.0
        elif scene == 4 and since >= 5:
            nxt = 5
            cars["actor1"].target, cars["actor1"].rate = 60 / 3.6, 1.0
            cars["actor3"].target, cars["actor3"].rate = 65 / 3.6, 1.0
        if nxt is not None:
            scene, entered = nxt, t
        if scene in (1, 2, 3):  # relative speed, re-evaluated every step
            cars["actor2"].target = ego_v + 15 / 3.6
        for c in cars.values():
            c.step(step, t + step)
    traci.close()
    trace.close()
    counts.close()
    print("python loop (%s): %s after %.2f s simulated" % (a.neighbours, verdict, t))


if __name__ == "__main__":
    start = time.time()
    main()
    print("wall %.3f s" % (time.time() - start))
