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


if __name__ == "__main__":
    unittest.main()
