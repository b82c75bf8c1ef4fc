"""The AFU's timing proxy, block by block: Yosys's `sta` (bench/area/yosys_timing.sh) on each
block of a generated AFU, with the cell delays Yosys 0.23 ships for Cyclone V and Arria V.

    tools/pyenv bench/area/afu_timing.py [generated/world ...] [--only REGEX] [--area] [--out bench/results/timing/afu.csv]

The blocks are those of the area tables: the AFU, its PUC and (world mode) its BroadPhase are
split into their own logic (every child a black box) and their children, each child whole with
its RAMs as black boxes (bench/sweeplib/area.py's afu_blocks). So a path that crosses
from one block into another is cut at the boundary, each side starting or ending at a port
(arrival 0 at an input): a block's figure is a lower bound of the paths through it.

Each row: the block, its count in the AFU, the slowest path's cell delay in ps for each family
(no routing, which on an FPGA is often as much again, and no RAM clock-to-output), the clock
that delay alone allows (MHz), where the path starts and ends and the LUTs and carry cells on
it, and the commit of the RTL. Cached by each block's Verilog (bench/sweeplib/area.py), as the area is. `--only` keeps the
blocks whose module name matches (for example `--only Scpu_` to compare SCPU configurations).
Without `--only`, each folder also gets its timing.json (bench/area/reached_clock.py).
`--area` also runs the area proxy (bench/area/yosys_area.sh) on each block as it is cut, and adds
its LUT cells, arithmetic cells, DSP blocks and flip-flops: what a shorter path costs. Without it,
those columns are filled for the blocks whose area is already cached, and left empty otherwise;
a folder whose every block has them gets its area against its part in timing.json.
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
from sweeplib import isoarea  # noqa: E402
import reached_clock  # noqa: E402

FIELDS = ["folder", "module", "count", *[f"{f}_ps" for f in area.TIMING_FAMILIES],
          *[f"{f}_mhz" for f in area.TIMING_FAMILIES], "path_from", "path_to", "path_luts", "path_carry",
          "path_dsp", "black_boxes", "commit"]
AREA = area.CELLS  # --area: the block's cells, as area.synth counts them
SIZES = list(isoarea.SIZES)  # its LUT cells by their inputs (areas cached before they were counted: empty)


def afu(folder: Path):
    """(config id, Verilog file, top module) of a generated AFU folder."""
    if not (folder / "manifest.json").exists():
        raise SystemExit(f"{folder}: no manifest.json (generate it first: tools/sbt \"run --preset world\")")
    man = json.loads((folder / "manifest.json").read_text())
    sv = folder / f"{man['topModule']}.sv"
    if not sv.exists():
        raise SystemExit(f"{folder}: no {sv.name}, which its manifest names as the top")
    return man["id"], sv, man["topModule"]


def rtl_commit(folder: Path) -> str:
    """The commit whose source made the folder's Verilog: the folder's own repository's HEAD
    (this one's for a folder outside any), with "+changes" while its RTL sources or generated
    folders differ from it (but for the timing.json files this writes, which are not RTL)."""
    def git(*args, cwd):
        return subprocess.run(["git", *args], cwd=cwd, capture_output=True, text=True)
    repo = folder if git("rev-parse", "--git-dir", cwd=folder).returncode == 0 else ROOT
    top = Path(git("rev-parse", "--show-toplevel", cwd=repo).stdout.strip())
    sha = git("rev-parse", "--short", "HEAD", cwd=top).stdout.strip()
    dirty = git("status", "--porcelain", "--", "src/main", "generated", ":!generated/*/timing.json", cwd=top).stdout.strip()
    return sha + ("+changes" if dirty else "")


def mhz(ps: int) -> str:
    return f"{1e6 / ps:.0f}" if ps else ""


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("folders", nargs="*", default=[str(ROOT / "generated/world")])
    ap.add_argument("--only", default="", help="time only the blocks whose module name matches this regex")
    ap.add_argument("--area", action="store_true", help="also the area proxy of each block (columns " + ", ".join(AREA) + ")")
    ap.add_argument("--out", default=str(ROOT / "bench/results/timing/afu.csv"))
    a = ap.parse_args(argv)
    try:
        only = re.compile(a.only)
    except re.error as e:
        raise SystemExit(f"--only {a.only!r}: not a regular expression ({e})")
    rows = []
    for folder in map(Path, a.folders):
        config_id, sv, top = afu(folder)
        commit = rtl_commit(folder.resolve())
        text = sv.read_text()
        for mod, n, black, what in area.afu_blocks(text, top):
            if not only.search(mod):
                continue
            print(f"timing {mod} ...", flush=True)
            r = area.timing(sv, mod, area.BUILD / "logs" / "timing", config_id, black)
            rows.append({"folder": folder.name, "module": mod, "count": n,
                         **{f"{f}_ps": r[f"{f}_ps"] for f in area.TIMING_FAMILIES},
                         **{f"{f}_mhz": mhz(r[f"{f}_ps"]) for f in area.TIMING_FAMILIES},
                         "path_from": r["path_from"], "path_to": r["path_to"], "path_luts": r["path_luts"],
                         "path_carry": r["path_carry"], "path_dsp": r["path_dsp"], "black_boxes": what, "commit": commit})
            if a.area or area.is_cached(sv, mod, config_id, black):  # an area already measured is reported
                print(f"area {mod} ...", flush=True)
                cells = area.synth(sv, mod, area.BUILD / "logs" / "area", config_id, black)
                rows[-1] |= {k: cells[k] for k in AREA} | {k: cells.get(k, "") for k in SIZES}
    if not rows:
        raise SystemExit(f"--only {a.only!r}: no block of {', '.join(a.folders)} matches")
    Path(a.out).parent.mkdir(parents=True, exist_ok=True)
    with open(a.out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=FIELDS + AREA + SIZES)
        w.writeheader()
        w.writerows(rows)
    fam = area.TIMING_FAMILIES
    print(f"| block | count | {fam[0]} (ps) | MHz | {fam[1]} (ps) | MHz | from | to | LUTs | carry |")
    print("|---|---:|---:|---:|---:|---:|---|---|---:|---:|")
    for r in rows:
        print(f"| {r['module']} | {r['count']} | {r[fam[0] + '_ps']:,} | {r[fam[0] + '_mhz']} | {r[fam[1] + '_ps']:,} | "
              f"{r[fam[1] + '_mhz']} | {r['path_from']} | {r['path_to']} | {r['path_luts']} | {r['path_carry']} |")
    print(f"wrote {a.out}")
    if not a.only:  # every block timed: the clock each folder reaches, for the host (timing.json)
        for folder in map(Path, a.folders):
            commit = next(r["commit"] for r in rows if r["folder"] == folder.name)  # as timed, before any write
            print(f"wrote {reached_clock.write(folder, rows, commit)}")


if __name__ == "__main__":
    main()
