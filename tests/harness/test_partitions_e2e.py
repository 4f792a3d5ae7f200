"""inputs/drum_partitions.in end to end: independent speeds in one MPI job, one LIGGGHTS partition
each (`-partition 2x1`), on a tiny drum (448 beads, 1000 steps). Each partition must run its own
speed from its own state and write only its own files; lists of the wrong length, and variables the
wrapper sets per partition given on the command line, must stop the job. Runs LIGGGHTS (LIGGGHTS
from the environment, as CTest sets it, or PATH) under mpirun, in a scratch directory with inputs/
linked, as a user runs from the repository root."""

import gzip
import os
import re
import shutil
import subprocess
import tempfile
import unittest
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
# the tiny drum: a 6 mm slab at 1 % fill (448 beads on the grid), the seed state 100 steps after the grid
SCENE = ["-var", "period", "0.006", "-var", "fill", "0.01"]
SPEEDS = (21, 42)


def liggghts():
    return os.environ.get("LIGGGHTS") or shutil.which("liggghts") or "liggghts"


def mpirun(ranks):
    cmd = ["mpirun", "--oversubscribe", "-np", str(ranks)]
    return cmd + ["--allow-run-as-root"] if os.geteuid() == 0 else cmd


def run(cmd, cwd):
    r = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=300)
    return r.returncode, r.stdout + r.stderr


def partitions(cwd, speeds, states, *extra):
    """The wrapper on 2 partitions of one rank each; LIGGGHTS' own per-partition logs in cwd."""
    return run(mpirun(2) + [liggghts(), "-partition", "2x1", "-in", "inputs/drum_partitions.in", "-screen", "none",
                            "-var", "speeds", speeds, "-var", "states", states, *SCENE, *extra], cwd)


def csv_rows(path):
    lines = path.read_text().split()
    return [dict(zip(lines[0].split(","), map(float, line.split(",")))) for line in lines[1:]]


class TwoSpeedsAtOnce(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = Path(tempfile.mkdtemp(prefix="partitions_e2e_"))
        (cls.dir / "inputs").symlink_to(REPO / "inputs")
        status, out = run([liggghts(), "-in", "inputs/drum.in", *SCENE, "-var", "start", "grid", "-var", "time", "0.002",
                           "-var", "dumpdt", "1", "-var", "name", "seed", "-log", "seed.log"], cls.dir)
        assert status == 0, out[-3000:]
        seed = cls.dir / "post" / "seed.restart"
        (cls.dir / "post" / "seed.restart.gz").write_bytes(gzip.compress(seed.read_bytes()))
        # partition 0 from the compressed state (as studies commit them), partition 1 from the plain one
        cls.status, cls.out = partitions(cls.dir, " ".join(map(str, SPEEDS)), "post/seed.restart.gz post/seed.restart",
                                         "-var", "tag", "pt", "-var", "time", "0.02", "-var", "dumpdt", "0.005")
        cls.post = cls.dir / "post" / "pt"

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.dir, ignore_errors=True)

    def scratch(self, name):
        """Another run's directory (its own LIGGGHTS logs and post/), inputs/ linked."""
        d = self.dir / name
        d.mkdir()
        (d / "inputs").symlink_to(REPO / "inputs")
        return d

    def test_each_partition_runs_its_own_speed(self):
        self.assertEqual(self.status, 0, self.out[-3000:])
        for k, rpm in enumerate(SPEEDS):
            log = (self.post / f"{rpm}rpm.log").read_text(errors="replace")
            self.assertIn(f"drum_partitions: partition {k} of 2: {rpm} rpm from post/seed.restart", log)
            self.assertIn(f"drum: 448 beads (target 412), period 0.006 m, {rpm} rpm, wall cylinder", log)
            self.assertIn("drum: done, 448 beads kept", log)
            self.assertIn("1 by 1 by 1 MPI processor grid", log)  # one rank each
            self.assertRegex(log, r"Loop time of \S+ on 1 procs for 1000 steps with 448 atoms")
            for other in SPEEDS:
                if other != rpm:
                    self.assertNotIn(f", {other} rpm,", log)
            # LIGGGHTS' own log of the partition holds the start, up to the switch to its own log
            own = (self.dir / f"log.liggghts.{k}").read_text(errors="replace")
            self.assertIn(f"Processor partition = {k}", own)
            self.assertIn(f"drum_partitions: partition {k} of 2: {rpm} rpm from post/seed.restart", own)
            self.assertIn(f"log post/pt/{rpm}rpm.log", own)
            # the run's metrics file: its speed in every row
            rows = csv_rows(self.post / f"{rpm}rpm_run.csv")
            self.assertEqual([r["rpm"] for r in rows], [rpm, rpm])

    def test_the_partitions_start_alike_and_end_apart(self):
        self.assertEqual(self.status, 0, self.out[-3000:])
        a, b = (self.post / f"{rpm}rpm_start.restart" for rpm in SPEEDS)
        self.assertEqual(a.read_bytes(), b.read_bytes())  # the same state, gzip-compressed or not
        runs = [csv_rows(self.post / f"{rpm}rpm_run.csv") for rpm in SPEEDS]
        self.assertEqual([r["time"] for r in runs[0]], [r["time"] for r in runs[1]])
        self.assertNotEqual(runs[0][-1]["centre_of_mass"], runs[1][-1]["centre_of_mass"])
        for a, b in ((f"{SPEEDS[0]}rpm.restart", f"{SPEEDS[1]}rpm.restart"),
                     (f"{SPEEDS[0]}rpm_1000.vtp", f"{SPEEDS[1]}rpm_1000.vtp")):
            self.assertNotEqual((self.post / a).read_bytes(), (self.post / b).read_bytes(), a)

    def test_no_file_is_written_by_both(self):
        self.assertEqual(self.status, 0, self.out[-3000:])
        snapshots = {}
        for rpm in SPEEDS:
            snapshots[rpm] = sorted(int(m.group(1)) for f in self.post.iterdir()
                                    if (m := re.fullmatch(rf"{rpm}rpm_(\d+)\.vtp", f.name)))
        self.assertEqual(snapshots[SPEEDS[0]], [250, 500, 750, 1000])  # from step 100, every 250 steps
        self.assertEqual(snapshots[SPEEDS[1]], snapshots[SPEEDS[0]])
        prefixes = tuple(f"{rpm}rpm" for rpm in SPEEDS)
        stray = [f.name for f in self.post.iterdir() if not f.name.startswith(prefixes)]
        self.assertEqual(stray, [])
        self.assertEqual(sorted(f.name for f in (self.dir / "post").iterdir()),
                         ["pt", "seed.restart", "seed.restart.gz", "seed_0.vtp", "seed_boundingBox_0.vtr", "seed_run.csv"])

    def test_one_speed_twice_and_times_per_partition(self):
        # two histories of one speed: told apart by their partition; each its own simulated time
        d, seed = self.scratch("twice"), self.dir / "post" / "seed.restart"
        status, out = partitions(d, "21 21", f"{seed} {seed}.gz", "-var", "tag", "twice",
                                 "-var", "times", "0.002 0.004", "-var", "dumpdt", "1")
        self.assertEqual(status, 0, out[-3000:])
        post = d / "post" / "twice"
        for k, steps in ((0, 100), (1, 200)):
            log = (post / f"21rpm_p{k}.log").read_text(errors="replace")
            self.assertIn(f"partition {k} of 2: 21 rpm", log)
            self.assertRegex(log, rf"Loop time of \S+ on 1 procs for {steps} steps")
            self.assertTrue((post / f"21rpm_p{k}.restart").exists())
        self.assertFalse(list(post.glob("21rpm.*")) + list(post.glob("21rpm_run.csv")))

    def test_a_list_of_the_wrong_length_stops_the_job(self):
        d = self.scratch("length")
        status, out = partitions(d, "21 42 63", "post/seed.restart post/seed.restart")
        self.assertNotEqual(status, 0, out[-3000:])
        said = "".join((d / f"log.liggghts.{k}").read_text(errors="replace") for k in (0, 1))
        self.assertIn("ERROR: World variable count doesn't match # of partitions", said, out[-3000:])

    def test_a_variable_set_per_partition_given_for_all_stops_the_job(self):
        d = self.scratch("given")
        status, out = partitions(d, "21 42", "post/seed.restart post/seed.restart", "-var", "rpm", "7")
        self.assertNotEqual(status, 0, out[-3000:])
        said = "".join((d / f"log.liggghts.{k}").read_text(errors="replace") for k in (0, 1))
        self.assertIn("ERROR: Cannot redefine variable as a different style", said, out[-3000:])


if __name__ == "__main__":
    unittest.main()
