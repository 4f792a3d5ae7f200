"""The drum study's plan: which runs and which metrics a study needs, what their files are
called, and which of them are already done. Pure logic (no runs, no file system except
through the callables passed in), shared by study.py (which does the work), collect.py
(which finds the files) and tests/harness/test_drum_drivers.py.

A study NAME keeps everything in post/NAME/:
  NAME_<rpm>rpm.*                 the speed chain: the slowest from the grid (time + settle),
                                  each faster one from the previous speed's end state (time)
  NAME_ramp_<from>_<to>.*         --ramp FROM:TO:SECONDS, from the FROM run's end state
  NAME_yade_<rpm>rpm.*            --yade RPM: YADE's conventions from the same state as the
                                  chain's RPM run (the speed before it), over --window's end
  {thesis,yade}_<rpm>rpm_window_* both runs' metrics over the same window after the speed change
  <run>.json                      written when a run has finished: its -var settings (the
                                  run counts as done only with this record and its restart file,
                                  and only if written after the record of the run it starts from)
  summary.{csv,md,png}            drum_metrics table of the chain
  study.json                      the study's settings and command (collect.py reads it)
"""

import math
from dataclasses import dataclass, field

# -var names the driver sets itself: a --var for them would be silently overridden or
# break the chain.
RESERVED = ("rpm", "rpm_end", "time", "start", "restart", "name", "period")


class PlanError(ValueError):
    """A bad option value; the message names the option."""


def parse_speeds(text, option="--speeds"):
    try:
        speeds = [int(s) for s in text.split(",")]
    except ValueError:
        raise PlanError(f"{option} {text}: expected integer rpm separated by commas, e.g. 7,14,21") from None
    if not speeds or any(s <= 0 for s in speeds):
        raise PlanError(f"{option} {text}: speeds must be positive")
    if speeds != sorted(set(speeds)):
        raise PlanError(f"{option} {text}: speeds must be ascending and distinct (each starts from the one before)")
    return speeds


def parse_ramp(text, speeds, option="--ramp"):
    """FROM:TO:SECONDS -> (from, to, seconds); FROM must be a speed of the chain."""
    parts = text.split(":")
    try:
        if len(parts) != 3:
            raise ValueError
        start, end, seconds = int(parts[0]), int(parts[1]), float(parts[2])
    except ValueError:
        raise PlanError(f"{option} {text}: expected FROM:TO:SECONDS, e.g. 21:28:3 (integer rpm)") from None
    if seconds <= 0 or end <= 0 or start == end:
        raise PlanError(f"{option} {text}: need SECONDS > 0 and TO != FROM, both positive")
    if start not in speeds:
        raise PlanError(f"{option} {text}: FROM {start} rpm is not in --speeds {','.join(map(str, speeds))} "
                        "(the ramp starts from that run's end state)")
    return start, end, seconds


def parse_window(text, option="--window"):
    """A:B seconds after the speed change -> (a, b)."""
    try:
        a, b = (float(x) for x in text.split(":"))
    except ValueError:
        raise PlanError(f"{option} {text}: expected A:B seconds after the speed change, e.g. 0.3:0.6") from None
    if not 0 <= a < b:
        raise PlanError(f"{option} {text}: need 0 <= A < B")
    return a, b


def parse_yade(rpm, speeds, time, window, option="--yade"):
    """The speed at which YADE's conventions are compared: a chain speed after the first
    (both runs start from the speed before it), long enough for the window."""
    if rpm not in speeds:
        raise PlanError(f"{option} {rpm}: not in --speeds {','.join(map(str, speeds))}")
    if rpm == speeds[0]:
        raise PlanError(f"{option} {rpm}: the slowest speed starts from the grid; compare at a faster one "
                        "(both runs start from the end state of the speed before)")
    if window[1] > time + 1e-12:
        raise PlanError(f"{option} {rpm}: --window ends {window[1]} s after the speed change, "
                        f"after the chain's run (--time {time})")
    return rpm


def parse_vars(pairs, option="--var"):
    """[(NAME, VALUE), ...] -> {NAME: VALUE}; the driver's own variables are refused."""
    out = {}
    for name, value in pairs or []:
        if name in RESERVED:
            raise PlanError(f"{option} {name} {value}: `{name}` is set by the driver "
                            f"(use its own option; reserved: {', '.join(RESERVED)})")
        out[name] = value
    return out


def speed_name(study, rpm):
    return f"{study}_{rpm}rpm"


def ramp_name(study, start, end):
    return f"{study}_ramp_{start}_{end}"


def yade_name(study, rpm):
    return f"{study}_yade_{rpm}rpm"


def window_name(conventions, rpm):
    return f"{conventions}_{rpm}rpm_window"


@dataclass
class Run:
    """One drum.in run: post/STUDY/NAME.* from `start_from`'s end state (None: the grid)."""
    name: str
    rpm: int
    variables: dict
    start_from: str = None
    t0: float = 0.0             # simulated time at its start [s]
    kind: str = "speed"         # speed | ramp | yade


@dataclass
class Series:
    """One `drum_metrics series` over the snapshots of run `reads`, to post/STUDY/OUT_*."""
    out: str
    reads: str
    rpm: int
    skip: float = None
    until: float = None
    average: str = None         # steady | all (drum_metrics' default: None)
    outputs: list = field(default_factory=list)

    def __post_init__(self):
        self.outputs = self.outputs or [f"{self.out}_metrics.csv", f"{self.out}_average.csv"]


def plan(study, speeds, time, settle, period, variables=None, ramp=None, yade=None, window=(0.3, 0.6)):
    """Runs and metrics of a study, in order. Variable values are strings, as on a command line."""
    variables = dict(variables or {})
    if yade is not None and variables.get("conventions", "thesis") != "thesis":
        raise PlanError(f"--yade {yade}: compares YADE's conventions with the thesis' ones; "
                        f"drop --var conventions {variables['conventions']}")
    runs, series = [], []
    previous, t0 = None, 0.0
    starts = {}
    for rpm in speeds:
        name = speed_name(study, rpm)
        duration = time + settle if previous is None else time
        v = {"period": period, "rpm": rpm, "time": _num(duration), "name": f"{study}/{name}", **variables}
        v.update({"start": "grid"} if previous is None else
                 {"start": "restart", "restart": f"post/{study}/{previous}.restart"})
        runs.append(Run(name, rpm, _strings(v), previous, round(t0, 9)))
        series.append(Series(name, name, rpm))
        starts[rpm] = (previous, t0)
        previous, t0 = name, t0 + duration
    if yade is not None:
        before, t_change = starts[yade]
        name = yade_name(study, yade)
        v = {"period": period, "rpm": yade, "time": _num(window[1]), "name": f"{study}/{name}", **variables,
             "conventions": "yade", "start": "restart", "restart": f"post/{study}/{before}.restart"}
        runs.append(Run(name, yade, _strings(v), before, round(t_change, 9), "yade"))
        skip, until = round(t_change + window[0], 9), round(t_change + window[1], 9)
        series.append(Series(window_name("yade", yade), name, yade, skip, until, "all"))
        series.append(Series(window_name("thesis", yade), speed_name(study, yade), yade, skip, until, "all"))
    if ramp is not None:
        start, end, seconds = ramp
        source = speed_name(study, start)
        name = ramp_name(study, start, end)
        source_run = next(r for r in runs if r.name == source)
        t_end = source_run.t0 + float(source_run.variables["time"])
        v = {"period": period, "rpm": start, "rpm_end": end, "time": _num(seconds), "name": f"{study}/{name}",
             **variables, "wall": "ramp", "start": "restart", "restart": f"post/{study}/{source}.restart"}
        runs.append(Run(name, start, _strings(v), source, round(t_end, 9), "ramp"))
        series.append(Series(name, name, start, average="all"))
    return runs, series


def decide(runs, series, record, mtime, force=False):
    """Which runs and metrics to (re)do. `record(name)`: the settings a finished run left
    (its NAME.json; None if absent); `mtime(file)`: when post/STUDY/file was written (None if
    absent).
    A run is redone when forced, when it has no record or restart file, or when the run it
    starts from is redone or finished after it (an earlier invocation redid it); a run whose
    record has other settings stops the study (rerun with --force or use another --name)
    rather than be overwritten or silently reused.
    Metrics are redone when the run they read is redone, or an output is missing or older
    than that run's record.
    Returns (set of run names, list of Series)."""
    redo = set()
    for run in runs:
        done = record(run.name)
        if done is not None and done != run.variables and not force:
            changed = sorted(k for k in set(done) | set(run.variables) if done.get(k) != run.variables.get(k))
            raise PlanError(f"{run.name} exists with other settings ({', '.join(changed)}): "
                            "--force reruns it, or choose another --name")
        stale = run.start_from and (mtime(run.start_from + ".json") or 0) > (mtime(run.name + ".json") or 0)
        if force or done is None or mtime(run.name + ".restart") is None or run.start_from in redo or stale:
            redo.add(run.name)

    def current(s):
        times = [mtime(f) for f in s.outputs]
        return None not in times and min(times) >= (mtime(s.reads + ".json") or 0)
    todo = [s for s in series if s.reads in redo or not current(s)]
    return redo, todo


def bands(times, rpms, start, end, width=1.0):
    """Snapshots of a ramp from `start` to `end` rpm grouped by drum speed: [(lo, hi, skip,
    until, count)] per band [lo, hi) of `width` rpm from the lower speed up (the top speed
    itself in the last band) that holds snapshots, with --skip/--until times halfway to the
    neighbouring snapshots (so no snapshot sits on a bound)."""
    bottom, top = min(start, end), max(start, end)
    last_band = max(math.ceil((top - bottom) / width - 1e-9) - 1, 0)
    pairs = sorted(zip(times, rpms))
    groups = []  # [band, first snapshot, last snapshot]
    for i, (t, r) in enumerate(pairs):
        k = min(max(math.floor((r - bottom) / width + 1e-9), 0), last_band)
        if groups and groups[-1][0] == k:
            groups[-1][2] = i
        else:
            groups.append([k, i, i])
    result = []
    for k, first, last in groups:
        lo, hi = bottom + k * width, min(bottom + (k + 1) * width, top)
        skip = (pairs[first - 1][0] + pairs[first][0]) / 2 if first > 0 else pairs[first][0] - 1.0
        until = (pairs[last][0] + pairs[last + 1][0]) / 2 if last + 1 < len(pairs) else pairs[last][0] + 1.0
        result.append((lo, hi, round(max(skip, 0.0), 9), round(until, 9), last - first + 1))
    return result


def _num(x):
    return f"{x:.10g}"


def _strings(v):
    return {k: x if isinstance(x, str) else _num(x) if isinstance(x, float) else str(x) for k, x in v.items()}
