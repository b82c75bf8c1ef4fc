"""The Slurm executor: each stage of a sweep (tasks.KINDS, split by Task.size) is one sbatch
job array, chained to the stages it needs by job dependencies; the driver then follows the
tasks through squeue and their records (tasks.Records) with the same progress bar.

Resuming: a task whose outputs are cached is not resubmitted, nor one whose job is still
queued or running (jobs.json remembers which job and index runs each task); the rest are.
Ctrl-C (or SIGTERM) cancels the jobs this sweep follows. Dependencies are `afterany`, and each
task checks on its node that what it needs is done (tasks.execute), so one failed task stops
only the tasks that need it, as in the local executor."""
import json
import signal
import time
from pathlib import Path

from . import slurmctl
from . import storage
from .paths import BUILD, ROOT, write_atomic
from .progress import Bar
from .tasks import KINDS, Records, node

# (kind, size) -> (CPUs, memory, time limit) of a task: estimates from the steps' costs on
# a 2-core machine (bench/slurm.md, "What each stage costs") with room to spare; sbt runs
# with -Xmx4g. --cpus-per-task, --mem and --time replace them for every job.
RESOURCES = {
    ("generate", "normal"): (2, "6G", "1:00:00"),
    ("accuracy", "normal"): (2, "6G", "2:00:00"),
    ("build", "normal"): (2, "4G", "1:00:00"),
    ("build", "big"): (2, "8G", "2:00:00"),
    ("area", "normal"): (1, "4G", "2:00:00"),
    ("area", "big"): (1, "16G", "12:00:00"),
    ("timing", "normal"): (1, "4G", "2:00:00"),
    ("timing", "big"): (1, "16G", "12:00:00"),
    ("run", "normal"): (1, "2G", "0:30:00"),
}
# How long a task that Slurm reports ended may take to show its record (attribute caching on
# a network filesystem) before it counts as ended without one.
RECORD_GRACE_S = 30


class Options:
    def __init__(self, partition=None, account=None, time=None, cpus_per_task=None, mem=None, sbatch_args=(),
                 poll=5.0, storage_is_shared=False):
        self.partition, self.account, self.time = partition, account, time
        self.cpus_per_task, self.mem, self.sbatch_args = cpus_per_task, mem, list(sbatch_args)
        self.poll, self.storage_is_shared = poll, storage_is_shared

    def sbatch(self, kind, size) -> list:
        cpus, mem, limit = RESOURCES[(kind, size)]
        args = [f"--cpus-per-task={self.cpus_per_task or cpus}", f"--mem={self.mem or mem}",
                f"--time={self.time or limit}"]
        args += [f"--partition={self.partition}"] if self.partition else []
        args += [f"--account={self.account}"] if self.account else []
        return args + self.sbatch_args


class Jobs:
    """jobs.json: task id -> {"job", "index", "log"}: which array task last ran (or runs) it."""

    def __init__(self, path: Path):
        self.path = path
        self.map = json.loads(path.read_text()) if path.exists() else {}

    def key(self, tid):
        j = self.map[tid]
        return f"{j['job']}_{j['index']}"

    def save(self):
        write_atomic(self.path, json.dumps(self.map, indent=1) + "\n")


def _stage(kind, size):
    return kind if size == "normal" else f"{kind}-{size}"


def _log_tail(path: Path, n=3) -> str:
    try:
        lines = [l for l in path.read_text(errors="replace").splitlines() if l.strip()]
    except OSError:
        return f"it left no log {path} (it never started, or build/ is not on storage the nodes share)"
    return "its log ends: " + " | ".join(lines[-n:]) if lines else "its log is empty"


class Driver:
    def __init__(self, runner, opts: Options, on_poll=None):
        self.runner, self.opts, self.on_poll = runner, opts, on_poll
        self.dir = runner.exec
        self.records = Records(self.dir / "records")
        self.jobs = Jobs(self.dir / "jobs.json")
        self.log_dir = runner.logs / "slurm"
        self.submitted = []   # task ids this run submitted (tests check resumption by it)
        self.followed = set()  # job ids this run follows: cancelled on Ctrl-C
        self.sbatch_seconds = 0.0  # time spent submitting (bench/results/executors)

    def check_storage(self):
        if not self.opts.storage_is_shared:
            storage.check([ROOT, BUILD], slurmctl.nodes(self.opts.partition), node())

    def submit(self, tasks, by_id, plan: Path):
        """Submits the tasks (none done, none queued), one job array per stage, in stage order."""
        groups = {}
        for t in tasks:
            groups.setdefault((KINDS.index(t.kind), t.kind, t.size), []).append(t)
        jobs_dir = self.dir / "jobs"
        for _, kind, size in sorted(groups):
            group = groups[(KINDS.index(kind), kind, size)]
            stage = _stage(kind, size)
            after = sorted({self.jobs.map[d]["job"] for t in group for d in t.deps
                            if d in self.jobs.map and not by_id[d].done()})
            n = len(list(jobs_dir.glob(f"{stage}-*.sh"))) if jobs_dir.exists() else 0
            listing = jobs_dir / f"{stage}-{n}.tasks"
            write_atomic(listing, "".join(t.id + "\n" for t in group))
            script = jobs_dir / f"{stage}-{n}.sh"
            write_atomic(script, f"""#!/usr/bin/env bash
# bench/sweep {self.runner.sweep.name}, stage {stage}: array index i runs line i+1 of {listing.name}
set -euo pipefail
cd {ROOT}
task="$(sed -n "$((SLURM_ARRAY_TASK_ID + 1))p" {listing})"
exec {ROOT / 'tools' / 'pyenv'} -m sweeplib.worker {plan} "$task"
""")
            for t in group:
                self.records.clear(t.id)
            self.log_dir.mkdir(parents=True, exist_ok=True)
            args = [f"--array=0-{len(group) - 1}", f"--job-name=sweep-{self.runner.sweep.name}-{stage}",
                    f"--output={self.log_dir}/{stage}-%A_%a.log", f"--chdir={ROOT}"]
            args += [f"--dependency=afterany:{':'.join(after)}"] if after else []
            t0 = time.time()
            job = slurmctl.sbatch(script, args + self.opts.sbatch(kind, size))
            self.sbatch_seconds += time.time() - t0
            self.followed.add(job)
            for i, t in enumerate(group):
                self.jobs.map[t.id] = {"job": job, "index": i, "log": str(self.log_dir / f"{stage}-{job}_{i}.log"),
                                       "submitted": time.time()}
                self.submitted.append(t.id)
            self.jobs.save()

    def run(self, tasks, plan: Path) -> dict:
        """Runs every task not done; returns {task id: record} of those that did not finish."""
        by_id = {t.id: t for t in tasks}
        todo = [t for t in tasks if not t.done()]
        if not todo:
            return {}
        self.check_storage()
        q = slurmctl.queue()
        live = {t.id for t in todo if t.id in self.jobs.map and q.get(self.jobs.key(t.id), ("",))[0] in slurmctl.ACTIVE}
        self.followed |= {self.jobs.map[i]["job"] for i in live}
        bar = Bar(sum(t.weight for t in todo), self.runner.sweep.name)
        old = signal.signal(signal.SIGTERM, signal.default_int_handler)  # scancel on SIGTERM as on Ctrl-C
        try:
            self.submit([t for t in todo if t.id not in live], by_id, plan)
            return self.follow(todo, bar)
        except KeyboardInterrupt:
            bar.write(f"{self.runner.sweep.name}: interrupted: cancelling jobs {', '.join(sorted(self.followed))}")
            slurmctl.cancel(self.followed)
            raise
        finally:
            signal.signal(signal.SIGTERM, old)
            bar.close()

    def follow(self, todo, bar) -> dict:
        waiting = {t.id: t for t in todo}
        ended_at, bad = {}, {}
        while waiting:
            if self.on_poll:
                self.on_poll(self)
            q = slurmctl.queue()  # before the records: a task that left the queue has written its record
            counts = {}
            for tid in list(waiting):
                state, reason, where = q.get(self.jobs.key(tid), ("", "", ""))
                rec = self.records.read(tid)
                final = rec is not None and rec["state"] != "running"
                if not final and state in slurmctl.ACTIVE:
                    counts[state] = counts.get(state, 0) + 1
                    continue
                if not final:  # left the queue (or ended) without a final record
                    first = ended_at.setdefault(tid, time.time())
                    if state == "COMPLETED" and time.time() - first < RECORD_GRACE_S:
                        continue
                    rec = self.vanished(tid, state, reason, rec)
                if rec["state"] != "done":
                    bad[tid] = rec | {"log": self.jobs.map[tid]["log"]}
                    bar.write(f"{self.runner.sweep.name}: {tid} {rec['state']}: {rec['error']} (log: {bad[tid]['log']})")
                bar.advance(waiting.pop(tid).weight)
            bar.status(", ".join(f"{n} {s.lower()}" for s, n in sorted(counts.items())))
            if waiting:
                time.sleep(self.opts.poll)
        return bad

    def vanished(self, tid, state, reason, rec):
        """The record of a task that ended without writing its own: killed by Slurm (time
        limit, memory, node failure, cancelled), or its worker could not start."""
        key, log = self.jobs.key(tid), Path(self.jobs.map[tid]["log"])
        acct = "" if state else slurmctl.accounting(key)
        why = f"Slurm says {state} ({reason})" if state else f"sacct says {acct}" if acct else \
            "it left the queue without a final state (cancelled before it started?)"
        rec = dict(state="failed", node=(rec or {}).get("node", ""),
                   error=f"job {key} ended without a record of its result: {why}; {_log_tail(log)}")
        self.records.write(tid, **rec)
        return rec
