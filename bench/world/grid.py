"""The tuned grid against today's simd grid: `collide spheres --backend simd` (grid + binary32
kernel) and `--backend grid` (the tuned grid, docs/host.md "The tuned grid") at 1 and 2
threads, on the same spheres in the same run; every run's contacts must be byte for byte the
simd backend's (the script stops otherwise).

    tools/pyenv bench/world/grid.py [--collide build/host/collide] [--repeat 20]
                                    [--sizes 10000,65536] [--seed 1] [--threads 1,2]
                                    [--out bench/results/grid] [--note TEXT]

Clouds: world.py's `uniform` (radius 0.5, about one contact a sphere) at each size, and
`clustered-mixed`: world.py's clustered layout (Gaussian clusters of about 200) with radii
log-uniform in [0.2, 0.8] and one sphere in 500 of radius log-uniform in [1.6, 4] (the tuned
grid's large spheres), seeded. Times are the fastest of --repeat per phase (broad, narrow,
finish), total their sum. Writes OUT/grid.csv and OUT/README.md (tables, the command, the
machine).
"""
import argparse
import csv
import os
import random
import shlex
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import world  # noqa: E402  (the uniform cloud, the CSV writer, the machine line)

ROOT = Path(__file__).resolve().parents[2]


def clustered_mixed(n, seed):
    """world.py's clustered layout with mixed radii and a few large spheres (binary32 values)."""
    rng = random.Random(f"clustered-mixed-{n}-{seed}")
    side = (n / world.DENSITY) ** (1 / 3)
    clusters = max(1, n // 200)
    sigma = 0.25 * side / clusters ** (1 / 3)
    centres = [[rng.uniform(0, side) for _ in range(3)] for _ in range(clusters)]
    out = []
    for k in range(n):
        c = centres[k % clusters]
        r = 1.6 * 2.5 ** rng.random() if rng.random() < 1 / 500 else 0.2 * 4 ** rng.random()
        out.append([world.f32(rng.gauss(c[a], sigma)) for a in range(3)] + [world.f32(r)])
    return out


def run(collide, path, backend, threads, repeat, work):
    return world.run(collide, path, backend, None, repeat, work, ("--threads", str(threads)) if threads else ())


def lscpu_model():
    try:
        text = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
    except OSError:
        return "?"
    return next((l.split(":", 1)[1].strip() for l in text.splitlines() if l.startswith("Model name")), "?")


def report(rows, out, cmd, start, end, note):
    ms = lambda ns: f"{float(ns) / 1e6:.3f}"
    lines = ["# The tuned grid against the simd grid (world mode on the CPU)", "",
             "`collide spheres --backend simd` (today's grid + the binary32 kernel) and `--backend grid`",
             "(the tuned grid, docs/host.md \"The tuned grid\") on the same spheres in the same run,",
             "fastest of N per phase; total = broad + narrow + finish. Every run's contacts file is byte",
             "for byte the simd backend's (checked by SHA-256 in the run). Every number: [grid.csv](grid.csv).", ""]
    for cloud in dict.fromkeys(r["cloud"] for r in rows):
        for n in dict.fromkeys(r["spheres"] for r in rows if r["cloud"] == cloud):
            rs = [r for r in rows if r["cloud"] == cloud and r["spheres"] == n]
            base = next(r for r in rs if r["config"] == "simd")
            one = next((r for r in rs if r["config"] == "grid, 1 thread"), None)
            lines += [f"## {cloud}, {n:,} spheres ({base['contacts']:,} contacts)", "",
                      "| config | broad (ms) | narrow (ms) | finish (ms) | total (ms) | ns / sphere | speed-up vs simd | candidates |",
                      "|---|---:|---:|---:|---:|---:|---:|---:|"]
            for r in rs:
                lines.append(f"| {r['config']} | {ms(r['broad_ns'])} | {ms(r['narrow_ns'])} | {ms(r['finish_ns'])} | "
                             f"{ms(r['total_ns'])} | {float(r['total_ns']) / n:,.0f} | "
                             f"{float(base['total_ns']) / float(r['total_ns']):.1f}x | {r['candidates']:,} |")
            two = [r for r in rs if r["config"].startswith("grid") and r is not one]
            if one:
                for r in two:
                    lines.append(f"\nThread scaling, {r['config']} against 1 thread: "
                                 f"{float(one['total_ns']) / float(r['total_ns']):.2f}x.")
            lines.append("")
    lines += ["## How and where", "", f"Command: `{cmd}` (collide built Release: `cmake -S host -B build/host -G Ninja "
              "-DCMAKE_BUILD_TYPE=Release -DCOLLIDE_AFU_PRESET= -DCOLLIDE_AFU_DIR=`).", "",
              f"Machine: {start}. End: {end}.", ""] + ([note, ""] if note else [])
    (out / "README.md").write_text("\n".join(lines) + "\n")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--collide", default=str(ROOT / "build/host/collide"))
    ap.add_argument("--repeat", type=int, default=20)
    ap.add_argument("--sizes", default="10000,65536")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--out", default=str(ROOT / "bench/results/grid"))
    ap.add_argument("--note", default="", help="a paragraph on the machine's state for the README")
    a = ap.parse_args(argv)
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    cmd = "tools/pyenv bench/world/grid.py " + shlex.join(argv if argv is not None else sys.argv[1:])
    start = (f"{lscpu_model()} ({os.cpu_count()} CPUs), load average {os.getloadavg()[0]:.2f} at start, "
             f"niceness {os.nice(0)}")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        for cloud in ["uniform", "clustered-mixed"]:
            for n in map(int, a.sizes.split(",")):
                path = work / "spheres.csv"
                world.write_cloud(path, world.cloud("uniform", n, a.seed) if cloud == "uniform" else clustered_mixed(n, a.seed))
                configs = [("simd", None)] + [("grid", int(t)) for t in a.threads.split(",")]
                want = None
                for backend, threads in configs:
                    s = run(a.collide, path, backend, threads, a.repeat, work)
                    want = want or s["sha256"]
                    if s["sha256"] != want:
                        sys.exit(f"grid: {cloud} {n}: --backend {backend} --threads {threads} wrote other contacts than simd")
                    config = "simd" if backend == "simd" else f"grid, {threads} thread{'s' if threads > 1 else ''}"
                    row = {"cloud": cloud, "spheres": n, "config": config, "contacts": s["contacts"],
                           "candidates": s["candidates"], "broad_ns": s["broad_ns"], "narrow_ns": s["narrow_ns"],
                           "finish_ns": s["finish_ns"], "total_ns": s["broad_ns"] + s["narrow_ns"] + s["finish_ns"],
                           "sha256": s["sha256"], "repeat": a.repeat}
                    rows.append(row)
                    print(f"{cloud:15} {n:6} {config:16} total {row['total_ns'] / 1e6:8.3f} ms  (broad {s['broad_ns'] / 1e6:.3f}, "
                          f"narrow {s['narrow_ns'] / 1e6:.3f}, finish {s['finish_ns'] / 1e6:.3f})", flush=True)
    with open(out / "grid.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    report(rows, out, cmd.strip(), start, f"load average {os.getloadavg()[0]:.2f}", a.note)
    return 0


if __name__ == "__main__":
    sys.exit(main())
