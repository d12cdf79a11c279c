"""Runs one OpenSCENARIO file in each player: the orchestrator (on SUMO, no background traffic)
and the peer, esmini (headless), both at a fixed step; each writes into its own folder.

What each run leaves for the comparison (compare.py):
- ours: trace.csv (every entity every step, its reference point; `driver` says who drove
  it), result.json (verdict, reason, the storyboard transitions as `events`), run.log;
- peer: sim.csv (dat2csv of the recording: every entity every step, its reference point),
  log.txt (every storyboard transition with its time).
"""
import dataclasses
import json
import pathlib
import re
import signal
import subprocess
import time

STEP = 0.05  # s, both players


@dataclasses.dataclass
class Run:
    """How a player's run went: `ok` when it ran (its outputs are there), else `error` says why."""
    folder: pathlib.Path
    ok: bool
    error: str = ""
    end_time: float = 0.0      # last simulated time it recorded
    seconds: float = 0.0       # wall-clock time the run took
    timed_out: bool = False
    crashed: bool = False      # ended without writing its result (killed, or a crash)


# An element of a controller in a file: an entity's ObjectController, a Controller (inline or
# in an AssignControllerAction), a ControllerAction (not TrafficSignalController's).
CONTROLLER_ELEMENT = re.compile(r"<(ObjectController|Controller|ControllerAction|ActivateControllerAction|"
                                r"AssignControllerAction)[\s>/]")
# esmini's log when one of its controllers takes over an entity ("Controller interactiveDriver
# active on domains: Lateral & Longitudinal (mask=0x3)").
PEER_CONTROLLER_ACTIVE = re.compile(r"\] \[info\] Controller (.+) active on domains: .*\(mask=0x0*[1-9a-f]")


def has_controllers(xosc: pathlib.Path) -> bool:
    """The file has a controller element: its runs may depend on what each player's controllers
    do (esmini's own models, SUMO's driver standing in, a system under test)."""
    return bool(CONTROLLER_ELEMENT.search(xosc.read_text(errors="replace")))


def controller_action_names(xosc: pathlib.Path) -> set:
    """The names of the file's storyboard Actions that activate or assign a controller. esmini
    --disable_controllers drops them from the storyboard when it loads the file ("Skipping
    ActivateControllerAction for object Ego due to --disable_controllers"): their Events run
    without them and log no transitions for them, while ours runs them (and logs them)."""
    import xml.etree.ElementTree as ET
    names = set()
    try:
        root = ET.parse(xosc).getroot()
    except ET.ParseError:
        return names
    for action in root.iter("Action"):
        if any(e.tag in ("ControllerAction", "ActivateControllerAction", "AssignControllerAction")
               for e in action.iter()):
            names.add(action.get("name", ""))
    return names


def peer_ran_controller(peer_folder: pathlib.Path) -> bool:
    """esmini activated a controller of its own in this run (its log.txt says so)."""
    log = peer_folder / "log.txt"
    return log.exists() and any(PEER_CONTROLLER_ACTIVE.search(line)
                                for line in log.read_text(errors="replace").splitlines())


def _first_line(text: str, prefix: str = "") -> str:
    for line in text.splitlines():
        if line.strip() and (not prefix or prefix in line):
            return line.strip()
    return ""


def _last_time(csv_file: pathlib.Path) -> float:
    """Time of the last row of a csv whose first column is the time (0 when there are none)."""
    last = 0.0
    with csv_file.open() as f:
        next(f, None)
        for line in f:
            head = line.split(",", 1)[0]
            try:
                last = float(head)
            except ValueError:
                continue
    return last


def _write_csv(esmini_bin: pathlib.Path, folder: pathlib.Path, sim: pathlib.Path, max_time: float) -> None:
    """dat2csv's rows up to `max_time` into sim.csv. esmini records only what changes, and
    dat2csv writes every step: a file whose StopTrigger never fires (entities standing at
    the road's end for hours of simulated time) would give gigabytes."""
    proc = subprocess.Popen([str(esmini_bin / "dat2csv"), "--file", "sim.dat", "--print_csv"], cwd=folder,
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    with sim.open("w") as out:
        header = False
        for line in proc.stdout:
            if not header:  # dat2csv prints esmini's version banner first
                header = line.startswith("time,")
                if not header:
                    continue
            head = line.split(",", 1)[0]
            if head.replace(".", "", 1).isdigit() and float(head) > max_time + 1e-6:
                break
            out.write(line)
    proc.kill()
    proc.wait()


# Each player's option that runs no controller: every entity follows the storyboard.
PEER_CONTROLLERS_OFF = ["--disable_controllers"]
OURS_CONTROLLERS_OFF = ["--controllers", "off"]


def run_peer(esmini_bin: pathlib.Path, xosc: pathlib.Path, folder: pathlib.Path, timeout: float,
             max_time: float, controllers: bool = True) -> Run:
    """esmini --headless at STEP; its recording converted to sim.csv up to `max_time` s. A
    file whose StopTrigger never fires would run forever: the run is stopped after `timeout` s
    of wall-clock time (what it recorded until then is compared). `controllers` False: with
    --disable_controllers."""
    folder.mkdir(parents=True, exist_ok=True)
    start = time.monotonic()
    cmd = [str(esmini_bin / "esmini"), "--headless", "--fixed_timestep", str(STEP), "--osc", str(xosc),
           "--record", "sim.dat", "--disable_stdout", "--logfile_path", "log.txt", "--seed", "1"]
    if not controllers:
        cmd += PEER_CONTROLLERS_OFF
    timed_out = False
    proc = subprocess.Popen(cmd, cwd=folder, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        rc = proc.wait(timeout=timeout)
    except subprocess.TimeoutExpired:
        # SIGINT: esmini closes its recording (a SIGKILL would leave it empty).
        proc.send_signal(signal.SIGINT)
        try:
            proc.wait(timeout=30)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
        rc, timed_out = 0, True
    log = folder / "log.txt"
    log_text = log.read_text(errors="replace") if log.exists() else ""
    if rc != 0 or not (folder / "sim.dat").exists():
        variations = sorted(folder.glob("sim_*_of_*.dat"))
        reason = (_first_line(log_text, "[error]") or
                  (f"a parameter distribution: esmini ran {variations[0].stem.split('_of_')[1]} variations"
                   if variations else f"esmini exit status {rc}, no recording"))
        return Run(folder, False, reason.replace("[] [error] ", ""), seconds=time.monotonic() - start)
    sim = folder / "sim.csv"
    _write_csv(esmini_bin, folder, sim, max_time)
    if not sim.exists() or sim.stat().st_size == 0:
        return Run(folder, False, "dat2csv wrote no rows", seconds=time.monotonic() - start)
    return Run(folder, True, end_time=_last_time(sim), seconds=time.monotonic() - start, timed_out=timed_out)


def run_ours(orchestrator: pathlib.Path, xosc: pathlib.Path, folder: pathlib.Path, max_time: float,
             timeout: float, controllers: bool = True) -> Run:
    """orchestrator run at STEP without background traffic, until the StopTrigger or
    `max_time` s of simulated time. `ok` when it recorded steps (verdict success or failure,
    or an error after the start: the comparison shows how far it went); an error before the
    first step (the file cannot be read or placed) is `error` with the program's reason.
    `controllers` False: with --controllers off."""
    folder.mkdir(parents=True, exist_ok=True)
    start = time.monotonic()
    cmd = [str(orchestrator), "run", str(xosc), "--out", str(folder), "--step", str(STEP), "--traffic", "none",
           "--max-time", f"{max_time:g}", "--no-report", "-q"] + ([] if controllers else OURS_CONTROLLERS_OFF)
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return Run(folder, False, f"no result after {timeout:g} s of wall-clock time", seconds=timeout, timed_out=True)
    seconds = time.monotonic() - start
    result_file, trace = folder / "result.json", folder / "trace.csv"
    result = json.loads(result_file.read_text()) if result_file.exists() else {}
    reason = result.get("reason", "") or _first_line(proc.stderr, "error") or _first_line(proc.stderr)
    # The simulated time it reached (the trace ends earlier when every entity has left the road).
    end = float(result.get("sim_time") or (_last_time(trace) if trace.exists() else 0.0))
    has_rows = trace.exists() and trace.stat().st_size > 0 and sum(1 for _ in trace.open()) > 1
    if not result_file.exists():
        # The program writes result.json whatever the verdict: without one it was killed or
        # crashed (a negative status is the signal), which the comparison must not hide.
        how = f"signal {-proc.returncode}" if proc.returncode < 0 else f"exit status {proc.returncode}"
        return Run(folder, False, f"ended without a result.json ({how}){': ' + reason if reason else ''}",
                   seconds=seconds, crashed=True)
    if not has_rows:
        return Run(folder, False, reason or f"exit status {proc.returncode}", seconds=seconds)
    run = Run(folder, True, end_time=end, seconds=seconds)
    if result.get("verdict") == "error":
        run.error = reason  # ran, then stopped with an error: compared up to there, the error reported
    return run
