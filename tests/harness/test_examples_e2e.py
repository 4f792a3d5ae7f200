"""The examples in inputs/examples/ end to end: each runs to its end without an ERROR or a WARNING,
and what it prints agrees with the physics (inputs/examples/README.md says what to expect and
why). Runs LIGGGHTS (env LIGGGHTS or PATH), serially; about 10 s.

two_beads.in: one collision of Table 3.1's beads at tc/5 (mu 0.5), at several start phases,
among them 0.0005: a touch just after a step, where exactRestitution loses the last step of
the oblique contact (README).
- Head-on (`-var vt 1e-6`: et stays defined, the pull of the tangential motion is nil): with
  exactCollision (the default mode) every single collision restitutes en to 1e-7, the
  precision law.md claims for head-on pairs in LIGGGHTS (tests/collide/test_exact_collision.cpp),
  and et the value the model logs at `run` (0.480793: Pournin's oscillator letting go where
  the normal force passes through zero, since et != en) to 2e-5, law.md's bound for a sticking
  pair against its law. With exactRestitution (`-var mode restitution`) at a whole tc/dt the
  correction is exact at every phase of a head-on collision (`contact_law single --en 0.56
  --et 0.46 --ratios 5`: worst 5e-10); held to 2e-6, law.md's bound for its phase average.
- Oblique (the default vn 1 m/s along the line of centres, vt 0.2 m/s across it). With
  exactCollision every start phase restitutes the continuous law's en and et. The law's values
  for this impact are those of the reference ODE (`collide case --geometry pair --tangential
  pournin --exact-collision on --vn 1 --vt 0.2`: its rigid-arm spring, tc/20000): en 0.559992
  (below the requested 0.56 by the pull vt^2/d of the tangential motion on the overlap) and et
  0.481149 (not the requested 0.46: with et != en the Coulomb cap passes through zero near the
  end of the contact while the spring holds force, docs/law.md). The tolerance, 3e-4 relative,
  is the one tests/collide/test_exact_collision.cpp (FiniteFrictionWithEtOtherThanEn) holds every
  start phase of this very impact to; 64 phases (k + 0.5)/64 gave en 1.1e-5 to 4.3e-5 below the
  law and et 1e-5 below it. With exactRestitution (tangential history: the README's setting for
  flows) the pull, which the correction does not follow, offsets en by about
  (vt^2/d) / (omega vn) = vt^2 tc / (pi d vn) = 4.2e-4 relative (64 phases: -4.4e-4 to -1e-5);
  the tolerance is 1e-3, twice that. Its et is LIGGGHTS' history model's, for which no
  reference law exists here: the 64 phases gave 0.4753-0.4779, and the test holds it to that
  band widened by 0.002 (a regression bound, not a law's value).

hopper.in: 459 beads settle in a slot hopper with the gate shut, then flow out into a bin.
- every bead kept (`thermo_modify lost error` also stops a run that loses one), all of them in
  the hopper (below the lattice's lowest layer, z < 0.035 m) and settled (kinetic energy below
  1 % of its peak during the fall; 0.04 % measured) before the gate opens, all of them through
  the outlet at the end;
- the discharge rate 0.05-0.15 s after opening within a factor 2 of Beverloo's correlation in
  its slot form, W = C rho_b sqrt(g) (L - k d) (b - k d)^(3/2) with C 1, k 1.5, bulk density
  0.6 rho, b = 18 mm (the outlet across the converging walls), L = 12 mm (between the parallel
  walls): 1.6e3 beads/s (C and k are empirical, the outlet only 4 d long, the bulk density a
  guess: hence the factor);
- the VTK snapshots: one every 0.01 s, the last holding every bead.
"""

import math
import re
import shutil
import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
import harness  # noqa: E402

TWO_BEADS = "inputs/examples/two_beads.in"
HOPPER = "inputs/examples/hopper.in"
RESULT_TWO_BEADS = re.compile(r"^RESULT en (\S+) et (\S+) \(mode (\w+), phase (\S+), gap (\S+) m\)$", re.M)
RESULT_HOPPER = re.compile(r"^RESULT hopper: (\d+) of (\d+) beads kept, (\d+) left through the outlet in (\S+) s "
                           r"\((\S+) beads/s 0\.05-0\.15 s after opening\), bed top at z = (\S+) m, ke (\S+) J$", re.M)
SETTLED = re.compile(r"^hopper: (\d+) beads settled, bed top at z = (\S+) m, ke (\S+) J; opening the gate$", re.M)


def clean(test, log):
    """The run printed no ERROR and no WARNING."""
    bad = [line for line in log.text.splitlines() if "ERROR" in line or "WARNING" in line]
    test.assertEqual(bad, [], f"{log.path}")


class TwoBeads(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = Path(tempfile.mkdtemp(prefix="examples_e2e_"))

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def collide(self, **variables):
        """(en, et) printed by one run of two_beads.in with these -var settings."""
        name = "_".join(f"{k}{v}" for k, v in variables.items()) or "default"
        log = harness.liggghts(TWO_BEADS, variables, log=self.tmp / f"two_beads_{name}.log")
        clean(self, log)
        m = RESULT_TWO_BEADS.search(log.text)
        self.assertIsNotNone(m, f"no RESULT line in {log.path}")
        self.assertGreater(float(m.group(5)), 0.0, "the beads are apart again at the end")
        return float(m.group(1)), float(m.group(2))

    def test_head_on_every_single_collision_restitutes_en(self):
        for phase in (0.5, 0.0005):
            with self.subTest(mode="collision", phase=phase):
                en, et = self.collide(vt=1e-6, phase=phase)
                self.assertLess(abs(en / 0.56 - 1), 1e-7, f"en {en}")
                self.assertLess(abs(et / 0.480793 - 1), 2e-5, f"et {et}")
            with self.subTest(mode="restitution", phase=phase):
                en, et = self.collide(mode="restitution", vt=1e-6, phase=phase)
                self.assertLess(abs(en / 0.56 - 1), 2e-6, f"en {en}")

    def test_exact_collision_restitutes_the_laws_en_and_et_at_every_start_phase(self):
        law_en, law_et, tolerance = 0.559992, 0.481149, 3e-4
        for variables in ({}, {"phase": 0.0005}, {"phase": 0.9}):  # {}: as the README runs it
            with self.subTest(**variables):
                en, et = self.collide(**variables)
                self.assertLess(abs(en / law_en - 1), tolerance, f"en {en}")
                self.assertLess(abs(et / law_et - 1), tolerance, f"et {et}")

    def test_exact_restitution_restitutes_en_within_the_pull_of_the_tangential_motion(self):
        for phase in (0.5, 0.1, 0.9):
            with self.subTest(phase=phase):
                en, et = self.collide(mode="restitution", phase=phase)
                self.assertLess(abs(en / 0.56 - 1), 1e-3, f"en {en}")
                self.assertGreater(et, 0.4753 - 0.002, f"et {et}")
                self.assertLess(et, 0.4779 + 0.002, f"et {et}")


class Hopper(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.out = Path(tempfile.mkdtemp(prefix="examples_e2e_hopper_"))
        cls.log = harness.liggghts(HOPPER, {"out": cls.out}, log=cls.out / "hopper.log")
        cls.settled = SETTLED.search(cls.log.text)
        cls.result = RESULT_HOPPER.search(cls.log.text)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.out, ignore_errors=True)

    def setUp(self):
        self.assertIsNotNone(self.settled, f"no settling line in {self.log.path}")
        self.assertIsNotNone(self.result, f"no RESULT line in {self.log.path}")

    def test_runs_to_its_end_without_errors_or_warnings(self):
        clean(self, self.log)

    def test_every_bead_settles_in_the_hopper_and_leaves_it(self):
        kept, created, out = (int(self.result.group(k)) for k in (1, 2, 3))
        self.assertEqual(created, 17 * 3 * 9)  # the lattice: 17 x 3 beads, 9 layers
        self.assertEqual(kept, created)
        self.assertLess(float(self.settled.group(2)), 0.035, "settled below the lattice's lowest layer")
        series = harness.read_csv(self.out / "hopper_series.csv")
        fall = max(row["ke"] for row in series if row["time"] <= 0.15)
        self.assertLess(float(self.settled.group(3)), 1e-2 * fall, "settled before the gate opens")
        self.assertEqual(out, created, "every bead through the outlet")
        self.assertLess(float(self.result.group(6)), 0.0, "the highest bead below the outlet")

    def test_discharge_rate_within_a_factor_2_of_beverloo(self):
        g, rho, d = 9.81, 2500.0, 0.003
        bead = rho * math.pi / 6 * d ** 3
        beverloo = 1.0 * 0.6 * rho * math.sqrt(g) * (0.012 - 1.5 * d) * (0.018 - 1.5 * d) ** 1.5 / bead
        rate = float(self.result.group(5))
        self.assertGreater(rate, beverloo / 2, f"{rate} beads/s, Beverloo {beverloo:.0f}")
        self.assertLess(rate, beverloo * 2, f"{rate} beads/s, Beverloo {beverloo:.0f}")

    def test_vtk_snapshots_for_paraview(self):
        snapshots = harness.snapshots(self.out / "hopper")
        self.assertEqual(len(snapshots), 51, "one every 0.01 s of 0.5 s, and the start")
        head = snapshots[-1][1].read_bytes()[:600].decode("ascii", errors="replace")
        self.assertIn('NumberOfPoints="459"', head)


if __name__ == "__main__":
    unittest.main()
