"""Compares a run of the orchestrator with the peer's run of the same file.

Positions: every entity that follows the storyboard in our run (trace.csv `driver` is
`script` in every row: SUMO, the reference driver and a plug-in drive the others), every
SAMPLE s from 0 to the end both runs reached, by its reference point. Both players record
the OpenSCENARIO reference point in the OpenDRIVE frame: esmini its entity's origin (the
rear axle centre of a vehicle), our trace the same point (SUMO's vehicle centre moved back
by the bounding box centre, openscenario_runner.cpp), so the points compare as they are.

Transitions: every start, end, stop and skip transition of a storyboard element (its name,
the transition, the time): ours from result.json `events`, the peer's from log.txt
(`[t] [info] NAME fromState -> xTransition -> toState`), within one step.
"""
import collections
import csv
import dataclasses
import json
import math
import pathlib
import re

from . import departures

SAMPLE = 0.5        # s between compared positions
TOLERANCE = 0.10    # m
STEP = 0.05         # s: transitions agree within one step
TRANSITIONS = ("startTransition", "endTransition", "stopTransition", "skipTransition")
# esmini logs its Init actions as "Init <entity> <ActionType>" (the standard gives them no
# names and no transitions; we do not log them): also an entity name with spaces ("Init ego
# jerk LongitudinalAction"), a global action without entity ("Init EnvironmentAction") and the
# copies it makes for the ghost of its own follow-ghost controller ("Init Ego
# TeleportAction_ghost-copy", acting on its helper entity Ego_ghost, not on the storyboard's).
PEER_INIT = re.compile(r"^Init (.+ )?[A-Z]\w*Action(_ghost-copy)?$")
# Actions esmini's own controllers inject into a run (its NaturalDriver's lane changes:
# "Adding action LaneChangeAction_0", then that name's transitions): no element of the file's
# storyboard, so not transitions of the standard; left out.
PEER_INJECTED = re.compile(r"^\[\d+\.\d+\] \[info\] Adding action (.+?)\s*$")
PEER_LINE = re.compile(r"^\[(\d+\.\d+)\] \[info\] (.+) (\w+State) -> (\w+Transition) -> (\w+State)\s*$")
# esmini calls the Storyboard element "storyBoard"; our log gives it no name (type storyboard).
# Its start (at 0 s in both) is not in our log: only its stop is compared.
PEER_NAMES = {"storyBoard": "Storyboard"}
STORYBOARD = "Storyboard"


@dataclasses.dataclass
class Difference:
    what: str       # "position" or "transition"
    subject: str    # entity or "element transition"
    time: float
    ours: str
    peer: str

    def text(self) -> str:
        return f"{self.subject} at {self.time:.2f} s: ours {self.ours}, peer {self.peer}"


@dataclasses.dataclass
class Comparison:
    compared_entities: list
    not_compared: dict          # entity -> why (who drove it)
    end_time: float             # compared up to
    positions: int              # compared points
    transitions: int            # compared transitions
    differences: list           # Difference, the first of each entity / element first, by time
    # The peer's departures from the standard's transitions that account for differences
    # (departures.py), and the differences left once they are accounted for.
    departures: list = dataclasses.field(default_factory=list)
    beyond_departures: list = dataclasses.field(default_factory=list)

    @property
    def matches(self) -> bool:
        return not self.differences

    @property
    def departs_only(self) -> bool:
        """Differs, but only by the peer's cited departures from the standard."""
        return bool(self.differences) and not self.beyond_departures


def _key(t: float) -> int:
    return int(round(t * 1000))


def read_our_trace(trace: pathlib.Path):
    """{entity: {time_ms: (x, y, z)}} and {entity: set of drivers}; z is None in a trace without it."""
    points, drivers = collections.defaultdict(dict), collections.defaultdict(set)
    with trace.open(newline="") as f:
        for row in csv.DictReader(f):
            name = row["actor_id"]
            z = float(row["z"]) if row.get("z") not in (None, "") else None
            points[name][_key(float(row["time"]))] = (float(row["x"]), float(row["y"]), z)
            drivers[name].add(row["driver"])
    return points, drivers


def read_peer_trace(sim_csv: pathlib.Path):
    """{entity: {time_ms: (x, y, z)}} from esmini's dat2csv output (columns with spaces)."""
    points = collections.defaultdict(dict)
    with sim_csv.open(newline="") as f:
        reader = csv.reader(f, skipinitialspace=True)
        header = [h.strip() for h in next(reader)]
        col = {h: i for i, h in enumerate(header)}
        for row in reader:
            if len(row) < len(header):
                continue
            z = float(row[col["z"]]) if "z" in col else None
            points[row[col["name"]]][_key(float(row[col["time"]]))] = (float(row[col["x"]]), float(row[col["y"]]), z)
    return points


def read_our_transitions(result_json: pathlib.Path, types: dict = None) -> list:
    """[(time, name, transition)] from result.json events ("<type> <name> <transition>");
    `types`, when given, gets each element's type by name."""
    result = json.loads(result_json.read_text())
    out = []
    for e in result.get("events", []):
        if e.get("kind") not in ("storyboard", "action"):
            continue
        parts = e["text"].split(" ")
        if len(parts) < 3 or parts[-1] not in TRANSITIONS:
            continue
        name = " ".join(parts[1:-1]).strip() or (STORYBOARD if parts[0] == "storyboard" else "")
        if types is not None:
            types[name] = parts[0]
        out.append((float(e["time"]), name, parts[-1]))
    return out


def read_peer_transitions(log_txt: pathlib.Path) -> list:
    out, injected = [], set()
    for line in log_txt.read_text(errors="replace").splitlines():
        added = PEER_INJECTED.match(line)
        if added:
            injected.add(added.group(1))
            continue
        m = PEER_LINE.match(line)
        if not m or m.group(4) not in TRANSITIONS or PEER_INIT.match(m.group(2)) or m.group(2) in injected:
            continue
        name = PEER_NAMES.get(m.group(2), m.group(2))
        if name == STORYBOARD and m.group(4) == "startTransition":
            continue
        out.append((float(m.group(1)), name, m.group(4)))
    return out


def stop_time_difference(result_json: pathlib.Path, peer_stop: float):
    """The Difference of the Storyboard's stop in our run (result.json) from the peer's time,
    or None within one step."""
    ours = [t for t, name, tr in read_our_transitions(result_json) if name == STORYBOARD and tr == "stopTransition"]
    if ours and abs(ours[0] - peer_stop) <= STEP + 1e-6:
        return None
    return Difference("transition", f"{STORYBOARD} stopTransition", min([peer_stop] + ours[:1]),
                      f"{ours[0]:.2f} s" if ours else "none", f"{peer_stop:.2f} s")


def _fmt_point(p) -> str:
    if not p:
        return "absent"
    return f"({p[0]:.3f}, {p[1]:.3f}" + (f", {p[2]:.3f})" if len(p) > 2 and p[2] is not None else ")")


def _distance(a, b) -> float:
    """Between reference points; in 3D when both players give z (roads with elevation)."""
    dz = a[2] - b[2] if len(a) > 2 and len(b) > 2 and a[2] is not None and b[2] is not None else 0.0
    return math.sqrt((a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2 + dz ** 2)


def compare_positions(ours, drivers, peer, end_time: float):
    """Differences (the first per entity), the entities compared, those not compared, count."""
    compared = sorted(n for n, d in drivers.items() if d == {"script"})
    not_compared = {n: "driven by " + "/".join(sorted(d - {"script"})) for n, d in drivers.items()
                    if d != {"script"}}
    differences, count = [], 0
    samples = [i * SAMPLE for i in range(int(math.floor(end_time / SAMPLE + 1e-9)) + 1)]
    for name in compared:
        for t in samples:
            k = _key(t)
            a, b = ours[name].get(k), peer.get(name, {}).get(k)
            if a is None and b is None:
                continue
            if a is None or b is None:
                # Added or deleted in a step next to this one by the other player (esmini records
                # an entity an AddEntityAction adds from the step after): within one step, as
                # the transitions.
                missing = ours[name] if a is None else peer.get(name, {})
                if any(_key(t + d) in missing for d in (-STEP, STEP)):
                    continue
                count += 1
                differences.append(Difference("position", name, t, _fmt_point(a), _fmt_point(b)))
                break
            count += 1
            if a[2] is None or b[2] is None:  # heights compared only where both players give them
                a, b = a[:2], b[:2]
            gap = _distance(a, b)
            if gap > TOLERANCE:
                differences.append(Difference("position", name, t, _fmt_point(a), f"{_fmt_point(b)}, {gap:.3f} m apart"))
                break
    return differences, compared, not_compared, count


def compare_transitions(ours: list, peer: list, end_time: float):
    """Pairs the k-th occurrence of each (element, transition) in both runs; a time off by
    more than one step, or an occurrence in one run only (before end_time), is a difference.
    An occurrence up to one step after end_time is paired too (and then compared), but not
    missed when the other run has none: a run that stops at its StopTrigger one step before
    the other (within the tolerance) ends the comparison there, and the other's stop is one
    step later."""
    def grouped(items):
        g = collections.defaultdict(list)
        for t, name, transition in items:
            if t <= end_time + STEP + 1e-6:
                g[(name, transition)].append(t)
        return g
    a, b = grouped(ours), grouped(peer)
    differences, count = [], 0
    for key in sorted(set(a) | set(b)):
        ta, tb = sorted(a.get(key, [])), sorted(b.get(key, []))
        subject = f"{key[0]} {key[1]}"
        for i in range(max(len(ta), len(tb))):
            count += 1
            x = ta[i] if i < len(ta) else None
            y = tb[i] if i < len(tb) else None
            if x is None or y is None:
                t = x if x is not None else y
                if t > end_time + 1e-6:  # after the compared end, in one run only: not compared
                    count -= 1
                    break
                differences.append(Difference("transition", subject, t, f"{x:.2f} s" if x is not None else "none",
                                              f"{y:.2f} s" if y is not None else "none"))
                break
            if abs(x - y) > STEP + 1e-6:
                differences.append(Difference("transition", subject, min(x, y), f"{x:.2f} s", f"{y:.2f} s"))
                break
    return differences, count


def compare_runs(our_folder: pathlib.Path, peer_folder: pathlib.Path, our_end: float, peer_end: float,
                 left_out_actions: frozenset = frozenset(), empty_groups: dict = None) -> Comparison:
    """`left_out_actions`: names of our actions whose transitions are not compared (the
    controller actions esmini drops with --disable_controllers); `empty_groups`: the file's
    ManeuverGroups without Maneuvers (departures.empty_groups)."""
    ours, drivers = read_our_trace(our_folder / "trace.csv")
    peer = read_peer_trace(peer_folder / "sim.csv")
    end = min(our_end, peer_end)
    pos_diff, compared, not_compared, positions = compare_positions(ours, drivers, peer, end)
    types = {}
    our_transitions = [tr for tr in read_our_transitions(our_folder / "result.json", types)
                       if tr[1] not in left_out_actions]
    peer_transitions = read_peer_transitions(peer_folder / "log.txt")
    tr_diff, transitions = compare_transitions(our_transitions, peer_transitions, end)
    differences = sorted(pos_diff + tr_diff, key=lambda d: (d.time, d.what, d.subject))
    found, beyond = [], differences
    if tr_diff:
        ours_std, peer_std, found = departures.standard_view(our_transitions, peer_transitions, types,
                                                             empty_groups or {})
        beyond = sorted(pos_diff + compare_transitions(ours_std, peer_std, end)[0],
                        key=lambda d: (d.time, d.what, d.subject))
        # Only the departures of elements that made a difference (in the compared time).
        subjects = {d.subject.rsplit(" ", 1)[0] for d in tr_diff}
        found = [f for f in found if f.element in subjects]
    return Comparison(compared, not_compared, end, positions, transitions, differences, found, beyond)
