"""bench/world/warp_world.py, the Warp backend of world mode, on Warp's CPU device: its contacts
file is byte for byte `collide spheres --backend simd`'s on the project's small worlds and on
random ones (touching pairs nudged by ulps, coincident centres, mixed radii, bad spheres,
decimal text); its input errors name the file and the line.

Random worlds print their seed: SEED=N replays one (else a hash of the test's name, mixed with
COLLIDE_RUN_SEED when set, as the Scala specs do). The comparison needs the host's collide
binary (build/host/collide: cmake -S host -B build/host ... --target collide) and skips, saying
so, without it. Run with the suite: tools/pyenv -m unittest discover -s bench/tests -v"""
import contextlib
import ctypes
import io
import math
import os
import random
import subprocess
import sys
import tempfile
import unittest
import zlib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench" / "world"))

try:
    import numpy as np
    import warp as wp
except ImportError as e:  # the pinned venv has both (bench/requirements.txt)
    raise unittest.SkipTest(f"warp_world needs warp-lang and numpy (tools/pyenv installs them): {e}")

wp.config.quiet = True
import warp_world  # noqa: E402
import world  # noqa: E402

COLLIDE = ROOT / "build" / "host" / "collide"


def seed(name):
    if os.environ.get("SEED"):
        s = int(os.environ["SEED"])
    else:
        s = (zlib.crc32(name.encode()) ^ int(os.environ.get("COLLIDE_RUN_SEED") or 0)) & 0xFFFFFFFF
    print(f"[{name}] seed = {s} (set with SEED={s})", file=sys.stderr)
    return s


def f32(v):
    return float(np.float32(v))


def ulps(v, k):
    """v moved k binary32 ulps (k < 0: down)."""
    x = np.float32(v)
    for _ in range(abs(k)):
        x = np.nextafter(x, np.float32(math.inf if k > 0 else -math.inf))
    return float(x)


def random_world(rng, n=1500):
    """Mixed radii (log-uniform 0.05-1 and a few up to 4), touching pairs on axes and diagonals
    nudged by -2..2 ulps, coincident centres (and centres 1e-30 apart, whose d^2 underflows),
    negative coordinates, and bad spheres of every kind."""
    side = (n / world.DENSITY) ** (1 / 3) * 0.5
    out = []
    for _ in range(n):
        r = 0.05 * 20 ** rng.random() if rng.random() < 0.99 else rng.uniform(1, 4)
        out.append([f32(rng.uniform(-side, side)) for _ in range(3)] + [f32(r)])
    for _ in range(n // 10):  # touching along an axis or a diagonal, nudged
        a = rng.choice(out)
        r2 = f32(0.05 * 20 ** rng.random())
        axis = rng.randrange(4)
        if axis < 3:
            b = list(a[:3])
            b[axis] = ulps(f32(a[axis] + (a[3] + r2)), rng.randint(-2, 2))
        else:
            u = [rng.gauss(0, 1) for _ in range(3)]
            norm = math.sqrt(sum(c * c for c in u))
            b = [ulps(f32(a[c] + (a[3] + r2) * u[c] / norm), rng.randint(-2, 2)) for c in range(3)]
        out.append(b + [r2])
    for _ in range(n // 50):  # coincident centres, two to four spheres
        a = rng.choice(out)
        for _ in range(rng.randint(1, 3)):
            out.append(a[:3] + [f32(0.05 * 20 ** rng.random())])
        out.append([a[0] + 1e-30 if a[0] == 0 else a[0], a[1], a[2], a[3]])
        out.append([f32(a[0] + 1e-30), a[1], a[2], a[3]])
    bad = [[math.nan, 0.0, 0.0, 1.0], [0.0, math.inf, 0.0, 1.0], [0.0, 0.0, 0.0, 0.0], [1.0, 1.0, 1.0, -0.5],
           [2e6, 0.0, 0.0, 0.5], [0.0, 0.0, 0.0, 2e6], [0.0, -1.5e6, 0.0, 0.5], [0.0, 0.0, 0.0, 1e-46]]
    for b in bad:
        out.insert(rng.randrange(len(out) + 1), b)
    rng.shuffle(out)
    return out


def write_hex(path, spheres):
    with open(path, "w") as f:
        f.write("x,y,z,r\n")
        for s in spheres:
            f.write(",".join(v.hex() if math.isfinite(v) else repr(v) for v in s) + "\n")


def write_decimal(path, spheres, rng):
    """Decimal text with up to 17 digits: the reader must round each once, as strtof does."""
    with open(path, "w") as f:
        f.write("x,y,z,r\n")
        for s in spheres:
            f.write(",".join(f"{v:.{rng.randint(3, 17)}g}" for v in s) + "\n")


class Formatting(unittest.TestCase):
    def test_hex_a_is_cs_percent_a(self):
        libc = ctypes.CDLL(None)
        buf = ctypes.create_string_buffer(64)
        rng = random.Random(seed("hex_a"))
        values = [0.0, -0.0, 1.0, -1.0, 0.5, 3.0, 1e-45, -1e-40, 3.4e38, math.inf, -math.inf]
        values += [float(np.frombuffer(rng.getrandbits(32).to_bytes(4, "little"), np.float32)[0]) for _ in range(2000)]
        for v in values:
            if math.isnan(v):
                continue
            libc.snprintf(buf, 64, b"%a", ctypes.c_double(v))
            self.assertEqual(warp_world.hex_a(v), buf.value.decode(), v)

    def test_strtof_rounds_once(self):
        # 1 + 2^-24 + 2^-60 is just above the binary32 midpoint after 1: binary64 first would
        # round it onto the midpoint and then to even (1.0); one rounding gives 1 + 2^-23.
        self.assertEqual(warp_world.parse_f32(b"1.000000059604644775390625000000000000000867"), 1 + 2 ** -23)
        self.assertEqual(warp_world.parse_f32(b"0x1.8p+1"), 3.0)
        self.assertIsNone(warp_world.parse_f32(b"1.5x"))
        self.assertIsNone(warp_world.parse_f32(b"1_000"))


class Options(unittest.TestCase):
    def test_the_kernels_are_compiled_without_fma_contraction_or_fast_math(self):
        # On CUDA this is NVRTC's --fmad=false (and no --use_fast_math: IEEE sqrt and division,
        # no flushing of subnormals); Warp's CPU build gives the same bits either way (tried).
        opts = wp.get_module_options(warp_world)
        self.assertIs(opts["fuse_fp"], False)
        self.assertIs(opts["fast_math"], False)

    def test_the_cuda_code_has_no_fma_and_ieee_sqrt_and_division(self):
        # Warp compiles CUDA code with NVRTC, which needs no GPU: the kernels for sm_90 (an H100),
        # as PTX. With fuse_fp on, the same PTX holds fma.rn.f32 (tried: 5 of them).
        with tempfile.TemporaryDirectory() as d:
            try:
                paths = wp.compile_aot_module(warp_world, arch=90, module_dir=d, use_ptx=True)
            except Exception as e:  # noqa: BLE001 (a Warp build without NVRTC)
                self.skipTest(f"Warp cannot compile CUDA code here: {e}")
            ptx = b"".join(Path(p).read_bytes() for p in paths if str(p).endswith(".ptx"))
        self.assertTrue(b"sqrt.rn.f32" in ptx, "no correctly rounded sqrt in the PTX")  # the kernel's one sqrt
        for bad in (b"fma.", b".approx", b".ftz"):
            self.assertFalse(bad in ptx, f"{bad.decode()} in the PTX for sm_90")

    def test_a_missing_cuda_device_is_refused(self):
        if wp.get_cuda_device_count() > 0:
            self.skipTest("this machine has a CUDA device")
        err = io.StringIO()
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
            rc = warp_world.main(["--spheres", str(ROOT / "test/scenes/world_mix.csv"), "--out", "-", "--device", "cuda:0"])
        self.assertEqual(rc, 2)
        self.assertIn("--device cuda:0: no such device", err.getvalue())


class InputErrors(unittest.TestCase):
    def run_main(self, text=None, path=None):
        with tempfile.TemporaryDirectory() as d:
            if path is None:
                path = Path(d) / "s.csv"
                Path(path).write_text(text)
            err = io.StringIO()
            with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
                rc = warp_world.main(["--spheres", str(path), "--out", str(Path(d) / "c.csv")])
            return rc, err.getvalue(), (Path(d) / "c.csv").exists()

    def test_a_missing_file_is_named(self):
        rc, err, wrote = self.run_main(path="/nonexistent/spheres.csv")
        self.assertEqual(rc, 1)
        self.assertIn("/nonexistent/spheres.csv: no such file", err)
        self.assertFalse(wrote)

    def test_a_malformed_row_names_its_line(self):
        for text, want in [("x,y,z,r\n1,2,3,0.5\n\n1,abc,3,0.5\n", ":4: y: not a number: 'abc'"),
                           ("x,y,z,r\n1,2,3\n", ":2: expected 4 fields, got 3"),
                           ("x,y,z,r\n1,2,,0.5\n", ":2: z: empty field"),
                           ("x,y,z,r\n1,2,3,1e39\n", ":2: r: '1e39' overflows binary32"),
                           ("x,y,z\n1,2,3\n", ":1: expected the header 'x,y,z,r', got 'x,y,z'"),
                           ("", ":1: empty input")]:
            rc, err, wrote = self.run_main(text)
            self.assertEqual(rc, 1, text)
            self.assertIn(want, err, text)
            self.assertFalse(wrote, text)

    def test_bad_spheres_are_rows_not_errors(self):
        rc, err, _ = self.run_main("\ufeffx,y,z,r\nnan,0,0,1\n0,0,0,inf\n0,0,0,0\n")
        self.assertEqual(rc, 0, err)
        self.assertIn("3 spheres (3 bad)", err)


@unittest.skipUnless(COLLIDE.exists(), f"needs the host's collide binary at {COLLIDE} (cmake -S host -B build/host "
                     "-G Ninja -DCMAKE_BUILD_TYPE=Release -DCOLLIDE_AFU_PRESET= -DCOLLIDE_AFU_DIR= && cmake --build "
                     "build/host --target collide)")
class SameContactsAsSimd(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.work = Path(self.dir.name)

    def tearDown(self):
        self.dir.cleanup()

    def check(self, path, label, min_contacts=1, device="cpu"):
        simd, warp_out = self.work / "simd.csv", self.work / "warp.csv"
        p = subprocess.run([str(COLLIDE), "spheres", "--backend", "simd", "--in", str(path), "--out", str(simd)],
                           capture_output=True, text=True)
        self.assertEqual(p.returncode, 0, p.stderr)
        err = io.StringIO()
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
            rc = warp_world.main(["--spheres", str(path), "--out", str(warp_out), "--device", device])
        self.assertEqual(rc, 0, err.getvalue())
        want, got = simd.read_bytes(), warp_out.read_bytes()
        if got != want:
            a, b = want.decode().splitlines(), got.decode().splitlines()
            first = next((k for k in range(min(len(a), len(b))) if a[k] != b[k]), min(len(a), len(b)))
            self.fail(f"{label}: {len(b) - 1} rows from warp, {len(a) - 1} from simd; first difference at row {first}:\n"
                      f"  simd {a[first] if first < len(a) else '(end)'}\n  warp {b[first] if first < len(b) else '(end)'}")
        contacts = sum(1 for line in want.decode().splitlines()[1:] if line.split(",")[1])
        self.assertGreaterEqual(contacts, min_contacts, label)  # the world has contacts to compare
        return want.decode()

    def test_the_projects_small_worlds(self):
        self.check(ROOT / "test" / "scenes" / "world_mix.csv", "world_mix.csv")
        for kind, n in [("uniform", 3000), ("clustered", 2000), ("mixed", 2000), ("diamond", 700)]:
            path = self.work / f"{kind}.csv"
            world.write_cloud(path, world.cloud(kind, n, 1))
            self.check(path, f"{kind} {n}", min_contacts=n // 2)

    def test_random_worlds_with_touching_pairs_coincident_centres_and_mixed_radii(self):
        rng = random.Random(seed("warp_world.random_worlds"))
        for k in range(4):
            spheres = random_world(rng)
            path = self.work / f"random{k}.csv"
            (write_decimal if k % 2 else write_hex)(path, spheres, *([rng] if k % 2 else []))
            text = self.check(path, f"random world {k}", min_contacts=200)
            flags = [line.rsplit(",", 1)[1] for line in text.splitlines()[1:]]
            self.assertIn("5", flags, "a coincident pair")  # the world holds each case
            self.assertIn("8", flags, "a non-finite sphere")
            self.assertIn("32", flags, "a sphere out of range")

    def test_on_a_cuda_device_where_there_is_one(self):
        if wp.get_cuda_device_count() == 0:
            self.skipTest("no CUDA device here: the Warp backend's GPU path is not tested on this machine")
        rng = random.Random(seed("warp_world.cuda"))
        path = self.work / "cuda.csv"
        write_hex(path, random_world(rng))
        self.check(path, "random world on cuda:0", min_contacts=200, device="cuda:0")
        world.write_cloud(path, world.cloud("mixed", 3000, 1))
        self.check(path, "mixed 3000 on cuda:0", min_contacts=1000, device="cuda:0")

    def test_an_empty_world_and_one_sphere(self):
        for text in ["x,y,z,r\n", "x,y,z,r\n1,2,3,0.5\n", "x,y,z,r\n0,0,0,1\n0,0,0,1\n"]:
            path = self.work / "tiny.csv"
            path.write_text(text)
            self.check(path, repr(text), min_contacts=0)


if __name__ == "__main__":
    unittest.main()
