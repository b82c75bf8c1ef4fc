"""Where things live, and the content hash that keys every cached step."""
import hashlib
import os
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BUILD = ROOT / "build" / "sweep"          # caches: generated RTL, host builds, run results
RESULTS = ROOT / "bench" / "results"      # committed: CSV, plots, machine description
EXEC = BUILD / "exec"                     # per sweep: the executors' plan, task records, Slurm jobs


def tree_hash(*parts: str) -> str:
    """sha1 over the files under ROOT/part for each part (a file or a folder)."""
    h = hashlib.sha1()
    for part in parts:
        p = ROOT / part
        files = sorted(f for f in (p.rglob("*") if p.is_dir() else [p]) if f.is_file())
        for f in files:
            h.update(str(f.relative_to(ROOT)).encode())
            h.update(f.read_bytes())
    return h.hexdigest()[:16]


def rtl_hash() -> str:
    """What the generated Verilog depends on."""
    return tree_hash("src/main", "build.sbt", "project/build.properties")


def host_hash() -> str:
    """What a host binary depends on, besides its AFU."""
    return tree_hash("host")


def write_atomic(path: Path, text: str) -> None:
    """Readers see the old file or the new one, never half of it. The temporary name is unique,
    so steps running in parallel (or on several nodes) may write the same file."""
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=path.name + ".", suffix=".tmp")
    with os.fdopen(fd, "w") as f:
        f.write(text)
    os.chmod(tmp, 0o644)
    os.replace(tmp, path)
