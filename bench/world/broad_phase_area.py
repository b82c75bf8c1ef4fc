"""The whole broad phase's logic, block by block: Yosys (bench/area/yosys_area.sh, the Cyclone V
proxy of every area here) on each module the BroadPhase instantiates, with its RAMs as black
boxes, and on the BroadPhase's own logic with all of them as black boxes; the total is each
block times its count. Synthesized whole, 16 lanes did not finish in 44 minutes; piece by piece
each block takes minutes and is cached (bench/sweeplib/area.py).

    tools/pyenv bench/world/broad_phase_area.py [generated/world] [--out bench/results/world-lanes/broad-phase-area.csv]

RAMs (firtool's memory modules, a `Memory` array each) are left out of the logic: the proxy
has no true dual-port block RAM and would build the sort's two-port tables from flip-flops.
Their bits are the manifest's `afu.ram.broadPhaseBits`. No optimization crosses a block's
boundary here, so a flattened synthesis may come out smaller (a lane's unused status logic, for
one). Writes one row per block and a total row; prints the table.
"""
import argparse
import csv
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
from sweeplib import area  # noqa: E402
sys.path.insert(0, str(Path(__file__).resolve().parent))
from lanes_area import broad_phase  # noqa: E402  (a generated world-mode folder's Verilog and BroadPhase)

# area.FIELDS without M10K: the RAMs are black boxes here, their bits the manifest's.
FIELDS = ("luts", "arith", "dsp", "ff")


memories = area.memories  # firtool's memory modules (bench/sweeplib/area.py)


def blocks(text: str, bp: str):
    """[(module, count, black boxes)]: the BroadPhase's own logic first (every child a black
    box), then each child with the RAMs below it as black boxes (area.blocks)."""
    return [(m, n, black) for m, n, black, _ in area.blocks(text, bp, lambda m: m == bp)]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("folder", nargs="?", default=str(ROOT / "generated/world"))
    ap.add_argument("--out", default=str(ROOT / "bench/results/world-lanes/broad-phase-area.csv"))
    a = ap.parse_args(argv)
    _, config_id, sv, bp, ram_bits, _, _ = broad_phase(Path(a.folder))  # refuses what is not a world-mode AFU
    text = sv.read_text()
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True).stdout.strip()
    rows, total = [], dict.fromkeys(FIELDS, 0)
    for mod, n, black in blocks(text, bp):
        print(f"synthesizing {mod} ...", flush=True)
        r = area.synth(sv, mod, area.BUILD / "logs" / "world-lanes", config_id, frozenset(black))
        own = mod == bp
        rows.append({"module": mod, "count": n, **{f: r[f] for f in FIELDS},
                     "black_boxes": "every block below" if own else "RAMs", "commit": commit})
        for f in FIELDS:
            total[f] += n * r[f]
    rows.append({"module": "total", "count": "", **total, "black_boxes": "", "commit": commit})
    with open(a.out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print(f"| block | count | LUT cells | arithmetic cells | DSP blocks | flip-flops |")
    print("|---|---:|---:|---:|---:|---:|")
    for r in rows:
        print(f"| {r['module']} | {r['count']} | " + " | ".join(f"{r[f]:,}" for f in FIELDS) + " |")
    print(f"RAM (not in the logic above): {int(ram_bits):,} bits; wrote {a.out}")


if __name__ == "__main__":
    main()
