#!/usr/bin/python3
"""A drum study's error bars re-derived from its committed series with tools/drum/estimator.py:
95 % half-widths and effective degrees of freedom beside the batch-means standard errors, and
the page that says what changed (docs/drum/error_bars.md).

For each speed of docs/drum/NAME.csv, each metric's series (docs/drum/NAME/<rpm>rpm/
series_metrics.csv) over exactly the snapshots the table's average spans: from the steady start
(the series' end minus the row's average_s, i.e. its start plus settle_s), the last whole
revolutions of finite values, as `drum_metrics series` batched them; for a row of the estimator's
stop rule (`steady.py --rule obm`, `batches` nan), every finite value of that window. The estimator's mean over
them must equal the table's to its printed digits (checked: the error bar belongs to the mean
printed). Written into the table, every existing column kept as it was: <key>_hw95_<unit> (95 %
half-width) and <key>_dof (effective degrees of freedom) per metric.

The page also checks the estimator on the committed data: each speed's window cut into halves,
each half's interval estimated alone, and the halves' difference set against its 95 % interval
(two halves of one steady state disagree in 5 % of such comparisons if the error bars hold, and
the window was steady); and on synthetic series with a known mean (tools/drum/synthetic.py).

  tools/drum/rederive.py                       # study_thesis: its table and docs/drum/error_bars.md
  tools/drum/rederive.py --name study_bound --no-page

A study whose speeds a running tools/drum/steady.py still adds to is best left until it is done:
steady.py rewrites its table from the new row's columns, which drops these.

Needs: python3-numpy, python3-scipy; python3-matplotlib (tools/harness).
"""

import argparse
import csv
import math
import sys
from pathlib import Path

import numpy as np
from scipy import stats

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))
import harness  # noqa: E402
import estimator  # noqa: E402
import synthetic  # noqa: E402

DOCS = harness.REPO / "docs" / "drum"
CONFIDENCE = 0.95
REPLICAS = 8000  # synthetic replicas per family on the page (binomial sd 0.24 % at 95 %)
TARGETS = {"Hc": 3e-4, "angle": 0.3}  # [m], [deg]: the stop rule's default targets


def hw_column(key, unit):
    return f"{key}_hw95_{unit}"


def dof_column(key):
    return f"{key}_dof"


def read_table(path):
    """(header, rows as dicts of the cells' text) of a study table."""
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        return list(reader.fieldnames), list(reader)


def write_table(path, header, rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=header)
        w.writeheader()
        w.writerows(rows)


def metrics(header):
    """[(key, value column, standard-error column, unit)] of a study table: each `<key>_se_<unit>`
    beside its `<key>_<unit>`."""
    out = []
    for se in header:
        key, sep, unit = se.partition("_se_")
        if sep and f"{key}_{unit}" in header:
            out.append((key, f"{key}_{unit}", se, unit))
    return out


def read_series(folder):
    """A speed's per-snapshot series as {column: numpy array}."""
    with open(folder / "series_metrics.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    return {c: np.array([float(r[c]) for r in rows]) for c in rows[0]}


def window(series, row, column):
    """The values of `column` the table's average of it spans (module note), and the snapshot
    spacing [s]."""
    t = series["time_s"]
    spacing = float(np.median(np.diff(t)))
    start = t[-1] - float(row["average_s"])
    if abs(t[0] + float(row["settle_s"]) - start) > spacing / 2:
        raise ValueError(f"{row['rpm']} rpm: the series' start plus settle_s is not its end minus average_s")
    x = series[column][t >= start - spacing / 2]
    x = x[np.isfinite(x)]
    if not math.isfinite(float(row.get("batches") or "nan")):
        return x, spacing  # a row of the estimator's stop rule (steady.py --rule obm): the whole steady window
    batch = max(1, round(60.0 / float(row["rpm"]) / spacing))
    return x[len(x) - len(x) // batch * batch:], spacing


def same_to_printed_digits(value, text):
    """`value` is the number printed as `text` to its printed digits: within one unit of the last
    (drum_metrics averaged the batch means, in another order of summation, so a value close to a
    rounding boundary may round the other way there)."""
    printed = float(text)
    mantissa = text.lower().split("e")[0].lstrip("+-")
    digits = len(mantissa.replace(".", "").lstrip("0")) or 1
    exponent = math.floor(math.log10(abs(printed))) if printed else 0
    return abs(value - printed) <= 10.0 ** (exponent - digits + 1)


def rederive(docs, name):
    """(header, rows, details) of docs/NAME.csv with the new columns (existing ones unchanged,
    earlier copies of the new ones replaced). details: {(rpm, key): {"interval", "se", "n",
    "tau_s", "swing_s", "x", "spacing"}} per metric and speed with a series."""
    header, rows = read_table(docs / f"{name}.csv")
    found = metrics(header)
    new = [c for key, _, _, unit in found for c in (hw_column(key, unit), dof_column(key))]
    header = [c for c in header if c not in new] + new
    details = {}
    for row in rows:
        folder = docs / name / f"{float(row['rpm']):g}rpm"
        if not (folder / "series_metrics.csv").exists():
            continue
        series = read_series(folder)
        for key, column, se, unit in found:
            x, spacing = window(series, row, column)
            interval = estimator.mean_interval(x, spacing, CONFIDENCE)
            if not same_to_printed_digits(interval.mean, row[column]):
                raise ValueError(f"{name} {row['rpm']} rpm {column}: the window's mean {interval.mean!r} is not "
                                 f"the table's {row[column]}")
            row[hw_column(key, unit)] = f"{interval.half_width:.10g}"
            row[dof_column(key)] = f"{interval.dof:.4g}"
            b, tau, period = estimator.batch_length(x)
            details[(float(row["rpm"]), key)] = {"interval": interval, "se": float(row[se]), "n": len(x),
                                                 "tau_s": tau * spacing, "swing_s": period * spacing, "x": x,
                                                 "spacing": spacing}
    return header, rows, details


def halves(details):
    """Each speed's and metric's window cut into two halves, each estimated alone:
    [(rpm, key, difference / its 95 % half-width, the halves' dof)]."""
    out = []
    for (rpm, key), d in sorted(details.items()):
        h = len(d["x"]) // 2
        a = estimator.mean_interval(d["x"][:h], d["spacing"], CONFIDENCE)
        b = estimator.mean_interval(d["x"][len(d["x"]) - h:], d["spacing"], CONFIDENCE)
        difference, half_width, _ = estimator.compare(a, b, CONFIDENCE)
        out.append((rpm, key, difference / half_width if half_width > 0 else math.inf, (a.dof, b.dof)))
    return out


def clopper_pearson(k, n, confidence=0.95):
    """The exact binomial confidence interval of a rate k / n."""
    a = (1 - confidence) / 2
    return (stats.beta.ppf(a, k, n - k + 1) if k else 0.0, stats.beta.ppf(1 - a, k + 1, n - k) if k < n else 1.0)


def needed_seconds(d, min_dof=estimator.MIN_DOF):
    """Simulated seconds a speed's window would need for `min_dof` at its batch length."""
    b = d["interval"].batch_seconds / d["spacing"]
    decay = 0.0 if d["swing_s"] else min(d["tau_s"] / d["spacing"], b / 2)
    return b * (1.0 + min_dof / (1.5 * (1.0 - decay / b))) * d["spacing"]


def answer(name, speeds, details, split, rates):
    """The page's answer: what changed, the synthetic coverage, the halves of the committed data."""
    keys = list(dict.fromkeys(k for _, k in details))
    dofs = [d["interval"].dof for d in details.values()]
    short = [(rpm, k) for rpm in speeds for k in keys if details[(rpm, k)]["interval"].dof < estimator.MIN_DOF]
    windows = [details[key]["n"] * details[key]["spacing"] for key in short]
    ratio = {k: [details[(rpm, k)]["interval"].half_width / (2 * details[(rpm, k)]["se"]) for rpm in speeds]
             for k in TARGETS}
    ar1, swing = rates["ar1"], rates["swing"]
    apart = [(rpm, key, t) for rpm, key, t, _ in split if abs(t) > 1]
    low, high = clopper_pearson(len(apart), len(split))
    rate = len(apart) / len(split)
    changed = (f"The 95 % half-width is {min(ratio['Hc']):.2f}–{max(ratio['Hc']):.2f} times the old ± 2 SE for Hc "
               f"(median {np.median(ratio['Hc']):.2f}) and {min(ratio['angle']):.2f}–{max(ratio['angle']):.2f} "
               f"times it for the angle (median {np.median(ratio['angle']):.2f}; Student's t at 10 degrees of "
               "freedom is 2.23): a standard error from 4 degrees of freedom is itself uncertain by a factor "
               "0.6–2.9 (95 %), the scatter seen here from speed to speed. The effective degrees of freedom are "
               f"{min(dofs):.1f}–{max(dofs):.1f} over the {len(keys)} metrics and {len(speeds)} speeds, against 4 "
               f"before. {len(dofs) - len(short)} of the {len(dofs)} averages reach the 10 asked for")
    if short:
        changed += (f"; the {len(short)} that do not are at "
                    f"{', '.join(f'{rpm:g}' for rpm in sorted({rpm for rpm, _ in short}))} rpm, whose steady "
                    f"windows ({min(windows):.2f}–{max(windows):.2f} s) are too short for the batch length their "
                    "correlation asks for (below: what they would need)")
    coverage = (f"({REPLICAS} replicas per family, 15–40 s at 0.05 s): the new 95 % interval covers the mean in "
                f"{100 * ar1['new']:.1f} % of AR(1) series (lag-one correlation 0.9, like the slowest metrics) and "
                f"{100 * swing['new']:.1f} % of series with a 0.5–1 Hz swing plus AR(1) noise; the old rule (five "
                f"batch means, ± 2 SE) in {100 * ar1['old']:.1f} % and {100 * swing['old']:.1f} %. Two replicas of "
                f"one state disagree at 95 % in {100 * ar1['alarms']:.1f} % and {100 * swing['alarms']:.1f} % of "
                f"pairs (the old rule: {100 * ar1['old_alarms']:.1f} % and {100 * swing['old_alarms']:.1f} %). The "
                f"binomial standard deviation of these rates is {100 * math.sqrt(0.05 * 0.95 / REPLICAS):.2f} %; "
                "`tests/harness/test_estimator.py` checks, at 2000 replicas, that the new rule lies within 3 "
                "binomial standard deviations (± 1.46 %) of 95 % and 5 % and the old rule outside.")
    which = ", ".join(f"{rpm:g} rpm {key}: {abs(t):.2f} half-widths apart" for rpm, key, t in apart)
    halves_text = (f"The halves' difference lies outside its 95 % interval in {len(apart)} of {len(split)} "
                   f"comparisons ({100 * rate:.1f} %; 95 % interval of the rate {100 * low:.1f}–{100 * high:.1f} %), "
                   f"{'not above' if rate <= 0.05 else 'ABOVE'} the 5 % the error bars allow"
                   + (f" ({which})" if apart else "") + ". The ten metrics of a speed share its flow, so the "
                   "comparisons are not independent and the rate's interval is narrower than it should be; where a "
                   "half has few degrees of freedom its comparison has little power.")
    return [f"**The averages of `{name}` now carry 95 % half-widths from overlapping batch means whose batch length "
            "follows each series' own correlation (`tools/drum/estimator.py`), instead of the standard error of "
            "five whole-revolution batch means (4 degrees of freedom, compared as ± 2 SE). The means are "
            f"unchanged** (checked to their printed digits); `docs/drum/{name}.csv` has the new columns "
            "`<key>_hw95_<unit>` and `<key>_dof` beside the old ones.", "",
            f"- **What changed.** {changed}.",
            f"- **Coverage on synthetic series with a known mean** {coverage}",
            f"- **The committed data, each speed's window cut into halves** and each half estimated alone. "
            f"{halves_text}", "",
            f"Only `{name}` is rewritten: `study_bound` and `study_yade` have series too, but the running campaign "
            "still adds speeds to them, and `tools/drum/steady.py` rewrites a table from its new row's columns, "
            "which would drop these; `tools/drum/rederive.py --name study_bound --no-page` (and "
            "`--name study_yade`) once they are finished."]


def stop_rule(speeds, details):
    """How steady.py's stop rule would use the estimator, and where the committed windows meet it."""
    missing = []
    for rpm in speeds:
        why = [f"{k} {details[(rpm, k)]['interval'].dof:.1f} dof" for k in TARGETS
               if details[(rpm, k)]["interval"].dof < estimator.MIN_DOF]
        why += [f"{k} {details[(rpm, k)]['interval'].half_width:.4g} above its target {target:g}"
                for k, target in TARGETS.items() if details[(rpm, k)]["interval"].half_width > target]
        if why:
            missing.append(f"{rpm:g} rpm ({', '.join(why)})")
    meets = [f"{rpm:g}" for rpm in speeds if not any(m.startswith(f"{rpm:g} rpm") for m in missing)]
    return ("`tools/drum/steady.py --rule obm` ends a speed when every targeted metric's 95 % half-width "
            "(`mean_interval` over the window after the steady start) is within its target (default Hc 0.3 mm, "
            "angle 0.3°) with at least 10 effective degrees of freedom, in place of five whole revolutions and the "
            "standard error (or its chi-square bound) within the target: the timestep ladder, the 12 mm period's "
            "check and `study_yade_low` run under it, `study_thesis` ran under the earlier rule. The window need not "
            "be whole "
            "revolutions: a calm speed stops as soon as its series holds 10 degrees of freedom, and one whose batch "
            "length is long (a slow metric, a swing) runs until its series is about 7.7 batch lengths long. On the "
            "committed windows (at their ends, not where such a rule would first have stopped) Hc and the angle "
            f"meet it at {', '.join(meets) + ' rpm' if meets else 'no speed'}"
            + (f"; not yet at {'; '.join(missing)}" if missing else "") + ". A rule checked after every segment "
            "stops at the first check that passes, so the interval at its stop covers the true mean somewhat less "
            "often than 95 %.")


def page(name, rows, details, split, rates, command):
    speeds = [float(r["rpm"]) for r in rows if (float(r["rpm"]), "Hc") in details]
    keys = list(dict.fromkeys(k for _, k in details))

    def old_new(rpm, key, scale):
        d = details[(rpm, key)]
        return f"{2 * d['se'] * scale:.3f} | {d['interval'].half_width * scale:.3f} | {d['interval'].dof:.1f}"

    def swing(d):
        return f"{d['swing_s']:.2f}" if d["swing_s"] else "–"

    lines = [harness.generated_note(command).rstrip("\n"), "",
             "# Error bars of the drum studies: 95 % intervals with enough degrees of freedom", "",
             "## Answer", "", *answer(name, speeds, details, split, rates), "",
             "## The stop rule with these error bars", "", stop_rule(speeds, details), "",
             "## Hc and the angle per speed", "",
             "Old: ± 2 standard errors of five revolution batches (4 degrees of freedom). New: the 95 % half-width "
             "and its effective degrees of freedom. Window: the snapshots averaged times their spacing. Batch: the "
             "batch length chosen for Hc; tau: Hc's integrated autocorrelation time; swing: the period found in "
             "Hc's autocorrelation (– none).", "",
             "| rpm | window [s] | Hc old ± 2 SE [mm] | Hc new 95 % [mm] | dof | batch [s] | tau [s] | swing [s] "
             "| angle old ± 2 SE [°] | angle new 95 % [°] | dof |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for rpm in speeds:
        d = details[(rpm, "Hc")]
        lines.append(f"| {rpm:g} | {d['n'] * d['spacing']:.2f} | {old_new(rpm, 'Hc', 1e3)} | "
                     f"{d['interval'].batch_seconds:.2f} | {d['tau_s']:.2f} | {swing(d)} | "
                     f"{old_new(rpm, 'angle', 1.0)} |")
    lines += ["", "## Degrees of freedom per metric and speed", "",
              "Effective degrees of freedom of each 95 % half-width (`<key>_dof`); **bold**: below 10, where the "
              "window is too short for the batch length its correlation asks for (at least 10 tau_int, whole "
              "swings); the next table says what it would need.", "",
              "| metric | " + " | ".join(f"{rpm:g} rpm" for rpm in speeds) + " |",
              "|---" * (len(speeds) + 1) + "|"]
    for k in keys:
        cells = [details[(rpm, k)]["interval"].dof for rpm in speeds]
        lines.append(f"| {k} | " + " | ".join(f"**{v:.1f}**" if v < estimator.MIN_DOF else f"{v:.1f}"
                                              for v in cells) + " |")
    lines += ["", "Where 10 degrees of freedom are not reached: the batch length, what set it, and the steady "
              "window that would give 10 at that batch length.", "",
              "| rpm | metric | dof | window [s] | batch [s] | tau [s] | swing [s] | window for 10 [s] |",
              "|---|---|---|---|---|---|---|---|"]
    for rpm in speeds:
        for k in keys:
            d = details[(rpm, k)]
            if d["interval"].dof < estimator.MIN_DOF:
                lines.append(f"| {rpm:g} | {k} | {d['interval'].dof:.1f} | {d['n'] * d['spacing']:.2f} | "
                             f"{d['interval'].batch_seconds:.2f} | {d['tau_s']:.2f} | {swing(d)} | "
                             f"{needed_seconds(d):.1f} |")
    lines += ["", "## Method", "", METHOD]
    return "\n".join(lines) + "\n"


METHOD = """`tools/drum/estimator.py`, `mean_interval(values, dt)`:

- The variance of the mean by overlapping batch means (Meketon & Schmeiser 1984): every run of b
  consecutive snapshots is a batch; about 1.5 (n/b − 1) effective degrees of freedom.
- The batch length b from the series: at least 10 integrated autocorrelation times (Sokal's automatic
  window, c = 6, corrected for the sample mean's bias), and where the autocorrelation's first positive
  lobe after its first zero stands above twice its Bartlett standard error, a whole number of those
  swing periods; within that, the longest b that leaves 10 degrees of freedom; where none does, the
  shortest allowed, and fewer degrees of freedom.
- The batch means' leading bias, about tau_int / b for correlations that decay without a swing,
  divided out of the variance and taken off the degrees of freedom (at most 11 %).
- The half-width: Student's t at the effective degrees of freedom times the standard error. Two
  intervals compared: the difference against t at Welch–Satterthwaite's degrees of freedom times the
  combined standard error (`compare`).

The window is the table's own: from the steady start, the last whole revolutions of the series (as
`drum_metrics series` batched them), so each half-width belongs to the mean printed beside it.

The synthetic families (`tools/drum/synthetic.py`): AR(1) with lag-one correlation 0.9; a damped
0.5–1 Hz resonance carrying half the variance, its autocorrelation 0.6 one period on, plus AR(1) noise
with 0.7; each replica 15–40 s; coverage is how often the interval holds the true mean, 0. On these the
old rule falls short by its 4 degrees of freedom and its factor 2 (Student's t at 4 degrees of freedom
is 2.78), not by a biased standard error: its batches, 3–8 s, are far longer than the correlations. The
new rule errs a little low on the AR(1) family, whose shortest replicas hold only about 30 tau_int and
estimate tau_int itself poorly, and a little high with a swing, whose batch means take up a few per
cent of the swing's variance.
"""


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--name", action="append", help="the study (repeatable; default: study_thesis)")
    p.add_argument("--docs", type=Path, default=DOCS, help="where the studies are (default: docs/drum)")
    p.add_argument("--out", type=Path, help="write the tables (and page) here instead of into --docs")
    p.add_argument("--no-page", action="store_true", help="tables only, no docs/drum/error_bars.md")
    args = p.parse_args(argv)
    names = args.name or ["study_thesis"]
    out = args.out or args.docs
    out.mkdir(parents=True, exist_ok=True)
    for name in names:
        header, rows, details = rederive(args.docs, name)
        write_table(out / f"{name}.csv", header, rows)
        short = sorted({(rpm, k) for (rpm, k), d in details.items() if d["interval"].dof < estimator.MIN_DOF})
        print(f"rederive: {out / f'{name}.csv'}: {len(details)} averages, {len(short)} below "
              f"{estimator.MIN_DOF} degrees of freedom")
        if name == names[0] and not args.no_page:
            rates = {f: synthetic.measure(f, REPLICAS, seed=20261205) for f in ("ar1", "swing")}
            command = "tools/drum/rederive.py " + " ".join(argv if argv is not None else sys.argv[1:])
            text = page(name, rows, details, halves(details), rates, command.strip())
            (out / "error_bars.md").write_text(text)
            print(f"rederive: {out / 'error_bars.md'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
