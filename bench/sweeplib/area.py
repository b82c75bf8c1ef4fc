"""Area proxy per block (bench/area/yosys_area.sh: Yosys synth_intel_alm, Cyclone V), cached
by the block's Verilog. The AFU's area is reported as PUC + N x SCPU, each synthesized on its
own (no optimization across the boundary; the SCPUs are identical, so one synthesis serves N)."""
import hashlib
import json
import re
import subprocess
from pathlib import Path

from paths import BUILD, ROOT, write_atomic

CACHE = BUILD / "area"


def modules(text: str) -> dict:
    """Every module of a Verilog file: name -> its text, `module` to `endmodule`."""
    return {m.group(1): m.group(0) for m in re.finditer(r"^module (\w+)\(.*?^endmodule\n?", text, re.M | re.S)}


def instances(block: str, names) -> list:
    """The module types a module's text instantiates (once per instance), among `names`."""
    return [n for n in re.findall(r"^\s+(\w+)\s+\w+\s*\(", block, re.M) if n in names]


def subtree(text: str, top: str, black=()):
    """The preamble (macros) and the modules `top` instantiates, transitively: what Yosys needs.
    Modules named in `black` are black boxes: their ports only, nothing below them, so Yosys
    counts none of their cells (a block's own logic, or a block with its RAMs left out)."""
    first = re.search(r"^module ", text, re.M)
    pre = text[:first.start()] if first else ""
    blocks = modules(text)
    if top not in blocks:
        raise RuntimeError(f"no module {top}")
    if top in black:
        raise RuntimeError(f"{top} is the top: it cannot be a black box")
    seen, todo = [], [top]
    while todo:
        name = todo.pop()
        if name in seen:
            continue
        seen.append(name)
        if name not in black:
            todo += instances(blocks[name], blocks)
    return pre, [black_box(blocks[n]) if n in black else blocks[n] for n in sorted(seen)]


def black_box(block: str) -> str:
    """A module's header (its ports) as a Yosys black box."""
    return "(* blackbox *)\n" + block[:block.index(");") + 2] + "\nendmodule\n"


def children(text: str, top: str) -> dict:
    """The modules `top` instantiates directly, with how many times."""
    blocks = modules(text)
    if top not in blocks:
        raise RuntimeError(f"no module {top}")
    out = {}
    for n in instances(blocks[top], blocks):
        out[n] = out.get(n, 0) + 1
    return out


def _cache(text: str, top: str, config_id: str, black=()):
    """(preamble, modules, cache file): the cache is keyed by the block's Verilog (black boxes
    as such) with the configuration's id (which every module name carries) taken out."""
    pre, mods = subtree(text, top, black)
    generic_top = top.replace(config_id, "ID")
    key = hashlib.sha1(("".join(mods).replace(config_id, "ID") + generic_top).encode()).hexdigest()[:16]
    return pre, mods, CACHE / f"{generic_top}-{key}.json"


def is_cached(sv: Path, top: str, config_id: str) -> bool:
    return _cache(sv.read_text(), top, config_id)[2].exists()


def synth(sv: Path, top: str, log_dir: Path, config_id: str, black=()) -> dict:
    """Area of `top` and what it instantiates, but for the modules in `black` (black boxes).
    Cached (see _cache), so an SCPU shared by several configurations (same spec, other SCPU
    counts) is synthesized once."""
    pre, mods, cached = _cache(sv.read_text(), top, config_id, black)
    if cached.exists():
        return json.loads(cached.read_text())
    log_dir.mkdir(parents=True, exist_ok=True)
    stem = top + (".black" if black else "")
    part = log_dir / f"{stem}.sv"
    part.write_text(pre + "".join(mods))
    log = log_dir / f"yosys-{stem}.log"
    r = subprocess.run(["bash", str(ROOT / "bench" / "area" / "yosys_area.sh"), str(part), top, str(log)],
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"yosys on {top}: {r.stderr.strip()}")
    res = json.loads(r.stdout.strip().splitlines()[-1])
    write_atomic(cached, json.dumps(res) + "\n")
    return res


FIELDS = ("luts", "arith", "dsp", "ff", "m10k")


def afu_area(puc, scpu: dict, n: int) -> dict:
    """scpu_*: one SCPU; scpus_*: N of them; puc_* and area_* (PUC + N x SCPU) when the PUC was
    synthesized (puc is None otherwise)."""
    r = {f"scpu_{k}": scpu[k] for k in FIELDS} | {f"scpus_{k}": n * scpu[k] for k in FIELDS}
    if puc is not None:
        r |= {f"area_{k}": puc[k] + n * scpu[k] for k in FIELDS} | {f"puc_{k}": puc[k] for k in FIELDS}
    return r
