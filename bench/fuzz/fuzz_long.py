#!/usr/bin/env python3
"""Runs every libFuzzer target of test/fuzz for a long, fixed number of executions and
commits what it found: executions, time, edge coverage (libFuzzer's cov and ft counts), the
corpus it grew to and any crash, to bench/results/fuzz/ (docs/fuzzing.md).

    tools/pyenv bench/fuzz/fuzz_long.py                 # 1,000,000 executions each
    tools/pyenv bench/fuzz/fuzz_long.py --runs 20000 --targets scene --out /tmp/fz

Builds build/fuzz (clang, ASan and UBSan, COLLIDE_FUZZ=ON) first. A crash is saved under
build/fuzz/artifacts/ and ends the script with a non-zero status after the report.
"""
import argparse
import csv
import datetime
import os
import platform
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
TARGETS = ["scene", "manifest", "link_params", "pairs_csv", "spheres_csv"]
FUZZ_DIR = ROOT / "test" / "fuzz"
BUILD = ROOT / "build" / "fuzz"
FOUND = "## Found and fixed"
STATS = re.compile(r"cov: (\d+) ft: (\d+) corp: (\d+)/(\S+)")


def build():
    subprocess.run(["cmake", "-S", "host", "-B", str(BUILD), "-G", "Ninja", "-DCMAKE_BUILD_TYPE=RelWithDebInfo",
                    "-DCMAKE_CXX_COMPILER=clang++", "-DCOLLIDE_FUZZ=ON", "-DCOLLIDE_SANITIZE=address,undefined",
                    "-DCOLLIDE_BUILD_TESTS=OFF"], cwd=ROOT, check=True, stdout=subprocess.DEVNULL)
    subprocess.run(["cmake", "--build", str(BUILD), "-j2", "--target", "fuzz_targets"], cwd=ROOT, check=True,
                   stdout=subprocess.DEVNULL)


def run_target(name, runs, seed, max_len):
    """One target from its committed corpus into a scratch folder: a dict of its figures."""
    artifacts = BUILD / "artifacts" / name
    artifacts.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix=f"fuzz-{name}-") as scratch:
        cmd = [str(BUILD / "test" / "fuzz" / f"fuzz_{name}"), f"-runs={runs}", f"-seed={seed}",
               f"-dict={FUZZ_DIR / 'collide.dict'}", f"-max_len={max_len}", "-print_final_stats=1",
               f"-artifact_prefix={artifacts}/", scratch, str(FUZZ_DIR / "corpus" / name)]
        t0 = time.monotonic()
        proc = subprocess.run(cmd, capture_output=True, text=True, errors="replace")
        seconds = time.monotonic() - t0
    log = proc.stderr
    (BUILD / f"fuzz_{name}.log").write_text(log)
    stats = STATS.findall(log)
    executed = re.search(r"stat::number_of_executed_units: (\d+)", log)
    cov, ft, corp, corp_size = stats[-1] if stats else ("", "", "", "")
    return {"target": name, "executions": int(executed.group(1)) if executed else 0, "seconds": round(seconds, 1),
            "cov_edges": cov, "features": ft, "corpus_units": corp, "corpus_size": corp_size,
            "seed_units": len(list((FUZZ_DIR / "corpus" / name).iterdir())),
            "crashes": 0 if proc.returncode == 0 else 1, "exit": proc.returncode}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--runs", type=int, default=1_000_000, help="executions per target (default 1,000,000)")
    ap.add_argument("--seed", type=int, default=1, help="libFuzzer's -seed (default 1)")
    ap.add_argument("--max-len", type=int, default=4096, help="largest input in bytes (default 4096)")
    ap.add_argument("--targets", default=",".join(TARGETS), help="comma-separated subset of " + ",".join(TARGETS))
    ap.add_argument("--out", type=Path, default=ROOT / "bench" / "results" / "fuzz", help="results folder")
    a = ap.parse_args()
    targets = [t for t in a.targets.split(",") if t]
    unknown = [t for t in targets if t not in TARGETS]
    if unknown:
        ap.error(f"--targets: unknown {', '.join(unknown)} (known: {', '.join(TARGETS)})")
    if a.runs < 1:
        ap.error(f"--runs: {a.runs} is not a positive count")
    build()
    rows = []
    for t in targets:
        r = run_target(t, a.runs, a.seed, a.max_len)
        print(f"{t}: {r['executions']} executions in {r['seconds']} s, cov {r['cov_edges']}, "
              f"{'CRASH (exit %d)' % r['exit'] if r['crashes'] else 'no crash'}", flush=True)
        rows.append(r)
    a.out.mkdir(parents=True, exist_ok=True)
    with open(a.out / "results.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    clang = subprocess.run(["clang++", "--version"], capture_output=True, text=True).stdout.splitlines()[0]
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True,
                            text=True).stdout.strip()
    lines = ["# Long fuzzing runs", "",
             f"Command: `tools/pyenv bench/fuzz/fuzz_long.py --runs {a.runs} --seed {a.seed}`. "
             f"Machine: {os.cpu_count()} cores, {platform.machine()}, {clang}, "
             f"{datetime.date.today().isoformat()}, commit {commit}.",
             "Each target is built with -fsanitize=fuzzer,address,undefined and starts from its committed corpus "
             "(test/fuzz/corpus/<target>) and the dictionary test/fuzz/collide.dict. cov: edges of the "
             "instrumented code reached; features: libFuzzer's finer coverage signal.", "",
             "| target | executions | seconds | cov (edges) | features | corpus grown to | seed inputs | crashes |",
             "|---|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        lines.append(f"| {r['target']} | {r['executions']:,} | {r['seconds']} | {r['cov_edges']} | {r['features']} | "
                     f"{r['corpus_units']} ({r['corpus_size']}) | {r['seed_units']} | {r['crashes']} |")
    # The hand-kept record of what the fuzzers found (from "## Found and fixed" on) survives.
    readme = a.out / "README.md"
    kept = ""
    if readme.exists():
        old = readme.read_text()
        at = old.find(FOUND)
        kept = "\n" + old[at:] if at >= 0 else ""
    readme.write_text("\n".join(lines) + "\n" + kept)
    print(f"fuzz_long: wrote {a.out / 'results.csv'} and README.md")
    return 1 if any(r["crashes"] for r in rows) else 0


if __name__ == "__main__":
    sys.exit(main())
