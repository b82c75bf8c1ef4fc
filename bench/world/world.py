"""World-mode benchmark: `collide spheres` on sphere clouds from 670 to 65,536 spheres, each
with ODE's hash space, ODE's sweep-and-prune space (both + dCollide, binary64) and the simd
backend (our grid + the binary32 kernel); broad and narrow phase timed apart, fastest of N.

    tools/pyenv bench/world/world.py [--collide build/host/collide] [--repeat 5]
                                     [--sizes 670,2000,...] [--out bench/results/world]
                                     [--dump-clouds DIR]

Writes OUT/world.csv (one row per cloud, size and backend), OUT/world.png (log-log: time of
broad + narrow phase against spheres, one panel per cloud) and OUT/MACHINE.md (the command
and the machine). Clouds (seeded, every value a binary32 value, so both formats see the same
spheres):
  uniform    radius 0.5 in a cube sized for about one contact per sphere;
  clustered  the same spheres in Gaussian clusters of about 200 (about 4x denser inside);
  mixed      radii log-uniform in [0.2, 0.8], the uniform cube.
"""
import argparse
import csv
import hashlib
import json
import math
import os
import platform
import random
import shlex
import struct
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SIZES = [670, 2000, 5000, 10000, 20000, 40000, 65536]
BACKENDS = [("ode", "hash"), ("ode", "sap"), ("simd", None)]
CLOUDS = ["uniform", "clustered", "mixed"]
# Uniform spheres of radius r at density rho touch about rho * (4/3) pi (2r)^3 / 2 others
# each (pairs counted once): one contact a sphere at r = 0.5 wants rho = 3 / (2 pi).
DENSITY = 3 / (2 * math.pi)


def f32(v):
    """v rounded to binary32 (exact in binary64 too)."""
    return struct.unpack("f", struct.pack("f", v))[0]


def diamond_hmax(n):
    """The hMax of the largest of the paper's diamonds with at most n spheres."""
    h = 1
    while (h + 1) * (2 * (h + 1) ** 2 + 1) // 3 <= n:
        h += 1
    return h


def diamond(h, radius=0.1):
    """The paper's diamond at step 0 (host/scene/diamond.cpp, dSph = 0): layers of n x n
    spheres whose in-layer neighbours touch, n = 1 .. hMax .. 1; binary64 like the host,
    then rounded once to binary32."""
    db = math.sqrt(2 * (2 * radius) ** 2) - 2 * radius
    a = db / 2 + radius
    out = []
    for step in range(2 * h - 1):
        n = step + 1 if step < h else 2 * h - 1 - step
        z = step * db + 2 * radius + 4
        out += [[f32((u - v) * a), f32((u + v - (n - 1)) * a), f32(z), f32(radius)] for u in range(n) for v in range(n)]
    return out


def cloud(kind, n, seed):
    """n spheres (x, y, z, r) of the named cloud ("diamond": the largest diamond of at most n,
    no randomness)."""
    if kind == "diamond":
        return diamond(diamond_hmax(n))
    rng = random.Random(f"{kind}-{n}-{seed}")
    side = (n / DENSITY) ** (1 / 3)
    out = []
    if kind == "clustered":
        clusters = max(1, n // 200)
        sigma = 0.25 * side / clusters ** (1 / 3)  # about 4x the mean density inside a cluster
        centres = [[rng.uniform(0, side) for _ in range(3)] for _ in range(clusters)]
        for k in range(n):
            c = centres[k % clusters]
            out.append([f32(rng.gauss(c[a], sigma)) for a in range(3)] + [f32(0.5)])
    else:
        for _ in range(n):
            r = 0.2 * 4 ** rng.random() if kind == "mixed" else 0.5
            out.append([f32(rng.uniform(0, side)) for _ in range(3)] + [f32(r)])
    return out


def write_cloud(path, spheres):
    with open(path, "w") as f:
        f.write("x,y,z,r\n")
        for s in spheres:
            f.write(",".join(v.hex() for v in s) + "\n")


def run(collide, path, backend, space, repeat, work, extra=()):
    """`collide spheres` once (fastest of `repeat` inside), its contacts in work/contacts.csv:
    its summary, with the contacts file's SHA-256 and the call's wall time (`sha256`, `wall_s`)."""
    summary, contacts = work / "summary.json", work / "contacts.csv"
    cmd = [str(collide), "spheres", "--backend", backend, "--in", str(path), "--out", str(contacts),
           "--repeat", str(repeat), "--summary", str(summary), *extra]
    if space:
        cmd += ["--space", space]
    t0 = time.monotonic()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.monotonic() - t0
    if p.returncode != 0:
        sys.exit(f"world: {' '.join(cmd)} failed ({p.returncode}):\n{p.stderr}")
    s = json.loads(summary.read_text())
    s["sha256"] = hashlib.sha256(contacts.read_bytes()).hexdigest()
    s["wall_s"] = wall
    return s


def plot(rows, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(CLOUDS), figsize=(5 * len(CLOUDS), 4.2), sharey=True)
    for ax, kind in zip(axes, CLOUDS):
        for backend, space in BACKENDS:
            name = f"{backend} {space}" if space else f"{backend} grid"
            rs = sorted((r for r in rows if r["cloud"] == kind and r["config"] == name), key=lambda r: r["spheres"])
            n = [r["spheres"] for r in rs]
            ax.plot(n, [(r["broad_ns"] + r["narrow_ns"]) / 1e3 for r in rs], "o-", label=f"{name}: broad + narrow")
            ax.plot(n, [r["broad_ns"] / 1e3 for r in rs], ":", color=ax.lines[-1].get_color(), label=f"{name}: broad")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(kind)
        ax.set_xlabel("spheres")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("time (us, fastest of N, measured)")
    axes[-1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=120)


def report(rows, out, machine_md):
    """README.md: the table (time of broad + narrow phase, ns a sphere) and what it shows."""
    num = lambda r, k: float(r[k])
    sizes = sorted({int(r["spheres"]) for r in rows})
    lines = ["# World mode on the CPU: broad + narrow phase against sphere count", "",
             "`collide spheres` on seeded clouds (bench/world/world.py): ODE 0.16's hash and sweep-and-prune",
             "spaces with dCollide (binary64), and the simd backend (our grid, docs/host.md \"The grid broad",
             "phase\", + the binary32 kernel). Wall clock, fastest of N per phase, on a shared 2-core machine",
             "(other jobs ran: single points move by up to 2x; see MACHINE.md). Plot: [world.png](world.png);",
             "every number: [world.csv](world.csv).", ""]
    for kind in CLOUDS:
        lines += [f"## {kind}", "", "| spheres | contacts | " + " | ".join(
            f"{c}: broad + narrow (us), ns/sphere" for c in ("ode hash", "ode sap", "simd grid")) + " | simd candidates / contact |",
            "|---:|---:|---:|---:|---:|---:|"]
        for n in sizes:
            rs = {r["config"]: r for r in rows if r["cloud"] == kind and int(r["spheres"]) == n}
            if len(rs) < 3:
                continue
            cells = [f"{(num(rs[c], 'broad_ns') + num(rs[c], 'narrow_ns')) / 1e3:,.0f}, {num(rs[c], 'ns_per_sphere'):,.0f}"
                     for c in ("ode hash", "ode sap", "simd grid")]
            g = rs["simd grid"]
            lines.append(f"| {n:,} | {int(g['contacts']):,} | " + " | ".join(cells) +
                         f" | {num(g, 'candidates') / max(num(g, 'contacts'), 1):.2f} |")
        lines.append("")
    big = max(sizes)
    total = {(r["cloud"], r["config"], int(r["spheres"])): num(r, "broad_ns") + num(r, "narrow_ns") for r in rows}
    ratio = lambda kind, a, b, n: total[(kind, a, n)] / total[(kind, b, n)]
    lines += ["## What it shows", ""]
    for kind in CLOUDS:
        lines.append(f"- {kind}: at {min(sizes):,} spheres ODE sap / simd grid = {ratio(kind, 'ode sap', 'simd grid', min(sizes)):.2f}x, "
                     f"at {big:,} {ratio(kind, 'ode sap', 'simd grid', big):.1f}x; ODE hash / sap at {big:,}: "
                     f"{ratio(kind, 'ode hash', 'ode sap', big):.1f}x.")
    share = [num(r, "narrow_ns") / (num(r, "broad_ns") + num(r, "narrow_ns")) for r in rows]
    lines += ["- The broad phase takes most of the time on every backend (the dotted lines of the plot): the",
              f"  narrow phase is {100 * min(share):.1f}-{100 * max(share):.1f} % of broad + narrow (the most in the",
              "  clustered cloud, which has the most contacts a sphere).",
              "- ODE's spaces grow faster than linearly (sweep-and-prune sorts along one axis, so each sphere",
              "  meets every sphere in its slab), the grid about linearly in spheres plus candidates.", "", machine_md]
    (out / "README.md").write_text("\n".join(lines) + "\n")


def machine():
    model = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
    load = os.getloadavg()
    return f"{os.cpu_count()} CPUs ({model}), {platform.system()} {platform.release()}, load average {load[0]:.2f} at start"


def write_results(out, csv_name, rows, script, argv, build, start):
    """OUT/<csv_name> (the rows) and OUT/MACHINE.md (the command, how collide was built, the
    machine at start and end); returns MACHINE.md's text."""
    with open(out / csv_name, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    cmd = f"tools/pyenv {script} " + shlex.join(argv if argv is not None else sys.argv[1:])
    machine_md = (f"## How and where\n\nCommand: `{cmd.strip()}` ({build}).\n\n"
                  f"Machine: {start}; end: load average {os.getloadavg()[0]:.2f}.\n")
    (out / "MACHINE.md").write_text(machine_md)
    return machine_md


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--collide", default=str(ROOT / "build/host/collide"))
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--sizes", default=",".join(map(str, SIZES)))
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out", default=str(ROOT / "bench/results/world"))
    ap.add_argument("--report-only", action="store_true", help="redraw the plot and README from OUT/world.csv")
    ap.add_argument("--dump-clouds", metavar="DIR",
                    help="only write each cloud to DIR/<cloud>-<spheres>.csv (for the RTL cycle report) and stop")
    a = ap.parse_args(argv)
    if a.dump_clouds:
        d = Path(a.dump_clouds)
        d.mkdir(parents=True, exist_ok=True)
        for kind in CLOUDS:
            for n in map(int, a.sizes.split(",")):
                write_cloud(d / f"{kind}-{n}.csv", cloud(kind, n, a.seed))
        return 0
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    if a.report_only:
        rows = list(csv.DictReader(open(out / "world.csv", newline="")))
        for r in rows:
            for k in ("spheres", "broad_ns", "narrow_ns"):
                r[k] = float(r[k])
        plot(rows, out / "world.png")
        report(rows, out, (out / "MACHINE.md").read_text())
        return 0
    start = machine()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        for kind in CLOUDS:
            for n in map(int, a.sizes.split(",")):
                path = work / "spheres.csv"
                write_cloud(path, cloud(kind, n, a.seed))
                for backend, space in BACKENDS:
                    s = run(a.collide, path, backend, space, a.repeat, work)
                    row = {"cloud": kind, "spheres": n, "config": f"{backend} {space}" if space else f"{backend} grid",
                           "format": s["format"], "candidates": s["candidates"], "contacts": s["contacts"],
                           "broad_ns": s["broad_ns"], "narrow_ns": s["narrow_ns"], "finish_ns": s["finish_ns"],
                           "ns_per_sphere": (s["broad_ns"] + s["narrow_ns"]) / n,
                           "cell_exp": s.get("grid", {}).get("cell_exp", ""),
                           "cell_pairs": s.get("grid", {}).get("cell_pairs", ""), "repeat": a.repeat}
                    rows.append(row)
                    print(f"{kind:9} {n:6} {row['config']:9} {row['candidates']:8} candidates {row['contacts']:6} contacts"
                          f"  broad {s['broad_ns'] / 1e3:10.1f} us  narrow {s['narrow_ns'] / 1e3:9.1f} us", flush=True)
    machine_md = write_results(out, "world.csv", rows, "bench/world/world.py", argv,
                               "collide built Release, `cmake -S host -B build/host -G Ninja -DCMAKE_BUILD_TYPE=Release`",
                               start)
    plot(rows, out / "world.png")
    report(rows, out, machine_md)
    return 0


if __name__ == "__main__":
    sys.exit(main())
