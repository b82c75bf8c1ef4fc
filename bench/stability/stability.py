"""Long-horizon stability per arithmetic: scenes at rest from their first step (scenes/rest_pile.json,
scenes/rest_stack.json) run for 2,000 steps with each arithmetic: the SCPU presets on the CPU
(`--backend model:<preset>`, bit for bit the golden model), and ODE's own collider, the binary32
simd kernel and the binary64 one beside them. For each run: kinetic energy, deepest contact and
spheres through a wall, per step (from `collide run --out`), and a table of what they did.

    tools/pyenv bench/stability/stability.py [--collide build/host/collide] [--steps 2000]
        [--scenes rest_pile,rest_stack] [--backends ode,simd,...] [--out bench/results/stability]
    tools/pyenv bench/stability/stability.py --report-only     # redraw from OUT/stability.csv and the step CSVs

Writes OUT/stability.csv (one row per scene and backend), OUT/steps/<scene>-<backend>.csv (the
per-step columns used), OUT/energy.png and OUT/depth.png, OUT/README.md and OUT/MACHINE.md.
"""
import argparse
import csv
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only
import matplotlib.pyplot as plt  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench" / "world"))
from world import machine, write_results  # noqa: E402
from sweeplib.machine import commit  # noqa: E402

SCENES = ("rest_pile", "rest_stack")
# The arithmetic presets of the list on the CPU model, and the CPU backends beside them.
BACKENDS = ("ode", "simd64", "simd", "model:fp64", "model:fp32", "model:fp32-robust", "model:fp24",
            "model:fp16", "model:fp16-robust", "model:bf16")
KEEP = ("step", "contacts", "other_contacts", "kinetic_j", "max_depth_m", "escaped")
# The settling window: the first SETTLE steps are the pile taking up its own weight.
SETTLE = 200


def run(collide, scene, backend, steps, work):
    out, summary = work / "steps.csv", work / "summary.json"
    t = time.time()
    subprocess.run([str(collide), "run", str(ROOT / "scenes" / f"{scene}.json"), "--backend", backend,
                    "--steps", str(steps), "--out", str(out), "--summary", str(summary)],
                   check=True, stdout=subprocess.DEVNULL)
    wall = time.time() - t
    steps_rows = [{k: r[k] for k in KEEP} for r in csv.DictReader(open(out, newline=""))]
    return steps_rows, json.loads(summary.read_text()), wall


def summarize(scene, backend, steps_rows, wall):
    ke = [float(r["kinetic_j"]) for r in steps_rows]
    depth = [float(r["max_depth_m"]) for r in steps_rows]
    contacts = [int(r["contacts"]) for r in steps_rows]
    late = ke[SETTLE:] or ke
    tail = ke[-100:]
    return {"scene": scene, "backend": backend, "steps": len(steps_rows),
            "max_ke_j": max(ke), "max_ke_after_settle_j": max(late), "mean_ke_last100_j": sum(tail) / len(tail),
            "max_depth_mm": 1e3 * max(depth), "max_depth_after_settle_mm": 1e3 * max(depth[SETTLE:] or depth),
            "max_escaped": max(int(r["escaped"]) for r in steps_rows),
            "contacts_first": contacts[0], "contacts_last": contacts[-1], "contacts_min": min(contacts),
            "wall_s": round(wall, 2)}


def plot(out, rows, steps_dir, column, ylabel, name, scale=1.0, log=True):
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    fig, axes = plt.subplots(1, len(scenes), figsize=(7 * len(scenes), 5), squeeze=False)
    for ax, scene in zip(axes[0], scenes):
        for r in rows:
            if r["scene"] != scene:
                continue
            s = list(csv.DictReader(open(steps_dir / f"{scene}-{r['backend'].replace(':', '_')}.csv", newline="")))
            ys = [max(float(x[column]) * scale, 1e-12) if log else float(x[column]) * scale for x in s]
            ax.plot([int(x["step"]) for x in s], ys, label=r["backend"], linewidth=1)
        ax.set_title(scene)
        ax.set_xlabel("step (dt 0.01 s)")
        ax.set_ylabel(ylabel)
        if log:
            ax.set_yscale("log")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / name, dpi=110)
    plt.close(fig)


def report(out, rows, machine_md):
    head = ("| scene | backend | max KE (J) | max KE after step 200 (J) | mean KE, last 100 steps (J) | deepest "
            "contact (mm) | after step 200 (mm) | through a wall | contacts first / last / fewest | wall (s) |\n"
            "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n")
    lines = "".join(f"| {r['scene']} | {r['backend']} | {float(r['max_ke_j']):.3g} | {float(r['max_ke_after_settle_j']):.3g} "
                    f"| {float(r['mean_ke_last100_j']):.3g} | {float(r['max_depth_mm']):.3g} "
                    f"| {float(r['max_depth_after_settle_mm']):.3g} | {r['max_escaped']} "
                    f"| {r['contacts_first']} / {r['contacts_last']} / {r['contacts_min']} | {r['wall_s']} |\n"
                    for r in rows)
    (out / "README.md").write_text(
        "# Long-horizon stability per arithmetic\n\n"
        "Scenes at rest from their first step (`scenes/rest_pile.json`: 452 spheres stacked fcc in a box; "
        "`scenes/rest_stack.json`: a 91-sphere cannonball pyramid in a frame), run under gravity with each "
        "arithmetic: `model:<preset>` is the SCPU of that AFU preset on the CPU, bit for bit the golden model "
        "(`ScpuModelCpp.*` checks it against the golden vectors); `ode` is ODE's own dCollideSpheres, `simd64` "
        "the same arithmetic vectorized, `simd` binary32. Only the sphere/sphere contacts change with the "
        "backend; sphere/plane contacts and the solver are ODE's, in binary64. Kinetic energy is translational "
        "plus rotational; a contact's depth is what the backend reported (sphere/plane: ODE's).\n\n"
        f"{head}{lines}\n"
        "![kinetic energy per step](energy.png)\n\n![deepest contact per step](depth.png)\n\n"
        "Per-step columns of every run: `steps/<scene>-<backend>.csv`.\n\n" + machine_md)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--collide", default=str(ROOT / "build/host/collide"))
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--scenes", default=",".join(SCENES))
    ap.add_argument("--backends", default=",".join(BACKENDS))
    ap.add_argument("--out", default=str(ROOT / "bench/results/stability"))
    ap.add_argument("--report-only", action="store_true")
    a = ap.parse_args(argv)
    out = Path(a.out)
    steps_dir = out / "steps"
    steps_dir.mkdir(parents=True, exist_ok=True)
    if a.report_only:
        rows = list(csv.DictReader(open(out / "stability.csv", newline="")))
    else:
        start = machine()
        rows = []
        with tempfile.TemporaryDirectory() as tmp:
            for scene in a.scenes.split(","):
                for backend in a.backends.split(","):
                    steps_rows, _, wall = run(a.collide, scene, backend, a.steps, Path(tmp))
                    with open(steps_dir / f"{scene}-{backend.replace(':', '_')}.csv", "w", newline="") as f:
                        w = csv.DictWriter(f, fieldnames=list(KEEP))
                        w.writeheader()
                        w.writerows(steps_rows)
                    r = summarize(scene, backend, steps_rows, wall)
                    rows.append(r)
                    print(f"{scene:10} {backend:18} max KE after settling {r['max_ke_after_settle_j']:.3g} J, "
                          f"deepest {r['max_depth_mm']:.3g} mm, escaped {r['max_escaped']}, {wall:.1f} s", flush=True)
        write_results(out, "stability.csv", rows, "bench/stability/stability.py", argv,
                      f"collide: `{Path(a.collide).resolve().relative_to(ROOT) if Path(a.collide).resolve().is_relative_to(ROOT) else a.collide}`, "
                      f"a Release build of this checkout (commit {commit()})", start)
    plot(out, rows, steps_dir, "kinetic_j", "kinetic energy (J)", "energy.png")
    plot(out, rows, steps_dir, "max_depth_m", "deepest contact (mm)", "depth.png", scale=1e3)
    report(out, rows, (out / "MACHINE.md").read_text())
    return 0


if __name__ == "__main__":
    sys.exit(main())
