"""inputs/materials.in as LIGGGHTS reads it equals what the harness reads (the scripts and the
inputs must see the same Table 3.1). Runs LIGGGHTS (env LIGGGHTS or PATH)."""

import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
import harness  # noqa: E402


class MaterialsAsLiggghtsReadsThem(unittest.TestCase):
    def test_every_variable(self):
        values = harness.materials()
        with tempfile.TemporaryDirectory() as d:
            script = Path(d) / "print.in"
            lines = [f"include {harness.REPO / 'inputs' / 'materials.in'}"]
            lines += [f'print "VALUE {name} ${{{name}}}"' for name in values]
            script.write_text("\n".join(lines) + "\n")
            log = harness.liggghts(script, log=Path(d) / "print.log")
        printed = {}
        for line in log.text.splitlines():
            words = line.split()
            if len(words) == 3 and words[0] == "VALUE":
                printed[words[1]] = float(words[2])
        self.assertEqual(printed, values)


if __name__ == "__main__":
    unittest.main()
