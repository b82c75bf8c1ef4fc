"""The local executor: runs a sweep's tasks on this machine, up to N at a time, each as soon
as the tasks it needs are done (graphlib's TopologicalSorter hands out the ready ones)."""
import graphlib
from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait

from .progress import Bar
from .tasks import Records, execute


def run(tasks, records: Records, jobs: int, desc: str) -> dict:
    """Runs every task not done yet; returns {task id: record} of those that failed or were
    skipped because a task they need failed (empty: all done). A failed task stops only what
    needs it: the others go on, so one run reports every failure."""
    if jobs < 1:
        raise ValueError(f"--jobs {jobs}: must be at least 1")
    by_id = {t.id: t for t in tasks}
    todo = {t.id for t in tasks if not t.done()}
    graph = graphlib.TopologicalSorter({i: [d for d in by_id[i].deps if d in todo] for i in sorted(todo)})
    graph.prepare()
    bar = Bar(sum(by_id[i].weight for i in todo), desc)
    bad, running = {}, {}
    pool = ThreadPoolExecutor(max_workers=jobs)  # threads suffice: every step is a subprocess
    try:
        ready = []
        while graph.is_active():
            # The heaviest ready task first: a long Yosys run started early ends the sweep sooner.
            ready = sorted(ready + list(graph.get_ready()), key=lambda i: -by_id[i].weight)
            while ready and len(running) < jobs:
                i = ready.pop(0)
                running[pool.submit(execute, by_id[i], records, by_id)] = i
            bar.status(", ".join(sorted(running.values())))
            finished, _ = wait(running, return_when=FIRST_COMPLETED)
            for f in finished:
                i = running.pop(f)
                rec = f.result()
                if rec["state"] != "done":
                    bad[i] = rec
                    bar.write(f"{desc}: {i} {rec['state']}: {rec['error']}")
                bar.advance(by_id[i].weight)
                graph.done(i)
    except BaseException:
        pool.shutdown(wait=False, cancel_futures=True)  # Ctrl-C: the running steps get the SIGINT too
        raise
    finally:
        bar.close()
    pool.shutdown()
    return bad
