#!/usr/bin/python3
"""Two histories of one drum state: do their time averages agree within their error bars?

A speed reached along two histories (arriving from the slower speed and continued from another
state, or two seeds) has one steady state, so its averages must agree within their combined
standard errors; where they do not, the error bars (or the steady-state detection) are wrong. For
each metric of `drum_metrics metrics`:
    t = (a - b) / sqrt(se_a^2 + se_b^2)
against the two-sided Student-t quantile at --alpha, Bonferroni-corrected over the metrics
compared, at the smaller side's degrees of freedom (a batch-means SE from n batches has n - 1):
whatever the ratio of the two standard errors, a method that is right then passes all of them
with probability at least 1 - alpha (Welch's t is at most as wide-tailed as Student's t at the
smaller side's degrees of freedom). Welch-Satterthwaite's degrees of freedom, estimated from the
same few batches, do not keep that rate where one side's error is several times the other's:
3 batches against 5, the 3-batch side's error 3-5 times the other's, 10-13 % false alarms over
7 metrics. The rows come from steady.py's study tables (docs/drum/NAME.csv), by rpm.
Agreement is only as telling as the test's power: each row also gives the true difference the
check would catch with 80 % probability (the check simulated at these standard errors and
batch counts), so that "agree" reads as "no difference as large as this". A side that did not end
by the stop rule (capped, or never found settled) is named as such: its averages are not steady ones.

  tools/drum/histories.py docs/drum/study_thesis.csv docs/drum/history_21rpm_from28.csv --rpm 21 \
      --out docs/drum/histories_21rpm.md
  tools/drum/histories.py docs/drum/study_thesis.csv docs/drum/study_bound.csv --rpm 14,21,28,35 \
      --out docs/drum/histories_bound/README.md

With several speeds, after each speed's own check, the rows of all of them at once: how many lie
beyond 2 combined standard errors against the count error bars that hold give (`pooled`).

Needs: python3-matplotlib (tools/harness), python3-numpy, python3-scipy; drum_metrics.
"""

import argparse
import json
import math
import sys
from pathlib import Path

import numpy as np
from scipy import optimize, stats

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import harness  # noqa: E402


def satterthwaite(parts):
    """Welch-Satterthwaite degrees of freedom of the sum of se^2 over parts [(se, batches)] (batch
    means: n - 1 each); nan where a part has fewer than 2 batches or every se is 0."""
    if any(n - 1 < 1 for _, n in parts) or not any(se > 0 for se, _ in parts):
        return float("nan")
    return sum(se ** 2 for se, _ in parts) ** 2 / sum(se ** 4 / (n - 1) for se, n in parts)


def welch_dof(se_a, batches_a, se_b, batches_b):
    """Welch-Satterthwaite degrees of freedom of se_a^2 + se_b^2."""
    return satterthwaite([(se_a, batches_a), (se_b, batches_b)])


def smaller_dof(batches_a, batches_b):
    """The degrees of freedom the check uses: the smaller side's n - 1 (nan below 2 batches)."""
    dof = min(batches_a, batches_b) - 1
    return dof if dof >= 1 else float("nan")


def detectable(se_a, batches_a, se_b, batches_b, critical_of, power=0.8, replicas=20000):
    """The true difference A - B that this check catches with probability `power`, the two sides'
    standard errors being se_a, se_b from batches_a, batches_b normal batch means. The check itself
    is simulated (`detectable_sum`, at the smaller side's degrees of freedom) -- so its power is the
    procedure's, lower at few batches than a noncentral t at the pooled degrees of freedom says."""
    return detectable_sum([(se_a, batches_a), (se_b, batches_b)], critical_of, power, replicas,
                          dof=smaller_dof(batches_a, batches_b))


def detectable_sum(parts, critical_of, power=0.8, replicas=20000, dof=None):
    """The true difference a Welch check on a sum of independent parts [(se, batches)] catches with
    probability `power` (two studies' steps compared: four parts). Simulated with common random
    numbers and a fixed seed: each replica estimates every part's SE (chi-square with n - 1 degrees
    of freedom), Satterthwaite's degrees of freedom (or the fixed `dof`) and the critical t from
    them (`critical_of(dof)`); nan where a part has fewer than 2 batches or the SEs are all zero."""
    scale = math.sqrt(sum(se ** 2 for se, _ in parts))
    if not (all(n >= 2 for _, n in parts) and scale > 0):
        return float("nan")
    rng = np.random.default_rng(20261204)
    dofs = [n - 1 for _, n in parts]
    est = [se * np.sqrt(rng.chisquare(k, replicas) / k) for (se, _), k in zip(parts, dofs)]
    noise = rng.normal(0.0, scale, replicas)
    if dof is None:
        with np.errstate(invalid="ignore", divide="ignore"):
            dof = sum(e ** 2 for e in est) ** 2 / sum(e ** 4 / k for e, k in zip(est, dofs))
    limit = critical_of(dof) * np.sqrt(sum(e ** 2 for e in est))
    caught = lambda delta: np.mean(np.abs(delta + noise) > limit) - power  # noqa: E731
    hi = scale
    while caught(hi) < 0.0 and hi < 1e4 * scale:
        hi *= 2.0
    return optimize.brentq(caught, 0.0, hi, xtol=1e-6 * scale) if caught(hi) >= 0.0 else float("inf")


def batches(row, m):
    """The batches a side's standard error of metric m stands on: a row with the metric's effective
    degrees of freedom (<key>_dof, tools/drum/estimator.py) counts as that many plus one."""
    dof = row.get(f"{m.get('key')}_dof", math.nan)
    return dof + 1.0 if isinstance(dof, float) and math.isfinite(dof) else row["batches"]


def compare(a, b, metrics, alpha=0.05, power=None):
    """One row per metric with finite values on both sides: both averages, the difference, its
    combined SE, t, the degrees of freedom, the critical t and whether they agree; with `power`,
    also the difference the check would catch with that probability (`detectable`)."""
    usable = [m for m in metrics if all(math.isfinite(r[c]) for r in (a, b) for c in (m["column"], m["se_column"]))]
    critical_of = lambda dof: stats.t.ppf(1 - alpha / (2 * len(usable)), dof)  # noqa: E731 (Bonferroni)
    rows = []
    for m in usable:
        va, sa, vb, sb = a[m["column"]], a[m["se_column"]], b[m["column"]], b[m["se_column"]]
        se = math.hypot(sa, sb)
        na, nb = batches(a, m), batches(b, m)
        dof = smaller_dof(na, nb)
        critical = critical_of(dof) if math.isfinite(dof) else float("nan")
        t = (va - vb) / se if se > 0 else float("inf") if va != vb else 0.0
        rows.append({"metric": m["label"], "unit": m["unit"], "a": va, "se_a": sa, "b": vb, "se_b": sb,
                     "difference": va - vb, "combined_se": se, "t": t, "dof": dof,
                     "welch_dof": welch_dof(sa, na, sb, nb), "critical_t": critical,
                     "agree": abs(t) <= critical})
        if power is not None:
            rows[-1]["detectable"] = detectable(sa, na, sb, nb, critical_of, power)
    return rows


# the check's outcome, agreeing and not, by what A and B are: two histories of one state (a
# difference is a failure of the error bars), or one state at two timesteps, under two sets of
# conventions or two other settings (a difference is the change's effect)
VERDICTS = {
    "histories": ("The histories agree within their error bars.",
                  "The histories DISAGREE: the error bars or the steady-state detection do not hold."),
    "timesteps": ("The two timesteps agree within the error bars.",
                  "The two timesteps DIFFER beyond the error bars (rows marked **no**): the timestep, with "
                  "whatever else differs (named below), changes the result there."),
    "conventions": ("The two sets of conventions agree within the error bars.",
                    "The two sets of conventions DIFFER beyond the error bars (rows marked **no**): they change "
                    "the result there."),
    "settings": ("The two settings agree within the error bars.",
                 "The two settings DIFFER beyond the error bars (rows marked **no**): the change of settings "
                 "changes the result there."),
}


def verdict(agree, kind="histories"):
    """The sentence for the check's outcome (VERDICTS)."""
    return VERDICTS[kind][0 if agree else 1]


def not_steady(side, row):
    """The sentence for a side whose speed did not end by the stop rule (steady.py's `done` False: the
    simulated-time cap, or a ramp's fixed time; its averages then span the series' second half, or
    what the detection called steady), empty otherwise: its error bars were not checked against the
    targets, and a drift inside its window shows in neither the averages nor their errors."""
    settled = "settle_s" not in row or (isinstance(row["settle_s"], float) and math.isfinite(row["settle_s"]))
    if str(row.get("done", "True")) == "True" and settled:  # (a table without these columns: no claim)
        return ""
    how = "settled, " if settled else "not found settled (averaged over the series' second half), "
    return (f"{side} did not end by the stop rule ({how}`done` {row.get('done')}): its averages are not those of "
            "a run that met the targets, so read this check as weaker than it looks. ")


def revolutions(row):
    """"N batches, R revolutions" of a side, or what stands in for them where it has no steady window."""
    r = row.get("revolutions")
    span = f"{r:.1f} revolutions" if isinstance(r, float) and math.isfinite(r) else "no steady window"
    return f"{row['batches']:g} batches, {span}"


def row_at(table, rpm):
    rows = [r for r in harness.read_csv(table) if r["rpm"] == rpm]
    if not rows:
        raise SystemExit(f"histories: {table} has no row for {rpm:g} rpm")
    return rows[0]


def variables(table, rpm):
    """The `-var` settings a study ran this speed with (steady.py's run.json beside its table:
    docs/drum/NAME/<rpm>rpm/run.json), with the period; None where there is no such record."""
    record = Path(table).with_suffix("") / f"{rpm:g}rpm" / "run.json"
    if not record.exists():
        return None
    settings = json.loads(record.read_text()).get("settings")
    if not isinstance(settings, dict):
        return None
    return {"period": settings.get("period"), **(settings.get("variables") or {})}


def same_value(x, y):
    """Two settings as written (strings): equal, also as numbers ("2e-5" and "2e-05")."""
    if x == y:
        return True
    try:
        return float(x) == float(y)
    except (TypeError, ValueError):
        return False


def differing(a, b):
    """The settings that differ between two studies' `variables`: [(name, in a, in b)], an unset
    one as "default" (drum.in's, whatever it was then); None where either has no record."""
    if a is None or b is None:
        return None
    names = sorted(set(a) | set(b))
    return [(k, a.get(k, "default"), b.get(k, "default")) for k in names
            if not same_value(a.get(k, "default"), b.get(k, "default"))]


def settings_sentence(diff):
    """What else separates A and B besides what the comparison is about (a difference found is
    theirs together)."""
    if diff is None:
        return "(No run record of A's or B's settings beside its table: what else differs is not checked.)"
    if not diff:
        return "A and B ran with the same `-var` settings."
    listed = ", ".join(f"{k} {va} against {vb}" for k, va, vb in diff)
    return (f"A and B differ in these `-var` settings: {listed}. A difference found is theirs together, "
            "not one setting's alone.")


def beyond(rows, t=2.0, dof="dof"):
    """How many rows lie beyond |t| = t, and each row's chance of it if the error bars hold: P(|T| > t)
    at the row's degrees of freedom (the smaller side's), at least the check's own chance whatever
    the ratio of the two errors (3 batches a side, equal errors: 0.18 against 0.11), so the count
    leans towards agreeing. It grows with every speed compared, so against error bars a little small
    everywhere it sees more than each speed's Bonferroni check, at fewer false alarms (test_histories)."""
    usable = [r for r in rows if math.isfinite(r[dof])]
    return sum(abs(r["t"]) > t for r in usable), [2.0 * stats.t.sf(t, r[dof]) for r in usable]


def at_least(k, probabilities):
    """P(at least k of independent events with these probabilities) (the Poisson-binomial tail)."""
    counts = np.zeros(len(probabilities) + 1)
    counts[0] = 1.0
    for q in probabilities:
        counts[1:] = counts[1:] * (1.0 - q) + counts[:-1] * q
        counts[0] *= 1.0 - q
    return float(counts[k:].sum())


def pooled(rows, t=2.0):
    """The sentence for several speeds at once: how many rows lie beyond |t| against chance."""
    k, probabilities = beyond(rows, t)
    expected, tail = sum(probabilities), at_least(k, probabilities)
    text = (f"Over these speeds, {k} of {len(probabilities)} rows lie more than {t:g} combined standard "
            f"errors apart, where error bars that hold give {expected:.1f} on average (each row's "
            f"P(|t| > {t:g}) at its degrees of freedom: at least the check's own chance); {k} or more would come by chance with probability "
            f"{tail:.2g} if the rows were independent (the metrics of one speed are correlated, so this is a "
            f"guide, not a test at a stated rate).")
    if tail < 0.05:
        text += " More rows lie beyond it than chance gives: the error bars may be somewhat small."
    if all("welch_dof" in r for r in rows):
        # the same count at Welch-Satterthwaite's degrees of freedom: nearer the true chance where the
        # two sides' errors are alike, too low where one is several times the other (module note)
        k, welch = beyond(rows, t, "welch_dof")
        text += (f" At Welch-Satterthwaite's degrees of freedom instead, {sum(welch):.1f} on average, and {k} or "
                 f"more with probability {at_least(k, welch):.2g}.")
    return text


def speeds(text):
    try:
        out = [float(x) for x in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"--rpm wants speeds separated by commas, got {text!r}") from None
    twice = sorted({x for x in out if out.count(x) > 1})
    if twice:  # it would count that speed's rows twice
        raise argparse.ArgumentTypeError(f"--rpm lists {', '.join(f'{x:g}' for x in twice)} more than once")
    return out


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("a", help="study table (steady.py's docs/drum/NAME.csv) of the first history")
    p.add_argument("b", help="study table of the second history")
    p.add_argument("--rpm", type=speeds, required=True,
                   help="the speed to compare, or several separated by commas (each checked on its own, then "
                        "how many rows lie beyond 2 standard errors over all of them, against chance)")
    p.add_argument("--alpha", type=float, default=0.05, help="family-wise false-alarm rate (default: %(default)s)")
    p.add_argument("--out", help="also write the comparison as Markdown here")
    kind = p.add_mutually_exclusive_group()
    kind.add_argument("--timesteps", dest="kind", action="store_const", const="timesteps", default="histories",
                      help="A and B are one state at two timesteps: a difference is the timestep's effect, not a "
                           "failure of the error bars")
    kind.add_argument("--conventions", dest="kind", action="store_const", const="conventions",
                      help="A and B are one speed under two sets of conventions (material table, mixing rules): "
                           "a difference is the set's effect, with whatever else differs (the output lists it)")
    kind.add_argument("--settings", dest="kind", action="store_const", const="settings",
                      help="A and B are one speed under two other settings (e.g. the drum's wall, named in the "
                           "output): a difference is the settings' effect")
    args = p.parse_args(argv)
    texts, every_row, agree = [], [], True
    for rpm in args.rpm:
        a, b = row_at(args.a, rpm), row_at(args.b, rpm)
        rows = compare(a, b, harness.drum_metric_table(), args.alpha, power=0.8)
        table = harness.markdown(rows, [
            ("metric", lambda r: f"{r['metric']} [{r['unit']}]", None),
            ("A", lambda r: f"{r['a']:.5g} ± {r['se_a']:.2g}", None),
            ("B", lambda r: f"{r['b']:.5g} ± {r['se_b']:.2g}", None),
            ("A − B", "difference", "{:.3g}"), ("t", "t", "{:.2f}"), ("dof", "dof", "{:.1f}"),
            ("critical t", "critical_t", "{:.2f}"), ("agree", lambda r: "yes" if r["agree"] else "**no**", None),
            ("caught at 80 %", "detectable", "{:.3g}")])
        here = all(r["agree"] for r in rows)
        # the answer first, then how it was reached
        texts.append(f"**{rpm:g} rpm: {verdict(here, args.kind)}** "
                     f"{settings_sentence(differing(variables(args.a, rpm), variables(args.b, rpm)))}\n\n"
                     f"A: `{args.a}` ({revolutions(a)}), B: `{args.b}` ({revolutions(b)}); two-sided "
                     f"{args.alpha:g} family-wise (Bonferroni over {len(rows)} metrics). \"caught at 80 %\": the "
                     f"true difference this check would catch with 80 % probability at these degrees of freedom (a "
                     f"smaller one may pass unseen).\n\n{table}\n{not_steady('A', a)}{not_steady('B', b)}")
        every_row += rows
        agree = agree and here
    if len(args.rpm) > 1:
        texts.append(pooled(every_row) + "\n")
    text = "\n".join(texts)
    print(text)
    if args.out:
        command = "tools/drum/histories.py " + " ".join(argv if argv is not None else sys.argv[1:])
        Path(args.out).write_text(harness.generated_note(command) + "\n" + text)
    return 0 if agree else 1


if __name__ == "__main__":
    sys.exit(main())
