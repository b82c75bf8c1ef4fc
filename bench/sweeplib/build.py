"""One host binary per configuration (CMake + Ninja, the Verilated AFU inside).

CMake re-Verilates only when the configuration's Verilog changed, and ccache (when present)
compiles the host's own sources once for all configurations."""
import os
import shutil
import subprocess
from pathlib import Path

from .paths import BUILD, ROOT, host_hash, write_atomic
from . import generate

HOST = BUILD / "host"


def binary(cfg) -> Path:
    return HOST / cfg.id / "collide"


def _stamp(cfg) -> Path:
    return HOST / cfg.id / ".sweep-key"


def _key(cfg) -> str:
    """What a binary was built from: its configuration's Verilog (by the RTL hash it was
    generated with) and the host's sources."""
    rtl = generate.folder(cfg) / ".rtl-hash"
    return f"{rtl.read_text() if rtl.exists() else '?'}-{host_hash()}"


def fresh(cfg) -> bool:
    """Built from today's Verilog and host sources: the step need not run again (an executor
    resuming a sweep does not resubmit it)."""
    s = _stamp(cfg)
    return binary(cfg).exists() and s.exists() and s.read_text() == _key(cfg)


def jobs() -> int:
    """Compile jobs: the CPUs a Slurm task was given, else 2 (a sweep's other steps run beside it)."""
    return int(os.environ.get("SLURM_CPUS_PER_TASK") or 2)


def build(cfg, log: Path) -> Path:
    d = HOST / cfg.id
    args = ["cmake", "-S", str(ROOT / "host"), "-B", str(d), "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
            f"-DCOLLIDE_AFU_DIR={generate.folder(cfg)}", "-DCOLLIDE_BUILD_TESTS=OFF"]
    if shutil.which("ccache"):
        args.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
    log.parent.mkdir(parents=True, exist_ok=True)
    with open(log, "w") as out:
        for cmd in (args, ["cmake", "--build", str(d), "--target", "collide", f"-j{jobs()}"]):
            if subprocess.run(cmd, stdout=out, stderr=subprocess.STDOUT).returncode != 0:
                raise RuntimeError(f"{cfg.id}: host build failed ({' '.join(cmd[:2])}); see {log}")
    write_atomic(_stamp(cfg), _key(cfg))
    return binary(cfg)
