"""The project's shell scripts parse and pass ShellCheck: tools/drum/campaign.sh runs for days
unattended, and a slip in a step that comes late (an unbound variable, a misquoted list) would
stop it only when it gets there."""

import shutil
import subprocess
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SKIP = {"build", "post", ".git"}


def scripts():
    found = [p for p in ROOT.rglob("*.sh") if not SKIP & set(p.relative_to(ROOT).parts)]
    return sorted(found) + [ROOT / ".ci" / "run"]


class Scripts(unittest.TestCase):
    def test_found(self):
        names = {p.relative_to(ROOT).as_posix() for p in scripts()}
        self.assertTrue({"setup.sh", "tools/drum/campaign.sh", ".ci/run"} <= names, names)

    def test_bash_parses(self):
        for path in scripts():
            with self.subTest(script=path.relative_to(ROOT).as_posix()):
                run = subprocess.run(["bash", "-n", str(path)], capture_output=True, text=True)
                self.assertEqual(run.returncode, 0, run.stderr)

    def test_shellcheck(self):
        shellcheck = shutil.which("shellcheck")
        self.assertIsNotNone(shellcheck, "shellcheck not installed (setup.sh installs it)")
        for path in scripts():
            with self.subTest(script=path.relative_to(ROOT).as_posix()):
                run = subprocess.run([shellcheck, "--shell=bash", str(path)], capture_output=True, text=True)
                self.assertEqual(run.returncode, 0, run.stdout + run.stderr)


if __name__ == "__main__":
    unittest.main()
