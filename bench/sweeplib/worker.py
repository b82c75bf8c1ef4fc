"""One Slurm task: `python -m sweeplib.worker PLAN TASK_ID` rebuilds the sweep's runner from the plan the
driver wrote (slurm.py), runs that task on this node and records how it went (tasks.execute).
Exits 1 when the task failed or could not run, so Slurm's own accounting agrees."""
import json
import sys
from pathlib import Path

from .sweep import Runner
from .tasks import Records, execute


def main(argv):
    if len(argv) != 2:
        print("usage: python -m sweeplib.worker PLAN.json TASK_ID", file=sys.stderr)
        return 2
    plan, tid = Path(argv[0]), argv[1]
    if not plan.exists():
        print(f"worker: {plan} not found on this node: is build/ on storage the nodes share?", file=sys.stderr)
        return 1
    runner = Runner.from_settings(json.loads(plan.read_text()))
    by_id = {t.id: t for t in runner.tasks()}
    if tid not in by_id:
        print(f"worker: the plan {plan} has no task {tid!r} (the sweep changed since it was submitted?)", file=sys.stderr)
        return 1
    print(f"worker: {tid}", flush=True)
    rec = execute(by_id[tid], Records(runner.exec / "records"), by_id)
    print(f"worker: {tid} {rec['state']}" + (f": {rec['error']}" if rec["error"] else ""), flush=True)
    return 0 if rec["state"] == "done" else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
