"""What each pair kind's unit costs: latency, the area proxy's cells and the timing proxy's
slowest path, for the sphere SCPU's datapath (sphere/sphere), SpherePlane and CapsuleSphere
built from the same SCPU configuration (docs/pair-kinds.md).

    tools/pyenv bench/pairs/unit_cost.py [SPEC ...] [--out bench/results/pair-kinds/units.csv]

SPEC is an SCPU configuration as the generator takes it (default: fp16:mhz=200 fp32:mhz=200,
every operator pipelined for 200 MHz). One sbt run writes the units (collide.pairs.report.
PairUnitsGen); then Yosys's area proxy (bench/area/yosys_area.sh: LUT cells, carry cells, DSP
blocks, flip-flops) and timing proxy (bench/area/yosys_timing.sh: Cyclone V and Arria V cell
delays, no routing) on each, two at a time, cached by the Verilog (bench/sweeplib/area.py).
`--cached-only` writes the rows whose results are cached and leaves the others "not measured"
(for a run cut short: Yosys takes minutes on a unit holding an SCPU datapath).
"""
import argparse
import csv
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from sweeplib import area
from sweeplib.paths import ROOT

FIELDS = ["kind", "scpu", "latency", *area.CELLS, *[f"{f}_ps" for f in area.TIMING_FAMILIES],
          *[f"{f}_mhz" for f in area.TIMING_FAMILIES], "path_from", "path_to", "commit"]


def generate(specs, out: Path):
    cmd = f"runMain collide.pairs.report.PairUnitsGen --out {out} {' '.join(specs)}"
    r = subprocess.run([str(ROOT / "tools" / "sbt"), cmd], cwd=ROOT, capture_output=True, text=True)
    rows = []
    for line in r.stdout.splitlines():
        parts = line.replace("[info] ", "").split()
        if len(parts) == 5 and parts[0].endswith(".sv"):
            rows.append({"file": ROOT / parts[0], "top": parts[1], "latency": int(parts[2]), "kind": parts[3], "scpu": parts[4]})
    if r.returncode != 0 or len(rows) != 3 * len(specs):
        raise SystemExit(f"PairUnitsGen failed (rc {r.returncode}):\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}")
    return rows


def cost(u: dict, log_dir: Path, cached_only: bool = False) -> dict:
    cid = u["top"].split("_", 1)[1]  # the SCPU configuration's id, which every module name carries
    if cached_only and not (area.is_cached(u["file"], u["top"], cid) and area.timing_is_cached(u["file"], u["top"], cid)):
        return {"kind": u["kind"], "scpu": u["scpu"], "latency": u["latency"], "path_from": "not measured"}
    a = area.synth(u["file"], u["top"], log_dir, cid)
    t = area.timing(u["file"], u["top"], log_dir, cid)
    row = {"kind": u["kind"], "scpu": u["scpu"], "latency": u["latency"], **{k: a.get(k, "") for k in area.CELLS}}
    for f in area.TIMING_FAMILIES:
        ps = t[f"{f}_ps"]
        row[f"{f}_ps"] = ps
        row[f"{f}_mhz"] = round(1e6 / ps) if ps else ""
    row["path_from"], row["path_to"] = t["path_from"], t["path_to"]
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("specs", nargs="*", default=["fp16:mhz=200", "fp32:mhz=200"])
    ap.add_argument("--out", default=str(ROOT / "bench" / "results" / "pair-kinds" / "units.csv"))
    ap.add_argument("--cached-only", action="store_true", help="report cached results only, the rest 'not measured'")
    a = ap.parse_args()
    build = ROOT / "build" / "pair-units"
    units = generate(a.specs, build)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True).stdout.strip()
    with ThreadPoolExecutor(2) as pool:
        rows = list(pool.map(lambda u: cost(u, build / "logs", a.cached_only), units))
    out = Path(a.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    with out.open("w", newline="") as f:
        w = csv.DictWriter(f, FIELDS)
        w.writeheader()
        for r in rows:
            w.writerow({**r, "commit": commit})
    for r in rows:
        print(f"{r['kind']:15} {r['scpu']:14} latency {r['latency']:4}  luts {r.get('luts', '-')}  dsp {r.get('dsp', '-')}  "
              f"ff {r.get('ff', '-')}  cyclonev {r.get('cyclonev_ps', '-')} ps")
    print(f"wrote {out}")


if __name__ == "__main__":
    sys.exit(main())
