"""bench/sweep: design-space sweeps of the collision AFU (see bench/README.md).

  bench/sweep list                      the named sweeps
  bench/sweep run NAME [--no-area] ...  run one (resumes where it stopped), write CSV + plots
        --executor local (default): on this machine, --jobs N steps at a time (default: the core count)
        --executor slurm: one sbatch job array per stage (--partition, --account, --time, ...)
  bench/sweep status NAME               what is done, queued, running, failed
  bench/sweep plot NAME                 redraw the plots and tables from the CSV
"""
import argparse
import dataclasses
import datetime
import json
import os
import sys
from pathlib import Path

from . import local
from . import machine
from . import plots
from . import report
from . import slurm
from . import status
from . import sweep as sweeplib
from .paths import EXEC, RESULTS, write_atomic
from .sweeps import SWEEPS
from .tasks import Records


def parser():
    ap = argparse.ArgumentParser(prog="bench/sweep", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    sub.add_parser("list", help="print the named sweeps")
    r = sub.add_parser("run", help="run a named sweep (cached, resumable) and write its CSV and plots")
    r.add_argument("name", choices=sorted(SWEEPS))
    r.add_argument("--out", type=Path, help="results folder (default bench/results/NAME)")
    r.add_argument("--no-area", action="store_true", help="skip the Yosys area step (slow: minutes a block)")
    r.add_argument("--cpu-repeat", type=int, default=0, help="ODE/simd timings: fastest of K (default: the sweep's)")
    r.add_argument("--configs", help="only these of the sweep's configurations (comma-separated ids, e.g. n1_fp32,n2_fp32)")
    r.add_argument("--executor", choices=("local", "slurm"), default="local",
                   help="local: on this machine (default); slurm: sbatch job arrays")
    r.add_argument("--jobs", type=int, default=len(os.sched_getaffinity(0)),  # the cores this process may use
                   help="local: steps run at once (default: the core count, %(default)s here)")
    s = r.add_argument_group("slurm (with --executor slurm; bench/slurm.md)")
    s.add_argument("--partition", help="sbatch --partition (default: the cluster's default partition)")
    s.add_argument("--account", help="sbatch --account")
    s.add_argument("--time", help="time limit of every job, replacing the per-step defaults (e.g. 4:00:00)")
    s.add_argument("--cpus-per-task", type=int, help="CPUs of every job, replacing the per-step defaults")
    s.add_argument("--mem", help="memory of every job, replacing the per-step defaults (e.g. 8G)")
    s.add_argument("--sbatch-arg", action="append", default=[], metavar="ARG",
                   help="one more sbatch argument for every job, e.g. --sbatch-arg=--qos=long (repeatable)")
    s.add_argument("--poll", type=float, default=5.0, help="seconds between squeue polls (default 5)")
    s.add_argument("--storage-is-shared", action="store_true",
                   help="skip the check that the checkout is not on a local filesystem (the nodes do see it)")
    st = sub.add_parser("status", help="what is done, queued, running and failed in a sweep")
    st.add_argument("name", choices=sorted(SWEEPS))
    p = sub.add_parser("plot", help="redraw a sweep's plots from its CSV")
    p.add_argument("name", choices=sorted(SWEEPS))
    p.add_argument("--out", type=Path)
    return ap


def slurm_options(a) -> slurm.Options:
    return slurm.Options(partition=a.partition, account=a.account, time=a.time, cpus_per_task=a.cpus_per_task,
                         mem=a.mem, sbatch_args=a.sbatch_arg, poll=a.poll, storage_is_shared=a.storage_is_shared)


def execute(runner, a, on_poll=None) -> dict:
    """Runs the sweep's tasks with the chosen executor; {task id: record} of those that did not finish."""
    tasks = runner.tasks()
    plan = runner.write_plan()
    if a.executor == "slurm":
        return slurm.Driver(runner, slurm_options(a), on_poll).run(tasks, plan)
    return local.run(tasks, Records(runner.exec / "records"), a.jobs, runner.sweep.name)


def machine_note(sw, cmd, secs, rows, a) -> str:
    how = f"local, --jobs {a.jobs}" if a.executor == "local" else "slurm" + "".join(
        f", --{k.replace('_', '-')} {v}" for k, v in (("partition", a.partition), ("account", a.account)) if v)
    nodes = sorted({r["node"] for r in rows if r.get("node")})
    return (f"# {sw.name}: how these results were made\n\n- command: `{cmd.strip()}`\n"
            f"- date: {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, "
            f"{secs:.0f} s for the steps not already cached\n- executor: {how}\n"
            + "".join(f"- node {n} (the `node` column; its rows' timings): {machine.node_line(n)}\n" for n in nodes)
            + ("- rows with no node: their runs were cached before the sweeps recorded nodes\n"
               if any(not r.get("node") for r in rows) else "")
            + f"- commit: {machine.commit()}\n")


def subset(ap, sw, ids):
    known = {c.id: c for c in sw.configs}
    unknown = [i for i in ids if i not in known]
    if unknown:
        ap.error(f"--configs: {', '.join(unknown)} not in sweep {sw.name} (its configurations: {', '.join(known)})")
    return dataclasses.replace(sw, configs=tuple(known[i] for i in ids))


def main(argv=None, on_poll=None):
    ap = parser()
    a = ap.parse_args(argv)
    if a.cmd == "list":
        for s in SWEEPS.values():
            print(f"{s.name:7s} {s.about}; {len(s.configs)} configurations x {len(s.scenes)} scenes x "
                  f"{len(s.links)} links")
        return 0
    sw = SWEEPS[a.name]
    if a.cmd == "status":
        plan = EXEC / sw.name / "plan.json"
        runner = sweeplib.Runner.from_settings(json.loads(plan.read_text())) if plan.exists() else \
            sweeplib.Runner(sw, RESULTS / sw.name, do_area=True, cpu_repeat=0)
        print(status.report(runner, runner.tasks()))
        return 0
    out = a.out or RESULTS / sw.name
    if a.cmd == "run":
        if a.cpu_repeat < 0:
            ap.error("--cpu-repeat: must be >= 1")
        if a.jobs < 1:
            ap.error(f"--jobs {a.jobs}: must be at least 1")
        if a.configs:
            sw = subset(ap, sw, a.configs.split(","))
        runner = sweeplib.Runner(sw, out, do_area=not a.no_area, cpu_repeat=a.cpu_repeat)
        t0 = datetime.datetime.now().timestamp()
        try:
            bad = execute(runner, a, on_poll)
        except RuntimeError as e:
            print(f"bench/sweep {sw.name}: {e}", file=sys.stderr)
            return 1
        except KeyboardInterrupt:
            print(f"bench/sweep {sw.name}: interrupted; finished steps are cached: run the same command again "
                  "to resume", file=sys.stderr)
            return 130
        if bad:
            print(f"bench/sweep {sw.name}: {len(bad)} of its steps did not finish:", file=sys.stderr)
            for tid, rec in sorted(bad.items()):
                print(f"  {tid}: {rec['state']}: {rec['error']}" + (f"\n    log: {rec['log']}" if rec.get("log") else ""),
                      file=sys.stderr)
            print("  (finished steps are cached; run the same command again to resume; "
                  f"`bench/sweep status {sw.name}` lists every step)", file=sys.stderr)
            return 1
        rows = runner.collect()
        secs = datetime.datetime.now().timestamp() - t0
        cmd = "bench/sweep run " + " ".join(sys.argv[2:] if argv is None else argv[1:])
        write_atomic(out / "MACHINE.md", machine_note(sw, cmd, secs, rows, a))
        print(f"{sw.name}: {len(rows)} rows -> {out / (sw.name + '.csv')}")
    rows = sweeplib.read_csv(out / f"{sw.name}.csv")
    for f in plots.draw(sw.name, rows, out):
        print(f"  plot {f}")
    print(f"  tables {report.write(sw.name, rows, out)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
