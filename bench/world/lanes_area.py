"""The broad phase's area against its lanes: Yosys (bench/area/yosys_area.sh, the Cyclone V
proxy of every area here) on the BroadPhase module of generated world-mode AFUs, one per lane
count, through the sweep's cached synthesis (bench/sweeplib/area.py).

    tools/sbt "run --preset world --world-lanes 1 --out /tmp/lanes-gen"   # and 4, 8, ... as wanted
    tools/pyenv bench/world/lanes_area.py generated/world /tmp/lanes-gen/n16_..._world [...]
                                         [--out bench/results/world-lanes/area.csv]

Writes one row per folder: lanes, sort ports and counters a word (from its manifest), the
BroadPhase module, LUT cells, arithmetic cells, DSP blocks, flip-flops, M10K blocks, the broad
phase's RAM bits (the manifest's broadPhaseBits; its sphere-table copies are the SphereRam's, not
counted here) and the commit of the RTL. Rows already in --out for other modules are kept (a
row of an earlier RTL says its commit), so one run adds to the table.
"""
import argparse
import csv
import json
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
from sweeplib import area  # noqa: E402
sys.path.insert(0, str(Path(__file__).resolve().parent))
from lanes import read_area  # noqa: E402  (the area CSV, as the lanes report reads it)


def broad_phase(folder: Path):
    """(lanes, config id, Verilog file, BroadPhase module name, RAM bits, sort ports, counters a
    word) of a generated world-mode folder."""
    if not (folder / "manifest.json").exists():
        raise SystemExit(f"{folder}: no manifest.json (generate it first: tools/sbt \"run --preset world\")")
    man = json.loads((folder / "manifest.json").read_text())
    bp = man["afu"].get("broadPhase")
    if not bp:
        raise SystemExit(f"{folder}: not a world-mode AFU (its manifest has no afu.broadPhase)")
    config_id = man["id"]
    svs = sorted(folder.glob("Afu_*.sv"))
    if len(svs) != 1:
        raise SystemExit(f"{folder}: expected one Afu_*.sv, found {len(svs)}")
    names = sorted(set(re.findall(r"^module (BroadPhase_\w+)\(", svs[0].read_text(), re.M)))
    if len(names) != 1:
        raise SystemExit(f"{folder}: expected one BroadPhase module, found {names}")
    return (int(bp.get("lanes", 1)), config_id, svs[0], names[0], man["afu"]["ram"]["broadPhaseBits"],
            int(bp.get("sortPorts", 1)), 1 << int(bp.get("wordLog2", 3)))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("folders", nargs="+", help="generated world-mode AFU folders")
    ap.add_argument("--out", default=str(ROOT / "bench/results/world-lanes/area.csv"))
    a = ap.parse_args(argv)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True).stdout.strip()
    rows = []
    for f in map(Path, a.folders):
        lanes, config_id, sv, top, bits, ports, per_word = broad_phase(f)
        res = area.synth(sv, top, area.BUILD / "logs" / "world-lanes", config_id)
        rows.append({"lanes": lanes, "sort_ports": ports, "per_word": per_word, "module": top,
                     **{k: res[k] for k in area.FIELDS}, "ram_bits": int(bits), "commit": commit})
        print(rows[-1], flush=True)
    new = {r["module"] for r in rows}
    rows = [r for r in read_area(Path(a.out)) if r["module"] not in new] + rows
    rows.sort(key=lambda r: (r["commit"] == commit, int(r["lanes"]), int(r["sort_ports"])))
    with open(a.out, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=["lanes", "sort_ports", "per_word", "module", *area.FIELDS, "ram_bits", "commit"])
        w.writeheader()
        w.writerows(rows)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
