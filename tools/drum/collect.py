#!/usr/bin/python3
"""Regenerates docs/drum/reduced_scene.md and docs/drum/speeds_and_ramp.md (the first, transient runs on the
6 mm slab, superseded by the thesis-scale studies) from those studies in post/.

Inputs (made by tools/drum/study.py; each study's settings and command from post/NAME/study.json;
they ran with drum.in's defaults then, which `V` below repeats: V = --var dt 1e-5 --var exact off
--var dumpdt 0.02 --var balance off --var wall surface --var skin 0.5, as `THEN` in benchmarks/common.py):
  post/SWEEP/   the speed chain with --yade RPM, e.g.
                tools/drum/study.py --speeds 7,14,21,28,35,42 --time 1.2 --settle 0.8 --name sweep --yade 21 V
  post/HIGH/    the faster speeds:  tools/drum/study.py --speeds 42,49,56,63 --time 1.2 --settle 0.8 --name high V
  post/RAMP/    the ramp:           tools/drum/study.py --speeds 21 --time 1.2 --settle 0.8 --ramp 21:28:3 --name ramp V
The drum wall study and the parallel runs are benchmarks (benchmarks/walls.py, scaling.py):
benchmarks/README.md shows them; the documents here link to it.
Tables are read from the studies' *_average.csv by column name; the chart of all speeds is
`drum_metrics table`'s, the ramp's chart is drawn here, the picture is ParaView's
(xvfb-run -a pvbatch tools/drum/render.py). Texts: tools/drum/templates/*.md.in.
A missing input stops the collection before anything is written, listing every missing
file; --allow-missing writes the documents with those sections marked as not collected.

Needs: python3-matplotlib (tools/harness); drum_metrics; pvbatch and xvfb-run (paraview, xvfb) for the picture.
"""

import math
import shlex
import shutil
import string
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))
import harness  # noqa: E402
import chain  # noqa: E402

WHO = "collect"
TEMPLATES = Path(__file__).resolve().parent / "templates"

def metrics():
    """The metrics tables' columns: (header, value column, standard error column), from the
    metric table of `drum_metrics metrics`."""
    return [(f"{m['label']} [{m['unit']}]", m["column"], m["se_column"]) for m in harness.drum_metric_table()]


def pm(value, se):
    """value ± standard error, both to the decimal of the error's second significant digit."""
    if not isinstance(value, float) or math.isnan(value):
        return "–"
    if not isinstance(se, float) or math.isnan(se) or se <= 0:
        return f"{value:.4g}"
    decimals = max(0, 1 - math.floor(math.log10(se)))
    return f"{value:.{decimals}f} ± {se:.{decimals}f}"


def steady(value):
    """steady_from_s: the time from which the metrics stopped drifting; NaN/empty: not steady."""
    return f"{value:g}" if isinstance(value, float) and not math.isnan(value) else "not steady: last half"


def metric_columns(rows):
    """The metrics present in `rows`, as harness.markdown columns."""
    return [(h, (lambda r, v=v, s=s: pm(r[v], r.get(s))), None) for h, v, s in metrics()
            if rows and all(v in r for r in rows)]


def speed_table(rows):
    columns = [("rpm", lambda r: f"{r['rpm']:g}", None), ("beads", lambda r: f"{r['beads']:.0f}", None),
               ("steady from [s]", lambda r: steady(r["steady_from_s"]), None),
               ("snapshots averaged", lambda r: f"{r['snapshots']:.0f}", None)]
    return harness.markdown(rows, columns + metric_columns(rows))


def span(rows, to=" to "):
    """'42 to 63 rpm' of rows sorted by speed."""
    if not rows:
        return "none"
    ends = sorted({f"{rows[0]['rpm']:g}", f"{rows[-1]['rpm']:g}"}, key=float)
    return to.join(ends) + " rpm"


def merge_speeds(first, second):
    """Rows of two chains, by speed; a speed in both is taken from `first`."""
    have = {r["rpm"] for r in first}
    return sorted(first + [r for r in second if r["rpm"] not in have], key=lambda r: r["rpm"])


class Collector:
    def __init__(self, args, command):
        self.args = args
        self.command = command
        self.missing = []
        self.copies = []     # (source, name in --out)
        self.actions = []    # callables run after every input was found

    def need(self, path):
        path = Path(path)
        if not path.exists():
            self.missing.append(path)
            return None
        return path

    def copy(self, source, name=None, optional=False):
        if source.exists():
            self.copies.append((source, name or source.name))
        elif not optional:
            self.missing.append(source)

    def study(self, name):
        """(settings, post/NAME/) of a study; settings None when it has no study.json."""
        directory = harness.REPO / "post" / name
        p = self.need(directory / "study.json")
        return (harness.read_json(p) if p else None), directory

    def averages(self, directory, names):
        files = [self.need(directory / (n + "_average.csv")) for n in names]
        return [harness.read_csv(f)[0] for f in files if f]

    def absent(self, what):
        return f"*(not collected: {what} missing)*"

    # ---- docs/drum/reduced_scene.md ------------------------------------------------------------
    def readme(self):
        a = self.args
        s, d = self.study(a.sweep)
        v = {"note": harness.generated_note(self.command), "sweep": a.sweep}
        v["sweep_command"] = s["command"] if s else f"# post/{a.sweep}/study.json missing"
        if s:
            rows = self.averages(d, [chain.speed_name(a.sweep, r) for r in s["speeds"]])
            v["summary_table"] = speed_table(rows) if rows else self.absent("the sweep's averages")
            for f in ("summary.csv", "summary.png"):
                self.copy(d / f)
            for r in s["speeds"]:
                self.copy(d / (chain.speed_name(a.sweep, r) + "_metrics.txt"))
                self.copy(d / (chain.speed_name(a.sweep, r) + "_metrics.png"), optional=True)
        else:
            v["summary_table"] = self.absent(f"post/{a.sweep}/study.json")
        v.update(self.yade(s, d))
        rpm = a.picture
        prefix = d / chain.speed_name(a.sweep, rpm)
        picture = f"drum_{rpm}rpm.png"
        v.update(picture_rpm=rpm, picture=picture,
                 render_command=f"xvfb-run -a pvbatch tools/drum/render.py {rel(prefix)}")
        if self.need(prefix.with_name(prefix.name + ".restart")):
            self.actions.append(lambda: harness.render(prefix, a.out / picture, "--size", 900))
        return v

    def yade(self, s, d):
        rpm = s and s.get("yade")
        if not rpm:
            return {k: "–" for k in ("yade_rpm", "yade_from", "yade_run", "window", "skip", "until")} | {
                "yade_table": self.absent(f"a sweep run with --yade (post/{self.args.sweep}/study.json)")}
        runs, series = chain.plan(self.args.sweep, s["speeds"], s["time"], s["settle"], s["period"],
                                  s["variables"], yade=rpm, window=tuple(s["window"]))
        run = next(r for r in runs if r.kind == "yade")
        window = next(x for x in series if x.out == chain.window_name("yade", rpm))
        rows = []
        for conventions in ("thesis", "yade"):
            p = self.need(d / (chain.window_name(conventions, rpm) + "_average.csv"))
            if p:
                rows.append({"conventions": conventions, **harness.read_csv(p)[0]})
        before = s["speeds"][s["speeds"].index(rpm) - 1]
        return {"yade_rpm": rpm, "yade_from": f"{before} rpm", "yade_run": run.name,
                "window": f"{s['window'][0]:g}–{s['window'][1]:g} s", "skip": f"{window.skip:g}",
                "until": f"{window.until:g}",
                "yade_table": harness.markdown(rows, [("conventions", "conventions", None)] + metric_columns(rows))
                if len(rows) == 2 else self.absent("the window averages")}

    # ---- docs/drum/speeds_and_ramp.md ----------------------------------------------------
    def speeds_and_ramp(self, scratch):
        a = self.args
        v = {"note": harness.generated_note(self.command)}
        sweep, sweep_dir = self.study(a.sweep)
        high, high_dir = self.study(a.high)
        v["high_command"] = high["command"] if high else f"# post/{a.high}/study.json missing"
        high_names = [chain.speed_name(a.high, r) for r in high["speeds"]] if high else []
        sweep_names = [chain.speed_name(a.sweep, r) for r in sweep["speeds"]] if sweep else []
        high_rows = self.averages(high_dir, high_names)
        sweep_rows = self.averages(sweep_dir, sweep_names)
        v["high_table"] = speed_table(high_rows) if high_rows else self.absent(f"post/{a.high}/*_average.csv")
        rows = merge_speeds(sweep_rows, high_rows)
        v["all_table"] = speed_table(rows) if rows else self.absent("the averages")
        v["all_sources"] = self.sources(sweep_rows, high_rows)
        v["high_span"] = span(high_rows)
        if high:
            self.copy(high_dir / "summary.csv", "summary_high.csv")
            for n in high_names:
                self.copy(high_dir / (n + "_metrics.txt"))
        if rows:
            from_sweep = {r["rpm"] for r in sweep_rows}
            files = [sweep_dir / (chain.speed_name(a.sweep, int(r["rpm"])) + "_average.csv") if r["rpm"] in from_sweep
                     else high_dir / (chain.speed_name(a.high, int(r["rpm"])) + "_average.csv") for r in rows]
            out = scratch / "summary_all"
            self.actions.append(lambda: harness.tool("drum_metrics", "table", "--out", out, *files))
            self.copies += [(out.with_suffix(".csv"), "summary_all.csv"), (out.with_suffix(".png"), "summary_all.png")]
        v.update(self.ramp())
        return v

    @staticmethod
    def sources(sweep_rows, high_rows):
        own = [r for r in high_rows if r["rpm"] not in {s["rpm"] for s in sweep_rows}]
        return (f"{span(sweep_rows, '–')} from the chain started at {sweep_rows[0]['rpm']:g} rpm "
                f"(`summary.csv`), {span(own, '–')} from the chain above" if sweep_rows else span(own, '–'))

    def ramp(self):
        a = self.args
        s, d = self.study(a.ramp)
        if not s or not s.get("ramp"):
            return {"ramp_command": f"# post/{a.ramp}/study.json with --ramp missing", "ramp_png": "", "ramp_span": "",
                    "ramp_metrics_csv": "", "band_table": self.absent(f"a --ramp study post/{a.ramp}")}
        start, end, seconds = s["ramp"]
        name = chain.ramp_name(a.ramp, start, end)
        doc = f"ramp_{start}_{end}"
        v = {"ramp_command": s["command"], "ramp_png": doc + ".png", "ramp_metrics_csv": doc + "_metrics.csv",
             "ramp_span": f"{start} → {end} rpm"}
        self.copy(d / (name + "_run.csv"), doc + "_run.csv")
        self.copy(d / (name + "_rpm.csv"), doc + "_metrics.csv")
        self.copy(d / (name + "_metrics.txt"), doc + "_metrics.txt")
        bands = self.need(d / (name + "_bands.csv"))
        record, series = self.need(d / (name + "_run.csv")), self.need(d / (name + "_rpm.csv"))
        if bands:
            rows = harness.read_csv(bands)
            columns = [("rpm", lambda r: f"{r['rpm_from']:g}–{r['rpm_to']:g}", None),
                       ("snapshots", lambda r: f"{r['snapshots']:.0f}", None),
                       ("drum force per touching bead [mN]",
                        lambda r: pm(1e3 * r["drum_force_N"], 1e3 * r["drum_force_se_N"]), None),
                       ("centre of mass Hc [m]", lambda r: pm(r["Hc_m"], r["Hc_se_m"]), None)]
            v["band_table"] = harness.markdown(rows, columns)
        else:
            v["band_table"] = self.absent(f"post/{a.ramp}/{name}_bands.csv")
        if record and series:
            title = (f"speed ramp {start} -> {end} rpm over {seconds:g} s "
                     f"(period {s['period']} m, dt {s['dt']} s)")
            self.actions.append(lambda: ramp_chart(record, series, a.out / (doc + ".png"), title))
        return v


def ramp_chart(record, series, png, title, smooth=9):
    """Fig. 3.5 and 3.6: centre of mass (the run's own record) and drum force (the snapshots'
    metrics) against the drum speed."""
    import numpy
    run = harness.read_csv(record)
    snaps = harness.read_csv(series)
    fig, (left, right) = harness.figure(1, 2, title=title)
    left.plot([r["rpm"] for r in run], [r["centre_of_mass"] for r in run], lw=2)
    left.set(xlabel="drum speed [rpm]", ylabel="centre of mass Hc above the axis [m]", title="Fig. 3.5: centre of mass")
    rpm = numpy.array([r["rpm"] for r in snaps])
    force = numpy.array([r["drum_force_N"] for r in snaps])
    right.plot(rpm, force, "o", ms=3, color="grey", label="snapshots")
    if len(force) >= smooth:
        kernel = numpy.ones(smooth) / smooth
        right.plot(numpy.convolve(rpm, kernel, "valid"), numpy.convolve(force, kernel, "valid"), lw=2,
                   color="darkred", label=f"moving average of {smooth}")
    right.legend()
    right.set(xlabel="drum speed [rpm]", ylabel="mean drum force along its motion per touching bead [N]",
              title="Fig. 3.6: drum tangential force")
    harness.save(fig, png)


def rel(path):
    """A path as the documents and messages show it: from the repository root if inside it."""
    path = Path(path)
    return str(path.relative_to(harness.REPO)) if path.is_relative_to(harness.REPO) else str(path)


def fill(template, values):
    values = {k: str(v).rstrip("\n") if k != "note" else v for k, v in values.items()}
    return string.Template((TEMPLATES / template).read_text()).substitute(values)


def main(argv=None):
    p = harness.options(__doc__, out=Path("docs/drum"))
    p.add_argument("--sweep", default="sweep", help="study of the speed chain, with --yade (default: %(default)s)")
    p.add_argument("--high", default="high", help="study of the faster speeds (default: %(default)s)")
    p.add_argument("--ramp", default="ramp", help="study with --ramp (default: %(default)s)")
    p.add_argument("--picture", type=int, default=21, help="the sweep's speed ParaView renders (default: %(default)s)")
    p.add_argument("--allow-missing", action="store_true", help="write the documents even if inputs are missing")
    argv = sys.argv[1:] if argv is None else argv
    args = p.parse_args(argv)
    args.out = harness.REPO / args.out
    c = Collector(args, shlex.join(["tools/drum/collect.py", *argv]))
    with tempfile.TemporaryDirectory() as scratch:
        readme = c.readme()
        ramp = c.speeds_and_ramp(Path(scratch))
        missing = sorted({rel(m) for m in c.missing})
        if missing and not args.allow_missing:
            harness.say(WHO, "ERROR: missing inputs (nothing written; --allow-missing writes what there is):\n  "
                        + "\n  ".join(missing))
            return 1
        for m in missing:
            harness.say(WHO, f"missing, not collected: {m}")
        args.out.mkdir(parents=True, exist_ok=True)
        try:
            for action in c.actions:
                action()
        except harness.RunFailed as e:
            harness.say(WHO, f"ERROR: {e}")
            return 1
        for source, name in c.copies:
            if source.exists():
                shutil.copyfile(source, args.out / name)
        for doc, values in (("reduced_scene.md", readme), ("speeds_and_ramp.md", ramp)):
            (args.out / doc).write_text(fill(doc + ".in", values))
            harness.say(WHO, f"wrote {args.out / doc}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
