"""A named sweep as tasks (generate, build, run, measure area/accuracy/drift) and the CSV
made from their cached outputs.

Every step is cached under build/sweep/ and keyed by what it depends on, so a sweep that
stops (Ctrl-C, a crash, a reboot, a cancelled Slurm job) resumes where it was, and a second
run only redoes what changed. An executor (local.py, slurm.py) runs the tasks; `collect`
then reads the results, the same whichever executor ran them."""
import csv
import json
from pathlib import Path

import accuracy
import area
import build
import generate
import runs
from paths import BUILD, EXEC, host_hash, rtl_hash, write_atomic
from sweeps import Scene, Sweep
from tasks import Task, node

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

    def cached(self, d: Path):
        """A run's summary if it was made with today's sources and settings."""
        k, s = d / "key.json", d / "summary.json"
        if k.exists() and s.exists() and json.loads(k.read_text()) == self.key:
            return json.loads(s.read_text())
        return None

    def run_dir(self, cfg, scene, backend, link) -> Path:
        return self.state / cfg.id / scene.id / (link or backend)

    def run_scene(self, cfg, scene, backend, link, positions=False):
        d = self.run_dir(cfg, scene, backend, link)
        hit = self.cached(d)
        if hit is not None:
            return hit, d
        s = runs.run(build.binary(cfg), scene, backend, d, link=link, cpu_repeat=self.cpu_repeat,
                     positions=positions)
        write_atomic(d / "node.txt", node() + "\n")   # the row's timings were measured there
        write_atomic(d / "key.json", json.dumps(self.key))
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
            for scene, backend, link, positions in self.scene_runs(cfg):
                out.append(Task(f"run/{cfg.id}/{scene.id}/{link or backend}", "run", (b,),
                                W_DRIFT if positions else W_RUN,
                                lambda a=(cfg, scene, backend, link, positions): self.run_scene(*a),
                                lambda a=(cfg, scene, backend, link): self.cached(self.run_dir(*a)) is not None))
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

    def synth(self, cfg, block, only_cached=False):
        """Area of cfg's SCPU or PUC (area.synth); only_cached: whether it is cached, without synthesizing."""
        if only_cached and not generate.fresh(cfg, self.key["rtl"]):
            return False
        sv, cid = generate.verilog(cfg), generate.manifest(cfg)["id"]
        top = generate.module_named(cfg, "Scpu_" if block == "scpu" else "Puc_")
        if only_cached:
            return area.is_cached(sv, top, cid)
        return area.synth(sv, top, self.logs, cid)

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
            drift = {}
            if sw.drift_steps:
                d = self.run_dir(cfg, self.drift_scene(), "rtl", "ideal")
                drift = runs.drift(d / "positions.csv", drift_ref) | {"drift_steps": sw.drift_steps}
            for scene in sw.scenes:
                for link in sw.links:
                    d = self.run_dir(cfg, scene, "rtl", link)
                    s = self.cached(d)
                    if s is None:
                        raise RuntimeError(f"{d}: no current result (its run task did not finish)")
                    where = (d / "node.txt").read_text().strip() if (d / "node.txt").exists() else ""
                    rows.append(row(sw, cfg, m, scene, link, s, areas, acc.get(cfg.spec, {}), drift, where))
        write_csv(self.out / f"{sw.name}.csv", rows)
        return rows


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
