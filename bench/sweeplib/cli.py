"""bench/sweep: design-space sweeps of the collision AFU (see bench/README.md).

  bench/sweep list                      the named sweeps
  bench/sweep run NAME [--no-area] ...  run one (resumes where it stopped), write CSV + plots
  bench/sweep plot NAME                 redraw the plots and tables from the CSV
"""
import argparse
import datetime
import platform
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import plots  # noqa: E402
import report  # noqa: E402
import sweep as sweeplib  # noqa: E402
from paths import RESULTS, ROOT, write_atomic  # noqa: E402
from sweeps import SWEEPS  # noqa: E402


def machine() -> str:
    def sh(cmd):
        try:
            return subprocess.run(cmd, shell=True, capture_output=True, text=True).stdout.strip()
        except OSError:
            return "?"
    model = sh("lscpu | sed -n 's/^Model name: *//p'") or platform.processor()
    mem = sh("free -g | awk '/Mem:/ {print $2}'")
    dirty = " (with uncommitted changes)" if sh(f"git -C {ROOT} status --porcelain -- src host") else ""
    return (f"- machine: {sh('nproc')} cores ({model}), {mem} GiB, {platform.system()} {platform.release()}\n"
            f"- tools: {sh('verilator --version')}; {sh('yosys -V')}; {sh('g++ --version | head -1')}\n"
            f"- commit: {sh(f'git -C {ROOT} rev-parse --short HEAD')}{dirty}\n")


def main(argv=None):
    ap = argparse.ArgumentParser(prog="bench/sweep", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    sub.add_parser("list", help="print the named sweeps")
    r = sub.add_parser("run", help="run a named sweep (cached, resumable) and write its CSV and plots")
    r.add_argument("name", choices=sorted(SWEEPS))
    r.add_argument("--out", type=Path, help="results folder (default bench/results/NAME)")
    r.add_argument("--no-area", action="store_true", help="skip the Yosys area step (slow: minutes a block)")
    r.add_argument("--cpu-repeat", type=int, default=0, help="ODE/simd timings: fastest of K (default: the sweep's)")
    p = sub.add_parser("plot", help="redraw a sweep's plots from its CSV")
    p.add_argument("name", choices=sorted(SWEEPS))
    p.add_argument("--out", type=Path)
    a = ap.parse_args(argv)

    if a.cmd == "list":
        for s in SWEEPS.values():
            print(f"{s.name:7s} {s.about}; {len(s.configs)} configurations x {len(s.scenes)} scenes x "
                  f"{len(s.links)} links")
        return 0
    sw = SWEEPS[a.name]
    out = a.out or RESULTS / sw.name
    if a.cmd == "run":
        if a.cpu_repeat < 0:
            ap.error("--cpu-repeat: must be >= 1")
        runner = sweeplib.Runner(sw, out, do_area=not a.no_area, cpu_repeat=a.cpu_repeat)
        try:
            rows, secs = runner.go()
        except RuntimeError as e:
            print(f"bench/sweep {sw.name}: {e}", file=sys.stderr)
            print("  (finished steps are cached; run the same command again to resume)", file=sys.stderr)
            return 1
        cmd = "bench/sweep run " + " ".join(sys.argv[2:] if argv is None else argv[1:])
        write_atomic(out / "MACHINE.md",
                     f"# {sw.name}: how these results were made\n\n- command: `{cmd.strip()}`\n"
                     f"- date: {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, "
                     f"{secs:.0f} s for the steps not already cached\n" + machine())
        print(f"{sw.name}: {len(rows)} rows -> {out / (sw.name + '.csv')}")
    rows = sweeplib.read_csv(out / f"{sw.name}.csv")
    for f in plots.draw(sw.name, rows, out):
        print(f"  plot {f}")
    print(f"  tables {report.write(sw.name, rows, out)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
