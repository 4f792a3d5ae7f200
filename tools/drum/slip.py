#!/usr/bin/python3
"""The slip test of Fig. 3.5-3.6: does the bed drop between 27 and 28 rpm?

The thesis raised the drum's speed incrementally from 21 to 28 rpm over 1e7 timesteps (about
12 s at its step) and saw the centre of mass drop between 27 and 28 rpm, which it put down to
the beads reaching the Coulomb limit on the drum. Here the same steps are runs of
tools/drum/steady.py with a fixed length per speed (`--cap` = `--segment`), each from the end
state of the speed before (so the study's folders hold one series per speed), once per set of
conventions. This script reads those series and, per speed, averages the last --window of it
(after the step's transient) with a standard error by batch means over --batches contiguous
batches; then, step by step, each metric's change in a two-sided Welch t-test at --alpha per
comparison (batch means from n batches have n - 1 degrees of freedom; with 3 batches a "twice
the combined error" rule would call 12 % of unchanged steps a change). A slip shows as a drop of
Hc (and of the head) at one step while the other steps rise, with the bed's turn (`bed_turn`)
falling below 1 and the drum contacts' rolling (`wall_roll`) and slip (`wall_slip`) rising.

  tools/drum/slip.py --study slip_thesis "thesis table (bead-drum mu 0.95)" \\
      --study slip_yade "YADE 1.12 conventions (bead-drum mu 0.5, facet meff m/2, no attraction)" \\
      --start study_thesis:21 --out docs/drum/slip_test

Needs: python3-matplotlib (tools/harness), python3-numpy, python3-scipy.
"""

import argparse
import json
import math
import shlex
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))
import harness  # noqa: E402
from harness import charts  # noqa: E402
from histories import detectable_sum, satterthwaite, welch_dof  # noqa: E402
import numpy as np  # noqa: E402
from scipy import stats  # noqa: E402

# (label, column, scale, unit, digits) of the metrics compared
METRICS = [("Hc", "Hc_m", 1e3, "mm", 2), ("Hh", "Hh_m", 1e3, "mm", 1), ("angle", "angle_deg", 1.0, "deg", 2),
           ("bed turn", "bed_turn_1", 1.0, "", 4), ("wall roll", "wall_roll_1", 1.0, "", 4),
           ("wall slip", "wall_slip_1", 1.0, "", 4)]


def se_column(col):
    """The standard error's column of a study table (docs/drum/NAME.csv): Hc_m -> Hc_se_m."""
    head, unit = col.rsplit("_", 1)
    return f"{head}_se_{unit}"


def batch_means(values, batches):
    """(mean, standard error) of `values` by batch means over `batches` contiguous batches of
    equal length (the first len % batches values left out); nan error with fewer than 2, and
    both nan where a value is missing (nan: a step with it then gets no verdict)."""
    n = len(values) // batches
    if not all(math.isfinite(v) for v in values):
        return float("nan"), float("nan")
    if batches < 2 or n < 1:
        return (statistics.fmean(values) if values else float("nan")), float("nan")
    kept = values[len(values) - n * batches:]
    means = [statistics.fmean(kept[k * n:(k + 1) * n]) for k in range(batches)]
    return statistics.fmean(means), statistics.stdev(means) / math.sqrt(batches)


def window_average(series, window, batches):
    """{column: (mean, se)} over the last `window` (a fraction) of a speed's series."""
    last = series[len(series) - max(1, round(window * len(series))):]
    return {col: batch_means([float(r[col]) for r in last], batches) for _, col, _, _, _ in METRICS}


def study_speeds(docs, name, window, batches):
    """[(rpm, {column: (mean, se)}, seconds, batches)] of a study's speeds that have a series, by speed."""
    out = []
    for folder in sorted((docs / name).glob("*rpm"), key=lambda p: float(p.name[:-3])):
        path = folder / "series_metrics.csv"
        if path.exists():
            series = harness.read_csv(path)
            if len(series) > 1:
                seconds = float(series[-1]["time_s"]) - float(series[0]["time_s"])
                out.append((float(folder.name[:-3]), window_average(series, window, batches), seconds, batches))
    return out


# bed_turn below which the bed no longer turns with the drum: in steady flow a carried bed has
# 0.99-1.00, one riding on a layer of rolling beads 0.45-0.51 (docs/drum/study_thesis.csv)
LETS_GO = 0.9
# ... and half-way from a carried bed to one on rolling beads ((0.99 + 0.45) / 2): a release takes
# about a second and a half, so its onset (LETS_GO) and its middle can fall in different speeds
HALF_WAY = 0.72


def ramp_series(docs, name):
    """[(time_s, rpm, Hc_m, bed_turn)] of a study's speeds in order: the ramp as one series. A
    speed's first sample repeats the previous speed's last state (same time) with `bed_turn`
    divided by the new speed: it is left out, as are samples without a `bed_turn`."""
    out = []
    for folder in sorted((docs / name).glob("*rpm"), key=lambda p: float(p.name[:-3])):
        path = folder / "series_metrics.csv"
        if path.exists():
            for r in harness.read_csv(path):
                t, turn = float(r["time_s"]), float(r["bed_turn_1"])
                if math.isfinite(turn) and (not out or t > out[-1][0]):
                    out.append((t, float(folder.name[:-3]), float(r["Hc_m"]), turn))
    return out


def running_median(values, span=5):
    """Each value's median over the `span` samples centred on it (fewer at the ends): a single
    sample across a threshold does not move what is read from the series."""
    half = span // 2
    return [statistics.median(values[max(0, k - half):k + half + 1]) for k in range(len(values))]


def lets_go(series, threshold=LETS_GO, least=4, span=5):
    """Where the bed lets go of the drum along a ramp: (time, rpm, time into that speed) of the
    first sample from which `bed_turn`, as a running median over `span` samples (a single sample
    just above or below the threshold does not move the answer), stays below `threshold` to the
    end, for at least `least` samples; None where it does not. The time into a speed counts from
    the speed's change, the time of the sample before its first."""
    smooth = running_median([s[3] for s in series], span)
    since = None
    for k, turn in enumerate(smooth):
        since = (since if since is not None else k) if turn < threshold else None
    if since is None or len(series) - since < least:
        return None
    t, rpm = series[since][:2]
    before = [s[0] for s in series if s[1] < rpm]
    start = max(before) if before else min(s[0] for s in series if s[1] == rpm)
    return t, rpm, t - start


class NullRate:
    """What null_rate found: per speed, the changes called and the comparisons made at each pair of
    consecutive pieces."""

    def __init__(self, pairs, hc=None, lag1=()):
        self.pairs = pairs  # [(rpm, called, compared)], one per pair of consecutive pieces
        self.hc = hc  # the same for Hc alone (a NullRate), the metric the slip test's answer reads
        # [(rpm, r)]: the lag-one correlation of Hc's consecutive batch means (a piece's batch
        # length) over each speed's steady series: batch means taken as independent need r near 0
        self.lag1 = list(lag1)

    def counts(self, lo=-math.inf, hi=math.inf):
        chosen = [(c, n) for rpm, c, n in self.pairs if lo <= rpm <= hi]
        return sum(c for c, _ in chosen), sum(n for _, n in chosen), len(chosen)

    def interval(self, lo=-math.inf, hi=math.inf):
        """(rate, low, high): the rate of changes called with a 95 % Clopper-Pearson interval on the
        effective number of comparisons. A pair of pieces' metrics are correlated (Hc with the angle
        about 0.7, with the head 0.5), so the comparisons count as fewer: divided by the design
        effect, the variance of the calls per pair over the binomial one, at least 1; with no
        change called that variance is unknown and a pair counts as one comparison (its metrics
        taken as one), the cautious end."""
        called, compared, pairs = self.counts(lo, hi)
        if not compared:
            return float("nan"), float("nan"), float("nan")
        rate = called / compared
        per_pair = compared / pairs
        if called == 0 or pairs < 2:
            effect = per_pair
        else:
            residuals = [c - rate * n for rpm, c, n in self.pairs if lo <= rpm <= hi]
            effect = statistics.pvariance(residuals) / (rate * (1.0 - rate) * per_pair) if rate < 1.0 else 1.0
        n = compared / max(effect, 1.0)
        x = rate * n
        low = stats.beta.ppf(0.025, x, n - x + 1) if x > 0 else 0.0
        high = stats.beta.ppf(0.975, x + 1, n - x) if x < n else 1.0
        return rate, float(low), float(high)


def null_rate(docs, name, block_s, window, batches, alpha):
    """This reading where nothing changes: each speed of the steady study `name` (docs/drum/NAME/
    <rpm>rpm/, from its steady start) cut into consecutive pieces of block_s seconds, each piece
    read as a slip speed is (its last `window`, `batches` batch means), consecutive pieces set
    against each other as steps are: the false-alarm rate on the drum's own fluctuations, where the
    stated one (alpha per comparison) assumes independent batch means. (A slip speed's window also
    holds what is left of its step's transient; steady pieces have none.)"""
    pairs, hc, lag1 = [], [], []
    for folder in sorted((docs / name).glob("*rpm"), key=lambda p: float(p.name[:-3])):
        series_path, average_path = folder / "series_metrics.csv", folder / "series_average.csv"
        if not (series_path.exists() and average_path.exists()):
            continue
        start = float(harness.read_csv(average_path)[0]["steady_from_s"])
        series = [r for r in harness.read_csv(series_path) if float(r["time_s"]) >= start - 1e-9]
        if len(series) < 2:
            continue
        step = statistics.median(float(b["time_s"]) - float(a["time_s"]) for a, b in zip(series, series[1:]))
        n = max(2, round(block_s / step) + 1)  # samples per piece: a run of block_s spans n - 1 steps
        # the pieces as speeds, read by the steps' own reading (one row per metric and pair)
        pieces = [(k, window_average(series[k * n:(k + 1) * n], window, batches), float("nan"), batches)
                  for k in range(len(series) // n)]
        rows = steps(pieces, alpha)
        for k in range(0, len(rows), len(METRICS)):
            verdicts = [row[3] for row in rows[k:k + len(METRICS)] if row[3] != "?"]
            pairs.append((float(folder.name[:-3]), sum(v != "no change" for v in verdicts), len(verdicts)))
            hc += [(float(folder.name[:-3]), int(row[3] != "no change"), 1) for row in rows[k:k + len(METRICS)]
                   if row[2] == "Hc" and row[3] != "?"]
        size = max(1, round(window * n)) // batches
        means = np.array([statistics.fmean(float(r["Hc_m"]) for r in series[k:k + size])
                          for k in range(0, len(series) - size + 1, size)]) if size else np.array([])
        if len(means) > 2 and np.ptp(means) > 0:
            means -= means.mean()
            lag1.append((float(folder.name[:-3]), float(np.sum(means[1:] * means[:-1]) / np.sum(means ** 2))))
    return NullRate(pairs, NullRate(hc), lag1)


def start_row(docs, spec):
    """--start NAME:RPM: that speed's steady averages from docs/drum/NAME.csv as the first point."""
    name, rpm = spec.split(":")
    table = docs / f"{name}.csv"
    rows = [r for r in harness.read_csv(table) if float(r["rpm"]) == float(rpm)] if table.exists() else []
    if not rows:
        raise harness.RunFailed(f"--start {spec}: no {rpm} rpm row in {table}")
    r = rows[0]
    return (float(rpm), {col: (float(r[col]), float(r[se_column(col)])) for _, col, _, _, _ in METRICS}, float("nan"),
            float(r["batches"]))


def change(xa, sa, na, xb, sb, nb, alpha):
    """(verdict, critical difference): 'rises' / 'drops' where b - a passes the two-sided Welch
    t-test at alpha, else 'no change'; '?' without error bars."""
    se = math.hypot(sa, sb)
    if not (math.isfinite(se) and se > 0):
        return ("no change" if se == 0 and xa == xb else "?"), float("nan")
    dof = welch_dof(sa, na, sb, nb)
    if not math.isfinite(dof):
        return "?", float("nan")
    critical = stats.t.ppf(1.0 - alpha / 2.0, dof) * se
    return ("rises" if xb - xa > critical else "drops" if xa - xb > critical else "no change"), critical


def steps(speeds, alpha):
    """[(from rpm, to rpm, label, verdict, difference, critical difference)] between consecutive speeds."""
    out = []
    for (a, ma, _, na), (b, mb, _, nb) in zip(speeds, speeds[1:]):
        for label, col, scale, _, _ in METRICS:
            (xa, sa), (xb, sb) = ma[col], mb[col]
            verdict, critical = change(xa, sa, na, xb, sb, nb, alpha)
            out.append((a, b, label, verdict, (xb - xa) * scale, critical * scale))
    return out


def answer(step_rows, a=27.0, b=28.0):
    """What the a -> b step of Hc says, with its numbers; None without that step."""
    for x, y, label, verdict, diff, critical in step_rows:
        if (x, y, label) == (a, b, "Hc"):
            return verdict, diff, critical
    return None


def step_change(speeds, col, a=27.0, b=28.0):
    """(b - a, its standard error, the pair's se and batches) of one metric between two speeds of a
    study; None where the study lacks either speed."""
    found = {rpm: (avg[col], n) for rpm, avg, _, n in speeds}
    if a not in found or b not in found:
        return None
    ((xa, sa), na), ((xb, sb), nb) = found[a], found[b]
    return xb - xa, math.hypot(sa, sb), (sa, na, sb, nb)


def catchable(parts, alpha, power=0.8):
    """The true change a step's test (two-sided Welch at alpha, Satterthwaite's degrees of freedom,
    as `change`) catches with probability `power`."""
    sa, na, sb, nb = parts
    return detectable_sum([(sa, na), (sb, nb)], lambda dof: stats.t.ppf(1.0 - alpha / 2.0, dof), power)


def contrast(x, y, alpha):
    """Whether two studies' changes at one step differ: (difference, critical difference) by a
    two-sided Welch test at alpha on the four batch-mean errors (Satterthwaite's degrees of freedom);
    x, y as step_change gives them."""
    (dx, sx, (s1, n1, s2, n2)), (dy, sy, (s3, n3, s4, n4)) = x, y
    se = math.hypot(sx, sy)
    dof = satterthwaite([(s1, n1), (s2, n2), (s3, n3), (s4, n4)]) if se > 0 else float("nan")
    if not math.isfinite(dof):
        return dy - dx, float("nan")
    return dy - dx, stats.t.ppf(1.0 - alpha / 2.0, dof) * se


def contrast_catchable(x, y, alpha, power=0.8):
    """The true difference between two studies' steps that `contrast` calls with probability
    `power` (x, y as step_change gives them): its four batch-mean errors simulated."""
    (_, _, (s1, n1, s2, n2)), (_, _, (s3, n3, s4, n4)) = x, y
    return detectable_sum([(s1, n1), (s2, n2), (s3, n3), (s4, n4)],
                          lambda dof: stats.t.ppf(1.0 - alpha / 2.0, dof), power)


# how "lets go" is read off `bed_turn`, said once for both texts that use it
RELEASE_RULE = (f"`bed_turn`, a running median over 5 samples, below {LETS_GO:g} from then on; "
                f"half-way: below {HALF_WAY:g}")


def ramp_clock(ramp, at):
    """A point along a step ramp (`lets_go`'s (time, rpm, time into that speed)) as one number:
    the speed plus the fraction of its run gone, so that 26.7 is 70 % into 26 rpm. The run is
    the span from the speed before's last sample to this speed's last."""
    _, rpm, into = at
    before = [s[0] for s in ramp if s[1] < rpm]
    own = [s[0] for s in ramp if s[1] == rpm]
    run = max(own) - (max(before) if before else min(own))
    return rpm + into / run if run > 0 else float(rpm)


def release(ramp):
    """Where along a ramp the bed lets go (`lets_go`: its onset, `bed_turn` below LETS_GO for
    good, and half-way, below HALF_WAY) as (onset, text), or None where it never does."""
    onset, half = lets_go(ramp), lets_go(ramp, HALF_WAY)
    if not onset:
        return None
    text = f"from {onset[2]:.2f} s into {onset[1]:g} rpm"
    text += f", half-way {half[2]:.2f} s into {half[1]:g} rpm" if half else ", not yet half-way"
    return onset, text


def released_line(studies, ramps):
    """Where along its ramp each study's bed lets go of the drum, in one line. A release that
    starts before 28 rpm is under way or over when the 27 -> 28 rpm step is measured: that step
    then measures a bed letting go or let go, not a release caused by the step."""
    parts = []
    for (label, speeds), ramp in zip(studies, ramps):
        if not ramp:
            continue
        got = release(ramp)
        if not got:
            parts.append(f"with {label} not up to {max(r[1] for r in ramp):g} rpm")
            continue
        onset, text = got
        if onset[1] < 28:
            text += " (before the 27 → 28 rpm step, which then measures a bed letting go or let go)"
        parts.append(f"with {label} {text}")
    if not parts:
        return []
    return [f"Along the ramp the bed lets go of the drum ({RELEASE_RULE}): " + "; ".join(parts)
            + ". The thesis saw its drop between 27 and 28 rpm.", ""]


def study_settings(docs, name):
    """The settings a study ran with (steady.py's run.json: its input variables and period), read
    from its first speed: studies with the same settings are histories of one set."""
    for folder in sorted((docs / name).glob("*rpm"), key=lambda p: float(p.name[:-3])):
        path = folder / "run.json"
        if path.exists():
            settings = json.loads(path.read_text())["settings"]
            return tuple(sorted(settings["variables"].items())) + (("period", settings["period"]),)
    return None


# the input variables a set differs in, by what they are (a label names the conventions itself)
PLAIN = {"dt": "dt {} s", "exact": "exactRestitution {}", "conventions": "conventions {}"}


def set_names(sets, labels=None):
    """A name per set of settings: the settings in which the sets differ ('default' where a set
    leaves one unset). With `labels` ({set: the label of its first history}) the label names the
    set, by what it is ("thesis table (bead-drum mu 0.95)"), followed by the other settings it
    differs in, in words (the conventions are the label's)."""
    keys = [dict(k or ()) for k in dict.fromkeys(sets)]
    differing = sorted({v for k in keys for v in k if len({k2.get(v) for k2 in keys}) > 1})
    if labels:
        rest = [v for v in differing if v != "conventions"]
        return {k: labels[k] + (" at " + ", ".join(PLAIN.get(v, v + " {}").format(dict(k or ()).get(v, "default"))
                                                  for v in rest) if rest else "")
                for k in dict.fromkeys(sets)}
    return {k: ", ".join(f"{v} {dict(k or ()).get(v, 'default')}" for v in differing) or "one set"
            for k in dict.fromkeys(sets)}


def between_histories(values, sets):
    """With exactly two sets of at least two histories each: (mean of the second set minus the
    first's, Welch's p) on one value per history, the history as the unit; else None."""
    keys = list(dict.fromkeys(sets))
    groups = [[v for v, k in zip(values, sets) if k == key] for key in keys]
    if len(groups) != 2 or min(len(g) for g in groups) < 2:
        return None
    return statistics.fmean(groups[1]) - statistics.fmean(groups[0]), float(
        stats.ttest_ind(groups[1], groups[0], equal_var=False).pvalue)


def plain_answer(sets, onsets, labels=None):
    """The answer in plain words, for the page's first lines: where each set's bed lets go along the
    ramp (the onsets on the ramp clock, by history) against the thesis' drop between 27 and 28 rpm;
    [] where a history has no onset."""
    if not onsets or any(o is None for o in onsets):
        return []
    names = set_names(sets, labels)
    said = []
    for k in names:
        v = [o for o, s in zip(onsets, sets) if s == k]
        lo, hi = min(v), max(v)
        where = f"at {lo:.1f} rpm" if hi - lo < 0.05 else f"between {lo:.1f} and {hi:.1f} rpm"
        if hi < 27.0:
            near = "before the speed of the thesis' drop"
        elif lo > 28.0:
            near = "so it is still carried at 28 rpm"
        else:
            near = "where the thesis saw its drop"
        said.append(f"with {names[k]}, the bed lets go of the drum {where} ({len(v)} histories), {near}")
    return ["In plain words: the thesis saw its drop between 27 and 28 rpm; " + "; ".join(said) + ". Which of "
            "the settings that differ moves the release is the question of docs/drum/release.csv (the "
            "bead-drum friction, then YADE's other conventions one at a time).", ""]


def sets_headline(verdicts, sets, pairs, level, onsets=None, robust=None, changes=None, labels=None):
    """The answer per set of settings, over its histories. First where each history's bed lets go
    along the ramp (`onsets`: ramp_clock of each release onset, None where a bed never lets go):
    its spread within a set against the gap between sets, described (a handful of histories; with
    two sets of two or more, Welch's p with the history as the unit). Then in how many histories
    Hc drops at the 27 -> 28 rpm step, with how many of the windows of window_section call that
    drop (`robust`: per history the verdicts over WINDOWS). Last the contrasts between sets, with
    what their error bars leave out, and the sets' steps (`changes`, one per history) compared
    with the history as the unit. Histories are listed in the order given. `labels`: set_names'."""
    names = set_names(sets, labels)
    lines = []
    if onsets and all(o is not None for o in onsets):
        by_set = {k: [o for o, s in zip(onsets, sets) if s == k] for k in names}
        parts = [f"with {names[k]} at " + " and ".join(f"{o:.1f}" for o in v) + " rpm"
                 + (f" ({max(v) - min(v):.1f} apart)" if len(v) > 1 else "") for k, v in by_set.items()]
        gaps = [abs(a - b) for i, (ka, a) in enumerate(zip(sets, onsets)) for kb, b in zip(sets[i + 1:], onsets[i + 1:])
                if ka != kb]
        text = ("**By set of settings, where the bed lets go of the drum along the ramp** (the onset on the ramp "
                "clock, a speed plus the fraction of its run gone, by history; described over "
                f"{len(onsets)} histories): " + "; ".join(parts) + ".")
        if gaps:
            text += f" Between sets: {min(gaps):.1f}-{max(gaps):.1f} rpm"
            unit = between_histories(onsets, sets)
            text += (f" (with the history as the unit, Welch's p = {unit[1]:.2f}: two histories a set give such "
                     "a test little power)." if unit else ".")
        lines += [text, ""]
    drops = {k: [i for i, s in enumerate(sets) if s == k] for k in names}
    parts = []
    for k, members in drops.items():
        called = sum(verdicts[i] == "drops" for i in members)
        part = f"with {names[k]} in {called} of {len(members)} histor{'y' if len(members) == 1 else 'ies'}"
        if robust and all(robust[i] for i in members):
            part += (" (a drop called in " + ", ".join(f"{sum(v == 'drops' for v in robust[i])}" for i in members)
                     + f" of {len(robust[members[0]])} windows, by history)")
        parts.append(part)
    lines += ["**By set of settings: Hc drops between 27 and 28 rpm " + "; ".join(parts) + ".**"]
    across = [(i, j, d, c) for i, j, d, c in pairs if sets[i] != sets[j]]
    if across and all(math.isfinite(c) for *_, c in across):
        apart = sum(abs(d) > c for *_, d, c in across)
        lines[-1] += (f" Steps of different sets differ in {apart} of {len(across)} Welch contrasts at {level} "
                      f"(below), which reuse the {len(verdicts)} histories and whose error bars hold only the "
                      "scatter within each run's windows, not the variation between histories: not independent "
                      "evidence.")
    unit = between_histories(changes, sets) if changes else None
    if unit:
        names_in_order = [names[k] for k in dict.fromkeys(sets)]
        lines[-1] += (f" With the history as the unit, the mean step with {names_in_order[1]} minus that with "
                      f"{names_in_order[0]}: {unit[0] * 1e3:+.2f} mm, Welch's p = {unit[1]:.2f}.")
    return lines + [""]


def answer_section(studies, alpha, ramps=None, sets=None, robust=None):
    """The question for two (or more) sets of conventions: does Hc drop between 27 and 28
    rpm with one and not the other? Each study's step by its own test; "one and not the other"
    only where the two steps also differ (their contrast): else the runs do not tell the
    conventions apart at this step, whatever the single tests say. With `ramps` (one per study,
    as ramp_series gives them), also where along the ramp each bed lets go. With `sets` (a key per
    study, as study_settings gives it), studies with the same key are histories of one set of
    settings: the answer is then given per set, and two histories of one set are compared as
    such (a step's error bar is the scatter within its two windows; it does not cover where along
    a ramp a release falls, so two histories' steps near a release may differ beyond it)."""
    if sets is None:
        sets = list(range(len(studies)))
    found, found_sets, onsets, windows = [], [], [], []
    for k, ((label, speeds), key) in enumerate(zip(studies, sets)):
        if got := step_change(speeds, "Hc_m"):
            found.append((label, got))
            found_sets.append(key)
            ramp = ramps[k] if ramps else []
            onset = lets_go(ramp) if ramp else None
            onsets.append(ramp_clock(ramp, onset) if onset else None)
            windows.append(robust[k] if robust else None)
    if len(found) < 2:
        return []
    level = f"{1.0 - alpha:.0%}"
    lines = ["## Answer: 27 → 28 rpm", ""]
    grouped = len(set(found_sets)) < len(found_sets)
    labels = {}  # each set by the label of its first history
    for (label, _), key in zip(found, found_sets):
        labels.setdefault(key, label)
    if grouped:
        lines += plain_answer(found_sets, onsets, labels)
    verdicts = []
    for label, (diff, _, parts) in found:
        verdict, critical = change(0.0, parts[0], parts[1], diff, parts[2], parts[3], alpha)
        verdicts.append(verdict)
        if verdict == "?":
            lines.append(f"- {label}: no verdict ({diff * 1e3:+.2f} mm, but a speed without error bars).")
        else:
            lines.append(f"- {label}: Hc {verdict}, {diff * 1e3:+.2f} ± {critical * 1e3:.2f} mm ({level} interval of "
                         f"the change); a drop of {catchable(parts, alpha) * 1e3:.2f} mm would be caught with 80 % "
                         "probability.")
    lines.append("")
    pairs = [(i, j) + contrast(found[i][1], found[j][1], alpha)
             for i in range(len(found)) for j in range(i + 1, len(found))]
    if grouped and "?" not in verdicts:
        lines += sets_headline(verdicts, found_sets, pairs, level, onsets, windows, [got[0] for _, got in found],
                               labels)
    same = []
    for i, j, difference, critical in pairs:
        (la, a), (lb, b), va, vb = found[i], found[j], verdicts[i], verdicts[j]
        if "?" in (va, vb) or not math.isfinite(critical):
            lines += [f"{la} against {lb}: no verdict (a speed without error bars).", ""]
            continue
        if found_sets[i] == found_sets[j]:
            within = abs(difference) <= critical
            same.append(f"{lb} minus {la}: {difference * 1e3:+.2f} ± {critical * 1e3:.2f} mm ({level}): "
                        + (f"within the steps' combined error bars (a difference of "
                           f"{contrast_catchable(a, b, alpha) * 1e3:.2f} mm would be seen with 80 % probability)"
                           if within else "BEYOND the steps' combined error bars"))
            continue
        differ = abs(difference) > critical
        if (va == "drops") != (vb == "drops"):
            dropper, other = (la, lb) if va == "drops" else (lb, la)
            summary = (f"Hc drops between 27 and 28 rpm with {dropper} and not with {other}, and the two steps "
                       "differ" if differ else
                       f"Hc drops between 27 and 28 rpm with {dropper} alone, but the two steps do not differ: "
                       "these runs do not tell the two apart at this step")
        elif va == "drops":
            summary = "Hc drops between 27 and 28 rpm with both" + (", by different amounts" if differ else "")
        else:
            summary = "Hc drops between 27 and 28 rpm with neither" + ("; the two steps differ" if differ else "")
        # with histories of one set, a pair of runs is no evidence between sets (its error bar holds
        # only the scatter within each run): plain text, after the per-set headline
        lead = (f"Pairwise, within-run scatter only: {summary}" if grouped else f"**{summary}**")
        lines += [f"{lead} ({lb} minus {la}: {difference * 1e3:+.2f} ± {critical * 1e3:.2f} mm, {level}, "
                  "Welch on the four speeds' batch errors, Satterthwaite's degrees of freedom"
                  + ("; see the set's histories above" if grouped else "") + ").", ""]
    if same:
        lines += ["Two histories of one set of settings, their 27 → 28 rpm steps compared (the same contrast): "
                  + "; ".join(same) + ". A step's error bar is the scatter within its two windows; it does not "
                  "cover where along a ramp a release falls, so near a release two histories' steps may differ "
                  "beyond it: there the place of the release, below, is what they can agree on.", ""]
    return lines + released_line(studies, ramps or [])


# the windows the 27 -> 28 rpm answer is read again with: how much of it rests on the choice
WINDOWS = (0.3, 0.4, 0.5, 0.7, 1.0)


def step_by_window(docs, name, batches, alpha):
    """The 27 -> 28 rpm step of Hc read with each of WINDOWS: [(verdict, difference, critical)],
    or [] where the study lacks either speed."""
    cells = []
    for window in WINDOWS:
        got = step_change(study_speeds(docs, name, window, batches), "Hc_m")
        if not got:
            return []
        diff, _, parts = got
        verdict, critical = change(0.0, parts[0], parts[1], diff, parts[2], parts[3], alpha)
        cells.append((verdict, diff, critical))
    return cells


def window_section(labels, by_window, batches, alpha):
    """The 27 -> 28 rpm step of Hc per study (`by_window`: step_by_window's cells per study), read
    with each of WINDOWS: a step that is the tail of a transient (its first speed still drifting)
    changes verdict with the window; a step the speed change causes does not."""
    lines = []
    for label, cells in zip(labels, by_window):
        if cells:
            lines.append(f"| {label} | " + " | ".join(f"{v} ({d * 1e3:+.2f} ± {c * 1e3:.2f})" if v != "?" else "?"
                                                      for v, d, c in cells) + " |")
    if not lines:
        return []
    return (["## The 27 → 28 rpm step by window", "",
             "Hc's step [mm] with each fraction of the runs averaged (the last part of each speed's run; "
             f"{batches} batches, {1.0 - alpha:.0%} interval):", "",
             "| study | " + " | ".join(f"last {w:g}" for w in WINDOWS) + " |", "|---|" + "---|" * len(WINDOWS)]
            + lines + [""])


def first_drop(step_rows):
    """The first step at which Hc drops: (from, to, difference, critical), or None."""
    for x, y, label, verdict, diff, critical in step_rows:
        if label == "Hc" and verdict == "drops":
            return x, y, diff, critical
    return None


def markdown(studies, window, batches, alpha, command, null=None, ramps=None, windows=(), sets=None, robust=None):
    # the answer first, then how the steps were read, then each study
    title = ["# The slip test (Fig. 3.5-3.6): does the bed drop between 27 and 28 rpm?", ""]
    lines = [f"Written by `{command}`. Each speed: the last {window:g} of its run, averaged with a standard "
             f"error by batch means over {batches} contiguous batches; a step counts as a rise or a drop "
             f"where it passes a two-sided Welch t-test at {alpha:g} (per comparison: about {alpha:g} of the "
             "steps without a change read as one). The first row of a study may be the steady speed it "
             "started from (its averages over whole revolutions).", ""]
    if null:
        name, block_s, found, scan = null
        text = []
        for what, lo, hi in (("every speed", -math.inf, math.inf), ("21-35 rpm, the slip's range", 21.0, 35.0)):
            called, compared, pairs = found.counts(lo, hi)
            rate, low, high = found.interval(lo, hi)
            if compared:
                text.append(f"{what}: {called} of {compared} ({rate:.1%}, 95 % interval {low:.1%}-{high:.1%} over "
                            f"{pairs} pairs of pieces)")
        if found.hc:
            called, compared, _ = found.hc.counts()
            rate, low, high = found.hc.interval()
            if compared:
                text.append(f"Hc alone, every speed: {called} of {compared} ({rate:.1%}, 95 % interval "
                            f"{low:.1%}-{high:.1%})")
        rate, low, high = found.interval()  # (every speed's, for the verdict)
        highs = [found.interval(lo, hi)[2] for lo, hi in ((-math.inf, math.inf), (21.0, 35.0))]
        bound = " at every speed" + (f", {highs[1]:.1%} at 21-35 rpm" if math.isfinite(highs[1]) else "")
        reading = ("MORE often than it states: its steps overstate their significance" if low > alpha else
                   f"at a rate not shown to exceed the stated one (the 95 % interval reaches {highs[0]:.1%}"
                   f"{bound}: a rate up to that is not excluded)")
        lines += [f"Where nothing changes: the steady series of `{name}` (each speed from its steady start) cut "
                  f"into consecutive pieces of {block_s:g} s, each read as a speed is here, consecutive pieces "
                  f"compared as steps are; changes called, stated {alpha:.0%} per comparison: "
                  + "; ".join(text) + f". On the drum's own fluctuations this reading calls changes {reading}. "
                  "(Consecutive pairs share a piece, and a piece's batch means may be correlated in time"
                  + (f" (lag-one correlation of Hc's consecutive batch means over each speed's steady series: "
                     f"{min(r for _, r in found.lag1):+.2f} to {max(r for _, r in found.lag1):+.2f})" if found.lag1 else "")
                  + ", so the intervals are approximate. A slip speed's window also holds the rest of its step's transient, "
                  "which steady pieces lack.)",
                  ""]
        above = [piece for piece, got in scan if got.interval()[1] > alpha]
        if above:
            lines[-2] += (f" With pieces of {', '.join(f'{p:g}' for p in above)} s, whose batches are shorter and "
                          "more alike, the rate EXCEEDS the stated one (below): the steps' error bars hold only "
                          "where a run's batches are long enough to be nearly independent.")
        if scan:
            lines += ["The same with other piece lengths (a piece's batches shorten with it, and shorter batches "
                      "are more alike):", "",
                      "| piece [s] | changes called | rate (95 % interval) | Hc alone | Hc's batch means, lag-one "
                      "correlation |", "|---|---|---|---|---|"]
            for piece, got in scan:
                called, compared, _ = got.counts()
                rate, low, high = got.interval()
                hc_called, hc_compared, _ = got.hc.counts()
                lag = [r for _, r in got.lag1]
                lines.append(f"| {piece:g} | {called} of {compared} | {rate:.1%} ({low:.1%}-{high:.1%}) | "
                             f"{hc_called} of {hc_compared} ({hc_called / max(hc_compared, 1):.1%}) | "
                             + (f"{min(lag):+.2f} to {max(lag):+.2f}" if lag else "-") + " |")
            lines.append("")
    lines = (title + answer_section(studies, alpha, ramps, sets, robust) + list(windows)
             + ["## How the steps were read", ""] + lines)
    for k, (label, speeds) in enumerate(studies):
        rows = steps(speeds, alpha)
        got, first = answer(rows), first_drop(rows)
        lines += [f"## {label}", ""]
        if got:
            verdict, diff, critical = got
            caught = catchable(step_change(speeds, "Hc_m")[2], alpha) * 1e3
            lines += [f"**27 → 28 rpm: Hc {verdict}** ({diff:+.2f} mm; a change counts beyond ±{critical:.2f} mm; "
                      f"a drop of {caught:.2f} mm would be caught with 80 % probability).", ""]
        else:
            lines += ["27 → 28 rpm: not run yet.", ""]
        ramp = ramps[k] if ramps else []
        released = release(ramp)
        if released:
            (t, _, _), text = released
            lines += [f"The bed lets go of the drum ({RELEASE_RULE}) at simulated time {t:.2f} s, {text}.", ""]
        elif ramp:
            lines += [f"The bed turns with the drum throughout (`bed_turn` never stays below {LETS_GO:g}).", ""]
        if first:
            lines += [f"First drop of Hc along the steps: {first[0]:g} → {first[1]:g} rpm ({first[2]:+.2f} mm, "
                      f"beyond ±{first[3]:.2f} mm).", ""]
        lines += ["| rpm | run [s] | " + " | ".join(f"{m[0]}{' [' + m[3] + ']' if m[3] else ''}" for m in METRICS) + " |",
                  "|---|---|" + "---|" * len(METRICS)]
        for rpm, avg, seconds, _ in speeds:
            cells = []
            for _, col, scale, _, digits in METRICS:
                v, e = avg[col]
                cells.append(f"{v * scale:.{digits}f} ± {e * scale:.{digits}f}" if math.isfinite(e) else f"{v * scale:.{digits}f}")
            lines.append(f"| {rpm:g} | {'steady start' if not math.isfinite(seconds) else f'{seconds:.2f}'} | "
                         + " | ".join(cells) + " |")
        lines += ["", "| step [rpm] | " + " | ".join(m[0] for m in METRICS) + " |", "|---|" + "---|" * len(METRICS)]
        for k in range(0, len(rows), len(METRICS)):
            chunk = rows[k:k + len(METRICS)]
            lines.append(f"| {chunk[0][0]:g} → {chunk[0][1]:g} | "
                         + " | ".join(f"{v} ({d:+.3g})" for _, _, _, v, d, _ in chunk) + " |")
        lines.append("")
    return "\n".join(lines)


def chart(studies, path, ramps=None):
    fig, axes = charts.figure(2, 2, title="slip test: speed raised step by step", size=(5.5, 4.2))
    for k, (label, speeds) in enumerate(studies):
        ramp = ramps[k] if ramps else []
        if ramp:  # the ramp in time, as Fig. 3.5 shows it; dotted: each speed's start
            t0 = ramp[0][0]
            line, = axes[2].plot([r[0] - t0 for r in ramp], [r[2] * 1e3 for r in ramp], lw=1, label=label)
            axes[3].plot([r[0] - t0 for r in ramp], [r[3] for r in ramp], lw=1, color=line.get_color(), label=label)
            axes[2].annotate(f"{ramp[0][1]:g}", (0.0, 1.0), xycoords=("data", "axes fraction"), fontsize=6, ha="left",
                             va="top")
            for a, b in zip(ramp, ramp[1:]):
                if b[1] != a[1]:
                    for ax in axes[2:]:
                        ax.axvline(b[0] - t0, color=line.get_color(), ls=":", lw=0.6)
                    axes[2].annotate(f"{b[1]:g}", (b[0] - t0, 1.0), xycoords=("data", "axes fraction"),
                                     fontsize=6, ha="left", va="top")

        rpm = [s[0] for s in speeds]
        for ax, col, scale in ((axes[0], "Hc_m", 1e3), (axes[1], "bed_turn_1", 1.0)):
            ax.errorbar(rpm, [s[1][col][0] * scale for s in speeds],
                        yerr=[s[1][col][1] * scale if math.isfinite(s[1][col][1]) else 0.0 for s in speeds],
                        marker="o", capsize=3, label=label)
    axes[0].set_ylabel("centre of mass Hc [mm]")
    axes[1].set_ylabel("bed turn (1: carried by the drum)")
    axes[2].set_ylabel("centre of mass Hc [mm]")
    axes[3].set_ylabel("bed turn")
    axes[3].axhline(LETS_GO, color="grey", ls="--", lw=0.8)
    axes[3].axhline(HALF_WAY, color="grey", ls=":", lw=0.8)
    for ax in axes[:2]:
        ax.set_xlabel("drum speed [rpm]")
    for ax in axes[2:]:
        ax.set_xlabel("time on the ramp [s] (numbers: rpm from there)")
    for ax in axes:
        ax.legend(fontsize=7)
    return charts.save(fig, path)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--study", nargs=2, action="append", metavar=("NAME", "LABEL"), required=True,
                   help="a steady.py study (docs/drum/NAME/<rpm>rpm/series_metrics.csv) and its label")
    p.add_argument("--start", action="append", default=[], metavar="NAME:RPM",
                   help="per --study, in order: the steady speed it started from, as its first point ('-': none)")
    p.add_argument("--window", type=float, default=0.5, help="the last fraction of each run averaged (default: %(default)s)")
    p.add_argument("--batches", type=int, default=3, help="batches for the standard error (default: %(default)s)")
    p.add_argument("--alpha", type=float, default=0.05, help="two-sided test level per step (default: %(default)s)")
    p.add_argument("--null", default="study_thesis", metavar="NAME",
                   help="a steady study whose series, cut into pieces as long as the slip speeds' runs, give "
                        "this reading's false-alarm rate where nothing changes ('-': none; default: %(default)s)")
    p.add_argument("--docs", default=str(harness.REPO / "docs" / "drum"), help="(default: docs/drum)")
    p.add_argument("--out", default=str(harness.REPO / "docs" / "drum" / "slip_test"),
                   help="OUT.md, OUT.csv, OUT.png (default: docs/drum/slip_test)")
    a = p.parse_args(argv)
    if not (0.0 < a.window <= 1.0) or a.batches < 2 or not (0.0 < a.alpha < 1.0):
        p.error(f"--window {a.window} --batches {a.batches} --alpha {a.alpha}: need 0 < window <= 1, batches >= 2, "
                "0 < alpha < 1")
    docs = Path(a.docs)
    starts = a.start + ["-"] * (len(a.study) - len(a.start))
    try:
        studies = []
        for (name, label), start in zip(a.study, starts):
            speeds = study_speeds(docs, name, a.window, a.batches)
            studies.append((label, ([start_row(docs, start)] if start != "-" else []) + speeds))
    except harness.RunFailed as e:
        harness.say("slip", f"ERROR: {e}")
        return 1
    null = None
    runs = [seconds for _, speeds in studies for _, _, seconds, _ in speeds if math.isfinite(seconds)]
    if a.null != "-" and runs and (docs / a.null).is_dir():
        block = statistics.median(runs)
        scan = [(piece, null_rate(docs, a.null, piece, a.window, a.batches, a.alpha))
                for piece in (2 / 3 * block, 5 / 6 * block, block, 7 / 6 * block, 4 / 3 * block)]
        null = (a.null, block, scan[2][1], scan)  # (the runs' own piece length, the middle of the scan)
    out = Path(a.out)
    command = "tools/drum/slip.py " + " ".join(f"--study {n} {shlex.quote(l)}" for n, l in a.study) + "".join(
        f" --start {s}" for s in a.start) + f" --window {a.window:g} --batches {a.batches} --alpha {a.alpha:g}" + (
        f" --null {a.null}" if a.null != "study_thesis" else "")
    ramps = [ramp_series(docs, name) for name, _ in a.study]
    by_window = [step_by_window(docs, name, a.batches, a.alpha) for name, _ in a.study]
    windows = window_section([l for _, l in a.study], by_window, a.batches, a.alpha)
    # a study whose settings are unknown (no run.json) is a set of its own
    sets = [study_settings(docs, name) or (("study", name),) for name, _ in a.study]
    robust = [[v for v, _, _ in cells] for cells in by_window]
    out.with_suffix(".md").write_text(markdown(studies, a.window, a.batches, a.alpha, command, null, ramps, windows,
                                               sets, robust))
    rows = []
    for label, speeds in studies:
        for rpm, avg, seconds, batches in speeds:
            row = {"study": label, "rpm": rpm, "run_s": seconds, "batches": batches}
            for _, col, _, _, _ in METRICS:
                row[col], row[se_column(col)] = avg[col]
            rows.append(row)
    harness.write_csv(out.with_suffix(".csv"), rows)
    chart(studies, out.with_suffix(".png"), ramps)
    harness.say("slip", f"wrote {out.with_suffix('.md')}, .csv, .png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
