"""tools/drum/rank_counts.py: the cuts on synthetic beds with known answers (quantile slabs, drum.in's
widened box, a y-z grid on a triangle), ghosts on a line of beads, LIGGGHTS' grid rule, the restart
reader on a file built here, and the model against what LIGGGHTS printed for a committed state."""

import gzip
import math
import struct
import sys
import tempfile
import unittest
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "tools" / "drum"))
import rank_counts as rc  # noqa: E402

DRUM_BOX = np.array([[0.0, 0.024], [-0.2265, 0.2265], [-0.2265, 0.2265]])


def state(y, z=None, x=None):
    """A State of beads at these coordinates in the drum's box."""
    y = np.asarray(y, float)
    z = np.zeros_like(y) if z is None else np.asarray(z, float)
    x = np.full_like(y, 0.012) if x is None else np.asarray(x, float)
    header = {"step": 0, "nprocs": 1, "procgrid_x": 1, "procgrid_y": 1, "procgrid_z": 1,
              **{k: DRUM_BOX[i, j] for i, a in enumerate("xyz") for j, k in enumerate((a + "lo", a + "hi"))}}
    return rc.State(header, np.column_stack([x, y, z]), np.full_like(y, 0.0015), np.arange(1, len(y) + 1))


def counts(layout, s):
    return np.bincount(layout.owner(s.x), minlength=layout.ranks).tolist()


class Cuts(unittest.TestCase):
    def test_quantile_slabs_hold_equal_counts(self):
        y = np.random.default_rng(1).permutation(np.arange(1000) * 1e-4)
        cuts = rc.quantile_cuts(y, 4)
        # 1 um above the 250th, 500th and 750th smallest, as drum.in's cut above the N/2-th
        np.testing.assert_allclose(cuts, np.array([249, 499, 749]) * 1e-4 + 1e-6)
        self.assertEqual(np.bincount(rc.slab_of(y, cuts)).tolist(), [250] * 4)
        self.assertAlmostEqual(rc.median_cut(y), 499e-4 + 1e-6)

    def test_drum_in_on_four_ranks_centres_a_uniform_grid_on_the_median(self):
        # 4000 beads uniform over y in [0, 0.2]: the median cut lies at 0.1 m, the widened box
        # [-0.2265, 0.4265] is cut every 0.163 m (at -0.063, 0.100, 0.263): the outer slabs hold
        # no bead, the middle two half each
        n = 4000
        s = state((np.arange(n) + 0.5) * 0.2 / n)
        slabs, drum_in, _ = rc.layouts(s, 4)
        self.assertEqual((slabs.name, slabs.grid, drum_in.name, drum_in.grid), ("slabs", (1, 4, 1), "drum.in", (1, 4, 1)))
        cut = rc.median_cut(s.x[:, 1])
        self.assertAlmostEqual(cut, 1999.5 * 0.2 / n + 1e-6)
        w = 0.2265 + cut
        np.testing.assert_allclose(drum_in.ycuts, [cut - w / 2, cut, cut + w / 2])
        self.assertEqual(counts(drum_in, s), [0, 2000, 2000, 0])
        self.assertEqual(counts(slabs, s), [1000] * 4)
        # on 2 ranks drum.in is the balanced cut itself
        two = rc.layouts(s, 2)
        np.testing.assert_allclose(two[0].ycuts, two[1].ycuts, atol=1e-15)

    def test_yz_grid_on_a_triangle(self):
        # beads uniform over the triangle 0 <= z <= y <= 1 (a lattice): the marginal medians are
        # y = 1/sqrt(2) and z = 1 - 1/sqrt(2), and the quadrants hold 2(ab - b^2/2), b(1 - a) (x2),
        # ... of the beads: 0.3284, 0.1716, 0.1716, 0.3284 (a = 1/sqrt 2, b = 1 - a)
        k = 600
        g = (np.arange(k) + 0.5) / k
        yy, zz = np.meshgrid(g, g, indexing="ij")
        inside = zz <= yy
        s = state(yy[inside] * 0.4 - 0.2, zz[inside] * 0.4 - 0.2)
        grid = rc.Layout("y-z grid", (1, 2, 2), rc.quantile_cuts(s.x[:, 1], 2), rc.quantile_cuts(s.x[:, 2], 2),
                         (-0.2265, 0.2265, -0.2265, 0.2265))
        a, b = 1 / math.sqrt(2), 1 - 1 / math.sqrt(2)
        low_low = 2 * (a * b - b * b / 2)
        # ranks: (y low, z low), (y low, z high), (y high, z low), (y high, z high)
        expected = [low_low, 0.5 - low_low, 0.5 - low_low, low_low]
        got = np.array(counts(grid, s)) / len(s.x)
        np.testing.assert_allclose(got, expected, atol=2e-3)
        # the layout from layouts() is this grid on the widened box (LIGGGHTS' rule: 1 x 2 x 2)
        yz = rc.layouts(s, 4)[2]
        self.assertEqual((yz.name, yz.grid), ("y-z grid", (1, 2, 2)))
        self.assertEqual(counts(yz, s), counts(grid, s))

    def test_ghosts_on_a_line_of_beads(self):
        # beads every mm along y at (i + 0.3) mm, two slabs cut at 50 mm, cutoff 2.5 mm: rank 0
        # receives rank 1's beads below 52.5 mm (50.3, 51.3, 52.3), rank 1 rank 0's from 47.5 mm
        # (48.3, 49.3); the first ten beads sit within the cutoff of the periodic x face, so rank 0
        # also holds their images
        y = (np.arange(100) + 0.3) * 1e-3
        x = np.where(np.arange(100) < 10, 0.001, 0.012)
        s = state(y, x=x)
        lay = rc.Layout("two", (1, 2, 1), [0.05], [], (0.0, 0.1, -0.2265, 0.2265))
        owner = lay.owner(s.x)
        self.assertEqual(rc.ghost_counts(s.x, owner, lay, 0.0025, 0.024).tolist(), [13, 2])
        # pairs within 1.5 mm: neighbours along the line, one across the cut (twice in newton off)
        pairs, wraps = rc.neighbour_pairs(s.x[10:], 0.0015, 0.024)
        self.assertEqual((len(pairs), int(wraps.sum())), (89, 0))
        work = rc.pair_work(lay.owner(s.x[10:]), pairs, wraps, 2)
        self.assertEqual(work.tolist(), [40, 50])

    def test_pairs_across_the_periodic_faces(self):
        s = state([0.0, 0.0], x=[0.0005, 0.0235])  # 1 mm apart through the x face
        pairs, wraps = rc.neighbour_pairs(s.x, 0.0015, 0.024)
        self.assertEqual((len(pairs), wraps.tolist()), (1, [True]))
        one = rc.Layout("one", (1, 1, 1), [], [], (-0.2265, 0.2265, -0.2265, 0.2265))
        self.assertEqual(rc.pair_work(one.owner(s.x), pairs, wraps, 1).tolist(), [2])

    def test_liggghts_grid_rule(self):
        box = (0.024, 0.59, 0.453)
        for p in (2, 4, 8, 16):
            self.assertEqual(rc.procgrid(p, box, (0, 0, 1)), (1, p, 1))
        self.assertEqual(rc.procgrid(4, box, (1, 0, 0)), (1, 2, 2))
        self.assertEqual(rc.procgrid(16, box, (1, 0, 0)), (1, 4, 4))
        self.assertEqual(rc.procgrid(8, (1, 1, 1), (0, 0, 0)), (2, 2, 2))
        with self.assertRaises(ValueError):
            rc.procgrid(3, box, (2, 0, 1))


def restart_bytes(chunks, natoms, nprocs, junk=b""):
    """A LIGGGHTS restart file: the header, `junk` for the style sections, then one chunk per rank
    of atom records (length, x, y, z, id, type, mask, image, vx, vy, vz, radius, extra...)."""
    out = bytearray()

    def flag(f, fmt, v):
        out.extend(struct.pack("<i", f) + struct.pack(fmt, v))

    def text(f, s):
        b = s.encode() + b"\0"
        out.extend(struct.pack("<ii", f, len(b)) + b)

    text(0, "Version LIGGGHTS-PUBLIC 3.8.0")
    flag(5, "<q", 1234)
    flag(7, "<i", nprocs)
    for f, v in ((8, 1), (9, nprocs), (10, 1)):
        flag(f, "<i", v)
    text(22, "granular")
    flag(23, "<q", natoms)
    for f, v in zip(range(37, 43), DRUM_BOX.ravel()):
        flag(f, "<d", v)
    out.extend(struct.pack("<i", -1))
    out.extend(junk)
    for chunk in chunks:
        values = []
        for tag, pos, extra in chunk:
            ints = [struct.unpack("<d", struct.pack("<q", v))[0] for v in (tag, 1, 1, 0)]  # ubuf
            rec = [*pos, *ints, 0.0, 0.0, 0.0, 0.0015, *([7.0] * extra)]
            values += [float(len(rec) + 1), *rec]
        out.extend(struct.pack("<i", len(values)) + struct.pack(f"<{len(values)}d", *values))
    return bytes(out)


class Reader(unittest.TestCase):
    CHUNKS = [[(3, (0.001, 0.01, -0.2), 0), (1, (0.002, 0.02, -0.1), 5)],
              [(2, (0.003, -0.03, -0.15), 2), (5, (0.004, 0.04, -0.05), 0), (4, (0.005, 0.05, -0.12), 19)]]
    # junk: bytes that look like a chunk's count, a misaligned copy of a record
    JUNK = struct.pack("<i", 3) + struct.pack("<3d", 13.0, 0.5, 0.5) + b"\x01\x02\x03"

    def test_reads_the_beads_plain_and_gzipped(self):
        data = restart_bytes(self.CHUNKS, 5, 2, self.JUNK)
        with tempfile.TemporaryDirectory() as d:
            for name, content in (("s.restart", data), ("s.restart.gz", gzip.compress(data))):
                path = Path(d) / name
                path.write_bytes(content)
                s = rc.read_restart(path)
                self.assertEqual(s.tag.tolist(), [3, 1, 2, 5, 4])
                np.testing.assert_array_equal(s.x[:, 1], [0.01, 0.02, -0.03, 0.04, 0.05])
                np.testing.assert_array_equal(s.radius, [0.0015] * 5)
                self.assertEqual((s.header["step"], s.header["nprocs"]), (1234, 2))
                np.testing.assert_array_equal(s.box, DRUM_BOX)

    def test_records_of_one_length_read_at_once(self):
        chunks = [[(k + 1, (0.001, 0.001 * k, 0.0), 3) for k in range(50)]]
        with tempfile.TemporaryDirectory() as d:
            path = Path(d) / "s.restart"
            path.write_bytes(restart_bytes(chunks, 50, 1))
            s = rc.read_restart(path)
        self.assertEqual(s.tag.tolist(), list(range(1, 51)))
        np.testing.assert_allclose(s.x[:, 1], 0.001 * np.arange(50))

    def test_a_count_that_does_not_match_is_refused(self):
        with tempfile.TemporaryDirectory() as d:
            path = Path(d) / "s.restart"
            path.write_bytes(restart_bytes(self.CHUNKS, 6, 2, self.JUNK))
            with self.assertRaisesRegex(rc.RestartError, "no 2 chunks of 6 atoms"):
                rc.read_restart(path)
            path.write_bytes(b"not a restart file at all")
            with self.assertRaises(rc.RestartError):
                rc.read_restart(path)


class AgainstLiggghts(unittest.TestCase):
    def test_the_committed_21rpm_state_as_liggghts_counted_it(self):
        # main_job.log is a run from this state: its run 0 printed the beads and ghosts per rank on
        # the state's own cut, and drum.in's balance printed the median cut
        study = REPO / "docs" / "drum" / "study_thesis"
        if not (study / "21rpm" / "state.restart.gz").exists() or not rc.MAIN_JOB_LOG.exists():
            self.skipTest("the committed 21 rpm state or main_job.log is missing")
        rows, states = rc.study_rows(study, [21], [2])
        check = rc.check_text(states)
        self.assertIsNotNone(check)
        self.assertIn(": identical.", check)
        self.assertIn("is the cut drum.in printed for that state", check)
        self.assertEqual([(r["layout"], r["beads_min"], r["beads_max"]) for r in rows],
                         [("slabs", 32672, 32672), ("drum.in", 32672, 32672)])


if __name__ == "__main__":
    unittest.main()
