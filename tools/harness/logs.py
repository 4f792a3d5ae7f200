"""What a LIGGGHTS log says about the run: LAMMPS' timing summary of the last `run`."""

import re
from pathlib import Path

_LOOP = re.compile(r"^Loop time of (\S+) on (\d+) procs for (\d+) steps with (\d+) atoms", re.M)
_STAT = re.compile(r"^(Nlocal|Nghost|Neighs):\s+(\S+) ave (\S+) max (\S+) min", re.M)
_SECTION = re.compile(r"^(Pair|Neigh|Comm|Outpt|Other)\s+time \(%\) = (\S+) \((\S+)\)", re.M)


class Log:
    """The timing summary of the last run in a log (the earlier ones are set-up runs)."""

    def __init__(self, path, returncode=0):
        self.path = Path(path)
        self.returncode = returncode
        self.text = self.path.read_text(errors="replace")
        loops = list(_LOOP.finditer(self.text))
        self.has_loop = bool(loops)
        # (steps, loop seconds) of every run that stepped (set-up `run 0`s left out)
        self.runs = [(int(m.group(3)), float(m.group(1))) for m in loops if int(m.group(3)) > 0]
        if loops:
            last = loops[-1]
            self.loop_time = float(last.group(1))   # wall seconds of the stepping loop
            self.procs = int(last.group(2))
            self.steps = int(last.group(3))
            self.atoms = int(last.group(4))
            tail = self.text[last.end():]
            # per rank: (ave, max, min) beads, ghosts, neighbour pairs
            self.per_rank = {m.group(1): tuple(float(x) for x in m.group(2, 3, 4)) for m in _STAT.finditer(tail)}
            self.sections = {m.group(1): float(m.group(3)) for m in _SECTION.finditer(tail)}  # percent of loop
            builds = re.search(r"^Neighbor list builds = (\d+)", tail, re.M)
            self.neighbor_builds = int(builds.group(1)) if builds else None

    @property
    def particle_steps_per_s(self):
        return self.atoms * self.steps / self.loop_time

    @property
    def cpu_seconds(self):
        """Loop time times ranks: the CPU cost of the loop."""
        return self.loop_time * self.procs

    def thermo(self):
        """The last thermo row as {column: value} (under LIGGGHTS' `Step ...` header); {} if none."""
        header, row = None, {}
        for line in self.text.splitlines():
            w = line.split()
            if w and w[0] == "Step":
                header = w
            elif header and len(w) == len(header):
                try:
                    row = dict(zip(header, map(float, w)))
                except ValueError:
                    header = None
            elif line.startswith("Loop time"):
                header = None
        return row

    def grep(self, pattern, group=1, cast=str, default=None):
        """The first match of `pattern` (a regex with one group) in the log, cast; `default` if absent."""
        m = re.search(pattern, self.text, re.M)
        return cast(m.group(group)) if m else default
