"""World mode in NVIDIA Warp: `collide spheres --backend simd`'s contacts, byte for byte, from
Warp kernels that run on the CPU here and on a CUDA device where there is one.

    tools/pyenv bench/world/warp_world.py --spheres FILE --out FILE [--device cpu|cuda:0]
                                          [--repeat N] [--summary FILE]

Input: the sphere CSV of `collide spheres` (header x,y,z,r; decimal or C99 hex floats, each
rounded once to binary32 by the C library's strtof, as host/cli/number_csv.cpp reads them).
Output: its contacts file (docs/host-world.md, "collide spheres"): i,j,px,py,pz,nx,ny,nz,depth,flags,
one row a contact, i < j, sorted by (i, j), binary32 values as C's %a, the normal from sphere j
to sphere i, flags 3 (contact) or 5 (coincident); a sphere the bad-pair rule rejects (non-finite,
radius outside (0, 1e6], a centre beyond +-1e6) is a row with j empty, zero fields and flags 8
or 32, in the same order by i.

Pipeline, all Warp kernels on --device (module option fuse_fp off: no fused multiply-add):
  h2d     the good spheres' binary32 values (and their binary64 widening for the grid) to the device;
  broad   wp.HashGrid (float64) of the centres, cells 2 reach(r_max) wide; each sphere i queries
          reach(r_i) + reach(r_max) around it and keeps every j > i whose centres are within
          reach(r_i) + reach(r_j) on each axis (reach(r) = r (1 + 2^-20) + 2^-60, in binary64,
          host/world/engine_broad_phase.hpp's: binary32 calls no farther pair a hit); a count
          pass, a prefix sum, an emit pass that keeps each sphere's j ascending, so the
          candidates come out sorted by (i, j);
  narrow  the binary32 sphere test and contact values of host/collide/simd_kernel.cpp on each
          candidate, in its operation order, and the record flags of contact_flags.cpp;
  finish  a prefix sum over the hits and a scatter that keeps them, in order;
  d2h     the contacts back to host memory.
Each phase is timed between wp.synchronize_device calls; --repeat N keeps the fastest of each.
Kernels are compiled (or loaded from Warp's cache) before any timing. Prints one JSON line on
stdout (and writes it to --summary): the phases in ns, counts, the device.
"""
import argparse
import ctypes
import json
import math
import sys
import time
from pathlib import Path

import numpy as np
import warp as wp

wp.config.log_level = wp.LOG_WARNING  # no banner: stdout carries the summary line

# No contraction of a * b + c into an FMA: every operation is one binary32 rounding in the
# kernel's order, as host/collide/simd_kernel.cpp is compiled (-ffp-contract=off).
wp.set_module_options({"fuse_fp": False, "fast_math": False, "enable_backward": False})

MAX_LINE_BYTES = 1 << 16
MAX_COORD, MAX_RADIUS = 1e6, 1e6       # host/batch/sane_ranges.hpp
REC_NONFINITE, REC_HOST_RANGE = 8, 32  # generated/afu_contract.hpp
FLAG_CONTACT = wp.constant(3)    # REC_HIT | KIND_CONTACT << REC_KIND_SHIFT
FLAG_COINCIDENT = wp.constant(5)  # REC_HIT | KIND_COINCIDENT << REC_KIND_SHIFT


class InputError(Exception):
    """A bad input file: the message names the file and, for a row, its line."""


# --- input: host/cli/number_csv.cpp's rules ------------------------------------------------

_libc = ctypes.CDLL(None)
_strtof = _libc.strtof
_strtof.restype = ctypes.c_float
_strtof.argtypes = [ctypes.c_char_p, ctypes.POINTER(ctypes.c_char_p)]


def parse_f32(field):
    """bytes -> the binary32 value strtof gives (one rounding, decimal or hex), or None when the
    field is not a whole number."""
    end = ctypes.c_char_p()
    buf = ctypes.create_string_buffer(field)
    v = _strtof(buf, ctypes.byref(end))
    used = ctypes.cast(end, ctypes.c_void_p).value - ctypes.addressof(buf)
    return v if used > 0 and used == len(field) else None


def _clip(b, n=64):
    s = b.decode("utf-8", "replace")
    return s if len(s) <= n else s[:n] + "..."


def read_spheres(path):
    """The spheres of a `collide spheres` CSV as a float32 array (n, 4); InputError names the
    file and the line of whatever is wrong."""
    name = str(path)
    try:
        data = Path(path).read_bytes()
    except FileNotFoundError:
        raise InputError(f"{name}: no such file") from None
    except IsADirectoryError:
        raise InputError(f"{name}: is a directory") from None
    except OSError as e:
        raise InputError(f"{name}: {e.strerror}") from None
    rows, header = [], False
    lines = data.split(b"\n")
    if lines and lines[-1] == b"":
        lines.pop()
    for number, raw in enumerate(lines, 1):
        if len(raw) > MAX_LINE_BYTES:
            raise InputError(f"{name}:{number}: line longer than {MAX_LINE_BYTES} bytes (a row is 4 numbers)")
        if number == 1 and raw.startswith(b"\xef\xbb\xbf"):
            raw = raw[3:]
        s = raw.strip(b" \t\r")
        if not s:
            continue
        if not header:
            if s != b"x,y,z,r":
                raise InputError(f"{name}:{number}: expected the header 'x,y,z,r', got '{_clip(s)}'")
            header = True
            continue
        fields = [f.strip(b" \t\r") for f in s.split(b",")]
        if len(fields) != 4:
            raise InputError(f"{name}:{number}: expected 4 fields, got {len(fields)}")
        row = []
        for column, f in zip("xyzr", fields):
            if not f:
                raise InputError(f"{name}:{number}: {column}: empty field")
            v = parse_f32(f)
            if v is None:
                raise InputError(f"{name}:{number}: {column}: not a number: '{_clip(f)}'")
            if math.isinf(v) and not any(c in f for c in b"iI"):
                raise InputError(f"{name}:{number}: {column}: '{_clip(f)}' overflows binary32")
            row.append(v)
        rows.append(row)
    if not header:
        raise InputError(f"{name}:{max(1, len(lines))}: empty input: expected the header 'x,y,z,r'")
    return np.array(rows, dtype=np.float32).reshape(-1, 4)


def classify(spheres):
    """(good mask, flag per sphere): host/collide/input_policy.cpp's classifySphere."""
    s = spheres.astype(np.float64)
    finite = np.isfinite(s).all(axis=1)
    in_range = (s[:, 3] > 0) & (s[:, 3] <= MAX_RADIUS) & (np.abs(s[:, :3]) <= MAX_COORD).all(axis=1)
    good = finite & in_range
    flags = np.where(finite, REC_HOST_RANGE, REC_NONFINITE).astype(np.int32)
    return good, flags


# --- output: host/cli/spheres_csv.cpp's writer --------------------------------------------

def hex_a(v):
    """C's %a of a binary64 value (glibc: no trailing zeros, 0x0p+0 for zero)."""
    if v != v:
        return "-nan" if math.copysign(1.0, v) < 0 else "nan"
    if math.isinf(v):
        return "-inf" if v < 0 else "inf"
    h = float.hex(v)
    mant, exp = h.split("p")
    if "." in mant:
        mant = mant.rstrip("0").rstrip(".")
    return f"{mant}p{exp}"


def write_contacts(path, i, j, values, flags, bad, bad_flags):
    """i, j: row numbers; values: (k, 7) float32; bad: ascending row numbers of bad spheres."""
    zeros = ",".join([hex_a(0.0)] * 7)
    out = ["i,j,px,py,pz,nx,ny,nz,depth,flags\n"]
    cache = {}

    def h(v):
        s = cache.get(v)
        if s is None:
            s = cache[v] = hex_a(v)
        return s

    vals = values.astype(np.float64).tolist()
    b, nb = 0, len(bad)
    for k, (a, c) in enumerate(zip(i.tolist(), j.tolist())):
        while b < nb and bad[b] < a:
            out.append(f"{bad[b]},,{zeros},{bad_flags[b]}\n")
            b += 1
        out.append(f"{a},{c},{','.join(h(v) for v in vals[k])},{flags[k]}\n")
    for k in range(b, nb):
        out.append(f"{bad[k]},,{zeros},{bad_flags[k]}\n")
    text = "".join(out)
    if str(path) == "-":
        sys.stdout.write(text)
    else:
        tmp = Path(str(path) + ".tmp")
        tmp.write_text(text)
        tmp.replace(path)


# --- kernels -------------------------------------------------------------------------------

# host/world/engine_broad_phase.hpp's reach: r (1 + 2^-20) + 2^-60, in binary64; the kernels'
# reach and the host's (reach_f64, which sizes the grid's cells and queries) share these.
REACH_SCALE = 1.0 + 2.0 ** -20
REACH_PAD = 2.0 ** -60


@wp.func
def reach(r: wp.float64):
    return r * wp.float64(REACH_SCALE) + wp.float64(REACH_PAD)


@wp.func
def within(p: wp.vec3d, q: wp.vec3d, ri: wp.float64, rj: wp.float64):
    lim = reach(ri) + reach(rj)
    return wp.abs(p[0] - q[0]) <= lim and wp.abs(p[1] - q[1]) <= lim and wp.abs(p[2] - q[2]) <= lim


@wp.kernel
def count_candidates(grid: wp.uint64, pos: wp.array(dtype=wp.vec3d), rad: wp.array(dtype=wp.float64),
                     reach_max: wp.float64, counts: wp.array(dtype=wp.int32)):
    i = wp.tid()
    p = pos[i]
    ri = rad[i]
    n = int(0)
    query = wp.hash_grid_query(grid, p, reach(ri) + reach_max)
    j = int(0)
    while wp.hash_grid_query_next(query, j):
        if j > i:
            if within(p, pos[j], ri, rad[j]):
                n += 1
    counts[i] = n


@wp.kernel
def emit_candidates(grid: wp.uint64, pos: wp.array(dtype=wp.vec3d), rad: wp.array(dtype=wp.float64),
                    reach_max: wp.float64, offsets: wp.array(dtype=wp.int32),
                    cand_i: wp.array(dtype=wp.int32), cand_j: wp.array(dtype=wp.int32)):
    i = wp.tid()
    p = pos[i]
    ri = rad[i]
    start = offsets[i]
    end = start
    query = wp.hash_grid_query(grid, p, reach(ri) + reach_max)
    j = int(0)
    while wp.hash_grid_query_next(query, j):
        if j > i:
            if within(p, pos[j], ri, rad[j]):
                # insertion into this sphere's own segment: its j's ascending
                k = end
                while k > start and cand_j[k - 1] > j:
                    cand_j[k] = cand_j[k - 1]
                    k -= 1
                cand_j[k] = j
                cand_i[end] = i
                end += 1


@wp.kernel
def narrow_phase(x: wp.array(dtype=wp.float32), y: wp.array(dtype=wp.float32), z: wp.array(dtype=wp.float32),
                 r: wp.array(dtype=wp.float32), cand_i: wp.array(dtype=wp.int32), cand_j: wp.array(dtype=wp.int32),
                 values: wp.array2d(dtype=wp.float32), hit: wp.array(dtype=wp.int32), flags: wp.array(dtype=wp.int32)):
    # host/collide/simd_kernel.cpp's body in binary32, operation for operation (ODE's dCollideSpheres):
    # d = sqrt((dx*dx + dy*dy) + dz*dz); a contact unless d > r1 + r2 (a NaN d is one);
    # d <= 0: pos p1, normal (1,0,0), depth r1 + r2; else normal (p1 - p2) * (1/d),
    # pos p1 + normal * (0.5 * ((r2 - r1) - d)), depth (r1 + r2) - d.
    k = wp.tid()
    a = cand_i[k]
    b = cand_j[k]
    x1 = x[a]
    y1 = y[a]
    z1 = z[a]
    r1 = r[a]
    x2 = x[b]
    y2 = y[b]
    z2 = z[b]
    r2 = r[b]
    dx = x1 - x2
    dy = y1 - y2
    dz = z1 - z2
    d2 = (dx * dx + dy * dy) + dz * dz
    d = wp.sqrt(d2)
    rsum = r1 + r2
    h = not (d > rsum)
    zero = wp.float32(0.0)
    if h:
        if d <= zero:
            values[k, 0] = x1
            values[k, 1] = y1
            values[k, 2] = z1
            values[k, 3] = wp.float32(1.0)
            values[k, 4] = zero
            values[k, 5] = zero
            values[k, 6] = rsum
        else:
            inv = wp.float32(1.0) / d
            ex = dx * inv
            ey = dy * inv
            ez = dz * inv
            kk = wp.float32(0.5) * ((r2 - r1) - d)
            values[k, 0] = x1 + ex * kk
            values[k, 1] = y1 + ey * kk
            values[k, 2] = z1 + ez * kk
            values[k, 3] = ex
            values[k, 4] = ey
            values[k, 5] = ez
            values[k, 6] = rsum - d
        hit[k] = 1
        # contact_flags.cpp: coincident where d^2 (the same sum) is zero
        if d2 == zero:
            flags[k] = FLAG_COINCIDENT
        else:
            flags[k] = FLAG_CONTACT
    else:
        hit[k] = 0
        flags[k] = 0


@wp.kernel
def keep_hits(hit: wp.array(dtype=wp.int32), where: wp.array(dtype=wp.int32), cand_i: wp.array(dtype=wp.int32),
              cand_j: wp.array(dtype=wp.int32), values: wp.array2d(dtype=wp.float32), flags: wp.array(dtype=wp.int32),
              out_i: wp.array(dtype=wp.int32), out_j: wp.array(dtype=wp.int32),
              out_values: wp.array2d(dtype=wp.float32), out_flags: wp.array(dtype=wp.int32)):
    k = wp.tid()
    if hit[k] != 0:
        w = where[k]
        out_i[w] = cand_i[k]
        out_j[w] = cand_j[k]
        for c in range(7):
            out_values[w, c] = values[k, c]
        out_flags[w] = flags[k]


KERNELS_MODULE = sys.modules[__name__]


# --- one collision -------------------------------------------------------------------------

def reach_f64(r):
    return r * REACH_SCALE + REACH_PAD


def grid_dims(n):
    """Hashed cells per axis: about 2n cells in all, at most 128^3."""
    return max(1, min(128, math.ceil((2 * max(n, 1)) ** (1 / 3))))


def collide_once(good, device):
    """good: float32 (m, 4) of the good spheres. Returns (times in ns, candidates,
    (i, j, values, flags) as numpy, in the spheres' compact numbering)."""
    m = len(good)
    t = {}

    def phase(name, t0):
        wp.synchronize_device(device)
        t[name] = time.perf_counter_ns() - t0

    # h2d: binary32 values for the narrow phase, their exact binary64 widening for the grid
    # (laid out in host memory first, untimed: the copies alone are timed)
    cols = [np.ascontiguousarray(good[:, c]) for c in range(4)]
    pos64, rad64 = np.ascontiguousarray(good[:, :3], dtype=np.float64), cols[3].astype(np.float64)
    wp.synchronize_device(device)
    t0 = time.perf_counter_ns()
    x, y, z, r = (wp.array(c, dtype=wp.float32, device=device) for c in cols)
    pos = wp.array(pos64, dtype=wp.vec3d, device=device)
    rad = wp.array(rad64, dtype=wp.float64, device=device)
    phase("h2d_ns", t0)

    r_max = float(good[:, 3].max()) if m else 1.0
    cell = max(2 * reach_f64(r_max), 2.0 ** -10)
    dim = grid_dims(m)

    # broad
    t0 = time.perf_counter_ns()
    grid = wp.HashGrid(dim, dim, dim, device=device, dtype=wp.float64)
    counts = wp.zeros(max(m, 1), dtype=wp.int32, device=device)
    offsets = wp.zeros(max(m, 1), dtype=wp.int32, device=device)
    if m:
        grid.build(pos, cell)
        wp.launch(count_candidates, dim=m, inputs=[grid.id, pos, rad, wp.float64(reach_f64(r_max)), counts], device=device)
        wp.utils.array_scan(counts, offsets, inclusive=False)
    total = int(offsets[m - 1:m].numpy()[0] + counts[m - 1:m].numpy()[0]) if m else 0
    cand_i = wp.empty(max(total, 1), dtype=wp.int32, device=device)
    cand_j = wp.empty(max(total, 1), dtype=wp.int32, device=device)
    if total:
        wp.launch(emit_candidates, dim=m, inputs=[grid.id, pos, rad, wp.float64(reach_f64(r_max)), offsets, cand_i, cand_j],
                  device=device)
    phase("broad_ns", t0)

    # narrow
    t0 = time.perf_counter_ns()
    values = wp.empty((max(total, 1), 7), dtype=wp.float32, device=device)
    hit = wp.zeros(max(total, 1), dtype=wp.int32, device=device)
    flags = wp.zeros(max(total, 1), dtype=wp.int32, device=device)
    if total:
        wp.launch(narrow_phase, dim=total, inputs=[x, y, z, r, cand_i, cand_j, values, hit, flags], device=device)
    phase("narrow_ns", t0)

    # finish: keep the hits, in order
    t0 = time.perf_counter_ns()
    where = wp.zeros(max(total, 1), dtype=wp.int32, device=device)
    if total:
        wp.utils.array_scan(hit, where, inclusive=False)
    hits = int(where[total - 1:total].numpy()[0] + hit[total - 1:total].numpy()[0]) if total else 0
    out_i = wp.empty(max(hits, 1), dtype=wp.int32, device=device)
    out_j = wp.empty(max(hits, 1), dtype=wp.int32, device=device)
    out_values = wp.empty((max(hits, 1), 7), dtype=wp.float32, device=device)
    out_flags = wp.empty(max(hits, 1), dtype=wp.int32, device=device)
    if hits:
        wp.launch(keep_hits, dim=total, inputs=[hit, where, cand_i, cand_j, values, flags, out_i, out_j, out_values, out_flags],
                  device=device)
    phase("finish_ns", t0)

    # d2h: copies into host memory of their own (on the CPU device a memcpy)
    t0 = time.perf_counter_ns()
    res = tuple(np.array(a.numpy()[:hits], copy=True) for a in (out_i, out_j, out_values, out_flags))
    phase("d2h_ns", t0)
    return t, total, res


def collide(spheres, device="cpu", repeat=1):
    """Every contact of a float32 (n, 4) sphere table on `device`: (summary dict, i, j,
    values, flags, bad rows, bad flags), i and j the table's row numbers."""
    good_mask, bad_flag = classify(spheres)
    members = np.flatnonzero(good_mask)
    good = np.ascontiguousarray(spheres[members])
    t0 = time.perf_counter()
    wp.load_module(KERNELS_MODULE, device=device)
    load_s = time.perf_counter() - t0
    best, res, total = None, None, 0
    for _ in range(repeat):
        t, total, res = collide_once(good, device)
        best = t if best is None else {k: min(best[k], v) for k, v in t.items()}
    ci, cj, values, flags = res
    bad = np.flatnonzero(~good_mask)
    summary = {"spheres": len(spheres), "bad_spheres": int(len(bad)), "candidates": total, "contacts": int(len(ci)),
               "backend": "warp", "broad_phase": "warp HashGrid", "format": "binary32",
               "device": str(wp.get_device(device)), "device_name": wp.get_device(device).name,
               "warp": wp.config.version, "repeat": repeat, **best,
               "kernels_ns": best["broad_ns"] + best["narrow_ns"] + best["finish_ns"],
               "copies_ns": best["h2d_ns"] + best["d2h_ns"], "load_s": load_s}
    return summary, members[ci], members[cj], values, flags, bad, bad_flag[bad]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--spheres", required=True, help="the sphere CSV (header x,y,z,r)")
    ap.add_argument("--out", required=True, help="the contacts file ('-': stdout)")
    ap.add_argument("--device", default="cpu", help="a Warp device: cpu (default), cuda:0, ...")
    ap.add_argument("--repeat", type=int, default=1, help="collide N times, keep each phase's fastest (1-1000)")
    ap.add_argument("--summary", help="also write the JSON summary to this file")
    a = ap.parse_args(argv)
    if not 1 <= a.repeat <= 1000:
        ap.error(f"--repeat {a.repeat}: expected 1 to 1000")
    wp.init()
    try:
        device = wp.get_device(a.device)
    except (RuntimeError, ValueError) as e:
        cuda = wp.get_cuda_device_count()
        print(f"warp_world: --device {a.device}: no such device ({e}; {cuda} CUDA device(s) here)", file=sys.stderr)
        return 2
    try:
        spheres = read_spheres(a.spheres)
    except InputError as e:
        print(f"warp_world: {e}", file=sys.stderr)
        return 1
    summary, i, j, values, flags, bad, bad_flags = collide(spheres, device, a.repeat)
    write_contacts(a.out, i, j, values, flags.tolist(), bad.tolist(), bad_flags.tolist())
    line = json.dumps(summary)
    if a.out != "-":
        print(line)
    ms = lambda k: f"{summary[k] / 1e6:.3f}"
    print(f"warp_world: {summary['spheres']} spheres ({summary['bad_spheres']} bad), {summary['candidates']} candidate "
          f"pairs, {summary['contacts']} contacts on {summary['device']} ({summary['device_name']}); fastest of "
          f"{a.repeat}: h2d {ms('h2d_ns')} ms, broad {ms('broad_ns')} ms, narrow {ms('narrow_ns')} ms, finish "
          f"{ms('finish_ns')} ms, d2h {ms('d2h_ns')} ms", file=sys.stderr)
    if a.summary:
        Path(a.summary).write_text(json.dumps(summary, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
