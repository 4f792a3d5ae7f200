#!/usr/bin/python3
"""Beads per MPI rank of the full drum on more ranks: the balanced cut of inputs/drum.in applied to
a study's committed end states for P ranks, and the parallel efficiency that implies.

Bead positions come from the committed end states (docs/drum/STUDY/<rpm>rpm/state.restart.gz),
read straight from LIGGGHTS' restart format (no LIGGGHTS run). Each state is decomposed as drum.in
would decompose it on P ranks (`processors * * 1`: on this box LIGGGHTS' rule, emulated here,
picks 1 x P x 1 for every P used, so x, 24 mm long, is never cut and the ranks are P slabs along y):

  slabs       the balance generalised: the P - 1 cuts each 1 um above the bead whose rank in y
              is k N / P, as drum.in's bisection puts its one cut 1 um above the N/2-th bead, so
              every slab holds N / P beads. LIGGGHTS 3.8 has no command that places more than
              one cut (no `balance`): this is what a balancer would reach, not what drum.in does.
  drum.in     what drum.in does on P ranks as written: the box widened so that its middle lies at
              the median y (the one cut its balance moves), LIGGGHTS' uniform 1 x P x 1 grid over
              that box; on 2 ranks the same as `slabs`.
  y-z grid    `processors 1 * *`: a py x pz grid over the drum's cross-section (the one LIGGGHTS'
              rule picks on the widened box), y cuts at the beads' y quantiles and z cuts at their
              z quantiles, as a balancer of each dimension would place them (LIGGGHTS' grids are
              tensor products: one set of z cuts for every column).

Per layout: beads per rank (min, max, mean) and mean/max, the parallel efficiency the bead counts
allow; ghosts per rank (the beads and periodic images within the ghost cutoff of a rank's
sub-domain that it does not own: what it receives every step, LIGGGHTS' Nghost); the efficiency
by neighbour pairs, the one-rank pair count over P times the busiest rank's (with `newton off` a
pair across two ranks is computed by both, and a pair across the periodic x faces twice by its
rank); and the busiest rank's pairs at 2 ranks over its pairs at P ranks, the speed-up over 2 ranks
that pair work alone allows (the ghosts' communication not counted: an upper bound). The ghost and
neighbour cutoff is a bead diameter plus the study's skin (`run.json`; drum.in's default 0.3 d).
Checked against LIGGGHTS: on the 21 rpm state's own cut the model gives the Nlocal and Nghost that
LIGGGHTS printed for that state (benchmarks/results/main_job.log), bead for bead.

  tools/drum/rank_counts.py --rpm 7,21,42,63 --ranks 2,4,8,16 --out docs/drum/rank_counts.md

Needs: python3-numpy, python3-scipy.
"""

import argparse
import csv
import datetime
import gzip
import json
import math
import os
import re
import struct
import sys
from pathlib import Path

import numpy as np
from scipy import spatial

REPO = Path(__file__).resolve().parents[2]
OFFSET = 1e-6  # drum.in places its cut 1 um above the bisection's bracket
DRUM_HALF_WIDTH = 0.2265  # drum.in: the drum spans -0.2265..0.2265 m in y and z
MAIN_JOB_LOG = REPO / "benchmarks" / "results" / "main_job.log"
STEADY_BENCHMARK = REPO / "benchmarks" / "results" / "full_scene_steady"  # .json, .csv

# LIGGGHTS' restart header (write_restart.cpp): a flag, then a value whose type the flag fixes
_CHAR_FLAGS = {0, 4, 22}  # VERSION, UNITS, ATOM_STYLE
_BIGINT_FLAGS = {5, 23, 25, 28, 31, 34}  # NTIMESTEP, NATOMS, NBONDS, NANGLES, NDIHEDRALS, NIMPROPERS
_DOUBLE_FLAGS = range(37, 52)  # BOXLO_0 ... YZ
_LAST_FLAG = 51
_HEADER = {5: "step", 7: "nprocs", 8: "procgrid_x", 9: "procgrid_y", 10: "procgrid_z", 22: "atom_style",
           23: "natoms", 37: "xlo", 38: "xhi", 39: "ylo", 40: "yhi", 41: "zlo", 42: "zhi"}
# an atom's record: its length, then x, y, z, id, type, mask, image, vx, vy, vz, radius, ...
_X, _TAG, _RADIUS, _MIN_RECORD = 1, 4, 11, 12


class RestartError(ValueError):
    """A file that is not a LIGGGHTS restart of granular beads this reader understands."""


class State:
    """A restart file's beads: positions x (N x 3), radii and ids; its header, box and step."""

    def __init__(self, header, x, radius, tag):
        self.header, self.x, self.radius, self.tag = header, x, radius, tag
        self.box = np.array([[header["xlo"], header["xhi"]], [header["ylo"], header["yhi"]],
                             [header["zlo"], header["zhi"]]])


def read_restart(path):
    """The beads of a LIGGGHTS 3.8 restart file (gzip-compressed or not).

    The file holds a header of flagged values; then sections whose layout depends on the styles in
    use (groups, the pair style's and the fixes' own data); then the atoms, one chunk per rank that
    wrote the file, each an int n and n doubles, to the end of the file. Each atom's record opens
    with its length, then x, y, z, id, type, mask, image (these four integers in a double's bits),
    v, radius (atom style granular). The chunks are found from the end: the last one starts at an
    int n that n doubles after it reach the end of the file, the one before ends where that one
    starts, and so on for the header's count of ranks; a candidate counts only if its records fill
    every chunk exactly and hold the header's number of atoms, each id once."""
    path = Path(path)
    data = path.read_bytes()
    if data[:2] == b"\x1f\x8b":
        data = gzip.decompress(data)
    header, pos = {}, 0
    try:
        while True:
            flag, = struct.unpack_from("<i", data, pos)
            pos += 4
            if flag == -1:
                break
            if flag in _CHAR_FLAGS:
                n, = struct.unpack_from("<i", data, pos)
                if not 0 < n < 4096:
                    raise RestartError(f"{path}: a text of {n} bytes in the header: not a LIGGGHTS restart file")
                value = data[pos + 4:pos + 4 + n].rstrip(b"\0").decode("ascii", "replace")
                pos += 4 + n
            elif flag in _BIGINT_FLAGS:
                value, = struct.unpack_from("<q", data, pos)
                pos += 8
            elif flag in _DOUBLE_FLAGS:
                value, = struct.unpack_from("<d", data, pos)
                pos += 8
            elif 0 <= flag <= _LAST_FLAG:
                value, = struct.unpack_from("<i", data, pos)
                pos += 4
            else:
                raise RestartError(f"{path}: flag {flag} in the header: not a LIGGGHTS restart file")
            if flag in _HEADER:
                header[_HEADER[flag]] = value
    except struct.error as e:
        raise RestartError(f"{path}: the header ends early: not a LIGGGHTS restart file") from e
    missing = [k for k in _HEADER.values() if k not in header]
    if missing:
        raise RestartError(f"{path}: the header lacks {', '.join(missing)}")
    if header["atom_style"] != "granular":
        raise RestartError(f"{path}: atom style {header['atom_style']!r}: expected granular")
    found = _atom_chunks(data, pos, header["nprocs"], header["natoms"])
    if found is None:
        raise RestartError(f"{path}: no {header['nprocs']} chunks of {header['natoms']} atoms end the file")
    rec = np.concatenate(found)
    return State(header, rec[:, _X:_X + 3].copy(), rec[:, _RADIUS].copy(), _tags(rec))


def _records(data, start, n):
    """The atom records of a chunk of n doubles at byte `start`, as rows of their first
    _MIN_RECORD values, or None if they do not fill it exactly."""
    values = np.frombuffer(data, "<f8", n, start)
    if n == 0:
        return values.reshape(0, _MIN_RECORD)
    m = values[0]
    # every record as long as the first (the usual case): whole rows at once
    if np.isfinite(m) and m == int(m) and _MIN_RECORD <= m <= n and n % int(m) == 0:
        rows = values.reshape(-1, int(m))
        if np.all(rows[:, 0] == m):
            return rows[:, :_MIN_RECORD]
    rows, i = [], 0
    while i < n:
        m = values[i]
        if not (np.isfinite(m) and m == int(m) and _MIN_RECORD <= m <= n - i):
            return None
        rows.append(values[i:i + _MIN_RECORD])
        i += int(m)
    return np.array(rows)


def _tags(rows):
    """The ids of atom records (LIGGGHTS packs integers into a double's bits)."""
    return np.ascontiguousarray(rows[:, _TAG]).view(np.int64)


def _atom_chunks(data, header_end, nprocs, natoms):
    """The records of the `nprocs` chunks that end the file, one array per chunk, or None."""

    def ending_at(end):
        # offsets p = end - 4 - 8 n (n >= 0, p after the header) whose int is n
        first = header_end + (end - 4 - header_end) % 8
        if end - 4 < first:
            return []
        offsets = np.arange(first, end - 3, 8)
        ints = np.ndarray((len(offsets),), "<i4", data, first, (8,)).astype(np.int64)
        return [int(p) for p in offsets[(ints >= 0) & (offsets + 4 + 8 * ints == end)]]

    def candidates(end, left):
        # every way `left` chunks can end at `end`, the largest chunk first
        for p in ending_at(end):
            here = (p + 4, (end - p - 4) // 8)
            if left == 1:
                yield [here]
            else:
                for rest in candidates(p, left - 1):
                    yield rest + [here]

    for chunks in candidates(len(data), nprocs):
        records = [_records(data, s, n) for s, n in chunks]
        if any(r is None for r in records) or sum(map(len, records)) != natoms:
            continue
        if len(np.unique(_tags(np.concatenate(records)))) == natoms:
            return records
    return None


# ---- decomposition ----------------------------------------------------------------------------


def procgrid(nprocs, prd, fixed=(0, 0, 1)):
    """The processor grid LIGGGHTS picks for `processors` with these counts fixed (0: `*`): of the
    factorisations px py pz = nprocs, the one with the least sub-domain surface
    xy/(px py) + xz/(px pz) + yz/(py pz), the first minimum with px, then py, ascending (LAMMPS'
    ProcMap, one level)."""
    area = (prd[0] * prd[1], prd[0] * prd[2], prd[1] * prd[2])
    best, best_surf = None, math.inf
    for px in range(1, nprocs + 1):
        for py in range(1, nprocs + 1):
            if nprocs % (px * py):
                continue
            pz = nprocs // (px * py)
            if any(f and f != p for f, p in zip(fixed, (px, py, pz))):
                continue
            surf = area[0] / px / py + area[1] / px / pz + area[2] / py / pz
            if surf < best_surf:
                best, best_surf = (px, py, pz), surf
    if best is None:
        raise ValueError(f"no {nprocs}-rank grid with the counts {fixed} fixed")
    return best


def quantile_cuts(values, parts):
    """The parts - 1 cuts that split `values` into `parts` groups of equal count, as drum.in's
    bisection splits the beads in two: cut k lies OFFSET above the floor(k N / parts)-th smallest
    value, so that the values at or below it are the floor(k N / parts) smallest."""
    v = np.sort(np.asarray(values, float))
    return np.array([v[(k * len(v)) // parts - 1] + OFFSET for k in range(1, parts)])


def median_cut(values):
    """drum.in's cut: OFFSET above the floor(N / 2)-th smallest value."""
    return quantile_cuts(values, 2)[0]


def drum_in_cuts(y, parts):
    """The y cuts of drum.in's balance on `parts` ranks, and the widened box's y range: the box
    [cut - w, cut + w], w = 0.2265 m + |cut| (the median cut at its middle), cut uniformly into
    `parts` slabs (LIGGGHTS' grids are uniform)."""
    cut = median_cut(y)
    w = DRUM_HALF_WIDTH + abs(cut)
    return cut - w + 2 * w * np.arange(1, parts) / parts, (cut - w, cut + w)


def slab_of(values, cuts):
    """Each value's slab: the number of cuts at or below it (a sub-domain holds lo <= v < hi)."""
    return np.searchsorted(np.asarray(cuts, float), values, side="right")


class Layout:
    """A decomposition of the drum's cross-section: its grid (px, py, pz; x is never cut), the y
    and z cuts, and the domain's (ylo, yhi, zlo, zhi). Rank r is column r // pz, layer r % pz."""

    def __init__(self, name, grid, ycuts, zcuts, bounds):
        if grid[0] != 1 or len(ycuts) != grid[1] - 1 or len(zcuts) != grid[2] - 1:
            raise ValueError(f"layout {name}: grid {grid} with {len(ycuts)} y and {len(zcuts)} z cuts")
        self.name, self.grid = name, tuple(grid)
        self.ycuts, self.zcuts = np.asarray(ycuts, float), np.asarray(zcuts, float)
        self.bounds = bounds

    @property
    def ranks(self):
        return self.grid[1] * self.grid[2]

    def owner(self, x):
        return slab_of(x[:, 1], self.ycuts) * self.grid[2] + slab_of(x[:, 2], self.zcuts)

    def edges(self, rank):
        ylo, yhi, zlo, zhi = self.bounds
        ys = np.concatenate([[ylo], self.ycuts, [yhi]])
        zs = np.concatenate([[zlo], self.zcuts, [zhi]])
        iy, iz = divmod(rank, self.grid[2])
        return ys[iy], ys[iy + 1], zs[iz], zs[iz + 1]


def ghost_counts(x, owner, layout, cutoff, period):
    """Ghosts per rank as LIGGGHTS acquires them: every bead, and every periodic image along x (the
    periodic axis, never cut here), within `cutoff` of the rank's sub-domain, except the rank's own
    beads themselves (their images count: LIGGGHTS stores them as ghosts)."""
    near_face = (x[:, 0] < cutoff) | (x[:, 0] >= period - cutoff)
    counts = []
    for r in range(layout.ranks):
        ylo, yhi, zlo, zhi = layout.edges(r)
        near = ((x[:, 1] >= ylo - cutoff) & (x[:, 1] < yhi + cutoff)
                & (x[:, 2] >= zlo - cutoff) & (x[:, 2] < zhi + cutoff))
        counts.append(int(np.sum(near & (owner != r)) + np.sum(near & near_face)))
    return np.array(counts)


def neighbour_pairs(x, cutoff, period):
    """The pairs (i, j) of beads closer than `cutoff` (periodic along x), and for each whether it
    spans the periodic x faces."""
    p = np.column_stack([np.mod(x[:, 0], period), x[:, 1:] - x[:, 1:].min(axis=0)])
    span = p[:, 1:].max(axis=0) + 2 * cutoff + 1.0  # y, z: wide enough never to wrap
    pairs = spatial.cKDTree(p, boxsize=[period, *span]).query_pairs(cutoff, output_type="ndarray")
    wraps = np.abs(p[pairs[:, 0], 0] - p[pairs[:, 1], 0]) > period / 2
    return pairs, wraps


def pair_work(owner, pairs, wraps, ranks):
    """Pairs in each rank's neighbour list with `newton off`: a pair within a rank once, across two
    ranks in both, across the periodic faces once per end (the other end is an image, a ghost)."""
    oi, oj = owner[pairs[:, 0]], owner[pairs[:, 1]]
    twice = (oi != oj) | wraps
    return np.bincount(oi, minlength=ranks) + np.bincount(oj[twice], minlength=ranks)


def measure(layout, x, pairs, wraps, cutoff, period):
    """Beads, ghosts and neighbour-pair work per rank under `layout`."""
    owner = layout.owner(x)
    beads = np.bincount(owner, minlength=layout.ranks)
    work = pair_work(owner, pairs, wraps, layout.ranks)
    serial = len(pairs) + int(np.sum(wraps))
    ghosts = ghost_counts(x, owner, layout, cutoff, period)
    return {"layout": layout.name, "grid": "×".join(map(str, layout.grid)), "ranks": layout.ranks,
            "beads_min": int(beads.min()), "beads_max": int(beads.max()), "beads_mean": float(beads.mean()),
            "efficiency": float(beads.mean() / beads.max()),
            "ghosts_max": int(ghosts.max()), "ghosts_mean": float(ghosts.mean()),
            "ghost_ratio": float(ghosts.mean() / beads.mean()),
            "work_max": int(work.max()), "work_min": int(work.min()), "serial_work": serial,
            "pair_efficiency": float(serial / (layout.ranks * work.max()))}


def layouts(state, ranks):
    """The decompositions of `state`'s beads on `ranks` ranks (the module's doc): slabs and
    drum.in, and from 4 ranks the y-z grid."""
    y = state.x[:, 1]
    prd = state.box[:, 1] - state.box[:, 0]
    grid = procgrid(ranks, prd, (0, 0, 1))
    if grid[0] != 1:
        raise ValueError(f"{ranks} ranks: LIGGGHTS would cut x too ({grid}): not modelled")
    cuts, (ylo, yhi) = drum_in_cuts(y, ranks)
    bounds = (ylo, yhi, *state.box[2])
    out = [Layout("slabs", grid, quantile_cuts(y, ranks), [], bounds),
           Layout("drum.in", grid, cuts, [], bounds)]
    if ranks >= 4:
        yz = procgrid(ranks, (prd[0], yhi - ylo, prd[2]), (1, 0, 0))
        out.append(Layout("y-z grid", yz, quantile_cuts(y, yz[1]) if yz[1] > 1 else [],
                          quantile_cuts(state.x[:, 2], yz[2]) if yz[2] > 1 else [], bounds))
    return out


def own_layout(state):
    """The cut the state was written with: its rank grid (the header's) uniform over its box."""
    grid = (state.header["procgrid_x"], state.header["procgrid_y"], state.header["procgrid_z"])
    (ylo, yhi), (zlo, zhi) = state.box[1], state.box[2]
    return Layout("as written", grid, ylo + (yhi - ylo) * np.arange(1, grid[1]) / grid[1],
                  zlo + (zhi - zlo) * np.arange(1, grid[2]) / grid[2], (ylo, yhi, zlo, zhi))


# ---- the study's states ---------------------------------------------------------------------


def skin_of(run_json):
    """The neighbour skin [bead diameters] a study's speed ran with (drum.in's default 0.3)."""
    try:
        settings = json.loads(Path(run_json).read_text()).get("settings", {})
        return float(settings.get("variables", {}).get("skin", 0.3))
    except (OSError, ValueError):
        return 0.3


def study_rows(study, rpms, ranks):
    """One row per speed, rank count and layout; and per speed its state's facts."""
    rows, states = [], []
    for rpm in rpms:
        folder = Path(study) / f"{rpm}rpm"
        state = read_restart(folder / "state.restart.gz")
        skin = skin_of(folder / "run.json")
        cutoff = 2 * float(state.radius.max()) * (1 + skin)
        period = float(state.box[0, 1] - state.box[0, 0])
        pairs, wraps = neighbour_pairs(state.x, cutoff, period)
        fact = {"rpm": rpm, "beads": len(state.x), "step": state.header["step"], "skin": skin, "cutoff": cutoff,
                "median_y": float(median_cut(state.x[:, 1]) - OFFSET), "pairs": len(pairs),
                "own": measure(own_layout(state), state.x, pairs, wraps, cutoff, period),
                "box": state.box.tolist(), "file": str(folder / "state.restart.gz")}
        states.append(fact)
        two = None
        for p in ranks:
            for lay in layouts(state, p):
                row = {"rpm": rpm, **measure(lay, state.x, pairs, wraps, cutoff, period)}
                if p == 2 and lay.name == "slabs":
                    two = row["work_max"]
                    fact["balanced_two"] = row
                rows.append(row)
        for row in rows:
            if row["rpm"] == rpm:
                row["speedup_vs_2"] = two / row["work_max"] if two else float("nan")
    return rows, states


def liggghts_counts(log):
    """LIGGGHTS' first Nlocal and Nghost statistics (ave, max, min) in a log and the box before them
    (what a `run 0` right after read_restart printed), and drum.in's balanced cut."""
    text = Path(log).read_text(errors="replace")
    box = re.search(r"orthogonal box = \(([^)]*)\) to \(([^)]*)\)", text)
    stats = {k: re.search(rf"{k}:\s+(\S+) ave (\S+) max (\S+) min", text) for k in ("Nlocal", "Nghost")}
    cut = re.search(r"drum: balance: cut at y = (\S+) m", text)
    if not box or not all(stats.values()):
        return None
    return {"box": [float(v) for v in (box.group(1) + " " + box.group(2)).split()],
            "cut": float(cut.group(1)) if cut else None,
            **{k: [float(v) for v in m.groups()] for k, m in stats.items()}}


# ---- output -----------------------------------------------------------------------------------


def table(rows, columns):
    head = "| " + " | ".join(c for c, _ in columns) + " |\n|" + "---|" * len(columns) + "\n"
    return head + "".join("| " + " | ".join(f(r) for _, f in columns) + " |\n" for r in rows)


COLUMNS = [("rpm", lambda r: str(r["rpm"])), ("ranks", lambda r: str(r["ranks"])),
           ("layout (px×py×pz)", lambda r: f"{r['layout']} ({r['grid']})"),
           ("beads per rank: min / max / mean",
            lambda r: f"{r['beads_min']:,} / {r['beads_max']:,} / {r['beads_mean']:,.0f}"),
           ("efficiency (mean/max)", lambda r: f"{r['efficiency']:.2f}"),
           ("ghosts per rank (max)", lambda r: f"{r['ghosts_max']:,}"),
           ("ghosts per bead", lambda r: f"{r['ghost_ratio']:.2f}"),
           ("efficiency by pairs", lambda r: f"{r['pair_efficiency']:.2f}"),
           ("speed-up over 2 ranks (pairs)", lambda r: f"{r['speedup_vs_2']:.2f}")]


def _span(values, fmt="{:.2f}"):
    lo, hi = min(values), max(values)
    return fmt.format(lo) if fmt.format(lo) == fmt.format(hi) else f"{fmt.format(lo)}–{fmt.format(hi)}"


def page(rows, states, command, study, check):
    """docs/drum/rank_counts.md: the answer, the table, how the cuts are placed, the check."""
    ranks = sorted({r["ranks"] for r in rows})
    by = lambda lay, p: [r for r in rows if r["layout"] == lay and r["ranks"] == p]  # noqa: E731
    top = max(ranks)
    slab_top, drum_4 = by("slabs", top), by("drum.in", 4)
    drum_top, yz_top = by("drum.in", top), by("y-z grid", top)
    rpms = ", ".join(str(s["rpm"]) for s in states)
    text = [f"<!-- Generated by `{command}` on {datetime.date.today().isoformat()} ({os.cpu_count()} cores); "
            "edit the generator, not this file. -->\n",
            "# Beads per rank on more cores\n",
            f"**Spend more cores on more speeds at once, 2 ranks each, not on more ranks per speed.** On the "
            f"committed steady states of `{study}` at {rpms} rpm, drum.in's balance, which moves the one cut of "
            "`processors * * 1`, splits the beads evenly only on 2 ranks: on 4 ranks its busiest rank holds "
            f"{_span([r['beads_max'] for r in drum_4], '{:,}')} of the {states[0]['beads']:,} beads (efficiency "
            f"{_span([r['efficiency'] for r in drum_4])}), so a speed runs at most "
            f"{_span([r['speedup_vs_2'] for r in drum_4])} times as fast as on 2 ranks, and on {top} ranks "
            f"{_span([r['speedup_vs_2'] for r in drum_top])} times (efficiency "
            f"{_span([r['efficiency'] for r in drum_top])}, ranks without a bead). Cuts at the bed's quantiles "
            "(what a balancer would place; LIGGGHTS 3.8 has none that places more than one) would split the beads "
            f"evenly, with an efficiency by neighbour pairs of {_span([r['pair_efficiency'] for r in slab_top])} on "
            f"{top} ranks, but each rank would then receive {_span([r['ghost_ratio'] for r in slab_top])} ghosts per "
            f"bead it owns every step, against {_span([r['ghost_ratio'] for r in by('slabs', 2)])} on 2 ranks; a y–z "
            f"grid at the quantiles of each dimension balances worse (efficiency "
            f"{_span([r['efficiency'] for r in yz_top])} on {top} ranks). Independent speeds need no communication "
            f"between them{side_by_side()}, so P/2 speeds at once, 2 ranks each, do P/2 times the work in the time of "
            "the longest. "
            "[Running many speeds at once](README.md#running-many-speeds-at-once) has the recipe and the projection "
            "for the nine speeds on 18 cores.\n",
            "Speed-up over 2 ranks counts neighbour pairs only (the busiest rank's at 2 ranks over its at P): the "
            "ghosts' communication comes on top, so it is an upper bound.\n",
            table(rows, COLUMNS),
            "## How the ranks are cut\n",
            "Bead positions are read from each speed's committed end state (`state.restart.gz`, LIGGGHTS' restart "
            "format read by the script, no LIGGGHTS run). drum.in declares `processors * * 1`; for P = "
            f"{', '.join(map(str, ranks))} on the drum's box LIGGGHTS' grid rule (least sub-domain surface, emulated) "
            "gives 1 × P × 1: the 24 mm period is never cut, so the ranks are P slabs along y. drum.in's balance "
            "(`-var balance on`) finds the median y by bisection with `count(all,region)`, puts its cut 1 µm above "
            "it and widens the box on one side so that the box's middle lies there. Generalised:\n\n"
            "- **slabs**: the P − 1 cuts 1 µm above the beads whose rank in y is k N/P (the balance's bisection "
            "for each quantile instead of the median): N/P beads per rank;\n"
            "- **drum.in**: the widened box, centred on the median cut, cut uniformly into P slabs, which is what "
            "drum.in does on P ranks as written (LIGGGHTS' grids are uniform; the box trick moves only the middle "
            "cut);\n"
            "- **y-z grid**: `processors 1 * *`, the py × pz grid LIGGGHTS' rule picks on the widened box, y cuts "
            "at the y quantiles and z cuts at the z quantiles (one set of z cuts for every column).\n\n"
            "Ghosts: the beads, and the periodic images along x, within the ghost cutoff (a bead diameter plus the "
            f"skin, {1e3 * states[0]['cutoff']:.1f} mm) of a rank's sub-domain that it does not own; neighbour pairs: "
            "beads closer than that cutoff (in a `newton off` list a pair across two ranks is held by both, one "
            "across the periodic faces twice by its rank).\n"]
    if check:
        text.append("## Check against LIGGGHTS\n")
        text.append(check + "\n")
    text.append("## The states\n")
    text.append(table(states, [("rpm", lambda s: str(s["rpm"])), ("step", lambda s: f"{s['step']:,}"),
                               ("beads", lambda s: f"{s['beads']:,}"),
                               ("median y [mm]", lambda s: f"{1e3 * s['median_y']:.2f}"),
                               ("neighbour pairs", lambda s: f"{s['pairs']:,}"),
                               ("skin [d]", lambda s: f"{s['skin']:g}")]))
    return "\n".join(text)


AT_ONCE = REPO / "benchmarks" / "results" / "full_scene_at_once.csv"


def side_by_side(results=AT_ONCE):
    """What the benchmark of runs side by side measured, as a clause: the throughput of two
    one-rank runs at once over one 2-rank run's, median and range over rounds ('' if not there)."""
    try:
        rows = list(csv.DictReader(open(results)))
    except OSError:
        return ""
    rate = {(r["variant"], r["round"]): float(r["particle_steps_per_s"]) for r in rows}
    ratios = sorted(rate[("2 at once", k)] / rate[("fast", k)] for v, k in rate if v == "2 at once" and ("fast", k) in rate)
    if not ratios:
        return ""
    return (f": on this machine two runs side by side, one rank each, had {float(np.median(ratios)):.2f} times "
            f"({ratios[0]:.2f}–{ratios[-1]:.2f} per round) the throughput of one after the other on 2 ranks "
            f"([benchmarks](../benchmarks.md#speed-of-the-full-drum), `{_shown(results)}`)")


def check_text(states, log=MAIN_JOB_LOG, steady=STEADY_BENCHMARK):
    """The model against what LIGGGHTS printed for the same state, where that is committed: a run
    from it (`log`: the same box and bead count; its `run 0` right after read_restart) and the
    steady-flow benchmark from the same file (`steady`.json names it; its neighbour pairs 5,000
    steps later). None if neither matches a state."""
    text = []
    counts = liggghts_counts(log) if Path(log).exists() else None
    for s in states if counts else []:
        box = np.array(s["box"]).T.ravel()  # xlo ylo zlo xhi yhi zhi, as LIGGGHTS prints it
        if not (np.allclose(counts["box"], box, atol=1e-6) and s["own"]["beads_mean"] == counts["Nlocal"][0]):
            continue
        own = s["own"]
        model = (own["beads_mean"], own["beads_max"], own["beads_min"], own["ghosts_mean"], own["ghosts_max"])
        seen = (*counts["Nlocal"], counts["Nghost"][0], counts["Nghost"][1])
        verdict = "identical" if all(abs(a - b) < 0.5 for a, b in zip(model, seen)) else "NOT identical"
        cut = s["median_y"] + OFFSET
        same_cut = counts["cut"] is not None and abs(cut - counts["cut"]) < 1e-9
        printed = (f"the cut drum.in printed for that state ({counts['cut']:.12f} m)" if same_cut else
                   f"NOT the cut drum.in printed ({counts['cut']})")
        text.append(f"`{_shown(log)}` is a run from the {s['rpm']} rpm state (the main job's shipped state; the "
                    f"same box). On the cut that state was written with ({own['grid']}, the box's middle) the model "
                    f"gives {own['beads_max']:,} / {own['beads_min']:,} beads (max / min) and "
                    f"{own['ghosts_mean']:,.1f} ghosts per rank on average, {own['ghosts_max']:,} at most; LIGGGHTS' "
                    f"`run 0` there printed Nlocal {counts['Nlocal'][1]:,.0f} / {counts['Nlocal'][2]:,.0f} and Nghost "
                    f"{counts['Nghost'][0]:,.1f} ave, {counts['Nghost'][1]:,.0f} max: {verdict}. The model's balanced "
                    f"cut on 2 ranks, y = {cut:.12f} m, is {printed}.")
    bench = _steady_neighbours(steady)
    for s in states if bench else []:
        if Path(s["file"]).read_bytes() != bench["restart"]:
            continue
        two = s["balanced_two"]
        text.append(f"Neighbour pairs: the steady-flow benchmark (`{_shown(steady)}.csv`) ran from the same file; "
                    f"5,000 steps later LIGGGHTS' lists held {bench['one']:,.0f} pairs on one rank and "
                    f"{bench['max']:,.0f} / {bench['min']:,.0f} on 2 balanced ranks (Neighs, max / min), where the "
                    f"model counts {two['serial_work']:,} and {two['work_max']:,} / {two['work_min']:,} on the state "
                    "itself.")
    return "\n\n".join(text) or None


def _shown(path):
    path = Path(path)
    return path.relative_to(REPO) if path.is_relative_to(REPO) else path


def _steady_neighbours(stem):
    """The steady-flow benchmark's start file (bytes) and its Neighs on 1 rank and on 2 (max, min)."""
    try:
        meta = json.loads(Path(f"{stem}.json").read_text())
        rows = list(csv.DictReader(open(f"{stem}.csv")))
        restart = (REPO / meta["restart"]).read_bytes()
        one = [r for r in rows if r["variant"] == "1 rank fast"][0]
        two = [r for r in rows if r["variant"] == "fast"][0]
    except (OSError, ValueError, KeyError, IndexError):
        return None
    return {"restart": restart, "one": float(one["neighs_max"]), "max": float(two["neighs_max"]),
            "min": float(two["neighs_min"])}


def main(argv=None):
    first, _, rest = __doc__.strip().partition("\n\n")
    p = argparse.ArgumentParser(description=" ".join(first.split()), epilog=rest,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--study", default="docs/drum/study_thesis",
                   help="the study whose committed end states to read (default: %(default)s)")
    p.add_argument("--rpm", default="7,21,42,63", help="speeds (default: %(default)s)")
    p.add_argument("--ranks", default="2,4,8,16", help="rank counts (default: %(default)s)")
    p.add_argument("--out", help="write the page (Markdown) here; else print the table")
    a = p.parse_args(argv)
    try:
        rpms = [int(v) for v in a.rpm.split(",")]
        ranks = [int(v) for v in a.ranks.split(",")]
    except ValueError:
        p.error("--rpm and --ranks take comma-separated integers")
    if 2 not in ranks or min(ranks) < 2:
        p.error("--ranks: 2 must be among them (the speed-ups are over 2 ranks), none below 2")
    study = Path(a.study)
    rows, states = study_rows(study if study.is_absolute() else REPO / study, rpms, ranks)
    if a.out:
        command = "tools/drum/rank_counts.py " + " ".join(argv if argv is not None else sys.argv[1:])
        Path(a.out).write_text(page(rows, states, command, a.study, check_text(states)))
    else:
        print(table(rows, COLUMNS))
    return rows, states


if __name__ == "__main__":
    main()
