"""The golden model's accuracy per SCPU spec (ScpuAccuracyReport --csv), cached by the RTL
sources' hash and the spec list. The model is bit-exact with the RTL (ScpuSpec)."""
import csv
import hashlib
import io
import subprocess
from pathlib import Path

from .paths import BUILD, ROOT, rtl_hash, tree_hash, write_atomic

PAIRS, SEED = 10000, 20261122


def cache_file(specs) -> Path:
    key = f"{rtl_hash()}-{tree_hash('src/test/scala/collide/scpu')}-{hashlib.sha1(','.join(specs).encode()).hexdigest()[:8]}"
    return BUILD / "accuracy" / f"{key}.csv"


def measure(specs, log: Path) -> dict:
    """spec -> the report's row (a dict of strings), in the order given."""
    out = cache_file(specs)
    if not out.exists():
        tmp = out.with_suffix(".part")
        tmp.parent.mkdir(parents=True, exist_ok=True)
        cmd = f"Test/runMain collide.scpu.ScpuAccuracyReport {PAIRS} {SEED} --csv {tmp} --configs {','.join(specs)}"
        log.parent.mkdir(parents=True, exist_ok=True)
        with open(log, "w") as f:
            r = subprocess.run([str(ROOT / "tools" / "sbt"), cmd], cwd=ROOT, stdout=f, stderr=subprocess.STDOUT)
        if r.returncode != 0 or not tmp.exists():
            raise RuntimeError(f"the accuracy report failed; see {log}")
        write_atomic(out, tmp.read_text())
        tmp.unlink()
    rows = list(csv.DictReader(io.StringIO(out.read_text())))
    if len(rows) != len(specs):
        raise RuntimeError(f"{out}: {len(rows)} rows for {len(specs)} specs")
    return dict(zip(specs, rows))
