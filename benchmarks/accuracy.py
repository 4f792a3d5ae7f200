#!/usr/bin/python3
"""Accuracy against cost, dt = tc/5 ... tc/81 (the thesis' 1.23 us).

  cost   CPU seconds per simulated second of the drum: the settled slab continued for --span
         simulated seconds at each dt, loop time x ranks / span; --rounds rounds, the dts
         interleaved, median. exactRestitution only changes the coefficients computed at init:
         its cost per step is the nominal one at the same dt.
  error  1. the head-on collision of two Table 3.1 beads (`collide sweep-dt`, 128 start phases):
         restitution and duration error against the requested en and tc, nominal coefficients
         (= stock hooke/stiffness given them: identical forces, see cost.py) and exactRestitution;
         2. drum metrics: the slab continued for --window s from the same state at each dt
         (snapshots every --snapshot-dt), Hc, Hd and the angle of repose averaged over the window
         (`drum_metrics series --average all`, batch-means standard errors); drift = difference to
         the finest nominal dt.
Writes OUT/accuracy_cost.csv (one row per dt and mode) and OUT/accuracy_cost.json.

Needs: python3-matplotlib (tools/harness), mpirun; liggghts, drum_metrics, collide."""

import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
import harness  # noqa: E402
import common  # noqa: E402
import cost  # noqa: E402

# (column prefix of accuracy_cost.csv, drum_metrics column, its standard error, scale to the unit)
METRICS = (("Hc_mm", "Hc_m", "Hc_se_m", 1e3), ("Hd_mm", "Hd_m", "Hd_se_m", 1e3),
           ("angle_deg", "angle_deg", "angle_se_deg", 1.0))
PHASES = 128
TARGET = 0.005  # accuracy target of the like-for-like headline: mean two-body restitution error
THESIS, THESIS_DT = "the thesis' ", ", the thesis' dt"  # said of tc/81


def parser():
    p = harness.options(__doc__, np=2, out=common.RESULTS, rounds=5, restart=None)
    p.add_argument("--ratios", default="5,10,20,40,81", help="tc/dt, nominal (default: 5,10,20,40,81)")
    p.add_argument("--exact-ratios", default="5,10,20", help="tc/dt with exactRestitution (default: 5,10,20)")
    p.add_argument("--span", type=float, default=0.01, help="simulated s per timed run (default: 0.01)")
    p.add_argument("--window", type=float, default=0.2, help="simulated s of the drum window (default: 0.2)")
    p.add_argument("--snapshot-dt", type=float, default=0.005, help="s between window snapshots (default: 0.005)")
    return p


def two_body(ratios, exact):
    m = harness.materials()
    path = harness.post(f"accuracy/twobody_exact_{exact}.csv")
    harness.tool("collide", "sweep-dt", "--geometry", "pair", "--en", m["bead_en"], "--et", m["bead_et"],
                 "--ratios", *ratios, "--phases", PHASES, "--exact-restitution", exact, "--csv", path)
    return {r["tc_over_dt"]: r for r in harness.read_csv(path)}


def run(args):
    ratios, exact_ratios = common.numbers(args.ratios), common.numbers(args.exact_ratios)
    two = {mode: two_body(ratios, mode) for mode in ("off", "on")}

    def drum(tag, ratio, **v):
        return harness.drum(harness.post(f"accuracy/{tag}.log"), np=args.np, **common.then(
            start="restart", restart=args.restart, rpm=common.RPM, dt=common.dt_of(ratio), name=f"accuracy/{tag}", **v))

    logs = harness.interleaved({r: (lambda r=r: drum(f"time_{r:g}", r, time=args.span, dumpdt=1)) for r in ratios},
                               args.rounds, progress=lambda s: harness.say("accuracy", "timing " + s))
    windows = {}
    for r, exact in [(r, "off") for r in ratios] + [(r, "on") for r in exact_ratios]:
        tag = f"window_{r:g}_{exact}"
        harness.say("accuracy", f"drum window {args.window} s at tc/{r:g}, exactRestitution {exact} ...")
        common.remove_snapshots(harness.post(f"accuracy/{tag}"))
        drum(tag, r, exact=exact, time=args.window, dumpdt=args.snapshot_dt)
        windows[r, exact] = common.window_average(harness.post(f"accuracy/{tag}"), common.dt_of(r), after_first=True)

    ref = windows[max(ratios), "off"]
    rows = []
    for exact in ("off", "on"):
        for r in sorted(x for x, e in windows if e == exact):
            w, loop, dt, t = windows[r, exact], harness.median([lg.loop_time for lg in logs[r]]), common.dt_of(r), two[exact][r]
            row = {"tc_over_dt": r, "exact": exact, "dt": dt, "cpu_s_per_simulated_s": loop * args.np / args.span,
                   "particle_steps_per_s": logs[r][0].atoms * (args.span / dt) / loop,
                   "restitution_err": t["restitution_rel_err"], "duration_err_steps": t["duration_err_steps"]}
            for name, key, se, scale in METRICS:
                row.update({name: w[key] * scale, name + "_err": w[se] * scale, name + "_drift": (w[key] - ref[key]) * scale})
            rows.append(row)
    harness.write_csv(Path(args.out) / "accuracy_cost.csv", rows)
    harness.write_json(Path(args.out) / "accuracy_cost.json", {
        "beads": logs[ratios[0]][0].atoms, "ranks": args.np, "rounds": args.rounds, "span_s": args.span,
        "window_s": args.window, "snapshot_dt_s": args.snapshot_dt, "phases": PHASES, "restart": str(args.restart),
        "standard_error": "batch means", "date": common.today()})


def thesis(ratio, text):
    """`text` if tc/ratio is the thesis' timestep (inputs/materials.in), else nothing."""
    m = harness.materials()
    return text if round(m["bead_tc"] / m["thesis_dt"]) == ratio else ""


def within(row, ref):
    """Every drum drift within twice the combined standard error of the two window averages."""
    return all(abs(row[n + "_drift"]) <= 2 * math.hypot(row[n + "_err"], ref[n + "_err"]) for n, _, _, _ in METRICS)


def findings(rows, stock):
    """The bullet list under the table: coarsest dt within the scatter, and the cost at equal two-body error."""
    finest = max(r["tc_over_dt"] for r in rows)
    ref = next(r for r in rows if r["exact"] == "off" and r["tc_over_dt"] == finest)
    text = ""
    for mode, name in (("off", "nominal"), ("on", "exactRestitution on")):
        ok = [r for r in rows if r["exact"] == mode and within(r, ref)]
        if ok:
            r = min(ok, key=lambda r: r["tc_over_dt"])
            text += (f"- {name}: the drum metrics stay within twice their standard error of the tc/{finest:g} reference "
                     f"down to **tc/{r['tc_over_dt']:g}** (coarsest such dt measured); two-body restitution error "
                     f"there {100 * r['restitution_err']:+.2f} %.\n")
    exact = [r for r in rows if r["exact"] == "on"]
    if exact:
        c = min(exact, key=lambda r: r["tc_over_dt"])
        e = abs(c["restitution_err"])
        nominal = sorted((r for r in rows if r["exact"] == "off"), key=lambda r: r["tc_over_dt"])
        match = [r for r in nominal if abs(r["restitution_err"]) <= max(e, 1e-9)]
        m = match[0] if match else nominal[-1]
        speedup = stock * m["cpu_s_per_simulated_s"] / c["cpu_s_per_simulated_s"]
        # the headline, like for like: one accuracy target, the cheapest run of each that meets it
        reach = [r for r in nominal if abs(r["restitution_err"]) <= TARGET]
        if reach:
            t = reach[0]
            # the same code at both settings: the ratio needs no cost ratio against stock
            same = t["cpu_s_per_simulated_s"] / c["cpu_s_per_simulated_s"]
            text += (f"- Same accuracy target (mean two-body restitution error ≤ {100 * TARGET:g} %), same scene: the "
                     f"coarsest nominal dt that meets it is tc/{t['tc_over_dt']:g} ({100 * t['restitution_err']:+.2f} %, "
                     f"{t['cpu_s_per_simulated_s']:.0f} CPU s per simulated s), exactRestitution meets it at "
                     f"tc/{c['tc_over_dt']:g} ({c['cpu_s_per_simulated_s']:.0f}): **{same:.1f}×** less CPU time, the "
                     f"same code at both settings. Stock hooke/stiffness computes the same forces (section 1); times "
                     f"section 1's stock/ours cost ratio ({stock:.2f}, the median of noisy rounds; section 5 "
                     f"measures it on the full scene) that is {stock * same:.1f}× against stock.\n")
        if match:
            text += (f"- Equal two-body error: exactRestitution at tc/{c['tc_over_dt']:g} ({100 * e:.3f} %) against "
                     f"stock at tc/{m['tc_over_dt']:g} ({100 * abs(m['restitution_err']):.3f} %): {speedup:.1f}× faster.\n")
        else:
            text += (f"- (Not a like-for-like figure: exactRestitution at tc/{c['tc_over_dt']:g} has {100 * e:.3f} %, which "
                     f"stock does not reach in this range: {100 * abs(m['restitution_err']):.2f} % at tc/{m['tc_over_dt']:g}"
                     f"{thesis(m['tc_over_dt'], THESIS_DT)}, {speedup:.1f}× the cost of exactRestitution at tc/{c['tc_over_dt']:g}.)\n")
    return text


def chart(rows, stock, path, meta):
    fig, (a, b) = harness.figure(1, 2)
    off = sorted((r for r in rows if r["exact"] == "off"), key=lambda r: r["tc_over_dt"])
    on = sorted((r for r in rows if r["exact"] == "on"), key=lambda r: r["tc_over_dt"])
    cost_of = lambda rs, k=1.0: [k * r["cpu_s_per_simulated_s"] for r in rs]  # noqa: E731
    err = lambda rs, floor=0.0: [max(100 * abs(r["restitution_err"]), floor) for r in rs]  # noqa: E731
    a.plot(cost_of(off), err(off), "o-", label="viscoelastic, nominal")
    a.plot(cost_of(off, stock), err(off), "o--", mfc="none", label="stock hooke/stiffness (same forces)")
    a.plot(cost_of(on), err(on, 1e-4), "s-", label="viscoelastic, exactRestitution on (below 1e-4 %: drawn at 1e-4)")
    for r in off:
        a.annotate(f"tc/{r['tc_over_dt']:g}", (r["cpu_s_per_simulated_s"], 100 * abs(r["restitution_err"])),
                   textcoords="offset points", xytext=(0, 6), ha="center", fontsize=8)
    a.set(title=f"head-on collision, en = {harness.materials()['bead_en']:g} ({meta['phases']} start phases)",
          ylabel="|restitution error| [%]")
    finest = off[-1]
    for (name, _, _, _), colour, label in zip(METRICS, ("C0", "C1", "C2"), ("Hc", "Hd", "angle")):
        drifted = [r for r in off if r is not finest]
        b.plot(cost_of(drifted), [abs(r[name + "_drift"]) for r in drifted], "o-", color=colour, label=f"{label}, nominal")
        b.plot(cost_of(on), [abs(r[name + "_drift"]) for r in on], "s--", color=colour, label=f"{label}, exact")
        # twice the combined standard error of two window averages of the reference's size: the scatter
        b.axhline(2 * math.hypot(finest[name + "_err"], finest[name + "_err"]), color=colour, ls=":",
                  label=f"scatter (2 sigma): {label}")
    b.set(title=f"drum ({common.RPM} rpm): drift of window averages against the finest nominal dt",
          ylabel="|drift|: Hc, Hd [mm]; angle of repose [deg]")
    for ax in (a, b):
        ax.set(xscale="log", yscale="log", xlabel=f"cost: CPU seconds per simulated second of the drum ({meta['beads']:,} beads)")
        ax.legend(fontsize=7)
    harness.save(fig, path)


@common.section_of("accuracy_cost", "accuracy")
def section(res, m, rows):
    stock = cost.stock_over_ours(res)
    chart(rows, stock, res.path("accuracy_cost.png"), m)
    finest = max(r["tc_over_dt"] for r in rows)
    naive = m["standard_error"] != "batch means"
    return (
        f"Cost: the settled 6 mm slab ({m['beads']:,} beads, {common.RPM} rpm, {m['ranks']} MPI ranks) continued at each "
        f"dt, median of {m['rounds']}\n"
        "interleaved rounds, in CPU seconds (loop time × ranks) per simulated second. Errors: the head-on\n"
        "collision against the requested en (restitution) and tc (duration, in steps), and the drum metrics\n"
        f"averaged over a window continued from the same state at each dt (snapshots every {1e3 * m['snapshot_dt_s']:g} ms), "
        "as drift\n"
        f"against the finest nominal dt (tc/{finest:g}, {thesis(finest, THESIS)}{1e6 * common.dt_of(finest):.3g} µs). "
        "Stock "
        "hooke/stiffness given our\n"
        "constants computes the same forces (section 1), so its errors are the nominal ones and its cost the\n"
        f"nominal cost × {stock:.3f} (section 1's stock/ours ratio). `exactRestitution` only changes\n"
        "the coefficients computed at init: its cost per step is the nominal one."
        + ("\nThe ± of these committed windows are naive standard errors of the snapshots; a rerun gives\n"
           "batch-means errors (`drum_metrics series`)." if naive else "") + "\n\n"
        + res.image("accuracy against cost", "accuracy_cost.png") + "\n"
        + harness.markdown(rows, [
            ("tc/dt", "tc_over_dt", "{:g}"), ("exactRestitution", "exact", None),
            ("CPU s / simulated s", "cpu_s_per_simulated_s", "{:.0f}"), ("particle-steps/s", "particle_steps_per_s", "{:.3g}"),
            ("restitution error", lambda r: 100 * r["restitution_err"], "{:+.3f} %"),
            ("duration error [steps]", "duration_err_steps", "{:+.2f}"),
        ] + [column for name, label in (("Hc_mm", "Hc [mm]"), ("Hd_mm", "Hd [mm]"), ("angle_deg", "angle [deg]"))
             for column in ((label, common.pm(name, "{:.2f}"), None),
                            (label.split()[0] + " drift", name + "_drift", "{:+.2f}"))])
        + "\n" + findings(rows, stock) + "\n"
        + common.sh(common.command("accuracy.py", restart=m["restart"])))


if __name__ == "__main__":
    run(parser().parse_args())
