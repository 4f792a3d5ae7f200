"""harness.liggghts runs a private copy of its input: LIGGGHTS reads its input as the run goes,
so a script rewritten during a run (as when inputs/drum.in is edited while a campaign runs)
would otherwise change that run. Runs LIGGGHTS (env LIGGGHTS or PATH)."""

import sys
import tempfile
import threading
import time
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
import harness  # noqa: E402


class PrivateInput(unittest.TestCase):
    def test_a_script_rewritten_during_the_run_does_not_reach_it(self):
        # 20 kB of comments between the pause and the last command: far beyond what stdio has
        # buffered when the pause starts, so LIGGGHTS reads that command from the file after it.
        # Without the copy, the run prints LATER (checked by hand with `liggghts -in` directly).
        pad = "".join(f"# padding {i:05d} {'x' * 40}\n" for i in range(400))
        with tempfile.TemporaryDirectory() as d:
            script = Path(d) / "pause.in"
            script.write_text('print "BEFORE"\nshell sleep 3\n' + pad + 'print "AFTER"\n')
            result = {}
            stale = harness.post(".inputs", "pause_4194304999_0.in")  # a pid no process has
            stale.write_text("left by a killed driver\n")
            run = threading.Thread(target=lambda: result.update(log=harness.liggghts(script, log=Path(d) / "pause.log")))
            run.start()
            time.sleep(1.5)
            with open(script, "r+") as f:  # in place, same length: what an editor saving over it does
                text = f.read().replace("AFTER", "LATER")
                f.seek(0)
                f.write(text)
            run.join()
            printed = [line for line in result["log"].text.splitlines() if line in ("BEFORE", "AFTER", "LATER")]
        self.assertEqual(printed, ["BEFORE", "AFTER"])
        self.assertFalse(list(harness.post(".inputs").glob("pause_*")),
                         "the run's copy is removed after it, a dead driver's before it")

    def test_a_missing_script_is_named(self):
        with self.assertRaisesRegex(harness.RunFailed, "no_such.in: no such input script"):
            harness.liggghts(Path("inputs/no_such.in"))


if __name__ == "__main__":
    unittest.main()
