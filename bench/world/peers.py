"""Engines people use, as world-mode backends, against ours: `collide spheres` with ODE's
spaces (sap, hash, quadtree; dCollide in binary64), Bullet's broad phases (dbvt, sap) and
FCL's managers (tree, sap, hash), each feeding the binary32 kernel, beside `--backend simd`
and `--backend grid --threads 1`, on the same spheres in the same run. Every binary32 run's
contacts must be byte for byte simd's, and the three ODE runs' byte for byte each other's
(the script stops otherwise).

    tools/pyenv bench/world/peers.py [--collide build/host/collide] [--repeat 5]
                                     [--sizes 10000,65536] [--seed 1] [--slow-s 2]
                                     [--out bench/results/peers] [--note TEXT]

Clouds: grid.py's (world.py's `uniform`, radius 0.5; `clustered-mixed`, radii 0.2-0.8 and one
sphere in 500 of 1.6-4). Each config runs once; if that took under --slow-s seconds it runs
again with --repeat and the fastest of those is kept per phase (broad, narrow, finish; total
their sum). Bullet's and FCL's own narrow phases on the same candidates are timed apart
(`engine` in the summary) and not in the total. Writes OUT/peers.csv and OUT/README.md.
"""
import argparse
import csv
import os
import shlex
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import grid  # noqa: E402  (clustered_mixed, lscpu_model)
import world  # noqa: E402  (the uniform cloud, the CSV writer, collide spheres)

ROOT = Path(__file__).resolve().parents[2]

# (config name, backend, options, which contacts it must equal)
CONFIGS = [
    ("simd", "simd", [], "binary32"),
    ("grid, 1 thread", "grid", ["--threads", "1"], "binary32"),
    ("ode sap", "ode", ["--space", "sap"], "binary64"),
    ("ode hash", "ode", ["--space", "hash"], "binary64"),
    ("ode quadtree", "ode", ["--space", "quadtree"], "binary64"),
    ("bullet dbvt", "bullet", ["--space", "dbvt"], "binary32"),
    ("bullet sap", "bullet", ["--space", "sap"], "binary32"),
    ("fcl tree", "fcl", ["--space", "tree"], "binary32"),
    ("fcl sap", "fcl", ["--space", "sap"], "binary32"),
    ("fcl hash", "fcl", ["--space", "hash"], "binary32"),
]


def uptime():
    try:
        return subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()
    except OSError:
        return f"load average {os.getloadavg()}"


def report(rows, out, cmd, start, end, note):
    ms = lambda ns: f"{float(ns) / 1e6:.3f}"
    lines = ["# Engines people use as world-mode backends, against ours", "",
             "`collide spheres` on the same spheres in the same run (docs/host.md, \"collide spheres\"):",
             "ODE's spaces with dCollide (binary64: ODE's own contacts); Bullet's and FCL's broad phases",
             "feeding the binary32 kernel (broad = the engine's broad phase built from scratch, narrow =",
             "the kernel on its candidates); `simd` (our grid + the kernel) and `grid` (the tuned grid) on",
             "one thread. Fastest of N per phase; total = broad + narrow + finish; ratio = total / the",
             "fastest total of the table. Every binary32 run's contacts file is byte for byte simd's, and",
             "ODE's three spaces' files byte for byte each other's (SHA-256, checked in the run).",
             "\"engine narrow\": Bullet's / FCL's own narrow phase on the same candidates (not in the",
             "total), with the pairs where its decision differs from binary32 (only-engine / only-binary32).",
             "Every number: [peers.csv](peers.csv).", ""]
    for cloud in dict.fromkeys(r["cloud"] for r in rows):
        for n in dict.fromkeys(r["spheres"] for r in rows if r["cloud"] == cloud):
            rs = [r for r in rows if r["cloud"] == cloud and r["spheres"] == n]
            best = min(float(r["total_ns"]) for r in rs)
            b32 = next(r for r in rs if r["config"] == "simd")
            b64 = next(r for r in rs if r["config"] == "ode sap")
            lines += [f"## {cloud}, {n:,} spheres ({b32['contacts']:,} binary32 contacts, {b64['contacts']:,} binary64)", "",
                      "| config | N | broad (ms) | narrow (ms) | finish (ms) | total (ms) | ns / sphere | ratio | candidates | engine narrow (ms) | only-engine / only-binary32 |",
                      "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
            for r in rs:
                eng = f"{ms(r['engine_ns'])} | {r['only_engine']} / {r['only_exact']}" if r["engine_ns"] != "" else "| "
                lines.append(f"| {r['config']} | {r['repeat']} | {ms(r['broad_ns'])} | {ms(r['narrow_ns'])} | "
                             f"{ms(r['finish_ns'])} | {ms(r['total_ns'])} | {float(r['total_ns']) / n:,.0f} | "
                             f"{float(r['total_ns']) / best:.1f} | {r['candidates']:,} | {eng} |")
            lines.append("")
    lines += ["## How and where", "", f"Command: `{cmd}` (collide built Release: `cmake -S host -B build/host -G Ninja "
              "-DCMAKE_BUILD_TYPE=Release -DCOLLIDE_AFU_PRESET= -DCOLLIDE_AFU_DIR=`, Debian's ODE 0.16.2, "
              "Bullet 3.24 and FCL 0.7.0).", "",
              f"Machine: {start}.", "", f"End: {end}.", ""] + ([note, ""] if note else [])
    (out / "README.md").write_text("\n".join(lines) + "\n")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--collide", default=str(ROOT / "build/host/collide"))
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--sizes", default="10000,65536")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--slow-s", type=float, default=2.0, help="a config whose first run took longer runs only once")
    ap.add_argument("--out", default=str(ROOT / "bench/results/peers"))
    ap.add_argument("--note", default="", help="a paragraph on the machine's state for the README")
    a = ap.parse_args(argv)
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    runner = "tools/pyenv" if "bench-venv" in sys.executable else "python3"  # the script needs only the stdlib
    cmd = f"{runner} bench/world/peers.py " + shlex.join(argv if argv is not None else sys.argv[1:])
    start = (f"{grid.lscpu_model()} ({os.cpu_count()} CPUs), niceness {os.nice(0)}; at start `uptime`: {uptime()}")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        for cloud in ["uniform", "clustered-mixed"]:
            for n in map(int, a.sizes.split(",")):
                path = work / "spheres.csv"
                world.write_cloud(path, world.cloud("uniform", n, a.seed) if cloud == "uniform" else grid.clustered_mixed(n, a.seed))
                want = {}
                for config, backend, opts, kind in CONFIGS:
                    s = world.run(a.collide, path, backend, None, 1, work, opts)
                    repeat = 1
                    if s["wall_s"] < a.slow_s and a.repeat > 1:
                        s = world.run(a.collide, path, backend, None, a.repeat, work, opts)
                        repeat = a.repeat
                    want.setdefault(kind, s["sha256"])
                    if s["sha256"] != want[kind]:
                        sys.exit(f"peers: {cloud} {n}: {config} wrote other contacts than the first {kind} run")
                    e = s.get("engine", {})
                    row = {"cloud": cloud, "spheres": n, "config": config, "repeat": repeat, "contacts": s["contacts"],
                           "candidates": s["candidates"], "broad_ns": s["broad_ns"], "narrow_ns": s["narrow_ns"],
                           "finish_ns": s["finish_ns"], "total_ns": s["broad_ns"] + s["narrow_ns"] + s["finish_ns"],
                           "engine_ns": e.get("narrow_ns", ""), "engine_contacts": e.get("contacts", ""),
                           "only_engine": e.get("only_engine", ""), "only_exact": e.get("only_exact", ""),
                           "broad_phase": s["broad_phase"], "format": s["format"], "sha256": s["sha256"]}
                    rows.append(row)
                    print(f"{cloud:15} {n:6} {config:15} x{repeat} total {row['total_ns'] / 1e6:9.3f} ms  (broad "
                          f"{s['broad_ns'] / 1e6:.3f}, narrow {s['narrow_ns'] / 1e6:.3f}, finish {s['finish_ns'] / 1e6:.3f})",
                          flush=True)
    with open(out / "peers.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    report(rows, out, cmd.strip(), start, f"`uptime`: {uptime()}", a.note)
    return 0


if __name__ == "__main__":
    sys.exit(main())
