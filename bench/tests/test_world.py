"""bench/world/world.py's clouds (no collide binary needed): the sizes asked for, every value
a binary32 value written exactly, about one contact a sphere in the uniform cloud.
Run with the suite: tools/pyenv -m unittest discover -s bench/tests -v"""
import itertools
import math
import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "world"))

import world  # noqa: E402


class WorldClouds(unittest.TestCase):
    def test_every_cloud_has_the_size_and_binary32_values(self):
        for kind in world.CLOUDS:
            spheres = world.cloud(kind, 500, 1)
            self.assertEqual(len(spheres), 500, kind)
            for s in spheres[:50]:
                self.assertEqual([world.f32(v) for v in s], s, kind)
                self.assertGreater(s[3], 0, kind)

    def test_the_uniform_cloud_has_about_one_contact_a_sphere(self):
        spheres = world.cloud("uniform", 1500, 2)
        contacts = sum(1 for a, b in itertools.combinations(spheres, 2)
                       if math.dist(a[:3], b[:3]) <= a[3] + b[3])
        self.assertGreater(contacts, 0.6 * 1500)  # the walls cost some
        self.assertLess(contacts, 1.2 * 1500)

    def test_the_csv_holds_exact_hex_floats(self):
        with tempfile.TemporaryDirectory() as d:
            p = Path(d) / "s.csv"
            spheres = world.cloud("mixed", 20, 3)
            world.write_cloud(p, spheres)
            lines = p.read_text().splitlines()
            self.assertEqual(lines[0], "x,y,z,r")
            self.assertEqual([[float.fromhex(v) for v in l.split(",")] for l in lines[1:]], spheres)


if __name__ == "__main__":
    unittest.main()
