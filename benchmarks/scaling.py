#!/usr/bin/python3
"""Parallel runs of the drum from one settled state (--restart) on each of --ranks MPI ranks,
interleaved over --rounds (1 2 4 1 2 4 ...), with the beads each rank held (LIGGGHTS' Nlocal
statistics) and the parallel efficiency t(1) / (n t(n)) per round (median). Ranks beyond the cores
are oversubscribed and say nothing about efficiency; they check that the decomposition runs.
The README section: the full thesis drum (24 mm state of reductions.py) and a projection of the
thesis' speed sweep from the best rate.
Writes OUT/scaling.csv (one row per run) and OUT/scaling.json.

Needs: python3-matplotlib (tools/harness), mpirun; liggghts."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
import harness  # noqa: E402
import common  # noqa: E402

# The thesis' speed sweep and what it cost there (YADE 1.12, thesis section 3.4: "about 22 days in
# real-time to simulate about 21.8x10^6 timesteps (26 s virtual time)" per speed, 16 cores): facts
THESIS_SPEEDS, THESIS_STEPS_PER_SPEED, THESIS_DAYS_PER_SPEED, THESIS_CORES = 9, 21.8e6, 22, 16


def parser():
    p = harness.options(__doc__, out=common.RESULTS, rounds=2, restart=None)
    p.add_argument("--ranks", default="1,2,4", help="MPI ranks (default: 1,2,4)")
    p.add_argument("--time", type=float, default=0.05, help="simulated s per run (default: 0.05)")
    p.add_argument("--period", type=float, default=0.006, help="axial period of the state [m] (default: 0.006)")
    return p


def run(args):
    ranks = [int(n) for n in common.numbers(args.ranks)]

    def on(n):
        tag = f"scaling/np{n}"
        return lambda: harness.drum(harness.post(tag + ".log"), np=n, **common.then(
            period=args.period, rpm=common.RPM, dt=common.dt_of(10), time=args.time, dumpdt=1000, start="restart",
            restart=args.restart, name=tag))

    logs = harness.interleaved({n: on(n) for n in ranks}, args.rounds, progress=lambda s: harness.say("scaling", s))
    rows = [{"ranks": n, "round": i + 1, "loop_seconds": lg.loop_time, "steps": lg.steps, "atoms": lg.atoms,
             "nlocal_ave": lg.per_rank["Nlocal"][0], "nlocal_max": lg.per_rank["Nlocal"][1],
             "nlocal_min": lg.per_rank["Nlocal"][2]}
            for i in range(args.rounds) for n in ranks for lg in [logs[n][i]]]
    harness.write_csv(Path(args.out) / "scaling.csv", rows)
    harness.write_json(Path(args.out) / "scaling.json", {"restart": str(args.restart), "time_s": args.time,
                                                          "rounds": args.rounds, "period_m": args.period,
                                                          "cores": harness.machine()["cores"], "date": common.today(),
                                                          "generator": "benchmarks/scaling.py"})


def per_ranks(rows, cores):
    """One row per rank count: median loop time, rate, beads per rank, median efficiency t(1)/(n t(n))."""
    one = {r["round"]: r["loop_seconds"] for r in rows if r["ranks"] == 1}
    table = []
    for n in sorted({int(r["ranks"]) for r in rows}):
        runs = [r for r in rows if r["ranks"] == n]
        t = harness.median([r["loop_seconds"] for r in runs])
        table.append({"ranks": n, "loop": t, "psps": runs[0]["atoms"] * runs[0]["steps"] / t,
                      "beads": " / ".join(f"{runs[0][k]:.0f}" for k in ("nlocal_ave", "nlocal_max", "nlocal_min")),
                      "efficiency": f"{harness.median([one[r['round']] / (n * r['loop_seconds']) for r in runs]):.2f}"
                                    + (" (oversubscribed)" if n > cores else "")})
    return table


def days_or_hours(seconds):
    return f"{seconds / 86400:.1f} days" if seconds >= 86400 else f"{seconds / 3600:.1f} h"


def projection(best, thesis_beads, span):
    """The thesis' sweep at the best measured rate, like for like: its beads and its simulated time
    per speed, at its dt and at ours."""
    m = harness.materials()
    thesis_ratio = round(m["bead_tc"] / m["thesis_dt"])
    simulated = THESIS_STEPS_PER_SPEED * m["thesis_dt"]
    text = (f"Projection of the thesis sweep ({THESIS_SPEEDS} speeds × {simulated:.1f} s simulated, the thesis' "
            f"{THESIS_STEPS_PER_SPEED:.3g} steps at its dt, {thesis_beads:,} beads as in the thesis) "
            f"at the {best['ranks']}-rank rate ({best['psps']:.3g} particle-steps/s):\n\n")
    rows = []
    for name, dt in ((f"tc/{thesis_ratio} (thesis, {1e6 * m['thesis_dt']:.3g} µs)", m["thesis_dt"]),
                     ("tc/10", common.dt_of(10)), ("tc/5 with exactRestitution", common.dt_of(5))):
        steps = simulated / dt
        rows.append({"dt": name, "steps": steps, "speed": thesis_beads * steps / best["psps"]})
    text += harness.markdown(rows, [("dt", "dt", None), ("steps per speed", "steps", "{:.3g}"),
                                    ("wall time per speed", lambda r: days_or_hours(r["speed"]), None),
                                    (f"sweep of {THESIS_SPEEDS} speeds",
                                     lambda r: days_or_hours(THESIS_SPEEDS * r["speed"]), None)])
    return text + (
        f"\nThe thesis: {THESIS_DAYS_PER_SPEED} days per speed on {THESIS_CORES} cores with YADE 1.12 at tc/{thesis_ratio}, "
        f"about {round(THESIS_SPEEDS * THESIS_DAYS_PER_SPEED, -2):.0f} days for the sweep; here "
        f"{THESIS_DAYS_PER_SPEED * 86400 / rows[0]['speed']:.1f}× less wall time per speed at this run's rate and "
        f"settings, like for like (the same steps, beads and dt), on {THESIS_CORES / best['ranks']:g}× fewer cores "
        f"(the study's settings, measured in the next section, run faster). (Projected from {span:g} s runs of "
        "the settled bed, whose grid fill holds fewer beads: the rate is per particle-step; long runs "
        "add output and neighbour-list rebuilds.)\n")


@common.section_of("scaling", "scaling")
def section(res, m, rows):
    table = per_ranks(rows, m["cores"])
    best = max(table, key=lambda r: r["ranks"] if r["ranks"] <= m["cores"] else 0)
    beads, thesis = int(rows[0]["atoms"]), int(harness.materials()["thesis_beads"])
    ranks = [r["ranks"] for r in table]
    return (
        f"The thesis scene ({1e3 * m['period_m']:.0f} mm period; the grid fill holds {beads:,} of the {thesis:,} beads, "
        f"{100 * (thesis - beads) / thesis:.1f} % fewer, see\n"
        f"the top-level README) settled by section 6's run, continued at {common.RPM} rpm and dt = tc/10 on "
        f"{common.fmt_list(ranks, ' and ')} MPI\n"
        f"ranks, interleaved ({' '.join(map(str, ranks * 2))} ...), LIGGGHTS loop time; beads per rank from LIGGGHTS' "
        "Nlocal statistics. These are the settings before the levers of the next section (the drum as a "
        "mesh,\nthe ranks cut at the box's middle, a 1.5 mm skin); the study's settings are measured there, "
        "in steady flow\nand at the thesis' tc/81 (\"Neighbour skin at the thesis' tc/81\").\n\n"
        f"From `{m['restart']}` at {common.RPM} rpm, {m['time_s']:g} s simulated, {m['rounds']} interleaved rounds;\n"
        f"generated by `{m['generator']}` on {m['date']} ({m['cores']} cores).\n\n"
        + harness.markdown(table, [("ranks", "ranks", None), ("loop time [s] (median)", "loop", "{:.1f}"),
                                   ("particle-steps/s", "psps", "{:.3g}"),
                                   ("beads per rank (ave / max / min)", "beads", None),
                                   ("efficiency t(1)/(n t(n))", "efficiency", None)])
        + "\n" + projection(best, thesis, m["time_s"]) + "\n"
        + common.sh(common.command("scaling.py", restart=m["restart"], period=m["period_m"],
                                   ranks=",".join(map(str, ranks)), rounds=m["rounds"], time=m["time_s"])))


if __name__ == "__main__":
    run(parser().parse_args())
