"""The steady-state study driver end to end on a tiny drum (tools/drum/steady.py): a run
interrupted in the middle and resumed gives the same averages as an uninterrupted one.
Runs LIGGGHTS (LIGGGHTS, DRUM_METRICS from the environment, as CTest sets them)."""

import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import unittest
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
STEADY = REPO / "tools" / "drum" / "steady.py"
# 2,058 beads (6 mm slab, 5 % fill) from the grid: three restart-chained segments, then the cap
SETTINGS = ["--speeds", "21", "--period", "0.006", "--var", "fill", "0.05", "--var", "dumpdt", "0.005",
            "--var", "dt", "2e-5", "--segment", "0.02", "--settle", "0.02", "--cap", "0.08"]


def command(name, docs):
    return [sys.executable, str(STEADY), "--name", name, "--docs", str(docs), *SETTINGS]


class InterruptedStudy(unittest.TestCase):
    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp(prefix="steady_e2e_"))
        self.names = [f"e2e_steady_{os.getpid()}_{k}" for k in ("whole", "cut")]

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)
        for n in self.names:
            shutil.rmtree(REPO / "post" / n, ignore_errors=True)

    def test_interrupted_and_resumed_gives_the_same_averages(self):
        whole, cut = self.names
        subprocess.run(command(whole, self.tmp / "whole"), cwd=REPO, check=True, capture_output=True)

        # the same study, killed (with its LIGGGHTS) once the first segment is recorded
        progress = REPO / "post" / cut / "21rpm_progress.json"
        p = subprocess.Popen(command(cut, self.tmp / "cut"), cwd=REPO, start_new_session=True,
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        deadline = time.monotonic() + 300
        while time.monotonic() < deadline and p.poll() is None:
            if progress.exists() and json.loads(progress.read_text())["segments"] >= 1:
                break
            time.sleep(0.2)
        self.assertIsNone(p.poll(), "the study ended before it could be interrupted")
        os.killpg(p.pid, signal.SIGKILL)  # at once: a later segment may already be under way, or not
        p.wait()
        recorded = json.loads(progress.read_text())["segments"]
        self.assertLess(recorded, 3, "killed after the last segment: nothing left to resume")
        resumed = subprocess.run(command(cut, self.tmp / "cut"), cwd=REPO, capture_output=True, text=True)
        said = resumed.stdout + resumed.stderr
        self.assertEqual(resumed.returncode, 0, said[-3000:])
        # it went on from the last recorded segment, not from the grid again
        self.assertIn(f"segment {recorded + 1}:", said)
        for k in range(1, recorded + 1):
            self.assertNotIn(f"segment {k}:", said)

        a = (self.tmp / "whole" / whole / "21rpm" / "series_average.csv").read_text().splitlines()
        b = (self.tmp / "cut" / cut / "21rpm" / "series_average.csv").read_text().splitlines()
        self.assertEqual(a[0], b[0])
        for x, y in zip(a[1].split(","), b[1].split(",")):
            if x in ("nan", "") or y in ("nan", ""):
                self.assertEqual(x, y)
            else:
                self.assertAlmostEqual(float(x), float(y), delta=1e-9 * max(1.0, abs(float(x))), msg=a[0])
        # the series too, snapshot by snapshot
        self.assertEqual((self.tmp / "whole" / whole / "21rpm" / "series_metrics.csv").read_text(),
                         (self.tmp / "cut" / cut / "21rpm" / "series_metrics.csv").read_text())


if __name__ == "__main__":
    unittest.main()
