"""Runs a named sweep: generate, build, run, measure area/accuracy/drift, write the CSV.

Every step is cached under build/sweep/ and keyed by what it depends on, so a sweep that
stops (Ctrl-C, a crash, a reboot) resumes where it was, and a second run only redoes what
changed."""
import csv
import json
import sys
import threading
import time
from pathlib import Path

from tqdm import tqdm

import accuracy
import area
import build
import generate
import runs
from paths import BUILD, host_hash, rtl_hash, write_atomic
from sweeps import Scene

# Rough cost of each step in seconds on a 2-core machine: the progress bar's weights, so
# its time-left estimate is about right before many steps have been timed.
W_GEN, W_RUN, W_DRIFT, W_ACC = 25, 3, 5, 90


def w_build(cfg):
    return 30 + 12 * cfg.scpus * (2 if "64" in cfg.spec else 1)


def w_area(cfg, puc=True):
    return (200 if puc else 0) + (600 if "64" in cfg.spec else 200)


class Runner:
    def __init__(self, sweep, out: Path, do_area: bool, cpu_repeat: int):
        self.sweep, self.out, self.do_area = sweep, out, do_area and sweep.area
        self.cpu_repeat = cpu_repeat or sweep.cpu_repeat
        self.state = BUILD / "runs" / sweep.name
        self.logs = BUILD / "logs" / sweep.name
        self.key = {"rtl": rtl_hash(), "host": host_hash(), "cpu_repeat": self.cpu_repeat}

    def cached(self, d: Path):
        """A run's summary if it was made with today's sources and settings."""
        k, s = d / "key.json", d / "summary.json"
        if k.exists() and s.exists() and json.loads(k.read_text()) == self.key:
            return json.loads(s.read_text())
        return None

    def run_scene(self, cfg, scene, backend, link, positions=False):
        d = self.state / cfg.id / scene.id / (link or backend)
        hit = self.cached(d)
        if hit is not None:
            return hit, d
        s = runs.run(build.binary(cfg), scene, backend, d, link=link, cpu_repeat=self.cpu_repeat,
                     positions=positions)
        write_atomic(d / "key.json", json.dumps(self.key))
        return s, d

    def plan_weight(self):
        sw = self.sweep
        stale = [c for c in sw.configs if not generate.fresh(c, self.key["rtl"])]
        w = W_GEN * len(stale) + sum(w_build(c) for c in sw.configs)
        w += W_RUN * len(sw.configs) * len(sw.scenes) * len(sw.links)
        if self.do_area:
            w += sum(w_area(c, sw.puc_area) for c in sw.configs)
        if sw.accuracy:
            w += W_ACC
        if sw.drift_steps:
            w += W_DRIFT * (len(sw.configs) + 1)
        return w

    def go(self):
        sw = self.sweep
        t0 = time.time()
        # smoothing=0: the time left is the average rate so far applied to the weight left; a
        # ticker redraws every 2 s so a long step (a Yosys run) still shows time passing.
        bar = tqdm(total=self.plan_weight(), unit="s~", desc=sw.name, dynamic_ncols=True, smoothing=0,
                   bar_format="{desc}: {percentage:3.0f}%|{bar}| {elapsed} elapsed, ~{remaining} left {postfix}")
        stop = threading.Event()

        def tick():
            while not stop.wait(2):
                bar.refresh()

        if sys.stderr.isatty():  # in a log file, one line a step is enough
            threading.Thread(target=tick, daemon=True).start()

        def step(what, weight, f):
            bar.set_postfix_str(what)
            r = f()
            bar.update(weight)
            return r

        stale = [c for c in sw.configs if not generate.fresh(c, self.key["rtl"])]
        step(f"generating {len(stale)} configurations", W_GEN * len(stale),
             lambda: generate.generate(sw.configs, self.logs / "generate.log"))
        acc = {}
        if sw.accuracy:
            acc = step("accuracy of the golden model", W_ACC,
                       lambda: accuracy.measure([c.spec for c in sw.configs], self.logs / "accuracy.log"))
        rows, drift_ref = [], None
        for cfg in sw.configs:
            m = generate.manifest(cfg)
            step(f"{cfg.id}: host + Verilated AFU", w_build(cfg),
                 lambda: build.build(cfg, self.logs / f"build-{cfg.id}.log"))
            areas = {}
            if self.do_area:
                def synth():
                    sv, cid = generate.verilog(cfg), m["id"]
                    scpu = area.synth(sv, generate.module_named(cfg, "Scpu_"), self.logs, cid)
                    puc = area.synth(sv, generate.module_named(cfg, "Puc_"), self.logs, cid) if sw.puc_area else None
                    return area.afu_area(puc, scpu, cfg.scpus)
                areas = step(f"{cfg.id}: Yosys area", w_area(cfg, sw.puc_area), synth)
            drift = {}
            if sw.drift_steps:
                dscene = Scene(10, sw.drift_steps) if sw.name != "smoke" else Scene(sw.scenes[0].hmax, sw.drift_steps)
                if drift_ref is None:
                    _, ref_dir = step("ODE reference for the drift", W_DRIFT,
                                      lambda: self.run_scene(cfg, dscene, "ode", None, positions=True))
                    drift_ref = ref_dir / "positions.csv"
                _, d = step(f"{cfg.id}: drift", W_DRIFT,
                            lambda: self.run_scene(cfg, dscene, "rtl", "ideal", positions=True))
                drift = runs.drift(d / "positions.csv", drift_ref) | {"drift_steps": sw.drift_steps}
            for scene in sw.scenes:
                for link in sw.links:
                    s, _ = step(f"{cfg.id}: {scene.id} over {link}", W_RUN,
                                lambda: self.run_scene(cfg, scene, "rtl", link))
                    rows.append(row(sw, cfg, m, scene, link, s, areas, acc.get(cfg.spec, {}), drift))
        stop.set()
        bar.close()
        write_csv(self.out / f"{sw.name}.csv", rows)
        return rows, time.time() - t0


def row(sw, cfg, m, scene, link, s, areas, acc, drift):
    a, sc = s["afu"], m["scpu"]
    pairs, contacts = s["pairs"], s["contacts"]
    peak = m["afu"]["peakPairsPerCycle"]
    compute_bound = pairs / peak * a["cycle_ns"] if pairs else 0.0
    per = lambda ns, n: ns / n if n else ""
    r = {
        "sweep": sw.name, "config": cfg.id, "scpus": cfg.scpus, "scpu_spec": cfg.spec,
        "format": sc["format"]["name"], "distance": sc["distance"], "sqrt_alg": sc["sqrtAlg"],
        "recip_alg": sc["recipAlg"], "rsqrt_alg": sc["rsqrtAlg"], "latency": sc["latency"],
        "link_format": m["link"]["format"], "records": m["buffers"].get("records", {}).get("layout", "full"),
        "record_bytes": m["buffers"]["recordBytes"],
        "scene": scene.id, "hmax": scene.hmax, "steps": scene.steps, "link": link,
        "spheres": s["spheres"], "pairs": pairs, "contacts": contacts,
        "modelled_ns": a["modelled_ns"], "ns_per_collision": per(a["modelled_ns"], contacts),
        "ns_per_pair": per(a["modelled_ns"], pairs),
        "link_bound_ns": a["link_bound_ns"], "over_link_bound": per(a["modelled_ns"], a["link_bound_ns"]),
        "compute_bound_ns": compute_bound, "over_compute_bound": per(a["modelled_ns"], compute_bound),
        "loading_ns": a["loading_ns"], "computing_ns": a["computing_ns"], "wait_read_ns": a["wait_read_ns"],
        "wait_write_ns": a["wait_write_ns"], "other_ns": a["other_ns"], "overhead_ns": a["overhead_ns"],
        "read_lines": a["read_lines"], "write_lines": a["write_lines"], "afu_runs": a["runs"],
        "ode_ns": s["ode_ns"], "simd_ns": s["simd_ns"], "ode_ns_per_collision": per(s["ode_ns"], contacts),
        "simd_ns_per_collision": per(s["simd_ns"], contacts), "cpu_repeat": s.get("cpu_repeat", 1),
        "rtl_wall_ns": s["backend_wall_ns"], "rtl_wall_over_ode": per(s["backend_wall_ns"], s["ode_ns"]),
        "cycles_stepped": a["cycles_stepped"], "cycles_skipped": a["cycles_skipped"],
        "ram_bits": m["afu"]["ram"]["sphereTableBits"] + m["afu"]["ram"]["pairBufferBits"],
    }
    r |= areas
    r |= {f"acc_{k}": v for k, v in acc.items() if k not in ("preset", "latency")}
    r |= drift
    return r


def write_csv(path: Path, rows):
    cols = []
    for r in rows:
        cols += [k for k in r if k not in cols]
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path.with_suffix(".tmp"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols)
        w.writeheader()
        w.writerows(rows)
    path.with_suffix(".tmp").replace(path)


def read_csv(path: Path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))
