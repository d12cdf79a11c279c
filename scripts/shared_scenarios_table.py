#!/usr/bin/env python3
"""Runs every real scenario file in ../shared/data/roadeditor/scenarios with the built
orchestrator and rewrites the table between the shared-table markers in docs/shared-scenarios.md.

Usage: scripts/shared_scenarios_table.py [--binary build/bin/orchestrator] [--jobs 2]
"""
import argparse
import json
import pathlib
import subprocess

from doc_tables import run_all, write_between

ROOT = pathlib.Path(__file__).resolve().parent.parent
SHARED = ROOT.parent / "shared" / "data" / "roadeditor" / "scenarios"
BEGIN, END = "<!-- shared-table:begin -->", "<!-- shared-table:end -->"


def run_one(binary: pathlib.Path, scenario: pathlib.Path, out_root: pathlib.Path) -> dict:
    out = out_root / scenario.stem
    proc = subprocess.run([str(binary), "run", str(scenario), "--out", str(out), "-q"],
                          capture_output=True, text=True)
    result = json.loads((out / "result.json").read_text())
    return {"file": scenario.name, "exit": proc.returncode, "result": result}


def table(rows: list) -> str:
    lines = ["| scenario | map | verdict | simulated time | scenes visited | ended by |",
             "|---|---|---|---|---|---|"]
    for row in rows:
        r = row["result"]
        scenes = " → ".join(str(s["scene_id"]) for s in r["scenes"])
        reason = r["reason"].replace("|", "\\|")
        lines.append(f"| {row['file']} | {r['map_id']} | {r['verdict']} | {r['sim_time']:.2f} s | {scenes} | {reason} |")
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", default=str(ROOT / "build" / "bin" / "orchestrator"))
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args()
    scenarios = sorted(SHARED.glob("*.json"))
    if not scenarios:
        raise SystemExit(f"no scenarios in {SHARED}")
    rows = run_all(lambda f, root: run_one(pathlib.Path(args.binary), f, root), scenarios, args.jobs)
    write_between(ROOT / "docs" / "shared-scenarios.md", BEGIN, END, table(rows))
    print(table(rows))


if __name__ == "__main__":
    main()
