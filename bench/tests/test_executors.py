"""Tests of the executors' own logic without builds or a cluster: the local executor's
scheduling, task records, the plan a sweep makes, Slurm job sizes, the shared-storage check
and `status`. Run: tools/pyenv -m unittest discover -s bench/tests -v"""
import sys
import tempfile
import threading
import unittest
from pathlib import Path
from unittest import mock


from sweeplib import local  # noqa: E402
from sweeplib import slurm  # noqa: E402
from sweeplib import status  # noqa: E402
from sweeplib import storage  # noqa: E402
from sweeplib import sweep  # noqa: E402
from sweeplib import tasks  # noqa: E402
from sweeplib.sweeps import SWEEPS, Sweep  # noqa: E402


class Fake:
    """Tasks whose actions log when they start and end, and may fail."""

    def __init__(self):
        self.events, self.lock, self.finished = [], threading.Lock(), set()

    def task(self, tid, deps=(), fail=False, body=None, done=False):
        if done:
            self.finished.add(tid)

        def act():
            with self.lock:
                self.events.append(("start", tid))
            if body:
                body()
            if fail:
                raise RuntimeError(f"{tid} broke; see /x/{tid}.log")
            with self.lock:
                self.events.append(("end", tid))
                self.finished.add(tid)
        return tasks.Task(tid, "run", tuple(deps), 1.0, act, lambda: tid in self.finished)


class LocalExecutor(unittest.TestCase):
    def run_all(self, ts, jobs=2):
        with tempfile.TemporaryDirectory() as d:
            recs = tasks.Records(Path(d))
            bad = local.run(ts, recs, jobs, "test")
            return bad, {t.id: recs.read(t.id) for t in ts}

    def test_a_task_starts_only_after_every_task_it_needs_has_ended(self):
        f = Fake()
        ts = [f.task("gen"), f.task("b1", ["gen"]), f.task("b2", ["gen"]), f.task("r1", ["b1"]),
              f.task("r2", ["b1", "b2"])]
        bad, _ = self.run_all(ts)
        self.assertEqual(bad, {})
        at = {e: i for i, e in enumerate(f.events)}
        for t in ts:
            for d in t.deps:
                self.assertLess(at[("end", d)], at[("start", t.id)], f"{t.id} started before {d} ended")

    def test_independent_tasks_run_at_the_same_time(self):
        f = Fake()
        both = threading.Barrier(2, timeout=30)  # passes only if the two bodies run at once
        ts = [f.task("a", body=both.wait), f.task("b", body=both.wait)]
        bad, _ = self.run_all(ts, jobs=2)
        self.assertEqual(bad, {})

    def test_with_one_job_no_two_tasks_overlap(self):
        f = Fake()
        ts = [f.task(f"t{i}") for i in range(4)]
        self.run_all(ts, jobs=1)
        kinds = [k for k, _ in f.events]
        self.assertEqual(kinds, ["start", "end"] * 4)

    def test_a_failure_stops_what_needs_it_and_nothing_else_and_every_failure_is_reported(self):
        f = Fake()
        ts = [f.task("b1", fail=True), f.task("b2"), f.task("b3", fail=True), f.task("r1", ["b1"]),
              f.task("r2", ["b2"])]
        bad, recs = self.run_all(ts)
        self.assertEqual(sorted(bad), ["b1", "b3", "r1"])
        self.assertEqual((bad["b1"]["state"], bad["r1"]["state"]), ("failed", "skipped"))
        self.assertIn("/x/b1.log", bad["b1"]["error"])
        self.assertIn("needs b1", bad["r1"]["error"])
        self.assertEqual(recs["r2"]["state"], "done")
        self.assertNotIn(("start", "r1"), f.events)

    def test_done_tasks_are_not_run_again(self):
        f = Fake()
        ts = [f.task("gen", done=True), f.task("b", ["gen"])]
        self.run_all(ts)
        self.assertEqual(f.events, [("start", "b"), ("end", "b")])

    def test_a_record_names_the_node_and_the_error(self):
        f = Fake()
        _, recs = self.run_all([f.task("x", fail=True)])
        self.assertEqual((recs["x"]["state"], recs["x"]["node"]), ("failed", tasks.node()))
        self.assertEqual(recs["x"]["error"], "x broke; see /x/x.log")


class Plan(unittest.TestCase):
    def plan(self, name, area=True):
        return {t.id: t for t in sweep.Runner(SWEEPS[name], Path("/tmp/x"), area, 0, Path("/tmp/w")).tasks()}

    def test_the_arith_plan_synthesizes_each_scpu_once_and_runs_each_scene_after_its_build(self):
        p = self.plan("arith")
        self.assertEqual(len([t for t in p.values() if t.kind == "area"]), 10)  # no PUC: puc_area=False
        self.assertEqual(p["area/n16_fp64/scpu"].size, "big")
        self.assertEqual(p["accuracy"].deps, ("generate",))  # two sbt sessions cannot share target/
        self.assertEqual(p["run/n16_fp16/diamond_h10_s1/qpi"].deps, ("build/n16_fp16",))
        self.assertIn("run/n16_fp32/diamond_h10_s6/ode", p)  # the drift's ODE reference

    def test_the_arith_plan_times_each_scpu_once_and_runs_its_links_at_the_cells_clock_after_both_parts(self):
        p = self.plan("arith")
        self.assertEqual(len([i for i in p if i.startswith("timing/") and i.endswith("/scpu")]), 10)
        self.assertEqual(len([i for i in p if i.startswith("timing/") and i.endswith("/rest")]), 10)
        self.assertEqual(p["timing/n16_fp64/scpu"].size, "big")
        self.assertEqual(p["run/n16_fp16/diamond_h10_s1/ideal@cells"].deps,
                         ("build/n16_fp16", "timing/n16_fp16/scpu", "timing/n16_fp16/rest"))
        self.assertEqual(p["run/n16_fp16/diamond_h10_s1/qpi"].deps, ("build/n16_fp16",))  # not held back by Yosys
        off = self.plan("arith", area=False)
        self.assertFalse([i for i in off if i.startswith("timing/") or i.endswith("@cells")])

    def test_the_scpus_plan_synthesizes_one_scpu_and_every_puc(self):
        p = self.plan("scpus")
        self.assertEqual(sorted(i for i in p if i.endswith("/scpu")), ["area/n1_fp32/scpu"])
        self.assertEqual(len([i for i in p if i.endswith("/puc")]), 6)
        self.assertNotIn("area/n1_fp32/scpu", self.plan("scpus", area=False))

    def test_a_runner_comes_back_the_same_from_its_settings(self):
        r = sweep.Runner(SWEEPS["links"], Path("/tmp/out"), False, 4, Path("/tmp/w"))
        back = sweep.Runner.from_settings(r.settings())
        self.assertEqual(back.sweep, r.sweep)
        self.assertEqual((back.out, back.do_area, back.cpu_repeat, back.state), (r.out, False, 4, r.state))
        self.assertEqual(Sweep.from_dict(SWEEPS["arith"].to_dict()), SWEEPS["arith"])


class SlurmJobs(unittest.TestCase):
    def test_a_job_is_sized_by_its_step_and_the_flags_replace_the_sizes(self):
        o = slurm.Options()
        self.assertEqual(o.sbatch("run", "normal"), ["--cpus-per-task=1", "--mem=2G", "--time=0:30:00"])
        self.assertEqual(o.sbatch("area", "big")[1:], ["--mem=16G", "--time=12:00:00"])
        o = slurm.Options(partition="p", account="a", time="9:00", mem="1G", sbatch_args=["--qos=x"])
        self.assertEqual(o.sbatch("area", "big"), ["--cpus-per-task=1", "--mem=1G", "--time=9:00",
                                                    "--partition=p", "--account=a", "--qos=x"])

    def test_every_kind_and_size_the_plans_make_has_a_size(self):
        for s in SWEEPS.values():
            for t in sweep.Runner(s, Path("/tmp/x"), True, 0, Path("/tmp/w")).tasks():
                self.assertIn((t.kind, t.size), slurm.RESOURCES, t.id)


class SharedStorage(unittest.TestCase):
    def test_a_local_filesystem_is_refused_when_other_nodes_would_run_tasks(self):
        with mock.patch.object(storage, "fs_type", return_value="ext2/ext3"):
            with self.assertRaisesRegex(RuntimeError, r"/repo is on a local ext2/ext3 filesystem, so the nodes n2"):
                storage.check([Path("/repo")], ["here", "n2"], "here")
            storage.check([Path("/repo")], ["here"], "here")  # a one-node cluster on this machine
        with mock.patch.object(storage, "fs_type", return_value="nfs"):
            storage.check([Path("/repo")], ["n1", "n2"], "here")

    def test_this_checkout_has_a_filesystem_type(self):
        self.assertRegex(storage.fs_type(Path(__file__)), r"\S")


class Status(unittest.TestCase):
    def test_each_task_is_reported_from_its_cache_and_record(self):
        f = Fake()
        ts = [f.task("gen", done=True), f.task("b", ["gen"]), f.task("c", ["gen"]), f.task("d", ["gen"])]
        with tempfile.TemporaryDirectory() as d:
            r = sweep.Runner(SWEEPS["smoke"], Path(d), False, 0, Path(d))
            recs = tasks.Records(r.exec / "records")
            recs.write("b", state="failed", error="it broke; see x.log", node="n")
            recs.write("c", state="running", node="elsewhere", pid=1)
            st = status.states(r, ts)
            self.assertEqual(st["gen"][0], "done")
            self.assertEqual(st["b"], ("failed", "it broke; see x.log"))
            self.assertEqual(st["c"][0], "interrupted")
            self.assertEqual(st["d"], ("to do", ""))
            text = status.report(r, ts)
            self.assertIn("smoke: 1 done, 1 failed, 1 interrupted, 1 to do", text)
            self.assertIn("failed      b: it broke; see x.log", text)


if __name__ == "__main__":
    unittest.main()
