"""Scale: the narrow phase's cost per pair and per collision against scene size, 1,000 to
1,000,000 spheres, for ODE's collider, the simd kernel in binary32 and binary64, and (as far
as a co-simulation goes in minutes) the AFU modelled over HARP v1 and the ideal link; with
each run's peak memory per sphere.

Scene families (written to OUT/scenes/, 2 steps each, pairs path):
  pile     a seeded random cloud poured into a box of planes under gravity, at pile_box's density
           (1,500 spheres on a 0.88 m square base); the base grows with the count, the height stays
  diamond  the paper's diamond at hMax 14, 24, 46 and 100 (1,834 to 666,700 spheres)
ODE's hash space holds at most 131,071 spheres; larger scenes use its sweep-and-prune space.

One `collide run --backend simd` per scene times ODE's collider, simd and simd64 on the very same
pairs each step (fastest of --cpu-repeat); `--backend rtl --link qpi|ideal` runs the AFU on them
(the first step's pairs are the same; the AFU's table holds 1,024 spheres, so a batch is split
into several calls, each paying its own per-call cost).

    tools/pyenv bench/scale/scale.py [--collide build/host/collide] [--rtl-max 16384] [--cpu-repeat 3]
        [--sizes 1000,...] [--out bench/results/scale]
    tools/pyenv bench/scale/scale.py --report-only
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only
import matplotlib.pyplot as plt  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench" / "world"))
from world import machine, write_results  # noqa: E402
from sweeplib.machine import commit  # noqa: E402

PILE_SIZES = (1000, 4000, 16000, 64000, 256000, 1000000)
DIAMOND_HMAX = (14, 24, 46, 100)
HASH_LIMIT = 131071  # ODE's hash space (docs/host.md)


def diamond_count(h):
    return h * (2 * h * h + 1) // 3


def pile_scene(n):
    w = 0.88 * math.sqrt(n / 1500)  # pile_box's base for 1,500 spheres, grown with the count
    half = w / 2 + 0.06
    return {
        "name": f"pile_{n}", "steps": 2, "dt": 0.01, "backend": "simd",
        "world": {"cfm": 1e-5, "erp": 0.2, "contact_max_correcting_vel": 0.1, "contact_surface_layer": 0.001},
        "effects": {"gravity": [0, 0, -9.81], "planes": [
            {"normal": [0, 0, 1], "offset": 0}, {"normal": [1, 0, 0], "offset": -half},
            {"normal": [-1, 0, 0], "offset": -half}, {"normal": [0, 1, 0], "offset": -half},
            {"normal": [0, -1, 0], "offset": -half}]},
        "contact": {"mu": 0.5, "friction": "coulomb", "soft_cfm": 0.0001},
        "collision": {"space": "hash" if n <= HASH_LIMIT else "sap"},
        "bodies": {"random_cloud": {"count": n, "seed": 7, "min": [-w / 2, -w / 2, 0.06], "max": [w / 2, w / 2, 2.5],
                                    "radius": [0.04, 0.06], "mass": 0.5}},
    }


def diamond_scene(h):
    return {"name": f"diamond_{h}", "steps": 2, "dt": 0.01, "backend": "simd",
            "world": {"cfm": 1e-5}, "contact": {"mu": "infinity", "bounce": 1.0, "bounce_vel": 0.1, "soft_cfm": 0.001},
            "collision": {"space": "hash" if diamond_count(h) <= HASH_LIMIT else "sap"},
            "bodies": {"diamond": {"hMax": h, "dSph": 0}}}


def run(collide, scene_path, args, work):
    """One `collide run`: its summary and its peak resident memory (this child's alone)."""
    summary = work / "summary.json"
    t = time.time()
    p = subprocess.Popen([str(collide), "run", str(scene_path), "--summary", str(summary), *args],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    _, status, usage = os.wait4(p.pid, 0)
    err = p.stderr.read()
    if os.waitstatus_to_exitcode(status) != 0:
        raise RuntimeError(f"collide run {scene_path.name} {' '.join(args)}: {err.strip()}")
    return json.loads(summary.read_text()), usage.ru_maxrss * 1024, time.time() - t


def rows_of(family, n, s, rss, wall):
    base = {"family": family, "spheres": n, "pairs": s["pairs"], "contacts": s["contacts"],
            "peak_rss_bytes": rss, "bytes_per_sphere": round(rss / n), "wall_s": round(wall, 2)}
    if "afu" in s:
        a = s["afu"]
        yield dict(base, backend=f"rtl {a['link']}", ns=a["modelled_ns"], calls=a["runs"])
        return
    for name, key in (("ode", "ode_ns"), ("simd", "simd_ns"), ("simd64", "simd64_ns")):
        yield dict(base, backend=name, ns=s[key], calls="")


def plot(rows, out):
    fig, axes = plt.subplots(1, 2, figsize=(13, 5))
    for ax, per in zip(axes, ("pairs", "contacts")):
        for family, marker in (("pile", "o"), ("diamond", "s")):
            for backend in dict.fromkeys(r["backend"] for r in rows):
                pts = sorted((int(r["spheres"]), float(r["ns"]) / int(r[per])) for r in rows
                             if r["family"] == family and r["backend"] == backend and int(r[per]) > 0)
                if pts:
                    ax.plot(*zip(*pts), marker=marker, label=f"{backend}, {family}", linewidth=1)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("spheres")
        ax.set_ylabel(f"ns per {'pair' if per == 'pairs' else 'collision'} (narrow phase, 2 steps)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(out / "scale.png", dpi=110)
    plt.close(fig)


def report(rows, out, machine_md):
    lines = ["| family | spheres | backend | pairs | contacts | ns/pair | ns/collision | AFU calls | peak RSS | bytes/sphere |",
             "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        pairs, contacts, ns = int(r["pairs"]), int(r["contacts"]), float(r["ns"])
        lines.append(f"| {r['family']} | {int(r['spheres']):,} | {r['backend']} | {pairs:,} | {contacts:,} | "
                     f"{ns / pairs if pairs else 0:.2f} | {ns / contacts if contacts else 0:.2f} | {r['calls']} | "
                     f"{int(r['peak_rss_bytes']) / 2**20:.0f} MiB | {int(r['bytes_per_sphere']):,} |")
    (out / "README.md").write_text(
        "# Scale: the narrow phase from 1,000 to 1,000,000 spheres\n\n"
        "`bench/scale/scale.py`: a pile poured into a box (pile_box's density, the base grown with the count) and "
        "the paper's diamond at larger hMax, 2 steps each. ODE's collider, simd (binary32) and simd64 (binary64) "
        "are timed on the very same pairs every step (wall clock, fastest of the repeats); the AFU rows are the "
        "Verilated default AFU's modelled time over the link named, on its own run of the scene (its first step's "
        "pairs are the same). Peak RSS is the whole `collide run` process (ODE's world, space and the batches): "
        "the memory a scene of that size needs, which `collide run` checks against the machine's available memory "
        "before it builds the world.\n\n" + "\n".join(lines) + "\n\n![ns per pair and per collision](scale.png)\n\n" +
        machine_md)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--collide", default=str(ROOT / "build/host/collide"))
    ap.add_argument("--sizes", default=",".join(map(str, PILE_SIZES)), help="pile sizes")
    ap.add_argument("--hmax", default=",".join(map(str, DIAMOND_HMAX)), help="diamond sizes")
    ap.add_argument("--rtl-max", type=int, default=16384, help="largest scene run on the AFU (co-simulation time)")
    ap.add_argument("--cpu-repeat", type=int, default=3)
    ap.add_argument("--out", default=str(ROOT / "bench/results/scale"))
    ap.add_argument("--report-only", action="store_true")
    a = ap.parse_args(argv)
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    if a.report_only:
        rows = list(csv.DictReader(open(out / "scale.csv", newline="")))
    else:
        start = machine()
        scenes = [("pile", int(n), pile_scene(int(n))) for n in a.sizes.split(",") if n] + \
                 [("diamond", diamond_count(int(h)), diamond_scene(int(h))) for h in a.hmax.split(",") if h]
        rows = []
        sdir = out / "scenes"
        sdir.mkdir(exist_ok=True)
        with tempfile.TemporaryDirectory() as tmp:
            for family, n, scene in scenes:
                path = sdir / f"{scene['name']}.json"
                path.write_text(json.dumps(scene, indent=1) + "\n")
                runs = [["--backend", "simd", "--cpu-repeat", str(a.cpu_repeat)]]
                if n <= a.rtl_max:
                    runs += [["--backend", "rtl", "--link", link] for link in ("qpi", "ideal")]
                for args in runs:
                    s, rss, wall = run(a.collide, path, args, Path(tmp))
                    for r in rows_of(family, n, s, rss, wall):
                        rows.append(r)
                        print(f"{family:8} {n:8} {r['backend']:10} {r['pairs']:8} pairs {r['contacts']:8} contacts "
                              f"{r['ns'] / max(1, r['pairs']):8.2f} ns/pair  {rss / 2**20:7.0f} MiB  {wall:6.1f} s",
                              flush=True)
        write_results(out, "scale.csv", rows, "bench/scale/scale.py", argv,
                      f"collide: `{a.collide}`, a Release build of this checkout (commit {commit()}) with the default "
                      "AFU Verilated", start)
    plot(rows, out)
    report(rows, out, (out / "MACHINE.md").read_text())
    return 0


if __name__ == "__main__":
    sys.exit(main())
