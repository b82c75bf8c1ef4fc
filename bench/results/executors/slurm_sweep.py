"""Run one sweep through the Slurm executor on a one-node Slurm cluster on this machine,
started as the tests start it (bench/tests/slurm_cluster.py; as root), and print its wall time.

With --cold, the sweep's own caches (its configurations' Verilog, host builds, runs and
records, and every Yosys area) are deleted first, so every step runs; ccache and sbt's
compiled generator stay warm. Anything after the sweep's name goes to `bench/sweep run`.

Usage (from the checkout):
  tools/pyenv bench/results/executors/slurm_sweep.py [--cold] NAME [bench/sweep run args ...]
e.g.
  tools/pyenv bench/results/executors/slurm_sweep.py --cold arith
  tools/pyenv bench/results/executors/slurm_sweep.py --cold scpus --configs n1_fp32,n2_fp32 --out /tmp/x"""
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
sys.path.insert(0, str(ROOT / "bench" / "tests"))

import slurm_cluster  # noqa: E402
from sweeplib.sweeps import SWEEPS  # noqa: E402


def cold(name: str, configs: list):
    sweep = ROOT / "build" / "sweep"
    for c in configs:
        for p in (f"gen/{c}", f"host/{c}"):
            shutil.rmtree(sweep / p, ignore_errors=True)
    for p in ("area", "accuracy", f"runs/{name}", f"exec/{name}", f"logs/{name}"):
        shutil.rmtree(sweep / p, ignore_errors=True)


def main(argv):
    is_cold = "--cold" in argv
    argv = [a for a in argv if a != "--cold"]
    if not argv or argv[0] not in SWEEPS:
        sys.exit(f"usage: slurm_sweep.py [--cold] NAME [bench/sweep run args]; NAME one of {', '.join(sorted(SWEEPS))}")
    name, rest = argv[0], argv[1:]
    if is_cold:
        only = next((rest[i + 1] for i, a in enumerate(rest[:-1]) if a == "--configs"), None)
        cold(name, only.split(",") if only else [c.id for c in SWEEPS[name].configs])
    with slurm_cluster.Cluster() as c:
        t = time.time()
        r = subprocess.run([str(ROOT / "bench" / "sweep"), "run", name, "--executor", "slurm", *rest],
                           env=c.env, cwd=ROOT)
        print(f"rc {r.returncode} wall_s {time.time() - t:.1f}")
    sys.exit(r.returncode)


if __name__ == "__main__":
    main(sys.argv[1:])
