"""Area proxy per block (bench/area/yosys_area.sh: Yosys synth_intel_alm, Cyclone V), cached
by the block's Verilog. The AFU's area is reported as PUC + N x SCPU, each synthesized on its
own (no optimization across the boundary; the SCPUs are identical, so one synthesis serves N)."""
import hashlib
import json
import subprocess
from pathlib import Path

from paths import BUILD, ROOT, write_atomic

CACHE = BUILD / "area"


def synth(sv: Path, top: str, log_dir: Path) -> dict:
    key = hashlib.sha1(sv.read_bytes() + top.encode()).hexdigest()[:16]
    cached = CACHE / f"{top}-{key}.json"
    if cached.exists():
        return json.loads(cached.read_text())
    log_dir.mkdir(parents=True, exist_ok=True)
    log = log_dir / f"yosys-{top}.log"
    r = subprocess.run(["bash", str(ROOT / "bench" / "area" / "yosys_area.sh"), str(sv), top, str(log)],
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"yosys on {top}: {r.stderr.strip()}")
    res = json.loads(r.stdout.strip().splitlines()[-1])
    write_atomic(cached, json.dumps(res) + "\n")
    return res


FIELDS = ("luts", "arith", "dsp", "ff", "m10k")


def afu_area(puc: dict, scpu: dict, n: int) -> dict:
    return {f"area_{k}": puc[k] + n * scpu[k] for k in FIELDS} | \
           {f"scpu_{k}": scpu[k] for k in FIELDS} | {f"puc_{k}": puc[k] for k in FIELDS}
