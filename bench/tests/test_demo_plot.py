"""tools/demo_plot.py (the demo's picture) on small generated inputs: it writes a non-empty PNG,
and a bad input names the file and the problem. Run with the suite:
tools/pyenv -m unittest discover -s bench/tests -v"""
import contextlib
import io
import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))

import demo_plot  # noqa: E402

CPU_HEADER = "step,pairs,contacts,other_contacts,backend_ns,ode_ns,simd_ns,simd64_ns,hit_mismatches\n"
RTL_HEADER = CPU_HEADER.rstrip("\n") + ",afu_runs,afu_modelled_ns,afu_cycles,afu_load,afu_compute,afu_wait_rd,afu_wait_wr\n"


class DemoPlot(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.d = Path(self.dir.name)
        steps = range(6)
        (self.d / "ode.csv").write_text(CPU_HEADER + "".join(
            f"{s},{5000 - s},{3000 + s},{s},{90000},{80000 + s},{20000 + s},{24000 + s},0\n" for s in steps))
        (self.d / "rtl.csv").write_text(RTL_HEADER + "".join(
            f"{s},{5000 - s},{3000 + s},0,1,1,1,1,0,1,{25000.5 + s},4000,300,400,300,2000\n" for s in steps))
        # %a as collide writes it, and plain decimals
        (self.d / "pos.csv").write_text("sphere,x,y,z\n0,0x1p-1,-0x1.8p+0,0x1p+2\n1,0.25,0.5,4.5\n2,0x0p+0,0x0p+0,0x1.2p+2\n")

    def tearDown(self):
        self.dir.cleanup()

    def run_plot(self, *args):
        err = io.StringIO()
        with contextlib.redirect_stderr(err):
            rc = demo_plot.main([str(a) for a in args])
        return rc, err.getvalue()

    def test_writes_a_png_with_every_panel(self):
        out = self.d / "demo.png"
        rc, err = self.run_plot(out, "--title", "t", "--cpu", self.d / "ode.csv",
                                "--afu", f"HARP v1 link={self.d / 'rtl.csv'}", "--positions", self.d / "pos.csv")
        self.assertEqual(rc, 0, err)
        self.assertNotIn("demo_plot:", err)  # (matplotlib's own deprecation warnings may show)
        data = out.read_bytes()
        self.assertEqual(data[:8], b"\x89PNG\r\n\x1a\n")
        self.assertGreater(len(data), 10_000)
        self.assertEqual(sorted(p.name for p in self.d.iterdir() if p.name.startswith(".")), [])  # no temporary left

    def test_an_unwritable_out_says_so_and_keeps_nothing_half_written(self):
        out = self.d / "no-such-dir" / "demo.png"
        rc, err = self.run_plot(out, "--cpu", self.d / "ode.csv")
        self.assertEqual(rc, 1)
        self.assertIn(f"demo_plot: {out}: cannot write", err)
        self.assertFalse(out.exists())

    def test_without_afu_or_positions_still_draws(self):
        out = self.d / "cpu.png"
        rc, err = self.run_plot(out, "--cpu", self.d / "ode.csv", "--cpu-label", "simd run")
        self.assertEqual(rc, 0, err)
        self.assertGreater(out.stat().st_size, 0)

    def test_hex_floats_are_read_as_collide_writes_them(self):
        pos = demo_plot.columns(self.d / "pos.csv", ["x", "y", "z"])
        self.assertEqual(pos["x"], [0.5, 0.25, 0.0])
        self.assertEqual(pos["y"], [-1.5, 0.5, 0.0])
        self.assertEqual(pos["z"], [4.0, 4.5, 4.5])

    def test_bad_inputs_name_the_file_and_the_problem(self):
        out = self.d / "x.png"
        rc, err = self.run_plot(out, "--cpu", self.d / "rtl.csv", "--afu", f"qpi={self.d / 'ode.csv'}")
        self.assertEqual(rc, 1)
        self.assertIn(f"demo_plot: {self.d / 'ode.csv'}: no column afu_modelled_ns", err)
        rc, err = self.run_plot(out, "--cpu", self.d / "missing.csv")
        self.assertEqual(rc, 1)
        self.assertIn("missing.csv: cannot read", err)
        rc, err = self.run_plot(out, "--cpu", self.d / "ode.csv", "--afu", "no-label")
        self.assertIn("expected LABEL=FILE", err)
        (self.d / "bad.csv").write_text("sphere,x,y,z\n0,1,zz,3\n")
        rc, err = self.run_plot(out, "--cpu", self.d / "ode.csv", "--positions", self.d / "bad.csv")
        self.assertIn("bad.csv:2: y: not a number: 'zz'", err)
        self.assertFalse(out.exists())


if __name__ == "__main__":
    unittest.main()
