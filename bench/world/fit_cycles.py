"""Fits the world-mode broad phase's measured RTL cycles (bench/results/world-rtl/cycles.csv,
written by `sbt "Test/runMain collide.world.BroadPhaseCycleReport ..."`) to linear models,
and sets them beside the CPU backends' times on the same spheres (bench/results/world).

    tools/pyenv bench/world/fit_cycles.py [--dir bench/results/world-rtl] [--cpu bench/results/world/world.csv]
                                          [--clock-mhz 200]

Writes DIR/README.md (coefficients, residuals, the table) and DIR/cycles.png. numpy's least
squares does the fits; matplotlib draws the plot.
"""
import argparse
import csv
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]


def load(path):
    rows = list(csv.DictReader(open(path, newline="")))
    for r in rows:
        for k, v in r.items():
            if k != "world":
                r[k] = int(v)
    return rows


def fit(rows, target, terms):
    """Least squares of target on the named columns, no constant (an empty world costs a few
    cycles); returns (coefficients, worst |residual| in %)."""
    a = np.array([[r[t] for t in terms] for r in rows], dtype=float)
    y = np.array([r[target] for r in rows], dtype=float)
    coef, *_ = np.linalg.lstsq(a, y, rcond=None)
    worst = float(np.max(np.abs(a @ coef - y) / y)) * 100
    return coef, worst


def formula(coef, terms):
    return " + ".join(f"{c:.2f} x {t}" for c, t in zip(coef, terms))


def plot(rows, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    for kind in sorted({r["world"] for r in rows if r["world"] in ("uniform", "clustered", "huge")}):
        rs = sorted((r for r in rows if r["world"] == kind), key=lambda r: r["spheres"])
        n = [r["spheres"] for r in rs]
        ax.plot(n, [r["total"] / r["spheres"] for r in rs], "o-", label=f"{kind}: all passes")
        ax.plot(n, [r["grid"] / r["spheres"] for r in rs], ":", color=ax.lines[-1].get_color(), label=f"{kind}: grid generation")
    ax.set_xscale("log")
    ax.set_xlabel("spheres")
    ax.set_ylabel("RTL cycles per sphere (one lane, measured)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=120)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dir", default=str(ROOT / "bench/results/world-rtl"))
    ap.add_argument("--cpu", default=str(ROOT / "bench/results/world/world.csv"))
    ap.add_argument("--clock-mhz", type=float, default=200.0)
    a = ap.parse_args(argv)
    d = Path(a.dir)
    rows = [r for r in load(d / "cycles.csv") if r.get("lanes", 1) == 1]  # one lane: bench/world/lanes.py has the rest
    generated = [r for r in rows if r["world"] in ("uniform", "clustered", "huge")]
    lines = ["# World mode: the broad phase's RTL cycles (one candidate-generator lane)", "",
             "Measured on Verilator by `collide.world.BroadPhaseCycleReport` (every world's pairs checked",
             "against the golden model), fitted by `bench/world/fit_cycles.py`. Cycles are exact counts of",
             "the RTL, independent of the machine that simulated them. Every number: [cycles.csv](cycles.csv);",
             "plot: [cycles.png](cycles.png).", ""]
    simple = ["spheres", "candidates"]
    coef, worst = fit(rows, "total", simple)
    lines += ["## Against spheres and candidates", "",
              f"total cycles = {formula(coef, simple)} (least squares over all {len(rows)} worlds; worst residual",
              f"{worst:.0f} %). Linear, but a poor predictor across clouds: a denser cloud streams more spheres past",
              "each chunk (probes) for the same spheres and candidates. The model below, on the work itself, fits:", ""]
    terms = ["spheres", "buckets", "probes", "chunks", "candidates"]
    coef2, worst2 = fit(rows, "total", terms)
    lines += ["## Against the work the RTL does", "",
              f"total cycles = {formula(coef2, terms)} (worst residual {worst2:.1f} %).", "",
              "What the design predicts for each term: spheres 3 (three reads of the table, one sphere a cycle);",
              "buckets 2/8 or more (the prefix sum and the walk a word of 8 buckets a cycle; the clear overlaps",
              "the first read; an occupied bucket costs the walk more); probes 1 (a sphere streamed past a chunk",
              "a cycle); chunks: a fixed cost per chunk (the",
              "scan's entries, pipeline fill, the drain before the next bucket); candidates: a probe with h hits",
              "holds the stream for h cycles (one pair a cycle leaves the matcher). The fitted terms are",
              "correlated (chunks with buckets, candidates with probes), so read them together, not one by one.", ""]
    lines += ["## Measured worlds", "",
              "uniform, clustered, huge: the spec's generators (BroadPhaseWorlds; huge = uniform plus four spheres",
              "of radius 20 to 1280). Their clustered cloud puts 1 + N/200 Gaussian clusters in a fixed box, so",
              "its density, and its work a sphere, grow with N; the named rows are bench/world/world.py's clouds",
              "(fixed density), whose cycles a sphere stay flat from 10,000 to 65,536.", "",
              "| world | spheres | buckets | cells | candidates | load | classify | prefix | scatter | grid | large pass | total | cycles/sphere | model (1 lane) | RTL / model | us at "
              f"{a.clock_mhz:.0f} MHz |", "|---|" + "---:|" * 15]
    for r in rows:
        lines.append(f"| {r['world']} | {r['spheres']:,} | {r['buckets']:,} | {r['cells']:,} | {r['candidates']:,} | {r['load']:,} | "
                     f"{r['classify']:,} | {r['prefix']:,} | {r['scatter']:,} | {r['grid']:,} | {r['large_pass']:,} | {r['total']:,} | "
                     f"{r['total'] / r['spheres']:.1f} | {r['model_total']:,} | {r['total'] / r['model_total']:.2f} | "
                     f"{r['total'] / a.clock_mhz:,.1f} |")
    cpu_path = Path(a.cpu)
    named = [r for r in rows if r not in generated]
    if cpu_path.exists() and named:
        cpu = list(csv.DictReader(open(cpu_path, newline="")))
        lines += ["", "## The same spheres on the CPU", "",
                  "The clouds of bench/world/world.py (`--dump-clouds`), so the rows below are the very spheres",
                  "bench/results/world timed. CPU: broad + narrow phase, wall clock, fastest of N (that",
                  f"benchmark's machine). RTL: the broad phase's cycles at {a.clock_mhz:.0f} MHz, one lane, not yet",
                  "behind the link (world mode is not in the AFU yet: no table read, no contact writes, no",
                  "narrow phase; 16 SCPUs would take the candidates in candidates / 16 cycles, overlapped).", "",
                  "| cloud | spheres | RTL broad phase (us) | ODE hash (us) | ODE sap (us) | simd grid (us) | ODE best / RTL | simd grid / RTL |",
                  "|---|---:|---:|---:|---:|---:|---:|---:|"]
        for r in named:
            kind, n = r["world"].rsplit("-", 1)
            t = {c["config"]: (float(c["broad_ns"]) + float(c["narrow_ns"])) / 1e3
                 for c in cpu if c["cloud"] == kind and int(c["spheres"]) == int(n)}
            if len(t) < 3:
                continue
            rtl = r["total"] / a.clock_mhz
            best = min(t["ode hash"], t["ode sap"])
            lines.append(f"| {kind} | {int(n):,} | {rtl:,.0f} | {t['ode hash']:,.0f} | {t['ode sap']:,.0f} | {t['simd grid']:,.0f} | "
                         f"{best / rtl:.1f}x | {t['simd grid'] / rtl:.1f}x |")
    lines += ["", "## How", "",
              "    sbt \"Test/runMain collide.world.BroadPhaseCycleReport --max 65536 --spheres CLOUD.csv ... --out bench/results/world-rtl/cycles.csv\"",
              "    tools/pyenv bench/world/fit_cycles.py", "",
              "with the clouds from `tools/pyenv bench/world/world.py --dump-clouds DIR --sizes 670,10000,65536`",
              "(the exact command of this run is in MACHINE.md)."]
    plot(rows, d / "cycles.png")
    (d / "README.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
