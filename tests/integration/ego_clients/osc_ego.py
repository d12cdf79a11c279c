#!/usr/bin/env python3
"""An external ego for OpenSCENARIO runs, on SUMO's own Python TraCI client.

It connects to `orchestrator run FILE.xosc --ego-port PORT`, watches the ego's vehicle
parameter `orch.hand_over` and leaves the driving to the orchestrator (SUMO's car-following
model, the storyboard's lane changes) until it turns "1" (an ActivateControllerAction on the
ego's controller); from then on it drives at --speed with SUMO's speed checks off. It writes
what it saw (speeds before the hand-over, when it came) to a JSON summary for the test.
"""
import argparse
import json
import sys

import traci
import traci.constants as tc


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--port", type=int, required=True)
    p.add_argument("--speed", type=float, default=12.0)
    p.add_argument("--summary")
    a = p.parse_args()
    summary = {"steps": 0, "hand_over": [], "speeds_before": [], "vehicles": None}
    traci.init(a.port, numRetries=60)
    traci.simulation.setParameter("", "orch.client", "OpenSCENARIO ego test client (Python traci)")
    traci.vehicle.subscribe("ego", [tc.VAR_SPEED, tc.VAR_PARAMETER], parameters={tc.VAR_PARAMETER: ("s", "orch.hand_over")})
    driving = False
    hand_over = ""
    try:
        while traci.simulation.getMinExpectedNumber() > 0:
            traci.simulationStep()
            summary["steps"] += 1
            now = traci.simulation.getTime()
            ego = traci.vehicle.getSubscriptionResults("ego")
            if summary["vehicles"] is None:
                summary["vehicles"] = sorted(traci.vehicle.getIDList())
            if ego.get(tc.VAR_PARAMETER, "") != hand_over:
                hand_over = ego.get(tc.VAR_PARAMETER, "")
                summary["hand_over"].append([now, hand_over])
            if hand_over == "1" and not driving:
                traci.vehicle.setSpeedMode("ego", 0)  # the ego's speed is exactly what it commands
                driving = True
            if driving:
                traci.vehicle.setSpeed("ego", a.speed)
            else:
                summary["speeds_before"].append([now, ego[tc.VAR_SPEED]])
        summary["ended_at"] = traci.simulation.getTime()
        traci.close()
    except traci.exceptions.FatalTraCIError as e:
        summary["fatal"] = str(e)
    if a.summary:
        with open(a.summary, "w") as f:
            json.dump(summary, f, indent=1)


if __name__ == "__main__":
    sys.exit(main())
