"""Engines people use, as world-mode backends, against ours: `collide spheres` with ODE's
spaces (sap, hash, quadtree; dCollide in binary64), Bullet's broad phases (dbvt, sap) and
FCL's managers (tree, sap, hash), each feeding the binary32 kernel, beside `--backend simd`
and `--backend grid --threads 1`, and the Warp backend (bench/world/warp_world.py) on Warp's
CPU device and on cuda:0, on the same spheres in the same run. Every binary32 run's
contacts must be byte for byte simd's, and the three ODE runs' byte for byte each other's
(the script stops otherwise). Where Warp sees no CUDA device the cuda:0 row says "not
measured".

    tools/pyenv bench/world/peers.py [--collide build/host/collide] [--repeat 5]
                                     [--sizes 10000,65536] [--seed 1] [--slow-s 2]
                                     [--clouds uniform,clustered-mixed] [--config NAME ...]
                                     [--out bench/results/peers] [--note TEXT]

Clouds: grid.py's (world.py's `uniform`, radius 0.5; `clustered-mixed`, radii 0.2-0.8 and one
sphere in 500 of 1.6-4). Each config runs once; if that took under --slow-s seconds it runs
again with --repeat and the fastest of those is kept per phase (broad, narrow, finish; total
their sum). Bullet's and FCL's own narrow phases on the same candidates are timed apart
(`engine` in the summary) and not in the total. The Warp rows' copies to and from the
device (h2d, d2h) are timed apart and not in the total either. Writes OUT/peers.csv and
OUT/README.md.
"""
import argparse
import csv
import hashlib
import json
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
    ("grid, all threads", "grid", [], "binary32"),
    ("ode sap", "ode", ["--space", "sap"], "binary64"),
    ("ode hash", "ode", ["--space", "hash"], "binary64"),
    ("ode quadtree", "ode", ["--space", "quadtree"], "binary64"),
    ("bullet dbvt", "bullet", ["--space", "dbvt"], "binary32"),
    ("bullet sap", "bullet", ["--space", "sap"], "binary32"),
    ("fcl tree", "fcl", ["--space", "tree"], "binary32"),
    ("fcl sap", "fcl", ["--space", "sap"], "binary32"),
    ("fcl hash", "fcl", ["--space", "hash"], "binary32"),
    # bench/world/warp_world.py: Warp kernels on a Warp device (backend "warp", the option its device)
    ("warp cpu", "warp", ["cpu"], "binary32"),
    ("warp cuda:0", "warp", ["cuda:0"], "binary32"),
]
NOT_MEASURED = "not measured"
NOT_RUN = "not run"
# Broad phases that grow much faster than the spheres here (65,536 uniform spheres: 0.9 s to
# 67 s, where the tuned grid takes 4 ms): above --slow-cap spheres they are not run, and
# their rows say so.
SLOW = {"ode hash", "ode quadtree", "bullet sap", "fcl sap", "fcl hash"}
ROW_KEYS = ["cloud", "spheres", "config", "repeat", "contacts", "candidates", "broad_ns", "narrow_ns", "finish_ns",
            "total_ns", "engine_ns", "engine_contacts", "only_engine", "only_exact", "broad_phase", "format", "sha256",
            "h2d_ns", "d2h_ns", "device"]


def cuda_devices():
    """How many CUDA devices Warp sees (in the pinned venv, where warp-lang is)."""
    p = subprocess.run([str(ROOT / "tools/pyenv"), "-c", "import warp as wp; wp.config.log_level = wp.LOG_ERROR; "
                        "print(wp.get_cuda_device_count())"], capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"peers: could not ask Warp for CUDA devices:\n{p.stderr}")
    return int(p.stdout.strip().splitlines()[-1])


def run_warp(path, device, repeat, work):
    """warp_world.py once (fastest of `repeat` inside), as world.run runs collide: its summary,
    with the contacts file's SHA-256 and the call's wall time."""
    summary, contacts = work / "summary.json", work / "contacts.csv"
    cmd = [str(ROOT / "tools/pyenv"), str(ROOT / "bench/world/warp_world.py"), "--spheres", str(path), "--out",
           str(contacts), "--device", device, "--repeat", str(repeat), "--summary", str(summary)]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"peers: {' '.join(cmd)} failed ({p.returncode}):\n{p.stderr}")
    s = json.loads(summary.read_text())
    s["sha256"] = hashlib.sha256(contacts.read_bytes()).hexdigest()
    # The collision's own time (kernels and copies), not Python's start, Warp's and the CSV's
    s["wall_s"] = (s["kernels_ns"] + s["copies_ns"]) * s["repeat"] / 1e9
    return s


def skipped(rows, cloud, n, config, what, why, **fields):
    """A config this run did not time: its row says `what` in place of every time, and why."""
    rows.append({**dict.fromkeys(ROW_KEYS, ""), "cloud": cloud, "spheres": n, "config": config,
                 **dict.fromkeys(("broad_ns", "narrow_ns", "finish_ns", "total_ns"), what), **fields})
    print(f"{cloud:15} {n:7} {config:17} {what} ({why})", flush=True)


def uptime():
    try:
        return subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()
    except OSError:
        return f"load average {os.getloadavg()}"


def report(rows, out, cmd, start, end, note):
    ms = lambda ns: f"{float(ns) / 1e6:.3f}" if ns not in ("", NOT_MEASURED) else ("-" if ns == "" else ns)
    measured = lambda r: r["total_ns"] not in (NOT_MEASURED, NOT_RUN)
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
             "`warp cpu` / `warp cuda:0`: bench/world/warp_world.py (Warp's hash grid + the binary32 test as",
             "Warp kernels, docs/host-world.md \"The Warp backend\"); broad, narrow and finish are its kernels,",
             "\"copies\" its host-to-device and device-to-host copies (not in the total); \"not measured\":",
             "Warp saw no such device in this run; \"not run\": a broad phase that grows much faster than the",
             "spheres, above --slow-cap. Every number: [peers.csv](peers.csv); total time against spheres,",
             "log-log: [peers.png](peers.png).", ""]
    for cloud in dict.fromkeys(r["cloud"] for r in rows):
        for n in dict.fromkeys(r["spheres"] for r in rows if r["cloud"] == cloud):
            rs = [r for r in rows if r["cloud"] == cloud and r["spheres"] == n]
            best = min(float(r["total_ns"]) for r in rs if measured(r))
            b64 = [r for r in rs if measured(r) and r["format"] == "binary64"][:1]
            counts = [f"{next(r for r in rs if measured(r) and r['format'] == 'binary32')['contacts']:,} binary32 contacts"]
            counts += [f"{b64[0]['contacts']:,} binary64"] if b64 else []
            lines += [f"## {cloud}, {n:,} spheres ({', '.join(counts)})", "",
                      "| config | N | broad (ms) | narrow (ms) | finish (ms) | total (ms) | ns / sphere | ratio | candidates | copies (ms) | engine narrow (ms) | only-engine / only-binary32 |",
                      "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
            for r in rs:
                eng = f"{ms(r['engine_ns'])} | {r['only_engine']} / {r['only_exact']}" if r["engine_ns"] != "" else "| "
                if not measured(r):
                    why = r["total_ns"] + (f" ({r['device']})" if r["total_ns"] == NOT_RUN else "")
                    lines.append(f"| {r['config']} | - | {why} | | | | | | | | | |")
                    continue
                copies = ms(float(r["h2d_ns"]) + float(r["d2h_ns"])) if r["h2d_ns"] != "" else ""
                lines.append(f"| {r['config']} | {r['repeat']} | {ms(r['broad_ns'])} | {ms(r['narrow_ns'])} | "
                             f"{ms(r['finish_ns'])} | {ms(r['total_ns'])} | {float(r['total_ns']) / n:,.0f} | "
                             f"{float(r['total_ns']) / best:.1f} | {r['candidates']:,} | {copies} | {eng} |")
            lines.append("")
    lines += ["## How and where", "", f"Command: `{cmd}` (collide built Release: `cmake -S host -B build/host -G Ninja "
              "-DCMAKE_BUILD_TYPE=Release -DCOLLIDE_AFU_PRESET= -DCOLLIDE_AFU_DIR=`, Debian's ODE 0.16.2, "
              "Bullet 3.24 and FCL 0.7.0; Warp as pinned in bench/requirements.txt).", "",
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
    ap.add_argument("--clouds", default="uniform,clustered-mixed")
    ap.add_argument("--config", action="append", default=[], metavar="NAME",
                    help="run only this config (repeatable, e.g. --config simd --config 'warp cpu'); default all")
    ap.add_argument("--slow-cap", type=int, default=70000, metavar="N",
                    help=f"run {', '.join(sorted(SLOW))} only on worlds of at most N spheres")
    ap.add_argument("--note", default="", help="a paragraph on the machine's state for the README")
    ap.add_argument("--replot", action="store_true", help="only draw OUT/peers.png again from OUT/peers.csv")
    a = ap.parse_args(argv)
    if a.replot:
        try:
            plot(list(csv.DictReader(open(Path(a.out) / "peers.csv", newline=""))), Path(a.out) / "peers.png")
        except OSError as e:
            ap.error(f"--replot: cannot read {Path(a.out) / 'peers.csv'}: {e.strerror}")
        return 0
    configs = CONFIGS
    if a.config:
        unknown = [c for c in a.config if c not in {c[0] for c in CONFIGS}]
        if unknown:
            ap.error(f"--config: unknown {', '.join(unknown)} (expected one of: {'; '.join(c[0] for c in CONFIGS)})")
        configs = [c for c in CONFIGS if c[0] in a.config]
    clouds = [c.strip() for c in a.clouds.split(",")]
    if any(c not in ("uniform", "clustered-mixed") for c in clouds):
        ap.error(f"--clouds {a.clouds}: expected uniform and/or clustered-mixed")
    cuda = cuda_devices() if any(c[1] == "warp" and c[2][0].startswith("cuda") for c in configs) else 0
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    runner = "tools/pyenv" if "bench-venv" in sys.executable else "python3"  # the script needs only the stdlib
    cmd = f"{runner} bench/world/peers.py " + shlex.join(argv if argv is not None else sys.argv[1:])
    start = (f"{grid.lscpu_model()} ({os.cpu_count()} CPUs), niceness {os.nice(0)}; at start `uptime`: {uptime()}")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        for cloud in clouds:
            for n in map(int, a.sizes.split(",")):
                path = work / "spheres.csv"
                world.write_cloud(path, world.cloud("uniform", n, a.seed) if cloud == "uniform" else grid.clustered_mixed(n, a.seed))
                want = {}
                for config, backend, opts, kind in configs:
                    if config in SLOW and n > a.slow_cap:
                        skipped(rows, cloud, n, config, NOT_RUN, f"above --slow-cap {a.slow_cap}",
                                device=f"above --slow-cap {a.slow_cap}")
                        continue
                    if backend == "warp" and opts[0].startswith("cuda") and cuda == 0:
                        skipped(rows, cloud, n, config, NOT_MEASURED, "no CUDA device", h2d_ns=NOT_MEASURED,
                                d2h_ns=NOT_MEASURED, broad_phase="warp HashGrid", format="binary32",
                                device=f"{opts[0]} (Warp saw no CUDA device)")
                        continue
                    once = (lambda rep: run_warp(path, opts[0], rep, work)) if backend == "warp" else \
                        (lambda rep: world.run(a.collide, path, backend, None, rep, work, opts))
                    s = once(1)
                    repeat = 1
                    if s["wall_s"] < a.slow_s and a.repeat > 1:
                        s = once(a.repeat)
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
                           "broad_phase": s["broad_phase"], "format": s["format"], "sha256": s["sha256"],
                           "h2d_ns": s.get("h2d_ns", ""), "d2h_ns": s.get("d2h_ns", ""),
                           "device": s.get("device_name", "CPU") if backend == "warp" else "CPU"}
                    rows.append(row)
                    print(f"{cloud:15} {n:7} {config:17} x{repeat} total {row['total_ns'] / 1e6:9.3f} ms  (broad "
                          f"{s['broad_ns'] / 1e6:.3f}, narrow {s['narrow_ns'] / 1e6:.3f}, finish {s['finish_ns'] / 1e6:.3f})",
                          flush=True)
    with open(out / "peers.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=ROW_KEYS)
        w.writeheader()
        w.writerows(rows)
    report(rows, out, cmd.strip(), start, f"`uptime`: {uptime()}", a.note)
    plot(rows, out / "peers.png")
    return 0


def plot(rows, path):
    """Total time against spheres, log-log, a panel per cloud and a line per config."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    clouds = list(dict.fromkeys(r["cloud"] for r in rows))
    fig, axes = plt.subplots(1, len(clouds), figsize=(6.5 * len(clouds), 5), squeeze=False, sharey=True)
    for ax, cloud in zip(axes[0], clouds):
        for k, config in enumerate(dict.fromkeys(r["config"] for r in rows)):
            pts = sorted((int(r["spheres"]), float(r["total_ns"]) / 1e6) for r in rows
                         if r["cloud"] == cloud and r["config"] == config and r["total_ns"] not in (NOT_MEASURED, NOT_RUN))
            if pts:
                ax.plot(*zip(*pts), marker="osD^v<>"[k % 7], color=plt.cm.tab20(k % 20), label=config)
        ax.set(xscale="log", yscale="log", xlabel="spheres", title=cloud)
        ax.grid(True, which="both", alpha=0.3)
    axes[0][0].set_ylabel("total time, ms (fastest of N)")
    axes[0][-1].legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
