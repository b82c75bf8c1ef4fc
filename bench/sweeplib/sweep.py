"""A named sweep as tasks (generate, build, run, measure area/accuracy/drift) and the CSV
made from their cached outputs.

Every step is cached under build/sweep/ and keyed by what it depends on, so a sweep that
stops (Ctrl-C, a crash, a reboot, a cancelled Slurm job) resumes where it was, and a second
run only redoes what changed. An executor (local.py, slurm.py) runs the tasks; `collect`
then reads the results, the same whichever executor ran them."""
import csv
import json
from pathlib import Path

from . import accuracy
from . import area
from . import build
from . import generate
from . import runs
from .paths import BUILD, EXEC, host_hash, rtl_hash, write_atomic
from .sweeps import Scene, Sweep
from .tasks import Task, node

# Rough cost of each step in seconds on a 2-core machine: the progress bar's weights, so
# its time-left estimate is about right before many steps have been timed.
W_GEN, W_RUN, W_DRIFT, W_ACC = 25, 3, 5, 90

# Columns measured by the clock of the node that ran the row (they move between runs and
# machines); every other column is the same whichever executor or node ran it.
TIMING_COLUMNS = ("ode_ns", "simd_ns", "ode_ns_per_collision", "simd_ns_per_collision", "rtl_wall_ns",
                  "rtl_wall_over_ode")


def w_build(cfg):
    return 30 + 12 * cfg.scpus * (2 if "64" in cfg.spec else 1)


def w_area(cfg, block):
    if block == "puc":
        return 200 * (2 if cfg.scpus >= 16 else 1)
    return 600 if "64" in cfg.spec else 200


def w_timing(cfg, part):
    return 2 * w_area(cfg, "scpu") if part == "scpu" else 150


# A link name with this suffix: the link preset run at the clock the AFU's cells allow (the
# timing proxy's first family, the slowest block of the AFU), not at the preset's own clock.
AT_CELLS = "@cells"
TIMING_PARTS = ("scpu", "rest")  # the SCPU, and the slowest of the AFU's other blocks


class Runner:
    def __init__(self, sweep, out: Path, do_area: bool, cpu_repeat: int, work: Path = None):
        """work: where the scene runs, the executors' state and the logs go (default
        build/sweep/{runs,exec,logs}/NAME; tests give a temporary folder). Generated Verilog,
        host builds and areas are shared by every sweep whatever `work` is."""
        self.sweep, self.out, self.do_area = sweep, out, do_area and sweep.area
        self.cpu_repeat = cpu_repeat or sweep.cpu_repeat
        self.work = work
        self.state = work / "runs" if work else BUILD / "runs" / sweep.name   # the scene runs' summaries
        self.exec = work / "exec" if work else EXEC / sweep.name              # plan, task records, Slurm jobs
        self.logs = work / "logs" if work else BUILD / "logs" / sweep.name
        self.key = {"rtl": rtl_hash(), "host": host_hash(), "cpu_repeat": self.cpu_repeat}
        self.do_timing = do_area and sweep.timing
        self._timed = {}  # (config, part) -> timed(): what Yosys's cached reports say

    def settings(self) -> dict:
        """Everything a Slurm task needs to rebuild this runner on its node (worker.py)."""
        return {"sweep": self.sweep.to_dict(), "out": str(self.out), "do_area": self.do_area,
                "cpu_repeat": self.cpu_repeat, "work": str(self.work) if self.work else None}

    def write_plan(self) -> Path:
        """exec/plan.json: the settings, for Slurm tasks (worker.py) and `bench/sweep status`."""
        p = self.exec / "plan.json"
        write_atomic(p, json.dumps(self.settings(), indent=1) + "\n")
        return p

    @staticmethod
    def from_settings(d: dict) -> "Runner":
        return Runner(Sweep.from_dict(d["sweep"]), Path(d["out"]), d["do_area"], d["cpu_repeat"],
                      Path(d["work"]) if d["work"] else None)

    def run_key(self, cfg, link) -> dict:
        """What a run's result depends on: the sources and settings, and for a run at the cells'
        clock that clock (which moves with the timing proxy)."""
        return self.key | ({"clock_mhz": self.at_cells_mhz(cfg, link)} if link and link.endswith(AT_CELLS) else {})

    def at_cells_mhz(self, cfg, link) -> float:
        """The clock of a `<preset>@cells` run: what the AFU's cells allow, but never above the
        preset's own clock (a design that reaches more still runs at its target's)."""
        return min(self.cells_mhz(cfg), self.preset_clock(cfg, link[:-len(AT_CELLS)]))

    def preset_clock(self, cfg, preset: str) -> float:
        return runs.preset_clock(build.binary(cfg), preset)

    def has_binary(self, cfg) -> bool:
        return build.binary(cfg).exists()

    def cached(self, d: Path, cfg=None, link=None):
        """A run's summary if it was made with today's sources and settings."""
        k, s = d / "key.json", d / "summary.json"
        if not (k.exists() and s.exists()):
            return None
        if link and link.endswith(AT_CELLS) and not (all(self.timed(cfg, p, only_cached=True) for p in TIMING_PARTS)
                                                     and self.has_binary(cfg)):
            return None  # its clock needs both parts' timing and the binary's link presets
        return json.loads(s.read_text()) if json.loads(k.read_text()) == self.run_key(cfg, link) else None

    def run_dir(self, cfg, scene, backend, link) -> Path:
        return self.state / cfg.id / scene.id / (link or backend)

    def run_scene(self, cfg, scene, backend, link, positions=False):
        d = self.run_dir(cfg, scene, backend, link)
        hit = self.cached(d, cfg, link)
        if hit is not None:
            return hit, d
        key = self.run_key(cfg, link)
        preset, clock = (link[:-len(AT_CELLS)], key["clock_mhz"]) if "clock_mhz" in key else (link, None)
        s = runs.run(build.binary(cfg), scene, backend, d, link=preset, cpu_repeat=self.cpu_repeat,
                     positions=positions, clock_mhz=clock)
        write_atomic(d / "node.txt", node() + "\n")   # the row's timings were measured there
        write_atomic(d / "key.json", json.dumps(key))
        return s, d

    def drift_scene(self):
        sw = self.sweep
        return Scene(10, sw.drift_steps) if sw.name != "smoke" else Scene(sw.scenes[0].hmax, sw.drift_steps)

    def tasks(self) -> list:
        """Every step of the sweep, with what it needs first. sbt steps (generate, accuracy) run
        one after the other: two sbt sessions cannot share the checkout's target/."""
        sw, logs, rkey = self.sweep, self.logs, self.key["rtl"]
        stale = [c for c in sw.configs if not generate.fresh(c, rkey)]
        out = [Task("generate", "generate", (), W_GEN * max(1, len(stale)),
                    lambda: generate.generate(sw.configs, logs / "generate.log"),
                    lambda: all(generate.fresh(c, rkey) for c in sw.configs))]
        if sw.accuracy:
            specs = [c.spec for c in sw.configs]
            out.append(Task("accuracy", "accuracy", ("generate",), W_ACC,
                            lambda: accuracy.measure(specs, logs / "accuracy.log"),
                            lambda: accuracy.cache_file(specs).exists()))
        scpu_blocks = {}  # one SCPU synthesis per spec and layout: the SCPU does not change with the count
        scpu_timed = {}   # the same for its timing
        for cfg in sw.configs:
            b = f"build/{cfg.id}"
            out.append(Task(b, "build", ("generate",), w_build(cfg),
                            lambda cfg=cfg: build.build(cfg, logs / f"build-{cfg.id}.log"),
                            lambda cfg=cfg: build.fresh(cfg), size="big" if cfg.scpus >= 16 else "normal"))
            if self.do_area:
                blocks = ["puc"] if sw.puc_area else []
                if scpu_blocks.setdefault((cfg.spec, cfg.records), cfg) is cfg:
                    blocks.insert(0, "scpu")
                for block in blocks:
                    big = "64" in cfg.spec if block == "scpu" else cfg.scpus >= 16
                    out.append(Task(f"area/{cfg.id}/{block}", "area", ("generate",), w_area(cfg, block),
                                    lambda cfg=cfg, block=block: self.synth(cfg, block),
                                    lambda cfg=cfg, block=block: self.synth(cfg, block, only_cached=True),
                                    size="big" if big else "normal"))
            timed = ()
            if self.do_timing:
                owner = scpu_timed.setdefault((cfg.spec, cfg.records), cfg)
                timed = (f"timing/{owner.id}/scpu", f"timing/{cfg.id}/rest")
                for part in TIMING_PARTS if owner is cfg else TIMING_PARTS[1:]:
                    out.append(Task(f"timing/{cfg.id}/{part}", "timing", ("generate",), w_timing(cfg, part),
                                    lambda cfg=cfg, part=part: self.timed(cfg, part),
                                    lambda cfg=cfg, part=part: self.timed(cfg, part, only_cached=True),
                                    size="big" if part == "scpu" and "64" in cfg.spec else "normal"))
            for scene, backend, link, positions in self.scene_runs(cfg):
                cells = bool(link) and link.endswith(AT_CELLS)
                out.append(Task(f"run/{cfg.id}/{scene.id}/{link or backend}", "run", (b, *timed) if cells else (b,),
                                W_DRIFT if positions else W_RUN,
                                lambda a=(cfg, scene, backend, link, positions): self.run_scene(*a),
                                lambda a=(cfg, scene, backend, link): self.cached(self.run_dir(*a), a[0], a[3]) is not None))
        ids = [t.id for t in out]
        if len(ids) != len(set(ids)):
            raise RuntimeError(f"sweep {sw.name}: two steps share an id: {sorted(i for i in ids if ids.count(i) > 1)}")
        return out

    def scene_runs(self, cfg):
        """(scene, backend, link, positions?) of each run through cfg's binary: the drift's ODE
        reference (the first configuration's binary runs it), its drift run, then the sweep's
        scenes and links."""
        sw = self.sweep
        if sw.drift_steps:
            if cfg == sw.configs[0]:
                yield self.drift_scene(), "ode", None, True
            yield self.drift_scene(), "rtl", "ideal", True
        for scene in sw.scenes:
            for link in sw.links:
                yield scene, "rtl", link, False
            if self.do_timing:
                for link in sw.links:
                    yield scene, "rtl", link + AT_CELLS, False

    def synth(self, cfg, block, only_cached=False):
        """Area of cfg's SCPU or PUC (area.synth); only_cached: whether it is cached, without synthesizing."""
        if only_cached and not generate.fresh(cfg, self.key["rtl"]):
            return False
        sv, cid = generate.verilog(cfg), generate.manifest(cfg)["id"]
        top = generate.module_named(cfg, "Scpu_" if block == "scpu" else "Puc_")
        if only_cached:
            return area.is_cached(sv, top, cid)
        return area.synth(sv, top, self.logs, cid)

    def timed(self, cfg, part, only_cached=False):
        """The timing proxy (area.timing) of cfg's AFU as bench/area/afu_timing.py cuts it into
        blocks: part "scpu" the SCPU, "rest" the slowest of its other blocks (TIMING_PARTS). A
        dict: <family>_ps for each of area.TIMING_FAMILIES, the block and its path (first
        family); kept for the runner's life, since the rows and the runs at the cells'
        clock each ask again. only_cached: whether every block it needs is cached, without Yosys."""
        if not only_cached and (cfg, part) in self._timed:
            return self._timed[(cfg, part)]
        if only_cached and not generate.fresh(cfg, self.key["rtl"]):
            return False
        sv, m = generate.verilog(cfg), generate.manifest(cfg)
        blocks = [(mod, black) for mod, _, black, _ in area.afu_blocks(sv.read_text(), m["topModule"])
                  if mod.startswith("Scpu_") == (part == "scpu")]
        if not blocks:
            raise RuntimeError(f"{cfg.id}: no {part} block in {sv}")
        if only_cached:
            return all(area.timing_is_cached(sv, mod, m["id"], black) for mod, black in blocks)
        res = [area.timing(sv, mod, self.logs / "timing", m["id"], black) | {"block": mod} for mod, black in blocks]
        self._timed[(cfg, part)] = max(res, key=lambda r: r[f"{area.TIMING_FAMILIES[0]}_ps"])
        return self._timed[(cfg, part)]

    def cells_mhz(self, cfg) -> float:
        """The clock the AFU's cells allow (cells_mhz of its two parts)."""
        return cells_mhz(*(self.timed(cfg, p) for p in TIMING_PARTS), cfg.id)

    def collect(self) -> list:
        """The CSV's rows from the tasks' cached outputs (every task done), written to NAME.csv."""
        sw = self.sweep
        acc = accuracy.measure([c.spec for c in sw.configs], self.logs / "accuracy.log") if sw.accuracy else {}
        drift_ref = self.run_dir(sw.configs[0], self.drift_scene(), "ode", None) / "positions.csv"
        rows = []
        for cfg in sw.configs:
            m = generate.manifest(cfg)
            areas = {}
            if self.do_area:  # cached by the area tasks: these are look-ups
                scpu = self.synth(cfg, "scpu")
                areas = area.afu_area(self.synth(cfg, "puc") if sw.puc_area else None, scpu, cfg.scpus)
            clock = {}
            if self.do_timing:  # cached by the timing tasks
                clock = timing_columns(self.timed(cfg, "scpu"), self.timed(cfg, "rest"), m["id"])
            drift = {}
            if sw.drift_steps:
                d = self.run_dir(cfg, self.drift_scene(), "rtl", "ideal")
                drift = runs.drift(d / "positions.csv", drift_ref) | {"drift_steps": sw.drift_steps}
            for scene, _, link, positions in self.scene_runs(cfg):
                if positions:
                    continue
                d = self.run_dir(cfg, scene, "rtl", link)
                s = self.cached(d, cfg, link)
                if s is None:
                    raise RuntimeError(f"{d}: no current result (its run task did not finish)")
                where = (d / "node.txt").read_text().strip() if (d / "node.txt").exists() else ""
                rows.append(row(sw, cfg, m, scene, link, s, areas | clock, acc.get(cfg.spec, {}), drift, where))
        write_csv(self.out / f"{sw.name}.csv", rows)
        return rows


def cells_mhz(scpu: dict, rest: dict, config_id: str) -> float:
    """The clock the slower of an AFU's two parts allows: its delay in the first family."""
    ps = max(scpu[f"{area.TIMING_FAMILIES[0]}_ps"], rest[f"{area.TIMING_FAMILIES[0]}_ps"])
    if not ps:
        raise RuntimeError(f"{config_id}: the timing proxy found no path in any block")
    return round(1e6 / ps, 3)


def timing_columns(scpu: dict, rest: dict, config_id: str) -> dict:
    """The timing proxy's columns of a configuration: its SCPU's slowest path and the slowest of
    its other blocks, each family in ps, and the clock the slower of the two allows (first
    family). Block names lose the configuration's id, which every module name carries."""
    fam = area.TIMING_FAMILIES
    r = {}
    for part, t in (("scpu", scpu), ("rest", rest)):
        r |= {f"{part}_{f}_ps": t[f"{f}_ps"] for f in fam}
        r[f"{part}_path"] = (f"{t['path_from'] or '<input>'} -> {t['path_to']}: {t['path_luts']} LUTs, "
                             f"{t['path_carry']} carry, {t['path_dsp']} DSP").replace(f"_{config_id}", "")
    r["rest_block"] = rest["block"].replace(f"_{config_id}", "")
    r["cells_mhz"] = cells_mhz(scpu, rest, config_id)
    return r


def clock_columns(c) -> dict:
    """Which clock a row's AFU times use and whether its design reaches it: the run summary's
    afu.clock (the host times at the lower of the target and the timing proxy's clock, where
    its build has the Verilog's timing.json; --clock-mhz is a study)."""
    if not c:
        return {"clock_kind": "", "clock_reached": "", "proxy_mhz": "", "routed_estimate_mhz": ""}
    r = c.get("reached") or {}
    kind = "study" if c.get("study") else ("target" if c.get("reaches_target") else
                                           ("reached" if r else "target, not measured"))
    return {"clock_kind": kind, "clock_reached": "" if not r else c.get("reaches_target", ""),
            "proxy_mhz": r.get("proxy_mhz", ""), "routed_estimate_mhz": r.get("routed_estimate_mhz", "")}


def row(sw, cfg, m, scene, link, s, areas, acc, drift, where=""):
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
        "node": where,  # the machine whose clock the timing columns are from (MACHINE.md describes it)
        "rtl_wall_ns": s["backend_wall_ns"], "rtl_wall_over_ode": per(s["backend_wall_ns"], s["ode_ns"]),
        "clock_mhz": round(1e3 / a["cycle_ns"], 3) if a.get("cycle_ns") else "",
        **clock_columns(a.get("clock")),
        "cycles_stepped": a["cycles_stepped"], "cycles_skipped": a["cycles_skipped"],
        "ram_bits": m["afu"]["ram"]["sphereTableBits"] + m["afu"]["ram"]["pairBufferBits"],
        "ram_ports": cfg.ram or "replicated", "sphere_table_bits": m["afu"]["ram"]["sphereTableBits"],
        "sphere_table_m20k": m["afu"]["ram"].get("sphereTableM20k", ""), "ram_banks": m["afu"]["ram"].get("banks", 1),
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
