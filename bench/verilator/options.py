"""Verilator build options against co-simulation speed, on the default AFU (16 fp32 SCPUs), and
the cosim preset beside it (the same AFU with its SCPUs as the C++ model behind their pipelines).

For each option set it configures a fresh host build (build/verilator-opts/<id>, the AFU of
generated/default Verilated into `collide`, no tests, no ccache, so every build compiles
everything), times the build, then runs the paper's diamond over the HARP v1 link with every
cycle evaluated (`--no-skip`, so the model's speed is what is timed) and reports wall time per
simulated cycle (the rtl backend's wall time over the cycles it stepped: fastest and median of
--runs, since a shared machine moves single runs by 1.5x).

    tools/pyenv bench/verilator/options.py [--sets O1,O2,O1-t2,O2-t2] [--steps 10] [--runs 3]
                                           [--out bench/results/verilator] [--no-build]

--no-build reuses the builds in build/verilator-opts and the build times of OUT/verilator.csv.

Writes OUT/verilator.csv, OUT/README.md and OUT/MACHINE.md. Two builds never run at once.
"""
import argparse
import csv
import json
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
from sweeplib import machine  # noqa: E402

# id -> (what it is, CMake cache settings). O1 with one thread is the project's default.
SETS = {
    "O1": ("-O1 per-cycle code, 1 thread (the default)", {"COLLIDE_VERILATOR_OPT_FAST": "-O1"}),
    "O2": ("-O2 per-cycle code, 1 thread", {"COLLIDE_VERILATOR_OPT_FAST": "-O2"}),
    "O3": ("-O3 per-cycle code, 1 thread", {"COLLIDE_VERILATOR_OPT_FAST": "-O3"}),
    "O1-t2": ("-O1, Verilator --threads 2", {"COLLIDE_VERILATOR_OPT_FAST": "-O1", "COLLIDE_VERILATOR_THREADS": "2"}),
    "O2-t2": ("-O2, Verilator --threads 2", {"COLLIDE_VERILATOR_OPT_FAST": "-O2", "COLLIDE_VERILATOR_THREADS": "2"}),
    "cosim": ("the cosim preset: the default AFU, its SCPUs the C++ model behind their pipelines (-O1, 1 thread)",
              {"COLLIDE_AFU_PRESET": "cosim"}),
}
SCENE = ROOT / "scenes" / "diamond.json"


def build(set_id: str, work: Path) -> float:
    d = work / set_id
    shutil.rmtree(d, ignore_errors=True)
    args = ["cmake", "-S", str(ROOT / "host"), "-B", str(d), "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
            "-DCOLLIDE_AFU_PRESET=default", "-DCOLLIDE_AFU_DIR=", "-DCOLLIDE_BUILD_TESTS=OFF"]
    args += [f"-D{k}={v}" for k, v in SETS[set_id][1].items()]
    log = work / f"{set_id}.log"
    with open(log, "w") as out:
        if subprocess.run(args, stdout=out, stderr=subprocess.STDOUT).returncode != 0:
            raise RuntimeError(f"{set_id}: cmake failed; see {log}")
        t0 = time.monotonic()
        if subprocess.run(["cmake", "--build", str(d), "--target", "collide", "-j2"], stdout=out,
                          stderr=subprocess.STDOUT).returncode != 0:
            raise RuntimeError(f"{set_id}: build failed; see {log}")
        return time.monotonic() - t0


def per_cycle(summary: dict) -> tuple:
    """(wall ns per stepped cycle, cycles stepped) of one `collide run --summary` file."""
    stepped = summary["afu"]["cycles_stepped"]
    if stepped <= 0:
        raise ValueError("the run stepped no cycles")
    return summary["backend_wall_ns"] / stepped, stepped


def run(set_id: str, work: Path, steps: int, runs: int) -> tuple:
    """(fastest, median) wall ns per stepped cycle over `runs` runs, and the cycles stepped."""
    times = []
    for _ in range(runs):
        with tempfile.TemporaryDirectory() as t:
            s = Path(t) / "s.json"
            r = subprocess.run([str(work / set_id / "collide"), "run", str(SCENE), "--backend", "rtl", "--link", "qpi",
                                "--steps", str(steps), "--no-skip", "--summary", str(s)], capture_output=True, text=True)
            if r.returncode != 0:
                raise RuntimeError(f"{set_id}: collide run failed:\n{r.stderr}")
            ns, stepped = per_cycle(json.loads(s.read_text()))
        times.append(ns)
    return min(times), statistics.median(times), stepped


def run_two(set_id: str, work: Path, steps: int, rounds: int = 3) -> float:
    """Median wall ns per stepped cycle when two runs share the machine (ctest -j2, a sweep's
    --jobs 2): each model's threads then compete with the other's."""
    times = []
    exe = str(work / set_id / "collide")
    for _ in range(rounds):
        with tempfile.TemporaryDirectory() as t:
            outs = [Path(t) / f"{k}.json" for k in (0, 1)]
            procs = [subprocess.Popen([exe, "run", str(SCENE), "--backend", "rtl", "--link", "qpi", "--steps", str(steps),
                                       "--no-skip", "--summary", str(o)], stdout=subprocess.DEVNULL,
                                      stderr=subprocess.PIPE, text=True) for o in outs]
            for pr in procs:
                if pr.wait() != 0:
                    raise RuntimeError(f"{set_id}: collide run failed (two at once):\n{pr.stderr.read()}")
            times += [per_cycle(json.loads(o.read_text()))[0] for o in outs]
    return statistics.median(times)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sets", default="O1,O2,O3,O1-t2,O2-t2")
    ap.add_argument("--steps", type=int, default=10)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--out", type=Path, default=ROOT / "bench" / "results" / "verilator")
    ap.add_argument("--no-build", action="store_true")
    a = ap.parse_args(argv)
    sets = [s for s in a.sets.split(",") if s]
    for s in sets:
        if s not in SETS:
            ap.error(f"--sets: unknown set {s!r} (known: {', '.join(SETS)})")
    work = ROOT / "build" / "verilator-opts"
    work.mkdir(parents=True, exist_ok=True)
    start = time.time()
    old = {}
    if a.no_build:
        with open(a.out / "verilator.csv", newline="") as f:
            old = {r["set"]: float(r["build_s"]) for r in csv.DictReader(f)}
    rows = []
    for s in sets:
        if a.no_build:
            if s not in old or not (work / s / "collide").exists():
                ap.error(f"--no-build: no build of {s} (run without --no-build first)")
            secs = old[s]
        else:
            print(f"verilator: {s}: building", flush=True)
            secs = build(s, work)
        best, med, stepped = run(s, work, a.steps, a.runs)
        two = run_two(s, work, min(a.steps, 10))
        rows.append({"set": s, "what": SETS[s][0], "build_s": round(secs, 1), "us_per_cycle": round(best / 1e3, 2),
                     "us_per_cycle_median": round(med / 1e3, 2), "us_per_cycle_two_at_once": round(two / 1e3, 2),
                     "cycles_stepped": stepped})
        print(f"verilator: {s}: build {secs:.0f} s, {best / 1e3:.2f} us a cycle (median {med / 1e3:.2f}; "
              f"two at once {two / 1e3:.2f})", flush=True)
    for r in rows:
        r["commit"] = machine.commit()
    # Sets not measured this time keep their earlier rows, with the commit that measured them.
    if (a.out / "verilator.csv").exists() and not a.no_build:
        with open(a.out / "verilator.csv", newline="") as f:
            kept = [dict(r, commit=r.get("commit") or "0fae89a") for r in csv.DictReader(f) if r["set"] not in sets]
        for r in kept:
            for k in ("build_s", "us_per_cycle", "us_per_cycle_median", "us_per_cycle_two_at_once"):
                r[k] = float(r[k])
        rows = [r for s_id in SETS for r in rows + kept if r["set"] == s_id]
    a.out.mkdir(parents=True, exist_ok=True)
    with open(a.out / "verilator.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]), lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
    base = next((r for r in rows if r["set"] == "O1"), rows[0])
    lines = ["# Verilator options: build time against co-simulation speed", "",
             f"The default AFU (generated/default, 16 fp32 SCPUs) Verilated into `collide` with each option set, "
             f"built from scratch (host sources included, no ccache; `-j2`), then the paper's diamond over HARP v1 "
             f"for {a.steps} steps with every cycle evaluated (`--no-skip`), {a.runs} runs: the fastest and the median. "
             "Command: `tools/pyenv bench/verilator/options.py`; machine and commit in [MACHINE.md](MACHINE.md).", "",
             "The last column runs two such co-simulations at once (10 steps, 3 rounds, median), as `ctest -j2` and a "
             "sweep's `--jobs 2` do on this 2-core machine.", "",
             f"| set | what | build (s) | us a cycle, fastest | median | speed vs {base['set']} (fastest, median) "
             "| us a cycle, two at once | commit |",
             "|---|---|---:|---:|---:|---:|---:|---|"]
    for r in rows:
        lines.append(f"| {r['set']} | {r['what']} | {r['build_s']:.0f} | {r['us_per_cycle']:.2f} | "
                     f"{r['us_per_cycle_median']:.2f} | {base['us_per_cycle'] / r['us_per_cycle']:.2f}x, "
                     f"{base['us_per_cycle_median'] / r['us_per_cycle_median']:.2f}x | {r['us_per_cycle_two_at_once']:.2f} "
                     f"| {r['commit']} |")
    lines.append("")
    (a.out / "README.md").write_text("\n".join(lines))
    (a.out / "MACHINE.md").write_text(
        f"# Machine\n\n- command: `tools/pyenv bench/verilator/options.py {' '.join(argv or sys.argv[1:])}`\n"
        f"- date: {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {time.time() - start:.0f} s\n"
        f"- commit: {machine.commit()}\n- machine: {machine.describe()}\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
