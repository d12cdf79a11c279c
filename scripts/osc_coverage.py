#!/usr/bin/env python3
"""OpenSCENARIO coverage, element by element, generated from the code and the differential
test's results (in the spirit of esmini's osc_coverage.txt): for every element of the
standard's schema (the orchestrator's own list, orchestrator/openscenario/standard_elements.cpp)
that a corpus file uses (the file itself and the catalog entries it references), how many of
those files ran here and matched the peer player (every compared point within 0.10 m, every
transition within a step), matched but for the peer's cited departures from the standard's
transitions (scripts/differential/departures.py), ran but differ, were refused, or the peer could not run; which
files refused it as "not supported"; and the files that check it against the peer.

Usage: scripts/osc_differential.py --results /tmp/osc.json   (the whole corpus)
       scripts/osc_coverage.py /tmp/osc.json [--write]        (print, or rewrite docs/openscenario-coverage.md)
"""
import argparse
import json
import pathlib
import re
import sys
import xml.etree.ElementTree as ET

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from doc_tables import write_between  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent
DOC = ROOT / "docs" / "openscenario-coverage.md"
BEGIN, END = "<!-- coverage:begin -->", "<!-- coverage:end -->"
RAN = ("match", "departs", "differs", "ours-error")


def standard_elements() -> list:
    text = (ROOT / "orchestrator" / "openscenario" / "standard_elements.cpp").read_text()
    block = text[text.index("kStandardElements"):]
    block = block[:block.index("});")]
    return sorted(set(re.findall(r'"([A-Za-z0-9]+)"', block)))


def parse(path: pathlib.Path):
    try:
        return ET.parse(path).getroot()
    except (ET.ParseError, OSError):
        return None


def catalog_entries(root, base: pathlib.Path) -> list:
    """The catalog entries the file references (CatalogReference catalogName / entryName)."""
    dirs = [base / d.get("path", "") for d in root.iter("Directory")]
    wanted = {(r.get("catalogName"), r.get("entryName")) for r in root.iter("CatalogReference")}
    entries = []
    for folder in dirs:
        for f in sorted(folder.glob("*.xosc")) if folder.is_dir() else []:
            catalog = parse(f)
            if catalog is None:
                continue
            for c in catalog.iter("Catalog"):
                entries += [e for e in c if (c.get("name"), e.get("name")) in wanted]
    return entries


def elements_of(file: pathlib.Path) -> set:
    root = parse(file)
    if root is None:
        return set()
    names = {e.tag for e in root.iter()}
    for entry in catalog_entries(root, file.parent):
        names |= {e.tag for e in entry.iter()}
    return names


def refused_element(detail: str):
    m = re.search(r"(\w+) in \w+ is an OpenSCENARIO element the orchestrator does not run", detail)
    return m.group(1) if m else None


def table(results: list) -> str:
    standard = standard_elements()
    uses = {name: [] for name in standard}
    for r in results:
        for name in elements_of((ROOT / r["file"]).resolve()):
            if name in uses:
                uses[name].append(r)
    rows = ["| element | files | ran: match | ran: match but for esmini's departures | ran: differ | refused here | peer cannot | refused as not supported by | checked against the peer by |",
            "|---|---|---|---|---|---|---|---|---|"]
    unused = []
    for name in standard:
        files = uses[name]
        if not files:
            unused.append(name)
            continue
        count = lambda *s: sum(1 for r in files if r["status"] in s)  # noqa: E731
        refused_by = [pathlib.Path(r["file"]).name for r in files if refused_element(r["detail"]) == name]
        matching = [pathlib.Path(r["file"]).name for r in files if r["status"] == "match"]
        rows.append(f"| {name} | {len(files)} | {count('match')} | {count('departs')} | {count('differs', 'ours-error')} | "
                    f"{count('unreadable')} | {count('peer-error', 'harness-error')} | "
                    f"{', '.join(refused_by[:3]) + (f' (+{len(refused_by) - 3})' if len(refused_by) > 3 else '')} | "
                    f"{', '.join(matching[:2]) + (f' (+{len(matching) - 2})' if len(matching) > 2 else '')} |")
    totals = {}
    for r in results:
        totals[r["status"]] = totals.get(r["status"], 0) + 1
    head = (f"{len(results)} corpus files: " + ", ".join(f"{n} {k}" for k, n in sorted(totals.items())) +
            f". {len(standard) - len(unused)} of the schema's {len(standard)} elements appear in them.")
    return head + "\n\n" + "\n".join(rows) + "\n\nElements of the schema no corpus file uses (not checked): " + \
        ", ".join(unused) + "."


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results", type=pathlib.Path, help="scripts/osc_differential.py --results FILE")
    parser.add_argument("--write", action="store_true", help=f"rewrite the table in {DOC.relative_to(ROOT)}")
    args = parser.parse_args()
    text = table(json.loads(args.results.read_text()))
    if args.write:
        write_between(DOC, BEGIN, END, text)
    else:
        print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
