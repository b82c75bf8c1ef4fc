"""bench/stability and bench/scale (no collide binary needed): the scenes scale.py writes (sizes,
density, the hash-space limit), and what stability.py makes of a run's steps (the settling
window, the last steps, the worst contact).
Run with the suite: tools/pyenv -m unittest discover -s bench/tests -v"""
import sys
import unittest
from pathlib import Path

root = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(root / "scale"), str(root / "stability")]

import scale  # noqa: E402
import stability  # noqa: E402


class ScaleScenes(unittest.TestCase):
    def test_the_pile_keeps_pile_boxs_density_and_takes_sap_past_the_hash_limit(self):
        small, big = scale.pile_scene(1500), scale.pile_scene(1_000_000)
        cloud = small["bodies"]["random_cloud"]
        self.assertAlmostEqual(cloud["max"][0] - cloud["min"][0], 0.88)  # pile_box's base
        self.assertEqual(small["collision"]["space"], "hash")
        self.assertEqual(big["collision"]["space"], "sap")
        side = big["bodies"]["random_cloud"]["max"][0] - big["bodies"]["random_cloud"]["min"][0]
        self.assertAlmostEqual(side * side / 1_000_000, 0.88 * 0.88 / 1500)  # spheres per m^2 of base
        walls = [p["offset"] for p in big["effects"]["planes"][1:]]
        self.assertTrue(all(abs(w) > side / 2 for w in walls), "the walls lie outside the cloud")

    def test_the_diamond_counts_are_the_papers(self):
        self.assertEqual(scale.diamond_count(10), 670)
        self.assertEqual([scale.diamond_count(h) for h in scale.DIAMOND_HMAX], [1834, 9224, 64906, 666700])
        self.assertEqual(scale.diamond_scene(46)["collision"]["space"], "hash")
        self.assertEqual(scale.diamond_scene(100)["collision"]["space"], "sap")


class StabilitySummary(unittest.TestCase):
    def steps(self, ke, depth):
        return [{"step": str(k), "contacts": "10", "other_contacts": "1", "kinetic_j": str(e), "max_depth_m": str(d),
                 "escaped": "0"} for k, (e, d) in enumerate(zip(ke, depth))]

    def test_the_settling_window_is_left_out_of_the_energy_after_settling(self):
        n = stability.SETTLE + 100
        ke = [5.0] * stability.SETTLE + [0.01] * 99 + [0.02]
        r = stability.summarize("s", "b", self.steps(ke, [0.001] * n), 1.0)
        self.assertEqual(r["max_ke_j"], 5.0)
        self.assertEqual(r["max_ke_after_settle_j"], 0.02)
        self.assertAlmostEqual(r["mean_ke_last100_j"], 0.0101)
        self.assertEqual(r["max_depth_mm"], 1.0)

    def test_a_short_run_uses_every_step(self):
        r = stability.summarize("s", "b", self.steps([1.0, 2.0], [0.002, 0.003]), 1.0)
        self.assertEqual(r["max_ke_after_settle_j"], 2.0)
        self.assertEqual(r["max_depth_after_settle_mm"], 3.0)


if __name__ == "__main__":
    unittest.main()
