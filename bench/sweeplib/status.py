"""`bench/sweep status NAME`: each task of a sweep as done, queued, running, failed, skipped,
interrupted or to do, from the caches, the task records and (for Slurm jobs) squeue."""
import os
import shutil

from . import slurmctl
from .slurm import Jobs
from .tasks import KINDS, Records, node

ORDER = ("done", "running", "queued", "failed", "skipped", "interrupted", "to do")


def _alive(pid) -> bool:
    try:
        os.kill(int(pid), 0)
        return True
    except (OSError, TypeError, ValueError):
        return False


def states(runner, tasks) -> dict:
    """task id -> (state, detail)."""
    records, jobs = Records(runner.exec / "records"), Jobs(runner.exec / "jobs.json")
    q = {}
    if jobs.map and shutil.which("squeue"):
        try:
            q = slurmctl.queue()
        except RuntimeError:  # no controller reachable: the records still tell most of it
            q = {}
    out = {}
    for t in tasks:
        rec = records.read(t.id) or {}
        job = q.get(jobs.key(t.id)) if t.id in jobs.map else None
        if t.done():
            out[t.id] = ("done", rec.get("node", ""))
        elif rec.get("state") in ("failed", "skipped"):
            # A final record wins over the queue, as in the executor's follow(): submitting
            # clears a task's record, so this one is the job's own, written as its worker ended
            # (the job can stay listed as running for a moment after).
            log = jobs.map.get(t.id, {}).get("log")
            out[t.id] = (rec["state"], rec["error"] + (f" (log: {log})" if log else ""))
        elif job and job[0] in slurmctl.ACTIVE:
            where = f"job {jobs.key(t.id)}" + (f" on {job[2]}" if job[2] else f" ({job[1]})")
            out[t.id] = ("queued" if job[0] == "PENDING" else "running", where)
        elif rec.get("state") == "running":
            local = rec.get("node") == node() and t.id not in jobs.map
            out[t.id] = ("running", f"on {node()}, pid {rec['pid']}") if local and _alive(rec.get("pid")) else \
                ("interrupted", f"started on {rec.get('node')}, ended without a result")
        else:
            out[t.id] = ("to do", "")
    return out


def report(runner, tasks) -> str:
    st = states(runner, tasks)
    lines = [f"{runner.sweep.name}: " + ", ".join(
        f"{sum(1 for s, _ in st.values() if s == k)} {k}" for k in ORDER if any(s == k for s, _ in st.values()))]
    for kind in KINDS:
        ks = [t for t in tasks if t.kind == kind]
        if ks:
            counts = ", ".join(f"{sum(1 for t in ks if st[t.id][0] == k)} {k}" for k in ORDER
                               if any(st[t.id][0] == k for t in ks))
            lines.append(f"  {kind}: {counts}")
    for t in tasks:
        s, detail = st[t.id]
        if s not in ("done", "to do"):  # the counts above say how many are left
            lines.append(f"  {s:11s} {t.id}" + (f": {detail}" if detail else ""))
    return "\n".join(lines)
