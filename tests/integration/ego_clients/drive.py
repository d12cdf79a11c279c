#!/usr/bin/env python3
"""An ego plug-in on SUMO's own Python TraCI client, for the integration tests.

It connects to `orchestrator run ... --ego-port PORT` exactly as it would connect to SUMO,
perceives through subscriptions, steers with set commands, and writes what it saw to a JSON
summary the tests check next to the orchestrator's trace.

Modes:
  hold       setSpeed(--speed) every step (SUMO's speed checks stay on); optional lane
             changes and blinker; probes what the server refuses.
  perceive   SUMO's speed checks off; drives at --speed and brakes for the vehicle ahead in
             its lane, which it knows only from its context subscription.
  blind      SUMO's speed checks off; --speed whatever is ahead (the negative control).
  census     setSpeed(--speed) every step; a context subscription of --range around the
             ego, checked every 10th step against every vehicle's position (getIDList).
  disconnect / hang / close   step --after times, then vanish / stop answering / close.
  handover   waits for the ego's `orch.hand_over` to turn "1" (an OpenSCENARIO
             ActivateControllerAction), only watching until then; then SUMO's speed checks off
             and setSpeed(--speed) every step.
"""
import argparse
import json
import math
import os
import sys
import time

import traci
import traci.constants as tc


def parse():
    p = argparse.ArgumentParser()
    p.add_argument("--port", type=int, required=True)
    p.add_argument("--mode", default="hold")
    p.add_argument("--speed", type=float, default=15.0)
    p.add_argument("--range", type=float, default=100.0)
    p.add_argument("--after", type=int, default=20)
    p.add_argument("--lane-change", action="append", default=[], help="T:LANE")
    p.add_argument("--signals-at", type=float)
    p.add_argument("--summary")
    return p.parse_args()


def ahead_in_lane(ego, around):
    """The nearest vehicle ahead in the ego's lane: (id, bumper-to-bumper gap)."""
    best = None
    for vid, v in around.items():
        if vid == "ego" or v[tc.VAR_ROAD_ID] != ego[tc.VAR_ROAD_ID] or v[tc.VAR_LANE_INDEX] != ego[tc.VAR_LANE_INDEX]:
            continue
        gap = v[tc.VAR_LANEPOSITION] - v[tc.VAR_LENGTH] - ego[tc.VAR_LANEPOSITION]
        if gap > -0.5 and (best is None or gap < best[1]):
            best = (vid, gap)
    return best


def main():
    a = parse()
    summary = {"mode": a.mode, "steps": 0, "hand_over": [], "perceived": None, "min_gap": None, "vehicles": None}
    version = traci.init(a.port, numRetries=60)
    summary["version"] = list(version)
    traci.setOrder(1)
    traci.simulation.setParameter("", "orch.client", "integration test client (Python traci)")
    traci.vehicle.subscribe("ego", [tc.VAR_SPEED, tc.VAR_ROAD_ID, tc.VAR_LANE_INDEX, tc.VAR_LANEPOSITION,
                                    tc.VAR_POSITION, tc.VAR_PARAMETER],
                            parameters={tc.VAR_PARAMETER: ("s", "orch.hand_over")})
    if a.mode in ("perceive", "blind"):
        traci.vehicle.setSpeedMode("ego", 0)  # the plug-in alone decides the speed
    if a.mode == "perceive":
        traci.vehicle.subscribeContext("ego", tc.CMD_GET_VEHICLE_VARIABLE, a.range,
                                       [tc.VAR_ROAD_ID, tc.VAR_LANE_INDEX, tc.VAR_LANEPOSITION, tc.VAR_LENGTH])
    if a.mode == "census":
        traci.vehicle.subscribeContext("ego", tc.CMD_GET_VEHICLE_VARIABLE, a.range, [tc.VAR_POSITION, tc.VAR_SPEED])
        summary["census"] = {"checks": 0, "mismatches": [], "most": 0}
    lane_changes = [(float(t), int(lane)) for t, lane in (x.split(":") for x in a.lane_change)]
    hand_over = ""
    try:
        while traci.simulation.getMinExpectedNumber() > 0:
            traci.simulationStep()
            summary["steps"] += 1
            now = traci.simulation.getTime()
            ego = traci.vehicle.getSubscriptionResults("ego")
            if ego.get(tc.VAR_PARAMETER, "") != hand_over:
                hand_over = ego.get(tc.VAR_PARAMETER, "")
                summary["hand_over"].append([now, hand_over])
                if a.mode == "handover" and hand_over == "1":
                    traci.vehicle.setSpeedMode("ego", 0)  # the commanded speed is exact
            if summary["vehicles"] is None:
                summary["vehicles"] = sorted(traci.vehicle.getIDList())
            if a.mode == "handover" and hand_over != "1":
                continue  # the orchestrator drives the ego until the hand-over
            if a.mode in ("disconnect", "hang", "close") and summary["steps"] >= a.after:
                summary["last_time"] = now
                write(a.summary, summary)
                if a.mode == "disconnect":
                    os._exit(0)  # the process dies: the socket closes without a TraCI close
                if a.mode == "hang":
                    time.sleep(600)
                traci.close()
                return
            speed = a.speed
            if a.mode == "perceive":
                ahead = ahead_in_lane(ego, traci.vehicle.getContextSubscriptionResults("ego"))
                if ahead:
                    if summary["perceived"] is None:
                        summary["perceived"] = {"id": ahead[0], "time": now, "gap": ahead[1]}
                    summary["min_gap"] = ahead[1] if summary["min_gap"] is None else min(summary["min_gap"], ahead[1])
                    # Stop 3 m behind it at 3 m/s^2.
                    speed = min(speed, math.sqrt(max(0.0, 2 * 3.0 * (ahead[1] - 3.0))))
            if a.mode == "census":
                if "ego" not in traci.vehicle.getIDList():  # it drove off the end of its route
                    summary["census"].setdefault("ego_left", now)
                    continue
                if summary["steps"] % 10 == 0:
                    census(a.range, now, summary["census"])
            traci.vehicle.setSpeed("ego", speed)
            for t, lane in lane_changes:
                if abs(now - t) < 1e-6:
                    traci.vehicle.changeLane("ego", lane, 3.0)
            if a.signals_at is not None and now >= a.signals_at - 1e-6:
                traci.vehicle.setSignals("ego", 2)  # SUMO recomputes the signals every step
            if summary["steps"] == 5 and a.mode == "hold":
                probe(summary)
        summary["ended_at"] = traci.simulation.getTime()
        traci.close()
    except traci.exceptions.FatalTraCIError as e:
        summary["fatal"] = str(e)
    write(a.summary, summary)


def probe(summary):
    """What the server refuses, and that the connection survives it."""
    try:
        traci.vehicle.setSpeed("actor1", 0)
        summary["refused"] = None
    except traci.TraCIException as e:
        summary["refused"] = str(e)
    try:
        traci.lane.getLength("nosuch_0")
        summary["not_implemented"] = None
    except traci.TraCIException as e:
        summary["not_implemented"] = str(e)
    summary["vehicles"] = sorted(traci.vehicle.getIDList())
    summary["leader"] = traci.vehicle.getLeader("ego", 1000)
    summary["delta_t"] = traci.simulation.getDeltaT()


def census(reach, now, out):
    """The context subscription's answer against the brute-force one, ids and values."""
    seen = traci.vehicle.getContextSubscriptionResults("ego")
    ex, ey = traci.vehicle.getPosition("ego")
    truth = {}
    for vid in traci.vehicle.getIDList():
        x, y = traci.vehicle.getPosition(vid)
        if math.sqrt((x - ex) ** 2 + (y - ey) ** 2) <= reach:  # SUMO's test
            truth[vid] = {tc.VAR_POSITION: (x, y), tc.VAR_SPEED: traci.vehicle.getSpeed(vid)}
    out["checks"] += 1
    out["most"] = max(out["most"], len(truth))
    got = {vid: {tc.VAR_POSITION: tuple(v[tc.VAR_POSITION]), tc.VAR_SPEED: v[tc.VAR_SPEED]} for vid, v in seen.items()}
    if got != truth:
        out["mismatches"].append({"time": now, "only_seen": sorted(set(got) - set(truth)),
                                  "only_truth": sorted(set(truth) - set(got))})


def write(path, summary):
    if path:
        with open(path, "w") as f:
            json.dump(summary, f, indent=1)


if __name__ == "__main__":
    sys.exit(main())
