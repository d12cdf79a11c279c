#!/usr/bin/env python3
"""Differential test of the OpenSCENARIO runtime against a peer player (esmini, headless,
../shared/tools/esmini): every file of the corpus runs in both at a 0.05 s step; every
entity that follows the storyboard is compared every 0.5 s by its reference point (0.10 m)
and every storyboard element transition by its time (one step). A file where either player
may run a controller is compared a second time with controllers off in both (esmini
--disable_controllers, ours --controllers off): reported per file and in the summary, not
judged (the file's status is the as-written comparison's). See docs/differential.md.

Corpus: ../shared/data/openscenario/*.xosc (OSC-ALKS), ../shared/data/esmini_examples/xosc/
*.xosc and scenarios/openscenario/*.xosc. A file that does not match is a failure unless
tests/differential/expected_differences.txt lists it with the right category; a listed file
that now matches, or now fails in another way, is a failure too (the list only shrinks
knowingly). Exit status 0 when every file is as expected, 1 otherwise.

Usage: scripts/osc_differential.py [--orchestrator build/bin/orchestrator] [--jobs N]
           [--work DIR] [--update] [--extra FILE.xosc]... [FILE.xosc...]
       scripts/osc_differential.py --check-doc | --write-doc
"""
import argparse
import concurrent.futures
import json
import os
import pathlib
import sys
import tempfile
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from differential import compare, departures, expected, players  # noqa: E402
from doc_tables import write_between  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent
SHARED = ROOT.parent / "shared"
EXPECTED = ROOT / "tests" / "differential" / "expected_differences.txt"
DOC = ROOT / "docs" / "differential.md"
BEGIN, END = "<!-- expected-differences:begin -->", "<!-- expected-differences:end -->"
CORPUS = [SHARED / "data" / "openscenario", SHARED / "data" / "esmini_examples" / "xosc",
          ROOT / "scenarios" / "openscenario"]
# Simulated seconds compared at most: files whose StopTrigger comes later (OSC-ALKS 4.1_1 at
# 300 s, whose steps cost ~15 times 4.1_2's on its curved roads; esmini's examples that stop
# at 1200 s) are compared over their first MAX_TIME s (the test's time budget on 2 cores).
MAX_TIME = 60.0
# A file whose StopTrigger fires after MAX_TIME and before this (acc-toggle at 117.8 s, OSC-ALKS
# 4.1_1 at 300 s, sumo-test at 600 s) is run once more to the end, to compare when it stops;
# esmini's examples without a StopTrigger end at 1200.05 s, esmini's own limit.
STOP_CHECK_UNTIL = 1000.0
PEER_TIMEOUT = 60.0      # s wall-clock: a file whose StopTrigger never fires
OURS_TIMEOUT = 900.0


def corpus_files() -> list:
    return sorted(f for d in CORPUS for f in d.glob("*.xosc"))


def relative(path: pathlib.Path) -> str:
    return os.path.relpath(path.resolve(), ROOT)


def run_pair(xosc: pathlib.Path, folder: pathlib.Path, orchestrator: pathlib.Path, esmini: pathlib.Path,
             controllers: bool = True) -> dict:
    """Both players on one file, with their controllers or (False) without any in both:
    {'status', 'detail', 'comparison'}; the peer's folder is folder/peer, ours folder/ours."""
    peer = players.run_peer(esmini, xosc, folder / "peer", PEER_TIMEOUT, MAX_TIME, controllers)
    out = {"comparison": None, "peer_controller": False}
    if not peer.ok:
        out.update(status="peer-error", detail=peer.error)
        return out
    out["peer_controller"] = players.peer_ran_controller(peer.folder)
    max_time = min(peer.end_time + 1.0, MAX_TIME)
    ours = players.run_ours(orchestrator, xosc, folder / "ours", max_time, OURS_TIMEOUT, controllers)
    if not ours.ok:
        out.update(status="ours-error" if ours.timed_out or ours.crashed else "unreadable", detail=ours.error)
        return out
    # Without controllers esmini drops the Activate/AssignControllerActions from the storyboard
    # (no transitions); ours runs them: theirs are not compared then.
    left_out = frozenset() if controllers else frozenset(players.controller_action_names(xosc))
    c = compare.compare_runs(ours.folder, peer.folder, ours.end_time, min(peer.end_time, MAX_TIME), left_out,
                             departures.empty_groups(xosc))
    if controllers and not ours.error:
        compare_stop_time(c, xosc, folder, orchestrator, peer.folder)
    out["comparison"] = c
    if ours.error:
        out.update(status="ours-error", detail=f"stopped at {ours.end_time:.2f} s: {ours.error}")
    elif c.departs_only:
        out.update(status="departs", detail=f"esmini's departures from the standard: {departures.summary(c.departures)}")
    elif c.differences:
        # The first difference the peer's departures do not account for.
        first = c.beyond_departures[0]
        more = f" (+{len(c.beyond_departures) - 1} more)" if len(c.beyond_departures) > 1 else ""
        cited = f"; and esmini's departures: {departures.summary(c.departures)}" if c.departures else ""
        out.update(status="differs", detail=f"{first.what} {first.text()}{more}{cited}")
    else:
        out.update(status="match", detail="")
    return out


def compare_stop_time(c, xosc: pathlib.Path, folder: pathlib.Path, orchestrator: pathlib.Path,
                      peer_folder: pathlib.Path) -> None:
    """When the peer's Storyboard stops after the compared MAX_TIME s (and before
    STOP_CHECK_UNTIL), runs ours once more to one step past that time and compares when the
    Storyboard stops: a difference of the comparison when it is more than a step apart, or
    never (its positions are not compared there)."""
    peer_stop = [t for t, name, tr in compare.read_peer_transitions(peer_folder / "log.txt")
                 if name == compare.STORYBOARD and tr == "stopTransition"]
    if not peer_stop or not MAX_TIME < peer_stop[0] < STOP_CHECK_UNTIL:
        return
    long_run = players.run_ours(orchestrator, xosc, folder / "ours-to-the-stop", peer_stop[0] + compare.STEP + 0.01,
                                OURS_TIMEOUT)
    if not long_run.ok:
        return  # the first run's comparison stands; this one adds only the stop
    difference = compare.stop_time_difference(long_run.folder / "result.json", peer_stop[0])
    c.transitions += 1
    if difference:
        c.differences.append(difference)
        c.beyond_departures.append(difference)


def runs_controllers(xosc: pathlib.Path, pair: dict) -> bool:
    """Whether either player may run a controller on this file: the file has a controller
    element, or the as-written runs show one (our trace has an entity SUMO, the reference
    driver or a plug-in drove; esmini's log has a controller of its own taking over)."""
    c = pair["comparison"]
    return players.has_controllers(xosc) or pair["peer_controller"] or bool(c and c.not_compared)


def clean(detail: str) -> str:
    """Paths in messages relative to the checkout, as in the table of expected differences."""
    return detail.replace(str(ROOT.parent.resolve()) + "/", "../").replace("invalid scenario: ", "")


def run_file(xosc: pathlib.Path, work: pathlib.Path, orchestrator: pathlib.Path, esmini: pathlib.Path) -> dict:
    """Both players on one file: {'file', 'status', 'detail', 'comparison', 'storyboard_only',
    'seconds'}. A file where either player may run a controller is compared a second time with
    controllers off in both (esmini --disable_controllers, ours --controllers off):
    `storyboard_only` is that comparison's {'status', 'detail', 'comparison'} (None for the
    other files); the file's status stays the as-written comparison's."""
    folder = work / relative(xosc).replace("../", "").replace("/", "__")
    start = time.monotonic()
    pair = run_pair(xosc, folder, orchestrator, esmini)
    out = {"file": relative(xosc), "status": pair["status"], "detail": clean(pair["detail"]),
           "comparison": pair["comparison"], "storyboard_only": None}
    if pair["status"] != "peer-error" and runs_controllers(xosc, pair):
        off = run_pair(xosc, folder / "controllers-off", orchestrator, esmini, controllers=False)
        out["storyboard_only"] = {"status": off["status"], "detail": clean(off["detail"]),
                                  "comparison": off["comparison"]}
    out["seconds"] = time.monotonic() - start
    return out


def run_guarded(xosc: pathlib.Path, work: pathlib.Path, orchestrator: pathlib.Path, esmini: pathlib.Path) -> dict:
    """run_file; a failure of the harness itself on one file is that file's result."""
    try:
        return run_file(xosc, work, orchestrator, esmini)
    except Exception as e:  # noqa: BLE001 (reported per file, the other files go on)
        return {"file": relative(xosc), "status": "harness-error", "detail": f"{type(e).__name__}: {e}",
                "comparison": None, "storyboard_only": None, "seconds": 0.0}


def summary_of(c) -> str:
    if c is None:
        return ""
    skipped = ", ".join(f"{n} {why}" for n, why in sorted(c.not_compared.items()))
    return (f"{len(c.compared_entities)} entities, {c.positions} points, {c.transitions} transitions up to "
            f"{c.end_time:.2f} s" + (f"; not compared: {skipped}" if skipped else ""))


def storyboard_only_text(result: dict) -> str:
    """The controllers-off comparison in words ("" for a file without controllers)."""
    off = result.get("storyboard_only")
    if not off:
        return ""
    if off["status"] in ("match", "departs"):
        why = f"; {off['detail']}" if off["detail"] else ""
        return f"controllers off in both: {off['status']} ({summary_of(off['comparison'])}{why})"
    return f"controllers off in both: {off['status']}: {off['detail']}"


def storyboard_only_figure(results: list) -> str:
    """'N of M files with controllers match with controllers off in both' (the extra files
    left out by the caller)."""
    with_controllers = [r for r in results if r.get("storyboard_only")]
    matching = sum(1 for r in with_controllers if r["storyboard_only"]["status"] == "match")
    departing = sum(1 for r in with_controllers if r["storyboard_only"]["status"] == "departs")
    return (f"{matching} of {len(with_controllers)} files with controllers match with controllers off in both"
            f" ({departing} more but for esmini's departures)")


# Statuses of a file both players ran to the end of the comparison.
COMPARED = ("match", "departs", "differs")


def positions_match(result: dict) -> bool:
    """Every compared point of the file within the tolerance (its transitions aside): the
    file ran to a comparison and no difference is a position's."""
    c = result.get("comparison")
    return result["status"] in COMPARED and c is not None and c.positions > 0 and \
        not any(d.what == "position" for d in c.differences)


def positions_figure(results: list) -> str:
    """'positions: N of M compared files within 0.10 m everywhere (esmini's examples: A of B)':
    what the players agree on where a file differs only in its storyboard transitions (mostly
    where esmini departs from the standard's transitions; the table gives each reason)."""
    compared = [r for r in results if r["status"] in COMPARED]
    examples = [r for r in compared if "/esmini_examples/" in r["file"]]
    return (f"positions: {sum(map(positions_match, compared))} of {len(compared)} compared files within the "
            f"tolerance at every point (esmini's examples: {sum(map(positions_match, examples))} of {len(examples)})")


def judge(result: dict, listed) -> tuple:
    """(ok, line) for one file against its entry in the table (or none). A file that differs
    only by the peer's departures (departures.py, each with the standard's text) is not
    listed: the rules are its reason, and its line names the ones it needed."""
    file, status, detail = result["file"], result["status"], result["detail"]
    summary = summary_of(result["comparison"])
    if status in ("match", "departs"):
        if listed:
            now = "matches the peer" if status == "match" else "differs only by esmini's cited departures"
            return False, f"FAIL {file}: listed as {listed.category} but now {now} ({summary}): remove its line"
        return True, f"{status} {file} ({summary})" + (f": {detail}" if detail else "")
    if not listed:
        return False, f"FAIL {file}: {status}: {detail}" + (f" [{summary}]" if summary else "")
    if listed.category != status:
        return False, f"FAIL {file}: listed as {listed.category}, now {status}: {detail}: update its line"
    return True, f"expected {file} [{status}: {listed.reason}] now: {detail}"


def check_doc(entries: dict) -> int:
    text = DOC.read_text()
    begin, end = text.index(BEGIN) + len(BEGIN), text.index(END)
    if text[begin:end].strip() != expected.doc_table(entries).strip():
        print(f"{relative(DOC)}: the table of expected differences is not {relative(EXPECTED)}'s: "
              "run scripts/osc_differential.py --write-doc")
        return 1
    print(f"{relative(DOC)}: table in step with {relative(EXPECTED)} ({len(entries)} files)")
    return 0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("files", nargs="*", type=pathlib.Path, help="only these files of the corpus")
    parser.add_argument("--orchestrator", type=pathlib.Path, default=ROOT / "build" / "bin" / "orchestrator")
    parser.add_argument("--esmini", type=pathlib.Path, default=SHARED / "tools" / "esmini" / "bin")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    parser.add_argument("--work", type=pathlib.Path, help="keep both players' outputs here (default: a temporary folder)")
    parser.add_argument("--extra", action="append", type=pathlib.Path, default=[], metavar="FILE.xosc",
                        help="a file outside the corpus (e.g. an OSC-ALKS template not in shared/): reported, not "
                             "judged; with only --extra files, only they run (repeat the option for more)")
    parser.add_argument("--results", type=pathlib.Path, metavar="FILE.json",
                        help="write every file's outcome here (file, status, detail, summary): the input of "
                             "scripts/osc_coverage.py")
    parser.add_argument("--update", action="store_true",
                        help="rewrite the table from this run (reasons kept where the category stays) and the doc")
    parser.add_argument("--check-doc", action="store_true", help="only check docs/differential.md's table")
    parser.add_argument("--write-doc", action="store_true", help="only rewrite docs/differential.md's table")
    args = parser.parse_args()
    entries = expected.read(EXPECTED)
    if args.check_doc:
        return check_doc(entries)
    if args.write_doc:
        write_between(DOC, BEGIN, END, expected.doc_table(entries))
        return 0
    for needed in (args.orchestrator, args.esmini / "esmini", args.esmini / "dat2csv"):
        if not needed.exists():
            print(f"differential: {needed} is missing")
            return 1
    corpus = corpus_files()
    files = [f.resolve() for f in args.files] if args.files or args.extra else corpus
    extra = [f.resolve() for f in args.extra]
    status = 0
    known = {relative(f) for f in corpus}
    for stale in sorted(set(entries) - known):
        print(f"FAIL {stale}: listed in {relative(EXPECTED)} but not in the corpus: remove its line")
        status = 1
    start = time.monotonic()
    counts, results = {}, []
    extra_names = {relative(f) for f in extra}
    with tempfile.TemporaryDirectory() as tmp, concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        work = args.work or pathlib.Path(tmp)
        futures = [pool.submit(run_guarded, f, work, args.orchestrator, args.esmini) for f in files + extra]
        for future in concurrent.futures.as_completed(futures):  # each file's line as soon as it is done
            r = future.result()
            results.append(r)
            counts[r["status"]] = counts.get(r["status"], 0) + 1
            if r["file"] in extra_names:
                off = storyboard_only_text(r)
                print(f"extra {r['file']}: {r['status']} {r['detail']} ({summary_of(r['comparison'])})" +
                      (f"\n    {off}" if off else ""), flush=True)
                continue
            ok, line = judge(r, entries.get(r["file"]))
            off = storyboard_only_text(r)
            print(line + (f"\n    {off}" if off else ""), flush=True)
            status |= 0 if ok else 1
    elapsed = time.monotonic() - start
    slowest = sorted(results, key=lambda r: -r["seconds"])[:3]
    print(f"differential: {len(results)} files in {elapsed:.1f} s with {args.jobs} jobs: " +
          ", ".join(f"{n} {k}" for k, n in sorted(counts.items())) +
          "; " + storyboard_only_figure([r for r in results if r["file"] not in extra_names]) +
          "; " + positions_figure([r for r in results if r["file"] not in extra_names]) +
          "; slowest: " + ", ".join(f"{pathlib.Path(r['file']).name} {r['seconds']:.1f} s" for r in slowest))
    if args.results:
        args.results.write_text(json.dumps(
            sorted(({"file": r["file"], "status": r["status"], "detail": r["detail"],
                     "summary": summary_of(r["comparison"]), "positions_match": positions_match(r),
                     "storyboard_only": None if not r.get("storyboard_only") else {
                         "status": r["storyboard_only"]["status"], "detail": r["storyboard_only"]["detail"],
                         "summary": summary_of(r["storyboard_only"]["comparison"])}}
                    for r in results), key=lambda r: r["file"]),
            indent=1) + "\n")
    if args.update:
        for r in results:
            if r["file"] in extra_names:
                continue
            old = entries.get(r["file"])
            if r["status"] in ("match", "departs"):
                entries.pop(r["file"], None)
            elif not old or old.category != r["status"]:
                entries[r["file"]] = expected.Entry(r["file"], r["status"], r["detail"])
        expected.write(EXPECTED, entries)
        write_between(DOC, BEGIN, END, expected.doc_table(entries))
        print(f"differential: wrote {relative(EXPECTED)} ({len(entries)} files) and {relative(DOC)}")
    return status


if __name__ == "__main__":
    sys.exit(main())
