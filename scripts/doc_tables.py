"""Helpers of the scripts that run scenario files and write their table into a doc page:
run every file in a thread pool, and replace the text between two markers."""
import concurrent.futures
import pathlib
import tempfile


def run_all(run_one, files: list, jobs: int) -> list:
    """run_one(file, out_root) for every file, `jobs` at a time, in a temporary folder."""
    with tempfile.TemporaryDirectory() as tmp, concurrent.futures.ThreadPoolExecutor(jobs) as pool:
        return list(pool.map(lambda f: run_one(f, pathlib.Path(tmp)), files))


def write_between(doc: pathlib.Path, begin: str, end: str, table: str) -> None:
    """Replaces what lies between the markers `begin` and `end` in `doc` with `table`."""
    text = doc.read_text()
    start, stop = text.index(begin) + len(begin), text.index(end)
    doc.write_text(text[:start] + "\n" + table + "\n" + text[stop:])
