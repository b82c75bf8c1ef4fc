"""Named sweeps: which AFU configurations, scenes and links each one runs.

A configuration is what the generator builds (SCPU count + SCPU spec, ScpuConfig.parse
syntax, and a record layout or the generator's default); a scene is a diamond (hMax, dSph 0)
simulated for a number of steps; a link is one of the host's link presets (`collide info
--links`). Every (configuration, scene, link) is one CSV row.
"""
import csv
from dataclasses import asdict, dataclass, field
from pathlib import Path
import re

from . import isoarea


@dataclass(frozen=True)
class Config:
    scpus: int
    spec: str  # ScpuConfig.parse: preset[:key=value]*
    records: str = ""  # full | derived | full-masked | derived-masked; "" = the generator's default
    ram: str = ""      # sphere table: banked | banked:B; "" = replicated (a copy per SCPU)

    @property
    def id(self) -> str:
        return (f"n{self.scpus}_" + re.sub(r"[^A-Za-z0-9-]+", "_", self.spec) + (f"_{self.records}" if self.records else "")
                + (f"_{re.sub(r'[^A-Za-z0-9]+', '', self.ram)}" if self.ram else ""))

    def generator_args(self) -> str:
        # A sweep studies the design space: a point beyond the paper's part is built and its
        # manifest says so (device.fits), rather than refused.
        return (f"--scpus {self.scpus} --scpu {self.spec}" + (f" --records {self.records}" if self.records else "")
                + (f" --ram-ports {self.ram}" if self.ram else "") + " --allow-overfit")


@dataclass(frozen=True)
class Scene:
    hmax: int
    steps: int = 1

    @property
    def id(self) -> str:
        return f"diamond_h{self.hmax}_s{self.steps}"


@dataclass(frozen=True)
class Sweep:
    name: str
    about: str
    configs: tuple
    scenes: tuple
    links: tuple = ("qpi", "ideal")
    area: bool = True          # Yosys area of each configuration's SCPU
    puc_area: bool = True      # ... and of its PUC (the AFU's area is then PUC + N x SCPU)
    timing: bool = False       # the timing proxy of each configuration's blocks, and its links again at
                               # the clock the cells allow (link "<preset>@cells"); with the area
    accuracy: bool = False     # the golden model's error against double, per SCPU spec
    drift_steps: int = 0       # > 0: diamond hMax 10 drift from ODE (double) after this many steps
    cpu_repeat: int = 20       # ODE / simd timings: fastest of this many a step

    def to_dict(self) -> dict:
        return asdict(self)

    @staticmethod
    def from_dict(d: dict) -> "Sweep":
        """The inverse of to_dict: how a Slurm task learns the sweep it belongs to."""
        return Sweep(**(d | {"configs": tuple(Config(**c) for c in d["configs"]),
                             "scenes": tuple(Scene(**s) for s in d["scenes"]), "links": tuple(d["links"])}))


SCPU_COUNTS = (1, 2, 4, 8, 16, 32)

# Arithmetic configurations at 16 SCPUs: formats, algorithms and Newton-Raphson settings.
ARITH_SPECS = (
    "fp32",                            # correctly rounded sqrt then reciprocal (digit recurrence)
    "fp32-rsqrt-dr",                   # one correctly rounded rsqrt instead
    "fp32-nr",                         # Newton-Raphson, 8-bit table, 2 iterations (faithful)
    "fp32:sqrt=nr8x1:recip=nr8x1",     # Newton-Raphson, one iteration (cheaper, less accurate)
    "fp32-robust",                     # power-of-two scaling: no overflow/underflow of d^2
    "fp64", "fp24", "fp16", "bf16",
    "fp16-robust",
)

# The formats and fp32's Newton-Raphson roots with every operator as deep as 200 MHz needs
# (ScpuConfig.atClock; `fp32-200` is the default AFU's SCPU, fp32:mhz=200 by its preset name).
# fp64 is not here: its carry chains (the 57-bit add, the 54-bit rounding increment, the
# product's 106-bit tile sums) are longer than a 200 MHz period of Cyclone V cells, so atClock
# refuses 200 for it (docs/timing.md, "What is left").
ARITH_200_SPECS = ("fp32-200", "fp32-nr:mhz=200", "fp16:mhz=200", "bf16:mhz=200")

# Link formats x record layouts at 16 SCPUs: what the bytes on the link cost, with indexed
# records (the masked sweep sets masked ones beside derived). Its results were measured when
# derived was the generator's default, under the config ids n16_<spec> (now n16_<spec>_derived).
LINK_CONFIGS = tuple(Config(16, spec, rec) for spec, rec in (
    ("fp32", "full"), ("fp32", "derived"),
    ("fp16", "full"), ("fp16", "derived"), ("bf16", "derived"),
    ("fp24", "derived"),
    ("fp64", "full"), ("fp64", "derived"),
))
LINK_PRESETS = ("ideal", "qpi", "harp2", "pac", "cxl")

# Indexed against masked records where masking shortens a slot enough to gain lines:
# binary32 derived 12 -> 9 bytes (5 -> 7 a line), binary16 derived 8 -> 5 (8 -> 12). Named
# explicitly, so the rows keep their meaning whatever the generator's default.
MASKED_CONFIGS = tuple(Config(16, spec, rec) for spec in ("fp32", "fp16") for rec in ("derived", "derived-masked"))

# The dispatcher hands out at most 16 pairs a cycle (one pair line), so an AFU with more SCPUs
# runs in the 16-SCPU time to the cycle (the scpus sweep: 16 and 32 are identical).
LANES = 16


def built_count(fit: int) -> int:
    """The SCPU count one would build when `fit` fit: the largest divisor of the 16 pairs of a
    pair line not above it. A pair line is dispatched in groups of N, so N = 15 takes two
    groups a line (15 + 1) and is no faster than 8 (the isoarea sweep measured it slower)."""
    return max(d for d in (1, 2, 4, 8, 16) if d <= max(1, min(fit, LANES)))


def isoarea_configs(results: Path):
    """One configuration per arithmetic and calibration at the SCPU count that fits the chip
    (isoarea.py), capped at LANES, with derived records (what its results were measured with:
    the default then); empty until the arith and scpus sweeps have results."""
    def rows(name):
        p = results / name / f"{name}.csv"
        return list(csv.DictReader(open(p, newline=""))) if p.exists() else []
    fit = isoarea.fits(rows("arith"), rows("scpus")) if rows("arith") and rows("scpus") else {}
    return tuple(dict.fromkeys(Config(built_count(n), spec, "derived") for (spec, _), (n, _) in sorted(fit.items())
                               if spec in ISOAREA_SPECS))


# The formats, and the two other root algorithms / distance methods of fp32.
ISOAREA_SPECS = ("fp32", "fp32-nr", "fp32-robust", "fp24", "fp16", "bf16", "fp64")


SWEEPS = {s.name: s for s in (
    Sweep("paper", "the paper's Figures 5-7: 16 fp32 SCPUs with the paper's full records, diamond hMax 1..10, "
          "HARP v1 and ideal links",
          configs=(Config(16, "fp32", "full"),), scenes=tuple(Scene(h) for h in range(1, 11))),
    Sweep("scpus", "SCPU count 1..32 (fp32), diamond hMax 10",
          configs=tuple(Config(n, "fp32") for n in SCPU_COUNTS), scenes=(Scene(10),)),
    Sweep("arith", "what accuracy costs: formats and algorithms at 16 SCPUs, diamond hMax 10",
          configs=tuple(Config(16, s) for s in ARITH_SPECS), scenes=(Scene(10),),
          accuracy=True, drift_steps=6, puc_area=False, timing=True),  # the PUC barely changes with the arithmetic
    Sweep("arith200", "what accuracy costs at 200 MHz: each format's SCPUs pipelined for the clock, 16 SCPUs, "
          "diamond hMax 10",
          configs=tuple(Config(16, s) for s in ARITH_200_SPECS), scenes=(Scene(10),),
          accuracy=True, drift_steps=6, puc_area=False, timing=True),
    Sweep("links", "what the link's bytes cost: formats x record layouts x link presets, diamond hMax 10 and 13",
          configs=LINK_CONFIGS, scenes=(Scene(10), Scene(13)), links=LINK_PRESETS, area=False, accuracy=True,
          cpu_repeat=5),
    Sweep("masked", "indexed against masked contact records (fp32, fp16 derived), diamond hMax 10 and 13, every link preset",
          configs=MASKED_CONFIGS, scenes=(Scene(10), Scene(13)), links=LINK_PRESETS, area=False, cpu_repeat=3),
    Sweep("isoarea", "what accuracy costs in time at a fixed chip (Stratix V 5SGXEA7): each arithmetic at the "
          "SCPU count that fits, diamond hMax 10, every link preset",
          configs=isoarea_configs(Path(__file__).resolve().parents[1] / "results"), scenes=(Scene(10),),
          links=LINK_PRESETS, area=False, cpu_repeat=3),
    Sweep("banked", "the sphere table in banks (one copy, two read ports a bank) against a copy per SCPU: "
          "fp32 at 4, 8 and 16 SCPUs, diamond hMax 10 and 13, HARP v1 and ideal links",
          configs=tuple(Config(n, "fp32", "", ram) for n in (4, 8, 16) for ram in ("", "banked")),
          scenes=(Scene(10), Scene(13)), cpu_repeat=3),
    Sweep("smoke", "a quick check of the tool itself: 2 fp32 SCPUs, diamond hMax 2, ideal link",
          configs=(Config(2, "fp32"),), scenes=(Scene(2),), links=("ideal",), area=False,
          accuracy=False, drift_steps=3, cpu_repeat=3),
)}
