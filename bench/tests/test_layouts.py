"""bench/layouts/pairs_layouts.py: its pairs and its verdict (no AFU needed), and, with SLOW=1,
`collide pairs` end to end through four fp32 AFUs that differ only in their record layout.
Run with the suite: tools/pyenv -m unittest discover -s bench/tests -v"""
import math
import os
import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "layouts"))

import pairs_layouts as pl  # noqa: E402


def value(text: str) -> float:
    return float.fromhex(text) if "0x" in text else float(text)


class LayoutPairs(unittest.TestCase):
    def test_the_pairs_are_seeded_and_mix_every_kind(self):
        a, b = pl.pairs(600, 7), pl.pairs(600, 7)
        self.assertEqual(a, b)
        self.assertNotEqual(a, pl.pairs(600, 8))
        good = a[:600]
        hits = misses = coincident = 0
        for row in good:
            v = [value(t) for t in row]
            d = math.dist(v[0:3], v[4:7])
            if d == 0:
                coincident += 1
            if d <= v[3] + v[7]:
                hits += 1
            else:
                misses += 1
        self.assertGreater(hits, 200)
        self.assertGreater(misses, 50)
        self.assertGreaterEqual(coincident, 100)
        # Half the rows are hex binary32 values, written exactly.
        hex_rows = [r for r in good if r[0].startswith(("0x", "-0x"))]
        self.assertEqual(len(hex_rows), 300)
        for r in hex_rows[:50]:
            self.assertEqual([pl.f32(value(t)) for t in r], [value(t) for t in r])
        # Then the bad pairs: NaN, infinity, radii <= 0, beyond the sane range.
        bad = a[600:]
        self.assertEqual(len(bad), 7)
        narrow = pl.pairs(60, 7, narrow=True)
        self.assertEqual(len(narrow), 65)
        self.assertTrue(all(abs(value(t)) <= 2000 for r in narrow[:60] for t in r))
        self.assertTrue(any("nan" in r for r in bad) and any("inf" in r for r in bad))

    def test_one_digest_per_spec_passes_and_any_other_fails(self):
        row = lambda spec, layout, digest: {"spec": spec, "layout": layout, "link": "ideal", "mode": "compact",
                                            "sha256": digest}
        same = pl.outputs_by_spec([row("fp32", "full", "aa"), row("fp32", "derived", "aa"), row("fp16", "full", "bb")])
        self.assertEqual({s: len(d) for s, d in same.items()}, {"fp32 compact": 1, "fp16 compact": 1})
        differ = pl.outputs_by_spec([row("fp32", "full", "aa"), row("fp32", "derived-masked", "ab")])
        self.assertEqual(differ["fp32 compact"], {"aa": ["full/ideal"], "ab": ["derived-masked/ideal"]})


@unittest.skipUnless(os.environ.get("SLOW") == "1",
                     "end to end (eight AFU builds, about 6 minutes cold): set SLOW=1, as `SLOW=1 tools/test` does")
class LayoutsEndToEnd(unittest.TestCase):
    def test_collide_pairs_gives_the_same_bytes_through_every_layout_and_mode(self):
        # fp16 too: its d^2 overflows inside the range, and compact mode once dropped those flags.
        with tempfile.TemporaryDirectory() as out:
            self.assertEqual(pl.main(["--specs", "fp32,fp16", "--pairs", "1500", "--out", out]), 0)
            text = (Path(out) / "README.md").read_text()
            self.assertIn("Every spec and mode gives one output", text)
            self.assertIn("- fp32: the same bytes.", text)
            self.assertIn("- fp16: the same bytes.", text)
            self.assertIn("| fp32 | derived-masked | qpi | dense |", text)


if __name__ == "__main__":
    unittest.main()
