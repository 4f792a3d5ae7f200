#!/usr/bin/python3
"""Draws the charts of the C++ tools (collide, drum_metrics) from the CSV files they write, in the
one style of tools/harness/charts.py, every axis in SI units or the unit it states.

  plot.py KIND CSV PNG [--title TEXT] [options]

KIND, one per chart (the command that writes its CSV):
  sweep-dt     `collide sweep-dt`: the |relative error| of the restitution (LIGGGHTS, and the
               recurrence's prediction, dashed), of the contact duration and, for an oblique
               impact, of the tangential restitution against tc/dt, log-log
               (--tangential auto: drawn where that error is non-zero)
  sweep-angle  `collide sweep-angle`: tangential restitution, rebound spin [rad/s] and rebound
               angle [deg] against the incidence angle [deg], three panels; LIGGGHTS' points on
               the reference's line, drawn from --reference (default CSV.reference.csv, which
               collide writes with --png; without it, or empty, the reference's columns of CSV)
  law-map      `collide law-map`: the continuous law's tangential restitution against the
               incidence angle [deg], one line per friction coefficient, the requested et dashed
  drum-series  `drum_metrics series` (OUT_metrics.csv): one panel per metric against time [s];
               --steady-from T marks where the steady state starts
  drum-table   `drum_metrics table` (OUT.csv): one panel per metric against the drum speed [rpm],
               its standard error as error bars
A drum panel's axis is --label COLUMN=TEXT (drum_metrics passes its metric table's label and
unit), else the column's key and unit (Hc_m: "Hc [m]"). A usage error (an unknown KIND, a
missing argument) is one line and exit status 2; a CSV that cannot be drawn, one line and 1.

Needs: python3-matplotlib (tools/harness).
"""

import argparse
import math
import sys
import textwrap
from pathlib import Path

# tools/harness beside this file: in the source tree (tools/) and where it is installed
# (share/liggghts_viscoelastic/python/)
sys.path.insert(0, str(Path(__file__).resolve().parent))
from harness import charts  # noqa: E402
from harness.tables import read_csv  # noqa: E402

PANEL = (6.5, 4.5)  # inches, charts.figure's default
DRUM_PANEL = (5.0, 3.4)
DRUM_COLUMNS = 3


class Usage(argparse.ArgumentParser):
    """A usage error as the project's tools report one: `plot.py: WHAT; see plot.py --help`, exit 2."""

    def error(self, message):
        sys.stderr.write(f"plot.py: {' '.join(message.split())}; see plot.py --help\n")
        sys.exit(2)


class Unplottable(Exception):
    """A CSV that is not the chart's: one line, exit status 1."""


def finite(x):
    return isinstance(x, float) and math.isfinite(x)


def column(rows, name, path):
    if rows and name not in rows[0]:
        raise Unplottable(f"{path} has no column {name} (columns: {', '.join(rows[0])})")
    return [r[name] for r in rows]


def load(path):
    rows = read_csv(path)
    if not rows:
        raise Unplottable(f"{path}: no rows")
    return rows


def figure(rows, cols, title, size=PANEL):
    """charts.figure with the title wrapped to the figure's width."""
    width = int(9.5 * cols * size[0])
    return charts.figure(rows, cols, textwrap.fill(title, width) if title else None, size)


def unit_of(col):
    """A drum column's axis text from its name, <key>_<unit> ('/' written 'p'): Hc_m -> 'Hc [m]'."""
    key, _, tag = col.rpartition("_")
    return f"{key} [{tag.replace('p', '/')}]" if key else col


# ---- collide ---------------------------------------------------------------------------------

def sweep_dt(a):
    rows = sorted(load(a.csv), key=lambda r: r["tc_over_dt"])
    x = column(rows, "tc_over_dt", a.csv)
    err = column(rows, "restitution_rel_err", a.csv)
    # the reference's restitution, from LIGGGHTS' and its relative error
    ref = [e / (1.0 + d) for e, d in zip(column(rows, "restitution", a.csv), err)]
    predicted = [p / r - 1.0 for p, r in zip(column(rows, "predicted_restitution", a.csv), ref)]
    tangential = column(rows, "tangential_rel_err", a.csv)
    fig, (ax,) = figure(1, 1, a.title or f"collide sweep-dt: {Path(a.csv).name}")
    drawn = 0

    def curve(values, label, **style):
        nonlocal drawn
        points = [(u, abs(v)) for u, v in zip(x, values) if finite(v) and v != 0.0]
        if points:
            ax.plot(*zip(*points), label=label, **style)
            drawn += 1

    curve(err, "restitution (LIGGGHTS)", marker="o", lw=2)
    curve(predicted, "restitution (predicted recurrence)", ls="--", lw=1.5)
    curve(column(rows, "duration_rel_err", a.csv), "contact duration", marker="o", lw=2)
    if a.tangential == "on" or (a.tangential == "auto" and any(finite(v) and v != 0.0 for v in tangential)):
        curve(tangential, "tangential restitution", marker="o", lw=2)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("tc / dt [1]")
    ax.set_ylabel("|relative error| [1]")
    if drawn:
        ax.legend(fontsize=8)
    else:
        ax.text(0.5, 0.5, "no non-zero error", transform=ax.transAxes, ha="center")
    return fig


def sweep_angle(a):
    rows = sorted(load(a.csv), key=lambda r: r["angle"])
    reference = Path(a.reference) if a.reference else Path(a.csv + ".reference.csv")
    # (a reference file without rows: angles outside 1-89 deg, where collide draws it)
    fine = sorted(read_csv(reference), key=lambda r: r["angle"]) if (a.reference or reference.is_file()) else None
    fig, axes = figure(1, 3, a.title or f"collide sweep-angle: {Path(a.csv).name}")
    panels = [("tangential restitution [1]", "tangential_restitution", "tangential_restitution"),
              ("rebound spin [rad/s]", "spin", "spin"),
              ("rebound angle [deg]", "rebound_angle", "rebound_angle")]
    angles = column(rows, "angle", a.csv)
    for ax, (label, fine_column, coarse) in zip(axes, panels):
        if fine:
            ax.plot(column(fine, "angle", reference), column(fine, fine_column, reference), lw=2, label="reference")
        else:
            ax.plot(angles, column(rows, coarse + "_ref", a.csv), lw=2, label="reference")
        ax.plot(angles, column(rows, coarse + "_liggghts", a.csv), "o", ms=6, label="LIGGGHTS")
        ax.set_xlabel("incidence angle from the normal [deg]")
        ax.set_ylabel(label)
        ax.legend(fontsize=8)
    return fig


def law_map(a):
    rows = load(a.csv)
    column(rows, "tangential_restitution", a.csv)
    mus = list(dict.fromkeys(column(rows, "mu", a.csv)))  # in the file's order
    fig, (ax,) = figure(1, 1, a.title or f"collide law-map: {Path(a.csv).name}")
    for mu in mus:
        line = sorted((r["angle"], r["tangential_restitution"]) for r in rows if r["mu"] == mu)
        ax.plot(*zip(*line), marker="o", lw=2, label=f"μ = {mu:g}")
    for k, et in enumerate(dict.fromkeys(column(rows, "requested_et", a.csv))):
        ax.axhline(et, ls="--", color="black", lw=1, label="requested et" if k == 0 else None)
    ax.set_xlabel("incidence angle from the normal [deg]")
    ax.set_ylabel("tangential restitution [1]")
    ax.legend(fontsize=8, loc="lower left")
    return fig


# ---- drum_metrics ----------------------------------------------------------------------------

def metric_panels(a, rows, columns, x, xlabel, se=None):
    """One panel per metric column against column `x`, with its standard-error column `se(c)` as
    error bars if given; a metric without a finite value says so."""
    if not columns:
        raise Unplottable(f"{a.csv}: no metric columns")
    labels = dict(a.label)
    n = len(columns)
    fig, axes = figure((n + DRUM_COLUMNS - 1) // DRUM_COLUMNS, DRUM_COLUMNS, a.title, DRUM_PANEL)
    xs = column(rows, x, a.csv)
    for ax, c in zip(axes, columns):
        ys = column(rows, c, a.csv)
        ax.set_xlabel(xlabel)
        ax.set_ylabel(labels.get(c, unit_of(c)), fontsize=9)
        if not any(finite(y) for y in ys):
            ax.text(0.5, 0.5, "no values", transform=ax.transAxes, ha="center", va="center")
            continue
        if se:
            ax.errorbar(xs, ys, yerr=[abs(e) if finite(e) else 0.0 for e in column(rows, se(c), a.csv)],
                        marker="o", ms=4, lw=1.5, capsize=3)
            ax.margins(0.05, 0.1)
        else:
            ax.plot(xs, ys, lw=1)
        if a.steady_from is not None:  # a mark, not data: the axis stays the data's
            limits = ax.get_xlim()
            ax.axvline(a.steady_from, ls="--", color="black", lw=1)
            ax.set_xlim(limits)
    for ax in axes[n:]:
        ax.set_visible(False)
    return fig


def se_column(c):
    key, _, unit = c.rpartition("_")
    return f"{key}_se_{unit}"


def drum_series(a):
    rows = sorted(load(a.csv), key=lambda r: r["time_s"])
    columns = [c for c in rows[0] if c not in ("time_s", "beads", "wall_contacts")]
    a.title = a.title or Path(a.csv).stem
    return metric_panels(a, rows, columns, "time_s", "time [s]")


def drum_table(a):
    rows = sorted(load(a.csv), key=lambda r: r["rpm"])
    names = list(rows[0])
    columns = [c for c in names if "_se_" not in c and se_column(c) in names]
    a.title = a.title or "time-averaged drum metrics against speed (error bars: standard error)"
    return metric_panels(a, rows, columns, "rpm", "drum speed [rpm]", se=se_column)


KINDS = {"sweep-dt": sweep_dt, "sweep-angle": sweep_angle, "law-map": law_map,
         "drum-series": drum_series, "drum-table": drum_table}


def label(text):
    col, sep, shown = text.partition("=")
    if not sep or not col:
        raise argparse.ArgumentTypeError(f"expected COLUMN=TEXT, got '{text}'")
    return col, shown


def kind(text):
    if text not in KINDS:
        raise argparse.ArgumentTypeError(f"'{text}' is not a chart: one of {', '.join(KINDS)}")
    return text


def main(argv=None):
    p = Usage(prog="plot.py", description=__doc__.split("\n\n")[0],
              formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__.split("\n\n", 1)[1])
    p.add_argument("kind", type=kind, metavar="KIND", help=", ".join(KINDS))
    p.add_argument("csv", metavar="CSV", help="the tool's CSV file")
    p.add_argument("png", metavar="PNG", help="the chart to write")
    p.add_argument("--title", help="the chart's title (default: the kind and the CSV's name)")
    p.add_argument("--tangential", choices=["auto", "on", "off"], default="auto",
                   help="sweep-dt: draw the tangential restitution's error (default: auto)")
    p.add_argument("--reference", help="sweep-angle: the reference on a fine grid (default: CSV.reference.csv)")
    p.add_argument("--steady-from", type=float, metavar="T", help="drum-series: the steady state's start [s]")
    p.add_argument("--label", type=label, action="append", default=[], metavar="COLUMN=TEXT",
                   help="drum-series, drum-table: a metric's axis label (repeatable)")
    a = p.parse_args(argv)
    try:
        fig = KINDS[a.kind](a)
        charts.save(fig, a.png)
    except (Unplottable, OSError, KeyError, TypeError, ValueError, ZeroDivisionError) as e:
        sys.stderr.write(f"plot.py: {a.kind} {a.csv} -> {a.png}: {' '.join(str(e).split())}\n")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
