#!/usr/bin/python3
"""Two histories of one drum state: do their time averages agree within their error bars?

A speed reached along two histories (arriving from the slower speed and continued from another
state, or two seeds) has one steady state, so its averages must agree within their combined
standard errors; where they do not, the error bars (or the steady-state detection) are wrong. For
each metric of `drum_metrics metrics`:
    t = (a - b) / sqrt(se_a^2 + se_b^2)
with Welch-Satterthwaite degrees of freedom from each side's batches (a batch-means SE from n
batches has n - 1), against the two-sided Student-t quantile at --alpha, Bonferroni-corrected
over the metrics compared (so a method that is right passes all of them with probability
1 - alpha). The rows come from steady.py's study tables (docs/drum/NAME.csv), by rpm.

  tools/drum/histories.py docs/drum/study_thesis.csv docs/drum/history_21rpm_settled.csv --rpm 21 \
      --out docs/drum/histories_21rpm.md
"""

import argparse
import math
import sys
from pathlib import Path

from scipy import stats

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import harness  # noqa: E402


def welch_dof(se_a, batches_a, se_b, batches_b):
    """Welch-Satterthwaite degrees of freedom of se_a^2 + se_b^2 (batch means: n - 1 each)."""
    na, nb = batches_a - 1, batches_b - 1
    if na < 1 or nb < 1:
        return float("nan")
    return (se_a ** 2 + se_b ** 2) ** 2 / (se_a ** 4 / na + se_b ** 4 / nb)


def compare(a, b, metrics, alpha=0.05):
    """One row per metric with finite values on both sides: both averages, the difference, its
    combined SE, t, the degrees of freedom, the critical t and whether they agree."""
    usable = [m for m in metrics if all(math.isfinite(r[c]) for r in (a, b) for c in (m["column"], m["se_column"]))]
    rows = []
    for m in usable:
        va, sa, vb, sb = a[m["column"]], a[m["se_column"]], b[m["column"]], b[m["se_column"]]
        se = math.hypot(sa, sb)
        dof = welch_dof(sa, a["batches"], sb, b["batches"])
        critical = stats.t.ppf(1 - alpha / (2 * len(usable)), dof) if math.isfinite(dof) else float("nan")
        t = (va - vb) / se if se > 0 else float("inf") if va != vb else 0.0
        rows.append({"metric": m["label"], "unit": m["unit"], "a": va, "se_a": sa, "b": vb, "se_b": sb,
                     "difference": va - vb, "combined_se": se, "t": t, "dof": dof, "critical_t": critical,
                     "agree": abs(t) <= critical})
    return rows


def verdict(agree, timesteps=False):
    if timesteps:
        return ("The two timesteps agree within the error bars." if agree else
                "The two timesteps DIFFER beyond the error bars: the timestep changes the result.")
    return ("The histories agree within their error bars." if agree else
            "The histories DISAGREE: the error bars or the steady-state detection do not hold.")


def row_at(table, rpm):
    rows = [r for r in harness.read_csv(table) if r["rpm"] == rpm]
    if not rows:
        raise SystemExit(f"histories: {table} has no row for {rpm:g} rpm")
    return rows[0]


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("a", help="study table (steady.py's docs/drum/NAME.csv) of the first history")
    p.add_argument("b", help="study table of the second history")
    p.add_argument("--rpm", type=float, required=True, help="the speed to compare")
    p.add_argument("--alpha", type=float, default=0.05, help="family-wise false-alarm rate (default: %(default)s)")
    p.add_argument("--out", help="also write the comparison as Markdown here")
    p.add_argument("--timesteps", action="store_true",
                   help="A and B are one state at two timesteps: a difference is the timestep's effect, not a "
                        "failure of the error bars")
    args = p.parse_args(argv)
    a, b = row_at(args.a, args.rpm), row_at(args.b, args.rpm)
    rows = compare(a, b, harness.drum_metric_table(), args.alpha)
    table = harness.markdown(rows, [
        ("metric", lambda r: f"{r['metric']} [{r['unit']}]", None),
        ("A", lambda r: f"{r['a']:.5g} ± {r['se_a']:.2g}", None), ("B", lambda r: f"{r['b']:.5g} ± {r['se_b']:.2g}", None),
        ("A − B", "difference", "{:.3g}"), ("t", "t", "{:.2f}"), ("dof", "dof", "{:.1f}"),
        ("critical t", "critical_t", "{:.2f}"), ("agree", lambda r: "yes" if r["agree"] else "**no**", None)])
    agree = all(r["agree"] for r in rows)
    text = (f"{args.rpm:g} rpm, A: `{args.a}` ({a['batches']:g} batches, {a['revolutions']:.1f} revolutions), "
            f"B: `{args.b}` ({b['batches']:g} batches, {b['revolutions']:.1f} revolutions); two-sided "
            f"{args.alpha:g} family-wise (Bonferroni over {len(rows)} metrics).\n\n{table}\n"
            f"{verdict(agree, args.timesteps)}\n")
    print(text)
    if args.out:
        command = "tools/drum/histories.py " + " ".join(argv if argv is not None else sys.argv[1:])
        Path(args.out).write_text(harness.generated_note(command) + "\n" + text)
    return 0 if agree else 1


if __name__ == "__main__":
    sys.exit(main())
