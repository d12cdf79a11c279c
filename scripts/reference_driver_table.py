#!/usr/bin/env python3
"""Runs every ALKS scenario of ../shared/data (ScenarioExecutor files in roadeditor/scenarios,
OpenSCENARIO files in openscenario/) with the SUMO ego and a reference run (the UN R157
reference driver as the ego), prints the table of both side by side and rewrites it between
the reference-table markers in docs/reference-driver.md.

Usage: scripts/reference_driver_table.py [--binary build/bin/orchestrator] [--jobs 2] [--max-time S]
"""
import argparse
import json
import pathlib
import subprocess

from doc_tables import run_all, write_between

ROOT = pathlib.Path(__file__).resolve().parent.parent
SHARED = ROOT.parent / "shared" / "data"
BEGIN, END = "<!-- reference-table:begin -->", "<!-- reference-table:end -->"


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


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", default=str(ROOT / "build" / "bin" / "orchestrator"))
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--max-time", type=float, default=0, help="end every run at this simulated time (0: none)")
    args = parser.parse_args()
    files = scenarios()
    if not files:
        raise SystemExit(f"no ALKS scenarios in {SHARED}")
    rows = run_all(lambda f, root: run_one(pathlib.Path(args.binary), f, root, args.max_time), files, args.jobs)
    write_between(ROOT / "docs" / "reference-driver.md", BEGIN, END, table(rows))
    print(table(rows))


if __name__ == "__main__":
    main()
