"""The steady-state study driver end to end on a tiny drum (tools/drum/steady.py): a run
interrupted in the middle and resumed gives the same averages as an uninterrupted one, both on
the same machine (from its segments in post/) and on a fresh clone (from the checkpoint in docs/).
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


def command(name, docs, *extra, settings=SETTINGS):
    return [sys.executable, str(STEADY), "--name", name, "--docs", str(docs), *settings, *extra]


def kill_after_first_segment(cmd, recorded_file):
    """Starts the study and kills it (with its LIGGGHTS) at once when `recorded_file` says a
    segment is recorded: a later segment may already be under way, or not. Returns what was
    recorded."""
    p = subprocess.Popen(cmd, cwd=REPO, start_new_session=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + 300
    while time.monotonic() < deadline and p.poll() is None:
        try:
            if json.loads(recorded_file.read_text())["segments"] >= 1:
                break
        except (OSError, ValueError):
            pass  # not there yet, or being written
        time.sleep(0.2)
    assert p.poll() is None, "the study ended before it could be interrupted"
    os.killpg(p.pid, signal.SIGKILL)
    p.wait()
    return json.loads(recorded_file.read_text())["segments"]


class Studies:
    """A test class's scratch docs/ (self.tmp) and its studies' names (one per KINDS), whose post/
    folders are removed afterwards."""
    PREFIX, KINDS = "", ()

    @classmethod
    def setUpClass(cls):
        cls.tmp = Path(tempfile.mkdtemp(prefix=f"{cls.PREFIX}_"))
        cls.names = [f"{cls.PREFIX}_{os.getpid()}_{k}" for k in cls.KINDS]

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)
        for n in cls.names:
            shutil.rmtree(REPO / "post" / n, ignore_errors=True)


class InterruptedStudy(Studies, unittest.TestCase):
    PREFIX, KINDS = "e2e_steady", ("whole", "cut", "clone")

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        subprocess.run(command(cls.names[0], cls.tmp / "whole"), cwd=REPO, check=True, capture_output=True)

    def test_interrupted_and_resumed_gives_the_same_averages(self):
        cut = self.names[1]
        recorded = kill_after_first_segment(command(cut, self.tmp / "cut"), REPO / "post" / cut / "21rpm_progress.json")
        self.assertLess(recorded, 3, "killed after the last segment: nothing left to resume")
        # --checkpoint-now puts the last recorded segment into docs/ (and runs nothing)
        subprocess.run(command(cut, self.tmp / "cut", "--checkpoint-now"), cwd=REPO, check=True, capture_output=True)
        part = self.tmp / "cut" / cut / "21rpm" / "partial"
        self.assertEqual(json.loads((part / "progress.json").read_text())["segments"], recorded)
        self.resume(cut, self.tmp / "cut", recorded)
        self.assertFalse(part.exists(), "a finished speed leaves no checkpoint behind")
        self.assertSameResults(cut)

    def test_resumed_on_a_fresh_clone_from_the_checkpoint(self):
        clone = self.names[2]
        docs = self.tmp / "clone"
        part = docs / clone / "21rpm" / "partial"
        # checkpoint after every segment; killed once one is checkpointed
        recorded = kill_after_first_segment(command(clone, docs, "--checkpoint-minutes", "0"), part / "progress.json")
        self.assertLess(recorded, 3, "killed after the last segment: nothing left to resume")
        self.assertEqual(len(list(part.glob("state_seg*.restart.gz"))), 1)
        self.assertTrue((part / "metrics_cache.csv").exists())
        shutil.rmtree(REPO / "post" / clone)  # a fresh clone has no post/: no segments, no snapshots
        self.assertIn("resuming from the checkpoint", self.resume(clone, docs, recorded))
        self.assertFalse(part.exists(), "a finished speed leaves no checkpoint behind")
        self.assertSameResults(clone)

    def test_zz_a_verdict_reached_before_an_interruption_stands(self):
        # the finished study with its results gone, as if killed after its last segment's verdict
        # and before they were written: the rerun writes them without running another segment
        whole = self.names[0]
        out = self.tmp / "whole" / whole / "21rpm"
        before = (out / "series_average.csv").read_text()
        (out / "run.json").unlink()
        (self.tmp / "whole" / f"{whole}.csv").unlink()
        rerun = subprocess.run(command(whole, self.tmp / "whole"), cwd=REPO, capture_output=True, text=True)
        said = rerun.stdout + rerun.stderr
        self.assertEqual(rerun.returncode, 0, said[-3000:])
        self.assertNotIn("segment", said)
        self.assertTrue((out / "run.json").exists() and (self.tmp / "whole" / f"{whole}.csv").exists())
        self.assertEqual((out / "series_average.csv").read_text(), before)

    def resume(self, name, docs, recorded):
        """Reruns the study; it must go on from the last recorded segment, not from the grid
        again. Returns what it said."""
        resumed = subprocess.run(command(name, docs), cwd=REPO, capture_output=True, text=True)
        said = resumed.stdout + resumed.stderr
        self.assertEqual(resumed.returncode, 0, said[-3000:])
        self.assertIn(f"segment {recorded + 1}:", said)
        for k in range(1, recorded + 1):
            self.assertNotIn(f"segment {k}:", said)
        return said

    def assertSameResults(self, name):
        whole = self.names[0]
        a = (self.tmp / "whole" / whole / "21rpm" / "series_average.csv").read_text().splitlines()
        b = (self.tmp / name.rsplit("_", 1)[1] / name / "21rpm" / "series_average.csv").read_text().splitlines()
        self.assertEqual(a[0], b[0])
        for x, y in zip(a[1].split(","), b[1].split(",")):
            if x in ("nan", "") or y in ("nan", ""):
                self.assertEqual(x, y)
            else:
                self.assertAlmostEqual(float(x), float(y), delta=1e-9 * max(1.0, abs(float(x))), msg=a[0])
        # each segment's loop kept, the resumed run's too (those before the interruption from its
        # progress): as many as segments, of the same lengths as the whole run's
        runs = [json.loads((folder / "21rpm" / "run.json").read_text())
                for folder in (self.tmp / "whole" / whole, self.tmp / name.rsplit("_", 1)[1] / name)]
        for run in runs:
            self.assertEqual(len(run["loops"]), run["segments"])
            self.assertTrue(all(loop["loop_s"] > 0 and loop["neighbor_builds"] >= 0 for loop in run["loops"]))
        self.assertEqual([loop["steps"] for loop in runs[0]["loops"]], [loop["steps"] for loop in runs[1]["loops"]])
        # the series too, snapshot by snapshot
        self.assertEqual((self.tmp / "whole" / whole / "21rpm" / "series_metrics.csv").read_text(),
                         (self.tmp / name.rsplit("_", 1)[1] / name / "21rpm" / "series_metrics.csv").read_text())


# two chained speeds, each capped after three segments: 28 rpm starts from 21 rpm's end state
CHAIN = ["--speeds", "21,28", "--period", "0.006", "--var", "fill", "0.05", "--var", "dumpdt", "0.005",
         "--var", "dt", "2e-5", "--segment", "0.02", "--settle", "0.02", "--cap", "0.06"]


class InterruptedChain(Studies, unittest.TestCase):
    """A chain interrupted in its second speed and resumed: the finished first speed is taken from
    docs/ (not run again, not read from post/), the second goes on from its last recorded segment,
    and both speeds' series and averages equal an uninterrupted chain's."""

    PREFIX, KINDS = "e2e_chain", ("whole", "cut")

    def test_a_chain_resumed_in_its_second_speed(self):
        whole, cut = self.names
        subprocess.run(command(whole, self.tmp / "whole", settings=CHAIN), cwd=REPO, check=True, capture_output=True)
        recorded = kill_after_first_segment(command(cut, self.tmp / "cut", settings=CHAIN),
                                            REPO / "post" / cut / "28rpm_progress.json")
        self.assertLess(recorded, 3, "killed after 28 rpm's last segment: nothing left to resume")
        self.assertTrue((self.tmp / "cut" / cut / "21rpm" / "state.restart.gz").exists())
        for f in (REPO / "post" / cut).glob("21rpm*"):  # 21 rpm must come from docs/ now
            f.unlink()
        resumed = subprocess.run(command(cut, self.tmp / "cut", settings=CHAIN), cwd=REPO, capture_output=True, text=True)
        said = resumed.stdout + resumed.stderr
        self.assertEqual(resumed.returncode, 0, said[-3000:])
        self.assertIn("plan: 21 rpm: committed", said)
        self.assertNotIn("21 rpm, segment", said)
        self.assertIn(f"28 rpm, segment {recorded + 1}:", said)
        for k in range(1, recorded + 1):
            self.assertNotIn(f"28 rpm, segment {k}:", said)
        for rpm in (21, 28):
            for f in ("series_metrics.csv", "series_average.csv"):
                self.assertEqual((self.tmp / "whole" / whole / f"{rpm}rpm" / f).read_text(),
                                 (self.tmp / "cut" / cut / f"{rpm}rpm" / f).read_text(), f"{rpm} rpm {f}")
        table = [(self.tmp / d / f"{n}.csv").read_text().splitlines() for d, n in (("whole", whole), ("cut", cut))]
        self.assertEqual(len(table[0]), 3)  # a header and a row per speed
        self.assertEqual(len(table[1]), 3)



class ExtendedChain(Studies, unittest.TestCase):
    """--extend: a committed chain (21 rpm capped after 2 segments, 28 rpm after 3) given a later
    cap runs on from each speed's committed end state, not from the grid; 21 rpm's series then
    equals that of a run capped there in the first place, and 28 rpm, started from 21 rpm's
    earlier end state, is extended too, not redone. A changed stop rule that asks for nothing
    more rewrites the records only."""

    PREFIX, KINDS = "e2e_extend", ("whole", "ext")

    def run_study(self, name, settings, *extra):
        r = subprocess.run(command(name, self.tmp, *extra, settings=settings), cwd=REPO, capture_output=True, text=True)
        said = r.stdout + r.stderr
        self.assertEqual(r.returncode, 0, said[-3000:])
        return said

    def test_an_extended_chain_runs_on_from_its_end_states(self):
        whole, ext = self.names
        longer = [x if x != "0.06" else "0.08" for x in CHAIN]  # --cap 0.08
        self.run_study(whole, ["--speeds", "21", *longer[2:]])
        self.run_study(ext, CHAIN)
        docs = self.tmp / ext
        before = {rpm: json.loads((docs / f"{rpm}rpm" / "run.json").read_text()) for rpm in (21, 28)}
        self.assertEqual((before[21]["segments"], before[28]["segments"]), (2, 3))
        # without --extend the longer cap is refused, naming the option
        r = subprocess.run(command(ext, self.tmp, settings=longer), cwd=REPO, capture_output=True, text=True)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("--extend", r.stdout + r.stderr)
        said = self.run_study(ext, longer, "--extend")
        for rpm, last in ((21, 2), (28, 3)):
            self.assertIn(f"plan: {rpm} rpm: to extend", said)
            self.assertIn(f"{rpm} rpm, segment {last + 1}:", said)
            for k in range(1, last + 1):
                self.assertNotIn(f"{rpm} rpm, segment {k}:", said)
        after = {rpm: json.loads((docs / f"{rpm}rpm" / "run.json").read_text()) for rpm in (21, 28)}
        # 21 rpm as if capped at 0.08 s from the start: the same series, snapshot by snapshot, and
        # averages within the series' 10 digits (the extension's earlier part is read from them)
        self.assertEqual((self.tmp / whole / "21rpm" / "series_metrics.csv").read_text(),
                         (docs / "21rpm" / "series_metrics.csv").read_text())
        a, b = [(d / "21rpm" / "series_average.csv").read_text().splitlines() for d in (self.tmp / whole, docs)]
        self.assertEqual(a[0], b[0])
        for key, x, y in zip(a[0].split(","), a[1].split(","), b[1].split(",")):
            if "nan" in (x, y) or "" in (x, y):
                self.assertEqual(x, y, key)
            else:
                self.assertAlmostEqual(float(x), float(y), delta=1e-9 * max(1.0, abs(float(x))), msg=key)
        self.assertEqual(after[21]["simulated_s"], json.loads((self.tmp / whole / "21rpm" / "run.json").read_text())[
            "simulated_s"])
        # 28 rpm kept its start, which 21 rpm lists among its earlier end states
        self.assertEqual(after[28]["start_state_sha256"], before[28]["start_state_sha256"])
        self.assertEqual(after[21]["earlier_states_sha256"], [before[21]["state_sha256"]])
        self.assertEqual(after[28]["segments"], 4)
        self.assertEqual(len(after[28]["loops"]), 4)
        # done: the same command runs nothing, and so does the chain's first (its series is in it)
        self.assertNotIn("rpm, segment", self.run_study(ext, longer, "--extend"))
        self.assertNotIn("rpm, segment", self.run_study(ext, CHAIN))
        # a stop rule that asks for nothing more (a target, the cap reached): records only
        state = (docs / "21rpm" / "state.restart.gz").read_bytes()
        said = self.run_study(ext, [*longer, "--target", "Hc=0.001"], "--extend",
                              "--refresh", f"touch {self.tmp / 'refreshed'}", "README.md", "--refresh", "false", "x")
        self.assertNotIn("rpm, segment", said)
        # --refresh: run after each finished speed; a failing one is reported, not fatal
        self.assertTrue((self.tmp / "refreshed").exists())
        self.assertIn("--refresh false: exit 1, x not refreshed", said)
        self.assertEqual((docs / "21rpm" / "state.restart.gz").read_bytes(), state)
        last = json.loads((docs / "21rpm" / "run.json").read_text())
        self.assertEqual(last["settings"]["targets"], {"Hc": 0.001})
        self.assertEqual((last["outcome"], last["state_sha256"], last["segments"]), ("capped", after[21]["state_sha256"], 3))
        self.assertEqual(last["earlier_states_sha256"], [before[21]["state_sha256"]])
        # decided again, nothing run: the record keeps where and when it ran
        self.assertEqual((last["date"], last["machine"]), (after[21]["date"], after[21]["machine"]))
        self.assertIn("decided_again", last)


if __name__ == "__main__":
    unittest.main()
