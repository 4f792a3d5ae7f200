#!/usr/bin/python3
"""Scene reduction by axial period: the drum at 21 rpm from the grid with each --periods period
(6, 12, 24 mm: 16,336 / 32,672 / 65,344 beads), the same protocol for each; the metrics averaged
over [--skip, --time] (`drum_metrics series --average all`, batch-means standard errors). Cost
per simulated second: --rounds rounds of --span s runs from each period's end state, the periods
interleaved, median. --cost-only re-times the end states of earlier runs.
The runs stay in post/reduce/: their restarts feed peers.py (12 mm) and scaling.py (24 mm).
Writes OUT/reductions.csv (one row per period) and OUT/reductions.json.

Needs: python3-matplotlib (tools/harness), mpirun; liggghts, drum_metrics."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
import harness  # noqa: E402
import common  # noqa: E402

# (drum_metrics column, header, scale to the unit, format)
METRICS = (("Hh_m", "Hh [mm]", 1e3), ("Hd_m", "Hd [mm]", 1e3), ("Hc_m", "Hc [mm]", 1e3))
COMPARED = ("Hc_m", "Hd_m", "angle_deg")  # the columns the σ distances are of


def parser():
    p = harness.options(__doc__, np=2, out=common.RESULTS, rounds=5)
    p.add_argument("--periods", default="0.006,0.012,0.024", help="axial periods [m] (default: 0.006,0.012,0.024)")
    p.add_argument("--time", type=float, default=1.0, help="simulated s from the grid (default: 1.0)")
    p.add_argument("--skip", type=float, default=0.5, help="average from this time [s] (default: 0.5)")
    p.add_argument("--span", type=float, default=0.003, help="simulated s per timed run (default: 0.003)")
    p.add_argument("--cost-only", action="store_true", help="only re-time the end states of earlier runs")
    return p


def state(period):
    """post/reduce/drum_L<mm>: the run's prefix, and its restart with .restart."""
    return f"reduce/drum_L{round(period * 1000)}"


def run(args):
    periods = common.numbers(args.periods)
    dt = common.dt_of(10)
    averages = {}
    for p in periods:
        name = state(p)
        if not args.cost_only:
            harness.say("reductions", f"{p * 1e3:g} mm period, {args.time} s from the grid ...")
            harness.drum(harness.post(name + ".log"), np=args.np,
                         **common.then(period=p, rpm=common.RPM, dt=dt, time=args.time, name=name))
        averages[p] = common.window_average(harness.post(name), dt, skip=args.skip)
    logs = harness.interleaved(
        {p: (lambda p=p: harness.drum(harness.post(f"reduce/time_L{round(p * 1000)}.log"), np=args.np, **common.then(
            period=p, rpm=common.RPM, dt=dt, time=args.span, dumpdt=1, start="restart",
            restart=harness.post(state(p) + ".restart"), name=f"reduce/time_L{round(p * 1000)}")))
         for p in periods}, args.rounds, progress=lambda s: harness.say("reductions", "timing " + s))
    rows = []
    for p in periods:
        loop = harness.median([lg.loop_time for lg in logs[p]])
        rows.append({"period_m": p, "loop_s_median": loop, "cpu_s_per_simulated_s": loop * args.np / args.span, **averages[p]})
    harness.write_csv(Path(args.out) / "reductions.csv", rows)
    harness.write_json(Path(args.out) / "reductions.json", {"time_s": args.time, "skip_s": args.skip, "ranks": args.np,
                                                            "rounds": args.rounds, "span_s": args.span,
                                                            "standard_error": "batch means", "date": common.today()})


def sigmas(row, full):
    """Distances of a period's Hc, Hd and angle from the full scene's, in combined standard errors."""
    se = {m["column"]: m["se_column"] for m in harness.drum_metric_table()}
    return [(row[k] - full[k]) / (row[se[k]] ** 2 + full[se[k]] ** 2) ** 0.5 for k in COMPARED]


def verdict(rows, full):
    close = [r for r in rows if r is not full and all(abs(s) <= 2 for s in sigmas(r, full))]
    if close:
        r = min(close, key=lambda r: r["period_m"])
        return (f"**The smallest scene within 2 σ of the full one: the {1e3 * r['period_m']:.0f} mm period** "
                f"({r['cpu_s_per_simulated_s'] / full['cpu_s_per_simulated_s']:.2f}× its cost).\n")
    biases = "; ".join(f"{1e3 * r['period_m']:.0f} mm: Hc {1e3 * (r['Hc_m'] - full['Hc_m']):+.1f} mm, angle "
                       f"{r['angle_deg'] - full['angle_deg']:+.1f}°" for r in rows if r is not full)
    gain = full["cpu_s_per_simulated_s"] / min(r["cpu_s_per_simulated_s"] for r in rows)
    return (f"**No reduced period stays within 2 σ of the full {1e3 * full['period_m']:.0f} mm scene** in this protocol: "
            f"the narrower the slab, the lower and flatter the bed ({biases}). The 6 mm slab (`-var period 0.006`, "
            f"for tests and quick trials) buys its {gain:.1f}× lower cost with that bias; runs meant for comparison "
            f"with the thesis need the {1e3 * full['period_m']:.0f} mm period, the input's default.\n")


@common.section_of("reductions", "reductions")
def section(res, m, rows):
    full = max(rows, key=lambda r: r["period_m"])
    plateau = all(r["steady_from_s"] != r["steady_from_s"] for r in rows)  # nan: MSER found no steady start
    mm = f"{1e3 * full['period_m']:.0f} mm"
    return (
        f"The same protocol at each axial period: the drum from the grid at {common.RPM} rpm for {m['time_s']:g} s, the "
        "metrics averaged\n"
        f"over {m['skip_s']:g}-{m['time_s']:g} s ({rows[0]['snapshots']:.0f} snapshots; ± standard error). Cost: CPU seconds "
        f"(loop time × {m['ranks']} MPI ranks) per\n"
        f"simulated second, median of {m['rounds']} rounds of {m['span_s']:g} s runs from each period's end state, the "
        "periods\n"
        f"interleaved. Difference to {mm} in units of the combined\n"
        "standard error. One run per period, so σ is the standard error of the time average, not a run-to-run\n"
        f"scatter; and {m['time_s']:g} s from the grid is not yet steady"
        + (" (the detector finds no plateau)" if plateau else "") + ": the comparison is\n"
        "between beds on the same schedule, not between steady states.\n\n"
        + harness.markdown(rows, [
            ("period [mm]", lambda r: 1e3 * r["period_m"], "{:.0f}"), ("beads", "beads", "{:.0f}"),
            ("CPU s / simulated s", "cpu_s_per_simulated_s", "{:.0f}")]
            + [(header, common.pm(key, "{:.1f}", scale, key.replace("_m", "_se_m")), None) for key, header, scale in METRICS]
            + [("angle [deg]", common.pm("angle_deg", "{:.1f}", error="angle_se_deg"), None),
               ("tangential force [mN]", common.pm("drum_force_N", "{:.1f}", 1e3, "drum_force_se_N"), None),
               (f"Hc, Hd, angle vs {mm} [σ]",
                lambda r: "reference" if r is full else ", ".join(f"{s:+.1f}" for s in sigmas(r, full)), None)])
        + "\n" + verdict(rows, full) + "\n" + common.sh(common.command("reductions.py")))


if __name__ == "__main__":
    run(parser().parse_args())
