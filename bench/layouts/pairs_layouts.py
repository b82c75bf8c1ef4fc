"""`collide pairs` through AFUs that differ only in their contact record layout: the contacts a
user gets must be the same bytes whatever the layout (docs/afu-interface.md, "Record layouts").

For each SCPU spec (default fp32 and fp16) it builds, through the sweep tool's caches
(build/sweep/gen, build/sweep/host), one 2-SCPU AFU per layout: full, derived, full-masked and
derived-masked. It runs `collide pairs --afu` on one pairs file with each, in compact and
dense mode, over the ideal and the HARP v1 link, and compares the output files byte for byte
within a spec. The same pairs through `--backend simd` (binary32) are set beside the fp32 rows.

    tools/pyenv bench/layouts/pairs_layouts.py [--specs fp32,fp16] [--pairs 6000] [--seed 20261202]
                                               [--out bench/results/layouts]

The pairs (pairs(): seeded) mix overlapping, grazing (a few ulps either side of r1 + r2),
separated, coincident and nested pairs over radii 1e-3..1e2 and centres up to 1e5, some written
as decimal text (the host rounds them once, RNE) and some as hex binary32, plus the bad pairs
of docs/host.md "Bad pairs" (NaN, infinity, a radius <= 0, beyond the sane range), which every
layout must flag the same way. Writes OUT/layouts.csv (one row per run: digest, rows, contacts,
flagged rows, modelled AFU time), OUT/README.md and OUT/MACHINE.md. Exit 1 if any spec's
outputs differ.
"""
import argparse
import csv
import hashlib
import math
import random
import struct
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
from sweeplib import build  # noqa: E402
from sweeplib import generate  # noqa: E402
from sweeplib import machine  # noqa: E402
from sweeplib.sweeps import Config  # noqa: E402

LAYOUTS = ("full", "derived", "full-masked", "derived-masked")
LINKS = ("ideal", "qpi")


def f32(v: float) -> float:
    return struct.unpack("<f", struct.pack("<f", v))[0]


NARROW = ("fp16", "bf16")  # 16-bit links: a finite literal past 65504 is refused by the reader


def pairs(n: int, seed: int, narrow: bool = False) -> list:
    """n seeded pairs (x1, y1, z1, r1, x2, y2, z2, r2) as text fields, then the bad ones. With
    `narrow` the centres stay within 1e3 and the bad pairs within what a 16-bit field reads
    (`collide pairs` refuses a finite literal that overflows the format, naming the line)."""
    rng = random.Random(seed)
    top = 3 if narrow else 5
    rows = []
    for k in range(n):
        r1 = 10 ** rng.uniform(-3, 2)
        r2 = r1 * 10 ** rng.uniform(-1.5, 1.5)
        c = [rng.uniform(-1, 1) * 10 ** rng.uniform(0, top) for _ in range(3)]
        u = [rng.gauss(0, 1) for _ in range(3)]
        norm = math.sqrt(sum(x * x for x in u)) or 1.0
        kind = k % 6
        if kind == 0:
            d = (r1 + r2) * rng.uniform(0.05, 0.999)      # overlapping
        elif kind == 1:
            d = (r1 + r2) * (1 + rng.randint(-8, 8) * 2.0 ** -23)  # grazing: ulps either side
        elif kind == 2:
            d = (r1 + r2) * rng.uniform(1.001, 3)           # separated
        elif kind == 3:
            d = 0.0                                         # coincident centres
        elif kind == 4:
            d = abs(r1 - r2) * rng.uniform(0, 1)            # one inside the other
        else:
            d = (r1 + r2) * rng.uniform(0.9, 1.1)
        p2 = [c[i] + d * u[i] / norm for i in range(3)]
        vals = [*c, r1, *p2, r2]
        if k % 2:  # hex binary32: exactly what reaches a binary32 AFU
            rows.append([float.hex(f32(v)) for v in vals])
        else:      # decimal text: the host rounds it into the link format once
            rows.append([repr(v) for v in vals])
    nan, inf = "nan", "inf"
    bad = [["0", "0", "0", "1", nan, "0", "0", "1"], ["0", "0", "0", inf, "1", "0", "0", "1"],
           ["0", "0", "0", "-1", "0.5", "0", "0", "1"], ["0", "0", "0", "0", "0.5", "0", "0", "1"]]
    if narrow:  # a radius that rounds to zero in the format
        bad += [["0", "0", "0", "1e-9", "0.5", "0", "0", "1"]]
    else:       # beyond the sane range (1e6 m), and near binary32's largest value
        bad += [["2e6", "0", "0", "1", "2e6", "0", "0", "1"], ["0", "0", "0", "2e6", "1", "0", "0", "1"],
                ["1e38", "0", "0", "1", "1e38", "0", "0", "1"]]
    rows.extend(bad)
    return rows


def write_pairs(path: Path, rows) -> None:
    with open(path, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["x1", "y1", "z1", "r1", "x2", "y2", "z2", "r2"])
        w.writerows(rows)


def run_pairs(collide: Path, args: list, pairs_csv: Path, out: Path) -> dict:
    r = subprocess.run([str(collide), "pairs", *args, "--in", str(pairs_csv), "--out", str(out)],
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"{collide} pairs {' '.join(args)}: exit {r.returncode}\n{r.stderr}")
    data = out.read_bytes()
    lines = data.decode().splitlines()
    header = lines[0].split(",")
    hit, flags = header.index("hit"), header.index("flags")
    body = [ln.split(",") for ln in lines[1:]]
    modelled = ""
    for ln in r.stderr.splitlines() + r.stdout.splitlines():
        if "modelled" in ln and " us" in ln:
            modelled = ln.strip()
            break
    return {"sha256": hashlib.sha256(data).hexdigest()[:16], "rows": len(body),
            "contacts": sum(1 for b in body if b[hit] == "1"),
            # REC_NONFINITE | REC_ARITH | REC_HOST_RANGE (generated/afu_contract.hpp): rows to distrust
            "flagged": sum(1 for b in body if int(b[flags] or 0) & (8 | 16 | 32)), "note": modelled}


def outputs_by_spec(rows) -> dict:
    """"spec mode" -> {digest: [the runs that gave it]}: one digest for each is the pass (the
    layouts and links agree). Compact against dense is reported apart (compact_vs_dense)."""
    out = {}
    for r in rows:
        out.setdefault(f"{r['spec']} {r['mode']}", {}).setdefault(r["sha256"], []).append(f"{r['layout']}/{r['link']}")
    return out


def compact_vs_dense(work: Path, rows) -> dict:
    """spec -> rows (pair index, flags compact, flags dense) that differ between the two modes of
    one AFU (the first layout's, over the ideal link)."""
    out = {}
    for spec in dict.fromkeys(r["spec"] for r in rows if r["mode"]):
        cfg = next(r["config"] for r in rows if r["spec"] == spec)
        a = (work / f"{cfg}_ideal.csv").read_text().splitlines()[1:]
        b = (work / f"{cfg}_ideal_dense.csv").read_text().splitlines()[1:]
        out[spec] = [(x.split(",")[0], x.split(",")[-1], y.split(",")[-1]) for x, y in zip(a, b) if x != y]
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--specs", default="fp32,fp16")
    ap.add_argument("--scpus", type=int, default=2)
    ap.add_argument("--pairs", type=int, default=6000)
    ap.add_argument("--seed", type=int, default=20261202)
    ap.add_argument("--out", type=Path, default=ROOT / "bench" / "results" / "layouts")
    a = ap.parse_args(argv)
    start = time.time()
    specs = [s for s in a.specs.split(",") if s]
    configs = {(s, L): Config(a.scpus, s, L) for s in specs for L in LAYOUTS}
    logs = ROOT / "build" / "sweep" / "logs" / "layouts"
    print(f"layouts: generating {len(configs)} AFUs (cached by the RTL's hash)", flush=True)
    generate.generate(list(configs.values()), logs / "generate.log")
    for cfg in configs.values():
        if not build.fresh(cfg):
            print(f"layouts: building {cfg.id}", flush=True)
            build.build(cfg, logs / f"build_{cfg.id}.log")

    work = ROOT / "build" / "layouts"
    work.mkdir(parents=True, exist_ok=True)
    files = {}
    for s in specs:
        narrow = s.split(":")[0].split("-")[0] in NARROW
        files[s] = work / ("pairs_narrow.csv" if narrow else "pairs.csv")
        write_pairs(files[s], pairs(a.pairs, a.seed, narrow))

    rows = []
    for s in specs:
        for L in LAYOUTS:
            cfg = configs[(s, L)]
            for link in LINKS:
                for dense in (False, True):
                    args = ["--afu", str(generate.folder(cfg)), "--link", link] + (["--dense"] if dense else [])
                    out = work / f"{cfg.id}_{link}{'_dense' if dense else ''}.csv"
                    r = run_pairs(build.binary(cfg), args, files[s], out)
                    rows.append({"spec": s, "layout": L, "link": link, "mode": "dense" if dense else "compact",
                                 "config": cfg.id, **r})
    outputs = outputs_by_spec(rows)
    ok = all(len(d) == 1 for d in outputs.values())
    modes = compact_vs_dense(work, rows)
    for s, d in outputs.items():
        if len(d) == 1:
            print(f"layouts: {s}: {len(next(iter(d.values())))} runs, one output ({next(iter(d))})")
        else:
            print(f"layouts: {s}: the outputs DIFFER: {d}", file=sys.stderr)
    # The CPU's binary32 kernel on the same pairs: beside the fp32 rows, for reference.
    any_bin = build.binary(next(iter(configs.values())))
    wide = work / "pairs.csv"
    write_pairs(wide, pairs(a.pairs, a.seed))
    simd = run_pairs(any_bin, ["--backend", "simd"], wide, work / "simd.csv")
    rows.append({"spec": "simd (CPU binary32)", "layout": "", "link": "", "mode": "", "config": "", **simd})

    a.out.mkdir(parents=True, exist_ok=True)
    with open(a.out / "layouts.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()), lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
    report(rows, specs, a, ok, a.out, modes)
    (a.out / "MACHINE.md").write_text(
        f"# Machine\n\n- command: `tools/pyenv bench/layouts/pairs_layouts.py {' '.join(argv or sys.argv[1:])}`\n"
        f"- date: {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {time.time() - start:.0f} s\n"
        f"- commit: {machine.commit()}\n- machine: {machine.describe()}\n")
    return 0 if ok else 1


def report(rows, specs, a, ok, out: Path, modes: dict) -> None:
    lines = ["# `collide pairs` across record layouts", "",
             f"{a.pairs} seeded pairs (seed {a.seed}) plus the bad ones (7; 5 for 16-bit links, whose centres stay within 1e3), through {a.scpus}-SCPU AFUs that differ only "
             "in `--records`, each in compact and dense mode over the ideal and HARP v1 (`qpi`) links: "
             "`tools/pyenv bench/layouts/pairs_layouts.py` (bench/layouts/pairs_layouts.py says how the pairs "
             "are made). The digest is the first 16 hex digits of the output file's SHA-256.", "",
             f"**{'Every spec and mode gives one output whatever the layout and link.' if ok else 'OUTPUTS DIFFER between layouts.'}**", "",
             "| spec | layout | link | mode | digest | rows | contacts | flagged |", "|---|---|---|---|---|---:|---:|---:|"]
    for r in rows:
        lines.append(f"| {r['spec']} | {r['layout']} | {r['link']} | {r['mode']} | `{r['sha256']}` | {r['rows']} | "
                     f"{r['contacts']} | {r['flagged']} |")
    fp32 = [r for r in rows if r["spec"] == "fp32"]
    simd = [r for r in rows if r["spec"].startswith("simd")]
    if fp32 and simd:
        same = fp32[0]["sha256"] == simd[0]["sha256"]
        lines += ["", f"The fp32 AFUs' output is {'the same bytes as' if same else 'not byte-identical to'} the "
                  "simd backend's (binary32 on the CPU)" + ("." if same else
                  ": see the SCPU's documented differences from the CPU kernel in docs/scpu.md; the layouts "
                  "agree with each other, which is what this check is for.")]
    lines += ["", "Compact against dense mode (the same AFU, ideal link):", ""]
    for spec, d in modes.items():
        if not d:
            lines.append(f"- {spec}: the same bytes.")
        else:
            kinds = sorted({(c, dn) for _, c, dn in d})
            lines.append(f"- {spec}: {len(d)} rows differ, all in their flags (compact, dense: "
                         + ", ".join(f"{c} vs {dn}" for c, dn in kinds) + "). Compact mode writes hits only, so a miss "
                         "that the arithmetic flagged (bit 4, overflow or invalid: a 16-bit d^2 overflows past "
                         "|difference| ~ 256) reaches the host as an unflagged miss; dense mode shows the flag.")
    lines += ["", "Machine and command: [MACHINE.md](MACHINE.md).", ""]
    (out / "README.md").write_text("\n".join(lines))


if __name__ == "__main__":
    sys.exit(main())
