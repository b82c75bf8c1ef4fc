"""The demo's picture, from its outputs: time per step for each backend, contacts per step, and
the scene's final state as a 3D scatter of the sphere centres.

    tools/pyenv tools/demo_plot.py OUT.png --title TITLE --cpu ode.csv
        [--cpu-label "ode run"] [--afu "LABEL=rtl_qpi.csv" ...] [--positions final.csv]

--cpu       a `collide run --out` CSV: its ode_ns and simd_ns columns (ODE's collider and the
            simd batch, measured on the run's pairs) and its contacts; --cpu-label names that run
--afu       a `collide run --backend rtl --out` CSV: its afu_modelled_ns and contacts, labelled
--positions a `collide run --positions` CSV (sphere,x,y,z; C99 hex floats or decimal)

A bad input exits 1 with "demo_plot: FILE: what is wrong".
"""
import argparse
import csv
import os
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only: no display on a build machine
import matplotlib.pyplot as plt  # noqa: E402


class InputError(Exception):
    pass


def number(text, where):
    t = text.strip()
    try:
        # collide writes positions with %a; float() does not read hex, float.fromhex reads
        # "1.5" as hex, so tell them apart by the 0x.
        return float.fromhex(t) if "0x" in t.lower() else float(t)
    except ValueError:
        raise InputError(f"{where}: not a number: {text!r}") from None


def has_column(path, name):
    try:
        with open(path, newline="") as f:
            return name in next(csv.reader(f), [])
    except OSError:
        return False  # columns() says why


def columns(path, wanted):
    """The named columns of a CSV as lists of floats; an error names the file and the column."""
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        raise InputError(f"{path}: cannot read: {e.strerror}") from None
    if not rows:
        raise InputError(f"{path}: no rows")
    missing = [c for c in wanted if c not in rows[0]]
    if missing:
        raise InputError(f"{path}: no column {', '.join(missing)} (has {', '.join(rows[0])})")
    return {c: [number(r[c], f"{path}:{k + 2}: {c}") for k, r in enumerate(rows)] for c in wanted}


def labelled(spec):
    label, sep, path = spec.partition("=")
    if not sep or not label or not path:
        raise InputError(f"--afu {spec!r}: expected LABEL=FILE")
    return label, path


def afu_colour(k):  # the same colour for an AFU run in both panels
    return f"C{2 + k % 3}"


def plot_times(ax, cpu, afus):
    us = lambda v: [x / 1e3 if x > 0 else float("nan") for x in v]  # log axis: leave out zeros
    ax.plot(cpu["step"], us(cpu["ode_ns"]), lw=1.4, color="C0", label="ODE collider, binary64 (CPU, measured)")
    ax.plot(cpu["step"], us(cpu["simd_ns"]), lw=1.4, color="C1", label="simd batch, binary32 (CPU, measured)")
    if "simd64_ns" in cpu:  # written by collide since the binary64 kernel; older CSVs lack it
        ax.plot(cpu["step"], us(cpu["simd64_ns"]), lw=1.2, ls="--", color="C1",
                label="simd batch, binary64 (CPU, measured)")
    for k, (label, a) in enumerate(afus):
        ax.plot(a["step"], us(a["afu_modelled_ns"]), lw=1.4, color=afu_colour(k), label=f"AFU, {label} (modelled)")
    ax.set_yscale("log")
    ax.set_xlabel("step")
    ax.set_ylabel("narrow phase time per step (µs)")
    ax.set_title("Time per step")
    ax.grid(alpha=.3, which="both")
    ax.legend(fontsize=9)


def plot_contacts(ax, cpu, cpu_label, afus):
    ax.plot(cpu["step"], cpu["contacts"], lw=1.6, color="C0", label=f"sphere/sphere contacts ({cpu_label})")
    for k, (label, a) in enumerate(afus):  # the rtl runs follow their own (binary32) trajectories
        ax.plot(a["step"], a["contacts"], lw=1.2, ls=("--", ":")[k % 2], color=afu_colour(k),
                label=f"sphere/sphere contacts (rtl, {label})")
    if any(cpu["other_contacts"]):
        ax.plot(cpu["step"], cpu["other_contacts"], lw=1.2, color="C5", label="sphere/plane contacts (on the CPU)")
    ax.plot(cpu["step"], cpu["pairs"], lw=1, color="gray", alpha=.7, label=f"pairs tested ({cpu_label})")
    ax.set_ylim(bottom=0)
    ax.set_xlabel("step")
    ax.set_ylabel("per step")
    ax.set_title("Contacts per step")
    ax.grid(alpha=.3)
    ax.legend(fontsize=9)


def plot_positions(ax, pos, path):
    x, y, z = pos["x"], pos["y"], pos["z"]
    size = max(2.0, min(30.0, 12000.0 / len(x)))  # points^2: readable from 100 to 10^5 spheres
    ax.scatter(x, y, z, c=z, cmap="viridis", s=size, depthshade=True)
    span = [max(v) - min(v) for v in (x, y, z)]
    ax.set_box_aspect([max(s, 1e-3 * max(span)) for s in span])  # true proportions
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    ax.set_title(f"Final state: {len(x):,} sphere centres\n({Path(path).name}, colour = z)")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("out", help="the PNG to write")
    p.add_argument("--title", default="collide run")
    p.add_argument("--cpu", required=True, help="a collide run --out CSV (ode_ns, simd_ns, contacts)")
    p.add_argument("--cpu-label", default="ode run", help="what the --cpu run was (legend)")
    p.add_argument("--afu", action="append", default=[], help="LABEL=FILE: an rtl run's --out CSV")
    p.add_argument("--positions", help="a collide run --positions CSV")
    a = p.parse_args(argv)
    try:
        wanted = ["step", "pairs", "contacts", "other_contacts", "ode_ns", "simd_ns"]
        cpu = columns(a.cpu, wanted + (["simd64_ns"] if has_column(a.cpu, "simd64_ns") else []))
        afus = [(label, columns(path, ["step", "contacts", "afu_modelled_ns"]))
                for label, path in map(labelled, a.afu)]
        pos = columns(a.positions, ["x", "y", "z"]) if a.positions else None
    except InputError as e:
        print(f"demo_plot: {e}", file=sys.stderr)
        return 1

    plt.rcParams.update({"font.size": 11, "axes.titlesize": 13, "axes.labelsize": 11})
    fig = plt.figure(figsize=(19, 6) if pos else (13, 5.5))
    grid = fig.add_gridspec(1, 3 if pos else 2, width_ratios=[1, 1, 1.15][:3 if pos else 2])
    plot_times(fig.add_subplot(grid[0]), cpu, afus)
    plot_contacts(fig.add_subplot(grid[1]), cpu, a.cpu_label, afus)
    if pos:
        plot_positions(fig.add_subplot(grid[2], projection="3d"), pos, a.positions)
    fig.suptitle(a.title, fontsize=15)
    fig.tight_layout()
    # Into a temporary file beside OUT that replaces it only when complete, as the host's own
    # outputs do: a failed write leaves the previous picture, never half a PNG.
    out = Path(a.out)
    tmp = out.with_name(f".{out.name}.{os.getpid()}.tmp")
    try:
        fig.savefig(tmp, dpi=110, format="png")
        os.replace(tmp, out)
    except OSError as e:
        tmp.unlink(missing_ok=True)
        print(f"demo_plot: {a.out}: cannot write: {e.strerror}", file=sys.stderr)
        return 1
    finally:
        plt.close(fig)
    return 0


if __name__ == "__main__":
    sys.exit(main())
