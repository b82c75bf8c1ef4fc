"""Iso-area: how many SCPUs of each arithmetic fit one FPGA, from the Yosys area proxy.

The chip is the paper's Stratix V 5SGXEA7 (Intel's Stratix V device overview: 234,720 ALMs,
256 variable-precision DSP blocks, 2,560 M20K blocks = 50 Mbit). The proxy synthesizes for
Cyclone V (bench/area/yosys_area.sh), whose ALMs have the same shape as Stratix V's for what
matters here: two adaptive LUTs and two adder bits per ALM, and (Stratix V) four registers.
So the ALMs a block needs lie between two counts, both reported:
  packed    max((LUT cells + adder cells) / 2, FFs / 4): every ALM used to the full
  unpacked  LUT cells + adder cells: one LUT per ALM
A real fit lies between them (alms_by_size: a third count, by the LUTs' inputs, where the
proxy counted them). DSPs: every multiplier Yosys maps (MISTRAL_MUL*) counts as one
block, although a Stratix V block holds two 18x18 or three 9x9 products, so narrow formats are
counted pessimistically. RAM: the sphere table copies and the pair buffer (the manifest's
bits) against 50 Mbit.

The PUC's area depends on the SCPU count (the replicated sphere tables, the dispatcher and
collector): it is interpolated between the counts the `scpus` sweep synthesized (1..32, fp32)
and extrapolated with the last slope; the narrower formats' PUC is taken as fp32's (an
overestimate: their tables and records are narrower).
"""
import math

CHIP = {"name": "Stratix V 5SGXEA7", "alms": 234720, "dsp": 256, "ram_bits": 2560 * 20 * 1024}
CALIBRATIONS = ("packed", "unpacked")
MAX_SPHERES = 1024     # the presets' on-chip table
PAIR_BUFFER_BITS = 34048  # 64 lines of 512 bits + line numbers (manifest afu.ram.pairBufferBits)


def _f(r, k):
    v = r.get(k, "")
    return float(v) if v not in ("", None) else 0.0


def alms(luts, arith, ff, calibration):
    if calibration == "packed":
        return max(math.ceil((luts + arith) / 2), math.ceil(ff / 4))
    return luts + arith


SIZES = ("lut6", "lut5", "lut4", "lut3")  # LUT cells by their inputs (lut3: three or fewer)


def alms_by_size(cells):
    """ALMs by the shapes an ALM takes in normal and arithmetic mode (Intel, Stratix V Device
    Handbook vol. 1, "Logic Array Blocks and Adaptive Logic Modules"): a 6-input LUT takes an ALM;
    a 5-input LUT takes one, with a LUT of three or fewer inputs beside it where there is one;
    the other LUTs of four or fewer inputs go two an ALM; adder cells two an ALM; at most four
    flip-flops an ALM. Between `packed` and `unpacked`: the estimate a fit is judged by. None
    unless `cells` has the LUT sizes (areas cached before they were counted)."""
    if not all(cells.get(k) not in (None, "") for k in SIZES + ("arith", "ff")):
        return None
    l6, l5, l4, l3, arith, ff = (int(cells[k]) for k in SIZES + ("arith", "ff"))
    luts = l6 + l5 + math.ceil((l4 + max(0, l3 - l5)) / 2)
    return max(luts + math.ceil(arith / 2), math.ceil(ff / 4))


def scpu_areas(arith_rows):
    """{spec: {luts, arith, dsp, ff, width}} from an arith sweep's rows (one SCPU each)."""
    out = {}
    for r in arith_rows:
        if r["scpu_spec"] in out or not r.get("scpu_luts"):
            continue
        width = {"fp16": 16, "bf16": 16, "fp64": 64}.get(r["format"], 32)
        out[r["scpu_spec"]] = {k: _f(r, f"scpu_{k}") for k in ("luts", "arith", "dsp", "ff")} | {"width": width}
    return out


def puc_table(scpus_rows):
    """[(n, {luts, arith, ff})] sorted by n, from a scpus sweep's rows."""
    t = {}
    for r in scpus_rows:
        if r.get("puc_luts"):
            t[int(r["scpus"])] = {k: _f(r, f"puc_{k}") for k in ("luts", "arith", "ff")}
    return sorted(t.items())


def puc_at(table, n):
    """The PUC's area at n SCPUs: linear between measured counts, the last slope beyond."""
    if not table:
        raise ValueError("no PUC areas: run `bench/sweep run scpus` first")
    pts = table if len(table) > 1 else table * 2
    for (n0, a0), (n1, a1) in zip(pts, pts[1:]):
        if n <= n1 or (n1, a1) == pts[-1]:
            t = (n - n0) / (n1 - n0) if n1 != n0 else 0.0
            return {k: a0[k] + t * (a1[k] - a0[k]) for k in a0}
    return pts[-1][1]


def fit(scpu, pucs, calibration):
    """(SCPUs that fit, the resource that stops one more) for one SCPU area."""
    n, why = 0, ""
    while n < 512:
        m = n + 1
        p = puc_at(pucs, m)
        use = {
            "ALMs": alms(p["luts"], p["arith"], p["ff"], calibration) + m * alms(scpu["luts"], scpu["arith"], scpu["ff"], calibration),
            "DSPs": m * scpu["dsp"],
            "RAM": m * MAX_SPHERES * 4 * scpu["width"] + PAIR_BUFFER_BITS,
        }
        over = [k for k, cap in (("ALMs", CHIP["alms"]), ("DSPs", CHIP["dsp"]), ("RAM", CHIP["ram_bits"])) if use[k] > cap]
        if over:
            why = over[0]
            break
        n = m
    return n, why


def fits(arith_rows, scpus_rows):
    """{(spec, calibration): (n, binding resource)} for every SCPU spec of the arith sweep."""
    pucs = puc_table(scpus_rows)
    return {(spec, cal): fit(a, pucs, cal) for spec, a in scpu_areas(arith_rows).items() for cal in CALIBRATIONS}
