"""The Slurm executor against a real one-node Slurm cluster that these tests start
(slurm_cluster.py: temporary directory, free ports, stopped afterwards even when a test fails).

End to end, like SmokeSweep: they need the smoke sweep's generated Verilog and host build
(made once, shared with SmokeSweep), so they run with COLLIDE_SWEEP_SMOKE=1, as tools/test
sets it. As anyone but root they fail, saying why (slurmd must run as root). Each test runs
in its own work folder (runs, records, jobs, logs), so the scene runs are redone each time."""
import dataclasses
import os
import shutil
import subprocess
import sys
import tempfile
import time
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from sweeplib import build  # noqa: E402
from sweeplib import slurm  # noqa: E402
import slurm_cluster  # noqa: E402
from sweeplib import slurmctl  # noqa: E402
from sweeplib import status  # noqa: E402
from sweeplib import sweep  # noqa: E402
from sweeplib.paths import BUILD, EXEC  # noqa: E402
from sweeplib.sweeps import SWEEPS  # noqa: E402

SMOKE = os.environ.get("COLLIDE_SWEEP_SMOKE") == "1"
CLUSTER = None


def setUpModule():
    global CLUSTER
    if not SMOKE:
        return
    CLUSTER = slurm_cluster.Cluster()
    unittest.addModuleCleanup(CLUSTER.__exit__, None, None, None)  # also after a failed test
    CLUSTER.__enter__()
    old = os.environ.get("SLURM_CONF")
    os.environ["SLURM_CONF"] = CLUSTER.env["SLURM_CONF"]  # the executor's sbatch/squeue talk to it
    unittest.addModuleCleanup(lambda: os.environ.pop("SLURM_CONF") if old is None else
                              os.environ.__setitem__("SLURM_CONF", old))


def smoke(work: Path, links=("ideal",)) -> sweep.Runner:
    return sweep.Runner(dataclasses.replace(SWEEPS["smoke"], links=links), work / "out", True, 0, work)


def through_slurm(runner, on_poll=None, **opts):
    drv = slurm.Driver(runner, slurm.Options(poll=0.3, **opts), on_poll)
    return drv, drv.run(runner.tasks(), runner.write_plan())


def rebuild_through_slurm():
    """Makes the (already built) smoke binary stale, so its build runs as a Slurm task too
    (a no-op for Ninja: seconds)."""
    cfg = SWEEPS["smoke"].configs[0]
    (build.HOST / cfg.id / ".sweep-key").unlink(missing_ok=True)


def active(job_ids) -> list:
    return [k for k, (state, _, _) in slurmctl.queue().items()
            if k.split("_")[0] in job_ids and state in slurmctl.ACTIVE]


@unittest.skipUnless(SMOKE, "end to end (a one-node Slurm cluster, the smoke sweep's builds): "
                            "set COLLIDE_SWEEP_SMOKE=1, as tools/test does")
class SlurmExecutor(unittest.TestCase):
    def test_the_smoke_sweep_through_slurm_gives_the_local_executors_csv_apart_from_timings(self):
        from sweeplib import cli
        with tempfile.TemporaryDirectory() as d:
            self.assertEqual(cli.main(["run", "smoke", "--out", f"{d}/local"]), 0)  # cached after SmokeSweep
            # The Slurm run redoes the runs and the build (a no-op for Ninja); the Verilog stays cached.
            shutil.rmtree(BUILD / "runs" / "smoke")
            shutil.rmtree(EXEC / "smoke")
            rebuild_through_slurm()
            seen = []
            self.assertEqual(cli.main(["run", "smoke", "--executor", "slurm", "--poll", "0.3", "--out", f"{d}/slurm"],
                                      on_poll=seen.append), 0)
            drv = seen[0]
            self.assertEqual(sorted(drv.submitted), ["build/n2_fp32", "run/n2_fp32/diamond_h2_s1/ideal",
                                                     "run/n2_fp32/diamond_h2_s3/ideal", "run/n2_fp32/diamond_h2_s3/ode"])
            want, got = (sweep.read_csv(Path(d) / ex / "smoke.csv") for ex in ("local", "slurm"))
            drop = lambda rows: [{k: v for k, v in r.items() if k not in sweep.TIMING_COLUMNS} for r in rows]
            self.assertEqual(drop(got), drop(want))
            self.assertEqual(list(got[0]), list(want[0]))
            host = slurm_cluster.socket.gethostname().split(".")[0]
            self.assertEqual(got[0]["node"], host)
            note = (Path(d) / "slurm" / "MACHINE.md").read_text()
            self.assertIn("- executor: slurm\n", note)
            self.assertIn(f"- node {host} (the `node` column; its rows' timings): ", note)
            for tid in drv.submitted:  # one log per task, saying what ran
                self.assertIn(f"worker: {tid} done", Path(drv.jobs.map[tid]["log"]).read_text())

    def test_a_broken_configuration_is_reported_with_its_log_and_the_rest_still_runs(self):
        with tempfile.TemporaryDirectory() as d:
            r = smoke(Path(d), links=("ideal", "no-such-link"))
            drv, bad = through_slurm(r)
            broken = "run/n2_fp32/diamond_h2_s1/no-such-link"
            self.assertEqual(sorted(bad), [broken])
            rec = bad[broken]
            self.assertEqual(rec["state"], "failed")
            self.assertRegex(rec["error"], r"--link no-such-link failed \(105\); see .*stdout\.txt")
            log = Path(rec["log"]).read_text()
            self.assertIn(f"worker: {broken} failed: ", log)
            self.assertIn("no-such-link not in", (r.run_dir(r.sweep.configs[0], r.sweep.scenes[0], "rtl",
                                                            "no-such-link") / "stdout.txt").read_text())
            tasks = r.tasks()
            self.assertEqual([t.id for t in tasks if t.kind == "run" and not t.done()], [broken])
            text = status.report(r, tasks)
            self.assertIn(f"failed      {broken}: ", text)
            self.assertIn(f"(log: {rec['log']})", text)

    def test_a_task_that_slurm_ends_is_reported_with_slurms_reason(self):
        with tempfile.TemporaryDirectory() as d:
            r = smoke(Path(d))
            ode = "run/n2_fp32/diamond_h2_s3/ode"
            acted = []

            def cancel_one(drv):  # the run array is held: cancel one of its tasks, release the others
                if not acted:
                    j = drv.jobs.map[ode]
                    subprocess.run(["scancel", f"{j['job']}_{j['index']}"], check=True, capture_output=True)
                    subprocess.run(["scontrol", "release", j["job"]], check=True, capture_output=True)
                    acted.append(True)

            _, bad = through_slurm(r, on_poll=cancel_one, sbatch_args=["--hold"])
            self.assertEqual(sorted(bad), [ode])
            # squeue shows a pending array task it cancelled as CANCELLED, or no longer at all
            self.assertRegex(bad[ode]["error"], r"ended without a record of its result: (Slurm says CANCELLED|"
                                                r"it left the queue without a final state).*it left no log .*never started")

    def test_an_interrupted_sweep_cancels_its_jobs_and_resumes_without_redoing_what_finished(self):
        with tempfile.TemporaryDirectory() as d:
            r = smoke(Path(d))
            rebuild_through_slurm()

            def ctrl_c_once_built(drv):
                if (drv.records.read("build/n2_fp32") or {}).get("state") == "done":
                    raise KeyboardInterrupt

            drv = slurm.Driver(r, slurm.Options(poll=0.3), ctrl_c_once_built)
            with self.assertRaises(KeyboardInterrupt):
                drv.run(r.tasks(), r.write_plan())
            for _ in range(60):  # scancel is asynchronous: wait for the jobs to leave the running states
                if not active(drv.followed):
                    break
                time.sleep(0.5)
            self.assertEqual(active(drv.followed), [])
            left = sorted(t.id for t in r.tasks() if not t.done())
            self.assertNotIn("build/n2_fp32", left)
            self.assertTrue(left, "every run finished before the interrupt: nothing left to resume")
            again, bad = through_slurm(r)
            self.assertEqual(bad, {})
            self.assertEqual(sorted(again.submitted), left)
            self.assertEqual(len(r.collect()), 1)

    def test_a_sweep_resumed_while_its_jobs_are_queued_follows_them_instead_of_resubmitting(self):
        with tempfile.TemporaryDirectory() as d:
            r = smoke(Path(d))

            class DriverLost(Exception):
                pass

            def lose(drv):
                raise DriverLost  # the driver dies (a closed terminal), its jobs stay queued

            first = slurm.Driver(r, slurm.Options(poll=0.3, sbatch_args=["--hold"]), lose)
            with self.assertRaises(DriverLost):
                first.run(r.tasks(), r.write_plan())
            self.assertEqual(len(first.submitted), 3)
            self.assertEqual(len(active(first.followed)), 3)

            released = []

            def release(drv):  # once the driver follows the held jobs
                if not released:
                    subprocess.run(["scontrol", "release", *sorted(first.followed)], check=True, capture_output=True)
                    released.append(True)

            again, bad = through_slurm(r, on_poll=release)
            self.assertEqual(bad, {})
            self.assertEqual(again.submitted, [])
            self.assertEqual(again.followed, first.followed)
            self.assertEqual(len(r.collect()), 1)


if __name__ == "__main__":
    unittest.main()
