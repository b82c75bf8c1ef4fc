"""Scene runs through a configuration's `collide` binary, and the diamond's drift from ODE."""
import functools
import json
import math
import re
import subprocess
from pathlib import Path

from .paths import BUILD, ROOT, write_atomic

SCENES = BUILD / "scenes"


def scene_file(scene, link: str = None, clock_mhz: float = None) -> Path:
    """scenes/diamond.json with the sweep's hMax and step count; with a clock, the link preset
    `link` at that clock (`collide run --link` takes a preset's own clock)."""
    s = json.loads((ROOT / "scenes" / "diamond.json").read_text())
    s["name"] = scene.id
    s["steps"] = scene.steps
    s["bodies"]["diamond"]["hMax"] = scene.hmax
    s["bodies"]["diamond"]["dSph"] = 0
    name = scene.id
    if clock_mhz is not None:
        s["link"] = {"type": link, "clock_mhz": clock_mhz}
        name += f"-{link}-{clock_mhz:g}MHz"
    path = SCENES / f"{name}.json"
    write_atomic(path, json.dumps(s, indent=2) + "\n")
    return path


def preset_clocks(info_text: str) -> dict:
    """{preset: its clock in MHz} from `collide info --links`: each preset's header line
    ("qpi (also harp1): ..." or "ideal: ...") then its "  clock N MHz" line."""
    out, name = {}, None
    for line in info_text.splitlines():
        head = re.match(r"^([A-Za-z0-9_-]+)(?: \(also [^)]*\))?: ", line)
        if head:
            name = head.group(1)
            continue
        m = re.match(r"^\s+clock ([0-9.]+) MHz", line)
        if m and name and name not in out:
            out[name] = float(m.group(1))
    return out


@functools.lru_cache(maxsize=None)
def preset_clock(binary: Path, preset: str) -> float:
    """The clock (MHz) the host's link preset `preset` runs its AFU at."""
    r = subprocess.run([str(binary), "info", "--links"], capture_output=True, text=True)
    clocks = preset_clocks(r.stdout) if r.returncode == 0 else {}
    if preset not in clocks:
        raise RuntimeError(f"{binary} info --links: no clock for link preset '{preset}' (found {sorted(clocks)})")
    return clocks[preset]


def run(binary: Path, scene, backend: str, out_dir: Path, link: str = None, cpu_repeat: int = 1,
        positions: bool = False, clock_mhz: float = None) -> dict:
    """`collide run` for one scene; returns its summary JSON (plus the positions file's path).
    clock_mhz: the link preset at that clock instead of its own (the scene names it)."""
    out_dir.mkdir(parents=True, exist_ok=True)
    summary = out_dir / "summary.json"
    cmd = [str(binary), "run", str(scene_file(scene, link, clock_mhz)), "--backend", backend, "--steps", str(scene.steps),
           "--summary", str(summary), "--cpu-repeat", str(cpu_repeat)]
    if link and clock_mhz is None:
        cmd += ["--link", link]
    if positions:
        cmd += ["--positions", str(out_dir / "positions.csv")]
    with open(out_dir / "stdout.txt", "w") as out:
        r = subprocess.run(cmd, stdout=out, stderr=subprocess.STDOUT)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({r.returncode}); see {out_dir / 'stdout.txt'}")
    return json.loads(summary.read_text())


def read_positions(path: Path) -> list:
    rows = path.read_text().splitlines()[1:]
    return [tuple(float.fromhex(v) for v in line.split(",")[1:4]) for line in rows]


def drift(a: Path, b: Path) -> dict:
    """Distance between the same sphere's final positions in two runs: worst and mean (m)."""
    pa, pb = read_positions(a), read_positions(b)
    if len(pa) != len(pb):
        raise RuntimeError(f"{a} and {b} hold different sphere counts ({len(pa)} vs {len(pb)})")
    d = [math.dist(x, y) for x, y in zip(pa, pb)]
    return {"drift_max_m": max(d), "drift_mean_m": sum(d) / len(d)}
