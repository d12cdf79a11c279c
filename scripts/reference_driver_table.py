#!/usr/bin/env python3
"""Runs every ALKS scenario of ../shared/data (ScenarioExecutor files in roadeditor/scenarios,
OpenSCENARIO files in openscenario/) with the SUMO ego and a reference run (the UN R157
reference driver as the ego), prints the table of both side by side and rewrites it between
the reference-table markers in docs/reference-driver.md.

--peer instead runs the OSC-ALKS templates (openscenario/alks_*.xosc) with our reference
driver and with esmini's ReferenceDriver (../shared/tools/esmini, ALKS_R157SM_Controller) and
writes that side-by-side table between the peer-table markers (reference_driver_peer.py).

Usage: scripts/reference_driver_table.py [--binary build/bin/orchestrator] [--jobs 2] [--max-time S]
       [--peer [--templates DIR]]
"""
import argparse
import json
import pathlib
import subprocess

from doc_tables import run_all, write_between
import reference_driver_peer as peer

ROOT = pathlib.Path(__file__).resolve().parent.parent
SHARED = ROOT.parent / "shared" / "data"
BEGIN, END = "<!-- reference-table:begin -->", "<!-- reference-table:end -->"
PEER_BEGIN, PEER_END = "<!-- peer-table:begin -->", "<!-- peer-table:end -->"
ESMINI = ROOT.parent / "shared" / "tools" / "esmini" / "bin"


def scenarios() -> list:
    files = sorted((SHARED / "roadeditor" / "scenarios").glob("ALKS_*.json"))
    files += sorted((SHARED / "openscenario").glob("alks_*.xosc"))
    return files


def run_one(binary: pathlib.Path, scenario: pathlib.Path, out_root: pathlib.Path, max_time: float) -> dict:
    out = out_root / scenario.stem
    cmd = [str(binary), "run", str(scenario), "--out", str(out), "-q", "--no-report", "--ego-model", "sumo",
           "--reference-run"]
    if max_time > 0:
        cmd += ["--max-time", str(max_time)]
    subprocess.run(cmd, capture_output=True, text=True)
    result = json.loads((out / "result.json").read_text())
    ref_file = out / "reference" / "result.json"
    reference = json.loads(ref_file.read_text()) if ref_file.exists() else {}
    return {"file": scenario.name, "result": result, "reference": reference}


def ttc(value) -> str:
    return "–" if value is None else f"{value:.2f} s"


def collision(c) -> str:
    if not c:
        return "none"
    speed = "" if c.get("relative_speed") is None else f", {c['relative_speed']:.1f} m/s"
    return f"{c['with']} at {c['time']:.2f} s{speed}"


def table(rows: list) -> str:
    lines = ["| scenario | sumo: verdict | sumo: min TTC | sumo: collision | r157: verdict | r157: min TTC "
             "| r157: collision | preventable |",
             "|---|---|---|---|---|---|---|---|"]
    for row in rows:
        r, ref = row["result"], row["reference"]
        rr = r.get("reference_run") or {}
        lines.append(f"| {row['file']} | {r['verdict']} | {ttc(rr.get('min_ttc'))} | {collision(r.get('collision'))} "
                     f"| {ref.get('verdict', '–')} | {ttc(rr.get('reference_min_ttc'))} "
                     f"| {collision(ref.get('collision'))} | {r.get('preventable', '–')} |")
    return "\n".join(lines)


def peer_row(binary: pathlib.Path, template: pathlib.Path, root: pathlib.Path) -> dict:
    return {"file": template.name, "ours": peer.ours(binary, template, root / ("ours_" + template.stem)),
            "peer": peer.peer(ESMINI, template, root / ("peer_" + template.stem))}


def peer_table(rows: list) -> str:
    def hit(c):
        return "none" if not c else f"{c['with']} at {c['time']:.2f} s"

    def num(v, unit):
        return "–" if v is None else f"{v:.2f} {unit}"

    def when(m):
        p, b = m.get("perceived"), m.get("braking")
        return f"{'–' if not p else f'{p[0]:.2f}'} / {'–' if not b else f'{b[0]:.2f}'}"

    lines = ["| template | ours: collision | ours: min gap | ours: min speed | ours: risk / braking (s) "
             "| esmini: collision | esmini: min gap | esmini: min speed | esmini: risk / braking (s) |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        o, e = r["ours"], r["peer"]
        lines.append(f"| {r['file'].replace('alks_scenario_', '').replace('_template.xosc', '')} "
                     f"| {hit(o['collision'])} | {num(o['min_gap'], 'm')} | {num(o['min_speed'], 'm/s')} | {when(o)} "
                     f"| {hit(e['collision'])} | {num(e['min_gap'], 'm')} | {num(e['min_speed'], 'm/s')} | {when(e)} |")
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", default=str(ROOT / "build" / "bin" / "orchestrator"))
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--max-time", type=float, default=0, help="end every run at this simulated time (0: none)")
    parser.add_argument("--peer", action="store_true", help="the side-by-side table with esmini's ReferenceDriver")
    parser.add_argument("--templates", default=str(SHARED / "openscenario"),
                        help="with --peer: the folder of the OSC-ALKS templates (alks_*.xosc, with their catalogs and roads)")
    args = parser.parse_args()
    if args.peer:
        templates = sorted(pathlib.Path(args.templates).glob("alks_*.xosc"))
        if not templates or not (ESMINI / "esmini").exists():
            raise SystemExit(f"need the OSC-ALKS templates in {args.templates} and esmini in {ESMINI}")
        rows = run_all(lambda f, root: peer_row(pathlib.Path(args.binary), f, root), templates, args.jobs)
        write_between(ROOT / "docs" / "reference-driver.md", PEER_BEGIN, PEER_END, peer_table(rows))
        print(peer_table(rows))
        return
    files = scenarios()
    if not files:
        raise SystemExit(f"no ALKS scenarios in {SHARED}")
    rows = run_all(lambda f, root: run_one(pathlib.Path(args.binary), f, root, args.max_time), files, args.jobs)
    write_between(ROOT / "docs" / "reference-driver.md", BEGIN, END, table(rows))
    print(table(rows))


if __name__ == "__main__":
    main()
