"""A sweep's steps as tasks (what to do, what it needs first, whether it is done) and their
records: one small JSON file per task saying how its last attempt went, on which node.

Both executors run tasks through `execute`, so the records (and `bench/sweep status`) look
the same whichever ran them."""
import json
import os
import socket
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

from . import machine
from .paths import write_atomic

# The order of the stages: a task only needs tasks of its own or an earlier kind.
KINDS = ("generate", "accuracy", "build", "area", "timing", "run")


@dataclass
class Task:
    id: str                      # e.g. "build/n2_fp32"; unique in a sweep
    kind: str                    # one of KINDS
    deps: tuple                  # ids of the tasks it needs
    weight: float                # rough seconds on a 2-core machine: the progress bar's unit
    action: Callable[[], object] = field(repr=False)
    done: Callable[[], bool] = field(repr=False)   # its outputs are cached and current
    size: str = "normal"         # "big": far more time and memory than its kind's usual (Slurm sizes jobs by it)

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"task {self.id}: unknown kind {self.kind!r} (one of {', '.join(KINDS)})")


def node() -> str:
    return socket.gethostname().split(".")[0]


class Records:
    """records/<task>.json: state (running, done, failed, skipped), node, pid, times, error."""

    def __init__(self, folder: Path):
        self.folder = folder

    def path(self, task_id: str) -> Path:
        return self.folder / (task_id.replace("/", "~") + ".json")

    def read(self, task_id: str):
        p = self.path(task_id)
        try:
            return json.loads(p.read_text())
        except (FileNotFoundError, json.JSONDecodeError):  # absent, or being replaced on a slow share
            return None

    def write(self, task_id: str, **fields):
        write_atomic(self.path(task_id), json.dumps({"task": task_id} | fields) + "\n")

    def clear(self, task_id: str):
        self.path(task_id).unlink(missing_ok=True)


def execute(task: Task, records: Records, by_id: dict) -> dict:
    """Runs one task (unless a task it needs is not done) and records how it went."""
    missing = [d for d in task.deps if not by_id[d].done()]
    if missing:
        rec = dict(state="skipped", node=node(), error=f"not run: it needs {', '.join(missing)}, which did not finish")
        records.write(task.id, **rec)
        return rec
    start = time.time()
    machine.record_node(node())  # MACHINE.md names the node of each row's timings
    records.write(task.id, state="running", node=node(), pid=os.getpid(), start=start)
    try:
        task.action()
        rec = dict(state="done", error="")
    except Exception as e:  # a step's failure is a result to report, not a crash of the executor
        msg = str(e) if isinstance(e, RuntimeError) else "".join(traceback.format_exception_only(e)).strip()
        rec = dict(state="failed", error=msg)
    rec |= dict(node=node(), start=start, end=time.time())
    records.write(task.id, **rec)
    return rec
