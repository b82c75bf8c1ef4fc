"""The scpus sweep's first two configurations with their areas through the Slurm executor,
from cold sweep caches (this checkout's Verilog, builds, areas and runs of those two deleted;
ccache warm), on a one-node Slurm cluster on this machine started as the tests start it
(bench/tests/slurm_cluster.py; as root). Compare its CSV with measure_jobs.sh's.
Usage (from the checkout): tools/pyenv bench/results/executors/measure_slurm_scpus.py OUT_DIR"""
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
sys.path.insert(0, str(ROOT / "bench" / "tests"))

import slurm_cluster  # noqa: E402


def main(out):
    with slurm_cluster.Cluster() as c:
        for p in ("gen/n1_fp32", "gen/n2_fp32", "host/n1_fp32", "host/n2_fp32", "area", "runs/scpus", "exec/scpus"):
            shutil.rmtree(ROOT / "build" / "sweep" / p, ignore_errors=True)
        t = time.time()
        r = subprocess.run([str(ROOT / "bench" / "sweep"), "run", "scpus", "--configs", "n1_fp32,n2_fp32",
                            "--executor", "slurm", "--out", out], env=c.env, cwd=ROOT)
        print(f"rc {r.returncode} wall_s {time.time() - t:.1f}")


if __name__ == "__main__":
    main(sys.argv[1])
