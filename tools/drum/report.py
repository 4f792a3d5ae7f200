#!/usr/bin/python3
"""A drum study's report from its table alone (docs/drum/NAME.csv, which tools/drum/steady.py
writes as speeds finish): docs/drum/NAME.md with each speed's averages and standard errors, the
thesis' findings beside what the averages show (a change between two speeds counts where it
exceeds twice the combined standard error), and the cost beside the thesis' Table 3.2; and
docs/drum/NAME.png, the metrics against speed shaped like Fig. 3.2-3.4 (Hh, Hd, Hc) with the
angle of repose, the drum force and the cost. steady.py rewrites both after each speed.

The time to the target: the stop rule (`drum_metrics steady`, the study's targets) replayed on
each finished speed's committed series where the study's driver checks it (after each segment):
when would the averages first have met the target standard errors with 3 batches (with and without
the standard errors' 95 % bound), and with the study's own rule? The
cost to there, as run, is the speed's CPU time per simulated second (both ranks busy throughout, so
half of it is the time on 2 cores). Loop times are wall times: other jobs on a shared machine
lengthen them. So the time to there is also given for the machine to itself: its particle-steps
at the rate benchmarks/full_scene.py measured for the study's settings (`fast`, median over its
rounds, from the steady 21 rpm state: BENCHMARK below), where that benchmark ran at the study's step.

  tools/drum/report.py --name study_thesis

Needs: python3-matplotlib (tools/harness); drum_metrics.
"""

import argparse
import csv
import math
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import harness  # noqa: E402
from harness import charts  # noqa: E402

# Table 3.2: real time [days] on one 16-core machine, timesteps, simulated time [s]
THESIS_RUNS = {7: (41.9, 51170037, 62.9), 14: (16.5, 16001794, 19.6), 21: (21.1, 20675746, 25.4),
               28: (25.2, 19864296, 24.4), 35: (20.1, 17137824, 21.0), 42: (16.6, 17965503, 22.1),
               49: (21.7, 19442342, 23.9), 56: (20.0, 19377426, 23.8), 63: (16.5, 14979367, 18.4)}
THESIS_CORES = 16
# Section 3.4's reading of Fig. 3.2-3.4, step by step through the chain ("the head increases up
# until 21 rpm, decreases suddenly at 28 rpm, and then increases from 35 rpm onwards"; Hd and Hc:
# "the sudden decrease" at 28 rpm); steps it does not describe are absent.
THESIS_FINDINGS = {
    "Hh": {(7, 14): "rises", (14, 21): "rises", (21, 28): "drops", (35, 42): "rises", (42, 49): "rises",
           (49, 56): "rises", (56, 63): "rises"},
    "Hd": {(21, 28): "drops"},
    "Hc": {(21, 28): "drops"},
}
# (key, column, standard-error column, scale, unit) of the metrics shown
SHOWN = [("Hh", "Hh_m", "Hh_se_m", 1e3, "mm"), ("Hd", "Hd_m", "Hd_se_m", 1e3, "mm"), ("Hc", "Hc_m", "Hc_se_m", 1e3, "mm"),
         ("angle", "angle_deg", "angle_se_deg", 1.0, "deg"), ("drum force", "drum_force_N", "drum_force_se_N", 1e3, "mN")]


def change(a, sa, b, sb):
    """'rises' / 'drops' where b - a exceeds twice the combined standard error, else 'no change'
    ('?' without error bars)."""
    sigma = math.hypot(sa, sb)
    if not math.isfinite(sigma) or not math.isfinite(a) or not math.isfinite(b):
        return "?"
    if b - a > 2.0 * sigma:
        return "rises"
    if a - b > 2.0 * sigma:
        return "drops"
    return "no change"


def thesis_cpu_hours(rpm):
    days = THESIS_RUNS[rpm][0] if rpm in THESIS_RUNS else float("nan")
    return days * 24.0 * THESIS_CORES


def findings(rows):
    """[(metric, from rpm, to rpm, thesis' reading or '', ours, difference, its 2-sigma)] between
    consecutive speeds of the table."""
    out = []
    for (key, col, se, scale, unit) in SHOWN[:3]:
        for r1, r2 in zip(rows, rows[1:]):
            a, b = float(r1[col]), float(r2[col])
            sa, sb = float(r1[se]), float(r2[se])
            out.append((key, r1["rpm"], r2["rpm"], THESIS_FINDINGS[key].get((int(r1["rpm"]), int(r2["rpm"])), ""),
                        change(a, sa, b, sb), (b - a) * scale, 2.0 * math.hypot(sa, sb) * scale, unit))
    return out


def time_to_target(series, run, rpm, dt, min_batches, confidence=0.0):
    """The stop rule replayed on a speed's series (rows of `drum_metrics series`, its first the
    speed's start state) where tools/drum/steady.py checks it: after the first segment (the run's
    --segment, plus --settle from the grid), then after each segment as long as its next_length
    makes it for `min_batches`. (Checking after every snapshot would stop sooner, and more often on
    a standard error that happens to be low.) Returns (simulated seconds from the start, the
    verdict's row) at the first check that says done with `min_batches` batches (and with
    `confidence` > 0, the standard errors' upper bound at that confidence within the targets);
    (nan, None) where none does within the series."""
    from steady import next_length  # (steady imports this module)
    t0, revolution = float(series[0]["time_s"]), 60.0 / rpm
    spacing = float(series[1]["time_s"]) - t0 if len(series) > 1 else revolution
    targets = [f"--target={k}={v:g}" for k, v in run["settings"]["targets"].items()]
    if confidence > 0:
        targets.append(f"--confidence={confidence:g}")
    columns = ["step"] + list(series[0].keys())
    segment = float(run["settings"]["segment"])
    t = segment + (float(run["settings"]["settle"]) if t0 == 0.0 else 0.0)  # a grid start settles first
    with tempfile.TemporaryDirectory() as tmp:
        cache = Path(tmp) / "cache.csv"
        while True:
            n = round(t / spacing) + 1
            if n > len(series):
                return float("nan"), None
            with open(cache, "w") as f:  # drum_metrics reads '\n' line ends
                csv.writer(f, lineterminator="\n").writerows(
                    [columns] + [[round(float(r["time_s"]) / dt), *(repr(v) if isinstance(v, float) else v
                                                                   for v in r.values())] for r in series[:n]])
            verdict = harness.read_csv_text(harness.tool(
                "drum_metrics", "steady", "--prefix", Path(tmp) / "none" / "beads", "--dt", f"{dt:g}", "--rpm", rpm,
                "--cache", cache, "--batch-seconds", f"{revolution:.10g}", "--min-batches", min_batches, *targets))[0]
            if int(verdict["done"]) == 1:
                return float(series[n - 1]["time_s"]) - t0, verdict
            t += next_length(verdict, float(series[n - 1]["time_s"]), rpm, segment, min_batches, spacing)


# The rate of the study's settings in steady flow: `fast` from the shipped steady 21 rpm state
# (`full_scene_steady` once measured, else the runs-at-once benchmark's `fast` from the same state).
# Not `full_scene_long`: its start, the 3 s state, has a bed that barely turns; it rebuilds the
# neighbour lists half as often (131 against 278 builds per 5,000 steps) and runs 1.4 times as fast.
_RESULTS = harness.REPO / "benchmarks" / "results"
BENCHMARK = next((_RESULTS / stem for stem in ("full_scene_steady", "full_scene_at_once")
                  if (_RESULTS / f"{stem}.csv").exists()), _RESULTS / "full_scene_steady")
# The drum.in variables of the benchmark's `fast` (benchmarks/full_scene.py) other than dt; a
# variable a study leaves out takes drum.in's default, given here where `fast` relies on it.
FAST = {"wall": "cylinder", "skin": "0.3", "exact": "on", "balance": "on", "conventions": "thesis",
        "collision": "off", "model": "viscoelastic", "tangential": "history"}


def alone_rate(dt, variables=None, benchmark=BENCHMARK):
    """Particle-steps per second of the study's settings (`fast`) on 2 ranks with the machine to
    itself: the median over the benchmark's rounds; nan without the benchmark, or for a study at
    another step or with other settings (`variables`: its drum.in variables; None: not checked)."""
    json_path = Path(f"{benchmark}.json")
    if not json_path.exists():
        return float("nan")
    if variables is not None and any(str(variables.get(k, v)) != v for k, v in FAST.items()):
        return float("nan")
    if not math.isclose(float(harness.read_json(json_path)["dt_s"]), dt, rel_tol=1e-9):
        return float("nan")
    rates = fast_rates(benchmark)
    return harness.median(rates) if rates else float("nan")


def fast_rates(benchmark=BENCHMARK):
    """The benchmark's `fast` particle-steps per second, one per round ([] without it)."""
    csv_path = Path(f"{benchmark}.csv")
    return [float(r["particle_steps_per_s"]) for r in harness.read_csv(csv_path)
            if r["variant"] == "fast"] if csv_path.exists() else []


def slowest_round(benchmark=BENCHMARK):
    """The benchmark's median `fast` rate over its slowest round's: how much longer the minutes
    with the machine to itself get at the slowest rate it measured (the same machine's speed
    varies from round to round); nan without the benchmark."""
    rates = fast_rates(benchmark)
    return harness.median(rates) / min(rates) if rates else float("nan")


# The stop rules replayed beside a study's own: (fewest batches, confidence of the SE bound; 0:
# the SE as estimated). 3 batches with the estimate alone is there to show why the bound is needed.
RULES = ((3, 0.0), (3, 0.95))


def rule_label(rule):
    batches, confidence = rule
    return f"{batches}" + (f", {100 * confidence:g} % bound" if confidence > 0 else "")


def targets_reached(docs, name, rows, rules=RULES, benchmark=BENCHMARK):
    """Per finished speed with its series committed: [(rpm, rule, simulated s, CPU hours,
    verdict row, minutes on 2 cores with the machine to itself)] for `rules` ((min_batches,
    confidence) pairs) and the study's own. Where the rule never said done (verdict None), the
    times are the whole run's: a lower bound."""
    out = []
    for r in rows:
        folder = docs / name / f"{r['rpm']:g}rpm"
        if not (folder / "series_metrics.csv").exists() or not (folder / "run.json").exists():
            continue
        series = harness.read_csv(folder / "series_metrics.csv")
        run = harness.read_json(folder / "run.json")
        per_second = run["cpu_s"] / 3600.0 / run["simulated_s"]
        dt = float(r["dt_s"])
        rate = alone_rate(dt, run["settings"]["variables"], benchmark)
        own = (run["settings"]["min_batches"], float(run["settings"].get("confidence", 0.0)))
        for rule in sorted({*rules, own}):
            t, verdict = time_to_target(series, run, r["rpm"], dt, *rule)
            if verdict is None:
                t = float(series[-1]["time_s"]) - float(series[0]["time_s"])
            out.append((int(r["rpm"]), rule, t, t * per_second, verdict, t / dt * run["beads"] / rate / 60.0))
    return out


def censored_median(values, lower_bounds):
    """The median of `values` as text, where values flagged in `lower_bounds` are only known to be at
    least that large: the median with them as given and with them infinite; one number where both
    agree, else '≥ the first'."""
    low = harness.median(values)
    high = harness.median([math.inf if b else v for v, b in zip(values, lower_bounds)])
    if high == low:
        return f"{low:.0f}"
    return f"{low:.0f}–{high:.0f}" if math.isfinite(high) else f"≥ {low:.0f}"


def answer(rows):
    """The study's answer in plain words, first in its report: how the head moves from speed to
    speed, and at how many of the steps the thesis describes (Fig. 3.2-3.4) it moves the thesis'
    way."""
    steps = [f for f in findings(rows) if f[0] == "Hh"]
    if not steps:
        return f"One speed ({rows[0]['rpm']:g} rpm) so far: no step to compare." if rows else "No speed yet."
    moves = "; ".join(f"{ours} {a:g} → {b:g} rpm" for _, a, b, _, ours, *_ in steps)
    said = [f for f in findings(rows) if f[3]]
    agree = [f for f in said if f[3] == f[4]]
    text = (f"**Answer.** The head Hh, speed by speed (a change beyond twice the combined standard error): "
            f"{moves}.")
    if said:
        differ = ", ".join(f"{k} {a:g} → {b:g} rpm (thesis: {t}; here: {o})" for k, a, b, t, o, *_ in said
                           if t != o)
        text += (f" Of the {len(said)} steps the thesis describes, {len(agree)} move its way"
                 + (f"; not: {differ}" if differ else "") + ".")
    return text


def markdown(name, rows, reached=(), slow=float("nan")):
    """The study's report; `slow`: slowest_round's factor, for the minutes at the benchmark's
    slowest round."""
    def pm(r, col, se, scale, digits):
        v, e = float(r[col]) * scale, float(r[se]) * scale
        return f"{v:.{digits}f} ± {e:.{digits}f}" if math.isfinite(e) else f"{v:.{digits}f}"

    obm = [r["rpm"] for r in rows if not math.isfinite(float(r.get("batches", math.nan)))]
    revs = [r["rpm"] for r in rows if r["rpm"] not in obm]

    def at(speeds):
        return "" if not obm or not revs else " at " + ", ".join(f"{x:g}" for x in speeds) + " rpm"
    bars = ([f"averages over whole revolutions after the steady start, ± their standard error by batch means (one "
             f"batch per revolution; the batches are the last whole revolutions from the steady start to the speed's "
             f"end, the part before them, less than a revolution, left out){at(revs)}"] if revs else []) + \
           ([f"averages over the whole steady window, ± the standard error of `tools/drum/estimator.py` (overlapping "
             f"batch means, batch length from the series; the 95 % half-widths and effective degrees of freedom are in "
             f"the table's `_hw95_` and `_dof` columns){at(obm)}"] if obm else [])
    lines = [f"# Drum study `{name}`", "", answer(rows), "",
             f"Written by `tools/drum/report.py --name {name}` from `docs/drum/{name}.csv` "
             "(one row per finished speed; `done`: the stop rule's target reached, else capped): "
             + "; ".join(bars) + ". `averaged` and `revolutions`: from the steady start to the speed's end.", "",
             f"![metrics against speed]({name}.png)", "",
             "| rpm | Hh [mm] | Hd [mm] | Hc [mm] | angle [deg] | drum force [mN] | settle [s] | averaged [s] "
             "| revolutions | done |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['rpm']:g} | {pm(r, 'Hh_m', 'Hh_se_m', 1e3, 1)} | {pm(r, 'Hd_m', 'Hd_se_m', 1e3, 1)} | "
                     f"{pm(r, 'Hc_m', 'Hc_se_m', 1e3, 2)} | {pm(r, 'angle_deg', 'angle_se_deg', 1.0, 2)} | "
                     f"{pm(r, 'drum_force_N', 'drum_force_se_N', 1e3, 3)} | {round(float(r['settle_s']), 6) + 0.0:.1f} | "
                     f"{float(r['average_s']):.1f} | {float(r['revolutions']):.1f} | "
                     f"{'yes' if r['done'] in (True, 1.0, 'True', 'true', '1') else 'capped'} |")
    lines += ["", "## The thesis' findings beside these averages", "",
              "A step between two speeds of the chain: the thesis' reading of Fig. 3.2-3.4 (blank where it "
              "says nothing) and what the averages show (a change larger than twice the combined standard "
              "error, else 'no change').", "",
              "| metric | step [rpm] | thesis | here | difference | 2σ |", "|---|---|---|---|---|---|"]
    for key, a, b, thesis, ours, diff, two_sigma, unit in findings(rows):
        lines.append(f"| {key} | {a:g} → {b:g} | {thesis} | {ours} | {diff:+.2f} {unit} | {two_sigma:.2f} {unit} |")
    lines += ["", "## Cost beside the thesis' Table 3.2", "",
              f"CPU hours per speed: here on this project's machines (`cpu_hours`: LIGGGHTS' loop CPU time "
              f"summed over ranks), the thesis' as real days times {THESIS_CORES} cores (YADE on one "
              "16-core machine per speed).", "",
              "| rpm | simulated [s] here | CPU hours here | thesis: simulated [s] | thesis: days | "
              "thesis: CPU hours | here / thesis, per simulated s |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        rpm = int(r["rpm"])
        simulated = float(r["settle_s"]) + float(r["average_s"])
        thesis = THESIS_RUNS.get(rpm, (float("nan"),) * 3)
        ours_rate = float(r["cpu_hours"]) / simulated if simulated > 0 else float("nan")
        lines.append(f"| {rpm} | {simulated:.1f} | {float(r['cpu_hours']):.1f} | {thesis[2]:.1f} | {thesis[0]:.1f} | "
                     f"{thesis_cpu_hours(rpm):.0f} | {ours_rate / (thesis_cpu_hours(rpm) / thesis[2]):.2g} |")
    if reached:
        lines += ["", "## Time to the target", "",
                  "The stop rule replayed on each speed's committed series where the study's driver checks "
                  "it (after each segment; once settled, segments end where the next batch completes): the "
                  "first check where the averages met the target standard errors with at least this many batches "
                  "(whole revolutions after the steady start; with a bound: where the standard errors' upper "
                  "confidence bound, chi-square over the batches' degrees of freedom, met them: 4.42 times the "
                  "estimate from 3 batches, 2.37 from 5), counted from the speed's start state (the first "
                  "speed's: the study's first state). Minutes on 2 cores, as run: half the CPU time (both ranks "
                  "busy throughout; wall times, which other jobs on the machine lengthen). With the machine to "
                  "itself: the particle-steps to there at the rate `benchmarks/full_scene.py` measured in steady "
                  "flow for the study's settings (`fast`, median over its rounds). The averages "
                  "there beside the speed's final ones (the table above) show what the shorter run would have "
                  "reported. A standard error from 3 batches has 2 degrees of freedom (from 5: 4): as "
                  "estimated it falls short of the true one in 63 % of 3-batch runs (chi-square), and the "
                  "rule stops at the first check where it is small enough; the bound, given in brackets, "
                  "covers the true one in 95 % at one check, for independent batches; checked again and "
                  "again until it passes, less: on normal batch means checked after every batch, the true "
                  "one lies above the target at the stop in at most 9.5 % of runs from 3 batches on, 8.0 % "
                  "from 5 (the README's stop rule).", "",
                  "| rpm | batches | simulated [s] | CPU hours | minutes on 2 cores, as run | minutes on 2 cores, "
                  "machine to itself | Hc [mm] | angle [deg] |",
                  "|---|---|---|---|---|---|---|---|"]
        for rpm, rule, t, cpu, v, alone in reached:
            # under a bound, the bound beside the estimate: the error bar to quote (from 2 degrees
            # of freedom, +-2 estimated SE covers 82 % of replicas, not 95 %)
            f = float(v.get("se_factor", 1.0)) if v and rule[1] > 0 else None
            bound = (lambda se: f" (≤ {se * f:.3f})") if f else (lambda se: "")
            avg = (f"{1e3 * float(v['Hc_m']):.3f} ± {1e3 * float(v['Hc_se_m']):.3f}{bound(1e3 * float(v['Hc_se_m']))} | "
                   f"{float(v['angle_deg']):.3f} ± {float(v['angle_se_deg']):.3f}{bound(float(v['angle_se_deg']))}"
                   ) if v else "not reached | –"
            more = "" if v else "> "
            lines.append(f"| {rpm} | {rule_label(rule)} | {more}{t:.2f} | {more}{cpu:.1f} | {more}{30.0 * cpu:.0f} | "
                         f"{more}{alone:.0f} | {avg} |")
        lines.append("")
        for b in sorted({r[1] for r in reached}):
            mine = [r for r in reached if r[1] == b]
            lower = [r[4] is None for r in mine]  # never done: the whole run's time, a lower bound
            missed = sum(lower)
            line = (f"- {b[0]} batches" + (f", the standard errors' {100 * b[1]:g} % bound" if b[1] > 0 else "")
                    + f": median over {len(mine)} speeds " + censored_median([30.0 * r[3] for r in mine], lower)
                    + " minutes on 2 cores as run")
            if all(math.isfinite(r[5]) for r in mine):
                line += ", " + censored_median([r[5] for r in mine], lower) + " with the machine to itself"
                if math.isfinite(slow):
                    line += (" (" + censored_median([slow * r[5] for r in mine], lower)
                             + " at the benchmark's slowest round)")
            if missed:
                line += (f" ({missed} never reached the target within its run, counted at its whole run's time, "
                         "a lower bound: the median lies in the range given, from those times as they are to "
                         "those times unbounded; '≥' where it has no upper end)")
            lines.append(line + ".")
    return "\n".join(lines) + "\n"


def chart(name, rows, path):
    fig, axes = charts.figure(2, 3, title=f"drum study {name}: averages against speed (± standard error)",
                              size=(4.2, 3.2))
    rpm = [float(r["rpm"]) for r in rows]
    for ax, (key, col, se, scale, unit) in zip(axes, SHOWN):
        errors = [float(r[se]) * scale for r in rows]  # none (nan) drawn as none
        ax.errorbar(rpm, [float(r[col]) * scale for r in rows], yerr=[e if math.isfinite(e) else 0.0 for e in errors],
                    marker="o", capsize=3)
        ax.set_xlabel("drum speed [rpm]")
        ax.set_ylabel(f"{key} [{unit}]")
        ax.ticklabel_format(axis="y", useOffset=False)
    ax = axes[5]
    ax.semilogy(rpm, [float(r["cpu_hours"]) for r in rows], "o-", label="here")
    ax.semilogy(rpm, [thesis_cpu_hours(int(r["rpm"])) for r in rows], "s--", label="thesis (Table 3.2)")
    ax.set_xlabel("drum speed [rpm]")
    ax.set_ylabel("CPU hours per speed")
    ax.legend()
    return charts.save(fig, path)


def write(name, docs=None):
    """Writes docs/drum/NAME.md and .png from docs/drum/NAME.csv; returns their paths (none
    without the table)."""
    docs = Path(docs) if docs else harness.REPO / "docs" / "drum"
    table = docs / f"{name}.csv"
    if not table.exists():
        return []
    rows = sorted(harness.read_csv(table), key=lambda r: float(r["rpm"]))
    md, png = docs / f"{name}.md", docs / f"{name}.png"
    md.write_text(markdown(name, rows, targets_reached(docs, name, rows), slowest_round()))
    chart(name, rows, png)
    return [md, png]


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--name", default="study_thesis", help="docs/drum/NAME.csv (default: %(default)s)")
    p.add_argument("--docs", default=None, help="directory of the table (default: docs/drum)")
    args = p.parse_args(argv)
    written = write(args.name, args.docs)
    print("report: " + (", ".join(map(str, written)) if written else "no table yet"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
