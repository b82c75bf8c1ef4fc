"""Verilog for each configuration, from the Chisel generator; cached by the RTL sources' hash."""
import json
import re
import subprocess
from pathlib import Path

from .paths import BUILD, ROOT, rtl_hash, write_atomic

GEN = BUILD / "gen"


def folder(cfg) -> Path:
    return GEN / cfg.id


def fresh(cfg, rhash: str) -> bool:
    stamp = folder(cfg) / ".rtl-hash"
    return stamp.exists() and stamp.read_text() == rhash and (folder(cfg) / "manifest.json").exists()


def generate(configs, log: Path) -> None:
    """Generates every stale configuration in one sbt session (one JVM start for all)."""
    rhash = rtl_hash()
    stale = [c for c in configs if not fresh(c, rhash)]
    if not stale:
        return
    cmds = [f"run {c.generator_args()} --out {GEN} --folder {c.id}" for c in stale]
    log.parent.mkdir(parents=True, exist_ok=True)
    with open(log, "w") as out:
        r = subprocess.run([str(ROOT / "tools" / "sbt"), *cmds], cwd=ROOT, stdout=out, stderr=subprocess.STDOUT)
    if r.returncode != 0:
        raise RuntimeError(f"the generator failed for {[c.id for c in stale]}; see {log}")
    for c in stale:
        if not (folder(c) / "manifest.json").exists():
            raise RuntimeError(f"{c.id}: the generator wrote no manifest; see {log}")
        write_atomic(folder(c) / ".rtl-hash", rhash)


def manifest(cfg) -> dict:
    return json.loads((folder(cfg) / "manifest.json").read_text())


def verilog(cfg) -> Path:
    files = sorted(folder(cfg).glob("*.sv"))
    if len(files) != 1:
        raise RuntimeError(f"{cfg.id}: expected one .sv file in {folder(cfg)}, found {len(files)}")
    return files[0]


def module_named(cfg, prefix: str) -> str:
    """The one module whose name starts with `prefix` (module names carry their parameters)."""
    names = re.findall(rf"^module ({re.escape(prefix)}\w*)\(", verilog(cfg).read_text(), re.M)
    if len(names) != 1:
        raise RuntimeError(f"{cfg.id}: expected one module named {prefix}*, found {names}")
    return names[0]
