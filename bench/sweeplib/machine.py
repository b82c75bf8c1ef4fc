"""What a machine is, for MACHINE.md: written once per node by the first task that runs there
(build/sweep/nodes/NODE.md), since with Slurm the rows' timings come from other machines."""
import platform
import subprocess

from .paths import BUILD, ROOT, write_atomic

NODES = BUILD / "nodes"


def _sh(cmd) -> str:
    try:
        return subprocess.run(cmd, shell=True, capture_output=True, text=True).stdout.strip()
    except OSError:
        return "?"


def describe() -> str:
    model = _sh("lscpu | sed -n 's/^Model name: *//p'") or platform.processor()
    mem = _sh("free -g | awk '/Mem:/ {print $2}'")
    return (f"{_sh('nproc')} cores ({model}), {mem} GiB, {platform.system()} {platform.release()}; "
            f"{_sh('verilator --version')}; {_sh('yosys -V')}; {_sh('g++ --version | head -1')}")


def record_node(name: str) -> None:
    p = NODES / f"{name}.md"
    if not p.exists():
        write_atomic(p, describe() + "\n")


def node_line(name: str) -> str:
    p = NODES / f"{name}.md"
    return p.read_text().strip() if p.exists() else "(not described: no task recorded it)"


def commit() -> str:
    dirty = " (with uncommitted changes)" if _sh(f"git -C {ROOT} status --porcelain -- src host") else ""
    return _sh(f"git -C {ROOT} rev-parse --short HEAD") + dirty
