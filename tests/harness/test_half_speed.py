"""tools/drum/half_speed.py: a released bed built from the carried curve at its own rotation reads
as the carried bed (differences of zero where the curve is quadratic), and one metric shifted by
several of its intervals reads as different; speeds beyond the carried ones are not read."""

import sys
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools" / "drum"))
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
import half_speed  # noqa: E402


def curve(col, x):
    """A smooth (quadratic) carried curve per metric, of the study's size."""
    base = {"Hc_m": -0.105, "Hh_m": 0.05, "Hd_m": 0.04, "angle_deg": 20.0, "layer_thickness_m": 0.06,
            "surface_velocity_mps": 0.3}[col]
    return base * (1.0 + 0.02 * x - 2e-4 * x * x)


def row(rpm, turn, shift=None):
    r = {"rpm": rpm, "bed_turn_1": turn, "bed_turn_hw95_1": 0.002, "bed_turn_dof": 10.0}
    for key, col, *_ in half_speed.METRICS:
        unit = col.rsplit("_", 1)[1]
        r[col] = curve(col, rpm * turn) + (shift or {}).get(col, 0.0)
        r[f"{key}_hw95_{unit}"] = 0.002 * abs(r[col])
        r[f"{key}_dof"] = 12.0
    return r


class HalfSpeed(unittest.TestCase):
    def table(self, shift=None):
        rows = [row(7, 0.999), row(14, 0.998), row(21, 0.997), row(28, 0.99),
                row(35, 0.45, shift), row(49, 0.48, shift), row(63, 0.51, shift)]
        return {float(r["rpm"]): r for r in rows}

    def test_the_carried_curve_at_the_beds_rotation_is_found(self):
        out = half_speed.compare(self.table())
        read = [r for r in out if r["metric"]]
        self.assertEqual(sorted({r["rpm"] for r in read}), [35.0, 49.0])
        for r in read:
            self.assertAlmostEqual(r["difference"], 0.0, delta=1e-9 * max(1.0, abs(r["released"])))
            self.assertTrue(r["agree"])
        # 63 rpm turns at 32.1 rpm, past the last carried speed (27.7) by more than a tenth of 7 rpm
        self.assertEqual([r["rpm"] for r in out if not r["metric"]], [63.0])

    def test_a_shifted_metric_is_found(self):
        shift = {"Hd_m": 10 * 0.002 * 0.04}  # ten of its 95 % half-widths
        out = half_speed.compare(self.table(shift))
        failed = {(r["rpm"], r["metric"]) for r in out if r["metric"] and not r["agree"]}
        self.assertEqual(failed, {(35.0, "Hd"), (49.0, "Hd")})

    def test_the_bed_turns_term_is_its_own_half_width(self):
        # a bed turn known to +-0.002 (95 %) at 1.5 dof moves the reading by slope x rpm x 0.002
        table = self.table()
        for r in table.values():
            r["bed_turn_dof"] = 1.5
        out = [r for r in half_speed.compare(table) if r["metric"] == "angle" and r["rpm"] == 35.0][0]
        lo, hi = 7 * 0.999, 21 * 0.997  # the three carried rotations nearest 35 x 0.45: 7, 14, 21 rpm
        slope = (curve("angle_deg", hi) - curve("angle_deg", lo)) / (hi - lo)
        self.assertAlmostEqual(out["bed_turn_term"], abs(slope) * 35.0 * 0.002, delta=0.05 * abs(slope) * 35.0 * 0.002)

    def test_the_page_answers_first(self):
        out = half_speed.compare(self.table({"Hd_m": 0.001}))
        text = half_speed.page("synthetic", out)
        first = text.split("\n\n")[2]
        self.assertIn("free-surface angle", first)
        self.assertIn("They do not for the departure shoulder Hd", text)


if __name__ == "__main__":
    unittest.main()
