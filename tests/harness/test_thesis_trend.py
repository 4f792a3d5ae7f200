"""tools/drum/thesis_trend.py on tables with known answers: a drop called only where its 95 %
interval excludes zero, from the half-widths and dof where the table has them, else from the
batch-means standard errors; and the answer's sentence for each study."""

import math
import sys
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools" / "drum"))
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
import thesis_trend  # noqa: E402


def row(rpm, hh, hd, hc, hw=None, dof=None, se=None, batches=5):
    r = {"rpm": rpm, "batches": batches, "Hh_m": hh, "Hd_m": hd, "Hc_m": hc}
    for key in ("Hh", "Hd", "Hc"):
        if hw is not None:
            r[f"{key}_hw95_m"], r[f"{key}_dof"] = hw, dof
        r[f"{key}_se_m"] = se if se is not None else math.nan
    return r


class Trend(unittest.TestCase):
    def test_a_drop_at_28_and_a_rise_from_35(self):
        # half-widths 1 mm at 10 dof a speed: a step's Welch half-width is t(20) sqrt(2) (1 mm / t(10))
        rows = [row(21, 0.100, 0.080, -0.097, 1e-3, 10), row(28, 0.0995, 0.070, -0.099, 1e-3, 10),
                row(35, 0.110, 0.072, -0.098, 1e-3, 10), row(42, 0.120, 0.080, -0.096, 1e-3, 10)]
        found = thesis_trend.steps(rows)
        verdict, d, hw = found[("Hh", 21, 28)]
        t10, t20 = (float(thesis_trend.stats.t.ppf(0.975, n)) for n in (10, 20))
        self.assertAlmostEqual(hw, t20 * math.sqrt(2) * 1e-3 / t10, places=12)
        self.assertEqual(verdict, "no change")  # -0.5 mm against a half-width of 1.32 mm
        self.assertEqual(found[("Hd", 21, 28)][0], "drops")
        self.assertEqual(found[("Hh", 35, 42)][0], "rises")
        text = thesis_trend.answer("s", "a set", found)
        self.assertIn("a drop at 28 rpm in Hd and Hc only (21 → 28: Hh no change -0.50 ± 1.32 mm, Hd drops", text)
        self.assertIn("from 35 rpm the head rises in 1 of 1 steps (28 → 35: rises)", text)
        # every drop called: the drop appears
        rows[1] = row(28, 0.095, 0.070, -0.099, 1e-3, 10)
        self.assertIn("the drop at 28 rpm appears", thesis_trend.answer("s", "a set", thesis_trend.steps(rows)))
        rows[1] = row(28, 0.110, 0.090, -0.090, 1e-3, 10)
        self.assertIn("no drop at 28 rpm (21 → 28: Hh rises", thesis_trend.answer("s", "a set", thesis_trend.steps(rows)))

    def test_batch_means_where_the_table_has_no_half_widths(self):
        # standard errors of 0.2 mm from 5 batches: 4 dof a side, Welch at 8
        rows = [row(21, 0.100, 0.08, -0.097, se=2e-4), row(28, 0.101, 0.08, -0.097, se=2e-4)]
        verdict, d, hw = thesis_trend.steps(rows)[("Hh", 21, 28)]
        self.assertAlmostEqual(hw, float(thesis_trend.stats.t.ppf(0.975, 8)) * math.sqrt(2) * 2e-4, places=12)
        self.assertEqual(verdict, "rises")
        self.assertIn("not yet two consecutive speeds", thesis_trend.answer("s", "a set", {}))
        page = thesis_trend.page([("s", "a set", rows), ("y", "another", [])])
        self.assertIn("| Hh | 21 → 28 | drops | rises +1.00 ± 0.65 |  |", page)


if __name__ == "__main__":
    unittest.main()
