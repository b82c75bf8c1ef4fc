"""PNG plots per sweep, drawn from its CSV (so `bench/sweep plot NAME` redraws them)."""
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# The paper's own figures as numbers it states in its text (Alves et al., Section V).
PAPER_AFU_NS_PER_COLLISION = 36.0   # average over hMax 1..10, HARP v1
PAPER_ODE_NS_PER_COLLISION = 41.0
PAPER_MEMORY_SHARE = 0.48           # Figure 6: memory access ~48 % of the AFU's time


def f(r, k):
    v = r.get(k, "")
    return float(v) if v not in ("", None) else None


def sel(rows, **kv):
    return [r for r in rows if all(r[k] == str(v) for k, v in kv.items())]


def save(fig, path: Path):
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def paper(rows, out):
    files = []
    for link, fname, title in (("qpi", "fig5_time_vs_collisions.png", "Figure 5: time against collisions (HARP v1 link)"),
                               ("ideal", "fig7_ideal_link.png", "Figure 7: without memory access time (ideal link)")):
        rs = sorted(sel(rows, link=link), key=lambda r: f(r, "contacts"))
        if not rs:
            continue
        x = [f(r, "contacts") for r in rs]
        fig, ax = plt.subplots(figsize=(7, 4.5))
        ax.plot(x, [f(r, "modelled_ns") / 1e3 for r in rs], "o-", label=f"AFU, 16 SCPUs fp32 (modelled, {link})")
        ax.plot(x, [f(r, "ode_ns") / 1e3 for r in rs], "s-", label="ODE dCollide (measured here)")
        ax.plot(x, [f(r, "simd_ns") / 1e3 for r in rs], "^-", label="simd batch, binary32 (measured here)")
        ax.plot(x, [f(r, "link_bound_ns") / 1e3 for r in rs], ":", color="gray", label="link model's bound")
        if link == "ideal":
            ax.plot(x, [f(r, "compute_bound_ns") / 1e3 for r in rs], "-.", color="black", lw=.8,
                    label="compute bound (16 pairs a cycle)")
        if link == "qpi":
            ax.plot(x, [PAPER_AFU_NS_PER_COLLISION * v / 1e3 for v in x], "--", color="C0", alpha=.5,
                    label="paper: AFU, 36 ns/collision (average)")
            ax.plot(x, [PAPER_ODE_NS_PER_COLLISION * v / 1e3 for v in x], "--", color="C1", alpha=.5,
                    label="paper: ODE, 41 ns/collision (average)")
        for r in rs:
            ax.annotate(f"h{r['hmax']}", (f(r, "contacts"), f(r, "modelled_ns") / 1e3), fontsize=7,
                        xytext=(2, 4), textcoords="offset points")
        ax.set_xlabel("collisions (contacts found) in one step")
        ax.set_ylabel("time (us)")
        ax.set_title(title)
        ax.legend(fontsize=8)
        ax.grid(alpha=.3)
        files.append(save(fig, out / fname))
    rs = sorted(sel(rows, link="qpi"), key=lambda r: int(r["hmax"]))
    if rs:
        parts = [("loading_ns", "loading spheres"), ("computing_ns", "computing"),
                 ("wait_read_ns", "waiting on reads"), ("wait_write_ns", "waiting on writes"),
                 ("other_ns", "other AFU cycles"), ("overhead_ns", "per-call overhead")]
        fig, ax = plt.subplots(figsize=(7, 4.5))
        bottom = [0.0] * len(rs)
        labels = [f"h{r['hmax']}\n{r['contacts']}" for r in rs]
        for k, name in parts:
            v = [max(f(r, k), 0.0) / 1e3 for r in rs]
            ax.bar(labels, v, bottom=bottom, label=name)
            bottom = [b + y for b, y in zip(bottom, v)]
        ax.set_ylabel("modelled time (us)")
        ax.set_xlabel("hMax / collisions")
        ax.set_title("Figure 6: where the AFU's time goes (HARP v1 link)\n"
                     f"paper: memory access ~{PAPER_MEMORY_SHARE:.0%}, processing ~{1 - PAPER_MEMORY_SHARE:.0%}")
        ax.legend(fontsize=8)
        files.append(save(fig, out / "fig6_time_split.png"))
    return files


def scpus(rows, out):
    files = []
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for link, mk in (("qpi", "o-"), ("ideal", "s-")):
        rs = sorted(sel(rows, link=link), key=lambda r: int(r["scpus"]))
        if not rs:
            continue
        n = [int(r["scpus"]) for r in rs]
        ax.plot(n, [f(r, "ns_per_collision") for r in rs], mk, label=f"modelled, {link}")
        ax.plot(n, [f(r, "link_bound_ns") / f(r, "contacts") for r in rs], ":", label=f"link bound, {link}")
        if link == "ideal":
            ax.plot(n, [f(r, "compute_bound_ns") / f(r, "contacts") for r in rs], "--", label="compute bound")
    ax.axhline(PAPER_AFU_NS_PER_COLLISION, color="gray", ls="--", lw=.8, label="paper: 36 ns")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("SCPUs")
    ax.set_ylabel("ns per collision (diamond hMax 10)")
    ax.set_title("Time against SCPU count (fp32)")
    ax.legend(fontsize=8)
    ax.grid(alpha=.3, which="both")
    files.append(save(fig, out / "scpus_time.png"))
    rs = sorted(sel(rows, link="qpi"), key=lambda r: int(r["scpus"]))
    if rs and f(rs[0], "area_luts") is not None:
        fig, ax = plt.subplots(figsize=(7, 4.5))
        n = [int(r["scpus"]) for r in rs]
        ax.plot(n, [f(r, "area_luts") for r in rs], "o-", label="LUTs (ALM cells)")
        ax.plot(n, [f(r, "area_ff") for r in rs], "s-", label="flip-flops")
        ax2 = ax.twinx()
        ax2.plot(n, [f(r, "area_dsp") for r in rs], "^--", color="C3", label="DSP blocks")
        ax.set_xscale("log", base=2)
        ax.set_xlabel("SCPUs")
        ax.set_ylabel("cells")
        ax2.set_ylabel("DSP blocks")
        ax.set_title("Area against SCPU count (Yosys synth_intel_alm, Cyclone V; PUC + N x SCPU)")
        ax.legend(loc="upper left", fontsize=8)
        ax2.legend(loc="lower right", fontsize=8)
        files.append(save(fig, out / "scpus_area.png"))
    return files


def pareto(pts):
    """The points no other point beats on both cost (x) and error (y), by increasing cost."""
    front, best = [], float("inf")
    for x, y, name in sorted(pts, key=lambda p: (p[0], p[1])):
        if y < best:
            front.append((x, y, name))
            best = y
    return front


def arith(rows, out):
    files = []
    rs = sel(rows, link="qpi")
    by = {(r["link"], r["config"]): r for r in rows}
    err = "acc_pos_rel_worst"
    if not rs or f(rs[0], err) is None:
        return files
    for xkey, xlabel, fname, src in (
            ("ns_per_collision", "modelled ns per collision, ideal link at 200 MHz (diamond hMax 10)",
             "arith_pareto_time.png", "ideal"),
            ("ns_per_collision", "modelled ns per collision, ideal link at the clock the cells allow\n"
             "(timing proxy: cell delays only, so a lower bound of these builds' time)", "arith_pareto_time_cells.png",
             "ideal@cells"),
            ("latency", "SCPU latency (cycles)", "arith_pareto_latency.png", "qpi"),
            ("scpus_luts", "area: LUTs of the 16 SCPUs (Yosys, Cyclone V; PUC not included)", "arith_pareto_area.png", "qpi")):
        pts = [(f(by.get((src, r["config"]), {}), xkey), f(r, err), r["scpu_spec"]) for r in rs]
        pts = [p for p in pts if p[0] is not None and p[1] is not None]
        if not pts:
            continue
        fig, ax = plt.subplots(figsize=(7, 4.5))
        ax.scatter([p[0] for p in pts], [max(p[1], 1e-17) for p in pts])
        front = pareto(pts)
        ax.step([p[0] for p in front], [max(p[1], 1e-17) for p in front], where="post", color="C1", lw=.8,
                label="Pareto front (nothing both cheaper and more accurate)")
        for k, (x, y, name) in enumerate(sorted(pts)):
            ax.annotate(name, (x, max(y, 1e-17)), fontsize=7, xytext=(3, 3 + 8 * (k % 3)), textcoords="offset points")
        ax.legend(fontsize=8, loc="lower left")
        ax.set_yscale("log")
        ax.set_xlabel(xlabel)
        ax.set_ylabel("worst relative error of the contact position\n(golden model vs double; fp64: exact)")
        ax.set_title("What accuracy costs")
        ax.grid(alpha=.3, which="both")
        files.append(save(fig, out / fname))
    return files


def label(r):
    """A links-sweep configuration as a reader names it: format, link format, record layout."""
    return f"{r['format']} {r['records']} ({r.get('record_bytes', '?')} B)"


def links(rows, out):
    """One Pareto plot per link preset: the contact position's worst error against modelled ns
    per collision (diamond hMax 10), every format and record layout."""
    files = []
    err = "acc_pos_rel_worst"
    for link in dict.fromkeys(r["link"] for r in rows):
        rs = [r for r in sel(rows, link=link, hmax=10) if f(r, err) is not None and f(r, "ns_per_collision")]
        if not rs:
            continue
        pts = [(f(r, "ns_per_collision"), max(f(r, err), 1e-17), label(r)) for r in rs]
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for r, p in zip(rs, pts):
            ax.scatter([p[0]], [p[1]], marker="o" if r["records"] == "derived" else "s",
                       color="C0" if r["records"] == "derived" else "C2")
        front = pareto(pts)
        ax.step([p[0] for p in front], [p[1] for p in front], where="post", color="C1", lw=.8,
                label="Pareto front (nothing both faster and more accurate)")
        for k, (x, y, name) in enumerate(sorted(pts)):
            ax.annotate(name, (x, y), fontsize=7, xytext=(3, 3 + 8 * (k % 3)), textcoords="offset points")
        ax.scatter([], [], marker="o", color="C0", label="derived records")
        ax.scatter([], [], marker="s", color="C2", label="full records")
        ax.legend(fontsize=8, loc="center right")
        ax.set_yscale("log")
        ax.set_xlabel(f"modelled ns per collision, link {link} (diamond hMax 10, 16 SCPUs)")
        ax.set_ylabel("worst relative error of the contact position\n(golden model vs double; fp64: exact)")
        ax.set_title(f"What accuracy costs in time: link {link}")
        ax.grid(alpha=.3, which="both")
        files.append(save(fig, out / f"links_pareto_{link}.png"))
    return files


def smoke(rows, out):
    return []


def draw(name, rows, out: Path):
    out.mkdir(parents=True, exist_ok=True)
    # isoarea and smoke: tables only
    return {"paper": paper, "scpus": scpus, "arith": arith, "arith200": arith, "links": links}.get(name, smoke)(rows, out)
