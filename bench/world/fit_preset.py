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
NUMERIC = ("spheres", "buckets", "cells", "chunks", "scanned", "probes", "candidates", "large", "total")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--csv", default=str(ROOT / "bench/results/world-lanes/box-buckets.csv"))
    a = ap.parse_args(argv)
    rows = list(csv.DictReader(open(a.csv, newline="")))
    configs = {tuple(r[k] for k in r if k not in NUMERIC and k not in ("world",) and not k.startswith("model")
                     and k not in ("load", "classify", "prefix", "scatter", "grid", "large_pass", "box_bits")) for r in rows}
    if len(configs) != 1:
        raise SystemExit(f"{a.csv}: rows of {len(configs)} configurations; fit one at a time")
    for r in rows:
        for k in NUMERIC:
            r[k] = int(r[k])
    out = [f"Least squares over the {len(rows)} worlds of {Path(a.csv).name} (no constant term):", ""]
    terms = ["spheres", "candidates"]
    coef, worst = fit(rows, "total", terms)
    out.append(f"- total cycles = {formula(coef, terms)}; worst residual {worst:.1f} %")
    print("\n".join(out))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
