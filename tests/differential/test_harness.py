"""The differential harness's own logic (scripts/differential, scripts/osc_differential.py) on
small outputs written here, in both players' formats: what is compared, what is a
difference, and how a file is judged against the table of expected differences."""
import json
import pathlib
import shutil
import sys
import tempfile
import unittest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
from differential import compare, departures, expected, players  # noqa: E402
import osc_differential  # noqa: E402

OUR_HEADER = "time,scene_id,actor_id,x,y,heading,speed,accel,edge,lane,lane_pos,lat_offset,signals,siren,driver\n"


def our_row(t, name, x, y, driver="script"):
    return f"{t:.3f},,{name},{x:.3f},{y:.3f},0,10,0,e,0,0,0,0,0,{driver}\n"


def peer_row(t, name, x, y):
    return f"{t:.3f}, 0, {name}, {x:.3f}, {y:.3f}, 0.000, 0.000, 0.000, 0.000, 10.000, 0.000, 0.000\n"


class Outputs:
    """Both players' output folders with a car A (scripted) and an ego (SUMO-driven) moving
    along x at 10 m/s for 2 s; `shift(t)` moves our A sideways."""

    def __init__(self, root: pathlib.Path, shift=lambda t: 0.0, ours_events=(), peer_log=""):
        self.ours, self.peer = root / "ours", root / "peer"
        self.ours.mkdir()
        self.peer.mkdir()
        trace, sim = [OUR_HEADER], ["time, id, name, x, y, z, h, p, r, speed, wheel_angle, wheel_rot\n"]
        for i in range(41):
            t = i * 0.05
            trace += [our_row(t, "A", 10 * t, -1.75 + shift(t)), our_row(t, "Ego", 10 * t + 50, -5.0, "sumo")]
            sim += [peer_row(t, "A", 10 * t, -1.75), peer_row(t, "Ego", 10 * t + 60, -5.0)]
        (self.ours / "trace.csv").write_text("".join(trace))
        (self.peer / "sim.csv").write_text("".join(sim))
        events = [{"time": t, "kind": k, "text": text} for t, k, text in ours_events]
        (self.ours / "result.json").write_text(json.dumps({"verdict": "success", "events": events}))
        (self.peer / "log.txt").write_text(peer_log)

    def compare(self):
        return compare.compare_runs(self.ours, self.peer, 2.0, 2.0)


PEER_LOG = """[0.000] [info] Init A TeleportAction initState -> startTransition -> runningState
[0.000] [info] storyBoard initState -> startTransition -> runningState
[0.000] [info] Act initState -> initToStandbyTransition -> standbyState
[1.000] [info] Go standbyState -> startTransition -> runningState
[1.000] [info] GoAction initState -> startTransition -> runningState
[1.550] [info] GoAction runningState -> endTransition -> completeState
[2.000] [info] storyBoard runningState -> stopTransition -> completeState
"""
OUR_EVENTS = [(1.0, "storyboard", "event Go startTransition"), (1.0, "action", "action GoAction startTransition"),
              (1.5, "action", "action GoAction endTransition"), (2.0, "storyboard", "storyboard  stopTransition")]


class Comparison(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = pathlib.Path(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def test_same_motion_and_transitions_match_and_sumo_driven_entities_are_not_compared(self):
        c = Outputs(self.root, ours_events=OUR_EVENTS, peer_log=PEER_LOG).compare()
        self.assertTrue(c.matches, [d.text() for d in c.differences])
        self.assertEqual(c.compared_entities, ["A"])          # the ego is 10 m off, but SUMO drove it
        self.assertEqual(c.not_compared, {"Ego": "driven by sumo"})
        self.assertEqual(c.positions, 5)                       # 0, 0.5, ... 2.0 s
        self.assertEqual(c.transitions, 4)                     # Init and standby transitions left out

    def test_a_position_beyond_the_tolerance_names_entity_time_and_both_points(self):
        c = Outputs(self.root, shift=lambda t: 0.11 if t >= 1.0 else 0.09).compare()
        self.assertEqual(len(c.differences), 1)
        d = c.differences[0]
        self.assertEqual((d.what, d.subject, d.time), ("position", "A", 1.0))
        self.assertIn("(10.000, -1.640)", d.ours)
        self.assertIn("(10.000, -1.750), 0.110 m apart", d.peer)

    def test_heights_are_compared_where_both_players_give_them(self):
        # A road with elevation: our trace has z (the road surface under the entity); 0.11 m
        # of height apart is a difference, as 0.11 m sideways is.
        ours, peer = self.root / "ours", self.root / "peer"
        ours.mkdir()
        peer.mkdir()
        trace = [OUR_HEADER.rstrip("\n") + ",z,pitch,roll\n"]
        sim = ["time, id, name, x, y, z, h, p, r, speed, wheel_angle, wheel_rot\n"]
        for i in range(41):
            t = i * 0.05
            trace.append(our_row(t, "A", 10 * t, -1.75).rstrip("\n") + f",{2.0 + (0.11 if t >= 1.0 else 0.0):.3f},0,0\n")
            sim.append(f"{t:.3f}, 0, A, {10 * t:.3f}, -1.750, 2.000, 0.000, 0.000, 0.000, 10.000, 0.000, 0.000\n")
        (ours / "trace.csv").write_text("".join(trace))
        (peer / "sim.csv").write_text("".join(sim))
        (ours / "result.json").write_text(json.dumps({"verdict": "success", "events": []}))
        (peer / "log.txt").write_text("")
        c = compare.compare_runs(ours, peer, 2.0, 2.0)
        self.assertEqual([(d.what, d.subject, d.time) for d in c.differences], [("position", "A", 1.0)])
        self.assertIn("(10.000, -1.750, 2.110)", c.differences[0].ours)
        self.assertIn("(10.000, -1.750, 2.000), 0.110 m apart", c.differences[0].peer)

    def test_a_transition_two_steps_late_or_missing_is_a_difference(self):
        events = [e for e in OUR_EVENTS if "GoAction endTransition" not in e[2]]
        (self.root / "late").mkdir()
        (self.root / "missing").mkdir()
        c = Outputs(self.root / "late", ours_events=events + [(1.65, "action", "action GoAction endTransition")],
                    peer_log=PEER_LOG).compare()
        self.assertEqual([d.text() for d in c.differences], ["GoAction endTransition at 1.55 s: ours 1.65 s, peer 1.55 s"])
        c = Outputs(self.root / "missing", ours_events=events, peer_log=PEER_LOG).compare()
        self.assertEqual([d.text() for d in c.differences], ["GoAction endTransition at 1.55 s: ours none, peer 1.55 s"])


    def test_a_file_differing_only_in_transitions_counts_as_positions_matching(self):
        events = [e for e in OUR_EVENTS if "GoAction endTransition" not in e[2]]
        for name in ("same", "transition", "position"):
            (self.root / name).mkdir()
        same = Outputs(self.root / "same", ours_events=OUR_EVENTS, peer_log=PEER_LOG).compare()
        transition = Outputs(self.root / "transition", ours_events=events, peer_log=PEER_LOG).compare()
        position = Outputs(self.root / "position", shift=lambda t: 0.2, ours_events=OUR_EVENTS, peer_log=PEER_LOG).compare()
        results = [{"file": f"../shared/data/esmini_examples/xosc/{n}.xosc", "status": s, "comparison": c}
                   for n, s, c in (("a", "match", same), ("b", "differs", transition), ("c", "differs", position))]
        results.append({"file": "scenarios/openscenario/d.xosc", "status": "unreadable", "comparison": None})
        self.assertEqual([osc_differential.positions_match(r) for r in results], [True, True, False, False])
        self.assertEqual(osc_differential.positions_figure(results),
                         "positions: 2 of 3 compared files within the tolerance at every point (esmini's examples: 2 of 3)")

    def test_a_stop_one_step_after_the_other_runs_end_is_paired_not_missed(self):
        # Ours stops at its StopTrigger at 2.00 s (the compared end), the peer one step later.
        late_stop = PEER_LOG.replace("[2.000] [info] storyBoard", "[2.050] [info] storyBoard")
        c = Outputs(self.root, ours_events=OUR_EVENTS, peer_log=late_stop).compare()
        self.assertTrue(c.matches, [d.text() for d in c.differences])
        self.assertEqual(c.transitions, 4)
        # The peer's stop one step after the end with none in ours is not compared ...
        (self.root / "none").mkdir()
        c = Outputs(self.root / "none", ours_events=OUR_EVENTS[:-1], peer_log=late_stop).compare()
        self.assertTrue(c.matches, [d.text() for d in c.differences])
        self.assertEqual(c.transitions, 3)
        # ... while one missing before the end is a difference, as always.
        (self.root / "missing").mkdir()
        c = Outputs(self.root / "missing", ours_events=OUR_EVENTS[:-1], peer_log=PEER_LOG).compare()
        self.assertEqual([d.text() for d in c.differences], ["Storyboard stopTransition at 2.00 s: ours none, peer 2.00 s"])

    def test_an_entity_added_one_step_apart_is_not_a_difference_two_steps_is(self):
        for peer_from, differs in ((1.05, False), (1.1, True)):
            folder = self.root / f"added_{peer_from}"
            folder.mkdir()
            o = Outputs(folder)
            with (o.ours / "trace.csv").open("a") as f:
                f.writelines(our_row(i * 0.05, "B", 330, -5.25) for i in range(20, 41))
            with (o.peer / "sim.csv").open("a") as f:
                f.writelines(peer_row(i * 0.05, "B", 330, -5.25) for i in range(int(round(peer_from / 0.05)), 41))
            c = o.compare()
            self.assertEqual([d.text() for d in c.differences],
                             ["B at 1.00 s: ours (330.000, -5.250), peer absent"] if differs else [])


    def test_peer_init_actions_and_actions_its_controllers_inject_are_no_transitions(self):
        # esmini's Init actions in every form it logs them, and a lane change its NaturalDriver
        # controller adds: none is an element of the storyboard, so none is compared.
        log = PEER_LOG + "\n".join([
            "[0.000] [info] Init ego jerk LongitudinalAction initState -> startTransition -> runningState",
            "[0.000] [info] Init EnvironmentAction runningState -> stopTransition -> completeState",
            "[0.000] [info] Init Ego TeleportAction_ghost-copy initState -> startTransition -> runningState",
            "[0.000] [info] Adding action LaneChangeAction_0",
            "[0.000] [info] LaneChangeAction_0 initState -> startTransition -> runningState",
            "[2.000] [info] LaneChangeAction_0 runningState -> endTransition -> completeState", ""])
        c = Outputs(self.root, ours_events=OUR_EVENTS, peer_log=log).compare()
        self.assertTrue(c.matches, [d.text() for d in c.differences])
        self.assertEqual(c.transitions, 4)
        # An element of the storyboard that merely starts with "Init" is compared.
        (self.root / "named").mkdir()
        c = Outputs(self.root / "named", ours_events=OUR_EVENTS,
                    peer_log=PEER_LOG + "[1.000] [info] Init speed initState -> startTransition -> runningState\n").compare()
        self.assertEqual([d.text() for d in c.differences], ["Init speed startTransition at 1.00 s: ours none, peer 1.00 s"])


class PeerCsv(unittest.TestCase):
    def test_dat2csv_rows_without_its_banner_and_only_up_to_the_compared_time(self):
        with tempfile.TemporaryDirectory() as tmp:
            root = pathlib.Path(tmp)
            fake = root / "dat2csv"  # prints as the real one does with --print_csv
            fake.write_text("#!/bin/sh\necho 'esmini GIT REV: v3.6.0'\necho 'time, id, name, x, y'\n"
                            "for t in 0.000 0.050 0.100 0.150; do echo \"$t, 0, A, 1.000, 2.000\"; done\n")
            fake.chmod(0o755)
            sim = root / "sim.csv"
            players._write_csv(root, root, sim, 0.1)
            self.assertEqual(sim.read_text().splitlines(),
                             ["time, id, name, x, y", "0.000, 0, A, 1.000, 2.000", "0.050, 0, A, 1.000, 2.000",
                              "0.100, 0, A, 1.000, 2.000"])


class ControllersOff(unittest.TestCase):
    """A file where either player may run a controller is compared again with controllers off
    in both; the file's status stays the as-written comparison's."""

    def test_which_files_have_controllers(self):
        with tempfile.TemporaryDirectory() as tmp:
            f = pathlib.Path(tmp) / "f.xosc"
            for text, has in (('<ObjectController><Controller name="c"/></ObjectController>', True),
                              ("<ObjectController>\n<CatalogReference/></ObjectController>", True),
                              ("<PrivateAction><ControllerAction><ActivateControllerAction/>", True),
                              ('<GlobalAction><InfrastructureAction><TrafficSignalAction><TrafficSignalControllerAction '
                               'trafficSignalControllerRef="x" phase="go"/>', False),
                              ('<TrafficSignalController name="x">', False)):
                f.write_text(text)
                self.assertEqual(players.has_controllers(f), has, text)

    def test_the_peers_log_says_when_a_controller_of_its_own_took_over(self):
        with tempfile.TemporaryDirectory() as tmp:
            folder = pathlib.Path(tmp)
            for line, ran in (("[0.000] [info] Controller interactiveDriver active on domains: Lateral & "
                               "Longitudinal (mask=0x3)", True),
                              ("[0.000] [info] Controller ACCController active on domains: Longitudinal (mask=0x1)", True),
                              ("[] [info] Skipping ActivateControllerAction for object Ego due to --disable_controllers",
                               False)):
                (folder / "log.txt").write_text(PEER_LOG + line + "\n")
                self.assertEqual(players.peer_ran_controller(folder), ran, line)

    def test_controller_actions_are_left_out_of_the_controllers_off_transitions(self):
        # esmini --disable_controllers drops them from its storyboard: no transitions there.
        with tempfile.TemporaryDirectory() as tmp:
            root = pathlib.Path(tmp)
            f = root / "f.xosc"
            f.write_text('<OpenSCENARIO><Storyboard><Action name="Go"><PrivateAction><LongitudinalAction/>'
                         '</PrivateAction></Action><Action name="HandOver"><PrivateAction><ControllerAction>'
                         '<ActivateControllerAction longitudinal="true"/></ControllerAction></PrivateAction></Action>'
                         '<Action name="Old"><PrivateAction><ActivateControllerAction/></PrivateAction></Action>'
                         '<Action name="Light"><GlobalAction><InfrastructureAction><TrafficSignalAction>'
                         '<TrafficSignalControllerAction/></TrafficSignalAction></InfrastructureAction></GlobalAction>'
                         '</Action></Storyboard></OpenSCENARIO>')
            self.assertEqual(players.controller_action_names(f), {"HandOver", "Old"})
            events = OUR_EVENTS + [(1.0, "action", "action HandOver startTransition"),
                                   (1.0, "action", "action HandOver endTransition")]
            o = Outputs(root / "run", ours_events=events, peer_log=PEER_LOG) if (root / "run").mkdir() is None else None
            self.assertFalse(o.compare().matches)
            c = compare.compare_runs(o.ours, o.peer, 2.0, 2.0, frozenset({"HandOver"}))
            self.assertTrue(c.matches, [d.text() for d in c.differences])

    def fake_players(self, root, calls, shift_when_controllers):
        """run_peer / run_ours that write Outputs-like folders: our car A is 0.5 m off the
        peer's while controllers run, on it without them."""
        def peer(esmini, xosc, folder, timeout, max_time, controllers=True):
            calls.append(("peer", controllers))
            return players.Run(folder, True, end_time=2.0)

        def ours(orchestrator, xosc, folder, max_time, timeout, controllers=True):
            calls.append(("ours", controllers))
            pair = folder.parent
            shutil.rmtree(pair, ignore_errors=True)
            pair.mkdir(parents=True)
            Outputs(pair, shift=lambda t: shift_when_controllers if controllers else 0.0,
                    ours_events=OUR_EVENTS, peer_log=PEER_LOG)
            return players.Run(folder, True, end_time=2.0)
        return peer, ours

    def run_file(self, text, shift=0.5):
        calls = []
        with tempfile.TemporaryDirectory() as tmp:
            root = pathlib.Path(tmp)
            xosc = root / "f.xosc"
            xosc.write_text(text)
            peer, ours = self.fake_players(root, calls, shift)
            saved = players.run_peer, players.run_ours
            players.run_peer, players.run_ours = peer, ours
            try:
                r = osc_differential.run_file(xosc, root / "work", root / "orchestrator", root / "esmini")
            finally:
                players.run_peer, players.run_ours = saved
        return r, calls

    def test_a_file_with_a_controller_runs_again_without_and_keeps_its_status(self):
        r, calls = self.run_file('<ObjectController><Controller name="interactiveDriver"/></ObjectController>')
        self.assertEqual(calls, [("peer", True), ("ours", True), ("peer", False), ("ours", False)])
        self.assertEqual(r["status"], "differs")                    # the headline: as written
        self.assertIn("position A at 0.00 s", r["detail"])
        self.assertEqual(r["storyboard_only"]["status"], "match")   # the storyboard alone agrees
        self.assertEqual(osc_differential.storyboard_only_text(r)[:35], "controllers off in both: match (1 e")
        self.assertEqual(osc_differential.storyboard_only_figure([r, {"storyboard_only": None}]),
                         "1 of 1 files with controllers match with controllers off in both (0 more but for esmini's departures)")

    def test_a_file_without_controllers_runs_once_unless_a_run_shows_one(self):
        # The Outputs' Ego is SUMO-driven in our trace: a controller ran (a system under test).
        r, calls = self.run_file("<Entities/>")
        self.assertEqual(len(calls), 4)
        self.assertIsNotNone(r["storyboard_only"])
        saved = players.has_controllers, players.peer_ran_controller
        players.has_controllers = players.peer_ran_controller = lambda _: False
        try:
            pair = {"comparison": compare.Comparison(["A"], {}, 2.0, 5, 0, []), "peer_controller": False}
            self.assertFalse(osc_differential.runs_controllers(pathlib.Path("f.xosc"), pair))
            pair["peer_controller"] = True
            self.assertTrue(osc_differential.runs_controllers(pathlib.Path("f.xosc"), pair))
        finally:
            players.has_controllers, players.peer_ran_controller = saved
        self.assertEqual(osc_differential.storyboard_only_text({"storyboard_only": None}), "")


def peer_line(t, name, transition):
    before, after = {"startTransition": ("initState", "runningState")}.get(transition, ("runningState", "completeState"))
    return f"[{t:.3f}] [info] {name} {before} -> {transition} -> {after}\n"


class StopTime(unittest.TestCase):
    """A file whose StopTrigger fires after the compared window is run to its stop: when the
    Storyboard stops is compared (one step)."""

    def test_the_storyboards_stop_agrees_within_a_step_or_is_a_difference(self):
        with tempfile.TemporaryDirectory() as tmp:
            result = pathlib.Path(tmp) / "result.json"
            stop = lambda t: json.dumps({"events": [{"time": t, "kind": "storyboard", "text": "storyboard  stopTransition"}]})  # noqa: E731
            result.write_text(stop(183.40))
            self.assertIsNone(compare.stop_time_difference(result, 183.45))
            result.write_text(stop(183.30))
            self.assertEqual(compare.stop_time_difference(result, 183.45).text(),
                             "Storyboard stopTransition at 183.30 s: ours 183.30 s, peer 183.45 s")
            result.write_text(json.dumps({"events": []}))
            self.assertEqual(compare.stop_time_difference(result, 364.2).text(),
                             "Storyboard stopTransition at 364.20 s: ours none, peer 364.20 s")


class PeerDepartures(unittest.TestCase):
    """esmini's departures from the standard's transitions (departures.py) account for the
    transition they name differently, and for nothing else."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = pathlib.Path(self.tmp.name)
        self.count = 0

    def tearDown(self):
        self.tmp.cleanup()

    def compare(self, ours, peer, groups=None):
        self.count += 1
        folder = self.root / str(self.count)
        folder.mkdir()
        events = [(t, "action" if kind == "action" else "storyboard", f"{kind} {name} {tr}") for t, kind, name, tr in ours]
        out = Outputs(folder, ours_events=events, peer_log="".join(peer_line(*p) for p in peer))
        return compare.compare_runs(out.ours, out.peer, 2.0, 2.0, empty_groups=groups)

    def test_an_overridden_event_the_peer_ends_is_a_departure_only_when_something_overrode_it(self):
        ours = [(0.5, "event", "E", "startTransition"), (0.5, "action", "A", "startTransition"),
                (1.5, "action", "A", "stopTransition"), (1.5, "event", "E", "stopTransition"),
                (1.5, "event", "F", "startTransition")]
        peer = [(0.5, "E", "startTransition"), (0.5, "A", "startTransition"), (1.5, "A", "endTransition"),
                (1.5, "E", "endTransition"), (1.5, "F", "startTransition")]
        c = self.compare(ours, peer)
        self.assertEqual(len(c.differences), 4)
        self.assertTrue(c.departs_only)
        self.assertEqual(departures.summary(c.departures), "STOPPED_ENDS x2 (A, E)")
        # At the stop trigger esmini may end the event and then stop it too: the end is dropped.
        stop = (1.5, "storyboard", "", "stopTransition")
        c = self.compare([o for o in ours if o[2] != "F"] + [stop],
                         [p for p in peer if p[1] != "F"] + [(1.5, "E", "stopTransition"), (1.5, "storyBoard", "stopTransition")])
        self.assertTrue(c.departs_only, [d.text() for d in c.beyond_departures])
        # Nothing starts or stops the storyboard in that step: no cited cause, a difference.
        c = self.compare([o for o in ours if o[2] != "F"], [p for p in peer if p[1] != "F"])
        self.assertFalse(c.departs_only)
        self.assertEqual(c.beyond_departures[0].text(), "A endTransition at 1.50 s: ours none, peer 1.50 s")
        # Two steps apart: a difference whatever the peer names it.
        late = [(1.6 if p[1] == "A" and p[2] == "endTransition" else p[0],) + p[1:] for p in peer]
        c = self.compare(ours, late)
        self.assertFalse(c.departs_only)

    def test_an_instant_action_the_peer_stops_is_a_departure_one_that_ran_is_not(self):
        peer = [(1.0, "P", "startTransition"), (1.0, "P", "stopTransition")]
        c = self.compare([(1.0, "action", "P", "startTransition"), (1.0, "action", "P", "endTransition")], peer)
        self.assertTrue(c.departs_only)
        self.assertEqual(departures.summary(c.departures), "INSTANT_STOPS x1 (P)")
        c = self.compare([(0.5, "action", "P", "startTransition"), (1.0, "action", "P", "endTransition")],
                         [(0.5, "P", "startTransition"), (1.0, "P", "stopTransition")])
        self.assertFalse(c.departs_only)

    def test_an_empty_maneuver_group_the_peer_keeps_running_until_the_stop_trigger(self):
        xosc = self.root / "f.xosc"
        xosc.write_text('<OpenSCENARIO><Storyboard><Story name="S"><Act name="Act1">'
                        '<ManeuverGroup name="G"/><ManeuverGroup name="H"><Maneuver name="M"/></ManeuverGroup>'
                        '</Act></Story></Storyboard></OpenSCENARIO>')
        groups = departures.empty_groups(xosc)
        self.assertEqual(groups, {"G": ("Act1", "S")})
        ours = [(0.0, "maneuverGroup", "G", "startTransition"), (0.0, "maneuverGroup", "G", "endTransition"),
                (0.0, "act", "Act1", "endTransition"), (0.0, "story", "S", "endTransition")]
        peer = [(0.0, "G", "startTransition"), (2.0, "G", "stopTransition"), (2.0, "Act1", "endTransition"),
                (2.0, "S", "endTransition")]
        c = self.compare(ours, peer, groups)
        self.assertTrue(c.departs_only)
        self.assertEqual(departures.summary(c.departures), "EMPTY_GROUP_RUNS x1 (G)")
        self.assertFalse(self.compare(ours, peer).departs_only)   # a group with Maneuvers: differs
        # The group's start is still compared.
        self.assertFalse(self.compare(ours, [(0.5, "G", "startTransition")] + peer[1:], groups).departs_only)


class Judgement(unittest.TestCase):
    def result(self, status, detail=""):
        return {"file": "f.xosc", "status": status, "detail": detail, "comparison": None}

    def test_the_table_only_shrinks_knowingly(self):
        listed = expected.Entry("f.xosc", "unreadable", "1.3 trailers")
        self.assertTrue(osc_differential.judge(self.result("match"), None)[0])
        ok, line = osc_differential.judge(self.result("match"), listed)
        self.assertFalse(ok)
        self.assertIn("now matches the peer", line)
        ok, line = osc_differential.judge(self.result("differs", "position A at 1.00 s"), listed)
        self.assertFalse(ok)
        self.assertIn("listed as unreadable, now differs", line)
        self.assertTrue(osc_differential.judge(self.result("unreadable", "error"), listed)[0])
        self.assertTrue(osc_differential.judge(self.result("departs", "STOPPED_ENDS x1 (A)"), None)[0])
        ok, line = osc_differential.judge(self.result("departs", "STOPPED_ENDS x1 (A)"), listed)
        self.assertFalse(ok)
        self.assertIn("differs only by esmini's cited departures", line)
        ok, line = osc_differential.judge(self.result("differs", "position A at 1.00 s"), None)
        self.assertFalse(ok)
        self.assertIn("position A at 1.00 s", line)

    def test_the_table_file_is_checked(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = pathlib.Path(tmp) / "t.txt"
            path.write_text("# comment\na.xosc | unreadable | why\n")
            self.assertEqual(expected.read(path)["a.xosc"].reason, "why")
            path.write_text("a.xosc | sometimes | why\n")
            with self.assertRaises(SystemExit) as e:
                expected.read(path)
            self.assertIn("t.txt:1: unknown category 'sometimes'", str(e.exception))
            path.write_text("a.xosc | unreadable | why\na.xosc | differs | why\n")
            with self.assertRaises(SystemExit) as e:
                expected.read(path)
            self.assertIn("t.txt:2: a.xosc is listed twice", str(e.exception))


if __name__ == "__main__":
    unittest.main()
