"""The README's results block is what tools/readme_results.py makes of the committed results, and
the generator notices a block that is not (a number edited by hand)."""

import shutil
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
SCRIPT = REPO / "tools" / "readme_results.py"


def check(readme):
    return subprocess.run([sys.executable, str(SCRIPT), "--check", "--readme", str(readme)], capture_output=True,
                          text=True)


class ReadmeResults(unittest.TestCase):
    def test_the_block_is_current(self):
        r = check(REPO / "README.md")
        self.assertEqual(r.returncode, 0, r.stderr)

    def test_a_number_edited_by_hand_is_noticed(self):
        with tempfile.TemporaryDirectory() as d:
            copy = Path(d) / "README.md"
            shutil.copy(REPO / "README.md", copy)
            text = copy.read_text()
            begin = text.index("<!-- results:")
            edited = text[:begin] + text[begin:].replace("31.5", "30.5", 1)
            self.assertNotEqual(edited, text)
            copy.write_text(edited)
            r = check(copy)
            self.assertEqual(r.returncode, 1)
            self.assertIn("not current", r.stderr)


class TimestepParagraph(unittest.TestCase):
    """The drum-timestep sentence picks, per law, the coarsest step whose Hc and angle both agree
    with tc/81, and says so where none does and while the reference runs."""

    def rows(self, law, ratio, state, agree, cost, other_agree=True):
        metrics = [("Hc_m", agree[0]), ("angle_deg", agree[1]), ("Hd_m", other_agree), ("bed_turn_1", True)]
        return [{"rpm": 21, "law": law, "tc_over_dt": ratio, "state": state, "metric": m,
                 "difference": "" if law == "plain" and ratio > 80 else 1e-5, "difference_hw95": 2e-5, "agree": ok,
                 "power": 0.9, "wall_s_per_simulated_s": cost, "window_s": 7.4} for m, ok in metrics]

    def paragraph(self, table):
        """The README's sentence for this table, whitespace folded."""
        sys.path.insert(0, str(REPO / "tools"))
        import readme_results
        with tempfile.TemporaryDirectory() as d:
            path = Path(d) / "t.csv"
            readme_results.harness.write_csv(path, table)
            return " ".join(readme_results.timestep_para(path).split())

    def test_coarsest_indistinguishable_step_per_law(self):
        table = (self.rows("plain", 81.3, "running", (True, True), 5000.0) +
                 self.rows("plain", 40, "done", (True, True), 2500.0) +
                 self.rows("plain", 10, "done", (True, True), 1000.0, other_agree=False) +
                 self.rows("plain", 20, "done", (False, True), 1600.0) +
                 self.rows("exactRestitution", 5, "done", (True, False), 500.0))
        text = self.paragraph(table)
        # tc/10 agrees on Hc and the angle (another metric's difference does not disqualify it);
        # tc/20 does not, which does not matter once a coarser step does
        self.assertIn("indistinguishable from tc/81 in Hc and the angle: nominal tc/10, at 0.2 of its wall time;"
                      " `exactRestitution`: none so far (run: tc/5)", text)
        self.assertIn("| nominal, tc/10 | +0.01 ± 0.02 | +0.00 ± 0.00 | 1 of 2 | 0.2 |", text)
        self.assertIn("Provisional: tc/81 is still running (7.4 s", text)
        import readme_results
        self.assertIsNone(readme_results.timestep_para(REPO / "no such results" / "missing.csv"))

    def test_a_reference_at_its_cap_states_its_half_widths(self):
        table = (self.rows("plain", 81.3, "capped", (True, True), 5000.0) +
                 self.rows("plain", 20, "done", (True, True), 1600.0))
        for r in table:
            r["hw95"] = {"Hc_m": 3.7e-5, "angle_deg": 0.06}.get(r["metric"], 1.0)
        text = self.paragraph(table)
        self.assertIn("tc/81 ran to its cap (7.4 s averaged, half-widths 0.037 mm and 0.060° where the 80 % power "
                      "asks 0.054)", text)
        self.assertNotIn("Provisional", text)


if __name__ == "__main__":
    unittest.main()
