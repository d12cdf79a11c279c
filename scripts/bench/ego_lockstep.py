#!/usr/bin/env python3
"""Lockstep benchmark of the external ego plug-in server.

The same loop -- simulationStep, read one subscription, send one command -- runs with SUMO's
Python client against `orchestrator run --ego-port` and against a plain `sumo --remote-port`
on the same net with the same step and SUMO options. Prints steps per second of both and
their ratio (orchestrator / plain SUMO): the figure docs/ego-plugin.md quotes. The plain loop
runs twice: as written (SUMO's default lane-change mode, 1621) and with the lane-change mode
the orchestrator gives an ego its plug-in drives (1536: no lane changes of SUMO's own; SUMO's
sublane model then costs ~20,000 more instructions per step for the one vehicle), so the
same simulation is compared too.

  ego_lockstep.py --orchestrator build/bin/orchestrator [--steps 2000]
  ego_lockstep.py --instructions     # both servers under valgrind's callgrind: instructions per step
                                     # (independent of the machine's load; 300 and 1300 steps, the difference)
(run with /usr/bin/python3 and PYTHONPATH=/usr/share/sumo/tools; ego_bench.sh does that)
"""
import argparse
import json
import os
import re
import socket
import subprocess
import sys
import tempfile
import time

import traci
import traci.constants as tc

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
NET = os.path.join(ROOT, "sumo_nets", "ALKS_Road", "ALKS_Road.net.xml")


# The ego alone on the 10 km ALKS road; nothing ends the run before the bench does.
SCENARIO = {
    "map_id": "ALKS_Road",
    "actors": {"ego": {"actor_id": 0, "model_id": "vehicle.toyota.prius"}, "others": []},
    "scenario": {
        "opening_scene": {"ego": {"start_position": {"wp_id": "Waypoint02", "wp_idx": 5},
                                  "end_position": {"wp_id": "Waypoint02", "wp_idx": 9000}},
                          "others": [], "next_scenes": [1]},
        "scenes": [],
        "ending_scenes": [{"scene_id": 1, "conditions": {"and": [{"simulation_time": {"comparison": ">=", "value": 3000}}]}}],
    },
}


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def cpu_seconds(pid):
    """User + system CPU time of a process so far (/proc/PID/stat, fields 14 and 15)."""
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def loop(conn, steps, pid):
    """The plug-in's step: advance, read the ego's speed from its subscription, command.
    Returns steps/s and the server's CPU microseconds per step during the loop: on a shared
    machine the rate follows how soon each process gets a core again, the CPU time what the
    server computes."""
    conn.vehicle.subscribe("ego", [tc.VAR_SPEED])
    start = time.perf_counter()
    cpu_start = cpu_seconds(pid)
    for _ in range(steps):
        conn.simulationStep()
        conn.vehicle.getSubscriptionResults("ego")[tc.VAR_SPEED]
        conn.vehicle.setSpeed("ego", 20.0)
    cpu_us = (cpu_seconds(pid) - cpu_start) / steps * 1e6
    return steps / (time.perf_counter() - start), cpu_us


def bench_orchestrator(binary, steps, tmp, wrap=()):
    scenario = os.path.join(tmp, "bench.json")
    with open(scenario, "w") as f:
        json.dump(SCENARIO, f)
    port = free_port()
    proc = subprocess.Popen(list(wrap) + [binary, "run", scenario, "--out", os.path.join(tmp, "out"), "-q",
                                          "--no-report", "--ego-port", str(port), "--ego-wait", "300",
                                          "--ego-timeout", "300"],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return drive(proc, port, steps, warm_up=False)


def drive(proc, port, steps, warm_up, lane_change_mode=None):
    """Connects to the server proc listens on, runs the loop, and never leaves proc behind.
    warm_up: one step first (a plain SUMO departs the ego in its first step)."""
    try:
        conn = traci.connect(port, numRetries=60)
        if warm_up:
            conn.simulationStep()
        if lane_change_mode is not None:
            conn.vehicle.setLaneChangeMode("ego", lane_change_mode)
        result = loop(conn, steps, proc.pid)
        conn.close()
        proc.wait(timeout=60)
        return result
    finally:
        if proc.poll() is None:
            proc.kill()


# orchestrator/run/ego_link.hpp: kPluginEgoLaneChangeMode
PLUGIN_EGO_LANE_CHANGE_MODE = 1621 & ~0xFF


def bench_plain_sumo(steps, tmp, wrap=(), lane_change_mode=None):
    # The road's edges in order (the map may split it where lanes start or end); SUMO routes
    # the trip from the first to the last.
    with open(NET) as f:
        edges = [e for e in re.findall(r'<edge id="([^":][^"]*)"', f.read())]
    edges.sort(key=lambda e: int(e.rsplit("#", 1)[1]) if "#" in e else 0)
    routes = os.path.join(tmp, "ego.rou.xml")
    with open(routes, "w") as f:
        f.write('<routes><trip id="ego" from="%s" to="%s" depart="0" departLane="1" departPos="10"/></routes>'
                % (edges[0], edges[-1]))
    port = free_port()
    # The orchestrator's SUMO options (orchestrator/run/simulator.cpp), so both simulate alike.
    proc = subprocess.Popen(list(wrap) + ["sumo", "-n", NET, "-r", routes, "--remote-port", str(port), "--step-length", "0.05",
                             "--seed", "42", "--lateral-resolution", "0.8", "--collision.action", "warn",
                             "--collision.check-junctions", "true", "--collision.mingap-factor", "0",
                             "--time-to-teleport", "-1", "--ignore-junction-blocker", "20", "--no-step-log",
                             "true", "--duration-log.disable", "true"],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return drive(proc, port, steps, warm_up=True, lane_change_mode=lane_change_mode)


def instructions_per_step(bench, tmp, name):
    """Instructions the server executes per lockstep step: callgrind's totals of a 1300-step
    and a 300-step run, their difference over 1000 steps (start-up and shut-down cancel)."""
    totals = []
    for steps in (300, 1300):
        out = os.path.join(tmp, "%s_%d.callgrind" % (name, steps))
        bench(steps, tmp, ["valgrind", "--tool=callgrind", "--callgrind-out-file=" + out])
        with open(out) as f:
            totals.append(int(re.search(r"^(?:summary|totals): (\d+)", f.read(), re.M).group(1)))
    return (totals[1] - totals[0]) / 1000


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--orchestrator", default=os.path.join(ROOT, "build", "bin", "orchestrator"))
    p.add_argument("--steps", type=int, default=2000)
    p.add_argument("--repeat", type=int, default=5, help="interleaved pairs")
    p.add_argument("--instructions", action="store_true", help="instructions per step under callgrind instead")
    a = p.parse_args()
    if a.instructions:
        with tempfile.TemporaryDirectory() as tmp:
            orch = instructions_per_step(lambda n, t, w: bench_orchestrator(a.orchestrator, n, t, w), tmp, "orch")
            plain = instructions_per_step(bench_plain_sumo, tmp, "sumo")
            plain_lc = instructions_per_step(
                lambda n, t, w: bench_plain_sumo(n, t, w, PLUGIN_EGO_LANE_CHANGE_MODE), tmp, "sumo_lc")
        print("lockstep server instructions per step (callgrind, 1000 steps):")
        print("  orchestrator --ego-port               : %8.0f" % orch)
        print("  plain sumo --remote-port              : %8.0f  ratio %.2f" % (plain, orch / plain))
        print("  plain sumo, the plug-in ego's LC mode : %8.0f  ratio %.2f" % (plain_lc, orch / plain_lc))
        return 0
    # Interleaved pairs: a slow spell of the shared machine hits both sides of a pair.
    orch, plain, orch_cpu, plain_cpu, lc, lc_cpu = [], [], [], [], [], []
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(a.repeat):
            rate, cpu = bench_orchestrator(a.orchestrator, a.steps, tmp)
            orch.append(rate)
            orch_cpu.append(cpu)
            rate, cpu = bench_plain_sumo(a.steps, tmp)
            plain.append(rate)
            plain_cpu.append(cpu)
            rate, cpu = bench_plain_sumo(a.steps, tmp, lane_change_mode=PLUGIN_EGO_LANE_CHANGE_MODE)
            lc.append(rate)
            lc_cpu.append(cpu)
    pairs = sorted(o / p for o, p in zip(orch, plain))
    lc_pairs = sorted(o / p for o, p in zip(orch, lc))
    print("lockstep, %d steps, Python traci, 1 subscription + 1 command per step (%d interleaved pairs; "
          "load average %.1f)" % (a.steps, a.repeat, os.getloadavg()[0]))
    print("  orchestrator --ego-port : %8.0f steps/s (best)" % max(orch))
    print("  plain sumo --remote-port: %8.0f steps/s (best)" % max(plain))
    print("  ratio                   : %8.2f (median of the pairs; %.2f-%.2f)" % (
        pairs[len(pairs) // 2], pairs[0], pairs[-1]))
    print("  plain sumo, LC mode %d : %8.0f steps/s (best); ratio %.2f (%.2f-%.2f); server CPU %.0f us" % (
        PLUGIN_EGO_LANE_CHANGE_MODE, max(lc), lc_pairs[len(lc_pairs) // 2], lc_pairs[0], lc_pairs[-1],
        sorted(lc_cpu)[len(lc_cpu) // 2]))
    cpu_pairs = sorted(o / p for o, p in zip(orch_cpu, plain_cpu))
    print("  server CPU per step     : orchestrator %.0f us, plain sumo %.0f us (medians); ratio %.2f (%.2f-%.2f)" % (
        sorted(orch_cpu)[len(orch_cpu) // 2], sorted(plain_cpu)[len(plain_cpu) // 2],
        cpu_pairs[len(cpu_pairs) // 2], cpu_pairs[0], cpu_pairs[-1]))


if __name__ == "__main__":
    sys.exit(main())
