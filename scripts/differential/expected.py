"""The table of expected differences: the files of the corpus that do not (yet) run like the
peer, each with its category and the reason, one a line:

    ../shared/data/esmini_examples/xosc/FILE.xosc | unreadable | why, in words

Paths are relative to the checkout. Categories (what the harness finds for the file):
- unreadable: our `run` stops before the first step (the file cannot be read or placed);
- ours-error: our run starts and stops with an error;
- peer-error: esmini cannot run the file (so there is nothing to compare with);
- differs: both run, and a position or a transition differs.
Lines starting with # are comments. The table is also docs/differential.md's table.
"""
import dataclasses
import pathlib

CATEGORIES = ("unreadable", "ours-error", "peer-error", "differs")


@dataclasses.dataclass
class Entry:
    file: str
    category: str
    reason: str


def read(path: pathlib.Path) -> dict:
    """{file: Entry}; a malformed line, an unknown category or a file listed twice stops with
    the line number."""
    entries = {}
    for number, line in enumerate(path.read_text().splitlines(), 1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        parts = [p.strip() for p in line.split("|", 2)]
        if len(parts) != 3 or not all(parts):
            raise SystemExit(f"{path}:{number}: expected 'file | category | reason', found: {line}")
        file, category, reason = parts
        if category not in CATEGORIES:
            raise SystemExit(f"{path}:{number}: unknown category {category!r} (one of {', '.join(CATEGORIES)})")
        if file in entries:
            raise SystemExit(f"{path}:{number}: {file} is listed twice")
        entries[file] = Entry(file, category, reason)
    return entries


def write(path: pathlib.Path, entries: dict) -> None:
    """Rewrites the table (the comment block at the top is kept), sorted by file."""
    head = []
    for line in path.read_text().splitlines() if path.exists() else []:
        if line.strip() and not line.lstrip().startswith("#"):
            break
        head.append(line)
    body = [f"{e.file} | {e.category} | {e.reason}" for e in sorted(entries.values(), key=lambda e: e.file)]
    path.write_text("\n".join(head + body) + "\n")


def doc_table(entries: dict) -> str:
    """The Markdown table of docs/differential.md."""
    lines = ["| file | category | reason |", "|---|---|---|"]
    for e in sorted(entries.values(), key=lambda e: e.file):
        name = e.file.replace("../shared/data/", "")
        lines.append(f"| `{name}` | {e.category} | {e.reason.replace('|', '/')} |")
    return "\n".join(lines)
