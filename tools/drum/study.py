#!/usr/bin/python3
"""The thesis' drum speed study (section 3.4.2): the speed chain, optionally the speed ramp (Fig. 3.5-3.6) and YADE's conventions at one speed.

The slowest speed starts from beads on a grid and runs --time + --settle; each faster speed
runs --time from the previous speed's end state. For every run: drum.in under mpirun, then
`drum_metrics series`; at the end `drum_metrics table` of the chain (post/NAME/summary.*).
Everything goes to post/NAME/ (file names: tools/drum/chain.py). A run that has finished
(its restart file and its settings record NAME_<rpm>rpm.json exist) is skipped, and so are
metrics whose files exist: rerunning the same command resumes an interrupted study; --force
redoes everything. A run that exists with other settings stops the study.

  tools/drum/study.py --speeds 7,14,21,28,35,42 --time 1.2 --settle 0.8 --name sweep --yade 21
  tools/drum/study.py --speeds 42,49,56,63 --time 1.2 --settle 0.8 --name high
  tools/drum/study.py --speeds 21 --time 1.2 --settle 0.8 --ramp 21:28:3 --name ramp
  tools/drum/study.py --speeds 21,28 --time 0.04 --settle 0.02 --name tiny --var fill 0.05 --var dumpdt 0.01

--yade RPM adds the comparison of docs/drum/README.md: a run with YADE's conventions
(-var conventions yade) from the same state as the chain's RPM run (the end of the speed
before), --window's end long, and both runs' metrics averaged over the same --window after
the speed change (post/NAME/{yade,thesis}_<RPM>rpm_window_average.csv).
--ramp FROM:TO:SECONDS adds a run from the FROM speed's end state whose drum speed rises
linearly to TO over SECONDS (-var wall ramp); its metrics get each snapshot's speed from the
run's own record (NAME_ramp_FROM_TO_rpm.csv), and are averaged per 1 rpm band
(NAME_ramp_FROM_TO_bands.csv).
Run from anywhere; liggghts and drum_metrics from PATH or LIGGGHTS=..., DRUM_METRICS=....

Needs: python3-matplotlib (tools/harness), mpirun (openmpi-bin); liggghts, drum_metrics.
"""

import re
import shlex
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))
import harness  # noqa: E402
import chain  # noqa: E402

WHO = "study"


def arguments(argv=None):
    p = harness.options(__doc__, np=2)
    p.add_argument("--speeds", default="7,14,21,28,35,42,49,56,63", help="rpm, ascending (default: %(default)s)")
    p.add_argument("--time", type=float, default=2.0, help="simulated seconds per speed (default: %(default)s)")
    p.add_argument("--settle", type=float, default=1.0,
                   help="extra seconds for the slowest speed, to settle from the grid (default: %(default)s)")
    p.add_argument("--period", default="0.006", help="axial period [m]; 0.024: the thesis scene (default: %(default)s)")
    p.add_argument("--name", default="sweep", help="study name: everything goes to post/NAME/ (default: %(default)s)")
    p.add_argument("--ramp", metavar="FROM:TO:SECONDS", help="after the chain, ramp FROM -> TO rpm over SECONDS")
    p.add_argument("--yade", type=int, metavar="RPM", help="compare YADE's conventions at this speed of the chain")
    p.add_argument("--window", default="0.3:0.6", metavar="A:B",
                   help="--yade: average from A to B seconds after the speed change (default: %(default)s)")
    p.add_argument("--var", nargs=2, action="append", metavar=("NAME", "VALUE"), default=[],
                   help="a drum.in -var for every run (repeatable), e.g. --var dt 2e-5")
    p.add_argument("--force", action="store_true", help="redo every run and metric, even those that exist")
    p.add_argument("--dry-run", action="store_true", help="print what would run, run nothing")
    args = p.parse_args(argv)
    try:
        args.speeds = chain.parse_speeds(args.speeds)
        args.ramp = chain.parse_ramp(args.ramp, args.speeds) if args.ramp else None
        args.window = chain.parse_window(args.window)
        if args.yade is not None:
            chain.parse_yade(args.yade, args.speeds, args.time, args.window)
        args.variables = chain.parse_vars(args.var)
        if args.time <= 0 or args.settle < 0:
            raise chain.PlanError(f"--time {args.time} --settle {args.settle}: need --time > 0, --settle >= 0")
    except chain.PlanError as e:
        p.error(str(e))
    return args


def drum_default(name):
    """The default of drum.in's `variable NAME index VALUE` (e.g. dt, to turn dump steps into times)."""
    text = (harness.REPO / "inputs" / "drum.in").read_text()
    m = re.search(rf"^variable\s+{re.escape(name)}\s+index\s+(\S+)", text, re.M)
    if not m:
        raise harness.RunFailed(f"inputs/drum.in has no `variable {name} index ...`")
    return m.group(1)


class Study:
    def __init__(self, args):
        self.args = args
        self.dir = harness.REPO / "post" / args.name
        self.dt = args.variables.get("dt") or drum_default("dt")
        self.runs, self.series = chain.plan(args.name, args.speeds, args.time, args.settle, args.period,
                                            args.variables, args.ramp, args.yade, args.window)

    def path(self, name):
        return self.dir / name

    def record(self, name):
        p = self.path(name + ".json")
        return harness.read_json(p)["variables"] if p.exists() else None

    def mtime(self, name):
        p = self.path(name)
        return p.stat().st_mtime if p.exists() else None

    def run(self, run, number):
        harness.say(WHO, f"{run.name} ({number}/{len(self.runs)}): {run.kind} at {run.rpm} rpm, "
                         f"{run.variables['time']} s from {run.start_from or 'the grid'}, {self.args.np} ranks ...")
        # a rerun's snapshots must not mix with an earlier run's (drum_metrics reads PREFIX_<step>.vtp)
        for old in [*self.dir.glob(run.name + "_*"), *(self.path(run.name + x) for x in (".json", ".restart"))]:
            old.unlink(missing_ok=True)
        log = harness.drum(self.path(run.name + ".log"), np=self.args.np, **run.variables)
        harness.write_json(self.path(run.name + ".json"),
                           {"variables": run.variables, "loop_time_s": log.loop_time, "steps": log.steps,
                            "beads": log.atoms, "ranks": log.procs, "t0_s": run.t0})
        return log

    def metrics(self, s):
        # snapshot times are step * dt: widen the bounds by a nanosecond so one on a bound counts
        text = harness.drum_series(self.path(s.reads), self.dt, s.rpm, out=self.path(s.out),
                                   skip=None if s.skip is None else f"{s.skip - 1e-9:.10g}",
                                   until=None if s.until is None else f"{s.until + 1e-9:.10g}",
                                   average=s.average or None)
        self.path(s.out + "_metrics.txt").write_text(text)

    def ramp_bands(self, run):
        """The ramp's snapshots with the drum speed the run recorded (interpolated to the
        snapshot's time), and drum_metrics' averages per 1 rpm band. The record's time starts
        at 0 with the run (LIGGGHTS resets `time` at read_restart), its first row one print
        interval later; the snapshots' time is step * dt."""
        import numpy
        record = harness.read_csv(self.path(run.name + "_run.csv"))
        rows = harness.read_csv(self.path(run.name + "_metrics.csv"))
        times = [run.t0] + [run.t0 + r["time"] for r in record]
        speeds = [run.rpm] + [r["rpm"] for r in record]
        for row in rows:
            row["rpm"] = float(numpy.interp(row["time_s"], times, speeds))
        harness.write_csv(self.path(run.name + "_rpm.csv"), rows)
        table = []
        for lo, hi, skip, until, count in chain.bands([r["time_s"] for r in rows], [r["rpm"] for r in rows],
                                                          run.rpm, int(run.variables["rpm_end"])):
            if count < 2:
                harness.say(WHO, f"{run.name}: {lo:g}-{hi:g} rpm holds {count} snapshot, no average")
                continue
            out = f"{run.name}_band_{lo:g}"
            self.metrics(chain.Series(out, run.name, run.rpm, skip, until, "all"))
            table.append({"rpm_from": lo, "rpm_to": hi, **harness.read_csv(self.path(out + "_average.csv"))[0]})
        harness.write_csv(self.path(run.name + "_bands.csv"), table, None if table else ["rpm_from", "rpm_to"])

    def main(self):
        args = self.args
        redo, todo = chain.decide(self.runs, self.series, self.record, self.mtime, args.force)
        if args.ramp:
            ramp = self.runs[-1].name
            if not self.path(ramp + "_bands.csv").exists() and not any(s.reads == ramp for s in todo):
                todo.append(next(s for s in self.series if s.reads == ramp))
        for run in self.runs:
            what = [s.out for s in todo if s.reads == run.name]
            harness.say(WHO, f"plan: {run.name}: {'run' if run.name in redo else 'done'}"
                             f"{', metrics ' + ' '.join(what) if what else ''}")
        if args.dry_run:
            return 0
        self.dir.mkdir(parents=True, exist_ok=True)
        command = "tools/drum/study.py " + shlex.join(sys.argv[1:])
        harness.write_json(self.path("study.json"), {
            "command": command, "speeds": args.speeds, "time": args.time, "settle": args.settle,
            "period": args.period, "ramp": args.ramp, "yade": args.yade, "window": args.window,
            "variables": args.variables, "dt": self.dt, "np": args.np})
        started = time.monotonic()
        for number, run in enumerate(self.runs, 1):
            begin = time.monotonic()
            log = self.run(run, number) if run.name in redo else None
            for s in [s for s in todo if s.reads == run.name]:
                self.metrics(s)
                if run.kind == "ramp":
                    self.ramp_bands(run)
            if log or any(s.reads == run.name for s in todo):
                loop = f" (LIGGGHTS loop {log.loop_time:.1f} s, {log.atoms} beads)" if log else ""
                harness.say(WHO, f"{run.name} done in {time.monotonic() - begin:.1f} s{loop}")
            else:
                harness.say(WHO, f"{run.name}: exists, skipped (--force redoes it)")
        averages = [self.path(r.name + "_average.csv") for r in self.runs if r.kind == "speed"]
        harness.tool("drum_metrics", "table", "--out", self.path("summary"), *averages)
        harness.say(WHO, f"wrote {self.path('summary')}.{{csv,md,png}}; {len(redo)} runs in "
                         f"{time.monotonic() - started:.1f} s")
        return 0


def main(argv=None):
    args = arguments(argv)
    try:
        return Study(args).main()
    except (harness.RunFailed, chain.PlanError, OSError) as e:
        harness.say(WHO, f"ERROR: {e}")
        return 1


if __name__ == "__main__":
    sys.exit(main())
