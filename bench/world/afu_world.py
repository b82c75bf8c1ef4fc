"""World mode on the AFU against the CPU: `collide spheres --afu generated/world` (the AFU's
broad phase and its SCPUs, Verilated, behind the link model; --afu another world folder) on the clouds of world.py,
beside ODE's sweep-and-prune space + dCollide and the simd backend (our grid + the binary32
kernel) measured on the same spheres in the same run. Above the world preset's 4,096 spheres
the host cuts the world into slabs along x or boxes along x and y, whichever carries the fewest
spheres (ghosts included), one AFU run each (docs/host.md).

    tools/pyenv bench/world/afu_world.py [--collide build/host/test/collide_world]
                                         [--afu generated/world] [--links qpi,ideal]
                                         [--sizes 670,2000,4096,10000,65536] [--repeat 5]
                                         [--clouds uniform,clustered,mixed,diamond]
                                         [--clock-mhz F] [--out bench/results/world-afu]

"diamond" is the paper's diamond at step 0, the largest with at most the size's spheres (hMax 10,
14, 18, 24, 46 for the default sizes: 670, 1,834, 3,894, 9,224, 64,906 spheres). Rows of clouds not named in --clouds are kept from an
earlier OUT/world-afu.csv, so one cloud can be re-run alone.

The AFU's times are modelled (the link model's clock and costs, docs/host.md; --clock-mhz: the
AFU at that clock instead of the link preset's, for example the one bench/area/afu_timing.py
says its cells allow), the CPU's are wall clock (fastest of --repeat). Writes OUT/world-afu.csv, OUT/README.md and OUT/MACHINE.md.
The collide binary must have the world AFU built in: build/host/test/collide_world, which the
test build makes from generated/world (or a host built with -DCOLLIDE_AFU_PRESET=world).
"""
import argparse
import csv
import json
import re
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import world  # noqa: E402  (the clouds, the machine line)

ROOT = Path(__file__).resolve().parents[2]
SIZES = [670, 2000, 4096, 10000, 65536]
CLOUDS = world.CLOUDS + ["diamond"]


REFUSED = "cannot be cut into runs"  # collide's refusal of a world no run of the table holds


def run(cmd, refusable=False):
    """Runs collide; returns its refusal (stderr) when `refusable` and it refused the world as
    too dense to cut into runs, stops on any other failure."""
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        if refusable and REFUSED in p.stderr:
            return p.stderr.strip()
        sys.exit(f"afu_world: {' '.join(map(str, cmd))} failed ({p.returncode}):\n{p.stderr}")
    return None


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--collide", default=str(ROOT / "build/host/test/collide_world"))
    ap.add_argument("--afu", default=str(ROOT / "generated/world"))
    ap.add_argument("--links", default="qpi,ideal")
    ap.add_argument("--sizes", default=",".join(map(str, SIZES)))
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--clouds", default=",".join(CLOUDS))
    ap.add_argument("--clock-mhz", type=float, default=None, help="the AFU's clock instead of each link preset's")
    ap.add_argument("--skip-ode-above", type=int, default=0, metavar="N",
                    help="leave ODE's sweep-and-prune out of worlds of more than N spheres (minutes a run at 1,000,000; "
                         "bench/results/peers has its time there); 0: never")
    ap.add_argument("--built", default="", help="where --collide was built, for MACHINE.md (e.g. a clean clone at a commit)")
    ap.add_argument("--out", default=str(ROOT / "bench/results/world-afu"))
    ap.add_argument("--report-only", action="store_true", help="rewrite README.md from OUT/world-afu.csv")
    ap.add_argument("--compare", default="", metavar="CSV",
                    help="an earlier world-afu.csv (e.g. run by run, before the run queue): its AFU time beside each row's")
    a = ap.parse_args(argv)
    # Given means given: 0 is a clock out of range, not "each preset's" (collide checks the range).
    if a.clock_mhz is not None and not a.clock_mhz > 0:
        ap.error(f"--clock-mhz: {a.clock_mhz:g} MHz is not a clock (collide takes 1..2000)")
    if a.skip_ode_above < 0:
        ap.error(f"--skip-ode-above: {a.skip_ode_above} is not a sphere count (0: never leave ODE out)")
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    clouds = a.clouds.split(",")
    for kind in clouds:
        if kind not in CLOUDS:
            ap.error(f"--clouds: unknown cloud {kind!r} (known: {', '.join(CLOUDS)})")
    earlier = out / "world-afu.csv"
    if a.report_only:
        report(read_rows(earlier), out, (out / "MACHINE.md").read_text(), **lanes_of(a.afu), compare=compared(a.compare))
        return 0
    start = world.machine()
    # Kept rows are written back as read (their text), and parsed for the report.
    kept_text = [r for r in csv.DictReader(open(earlier, newline="")) if r["cloud"] not in clouds] if earlier.exists() else []
    kept = [parse(r) for r in kept_text]
    earlier_machine = (out / "MACHINE.md").read_text() if kept else ""
    rows, refused = [], []
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        for kind in clouds:
            for size in map(int, a.sizes.split(",")):
                path = work / "spheres.csv"
                spheres = world.cloud(kind, size, a.seed)
                n = len(spheres)  # the diamond's: at most the size asked for
                world.write_cloud(path, spheres)
                cpu = {}
                # The tuned grid last: simd's contacts file is the one the AFU's is compared with.
                for name, backend, space, extra in (("ode", "ode", "sap", ()), ("tuned1", "grid", None, ("--threads", "1")),
                                                    ("tuned", "grid", None, ()), ("simd", "simd", None, ())):
                    if name == "ode" and 0 < a.skip_ode_above < n:
                        continue
                    cpu[name] = world.run(a.collide, path, backend, space, a.repeat, work, extra)
                for link in a.links.split(","):
                    summary = work / "afu.json"
                    clock = ["--clock-mhz", str(a.clock_mhz)] if a.clock_mhz is not None else []
                    refusal = run([a.collide, "spheres", "--afu", a.afu, "--link", link, *clock, "--in", path, "--out",
                                   work / "afu.csv", "--summary", summary], refusable=True)
                    if refusal:
                        what = f"{n:,} spheres (hMax {world.diamond_hmax(size)})" if kind == "diamond" else f"{n:,} spheres"
                        refused.append(f"{kind}, {what}, {link}: {refusal}")
                        print(f"{kind:9} {n:5} {link:6} refused: {refusal}", flush=True)
                        continue
                    s = json.loads(summary.read_text())
                    if (work / "afu.csv").read_text() != (work / "contacts.csv").read_text():
                        sys.exit(f"afu_world: {kind} {n}: the AFU's contacts differ from simd's")
                    f = s["afu"]
                    ode = cpu["ode"]["broad_ns"] + cpu["ode"]["narrow_ns"] if "ode" in cpu else None
                    grid = cpu["simd"]["broad_ns"] + cpu["simd"]["narrow_ns"]
                    # The tuned grid's whole time (its finish is part of its work), one thread and all.
                    tuned1, tuned = (cpu[k]["broad_ns"] + cpu[k]["narrow_ns"] + cpu[k].get("finish_ns", 0) for k in ("tuned1", "tuned"))
                    best = min(t for t in (ode, grid, tuned1, tuned) if t is not None)
                    row = {"cloud": kind, "spheres": n, "link": link, "clock_mhz": f["clock_mhz"],
                           "clock_given": 0 if a.clock_mhz is None else 1, "candidates": s["candidates"],
                           "contacts": s["contacts"], "afu_ns": f["modelled_ns"], "link_bound_ns": f["link_bound_ns"],
                           "afu_over_bound": f["modelled_ns"] / f["link_bound_ns"], "runs": f["runs"],
                           "slabs": f["slabs"], "calls": f.get("calls", f["slabs"]),
                           "read_lines": f["read_lines"], "write_lines": f["write_lines"],
                           "cycles_total": f["cycles_total"], "cycles_broad": f["cycles_broad"],
                           "cycles_load": f["cycles_load"], "cell_edge": f["cell_edge"], "large": f["large"],
                           "ode_sap_ns": ode, "simd_grid_ns": grid,
                           "ode_over_afu": ode / f["modelled_ns"] if ode is not None else None, "grid_over_afu": grid / f["modelled_ns"],
                           "tuned_grid_1t_ns": tuned1, "tuned_grid_ns": tuned, "threads": cpu["tuned"].get("threads", 0),
                           "best_cpu_ns": best, "best_cpu_over_afu": best / f["modelled_ns"]}
                    rows.append(row)
                    print(f"{kind:9} {n:5} {link:6} {s['contacts']:6} contacts  afu {f['modelled_ns'] / 1e3:8.1f} us"
                          f" (bound {f['link_bound_ns'] / 1e3:6.1f}, broad {f['cycles_broad']} cycles)  ode sap "
                          f"{ode / 1e3 if ode is not None else float('nan'):8.1f} us  grid {grid / 1e3:7.1f} us  tuned {tuned1 / 1e3:7.1f} / {tuned / 1e3:7.1f} us", flush=True)
    order = lambda r: CLOUDS.index(r["cloud"])
    rows, text_rows = sorted(kept + rows, key=order), sorted(kept_text + rows, key=order)
    refused = [l for l in refused_lines(out) if l.split(",")[0] not in clouds] + refused
    if refused:
        (out / "refused.txt").write_text("".join(l + "\n" for l in refused))
    else:
        (out / "refused.txt").unlink(missing_ok=True)
    shape = lanes_of(a.afu)
    machine_md = world.write_results(out, "world-afu.csv", text_rows, "bench/world/afu_world.py", argv,
                                     f"{shown(Path(a.collide))}: the CLI with {shape['afu']}'s AFU Verilated in "
                                     "(tools/test's Release build makes build/host/test/collide_world from generated/world)"
                                     + (f"; {a.built}" if a.built else ""), start)
    if kept:  # the kept rows' command and machine stay beside this run's
        old = kept_sections(earlier_machine, sorted({r["cloud"] for r in kept}), clouds)
        machine_md = old + "\n\n" + machine_md.replace("## How and where", "## How and where: " + ", ".join(clouds), 1)
        (out / "MACHINE.md").write_text(machine_md)
    report(rows, out, machine_md, **shape, compare=compared(a.compare))
    return 0


def compared(path):
    """An earlier CSV's AFU time by (cloud, spheres, link), or {} without one."""
    if not path:
        return {}
    try:
        return {(r["cloud"], int(float(r["spheres"])), r["link"]): float(r["afu_ns"]) for r in csv.DictReader(open(path, newline=""))}
    except (OSError, KeyError, ValueError) as e:
        sys.exit(f"afu_world: --compare {path}: not a world-afu.csv ({e})")


def kept_sections(text, kept_clouds, rerun):
    """MACHINE.md's sections for the rows kept: an unlabelled one (a run of every cloud) is
    labelled with the kept clouds; a labelled one stays unless it names a cloud re-run now."""
    parts = re.split(r"^(?=## How and where)", text, flags=re.M)
    out = []
    for p in (p for p in parts if p.strip()):
        head = p.splitlines()[0]
        if head.strip() == "## How and where":
            out.append(p.replace("## How and where", "## How and where: " + ", ".join(kept_clouds), 1))
        elif not set(head.split(":", 1)[1].replace(" ", "").split(",")) & set(rerun):
            out.append(p)
    return "\n".join(x.rstrip() + "\n" for x in out).rstrip()


def refused_lines(out):
    p = out / "refused.txt"
    return p.read_text().splitlines() if p.exists() else []


def parse(row):
    """A CSV row's numbers as floats; a peer left out (empty) as None."""
    return {k: (v if k in ("cloud", "link") else float(v) if v != "" else None) for k, v in row.items()}


def us(v):
    return "-" if v is None else f"{v / 1e3:,.1f}"


def times(v, digits=2):
    return "-" if v is None else f"{v:.{digits}f}x"


def read_rows(path):
    return [parse(r) for r in csv.DictReader(open(path, newline=""))]


def lanes_of(afu):
    """The broad phase's candidate lanes and sort ports, from the AFU's manifest (1 before each
    was built)."""
    m = json.loads((Path(afu) / "manifest.json").read_text())
    bp = m["afu"].get("broadPhase") or {}
    return {"lanes": int(bp.get("lanes", 1)), "ports": int(bp.get("sortPorts", 1)),
            "scpus": f"{m['afu']['scpus']} {m['scpu']['name']}", "afu": shown(Path(afu))}


def shown(path):
    """A folder as the docs name it: relative to the repository where it is inside it."""
    try:
        return str(path.resolve().relative_to(ROOT))
    except ValueError:
        return str(path)


def clock_note(rows):
    """The sentence that says the clock the AFU's rows ran at (none for rows from before the column)."""
    given = [r for r in rows if r.get("clock_given")]
    timed = given or [r for r in rows if "clock_mhz" in r]
    if not timed:
        return []
    mhz = ", ".join(sorted({format(r["clock_mhz"], "g") for r in timed}))
    if given:
        return [f"The AFU runs at {mhz} MHz here (`--clock-mhz`), not at its links' own clocks; the links' rates and "
                "latencies stay in ns."]
    return [f"The AFU runs at {mhz} MHz here: the lower of the link's target and the clock the AFU folder's "
            "timing.json says its cells reach."]


def report(rows, out, machine_md, lanes, ports=1, compare=None, scpus="16 fp32", afu="generated/world"):
    plural = "s" if lanes > 1 else ""
    spheres_a_cycle = f"{ports} sphere{'s' if ports > 1 else ''} a cycle"
    lines = ["# World mode on the AFU against ODE and the CPU grid", "",
             f"`collide spheres --afu {afu}` (the on-chip broad phase, {lanes} candidate lane{plural} and its sort's passes {spheres_a_cycle}, and {scpus}",
             "SCPUs; time modelled by the link model; above 4,096 spheres the host cuts the world into slabs",
             "along x or boxes along x and y, whichever carries the fewest spheres (a run counting for 256), one AFU run each, all in one call",
             "through the AFU's run queue where the manifest has one: each run's table loads, and is fed to the broad",
             "phase, while the run before it computes) beside `--backend ode",
             "--space sap` (ODE 0.16's sweep-and-prune space + dCollide, binary64), `--backend simd` (our",
             "grid + the binary32 kernel) and, where the columns are there, `--backend grid` (the tuned grid, one thread and all),",
             "both wall clock, fastest of N, on the same spheres in the same run (bench/world/afu_world.py).",
             "The AFU's contacts equal simd's byte for byte in every row (the script stops otherwise).",
             *clock_note(rows),
             *(["ODE's sweep-and-prune is left out of the rows marked - (`--skip-ode-above`: minutes a run); "
                "bench/results/peers measures it at 1,000,000 spheres."] if any(r.get("ode_sap_ns", 0) is None for r in rows) else []),
             "Every number: [world-afu.csv](world-afu.csv)." +
             (" \"Before\": the same row's AFU time in the CSV given to --compare (see MACHINE.md's command)." if compare else ""), ""]
    cmp = compare or {}
    tuned_cols = all("best_cpu_ns" in r for r in rows)  # rows measured before the tuned grid lack them
    for kind in [c for c in CLOUDS if any(r["cloud"] == c for r in rows)]:
        lines += [f"## {kind}" + (" (the paper's diamond at step 0, the largest with at most the row's size)" if kind == "diamond" else ""), "",
                  "| spheres | contacts | link | AFU runs | calls | AFU (us) | " + ("before (us) | " if cmp else "") +
                  "link bound (us) | AFU / bound | broad-phase cycles | ODE sap (us) | ODE / AFU | grid (us) | grid / AFU |" +
                  (" tuned grid, 1 thread (us) | tuned grid, all threads (us) | fastest CPU / AFU |" if tuned_cols else ""),
                  "|---:|---:|---|---:|---:|---:|" + ("---:|" if cmp else "") + "---:|---:|---:|---:|---:|---:|---:|" +
                  ("---:|---:|---:|" if tuned_cols else "")]
        for r in rows:
            if r["cloud"] != kind:
                continue
            was = cmp.get((r["cloud"], int(r["spheres"]), r["link"]))
            before = (f"{was / 1e3:,.1f} | " if was else "- | ") if cmp else ""
            lines.append(f"| {int(r['spheres']):,} | {int(r['contacts']):,} | {r['link']} | {int(r['slabs'])} | "
                         f"{int(r.get('calls', r['slabs']))} | {r['afu_ns'] / 1e3:,.1f} | {before}"
                         f"{r['link_bound_ns'] / 1e3:,.1f} | {r['afu_over_bound']:.1f}x | {int(r['cycles_broad']):,} | "
                         f"{us(r['ode_sap_ns'])} | {times(r['ode_over_afu'])} | {r['simd_grid_ns'] / 1e3:,.1f} | "
                         f"{r['grid_over_afu']:.2f}x |" +
                         (f" {r['tuned_grid_1t_ns'] / 1e3:,.1f} | {r['tuned_grid_ns'] / 1e3:,.1f} | {r['best_cpu_over_afu']:.2f}x |"
                          if tuned_cols else ""))
        refusals = [l for l in refused_lines(out) if l.startswith(kind + ",")]
        if refusals:
            lines += ["Refused by `collide spheres` (no cut of the world into runs of the AFU's table holds it; nothing", "was computed, nothing is missing from the rows above):", ""]
            lines += [f"- {l}" for l in refusals]
        lines.append("")
    rng = lambda k, sel=lambda r: True: (min(r[k] for r in rows if sel(r) and r[k] is not None),
                                         max(r[k] for r in rows if sel(r) and r[k] is not None))
    qpi = lambda r: r["link"] == "qpi"
    per = [r["cycles_broad"] / r["spheres"] for r in rows]
    one = [r["cycles_broad"] / r["spheres"] for r in rows if int(r["slabs"]) == 1] or per
    dia = [r for r in rows if r["cloud"] == "diamond" and qpi(r)]
    diamond_note = ([f"- The diamond (close-packed: {min(r['contacts'] / r['spheres'] for r in dia):.1f}-"
                     f"{max(r['contacts'] / r['spheres'] for r in dia):.1f} contacts a sphere) is nearer its QPI bound, "
                     f"{min(r['afu_over_bound'] for r in dia):.1f}-{max(r['afu_over_bound'] for r in dia):.1f}x, since its "
                     "contact writes are a larger part of the bound. ODE's sweep-and-prune beats our CPU grid on it up to "
                     f"{max([int(r['spheres']) for r in dia if r['ode_sap_ns'] is not None and r['ode_sap_ns'] < r['simd_grid_ns']] or [0]):,} spheres "
                     "(the grid's power-of-two cells hold many of its close-packed spheres) and loses above."] if dia else [])
    within = [f"{r['cloud']} {int(r['spheres']):,}" for r in rows if qpi(r) and r["afu_over_bound"] <= 2.0]
    link_clause = (f"- It is {rng('afu_over_bound', qpi)[0]:.1f}-{rng('afu_over_bound', qpi)[1]:.1f}x its link bound on HARP v1's "
                   "QPI link" + (", within 2x only for " + ", ".join(within) if within else ", never within 2x") +
                   ": the broad phase takes " if any(qpi(r) for r in rows)
                   else "- HARP v1's QPI link was not run here (`--links`). The broad phase takes ")
    with_ode = [r for r in rows if r["ode_sap_ns"] is not None]
    ode_clause = (f"{rng('ode_over_afu')[0]:.1f}-{rng('ode_over_afu')[1]:.1f}x faster than ODE's sweep-and-prune space + "
                  "dCollide" + (" (where it was run: `--skip-ode-above`)" if len(with_ode) < len(rows) else "") + " and "
                  if with_ode else "")
    lines += ["## What it shows", "",
              "- The AFU's world mode is " + ode_clause +
              f"{rng('grid_over_afu')[0]:.1f}-{rng('grid_over_afu')[1]:.1f}x faster "
              "than our CPU grid + simd kernel on every cloud and size here (modelled AFU time against measured CPU time)" +
              (f"; the fastest CPU peer measured beside it (the tuned grid, `--backend grid`, on one thread or all "
               f"{int(max(r['threads'] for r in rows))}, or another) takes {rng('best_cpu_over_afu')[0]:.2f}-"
               f"{rng('best_cpu_over_afu')[1]:.2f}x the AFU's time." if tuned_cols else "."),
              link_clause +
              f"{min(per):.1f}-{max(per):.1f} cycles a sphere of the world (one run: {min(one):.1f}-{max(one):.1f}; runs re-read their ghosts;",
              f"  its {lanes} candidate lane{plural} and its sort's passes of {spheres_a_cycle}),",
              "  while the link brings four spheres a line and a line a cycle. The cell level is chosen as the table",
              "  arrives, so what follows the table is the sort's three passes and the grid (docs/afu.md, \"World mode\",",
              "  \"Coarse chunks\", \"The fed table and eight sort ports\", \"Claimed work\", \"Queued hits and 32 counters a word\", \"Box buckets\").",
              ] + diamond_note + [
              "- Above 4,096 spheres (the world preset's table; a record names i and j in 12 bits each) every",
              "  slab along x or box along x and y is a run of its own, its ghosts read twice: the host takes the cut",
              "  with the fewest spheres in all (near-square columns for the 65,536-sphere clouds; slabs cannot hold",
              "  the 64,906-sphere diamond at all); with the run queue all runs are one call (one transaction's",
              "  costs, and one call's link bound), each table read while the run before computes (docs/host.md). One run of a",
              "  whole 64k world needs wider record tags (not built; banked sphere RAM, which makes its table",
              "  affordable, is).", "", machine_md]
    (out / "README.md").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    sys.exit(main())
