"""One host binary per configuration (CMake + Ninja, the Verilated AFU inside).

CMake re-Verilates only when the configuration's Verilog changed, and ccache (when present)
compiles the host's own sources once for all configurations."""
import shutil
import subprocess
from pathlib import Path

from paths import BUILD, ROOT
import generate

HOST = BUILD / "host"


def binary(cfg) -> Path:
    return HOST / cfg.id / "collide"


def build(cfg, log: Path) -> Path:
    d = HOST / cfg.id
    args = ["cmake", "-S", str(ROOT / "host"), "-B", str(d), "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
            f"-DCOLLIDE_AFU_DIR={generate.folder(cfg)}", "-DCOLLIDE_BUILD_TESTS=OFF"]
    if shutil.which("ccache"):
        args.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
    log.parent.mkdir(parents=True, exist_ok=True)
    with open(log, "w") as out:
        for cmd in (args, ["cmake", "--build", str(d), "--target", "collide", "-j2"]):
            if subprocess.run(cmd, stdout=out, stderr=subprocess.STDOUT).returncode != 0:
                raise RuntimeError(f"{cfg.id}: host build failed ({' '.join(cmd[:2])}); see {log}")
    return binary(cfg)
