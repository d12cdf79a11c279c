"""esmini's departures from the standard's storyboard transitions, as rules: where a file's
only differences are these, it runs like the peer but for transitions the standard names
otherwise, and is reported as such ("departs"), apart from a match and from a difference.

Each rule needs both players' runs to agree on *when* an element leaves its running state; it
only accounts for *which* transition the peer names, or (an empty ManeuverGroup) for how long
the peer keeps an element running that has nothing to run. A time that differs, a transition
in one run only for any other cause, and every position stay differences. The standard's text
is OpenSCENARIO XML 1.3, the same citations as docs/openscenario.md "When an element ends":

- STOPPED_ENDS: "A terminated Event moves to completeState with stopTransition" (8.4.2.2:
  terminated by an event of priority `override`, or by "a stop trigger ... issued by the
  enclosing Act or Storyboard"), and an action replaced by a new one of its entity and motion
  domain is stopped, not ended. esmini logs endTransition (at a stop trigger sometimes an
  endTransition and then a stopTransition: the end is not compared). Counted where our run has the
  element's stopTransition and the peer its endTransition in the same step, and in that step
  our run starts another element (the overriding event, the replacing action) or stops the
  Storyboard or an Act (a stop trigger).
- INSTANT_STOPS: an action that takes no time (a ParameterSetAction, an EnvironmentAction, a
  VariableSetAction, a traffic signal state) has run to its end in the step it starts:
  endTransition, which "symbolizes that runningState has ended regularly without being
  stopped" (8.2); esmini logs stopTransition. Counted where our run starts and ends the
  action in one step and the peer stops it in that step.
- EMPTY_GROUP_RUNS: a ManeuverGroup without Maneuvers has nothing to run: "The duration of an
  execution is determined by ... waiting time for start triggers, execution time for nested
  Action instances, waiting time for stop triggers. There is no other runtime aspect that
  consumes simulation time" (8.3.1); ours ends it in the step it starts, esmini keeps it
  running until the StopTrigger stops it. The group's transitions after its start are not
  compared, nor the endTransition of its Act and Story where the peer's comes in the step
  its empty group stops (that end is the group's, not theirs).
"""
import dataclasses
import xml.etree.ElementTree as ET

STEP = 0.05
RULES = ("STOPPED_ENDS", "INSTANT_STOPS", "EMPTY_GROUP_RUNS")


@dataclasses.dataclass(frozen=True)
class Departure:
    rule: str
    element: str
    time: float

    def text(self) -> str:
        return f"{self.rule} {self.element} at {self.time:.2f} s"


def empty_groups(xosc) -> dict:
    """{ManeuverGroup name: (Act name, Story name)} for the file's groups without a Maneuver
    (neither inline nor by catalog reference); an unreadable file has none."""
    try:
        root = ET.parse(xosc).getroot()
    except (ET.ParseError, OSError):
        return {}
    out = {}
    for story in root.iter("Story"):
        for act in story.iter("Act"):
            for group in act.iter("ManeuverGroup"):
                if group.find("Maneuver") is None and group.find("CatalogReference") is None:
                    out[group.get("name", "")] = (act.get("name", ""), story.get("name", ""))
    return out


def _near(a: float, b: float) -> bool:
    return abs(a - b) <= STEP + 1e-6


def standard_view(ours: list, peer: list, our_types: dict, groups: dict) -> tuple:
    """(ours, peer, departures): both runs' transitions [(time, name, transition)] with the
    peer's departures from the standard accounted for by the rules above. `our_types`: our
    elements' types by name ("action", "event", "act", "storyboard", ...)."""
    ours, peer = list(ours), list(peer)
    departures = []
    trigger_stops = [t for t, n, tr in ours if tr == "stopTransition" and our_types.get(n) in ("storyboard", "act")]

    def ours_has(name, transition, t):
        return any(n == name and tr == transition and _near(x, t) for x, n, tr in ours)

    for i, (t, name, transition) in enumerate(peer):
        if transition == "endTransition" and ours_has(name, "stopTransition", t) and not ours_has(name, "endTransition", t):
            started_other = any(_near(x, t) for x, n, tr in ours if tr == "startTransition" and n != name)
            if started_other or any(_near(x, t) for x in trigger_stops):
                # At a stop trigger esmini may log an endTransition and then a stopTransition
                # for the same element: the stop is the standard's, the end is dropped.
                also_stopped = any(p and p[1] == name and p[2] == "stopTransition" and _near(p[0], t) for p in peer)
                peer[i] = None if also_stopped else (t, name, "stopTransition")
                departures.append(Departure("STOPPED_ENDS", name, t))
        elif (transition == "stopTransition" and our_types.get(name) == "action"
              and ours_has(name, "endTransition", t) and ours_has(name, "startTransition", t)
              and not ours_has(name, "stopTransition", t)):
            peer[i] = (t, name, "endTransition")
            departures.append(Departure("INSTANT_STOPS", name, t))
    peer = [p for p in peer if p is not None]
    for group, (act, story) in groups.items():
        peer_stops = [t for t, n, tr in peer if n == group and tr in ("stopTransition", "endTransition")]
        our_start = [t for t, n, tr in ours if n == group and tr == "startTransition"]
        if not peer_stops or not our_start or not ours_has(group, "endTransition", our_start[0]):
            continue  # not started, or not ended by us as having nothing to run
        stop = peer_stops[0]
        dropped = {(group, "endTransition"), (group, "stopTransition")}
        for parent in (act, story):
            if any(n == parent and tr == "endTransition" and _near(t, stop) for t, n, tr in peer):
                dropped.add((parent, "endTransition"))
        ours = [x for x in ours if (x[1], x[2]) not in dropped]
        peer = [x for x in peer if (x[1], x[2]) not in dropped]
        departures.append(Departure("EMPTY_GROUP_RUNS", group, stop))
    return ours, peer, departures


def summary(departures: list) -> str:
    """'STOPPED_ENDS x2 (A, B), EMPTY_GROUP_RUNS x1 (G)'."""
    parts = []
    for rule in RULES:
        names = sorted({d.element for d in departures if d.rule == rule})
        count = sum(1 for d in departures if d.rule == rule)
        if count:
            parts.append(f"{rule} x{count} ({', '.join(names)})")
    return ", ".join(parts)
