"""The clock a generated AFU reaches, written beside its Verilog as timing.json for the host.

    tools/pyenv bench/area/reached_clock.py generated/default generated/world [--csv bench/results/timing/afu.csv]

From the timing proxy's rows of the folder (bench/area/afu_timing.py, which also calls this
after a full run): for each family, the slowest block's cells-only delay and the clock it
allows. That is an upper bound on the frequency (no routing). Beside it, a routing-calibrated
estimate: the proxy's period times the median ratio of routed (nextpnr-ecp5) to cells-only
(Cyclone V proxy) delay over the operators of bench/results/pnr/operators.csv, a model, not a
measurement of an Intel part (docs/timing.md).

timing.json names the Verilog it describes by SHA-256, so the host build (CollideVerilate.cmake)
uses it only for that Verilog; the rows must come from the commit of the folder's Verilog.
"""
import argparse
import csv
import hashlib
import json
import statistics
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
from sweeplib import area  # noqa: E402
from sweeplib import isoarea  # noqa: E402

PNR_CSV = ROOT / "bench/results/pnr/operators.csv"


def routed_ratio(pnr_csv: Path = PNR_CSV):
    """(median routed / Cyclone V cells-only ratio, how many operators) from the P&R results."""
    with open(pnr_csv) as f:
        ratios = [float(r["routed_over_cyclonev"]) for r in csv.DictReader(f) if r["routed_over_cyclonev"]]
    if not ratios:
        raise SystemExit(f"{pnr_csv}: no routed_over_cyclonev figures")
    return statistics.median(ratios), len(ratios)


def sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def describe(folder: Path, rows, commit: str, pnr_csv: Path = PNR_CSV) -> dict:
    """timing.json's content for the folder from its afu.csv rows (dicts as afu_timing writes)."""
    rows = [r for r in rows if r["folder"] == folder.name]
    if not rows:
        raise SystemExit(f"{folder}: no rows of it in the timing CSV (run bench/area/afu_timing.py {folder})")
    ratio, n = routed_ratio(pnr_csv)
    families = {}
    for fam in area.TIMING_FAMILIES:
        worst = max(rows, key=lambda r: int(r[f"{fam}_ps"]))
        ps = int(worst[f"{fam}_ps"])
        if ps <= 0:
            raise SystemExit(f"{folder}: no timed block for {fam}")
        families[fam] = {"slowest_block": worst["module"], "cells_ps": ps, "proxy_mhz": round(1e6 / ps, 2),
                         "routed_estimate_mhz": round(1e6 / (ps * ratio), 2)}
    out = {
        "what": "the clock this Verilog reaches by the timing proxy: Yosys sta over each family's cell delays, "
                "block by block, no routing (an upper bound on the frequency); routed_estimate_mhz divides it by the "
                "median routed/cells-only ratio of the ECP5 place and route (a model)",
        "commit": commit,
        "verilog": {sv.name: sha256(sv) for sv in sorted(folder.glob("*.sv"))},
        "families": families,
        "routing_model": {"ratio": round(ratio, 3), "operators": n, "source": "bench/results/pnr/operators.csv"},
    }
    fit = area_on_part(folder, rows)
    if fit:
        out["area"] = fit
    return out


def area_on_part(folder: Path, rows):
    """The area proxy's cells summed over the folder's blocks (each times its count; RAMs are
    black boxes, counted by the generator's M20K estimate instead) and the ALMs they take
    against the part its manifest names: None unless every block has its area."""
    if not all(r.get(k) not in (None, "") for r in rows for k in area.CELLS):
        return None
    total = {k: sum(int(r["count"]) * int(r[k]) for r in rows) for k in area.CELLS}
    alms = {c: isoarea.alms(total["luts"], total["arith"], total["ff"], c) for c in isoarea.CALIBRATIONS}
    # By the LUTs' inputs, block by block (a block's LUTs share ALMs only with its own).
    by_size = [isoarea.alms_by_size(r) for r in rows]
    if all(b is not None for b in by_size):
        alms["by_size"] = sum(int(r["count"]) * b for r, b in zip(rows, by_size))
    out = {"what": "the area proxy (Yosys synth_intel_alm, Cyclone V cells) over every block, RAMs apart; ALMs "
                   "packed: max((LUT + adder cells) / 2, FFs / 4), a lower bound; unpacked: LUT + adder cells, "
                   "one LUT an ALM, an upper bound; by_size (where the LUTs' inputs were counted): a 6-input LUT an "
                   "ALM, a 5-input one an ALM shared with a LUT of 3 or fewer inputs, other LUTs and adder cells two an "
                   "ALM, block by block, the estimate a fit is judged by",
           **total, "alms": alms}
    manifest = folder / "manifest.json"
    device = json.loads(manifest.read_text()).get("device") if manifest.exists() else None
    if device:
        out["device"] = {"name": device["name"], "alms": device["alms"], "dsp_blocks": device["dspBlocks"],
                         "alms_share": {c: round(v / device["alms"], 3) for c, v in alms.items()},
                         "dsp_share": round(total["dsp"] / device["dspBlocks"], 3)}
    return out


def write(folder: Path, rows, commit: str) -> Path:
    out = folder / "timing.json"
    out.write_text(json.dumps(describe(folder, rows, commit), indent=2) + "\n")
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("folders", nargs="+")
    ap.add_argument("--csv", default=str(ROOT / "bench/results/timing/afu.csv"))
    a = ap.parse_args(argv)
    with open(a.csv) as f:
        rows = list(csv.DictReader(f))
    for folder in map(Path, a.folders):
        commits = {r["commit"] for r in rows if r["folder"] == folder.name}
        if len(commits) != 1 or "+changes" in next(iter(commits), "+changes"):
            raise SystemExit(f"{folder}: the CSV's rows name {sorted(commits) or 'no commit'}; need one clean commit")
        commit = commits.pop()
        # The rows must describe this Verilog: unchanged since the commit they timed.
        diff = subprocess.run(["git", "diff", "--quiet", commit, "--", str(folder.resolve() / "*.sv")], cwd=ROOT)
        if diff.returncode != 0:
            raise SystemExit(f"{folder}: its Verilog changed since {commit}, which the CSV timed: run "
                             f"bench/area/afu_timing.py {folder} again")
        print(f"wrote {write(folder, rows, commit)}")


if __name__ == "__main__":
    main()
