"""Fits the `world` preset's measured broad-phase cycles (a BroadPhaseCycleReport CSV of one
configuration, e.g. bench/results/world-lanes/box-buckets.csv) to the linear model the issue
asks for, total cycles against spheres and candidates (bench/world/fit_cycles.py fits it for one
lane). With 16 lanes the finer model on the work itself does not apply: the lanes share the
probes unevenly. Prints the fit (docs/afu.md, "Cycle model and what it predicts", quotes it).

    tools/pyenv bench/world/fit_preset.py [--csv bench/results/world-lanes/box-buckets.csv]
"""
import argparse
import csv
from pathlib import Path

from fit_cycles import fit, formula

ROOT = Path(__file__).resolve().parents[2]
# The columns that name a configuration (the rest are worlds and their counts).
CONFIG = ("lanes", "sort_ports", "word_log2", "cell_steps", "chunk", "coarse_chunks", "team", "feed", "claims",
          "hit_queue", "box_buckets")
TERMS = ["spheres", "candidates"]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--csv", default=str(ROOT / "bench/results/world-lanes/box-buckets.csv"))
    a = ap.parse_args(argv)
    try:
        rows = list(csv.DictReader(open(a.csv, newline="")))
    except OSError as e:
        raise SystemExit(f"{a.csv}: cannot read it: {e.strerror}")
    missing = [k for k in TERMS + ["total"] if not rows or k not in rows[0]]
    if missing:
        raise SystemExit(f"{a.csv}: not a BroadPhaseCycleReport CSV with rows (no column {', '.join(missing)})")
    configs = {tuple(r.get(k) for k in CONFIG) for r in rows}
    if len(configs) != 1:
        raise SystemExit(f"{a.csv}: rows of {len(configs)} configurations; fit one at a time")
    for n, r in enumerate(rows, start=2):
        for k in TERMS + ["total"]:
            try:
                r[k] = int(r[k])
            except ValueError:
                raise SystemExit(f"{a.csv} line {n}: {k} is '{r[k]}', not a whole number")
    out = [f"Least squares over the {len(rows)} worlds of {Path(a.csv).name} (no constant term):", ""]
    coef, worst = fit(rows, "total", TERMS)
    out.append(f"- total cycles = {formula(coef, TERMS)}; worst residual {worst:.1f} %")
    print("\n".join(out))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
