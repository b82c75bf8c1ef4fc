"""The Slurm executor's overhead over the local one on the smoke sweep, on a one-node Slurm
cluster on this machine started as the tests start it (bench/tests/slurm_cluster.py; as root).

Each repetition runs the smoke sweep once with each executor in a fresh work folder, so its
four tasks run (the build is made stale first: a no-op Ninja run; the Verilog stays cached),
and splits the wall time along the critical path (build, then the three runs at once):
submission (sbatch), waiting before the build starts, between the build's end and the first
run's start, and from the last run's end until the driver has noticed it (polling).
Usage: tools/pyenv bench/results/executors/measure_slurm.py [REPS [POLL_S]]"""
import os
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
sys.path.insert(0, str(ROOT / "bench" / "tests"))

from sweeplib import build  # noqa: E402
from sweeplib import local  # noqa: E402
from sweeplib import slurm  # noqa: E402
import slurm_cluster  # noqa: E402
from sweeplib import sweep  # noqa: E402
from sweeplib.sweeps import SWEEPS  # noqa: E402
from sweeplib.tasks import Records  # noqa: E402


def once(executor, work: Path, poll: float) -> dict:
    r = sweep.Runner(SWEEPS["smoke"], work / "out", True, 0, work)
    (build.HOST / r.sweep.configs[0].id / ".sweep-key").unlink(missing_ok=True)
    tasks = r.tasks()
    t0 = time.time()
    submission = 0.0
    if executor == "local":
        bad = local.run(tasks, Records(r.exec / "records"), 2, "local")
    else:
        drv = slurm.Driver(r, slurm.Options(poll=poll))
        bad = drv.run(tasks, r.write_plan())
        submission = drv.sbatch_seconds
    t1 = time.time()
    if bad:
        raise RuntimeError(f"{executor}: {bad}")
    r.collect()
    recs = Records(r.exec / "records")
    b = recs.read("build/n2_fp32")
    runs = [recs.read(t.id) for t in tasks if t.kind == "run"]
    return {"wall": t1 - t0, "submission": submission, "before_build": b["start"] - t0,
            "build": b["end"] - b["start"], "build_to_runs": min(x["start"] for x in runs) - b["end"],
            "runs": max(x["end"] for x in runs) - min(x["start"] for x in runs),
            "noticed": t1 - max(x["end"] for x in runs)}


def main(argv):
    reps = int(argv[0]) if argv else 3
    poll = float(argv[1]) if len(argv) > 1 else 5.0
    cols = ("wall", "submission", "before_build", "build", "build_to_runs", "runs", "noticed")
    print(f"poll {poll} s; seconds\n\n| rep | executor | " + " | ".join(cols) + " |\n|---|---|" + "---:|" * len(cols))
    with slurm_cluster.Cluster() as c, tempfile.TemporaryDirectory() as d:
        os.environ["SLURM_CONF"] = c.env["SLURM_CONF"]
        for i in range(reps):
            for ex in ("local", "slurm"):
                m = once(ex, Path(d) / f"{ex}{i}", poll)
                print(f"| {i} | {ex} | " + " | ".join(f"{m[k]:.2f}" for k in cols) + " |", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
