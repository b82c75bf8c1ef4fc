"""The broad phase's area against its lanes: Yosys (bench/area/yosys_area.sh, the Cyclone V
proxy of every area here) on the BroadPhase module of generated world-mode AFUs, one per lane
count, through the sweep's cached synthesis (bench/sweeplib/area.py).

    tools/sbt "run --preset world --world-lanes 1 --out /tmp/lanes-gen"   # and 4, 8, ... as wanted
    tools/pyenv bench/world/lanes_area.py generated/world /tmp/lanes-gen/n16_..._world [...]
                                         [--out bench/results/world-lanes/area.csv]

Writes one row per folder: lanes (from its manifest), the BroadPhase module, LUT cells,
arithmetic cells, DSP blocks, flip-flops, M10K blocks, and the broad phase's RAM bits (the
manifest's broadPhaseBits; its sphere-table copies are the SphereRam's, not counted here).
"""
import argparse
import csv
import json
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench" / "sweeplib"))
import area  # noqa: E402


def broad_phase(folder: Path):
    """(lanes, config id, Verilog file, BroadPhase module name) of a generated world-mode folder."""
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
    return int(bp.get("lanes", 1)), config_id, svs[0], names[0], man["afu"]["ram"]["broadPhaseBits"]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("folders", nargs="+", help="generated world-mode AFU folders")
    ap.add_argument("--out", default=str(ROOT / "bench/results/world-lanes/area.csv"))
    a = ap.parse_args(argv)
    rows = []
    for f in map(Path, a.folders):
        lanes, config_id, sv, top, bits = broad_phase(f)
        res = area.synth(sv, top, area.BUILD / "logs" / "world-lanes", config_id)
        rows.append({"lanes": lanes, "module": top, **{k: res[k] for k in area.FIELDS}, "ram_bits": int(bits)})
        print(rows[-1], flush=True)
    rows.sort(key=lambda r: r["lanes"])
    with open(a.out, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
