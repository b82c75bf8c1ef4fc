"""The timing proxy (bench/area/yosys_timing.sh, bench/sweeplib/area.py's parse_sta and timing,
bench/area/afu_timing.py): reading Yosys's sta reports, the blocks an AFU is cut into, and one
real run of Yosys on registered adders of two widths.
Run with the suite: tools/pyenv -m unittest discover -s bench/tests -v"""
import csv
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench" / "area"))

from sweeplib import area  # noqa: E402
import afu_timing  # noqa: E402

# Two sta reports as Yosys 0.23 writes them: a register-to-register path, then one ending at a
# black box's input (<unknown>), with a warning inside it.
LOG = """
7. Executing STA pass (static timing analysis).
Warning: Module 'MISTRAL_CLKBUF' has no timing arcs!
Latest arrival time in 'top' is 2844:
    2844 s_MISTRAL_FF_Q (MISTRAL_FF.DATAIN)
           \\s_MISTRAL_FF_Q_DATAIN [15]
    2844 rb_MISTRAL_ALUT_ARITH_A_10 (MISTRAL_ALUT_ARITH.CI->SO)
           \\rb_MISTRAL_ALUT_ARITH_A_CO [14]
    2476 rb_MISTRAL_ALUT_ARITH_A_11 (MISTRAL_ALUT_ARITH.B->CO)
           \\rb [1]
    1200 x_MISTRAL_ALUT6_Q (MISTRAL_ALUT6.A->Q)
           \\rb [0]
     731 rb_MISTRAL_FF_Q (MISTRAL_FF.CLK->Q)
           \\clk
       0   \\clk (<primary input>)

Arrival histogram:
(  1512,   1008] | 

12. Executing STA pass (static timing analysis).
Latest arrival time in 'top' is 7483:
    7483 (<unknown>)
Warning: Critical-path does not terminate in a recognised endpoint.
           \\_GEN_5 [2]
    7483 _GEN_5_MISTRAL_ALUT2_Q (MISTRAL_ALUT2.B->Q)
           \\io_a [3]
       0   \\io_a [3] (<primary input>)

13. Executing STA pass (static timing analysis).
No timing paths found.
"""

ADDER = """module add{w}(input clk, input [{m}:0] a, input [{m}:0] b, output reg [{m}:0] s);
  reg [{m}:0] ra, rb;
  always @(posedge clk) begin ra <= a; rb <= b; s <= ra + rb; end
endmodule
"""


class ParseSta(unittest.TestCase):
    def test_each_report_gives_its_delay_its_ends_and_the_logic_on_its_path(self):
        a, b, c = area.parse_sta(LOG)
        # The launching register and the endpoint are named by their RTL signals; the clock
        # input and both registers are not logic on the path.
        self.assertEqual(a, {"ps": 2844, "to": "s", "from": "rb", "luts": 1, "carry": 2, "dsp": 0, "cells": 3})
        self.assertEqual(b, {"ps": 7483, "to": "<black box>", "from": "io_a", "luts": 1, "carry": 0, "dsp": 0, "cells": 1})
        self.assertIsNone(c)


class AfuBlocks(unittest.TestCase):
    SV = ("module mem_x(\n  input a\n);\n  reg [3:0] Memory[0:7];\nendmodule\n"
          "module Gen_x(\n  input a\n);\n  mem_x m (\n    .a(a)\n  );\nendmodule\n"
          "module BroadPhase_x(\n  input a\n);\n  Gen_x g0 (\n    .a(a)\n  );\n  Gen_x g1 (\n    .a(a)\n  );\nendmodule\n"
          "module Puc_x(\n  input a\n);\n  BroadPhase_x b (\n    .a(a)\n  );\n  mem_x t (\n    .a(a)\n  );\nendmodule\n"
          "module Scpu_x(\n  input a\n);\nendmodule\n"
          "module Afu_x(\n  input a\n);\n  Puc_x p (\n    .a(a)\n  );\n  Scpu_x s0 (\n    .a(a)\n  );\n"
          "  Scpu_x s1 (\n    .a(a)\n  );\n  Scpu_x s2 (\n    .a(a)\n  );\nendmodule\n")

    def test_the_afu_the_puc_and_the_broad_phase_are_split_and_counts_multiply_down(self):
        rows = area.afu_blocks(self.SV, "Afu_x")
        self.assertEqual([(m, n, what) for m, n, _, what in rows],
                         [("Afu_x", 1, "every block below"), ("Puc_x", 1, "every block below"),
                          ("Scpu_x", 3, "RAMs"), ("BroadPhase_x", 1, "every block below"), ("Gen_x", 2, "RAMs")])
        self.assertEqual(rows[1][2], {"BroadPhase_x", "mem_x"})
        self.assertEqual(rows[4][2], {"mem_x"})

    def test_a_folder_without_a_manifest_or_its_top_is_refused_by_name(self):
        with tempfile.TemporaryDirectory() as d:
            with self.assertRaises(SystemExit) as e:
                afu_timing.afu(Path(d))
            self.assertIn("no manifest.json", str(e.exception.code))
            (Path(d) / "manifest.json").write_text('{"id": "x", "topModule": "Afu_x"}')
            with self.assertRaises(SystemExit) as e:
                afu_timing.afu(Path(d))
            self.assertIn("no Afu_x.sv", str(e.exception.code))


RAM_FED = """(* blackbox *)
module ram_x(input clk, input [3:0] a, output [15:0] q);
endmodule
module top_x(input clk, input [3:0] a, output reg [15:0] s);
  wire [15:0] q;
  ram_x r (.clk(clk), .a(a), .q(q));
  always @(posedge clk) s <= q + 16'd1;
endmodule
"""


class YosysTiming(unittest.TestCase):
    def run_adder(self, width: int, d: Path) -> list:
        sv = d / f"add{width}.v"
        sv.write_text(ADDER.format(w=width, m=width - 1))
        log = d / f"add{width}.log"
        subprocess.run(["bash", str(ROOT / "bench/area/yosys_timing.sh"), str(sv), f"add{width}", str(log)], check=True)
        return area.parse_sta(log.read_text())

    def test_a_registered_adder_is_a_carry_chain_between_registers_and_a_wider_one_is_slower(self):
        with tempfile.TemporaryDirectory() as d:
            narrow, wide = self.run_adder(8, Path(d)), self.run_adder(32, Path(d))
        self.assertEqual(len(narrow), len(area.TIMING_FAMILIES))
        for n, w in zip(narrow, wide):
            # A register launches it (the clock buffer is left out, so flip-flops launch paths).
            self.assertIn(n["from"], ("ra", "rb"))
            self.assertEqual(n["to"], "s")
            self.assertEqual((n["carry"], w["carry"]), (8, 32))
            self.assertGreater(w["ps"], n["ps"] + 20 * 20)  # 24 more carry cells, each tens of ps

    def test_a_path_from_a_black_box_is_seen_only_when_the_black_box_is_everted(self):
        with tempfile.TemporaryDirectory() as d:
            sv = Path(d) / "top.v"
            sv.write_text(RAM_FED)
            reports = []
            for black in ([], ["ram_x"]):
                log = Path(d) / f"top{len(black)}.log"
                subprocess.run(["bash", str(ROOT / "bench/area/yosys_timing.sh"), str(sv), "top_x", str(log), *black], check=True)
                reports.append(area.parse_sta(log.read_text()))
        # A black box has no timing arcs: nothing reaches s (the slowest path is s's own to the
        # output); everted, its output starts the adder into s.
        for rep in reports[0]:
            self.assertEqual((rep["from"], rep["to"], rep["carry"]), ("s", "<output>", 0))
        for rep in reports[1]:
            self.assertEqual(rep["to"], "s")
            self.assertGreater(rep["carry"], 0)


class AfuTimingCli(unittest.TestCase):
    def test_an_only_that_matches_nothing_or_is_not_a_regex_is_refused_by_name(self):
        with tempfile.TemporaryDirectory() as d:
            (Path(d) / "manifest.json").write_text('{"id": "x", "topModule": "Afu_x"}')
            (Path(d) / "Afu_x.sv").write_text(AfuBlocks.SV)
            with self.assertRaises(SystemExit) as e:
                afu_timing.main([d, "--only", "Nothing_", "--out", str(Path(d) / "t.csv")])
            self.assertIn("--only 'Nothing_': no block", str(e.exception.code))
            with self.assertRaises(SystemExit) as e:
                afu_timing.main([d, "--only", "(", "--out", str(Path(d) / "t.csv")])
            self.assertIn("not a regular expression", str(e.exception.code))

    def test_area_adds_each_blocks_cells_beside_its_path(self):
        # A two-SCPU AFU whose SCPU is a registered 8-bit adder: 24 flip-flops and a carry
        # chain; the caches go to a temporary folder, not the repository's build tree.
        sv = ("module Scpu_t(input clk, input [7:0] a, input [7:0] b, output reg [7:0] s);\n"
              "  reg [7:0] ra, rb;\n  always @(posedge clk) begin ra <= a; rb <= b; s <= ra + rb; end\nendmodule\n"
              "module Afu_t(input clk, input [7:0] a, input [7:0] b, output [7:0] s0, output [7:0] s1);\n"
              "  Scpu_t u0 (\n    .clk(clk), .a(a), .b(b), .s(s0)\n  );\n"
              "  Scpu_t u1 (\n    .clk(clk), .a(b), .b(a), .s(s1)\n  );\nendmodule\n")
        with tempfile.TemporaryDirectory() as d:
            (Path(d) / "manifest.json").write_text('{"id": "t", "topModule": "Afu_t"}')
            (Path(d) / "Afu_t.sv").write_text(sv)
            out = Path(d) / "t.csv"
            saved = area.CACHE, area.BUILD
            area.CACHE, area.BUILD = Path(d) / "cache", Path(d) / "build"
            try:
                afu_timing.main([d, "--only", "^Scpu_", "--area", "--out", str(out)])
                rows = list(csv.DictReader(out.open()))
                afu_timing.main([d, "--only", "^Scpu_", "--out", str(out)])
                plain = list(csv.DictReader(out.open()))
                (Path(d) / "Afu_t.sv").write_text(sv.replace("s <= ra + rb", "s <= ra - rb"))
                afu_timing.main([d, "--only", "^Scpu_", "--out", str(out)])
                other = list(csv.DictReader(out.open()))
            finally:
                area.CACHE, area.BUILD = saved
        self.assertEqual([(r["module"], r["count"]) for r in rows], [("Scpu_t", "2")])
        self.assertEqual(rows[0]["ff"], "24")
        self.assertGreater(int(rows[0]["arith"]) + int(rows[0]["luts"]), 0)
        self.assertEqual(rows[0]["path_to"], "s")
        # Without --area, an area already measured for this Verilog is reported; none for other Verilog.
        self.assertEqual(plain[0]["ff"], "24")
        self.assertEqual(plain[0]["cyclonev_ps"], rows[0]["cyclonev_ps"])
        self.assertEqual([other[0][k] for k in ("luts", "arith", "dsp", "ff")], ["", "", "", ""])


class CommittedResults(unittest.TestCase):
    """The committed proxy figures of the presets belong to the committed Verilog: each row of
    bench/results/timing/afu.csv names the commit whose generated/<folder> it timed, and that
    folder's Verilog must not have changed since (or the figures describe another design)."""

    def git(self, *args):
        return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True)

    def test_each_preset_row_names_a_commit_whose_verilog_is_the_committed_one(self):
        if self.git("rev-parse", "--is-shallow-repository").stdout.strip() != "false":
            self.skipTest("needs the repository's history (a full clone)")
        with open(ROOT / "bench/results/timing/afu.csv") as f:
            pairs = {(r["folder"], r["commit"]) for r in csv.DictReader(f)}
        self.assertTrue(pairs)
        for folder, commit in sorted(pairs):
            self.assertNotIn("+changes", commit, f"afu.csv's {folder} rows timed uncommitted Verilog")
            self.assertEqual(self.git("cat-file", "-e", f"{commit}^{{commit}}").returncode, 0,
                             f"afu.csv's {folder} rows name {commit}, not a commit of this repository")
            diff = self.git("diff", "--stat", commit, "HEAD", "--", f"generated/{folder}/*.sv")
            self.assertEqual(diff.stdout.strip(), "",
                             f"generated/{folder} changed since {commit}, whose Verilog afu.csv timed: run "
                             f"tools/pyenv bench/area/afu_timing.py generated/world generated/default again")



class ReachedClock(unittest.TestCase):
    """bench/area/reached_clock.py: each folder's timing.json, the clock its Verilog reaches."""

    def test_the_slowest_block_of_each_family_sets_the_clock_and_the_verilog_is_named_by_hash(self):
        import reached_clock
        with tempfile.TemporaryDirectory() as d:
            folder = Path(d) / "x"
            folder.mkdir()
            (folder / "Afu_x.sv").write_text("module Afu_x; endmodule\n")
            rows = [{"folder": "x", "module": "A", "cyclonev_ps": "5000", "arriav_ps": "9000"},
                    {"folder": "x", "module": "B", "cyclonev_ps": "20000", "arriav_ps": "4000"},
                    {"folder": "y", "module": "C", "cyclonev_ps": "90000", "arriav_ps": "90000"}]
            pnr = Path(d) / "pnr.csv"
            pnr.write_text("op,routed_over_cyclonev\nadd,1.5\nmul,2.0\nsqrt,\nrecip,1.0\n")
            t = reached_clock.describe(folder, rows, "abc1234", pnr)
            self.assertEqual(t["families"]["cyclonev"], {"slowest_block": "B", "cells_ps": 20000, "proxy_mhz": 50.0,
                                                         "routed_estimate_mhz": 33.33})
            self.assertEqual(t["families"]["arriav"]["slowest_block"], "A")
            self.assertEqual(t["routing_model"]["ratio"], 1.5)
            self.assertEqual(t["routing_model"]["operators"], 3)
            self.assertEqual(list(t["verilog"]), ["Afu_x.sv"])
            self.assertEqual(t["verilog"]["Afu_x.sv"], reached_clock.sha256(folder / "Afu_x.sv"))
            with self.assertRaises(SystemExit) as e:
                reached_clock.describe(Path(d) / "z", rows, "abc1234", pnr)
            self.assertIn("no rows of it", str(e.exception))

    def test_a_folder_whose_blocks_all_have_their_area_gets_its_alms_against_its_part(self):
        import json
        import reached_clock
        with tempfile.TemporaryDirectory() as d:
            folder = Path(d) / "x"
            folder.mkdir()
            (folder / "Afu_x.sv").write_text("module Afu_x; endmodule\n")
            (folder / "manifest.json").write_text(json.dumps({"device": {"name": "P", "alms": 1000, "dspBlocks": 10}}))
            rows = [{"folder": "x", "module": "A", "count": "1", "cyclonev_ps": "5000", "arriav_ps": "4000",
                     "luts": "100", "arith": "40", "ff": "400", "dsp": "1"},
                    {"folder": "x", "module": "S", "count": "3", "cyclonev_ps": "4000", "arriav_ps": "3000",
                     "luts": "50", "arith": "20", "ff": "40", "dsp": "2"}]
            pnr = Path(d) / "pnr.csv"
            pnr.write_text("op,routed_over_cyclonev\nadd,1.5\n")
            a = reached_clock.describe(folder, rows, "abc1234", pnr)["area"]
            # 250 LUTs, 100 adder cells, 520 FFs, 7 DSPs: packed max(175, 130), unpacked 350.
            self.assertEqual((a["luts"], a["arith"], a["ff"], a["dsp"]), (250, 100, 520, 7))
            self.assertEqual(a["alms"], {"packed": 175, "unpacked": 350})
            # With the LUTs by their inputs, the count by ALM shapes, block by block: A takes
            # 20 + 30 (its 5-input LUTs beside 20 of its small ones) + 15 (30 4-input LUTs two an
            # ALM) + 20 adder ALMs = 85, under its 100 flip-flop ALMs; each S 10 + 20 + 10 = 40.
            rows[0] |= {"lut6": "20", "lut5": "30", "lut4": "30", "lut3": "20"}
            rows[1] |= {"lut6": "10", "lut5": "0", "lut4": "20", "lut3": "20"}
            a = reached_clock.describe(folder, rows, "abc1234", pnr)["area"]
            self.assertEqual(a["alms"], {"packed": 175, "unpacked": 350, "by_size": 100 + 3 * 40})
            self.assertEqual(a["device"]["alms_share"], {"packed": 0.175, "unpacked": 0.35, "by_size": 0.22})
            self.assertEqual(a["device"]["dsp_share"], 0.7)
            rows[1]["ff"] = ""  # one block without its area: no area at all, rather than a partial sum
            self.assertNotIn("area", reached_clock.describe(folder, rows, "abc1234", pnr))

    def test_the_committed_timing_json_describes_the_committed_verilog_and_afu_csv(self):
        import json
        import reached_clock
        with open(ROOT / "bench/results/timing/afu.csv") as f:
            rows = list(csv.DictReader(f))
        for name in sorted({r["folder"] for r in rows}):
            folder = ROOT / "generated" / name
            have = json.loads((folder / "timing.json").read_text())
            commit = next(r["commit"] for r in rows if r["folder"] == name)
            self.assertEqual(have, reached_clock.describe(folder, rows, commit),
                             f"generated/{name}/timing.json is stale: run tools/pyenv bench/area/reached_clock.py generated/{name}")
