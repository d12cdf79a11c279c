"""The R157 reference driver beside esmini's ReferenceDriver (ALKS_R157SM_Controller, model
ReferenceDriver) on the OSC-ALKS templates: both players' runs, measured the same way.

Our run: `orchestrator run TEMPLATE --ego-model r157`. The peer's: a copy of the template (in a
temporary copy of its folder, so that its roads and catalogs resolve) whose ego's controller is
ALKS_R157SM_Controller with model ReferenceDriver, run headless by esmini at the same step.
Both are measured from their traces with one function (boxes in the ego's frame): the ego's
first collision, its minimum bumper-to-bumper gap to what is ahead of it with bodies
overlapping laterally, its minimum speed; and from their logs when the risk was perceived
and when braking began."""
import csv
import math
import pathlib
import re
import shutil
import subprocess

ESMINI_CONTROLLER = ('<ObjectController><Controller name="ALKS_R157SM_Controller"><Properties>'
                     '<Property name="model" value="ReferenceDriver"/><Property name="logLevel" value="2"/>'
                     '<Property name="cruise" value="true"/></Properties></Controller></ObjectController>')


class Box:
    def __init__(self, x, y, h, length, width, speed):
        self.x, self.y, self.h, self.length, self.width, self.speed = x, y, h, length, width, speed


def measure(frames: list, ego: str) -> dict:
    """frames: [(time, {name: Box})]. The ego's first collision, minimum gap ahead, minimum speed."""
    out = {"collision": None, "min_gap": None, "min_speed": None}
    for time, boxes in frames:
        me = boxes.get(ego)
        if me is None:
            continue
        out["min_speed"] = me.speed if out["min_speed"] is None else min(out["min_speed"], me.speed)
        c, s = math.cos(me.h), math.sin(me.h)
        for name, o in boxes.items():
            if name == ego:
                continue
            dx = (o.x - me.x) * c + (o.y - me.y) * s
            dy = -(o.x - me.x) * s + (o.y - me.y) * c
            if abs(dy) >= (me.width + o.width) / 2:
                continue  # beside, not in the ego's way
            gap = abs(dx) - (me.length + o.length) / 2
            if gap <= 0 and out["collision"] is None:
                out["collision"] = {"with": name, "time": time}
            if dx > 0:
                g = max(gap, 0.0)
                out["min_gap"] = g if out["min_gap"] is None else min(out["min_gap"], g)
    return out


def ours(binary: pathlib.Path, template: pathlib.Path, out: pathlib.Path) -> dict:
    subprocess.run([str(binary), "run", str(template), "--out", str(out), "-q", "--no-report", "--ego-model", "r157"],
                   capture_output=True, text=True)
    result = __import__("json").loads((out / "result.json").read_text())
    sizes = {a["sumo_id"]: (a["length"], a["width"]) for a in result.get("actors", [])}
    ego = next((a["sumo_id"] for a in result.get("actors", []) if a.get("ego")), "Ego")
    frames, current, now = [], {}, None
    with open(out / "trace.csv") as f:
        for row in csv.DictReader(f):
            t = float(row["time"])
            if now is not None and t != now:
                frames.append((now, current))
                current = {}
            now = t
            name = row["actor_id"]
            length, width = sizes.get(name, (4.5, 1.8))
            current[name] = Box(float(row["x"]), float(row["y"]), float(row["heading"]), length, width,
                                float(row["speed"]))
    if current:
        frames.append((now, current))
    m = measure(frames, ego)
    events = [(float(t), text) for t, text in re.findall(r"^t=\s*([\d.]+)\s+(r157: .*)$",
                                                          (out / "run.log").read_text(), re.M)]
    m["perceived"] = next(((t, e) for t, e in events if e.endswith("risk perceived")), None)
    m["braking"] = next(((t, e) for t, e in events if e.endswith(": braking")), None)
    m["verdict"] = result["verdict"]
    return m


def peer_copy(template: pathlib.Path, folder: pathlib.Path) -> pathlib.Path:
    """A copy of `template` beside copies of its roads and catalogs, its ego driven by esmini's
    ReferenceDriver."""
    if not (folder / "catalogs").exists():
        shutil.copytree(template.parent, folder, dirs_exist_ok=True)
    text = template.read_text()
    ego = re.search(r'<ScenarioObject name="Ego">.*?</ScenarioObject>', text, re.S)
    if not ego:
        raise SystemExit(f"{template}: no ScenarioObject Ego")
    changed = re.sub(r"<ObjectController>.*?</ObjectController>", ESMINI_CONTROLLER, ego.group(0), flags=re.S)
    copy = folder / ("peer_" + template.name)
    copy.write_text(text.replace(ego.group(0), changed))
    return copy


def esmini_frames(csv_file: pathlib.Path) -> list:
    lines = csv_file.read_text().splitlines()
    at = next(i for i, line in enumerate(lines) if line.startswith("Index"))
    header = [h.strip() for h in lines[at].split(",")]
    groups = {}
    for i, h in enumerate(header):
        m = re.match(r"#(\d+) (.*)", h)
        if m:
            groups.setdefault(int(m.group(1)), {})[m.group(2)] = i
    frames = []
    for line in lines[at + 1:]:
        f = [x.strip() for x in line.split(",")]
        if len(f) < len(header) - 1:
            continue
        boxes = {}
        for g in groups.values():
            h = float(f[g["World_Heading_Angle [rad]"]])
            bx, by = float(f[g["bb_x [m]"]]), float(f[g["bb_y [m]"]])
            x = float(f[g["World_Position_X [m]"]]) + bx * math.cos(h) - by * math.sin(h)
            y = float(f[g["World_Position_Y [m]"]]) + bx * math.sin(h) + by * math.cos(h)
            boxes[f[g["Entity_Name [-]"]]] = Box(x, y, h, float(f[g["bb_length [m]"]]), float(f[g["bb_width [m]"]]),
                                                 float(f[g["Current_Speed [m/s]"]]))
        frames.append((float(f[1]), boxes))
    return frames


def peer(esmini_bin: pathlib.Path, template: pathlib.Path, folder: pathlib.Path) -> dict:
    copy = peer_copy(template, folder)
    stem = copy.stem
    subprocess.run([str(esmini_bin / "esmini"), "--headless", "--fixed_timestep", "0.05", "--osc", copy.name,
                    "--csv_logger", stem + ".csv", "--collision", "--disable_stdout", "--logfile_path", stem + ".log"],
                   cwd=folder, capture_output=True, text=True, timeout=600)
    m = measure(esmini_frames(folder / (stem + ".csv")), "Ego")
    log = (folder / (stem + ".log")).read_text()
    events = [(float(t), text) for t, text in re.findall(r"^\[([\d.]+)\] \[info\] ALKS R157 ReferenceDriver (.*)$", log, re.M)]
    m["perceived"] = next(((t, e) for t, e in events if "-> PERCEIVE" in e), None)
    m["braking"] = next(((t, e) for t, e in events if "-> BRAKE" in e or "AEB activated" in e), None)
    scenario = next((e for _, e in events if e.startswith("Detected object")), None)
    m["risk"] = scenario
    return m
