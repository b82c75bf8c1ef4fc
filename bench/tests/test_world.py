"""bench/world/world.py's clouds (no collide binary needed): the sizes asked for, every value
a binary32 value written exactly, about one contact a sphere in the uniform cloud.
Run with the suite: tools/pyenv -m unittest discover -s bench/tests -v"""
import contextlib
import io
import itertools
import json
import math
import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "world"))

import world  # noqa: E402
import afu_world  # noqa: E402
import lanes  # noqa: E402
import lanes_area  # noqa: E402
import fit_preset  # noqa: E402
import broad_phase_area  # noqa: E402


class WorldClouds(unittest.TestCase):
    def test_every_cloud_has_the_size_and_binary32_values(self):
        for kind in world.CLOUDS:
            spheres = world.cloud(kind, 500, 1)
            self.assertEqual(len(spheres), 500, kind)
            for s in spheres[:50]:
                self.assertEqual([world.f32(v) for v in s], s, kind)
                self.assertGreater(s[3], 0, kind)

    def test_the_uniform_cloud_has_about_one_contact_a_sphere(self):
        spheres = world.cloud("uniform", 1500, 2)
        contacts = sum(1 for a, b in itertools.combinations(spheres, 2)
                       if math.dist(a[:3], b[:3]) <= a[3] + b[3])
        self.assertGreater(contacts, 0.6 * 1500)  # the walls cost some
        self.assertLess(contacts, 1.2 * 1500)

    def test_the_diamond_is_the_largest_of_the_papers_diamonds_that_fits(self):
        for n, h in ((1, 1), (5, 1), (6, 2), (670, 10), (669, 9), (65536, 46)):
            self.assertEqual(world.diamond_hmax(n), h, n)
        spheres = world.cloud("diamond", 700, 1)
        self.assertEqual(len(spheres), 10 * (2 * 10 ** 2 + 1) // 3)
        self.assertEqual([world.f32(v) for s in spheres for v in s], [v for s in spheres for v in s])
        # Layer 1 (2 x 2 spheres, after the one-sphere apex): in-layer neighbours touch, d = 2r.
        layer = spheres[1:5]
        self.assertEqual(len({s[2] for s in layer}), 1)
        self.assertAlmostEqual(math.dist(layer[0][:3], layer[1][:3]), 0.2, places=6)
        self.assertEqual(spheres[0][:3], [0.0, 0.0, world.f32(4.2)])

    def test_the_csv_holds_exact_hex_floats(self):
        with tempfile.TemporaryDirectory() as d:
            p = Path(d) / "s.csv"
            spheres = world.cloud("mixed", 20, 3)
            world.write_cloud(p, spheres)
            lines = p.read_text().splitlines()
            self.assertEqual(lines[0], "x,y,z,r")
            self.assertEqual([[float.fromhex(v) for v in l.split(",")] for l in lines[1:]], spheres)


class AfuWorldReport(unittest.TestCase):
    def row(self, cloud, spheres, link):
        r = dict.fromkeys(["candidates", "contacts", "afu_ns", "link_bound_ns", "afu_over_bound", "runs", "slabs",
                           "cycles_broad", "ode_sap_ns", "simd_grid_ns", "ode_over_afu", "grid_over_afu"], 2.0)
        return r | {"cloud": cloud, "spheres": float(spheres), "link": link, "contacts": 3.0 * spheres}

    def test_an_earlier_csv_puts_its_time_beside_each_row_and_a_foreign_one_is_refused(self):
        with tempfile.TemporaryDirectory() as d:
            out = Path(d)
            rows = [self.row("uniform", 670, "qpi"), self.row("uniform", 2000, "qpi")]
            afu_world.report(rows, out, "## How and where\n", lanes=16, ports=8, compare={("uniform", 670, "qpi"): 4500.0})
            text = (out / "README.md").read_text()
            self.assertIn("| calls | AFU (us) | before (us) | link bound", text)
            self.assertIn("| 670 | 2,010 | qpi | 2 | 2 | 0.0 | 4.5 |", text)
            self.assertIn("| 2,000 | 6,000 | qpi | 2 | 2 | 0.0 | - |", text)  # no earlier row
            (out / "bad.csv").write_text("a,b\n1,2\n")
            with self.assertRaises(SystemExit) as e:
                afu_world.compared(str(out / "bad.csv"))
            self.assertIn("not a world-afu.csv", str(e.exception))

    def test_a_clock_of_zero_is_refused_before_any_work_not_taken_as_each_presets(self):
        with tempfile.TemporaryDirectory() as d:
            for bad in ("0", "-5"):
                with self.assertRaises(SystemExit) as e, contextlib.redirect_stderr(io.StringIO()) as err:
                    afu_world.main(["--clock-mhz", bad, "--collide", "/nonexistent/collide", "--out", d])
                self.assertEqual(e.exception.code, 2)
                self.assertIn("--clock-mhz", err.getvalue())
            self.assertEqual(list(Path(d).iterdir()), [])

    def test_a_negative_ode_bound_is_refused_before_any_work(self):
        with tempfile.TemporaryDirectory() as d:
            with self.assertRaises(SystemExit) as e, contextlib.redirect_stderr(io.StringIO()) as err:
                afu_world.main(["--skip-ode-above", "-1", "--collide", "/nonexistent/collide", "--out", d])
            self.assertEqual(e.exception.code, 2)
            self.assertIn("--skip-ode-above: -1 is not a sphere count", err.getvalue())
            self.assertEqual(list(Path(d).iterdir()), [])

    def test_rows_at_another_clock_say_so_and_rows_at_the_links_own_do_not(self):
        with tempfile.TemporaryDirectory() as d:
            out = Path(d)
            afu_world.report([self.row("uniform", 670, "qpi") | {"clock_mhz": 29.121, "clock_given": 1.0}], out, "", lanes=16, ports=8)
            self.assertIn("The AFU runs at 29.121 MHz here (`--clock-mhz`)", (out / "README.md").read_text())
            afu_world.report([self.row("uniform", 670, "qpi") | {"clock_mhz": 200.0, "clock_given": 0.0}], out, "", lanes=16, ports=8)
            self.assertNotIn("--clock-mhz", (out / "README.md").read_text())
            afu_world.report([self.row("uniform", 670, "qpi")], out, "", lanes=16, ports=8)  # an older CSV: no column
            self.assertNotIn("--clock-mhz", (out / "README.md").read_text())

    def test_a_world_without_ode_gets_a_dash_and_the_summary_says_where_ode_was_run(self):
        with tempfile.TemporaryDirectory() as d:
            out = Path(d)
            big = self.row("uniform", 1000000, "qpi") | {"ode_sap_ns": None, "ode_over_afu": None}
            afu_world.report([self.row("uniform", 670, "qpi"), big], out, "", lanes=16, ports=8)
            text = (out / "README.md").read_text()
            self.assertIn("| 1,000,000 | 3,000,000 | qpi | 2 | 2 | 0.0 | 0.0 | 2.0x | 2 | - | - | 0.0 | 2.00x |", text)
            self.assertIn("faster than ODE's sweep-and-prune space + dCollide (where it was run: `--skip-ode-above`)", text)
            self.assertIn("ODE's sweep-and-prune is left out of the rows marked -", text)
            afu_world.report([big], out, "", lanes=16, ports=8)  # no ODE at all: no ODE clause
            self.assertNotIn("faster than ODE's", (out / "README.md").read_text())
            # A CSV's empty cell reads back as a peer left out.
            self.assertIsNone(afu_world.parse({"cloud": "uniform", "link": "qpi", "ode_sap_ns": ""})["ode_sap_ns"])

    def test_a_run_of_the_ideal_link_alone_gets_its_report_and_says_harp_was_not_run(self):
        with tempfile.TemporaryDirectory() as d:
            out = Path(d)
            afu_world.report([self.row("uniform", 670, "ideal"), self.row("diamond", 3894, "ideal")], out, "", lanes=32, ports=16)
            text = (out / "README.md").read_text()
            self.assertIn("HARP v1's QPI link was not run here", text)
            self.assertNotIn("its link bound on HARP v1", text)

    def test_a_refused_world_is_listed_under_its_cloud_and_the_diamond_gets_its_section(self):
        with tempfile.TemporaryDirectory() as d:
            out = Path(d)
            (out / "refused.txt").write_text("diamond, 64,906 spheres (hMax 46), qpi: this world cannot be cut into runs\n")
            rows = [self.row("uniform", 670, "qpi"), self.row("diamond", 670, "qpi")]
            afu_world.report(rows, out, "## How and where\n", lanes=16, ports=2)
            text = (out / "README.md").read_text()
            self.assertIn("16 candidate lanes and its sort's passes 2 spheres a cycle", text)
            self.assertIn("within 2x only for uniform 670, diamond 670", text)  # both rows are 2.0x
            self.assertIn("## diamond (the paper's diamond", text)
            self.assertIn("- diamond, 64,906 spheres (hMax 46), qpi: this world cannot be cut into runs", text)
            self.assertNotIn("## clustered", text)  # no rows, no section
            self.assertIn("The diamond (close-packed: 3.0-3.0 contacts a sphere)", text)
            # The refusal sits in the diamond's section, not under uniform.
            self.assertLess(text.index("## diamond"), text.index("cannot be cut"))

    def test_re_running_one_cloud_keeps_the_other_clouds_machine_section(self):
        text = "## How and where\n\nCommand: all\n\n## How and where: diamond\n\nCommand: old diamond\n"
        kept = afu_world.kept_sections(text, ["uniform"], ["diamond"])
        self.assertEqual(kept, "## How and where: uniform\n\nCommand: all")
        self.assertIn("old diamond", afu_world.kept_sections(text, ["uniform", "diamond"], ["mixed"]))


class LanesReport(unittest.TestCase):
    HEADER = ("world,spheres,buckets,cells,chunks,scanned,probes,candidates,large,load,classify,prefix,scatter,"
              "grid,large_pass,total,model_generate,model_total,lanes")

    def test_the_table_gives_each_worlds_speed_up_candidates_a_cycle_and_the_passes_share(self):
        rows = ["w,100,256,1,1,1,1,400,0,100,100,32,100,1668,0,2000,0,0,1",
                "w,100,256,1,1,1,1,400,0,100,100,32,100,168,0,500,0,0,4"]
        with tempfile.TemporaryDirectory() as d:
            path = Path(d) / "c.csv"
            path.write_text("\n".join([self.HEADER] + rows) + "\n")
            text = lanes.table(lanes.load(path), 200.0)
            # 2000 / 500 = 4x at 4 lanes; grid 1668 / 168; 400 / 500 candidates a cycle; passes 332 / 500
            self.assertIn("| w | 100 | 400 | 2,000 | 500 | 4.00x (4) | 9.9x | 0.80 | 66 % | 2 |", text)

    def test_sort_ports_get_columns_of_their_own_and_the_best_is_named_by_both(self):
        rows = ["w,100,256,1,1,1,1,400,0,100,100,32,100,1668,0,2000,0,0,1,1",
                "w,100,256,1,1,1,1,400,0,100,100,32,100,168,0,500,0,0,4,1",
                "w,100,256,1,1,1,1,400,0,50,50,32,50,168,0,350,0,0,4,2"]
        with tempfile.TemporaryDirectory() as d:
            path = Path(d) / "c.csv"
            path.write_text("\n".join([self.HEADER + ",sort_ports"] + rows) + "\n")
            text = lanes.table(lanes.load(path), 200.0)
            self.assertIn("| 1 lane | 4 lanes | 4 lanes, 2 ports |", text)
            # 2000 / 350 = 5.71x; passes 182 / 350
            self.assertIn("| w | 100 | 400 | 2,000 | 500 | 350 | 5.71x (4, 2 ports) | 9.9x | 1.14 | 52 % | 2 |", text)

    def test_a_csv_without_lanes_is_refused_by_name(self):
        with tempfile.TemporaryDirectory() as d:
            path = Path(d) / "old.csv"
            path.write_text("world,spheres\nw,1\n")
            with self.assertRaises(SystemExit) as e:
                lanes.load(path)
            self.assertIn("old.csv", str(e.exception))


class LanesArea(unittest.TestCase):
    def folder(self, d, broad_phase, modules):
        f = Path(d) / "cfg"
        f.mkdir()
        afu = {"ram": {"broadPhaseBits": 123.0}} | ({"broadPhase": broad_phase} if broad_phase else {})
        (f / "manifest.json").write_text(json.dumps({"id": "cfg", "afu": afu}))
        (f / "Afu_cfg.sv").write_text("".join(f"module {m}(\n);\nendmodule\n" for m in modules))
        return f

    def test_it_finds_the_lane_count_and_the_broad_phase_module(self):
        with tempfile.TemporaryDirectory() as d:
            f = self.folder(d, {"lanes": 4, "sortPorts": 2, "wordLog2": 4}, ["Afu_cfg", "BroadPhase_fp32_l4_cfg", "BucketSort_cfg"])
            self.assertEqual(lanes_area.broad_phase(f)[0:2], (4, "cfg"))
            self.assertEqual(lanes_area.broad_phase(f)[3:], ("BroadPhase_fp32_l4_cfg", 123.0, 2, 16))

    def test_a_manifest_from_before_sort_ports_means_one_port_and_eight_a_word(self):
        with tempfile.TemporaryDirectory() as d:
            f = self.folder(d, {"lanes": 2}, ["Afu_cfg", "BroadPhase_fp32_l2_cfg"])
            self.assertEqual(lanes_area.broad_phase(f)[5:], (1, 8))

    def test_the_area_table_compares_each_row_with_the_one_lane_row_of_its_own_rtl(self):
        with tempfile.TemporaryDirectory() as d:
            path = Path(d) / "area.csv"
            path.write_text("lanes,sort_ports,per_word,module,luts,arith,dsp,ff,m10k,ram_bits,commit\n"
                            "1,1,8,a,100,1,0,1,1,1,old\n4,1,8,b,300,1,0,1,1,1,old\n"
                            "1,1,16,c,200,1,0,1,1,1,new\n4,2,16,d,1000,1,0,1,1,1,new\n")
            text = "\n".join(lanes.area_table(path))
            self.assertIn("| 4 | 1 | 8 | 300 | 1 | 1 | 1 | 1 | 3.0x | old |", text)
            self.assertIn("| 4 | 2 | 16 | 1,000 | 1 | 1 | 1 | 1 | 5.0x | new |", text)

    def test_a_folder_without_world_mode_is_refused_by_name(self):
        with tempfile.TemporaryDirectory() as d:
            f = self.folder(d, None, ["Afu_cfg"])
            with self.assertRaises(SystemExit) as e:
                lanes_area.broad_phase(f)
            self.assertIn("not a world-mode AFU", str(e.exception))

    def test_a_folder_without_a_manifest_is_refused_by_name(self):
        with tempfile.TemporaryDirectory() as d:
            with self.assertRaises(SystemExit) as e:
                lanes_area.broad_phase(Path(d))
            self.assertIn(f"{d}: no manifest.json", str(e.exception))


class FitPreset(unittest.TestCase):
    """bench/world/fit_preset.py: the committed preset rows fit; a bad CSV is refused by name."""

    def run_fit(self, text):
        with tempfile.TemporaryDirectory() as d:
            p = Path(d) / "cycles.csv"
            p.write_text(text)
            with self.assertRaises(SystemExit) as e:
                fit_preset.main(["--csv", str(p)])
            return str(e.exception.code)

    def test_the_committed_preset_rows_fit_spheres_and_candidates(self):
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            self.assertEqual(fit_preset.main([]), 0)
        self.assertIn("x spheres +", out.getvalue())
        self.assertIn("x candidates; worst residual", out.getvalue())

    def test_a_missing_file_a_foreign_csv_a_bad_number_and_mixed_configurations_are_refused(self):
        with self.assertRaises(SystemExit) as e:
            fit_preset.main(["--csv", "/no/such/cycles.csv"])
        self.assertIn("/no/such/cycles.csv: cannot read it", str(e.exception.code))
        self.assertIn("no column spheres, candidates, total", self.run_fit("a,b\n1,2\n"))
        head = "world,spheres,candidates,total,lanes\n"
        self.assertIn("line 2: spheres is 'x'", self.run_fit(head + "u,x,3,9,16\n"))
        self.assertIn("rows of 2 configurations", self.run_fit(head + "u,1,3,9,16\nu,2,3,9,8\n"))


class BroadPhaseArea(unittest.TestCase):
    SV = ("module mem_x(\n  input a\n);\n  reg [3:0] Memory[0:7];\nendmodule\n"
          "module Gen_x(\n  input a\n);\n  mem_x m (\n    .a(a)\n  );\nendmodule\n"
          "module Sort_x(\n  input a\n);\nendmodule\n"
          "module BroadPhase_x(\n  input a\n);\n  Gen_x g0 (\n    .a(a)\n  );\n  Gen_x g1 (\n    .a(a)\n  );\n"
          "  Sort_x s (\n    .a(a)\n  );\n  mem_x d (\n    .a(a)\n  );\nendmodule\n")

    def test_each_block_is_counted_with_its_rams_left_out(self):
        self.assertEqual(broad_phase_area.memories(self.SV), {"mem_x"})
        rows = broad_phase_area.blocks(self.SV, "BroadPhase_x")
        # Its own logic with every child a black box; each logic child once with its count; the
        # RAM child not at all.
        self.assertEqual(rows[0], ("BroadPhase_x", 1, {"Gen_x", "Sort_x", "mem_x"}))
        self.assertEqual([(m, n) for m, n, _ in rows[1:]], [("Gen_x", 2), ("Sort_x", 1)])
        self.assertEqual(rows[1][2], {"mem_x"})


if __name__ == "__main__":
    unittest.main()
