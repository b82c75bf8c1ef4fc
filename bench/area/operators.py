"""What each FP operator pays to reach a clock, and what it reaches: the generator writes each
operator between registers at the latency a clock needs on a family (OperatorGen --mhz) or at a
latency given, then the timing proxy (Yosys's Cyclone V and Arria V cell delays, no routing) and
a real place and route on a Lattice ECP5-85F (bench/area/pnr_ecp5.py) time the same Verilog.

    tools/pyenv bench/area/operators.py [SPEC ...] [--out bench/results/pnr/operators.csv]

SPEC is op:format:family:mhz=F or op:format:family:latency=N (op add, mul, sqrt, recip or rsqrt;
family cyclonev, arriav or ecp5), e.g. add:fp32:cyclonev:mhz=200; a root (digit recurrence) at a
clock has every stage registered, whatever the clock. Without SPECs, the set the results folder holds.
Each row: the operator, its latency and its stages' estimated longest run (the model that placed
its registers), the proxy's slowest path on Cyclone V and Arria V, and the ECP5 result (Fmax,
logic and routing on the critical path, LUT4s, flip-flops, multipliers).
"""
import argparse
import csv
import re
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench" / "area"))
import pnr_ecp5  # noqa: E402

DEFAULT = [f"{op}:{fmt}:cyclonev:mhz=200" for fmt in ("fp16", "fp32") for op in ("add", "mul")] + \
          [f"{op}:{fmt}:ecp5:mhz=100" for fmt in ("fp16", "fp32") for op in ("add", "mul")] + \
          [f"{op}:{fmt}:cyclonev:mhz=200" for fmt in ("fp16", "fp32") for op in ("sqrt", "recip")] + \
          [f"{op}:fp32:cyclonev:latency=1" for op in ("add", "mul")] + ["sqrt:fp32:cyclonev:latency=7"]
FIELDS = ["op", "format", "family", "target_mhz", "latency", "est_ps", "cyclonev_ps", "arriav_ps", "fmax_mhz",
          "path_ns", "logic_ns", "routing_ns", "routing_share", "routed_over_cyclonev", "luts", "ff", "dsp", "commit"]
OPS = ("add", "mul", "sqrt", "recip", "rsqrt")
LINE = re.compile(r"(\S+\.sv) (\S+) (\d+)$")
EST = re.compile(r"longest run (\d+) ps")


def parse_spec(spec: str) -> dict:
    parts = spec.split(":")
    if len(parts) != 4 or parts[0] not in OPS or not re.fullmatch(r"(mhz|latency)=[\d.]+", parts[3]):
        raise SystemExit(f"{spec}: expected op:format:family:mhz=F or op:format:family:latency=N (op one of {', '.join(OPS)})")
    key, val = parts[3].split("=")
    return {"op": parts[0], "format": parts[1], "family": parts[2], key: val}


def generate(specs, out: Path):
    """One sbt run writes every operator; returns (spec, file, top, latency, estimate) each."""
    cmds = []
    for s in specs:
        how = f"--mhz {s['mhz']}" if "mhz" in s else f"--latency {s['latency']}"
        cmds.append(f"runMain collide.fp.report.OperatorGen --op {s['op']} --format {s['format']} "
                    f"--family {s['family']} {how} --out {out}")
    r = subprocess.run([str(ROOT / "tools/sbt"), *cmds], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    files = [m.groups() for line in r.stdout.splitlines() if (m := LINE.search(line.strip()))]
    if r.returncode != 0 or len(files) != len(specs):
        raise SystemExit(f"OperatorGen failed:\n{r.stdout[-3000:]}")
    # sbt prints each run's lines in order: an estimate (add, mul) precedes its file's line.
    out, est = [], ""
    for line in r.stdout.splitlines():
        if (m := EST.search(line)):
            est = m.group(1)
        elif (m := LINE.search(line.strip())):
            out.append((m.group(1), m.group(2), int(m.group(3)), est))
            est = ""
    return [(s, f, top, lat, e) for s, (f, top, lat, e) in zip(specs, out)]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("specs", nargs="*", default=DEFAULT)
    ap.add_argument("--freq", type=float, default=100.0, help="nextpnr's clock constraint (MHz)")
    ap.add_argument("--out", default=str(ROOT / "bench/results/pnr/operators.csv"))
    a = ap.parse_args(argv)
    specs = [parse_spec(s) for s in a.specs]
    rows = []
    with tempfile.TemporaryDirectory() as d:
        for s, f, top, lat, est in generate(specs, Path(d)):
            r = pnr_ecp5.run([f"{f}:{top}"], freq=a.freq, with_proxy=True)[0]
            rows.append({**r, "op": s["op"], "format": s["format"], "family": s["family"],
                         "target_mhz": s.get("mhz", ""), "latency": lat, "est_ps": est})
    Path(a.out).parent.mkdir(parents=True, exist_ok=True)
    with open(a.out, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=FIELDS, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {a.out} ({len(rows)} operators)")


if __name__ == "__main__":
    main()
