#!/usr/bin/env python3
"""Cost of hostile inputs (docs/hardening.md): wall and CPU time and peak RSS of `validate` and
`run` on an empty object, 1 MB of nesting (arrays and objects) and a 100 MB scenario (the
bench scenario with a 100 MB array under an extra key), each as its own process. Figures,
not a test: the memory above an empty run's is compared with the file's size.
Usage: input_limits.py --binary build/bin/orchestrator [--mb 100] [--repeat 3]"""
import argparse
import json
import os
import pathlib
import subprocess
import tempfile
import time

HERE = pathlib.Path(__file__).resolve().parent


def measure(cmd):
    """(wall seconds, CPU seconds, peak RSS in MB, exit status) of one process. CPU time
    (user + system) is what to compare on a shared machine, where wall time waits."""
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    return wall, usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024.0, os.waitstatus_to_exitcode(status)


def write_inputs(folder, mb):
    files = {}
    files["empty object"] = folder / "empty.json"
    files["empty object"].write_text("{}\n")
    half = 512 * 1024
    files["1 MB of nested arrays"] = folder / "deep_arrays.json"
    files["1 MB of nested arrays"].write_text("[" * half + "]" * half)
    files["1 MB of nested objects"] = folder / "deep_objects.json"
    files["1 MB of nested objects"].write_text('{"a":' * (1024 * 1024 // 6) + "1" + "}" * (1024 * 1024 // 6))
    scenario = json.loads((HERE / "bench_scenario.json").read_text())
    big = folder / "big.json"
    with big.open("w") as out:
        text = json.dumps(scenario, indent=2)
        out.write(text[: text.rfind("}")] + ',\n  "padding": [\n')
        line = ", ".join(str(1000000 + i) for i in range(12)) + ",\n"
        for _ in range(mb * 1024 * 1024 // len(line)):
            out.write("    " + line)
        out.write("    0\n  ]\n}\n")
    files[f"{mb} MB scenario"] = big
    return files


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--binary", required=True)
    ap.add_argument("--mb", type=int, default=100)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    print(f"load average: {os.getloadavg()}")
    with tempfile.TemporaryDirectory() as tmp:
        folder = pathlib.Path(tmp)
        files = write_inputs(folder, args.mb)
        rows = []
        for name, path in files.items():
            size_mb = path.stat().st_size / 1e6
            for command in ("validate", "run"):
                cmd = [args.binary, command, str(path)]
                if command == "run":
                    cmd += ["--out", str(folder / "out"), "-q"]
                best = min((measure(cmd) for _ in range(args.repeat)), key=lambda m: m[1])
                rows.append((name, size_mb, command, *best))
        empty = {c: (cpu, rss) for (n, _, c, _, cpu, rss, _) in rows if n == "empty object"}
        print(f"\n| input | size MB | command | exit | wall s | CPU s | CPU s above empty | peak RSS MB "
              f"| RSS above empty / size |")
        print("|---|---|---|---|---|---|---|---|---|")
        for name, size_mb, command, wall, cpu, rss, code in rows:
            base_cpu, base_rss = empty[command]
            above = f"{(rss - base_rss) / size_mb:.2f}" if name != "empty object" else "-"
            print(f"| {name} | {size_mb:.1f} | {command} | {code} | {wall:.3f} | {cpu:.3f} | {cpu - base_cpu:.3f} "
                  f"| {rss:.0f} | {above} |")


if __name__ == "__main__":
    main()
