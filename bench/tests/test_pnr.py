"""The ECP5 place-and-route flow (bench/area/pnr_ecp5.py): reading nextpnr's report, and the
whole flow, Yosys synth_ecp5 then nextpnr-ecp5, on one small block the generator writes (an fp16
adder between registers), so the flow cannot rot. About a minute: sbt writes the Verilog, the
two tools take seconds.
Run with the suite: tools/pyenv -m unittest discover -s bench/tests -v"""
import csv
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench" / "area"))

import pnr_ecp5  # noqa: E402

# A report as nextpnr-ecp5 0.11 writes it (--report), cut to the fields the flow reads.
REPORT = {
    "fmax": {"clock": {"achieved": 131.94, "constraint": 100}},
    "critical_paths": [{"from": {"cell": "a"}, "to": {"cell": "b"}, "path": [
        {"type": "clk-to-q", "delay": 0.525}, {"type": "routing", "delay": 0.954}, {"type": "logic", "delay": 0.236},
        {"type": "routing", "delay": 1.079}, {"type": "logic", "delay": 0.447}, {"type": "setup", "delay": 0.0}]}],
    "utilization": {"TRELLIS_COMB": {"available": 83640, "used": 755}, "TRELLIS_FF": {"available": 83640, "used": 346},
                    "MULT18X18D": {"available": 156, "used": 4}},
}


class Summary(unittest.TestCase):
    def test_the_critical_path_splits_into_logic_and_routing_and_resources_carry_their_totals(self):
        row = pnr_ecp5.summarize(REPORT)
        self.assertEqual(row["fmax_mhz"], "131.9")
        self.assertEqual((row["logic_ns"], row["routing_ns"], row["path_ns"]), ("1.21", "2.03", "3.24"))
        self.assertEqual((row["luts"], row["luts_of"], row["dsp"], row["dsp_of"]), (755, 83640, 4, 156))
        self.assertEqual((row["bram"], row["bram_of"]), (0, ""))  # a cell the design does not use

    def test_a_missing_file_is_refused_by_name(self):
        with self.assertRaises(SystemExit) as e:
            pnr_ecp5.run(["/nonexistent/x.sv"])
        self.assertIn("/nonexistent/x.sv: no such Verilog file", str(e.exception.code))


class Flow(unittest.TestCase):
    def test_an_fp16_adder_places_and_routes_on_an_ecp5_85f_with_its_clock_and_cells(self):
        with tempfile.TemporaryDirectory() as d:
            gen = subprocess.run([str(ROOT / "tools/sbt"),
                                  f"runMain collide.fp.report.OperatorGen --op add --format fp16 --latency 3 --out {d}"],
                                 capture_output=True, text=True)
            self.assertEqual(gen.returncode, 0, gen.stdout[-3000:])
            sv = Path(d) / "Timed_FpAdd_fp16_L3.sv"
            self.assertTrue(sv.exists(), gen.stdout[-3000:])
            out = Path(d) / "pnr.csv"
            pnr_ecp5.main([str(sv), "--out", str(out), "--work", str(Path(d) / "work")])
            row = next(csv.DictReader(out.open()))
        self.assertEqual(row["top"], "Timed_FpAdd_fp16_L3")
        fmax, path = float(row["fmax_mhz"]), float(row["path_ns"])
        # nextpnr's Fmax is the critical path's reciprocal; routing is part of it, and the
        # adder takes hundreds of LUT4s, 16 + 16 + 4 input and 21 output flip-flops at least.
        self.assertGreater(fmax, 10)
        self.assertAlmostEqual(1000 / fmax, path, delta=0.05 * path)
        self.assertGreater(float(row["routing_ns"]), 0)
        self.assertGreater(int(row["luts"]), 100)
        self.assertGreaterEqual(int(row["ff"]), 57)
        self.assertEqual(int(row["luts_of"]), 83640)


if __name__ == "__main__":
    unittest.main()
