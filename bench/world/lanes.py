"""What several candidate-generator lanes, and the sort's second port, buy the world-mode broad
phase: measured RTL cycles (`sbt "Test/runMain collide.world.BroadPhaseCycleReport --lanes
1,2,4,8,16 --sort-ports 1,2 ..."`, every world's pairs checked against the golden model) per
world and configuration (lanes, sort ports; a CSV without sort_ports has one port).

    tools/pyenv bench/world/lanes.py --csv CYCLES.csv [--out bench/results/world-lanes] [--clock-mhz 200]
                                     [--machine TEXT]

Writes OUT/cycles.csv (a copy of the input), OUT/README.md (cycles, speed-up over one lane,
candidates a cycle, where the cycles go; and the area, when OUT/area.csv from
bench/world/lanes_area.py is there) and OUT/lanes.png (speed-up against lanes, log2 axes).
matplotlib draws the plot.
"""
import argparse
import csv
import shutil
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PASSES = ("load", "classify", "prefix", "scatter", "grid", "large_pass")


def load(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows or "lanes" not in rows[0]:
        raise SystemExit(f"{path}: no 'lanes' column; write it with BroadPhaseCycleReport --lanes")
    for r in rows:
        for k, v in r.items():
            if k != "world":
                r[k] = int(v)
        r.setdefault("sort_ports", 1)
        r.setdefault("word_log2", 3)
    return rows


def config(r):
    """(sort ports, counters a word, lanes): one port and eight counters a word first, so the
    one-lane, one-port run is the baseline."""
    return (r["sort_ports"], r["word_log2"], r["lanes"])


def extras(c):
    ports, word_log2, _ = c
    return (f", {ports} ports" if ports > 1 else "") + (f", {1 << word_log2} a word" if word_log2 != 3 else "")


def label(c):
    lanes = c[2]
    return f"{lanes} lane{'s' if lanes > 1 else ''}" + extras(c)


def best_label(c):
    return f"{c[2]}" + extras(c)


def worlds(rows):
    """(world, spheres) in first-seen order."""
    seen = []
    for r in rows:
        if (r["world"], r["spheres"]) not in seen:
            seen.append((r["world"], r["spheres"]))
    return seen


def table(rows, clock_mhz):
    configs = sorted({config(r) for r in rows})
    by = {(r["world"], r["spheres"], config(r)): r for r in rows}
    out = ["| world | spheres | candidates | " + " | ".join(label(c) for c in configs) +
           f" | best: speed-up | its grid's speed-up | candidates a cycle | passes' share | us at {clock_mhz:.0f} MHz |",
           "|---|---:|---:|" + "---:|" * len(configs) + "---:|---:|---:|---:|---:|"]
    for w, n in worlds(rows):
        rs = [by.get((w, n, c)) for c in configs]
        if rs[0] is None or any(r is None for r in rs):
            continue
        best = min(rs, key=lambda r: r["total"])
        passes = best["load"] + best["classify"] + best["prefix"] + best["scatter"]
        out.append(f"| {w} | {n:,} | {rs[0]['candidates']:,} | " + " | ".join(f"{r['total']:,}" for r in rs) +
                   f" | {rs[0]['total'] / best['total']:.2f}x ({best_label(config(best))}) | {rs[0]['grid'] / best['grid']:.1f}x"
                   f" | {best['candidates'] / best['total']:.2f}"
                   f" | {100 * passes / best['total']:.0f} % | {best['total'] / clock_mhz:,.0f} |")
    return "\n".join(out)


def read_area(path):
    """The rows of lanes_area.py's CSV ([] without one); an old one without the newer columns
    gets their defaults (one sort port, eight counters a word, no commit)."""
    if not Path(path).exists():
        return []
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        r.setdefault("sort_ports", "1")
        r.setdefault("per_word", "8")
        r.setdefault("commit", "")
    return rows


def area_table(path):
    """The broad phase's Yosys area per configuration (lanes_area.py's CSV), or [] without one."""
    if not path.exists():
        return []
    rows = read_area(path)
    # Ratios against the one-lane row of the same RTL (commit).
    ones = {r["commit"]: r for r in rows if r["lanes"] == "1"}
    out = ["## Area (Yosys 0.23, the Cyclone V proxy; the BroadPhase module alone)", "",
           "From [area.csv](area.csv) (`tools/pyenv bench/world/lanes_area.py ...`). The sphere-table copies the",
           "lanes read are the SphereRam's (two lanes a copy of 0.5 Mbit at 4,096 spheres), not counted here.",
           "Each row's RTL is its commit's; the ratio is to the one-lane row of the same commit.", "",
           "| lanes | sort ports | counters a word | LUT cells | arithmetic cells | flip-flops | M10K blocks | sort RAM bits | LUT cells / one lane's | RTL |",
           "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"]
    for r in rows:
        one = ones.get(r["commit"])
        ratio = f"{int(r['luts']) / int(one['luts']):.1f}x" if one else ""
        out.append(f"| {r['lanes']} | {r['sort_ports']} | {r['per_word']} | {int(r['luts']):,} | {int(r['arith']):,} | "
                   f"{int(r['ff']):,} | {int(r['m10k']):,} | {int(r['ram_bits']):,} | {ratio} | {r['commit']} |")
    return out + [""]


def plot(rows, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    for i, (w, n) in enumerate(worlds(rows)):
        mine = [r for r in rows if (r["world"], r["spheres"]) == (w, n)]
        one = next((r for r in mine if config(r) == (1, 3, 1)), None)
        if one is None or n < 5000:
            continue
        for ports, word_log2 in sorted({config(r)[:2] for r in mine}):
            rs = sorted((r for r in mine if config(r)[:2] == (ports, word_log2)), key=lambda r: r["lanes"])
            ax.plot([r["lanes"] for r in rs], [one["total"] / r["total"] for r in rs],
                    "o-" if ports == 1 else ("s--" if word_log2 == 3 else "D"), color=f"C{i % 10}",
                    label=f"{w} {n:,}" + extras((ports, word_log2, 0)))
    ls = sorted({r["lanes"] for r in rows})
    ax.plot(ls, ls, ":", color="grey", label="linear")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log", base=2)
    ax.set_xlabel("candidate-generator lanes")
    ax.set_ylabel("speed-up over one lane, one port (RTL cycles)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=120)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--csv", required=True, help="BroadPhaseCycleReport's output, with a lanes column")
    ap.add_argument("--out", default=str(ROOT / "bench/results/world-lanes"))
    ap.add_argument("--clock-mhz", type=float, default=200.0)
    ap.add_argument("--machine", default="", help="how and where the cycles were made (kept in README.md)")
    a = ap.parse_args(argv)
    rows = load(a.csv)
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    if Path(a.csv).resolve() != (out / "cycles.csv").resolve():
        shutil.copyfile(a.csv, out / "cycles.csv")
    plot(rows, out / "lanes.png")
    text = ["# World mode: candidate-generator lanes and sort ports (RTL cycles)", "",
            "Cycles of the whole broad phase (all passes) on Verilator for each number of lanes and of the",
            "sort's ports; every run's pairs equal the golden model's. Cycle counts do not depend on the",
            "machine. Every number: [cycles.csv](cycles.csv); the plot: [lanes.png](lanes.png). Passes' share:",
            "the table's three reads (one sphere a cycle per sort port) and the prefix sum (eight buckets a",
            "cycle). The grid: the candidate generation itself, which the lanes share. Speed-up: over one",
            "lane and one port.", "",
            table(rows, a.clock_mhz), ""] + area_table(out / "area.csv")
    if a.machine:
        text += ["## How and where", "", a.machine, ""]
    (out / "README.md").write_text("\n".join(text))
    print((out / "README.md").read_text())
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
