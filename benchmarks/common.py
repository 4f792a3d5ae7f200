"""What the benchmarks share on top of tools/harness: the results directory and what a README
section reads from it, the stock constants and stability limits (from `contact_law`), drum windows
(from `drum_metrics`), LIGGGHTS' thermo output, and the machine the results were measured on.

Not a driver: every benchmark file (cost.py, accuracy.py, ...) imports it."""

import datetime
import os
import shlex
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
import harness  # noqa: E402

HERE = Path(__file__).resolve().parent
RESULTS = HERE / "results"
RPM = 21  # every benchmark drives the drum at the thesis' middle speed
# The drum's wall and skin these benchmarks' committed results were measured with (inputs/drum.in's
# defaults until the primitive cylinder and 0.3 d became them): explicit, so a rerun repeats them.
MESH = {"wall": "surface", "skin": 0.5}
# inputs/drum.in's defaults on 2026-11-22, when cost, accuracy, reductions, scaling, walls, peers and
# stability's plain drum rows were measured (the 6 mm slab from the grid at tc/10, the nominal law,
# snapshots every 0.02 s, the rank cut at the middle of the box, the mesh above; skin and balance
# came later with those values as their defaults). Several have changed since (the full scene from
# a shipped steady state at tc/5, exactRestitution auto, the cut at the beds' median): those
# benchmarks pass all of them, so a rerun repeats what was measured whatever drum.in's defaults are.
THEN = {**MESH, "period": 0.006, "dt": 1e-5, "exact": "off", "start": "grid", "dumpdt": 0.02, "balance": "off",
        "fill": 0.40, "segments": 180, "conventions": "thesis", "tangential": "history", "collision": "off",
        "model": "viscoelastic", "vrandom": 0.1, "seed": 15485863, "sort": 1000,
        # added since, at the values that keep what was measured then
        "bd_mu": -1, "bd_en": -1, "attraction": "auto", "facetmass": "auto", "history": "keep"}
# drum.in variables a benchmark run sets itself (or that THEN's start leaves unused)
PER_RUN = ("rpm", "rpm_end", "time", "name", "restart", "stock")


def then(**given):
    """drum.in -var values for a benchmark measured with THEN's defaults: THEN, overridden by `given`."""
    return {**THEN, **given}


def today():
    return datetime.datetime.now(datetime.timezone.utc).date().isoformat()


def tc():
    """Table 3.1's contact duration [s] (inputs/materials.in)."""
    return harness.materials()["bead_tc"]


def dt_of(ratio):
    """The timestep tc / ratio [s]."""
    return tc() / float(ratio)


def numbers(text):
    """A comma-separated option value as floats ("0.1,0.2" -> [0.1, 0.2])."""
    return [float(x) for x in str(text).split(",") if x]


def words(text):
    return [x for x in str(text).split(",") if x]


def fmt_list(values, last=", "):
    """[0.3, 0.56, 0.9] -> "0.3, 0.56, 0.9" (`last` joins the last two)."""
    text = [f"{v:g}" if isinstance(v, float) else str(v) for v in values]
    return last.join([", ".join(text[:-1]), text[-1]]) if len(text) > 1 else "".join(text)


def sci(x):
    """1e-4 as "1e-4" (Python's :g writes 0.0001 or 1e-06)."""
    mantissa, exponent = f"{x:e}".split("e")
    return f"{float(mantissa):g}e{int(exponent)}"


# --- the project's binaries ---------------------------------------------------------------------

def stock_file(path, uniform=None, exact_dt=None):
    """The stock hooke/stiffness constants (`contact_law stock`) in `path`: Table 3.1 with the thesis
    conventions, or en = et = `uniform` for every pair; with `exact_dt` the exactRestitution
    coefficients for that timestep."""
    args = ["stock"] + ([] if uniform is None else ["--uniform", uniform])
    args += [] if exact_dt is None else ["--exact", "--dt", f"{exact_dt:.10g}"]
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(harness.tool("contact_law", *args))
    return path


def limits(en, law="nominal", et=None):
    """`contact_law limit --en EN [--et ET] --law LAW`: {tc_s, en, et, binary_limit_s, guard_s,
    binary_limit_tc, guard_tc}, the guard on the coefficients LAW applies (et: en unless given)."""
    extra = ["--et", et] if et is not None else []
    return harness.read_csv_text(harness.tool("contact_law", "limit", "--en", en, *extra, "--law", law))[0]


def stiffening(en, fraction, law="nominal"):
    """`contact_law limit --en EN --at FRACTION --law LAW`: the stiffening Z for which the binary (Jury)
    limit of a contact Z times stiffer and more damped is dt = FRACTION tc (the guard's form), on the
    coefficients LAW applies at that dt."""
    return harness.read_csv_text(harness.tool("contact_law", "limit", "--en", en, "--at", fraction, "--law", law))[0][
        "stiffening_at"]


def window_average(prefix, dt, rpm=RPM, skip=None, until=None, after_first=False):
    """Time averages and their batch-means standard errors over a window of a run's snapshots
    (`drum_metrics series --average all`): the row of PREFIX_average.csv. `after_first`: skip the
    first snapshot (the shared start state of a continued run)."""
    if after_first:
        skip = (harness.snapshots(prefix)[0][0] + 0.5) * dt
    harness.drum_series(prefix, dt, rpm, skip=skip, until=until, average="all")
    return harness.read_csv(f"{prefix}_average.csv")[0]


def remove_snapshots(prefix):
    for _, f in harness.snapshots(prefix):
        f.unlink()


# --- LIGGGHTS logs ------------------------------------------------------------------------------

def guard_stopped(log):
    """Did the model's timestep guard stop the run?"""
    return "exceeds the stable timestep" in log.text


# --- results and README sections -----------------------------------------------------------------

class Results:
    """A results directory as a README section reads it; `readme` is the page's directory (image
    links are relative to it)."""

    def __init__(self, directory=RESULTS, readme=HERE):
        self.dir, self.readme = Path(directory), Path(readme)

    def path(self, name):
        return self.dir / name

    def has(self, *names):
        return all(self.path(n).exists() for n in names)

    def csv(self, name):
        return harness.read_csv(self.path(name))

    def json(self, name):
        return harness.read_json(self.path(name))

    def image(self, alt, name):
        return f"![{alt}]({os.path.relpath(self.path(name), self.readme)})\n"


def program_option(p, name, what):
    """--binary: a program of ours built in build/benchmarks (default build/benchmarks/NAME)."""
    p.add_argument("--binary", type=Path, default=harness.REPO / "build/benchmarks" / name,
                   help=f"{what} (default: build/benchmarks/{name})")


def require_program(path, build):
    """Stops with what to build when the program at `path` is missing (`build`: the CMake options)."""
    if not path.exists():
        raise harness.RunFailed(f"{path} missing: build with {build}")


def section_of(stem, name):
    """Decorator of a README section rendered as render(res, STEM.json, rows of STEM.csv); without
    those files the section says how to produce them (`benchmarks/run.py NAME`)."""
    def wrap(render):
        def section(res):
            if not res.has(stem + ".csv", stem + ".json"):
                return not_run(name)
            return render(res, res.json(stem + ".json"), res.csv(stem + ".csv"))
        return section
    return wrap


def pm(name, fmt, scale=1.0, error=None):
    """A Markdown cell getter: "value ± standard error" of column `name` (error column `error`,
    default NAME_err), both scaled and formatted with `fmt`."""
    error = error or name + "_err"
    return lambda r: f"{fmt.format(scale * r[name])} ± {fmt.format(scale * r[error])}"


def not_run(section):
    return f"Not run yet: `benchmarks/run.py {section}`.\n"


def sh(*commands):
    return "```sh\n" + "".join(c + "\n" for c in commands) + "```\n"


def command(script, **options):
    """`benchmarks/SCRIPT --name value ...` (None values left out, True as a bare flag)."""
    parts = [f"benchmarks/{script}"]
    for k, v in options.items():
        if v is None or v is False:
            continue
        parts.append("--" + k.replace("_", "-") + ("" if v is True else " " + shlex.quote(str(v))))
    return " ".join(parts)
