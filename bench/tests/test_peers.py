"""bench/world/peers.py without running any engine: --replot's refusal of a missing CSV, and the
plot drawn from a CSV whose rows include configs a run did not time."""
import contextlib
import csv
import io
import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "world"))

import peers  # noqa: E402


class Replot(unittest.TestCase):
    def test_a_missing_csv_is_refused_by_name_with_a_nonzero_exit(self):
        with tempfile.TemporaryDirectory() as d, contextlib.redirect_stderr(io.StringIO()) as err:
            with self.assertRaises(SystemExit) as e:
                peers.main(["--replot", "--out", d])
        self.assertNotEqual(e.exception.code, 0)
        self.assertIn(str(Path(d) / "peers.csv"), err.getvalue())
        self.assertFalse((Path(d) / "peers.png").exists(), "nothing is drawn for a missing CSV")

    def test_rows_not_run_or_not_measured_are_left_out_of_the_plot_but_it_is_drawn(self):
        rows = [{"cloud": "uniform", "spheres": n, "config": "grid, 1 thread", "total_ns": t}
                for n, t in ((1000, 57000), (10000, 767000))]
        rows += [{"cloud": "uniform", "spheres": 10000, "config": "ode hash", "total_ns": peers.NOT_RUN},
                 {"cloud": "uniform", "spheres": 10000, "config": "warp cuda:0", "total_ns": peers.NOT_MEASURED}]
        with tempfile.TemporaryDirectory() as d:
            with open(Path(d) / "peers.csv", "w", newline="") as f:
                w = csv.DictWriter(f, fieldnames=peers.ROW_KEYS, restval="")
                w.writeheader()
                w.writerows(rows)
            self.assertEqual(peers.main(["--replot", "--out", d]), 0)
            self.assertGreater((Path(d) / "peers.png").stat().st_size, 1000)


if __name__ == "__main__":
    unittest.main()
