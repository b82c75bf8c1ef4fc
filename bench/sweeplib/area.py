"""Area proxy per block (bench/area/yosys_area.sh: Yosys synth_intel_alm, Cyclone V), cached
by the block's Verilog. The AFU's area is reported as PUC + N x SCPU, each synthesized on its
own (no optimization across the boundary; the SCPUs are identical, so one synthesis serves N)."""
import hashlib
import json
import re
import subprocess
from pathlib import Path

from .paths import BUILD, ROOT, write_atomic

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


def memories(text: str) -> set:
    """firtool's memory modules: a `reg ... Memory[...]` array."""
    return {n for n, block in modules(text).items() if re.search(r"^\s+reg\s.*\bMemory\[", block, re.M)}


def blocks(text: str, top: str, split) -> list:
    """A Verilog file cut into blocks for Yosys, from `top` down: [(module, count under top, black
    boxes, what is black)]. A module for which `split(name)` holds is its own logic (its children
    black boxes), then its children the same way, breadth first; any other module is whole, with
    its RAMs (memories) as black boxes. Counts multiply down the tree."""
    mems = memories(text)
    rows, todo = [], [(top, 1)]
    while todo:
        mod, n = todo.pop(0)
        if split(mod):
            kids = children(text, mod)
            rows.append((mod, n, frozenset(kids), "every block below"))
            todo += [(k, n * c) for k, c in sorted(kids.items()) if k not in mems]
        else:
            rows.append((mod, n, frozenset(mems), "RAMs"))
    return rows


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


CELLS = ["luts", "arith", "dsp", "ff"]  # the cells synth reports (besides the LUTs by inputs, isoarea.SIZES)


def is_cached(sv: Path, top: str, config_id: str, black=()) -> bool:
    return _cache(sv.read_text(), top, config_id, black)[2].exists()


def _job(sv: Path, top: str, log_dir: Path, config_id: str, black, kind: str):
    """(cache file, Yosys's input: top's subtree, the file it goes in, Yosys's log) of one block
    and kind of result; nothing is written (see _write)."""
    pre, mods, cached = _cache(sv.read_text(), top, config_id, black)
    if kind:
        cached = cached.with_name(cached.stem + f"-{kind}.json")
    stem = top + (".black" if black else "")
    return cached, pre + "".join(mods), log_dir / f"{stem}.sv", log_dir / f"yosys-{stem}{'-' + kind if kind else ''}.log"


def _write(text: str, part: Path) -> None:
    part.parent.mkdir(parents=True, exist_ok=True)
    part.write_text(text)


def synth(sv: Path, top: str, log_dir: Path, config_id: str, black=()) -> dict:
    """Area of `top` and what it instantiates, but for the modules in `black` (black boxes).
    Cached (see _cache), so an SCPU shared by several configurations (same spec, other SCPU
    counts) is synthesized once."""
    cached, text, part, log = _job(sv, top, log_dir, config_id, black, "")
    if cached.exists():
        return json.loads(cached.read_text())
    _write(text, part)
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


# --- timing proxy ---------------------------------------------------------------------------
TIMING_FAMILIES = ("cyclonev", "arriav")
_PATH_CELL = re.compile(r"^\s+(\d+)\s+(\S+)\s+\((MISTRAL_\w+)\.\w+(?:->\w+)?\)")
_PATH_OUT = re.compile(r"^\s+(\d+)\s+\(<(primary output|unknown)>\)")
_PATH_IN = re.compile(r"^\s+(\d+)\s+\\?(\S+)(?: \[\d+\])? \(<primary input>\)")


def _signal(cell: str) -> str:
    """The RTL signal a mapped cell was named after (Yosys appends _MISTRAL_<type>_<port>...)."""
    return cell.split("_MISTRAL_")[0]


def parse_sta(log: str) -> list:
    """Each `sta` report of a Yosys log, in order: the slowest path's arrival (ps; cell delays
    only), the register or output it ends at and the register or input it starts from, and the
    logic on it: LUTs, carry-chain cells (one arithmetic cell a bit) and DSP blocks. None for a
    report without a path."""
    out = []
    for section in log.split("Executing STA pass")[1:]:
        head = re.search(r"Latest arrival time in '[^']*' is (\d+):", section)
        if not head:
            out.append(None)
            continue
        cells, start, end = [], "", ""
        for line in section[head.end():].splitlines()[1:]:
            if (c := _PATH_CELL.match(line)):
                cells.append((c.group(2), c.group(3)))
            elif (o := _PATH_OUT.match(line)):
                # an output port, or (<unknown>) the input of a black box
                end = "<output>" if o.group(2) == "primary output" else "<black box>"
            elif (i := _PATH_IN.match(line)):
                start = i.group(2)
            elif line.strip() and not line.startswith((" ", "Warning:")):
                break
        if not end and cells:
            end = _signal(cells.pop(0)[0]) # the endpoint: a register's (or RAM's) input
        if cells and cells[-1][1] == "MISTRAL_FF":
            start = _signal(cells.pop()[0]) # the launching register (its clock is the input)
        kinds = [k for _, k in cells]
        out.append({"ps": int(head.group(1)), "to": end, "from": start,
                    "luts": sum(k in ("MISTRAL_NOT",) or re.fullmatch(r"MISTRAL_ALUT\d", k) is not None for k in kinds),
                    "carry": kinds.count("MISTRAL_ALUT_ARITH"),
                    "dsp": sum(k.startswith("MISTRAL_MUL") for k in kinds),
                    "cells": len(kinds)})
    return out


# The AFU's blocks as the timing proxy cuts them: these are their own logic, children apart.
AFU_SPLIT = ("Afu_", "Puc_", "BroadPhase_")


def afu_blocks(text: str, top: str) -> list:
    """blocks(), split at the AFU, its PUC and its broad phase: each one's own logic (every
    child a black box), every other block whole with its RAMs as black boxes."""
    return blocks(text, top, lambda m: m.startswith(AFU_SPLIT))


TIMING_SCRIPT = ROOT / "bench" / "area" / "yosys_timing.sh"


def _timing_job(sv: Path, top: str, log_dir: Path, config_id: str, black):
    # The flow is part of the key: a changed script times every block again.
    flow = hashlib.sha1(TIMING_SCRIPT.read_bytes()).hexdigest()[:8]
    return _job(sv, top, log_dir, config_id, black, f"timing-{flow}")


def timing_is_cached(sv: Path, top: str, config_id: str, black=()) -> bool:
    return _timing_job(sv, top, Path("."), config_id, black)[0].exists()


def timing(sv: Path, top: str, log_dir: Path, config_id: str, black=()) -> dict:
    """The timing proxy of `top` (bench/area/yosys_timing.sh): for each family of
    TIMING_FAMILIES, the slowest path's cell delay in ps (`<family>_ps`, 0 without a path) and,
    for the first, what the path is. Cached as synth is."""
    script = TIMING_SCRIPT
    cached, text, part, log = _timing_job(sv, top, log_dir, config_id, black)
    # The path's ends name module instances, whose names carry the configuration's id: cached
    # with a placeholder, so a block shared by configurations names each its own.
    def named(res: dict, a: str, b: str) -> dict:
        return {k: (v.replace(a, b) if isinstance(v, str) else v) for k, v in res.items()}
    if cached.exists():
        return named(json.loads(cached.read_text()), "_{id}", f"_{config_id}")
    _write(text, part)
    # Only the black boxes top's subtree instantiates (a module Yosys never read cannot be selected).
    present = sorted(set(black) & modules(text).keys())
    r = subprocess.run(["bash", str(script), str(part), top, str(log), *present], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"yosys on {top}: {r.stderr.strip()}")
    reports = parse_sta(log.read_text())
    if len(reports) != len(TIMING_FAMILIES):
        raise RuntimeError(f"{log}: expected {len(TIMING_FAMILIES)} sta reports, found {len(reports)}")
    first = reports[0] or {"ps": 0, "to": "", "from": "", "luts": 0, "carry": 0, "dsp": 0, "cells": 0}
    res = {"top": top, **{f"{fam}_ps": (rep["ps"] if rep else 0) for fam, rep in zip(TIMING_FAMILIES, reports)},
           **{f"path_{k}": first[k] for k in ("luts", "carry", "dsp", "cells", "from", "to")}}
    write_atomic(cached, json.dumps(named(res, f"_{config_id}", "_{id}")) + "\n")
    return res
