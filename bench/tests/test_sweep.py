"""Tests of bench/sweep's own logic (no builds): ids, derived figures, drift, caching, CSV
and plots. Run: tools/.cache/bench-venv/bin/python -m unittest discover -s bench/tests -v"""
import csv
import json
import os
import sys
import tempfile
import unittest
from pathlib import Path


from sweeplib import plots  # noqa: E402
from sweeplib import report  # noqa: E402
from sweeplib import runs  # noqa: E402
from sweeplib import isoarea  # noqa: E402
from sweeplib import sweep  # noqa: E402
from sweeplib.sweeps import SWEEPS, Config, Scene  # noqa: E402

MANIFEST = {"afu": {"peakPairsPerCycle": 16, "ram": {"sphereTableBits": 2097152, "pairBufferBits": 34048}},
            "scpu": {"format": {"name": "fp32"}, "distance": "sqrt-recip", "sqrtAlg": "dr", "recipAlg": "dr",
                     "rsqrtAlg": "dr", "latency": 21},
            "link": {"format": "binary32"},
            "buffers": {"recordBytes": 12, "records": {"layout": "derived"}}}


def summary(pairs=5829, contacts=3593, modelled=31100.0, bound=28829.0):
    return {"spheres": 670, "pairs": pairs, "contacts": contacts, "ode_ns": 93000, "simd_ns": 56000,
            "backend_wall_ns": 91000000, "cpu_repeat": 20,
            "afu": {"modelled_ns": modelled, "link_bound_ns": bound, "cycle_ns": 5.0, "loading_ns": 1785.0,
                    "computing_ns": 1825.0, "wait_read_ns": 1780.0, "wait_write_ns": 14255.0, "other_ns": 5475.0,
                    "overhead_ns": 5980.0, "read_lines": 533, "write_lines": 1798, "runs": 1,
                    "cycles_stepped": 5011, "cycles_skipped": 94}}


class ClockColumns(unittest.TestCase):
    def test_a_row_says_which_clock_its_times_use_and_whether_the_design_reaches_it(self):
        reached = {"proxy_mhz": 202.1, "routed_estimate_mhz": 131.23, "slowest_block": "Puc_default"}
        at = lambda **c: sweep.clock_columns(c)
        self.assertEqual(at(target_mhz=200.0, used_mhz=200.0, study=False, reaches_target=True, reached=reached),
                         {"clock_kind": "target", "clock_reached": True, "proxy_mhz": 202.1, "routed_estimate_mhz": 131.23})
        short = at(target_mhz=200.0, used_mhz=38.4, study=False, reaches_target=False, reached=dict(reached, proxy_mhz=38.4))
        self.assertEqual((short["clock_kind"], short["clock_reached"], short["proxy_mhz"]), ("reached", False, 38.4))
        self.assertEqual(at(target_mhz=200.0, used_mhz=200.0, study=False, reaches_target=False, reached=None)["clock_kind"],
                         "target, not measured")
        self.assertEqual(at(target_mhz=200.0, used_mhz=131.2, study=True, reaches_target=True, reached=reached)["clock_kind"], "study")
        self.assertEqual(sweep.clock_columns(None)["clock_kind"], "")


class ConfigIds(unittest.TestCase):
    def test_every_configuration_of_every_sweep_has_a_distinct_folder_name(self):
        cfgs = {c for s in SWEEPS.values() for c in s.configs}
        ids = [c.id for c in cfgs]
        self.assertEqual(len(ids), len(set(ids)))
        for i in ids:
            self.assertRegex(i, r"^[A-Za-z0-9_-]+$")

    def test_the_generator_gets_the_count_and_the_spec(self):
        c = Config(8, "fp32:sqrt=nr8x1:recip=nr8x1")
        self.assertEqual(c.generator_args(), "--scpus 8 --scpu fp32:sqrt=nr8x1:recip=nr8x1 --allow-overfit")
        self.assertEqual(c.id, "n8_fp32_sqrt_nr8x1_recip_nr8x1")

    def test_a_record_layout_is_passed_on_and_named_only_when_asked_for(self):
        self.assertEqual(Config(16, "fp16", "full").generator_args(), "--scpus 16 --scpu fp16 --records full --allow-overfit")
        self.assertEqual(Config(16, "fp16", "full").id, "n16_fp16_full")
        self.assertEqual(Config(16, "fp16").id, "n16_fp16")
        r = sweep.row(SWEEPS["links"], Config(16, "fp32"), MANIFEST, Scene(10), "pac", summary(), {}, {}, {})
        self.assertEqual((r["link_format"], r["records"], r["record_bytes"], r["link"]), ("binary32", "derived", 12, "pac"))

    def test_a_banked_sphere_table_is_passed_on_and_named_only_when_asked_for(self):
        self.assertEqual(Config(16, "fp32", "", "banked").generator_args(), "--scpus 16 --scpu fp32 --ram-ports banked --allow-overfit")
        self.assertEqual(Config(16, "fp32", "", "banked:64").id, "n16_fp32_banked64")
        self.assertNotEqual(Config(16, "fp32", "", "banked").id, Config(16, "fp32").id)
        rep = sweep.row(SWEEPS["banked"], Config(4, "fp32"), MANIFEST, Scene(10), "qpi", summary(), {}, {}, {})
        bank = sweep.row(SWEEPS["banked"], Config(4, "fp32", "", "banked"), MANIFEST, Scene(10), "qpi",
                         summary(modelled=34210.0), {}, {}, {})
        self.assertEqual((rep["ram_ports"], bank["ram_ports"]), ("replicated", "banked"))
        # the banked row beside its replicated twin, with the time ratio
        t = report.banked_table([rep, bank])
        self.assertEqual(len(t.splitlines()), 3, t)
        self.assertIn("| 31.10 / 34.21 | 1.100 |", t)

    def test_the_ram_table_sets_each_count_beside_its_banked_twin_and_says_what_does_not_fit(self):
        row = lambda n, ports, banks, bits, m20k, fits: {"max_spheres": "65536", "scpus": str(n), "ram_ports": ports,
            "copies": "1", "banks": str(banks), "sphere_table_bits": str(bits), "m20k": str(m20k),
            "m20k_pct_5sgxea7": f"{100 * m20k / 2560:.1f}", "fits": fits}
        t = report.ram_table([row(16, "replicated", 1, 16 * 2**23, 6592, "false"), row(16, "banked", 32, 2**23, 416, "true")])
        self.assertIn("| 65536 | 16 | 128.00 | 6592 (257.5 %), does not fit | 32 | 8.00 | 416 (16.2 %) |", t)
        with tempfile.TemporaryDirectory() as d:  # the sweep's tables read ram.csv beside its CSV
            rows = [row(16, "replicated", 1, 16 * 2**23, 6592, "false"), row(16, "banked", 32, 2**23, 416, "true")]
            with open(Path(d) / "ram.csv", "w", newline="") as fh:
                w = csv.DictWriter(fh, fieldnames=list(rows[0]))
                w.writeheader()
                w.writerows(rows)
            rep = sweep.row(SWEEPS["banked"], Config(16, "fp32"), MANIFEST, Scene(10), "qpi", summary(), {}, {}, {})
            md = report.write("banked", [rep], Path(d)).read_text()
            self.assertIn("6592 (257.5 %), does not fit", md)


class IsoArea(unittest.TestCase):
    PUCS = [{"scpus": "1", "puc_luts": "1000", "puc_arith": "0", "puc_ff": "0"},
            {"scpus": "3", "puc_luts": "3000", "puc_arith": "0", "puc_ff": "0"}]

    def arith(self, luts, arith, dsp, ff, fmt="fp32"):
        return [{"scpu_spec": "x", "format": fmt, "scpu_luts": str(luts), "scpu_arith": str(arith),
                 "scpu_dsp": str(dsp), "scpu_ff": str(ff)}]

    def test_the_two_calibrations_bracket_the_alms_a_block_needs(self):
        self.assertEqual(isoarea.alms(100, 50, 40, "unpacked"), 150)
        self.assertEqual(isoarea.alms(100, 50, 40, "packed"), 75)
        self.assertEqual(isoarea.alms(10, 0, 400, "packed"), 100)  # four registers an ALM

    def test_the_puc_is_interpolated_and_extrapolated_with_the_last_slope(self):
        t = isoarea.puc_table(self.PUCS)
        self.assertEqual(isoarea.puc_at(t, 2)["luts"], 2000)
        self.assertEqual(isoarea.puc_at(t, 5)["luts"], 5000)

    def test_the_count_stops_at_the_first_resource_that_runs_out(self):
        cap = isoarea.CHIP
        # ALMs: PUC n * 1000 + n * 9000 (unpacked) <= 234,720 -> 23
        n, why = isoarea.fits(self.arith(9000, 0, 1, 0), self.PUCS)[("x", "unpacked")]
        self.assertEqual((n, why), (cap["alms"] // 10000, "ALMs"))
        # DSPs: 100 a unit -> 2
        self.assertEqual(isoarea.fits(self.arith(10, 0, 100, 0), self.PUCS)[("x", "packed")], (2, "DSPs"))


class Rows(unittest.TestCase):
    def test_a_row_derives_per_collision_figures_and_both_bounds(self):
        sw = SWEEPS["paper"]
        r = sweep.row(sw, Config(16, "fp32"), MANIFEST, Scene(10), "qpi", summary(), {}, {}, {})
        self.assertAlmostEqual(r["ns_per_collision"], 31100.0 / 3593)
        self.assertAlmostEqual(r["ns_per_pair"], 31100.0 / 5829)
        self.assertAlmostEqual(r["over_link_bound"], 31100.0 / 28829.0)
        # 16 pairs a cycle at 5 ns: 0.3125 ns a pair
        self.assertAlmostEqual(r["compute_bound_ns"], 5829 * 0.3125)
        self.assertAlmostEqual(r["rtl_wall_over_ode"], 91000000 / 93000)
        self.assertEqual(r["ram_bits"], 2097152 + 34048)

    def test_an_empty_step_gives_blank_ratios_not_a_division_error(self):
        r = sweep.row(SWEEPS["paper"], Config(16, "fp32"), MANIFEST, Scene(1), "qpi",
                      summary(pairs=0, contacts=0), {}, {}, {})
        self.assertEqual(r["ns_per_collision"], "")
        self.assertEqual(r["over_compute_bound"], "")

    def test_csv_round_trip_keeps_every_column_of_every_row(self):
        with tempfile.TemporaryDirectory() as d:
            p = Path(d) / "x.csv"
            sweep.write_csv(p, [{"a": 1, "b": 2}, {"a": 3, "c": 4}])
            rows = sweep.read_csv(p)
            self.assertEqual(rows, [{"a": "1", "b": "2", "c": ""}, {"a": "3", "b": "", "c": "4"}])


class Drift(unittest.TestCase):
    def test_drift_is_the_distance_between_the_same_spheres(self):
        with tempfile.TemporaryDirectory() as d:
            a, b = Path(d) / "a.csv", Path(d) / "b.csv"
            a.write_text("sphere,x,y,z\n0,0x0p+0,0x0p+0,0x0p+0\n1,0x1p+0,0x0p+0,0x0p+0\n")
            b.write_text("sphere,x,y,z\n0,0x1.8p+1,0x1p+2,0x0p+0\n1,0x1p+0,0x0p+0,0x0p+0\n")
            self.assertEqual(runs.drift(a, b), {"drift_max_m": 5.0, "drift_mean_m": 2.5})
            b.write_text("sphere,x,y,z\n0,0x0p+0,0x0p+0,0x0p+0\n")
            with self.assertRaisesRegex(RuntimeError, "different sphere counts"):
                runs.drift(a, b)


class Caching(unittest.TestCase):
    def test_a_cached_run_is_used_only_with_the_same_sources_and_settings(self):
        with tempfile.TemporaryDirectory() as d:
            r = sweep.Runner.__new__(sweep.Runner)
            r.key = {"rtl": "abc", "host": "def", "cpu_repeat": 20}
            run = Path(d)
            self.assertIsNone(r.cached(run))
            (run / "summary.json").write_text(json.dumps({"pairs": 1}))
            (run / "key.json").write_text(json.dumps(r.key))
            self.assertEqual(r.cached(run), {"pairs": 1})
            r.key = dict(r.key, rtl="changed")
            self.assertIsNone(r.cached(run))


    def test_a_run_at_the_cells_clock_is_used_only_while_that_clock_is_the_same(self):
        with tempfile.TemporaryDirectory() as d:
            r = sweep.Runner.__new__(sweep.Runner)
            r.key = {"rtl": "abc", "host": "def", "cpu_repeat": 20}
            clock = {"mhz": 29.123}
            r.timed = lambda cfg, part, only_cached=False: True
            r.cells_mhz = lambda cfg: clock["mhz"]
            r.preset_clock = lambda cfg, preset: {"ideal": 200.0}[preset]
            r.has_binary = lambda cfg: True
            run, cfg = Path(d), Config(16, "fp32")
            (run / "summary.json").write_text(json.dumps({"pairs": 1}))
            (run / "key.json").write_text(json.dumps(r.run_key(cfg, "ideal@cells")))
            self.assertEqual(r.run_key(cfg, "ideal@cells")["clock_mhz"], 29.123)
            self.assertNotIn("clock_mhz", r.run_key(cfg, "ideal"))
            self.assertEqual(r.cached(run, cfg, "ideal@cells"), {"pairs": 1})
            clock["mhz"] = 31.0   # the timing proxy moved: the run is stale
            self.assertIsNone(r.cached(run, cfg, "ideal@cells"))
            r.timed = lambda cfg, part, only_cached=False: False  # and while the timing is not cached
            self.assertIsNone(r.cached(run, cfg, "ideal@cells"))

    def test_a_run_at_the_cells_clock_never_runs_above_its_presets_own_clock(self):
        r = sweep.Runner.__new__(sweep.Runner)
        r.key = {"rtl": "abc", "host": "def", "cpu_repeat": 20}
        r.cells_mhz = lambda cfg: 202.1
        r.preset_clock = lambda cfg, preset: {"qpi": 200.0, "harp2": 400.0}[preset]
        cfg = Config(16, "fp32")
        self.assertEqual(r.run_key(cfg, "qpi@cells")["clock_mhz"], 200.0)
        self.assertEqual(r.run_key(cfg, "harp2@cells")["clock_mhz"], 202.1)

    def test_each_link_presets_clock_is_read_from_the_hosts_own_list(self):
        text = ("link presets (collide run/pairs --link NAME):\n\nideal: preloaded data\n"
                "  clock 200 MHz (AFU port 12.8 GB/s a direction), 64 reads\n  sources:\n    - clock 1 MHz: not this\n\n"
                "qpi (also harp1): HARP v1\n  clock 200 MHz (AFU port)\n\nharp2: HARP v2\n  clock 400 MHz (AFU port)\n")
        self.assertEqual(runs.preset_clocks(text), {"ideal": 200.0, "qpi": 200.0, "harp2": 400.0})


class Clock(unittest.TestCase):
    T = {"cyclonev_ps": 34339, "arriav_ps": 29747, "path_from": "s_q", "path_to": "p_r", "path_luts": 3,
         "path_carry": 50, "path_dsp": 1, "block": "Scpu_fp32_n16_fp32"}

    def test_the_clock_is_the_slower_part_and_block_names_lose_the_configuration(self):
        rest = self.T | {"cyclonev_ps": 40000, "arriav_ps": 39000, "path_from": "", "path_to": "q.Fp_n16_fp32.r",
                         "block": "ContactCollector_n16_n16_fp32"}
        c = sweep.timing_columns(self.T, rest, "n16_fp32")
        self.assertEqual((c["scpu_cyclonev_ps"], c["rest_arriav_ps"], c["cells_mhz"]), (34339, 39000, 25.0))
        self.assertEqual(c["rest_block"], "ContactCollector_n16")
        self.assertEqual(c["rest_path"], "<input> -> q.Fp.r: 3 LUTs, 50 carry, 1 DSP")
        self.assertEqual(sweep.timing_columns(self.T, rest | {"cyclonev_ps": 1000}, "x")["cells_mhz"], round(1e6 / 34339, 3))
        with self.assertRaisesRegex(RuntimeError, "x: the timing proxy found no path"):
            sweep.cells_mhz(self.T | {"cyclonev_ps": 0}, rest | {"cyclonev_ps": 0}, "x")

    def test_a_scene_at_a_clock_names_the_link_there_and_in_its_file_name(self):
        a, b = runs.scene_file(Scene(3)), runs.scene_file(Scene(3), "ideal", 29.5)
        self.assertNotEqual(a, b)
        self.assertEqual(json.loads(b.read_text())["link"], {"type": "ideal", "clock_mhz": 29.5})
        self.assertEqual(json.loads(a.read_text())["link"], {"type": "qpi"})  # scenes/diamond.json's own

    def test_the_clock_table_sets_each_link_beside_itself_at_the_cells_clock(self):
        cols = sweep.timing_columns(self.T, self.T | {"cyclonev_ps": 20000, "block": "X_n16_fp32"}, "n16_fp32")
        rows = []
        for link, ns, cyc in (("ideal", 4716.0, 5.0), ("ideal@cells", 33000.0, 34.339)):
            s = summary(modelled=ns)
            s["afu"]["cycle_ns"] = cyc
            rows.append(sweep.row(SWEEPS["arith"], Config(16, "fp32"), MANIFEST, Scene(10), link, s, cols, {}, {}))
        self.assertEqual((rows[0]["clock_mhz"], rows[1]["clock_mhz"]), (200.0, 29.121))
        t = report.clock_table(sweep.read_csv(self.csv(rows)))
        self.assertIn("| n16_fp32 | 21 | 34.3 (29.7) | s_q -> p_r: 3 LUTs, 50 carry, 1 DSP | X | 20.0 (29.7) | 29.1 | "
                      "4.72 / 33.00 (7.0) |", t)
        self.assertIn("ideal: us at 200 MHz / at the cells' clock (x)", t)

    def csv(self, rows):
        d = tempfile.mkdtemp()
        sweep.write_csv(Path(d) / "x.csv", rows)
        return Path(d) / "x.csv"


class Plots(unittest.TestCase):
    def test_the_paper_sweep_draws_figures_5_6_and_7(self):
        rows = []
        for h, (pairs, contacts) in enumerate([(13, 13), (300, 200), (5829, 3593)], start=1):
            for link in ("qpi", "ideal"):
                r = sweep.row(SWEEPS["paper"], Config(16, "fp32"), MANIFEST, Scene(h), link,
                              summary(pairs, contacts), {}, {}, {})
                rows.append({k: str(v) for k, v in r.items()})
        with tempfile.TemporaryDirectory() as d:
            files = plots.draw("paper", rows, Path(d))
            self.assertEqual(sorted(f.name for f in files),
                             ["fig5_time_vs_collisions.png", "fig6_time_split.png", "fig7_ideal_link.png"])
            for f in files:
                self.assertGreater(f.stat().st_size, 10000)
                self.assertEqual(f.read_bytes()[:8], b"\x89PNG\r\n\x1a\n")
            md = report.write("paper", rows, Path(d)).read_text()
            # hMax 3 over qpi: 31.10 us modelled, 8.66 ns/collision, 1.08x the link bound
            self.assertIn("| n16_fp32 | 3 | qpi | 5829 | 3593 | 31.10 | 8.66 | 5.34 | 28.83 | 1.08 |", md)
            self.assertIn("200,844 logic elements", md)


class Links(unittest.TestCase):
    def rows(self):
        out = []
        for cfg, fmt, rec, nbytes, err, ns in (("n16_fp32", "fp32", "derived", 12, 1e-7, {"qpi": 4.8, "ideal": 1.5}),
                                                ("n16_fp16", "fp16", "derived", 8, 1e-3, {"qpi": 3.9, "ideal": 1.1}),
                                                ("n16_fp32_full", "fp32", "full", 32, 1e-7, {"qpi": 8.7, "ideal": 3.0})):
            for link, v in ns.items():
                out.append({"config": cfg, "format": fmt, "link_format": "binary" + fmt[2:], "records": rec,
                            "record_bytes": str(nbytes), "hmax": "10", "link": link, "ns_per_collision": str(v),
                            "over_link_bound": "1.10", "acc_pos_rel_worst": str(err), "scpu_spec": fmt})
        return out

    def test_one_pareto_plot_per_link_and_a_table_of_every_configuration_on_every_link(self):
        with tempfile.TemporaryDirectory() as d:
            files = plots.draw("links", self.rows(), Path(d))
            self.assertEqual(sorted(f.name for f in files), ["links_pareto_ideal.png", "links_pareto_qpi.png"])
            md = report.links_table(self.rows())
            self.assertIn("| fp16 | binary16 | derived | 8 | 10 | 3.90 (1.10) | 1.10 (1.10) |", md)
            self.assertIn("| fp32 | binary32 | full | 32 | 10 | 8.70 (1.10) | 3.00 (1.10) |", md)

    def test_the_front_is_the_fast_and_accurate_points(self):
        pts = [(4.8, 1e-7, "fp32"), (3.9, 1e-3, "fp16"), (8.7, 1e-7, "fp32 full")]
        self.assertEqual([p[2] for p in plots.pareto(pts)], ["fp16", "fp32"])


if __name__ == "__main__":
    unittest.main()


class Area(unittest.TestCase):
    SV = ("`define X 1\n"
          "module Leaf_a(\n  input x\n);\nendmodule\n"
          "module Mid_a(\n  input x\n);\n  Leaf_a leaf (\n    .x(x)\n  );\nendmodule\n"
          "module Other_a(\n  input x\n);\nendmodule\n"
          "module Top_a(\n  input x\n);\n  Mid_a m (\n    .x(x)\n  );\n  Other_a o (\n    .x(x)\n  );\nendmodule\n")

    def test_a_blocks_verilog_is_its_module_and_everything_below_it(self):
        from sweeplib import area
        pre, mods = area.subtree(self.SV, "Mid_a")
        self.assertEqual(pre, "`define X 1\n")
        self.assertEqual([m.split("(")[0] for m in mods], ["module Leaf_a", "module Mid_a"])
        _, mods = area.subtree(self.SV, "Top_a")
        self.assertEqual(len(mods), 4)
        with self.assertRaisesRegex(RuntimeError, "no module Nope"):
            area.subtree(self.SV, "Nope")

    def test_a_black_box_keeps_its_ports_and_nothing_below_it(self):
        from sweeplib import area
        _, mods = area.subtree(self.SV, "Top_a", black={"Mid_a"})
        self.assertEqual(mods[0], "(* blackbox *)\nmodule Mid_a(\n  input x\n);\nendmodule\n")
        self.assertEqual([m.split("(")[0] for m in mods[1:]], ["module Other_a", "module Top_a"])
        with self.assertRaisesRegex(RuntimeError, "Top_a is the top"):
            area.subtree(self.SV, "Top_a", black={"Top_a"})
        self.assertEqual(area.children(self.SV, "Top_a"), {"Mid_a": 1, "Other_a": 1})
        self.assertEqual(area.children(self.SV, "Leaf_a"), {})

    def test_the_afu_area_is_the_puc_plus_n_scpus(self):
        from sweeplib import area
        puc = {"luts": 100, "arith": 10, "dsp": 0, "ff": 50, "m10k": 40}
        scpu = {"luts": 7, "arith": 3, "dsp": 9, "ff": 5, "m10k": 0}
        a = area.afu_area(puc, scpu, 16)
        self.assertEqual((a["area_luts"], a["area_dsp"], a["area_m10k"]), (212, 144, 40))
        self.assertEqual(a["scpus_luts"], 112)
        b = area.afu_area(None, scpu, 16)
        self.assertNotIn("area_luts", b)
        self.assertEqual(b["scpus_dsp"], 144)


class Pareto(unittest.TestCase):
    def test_the_front_keeps_only_points_nothing_beats_on_both_axes(self):
        pts = [(3, 1e-7, "fp32"), (1, 1e-2, "bf16"), (2, 1e-3, "fp16"), (2.5, 1e-2, "worse"), (9, 0.0, "fp64")]
        self.assertEqual([p[2] for p in plots.pareto(pts)], ["bf16", "fp16", "fp32", "fp64"])


@unittest.skipUnless(os.environ.get("COLLIDE_SWEEP_SMOKE") == "1",
                     "end to end (sbt, Verilator, a host build): set COLLIDE_SWEEP_SMOKE=1, as tools/test does")
class SmokeSweep(unittest.TestCase):
    def test_one_command_generates_builds_runs_and_writes_the_csv_tables_and_machine_note(self):
        from sweeplib import cli
        with tempfile.TemporaryDirectory() as d:
            self.assertEqual(cli.main(["run", "smoke", "--out", d]), 0)
            rows = sweep.read_csv(Path(d) / "smoke.csv")
            self.assertEqual(len(rows), 1)
            r = rows[0]
            self.assertEqual((r["config"], r["link"], r["hmax"]), ("n2_fp32", "ideal", "2"))
            # the diamond at hMax 2: 6 spheres, every tested pair touching or overlapping
            self.assertEqual((r["spheres"], r["pairs"], r["contacts"]), ("6", "13", "13"))
            self.assertGreater(float(r["modelled_ns"]), 0)
            self.assertGreaterEqual(float(r["modelled_ns"]), float(r["link_bound_ns"]))
            self.assertGreater(float(r["drift_max_m"]), 0)  # fp32 against ODE's double
            self.assertIn("| n2_fp32 | 2 | ideal | 13 | 13 |", (Path(d) / "smoke.md").read_text())
            self.assertIn("- command: `bench/sweep run", (Path(d) / "MACHINE.md").read_text())
