#!/usr/bin/python3
"""The thesis' Fig. 3.2-3.4 trend beside the steady studies, step by step: docs/drum/thesis_trend.md.

Section 3.4 reads its figures as: the head rises up to 21 rpm, drops suddenly at 28 rpm (with the
shoulder Hd and the centre of mass Hc) and rises again from 35 rpm (tools/drum/report.py's
THESIS_FINDINGS). For each step between consecutive speeds this page sets what the thesis says
beside what each study shows: the change of the metric with its 95 % interval (Welch, from the
rows' 95 % half-widths and effective degrees of freedom where the table has them, else from the
batch-means standard errors at batches - 1 degrees of freedom), called a rise or a drop where the
interval excludes zero. The studies: study_thesis (the thesis' Table 3.1, tc/5 with
exactRestitution) and study_yade (YADE 1.12's conventions: bead-drum mu 0.5, facet meff m/2, no
attraction; the nominal law at tc/10; its 7 and 14 rpm from study_yade_low), each as far as it has run. The answer first: does the drop
come at 28 rpm, and does the bed rise again from 35?

  tools/drum/thesis_trend.py            # docs/drum/thesis_trend.md

Needs: python3-scipy.
"""

import argparse
import math
import sys
from pathlib import Path

from scipy import stats

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))
import harness  # noqa: E402
import estimator  # noqa: E402
import report  # noqa: E402

DOCS = harness.REPO / "docs" / "drum"
# (name, label, the tables its speeds come from: study_yade_low holds YADE's 7 and 14 rpm)
STUDIES = [("study_thesis", "the thesis' table (bead–drum μ 0.95), tc/5, exactRestitution", ["study_thesis"]),
           ("study_yade", "YADE 1.12's conventions (bead–drum μ 0.5, facet meff m/2, no attraction), tc/10",
            ["study_yade_low", "study_yade"])]
METRICS = [("Hh", "Hh_m"), ("Hd", "Hd_m"), ("Hc", "Hc_m")]
SPEEDS = (7, 14, 21, 28, 35, 42, 49, 56, 63)


def interval(row, key, column):
    """The row's estimate of `column` as an estimator.Interval: from its 95 % half-width and dof
    where the table has them, else its batch-means standard error at batches - 1 dof."""
    unit = column.rsplit("_", 1)[1]
    mean = float(row[column])
    hw, dof = row.get(f"{key}_hw95_{unit}"), row.get(f"{key}_dof")
    if hw not in (None, "") and dof not in (None, "") and math.isfinite(float(hw)) and float(dof) > 0:
        hw, dof = float(hw), float(dof)
        return estimator.Interval(mean, hw, dof, math.nan, hw / float(stats.t.ppf(0.975, dof)))
    se, dof = float(row[f"{key}_se_{unit}"]), float(row.get("batches") or math.nan) - 1.0
    return estimator.Interval(mean, float(stats.t.ppf(0.975, dof)) * se if dof > 0 else math.nan, dof, math.nan, se)


def step(a, b, key, column):
    """(verdict, b - a, its 95 % half-width): 'rises' / 'drops' where the interval excludes 0."""
    d, hw, _ = estimator.compare(interval(b, key, column), interval(a, key, column))
    if not math.isfinite(hw):
        return "?", d, hw
    return ("rises" if d > hw else "drops" if d < -hw else "no change"), d, hw


def steps(rows):
    """{(key, from rpm, to rpm): (verdict, difference [m], half-width [m])} between the study's
    consecutive speeds of the thesis' chain."""
    by = {round(float(r["rpm"])): r for r in rows}
    out = {}
    for a, b in zip(SPEEDS, SPEEDS[1:]):
        if a in by and b in by:
            for key, column in METRICS:
                out[(key, a, b)] = step(by[a], by[b], key, column)
    return out


def answer(name, label, found):
    """Two sentences for one study: the 21 -> 28 rpm step, and the steps from 35 rpm on."""
    if not found:
        return f"With {label}: not yet two consecutive speeds."
    drop = [k for k in ("Hh", "Hd", "Hc") if (k, 21, 28) in found]
    text = f"With {label} (`{name}`): "
    if drop:
        calls = {k: found[(k, 21, 28)][0] for k in drop}
        dropped = [k for k, v in calls.items() if v == "drops"]
        what = ("the drop at 28 rpm appears" if len(dropped) == len(drop) else
                "no drop at 28 rpm" if not dropped else f"a drop at 28 rpm in {' and '.join(dropped)} only")
        text += what + " (21 → 28: " + ", ".join(f"{k} {calls[k]} {1e3 * found[(k, 21, 28)][1]:+.2f} ± "
                                                f"{1e3 * found[(k, 21, 28)][2]:.2f} mm" for k in drop) + ")"
    else:
        text += "21 and 28 rpm not both run yet"
    rise = [(a, b) for a, b in zip(SPEEDS[4:], SPEEDS[5:]) if ("Hh", a, b) in found]
    if rise:
        up = sum(found[("Hh", a, b)][0] == "rises" for a, b in rise)
        text += f"; from 35 rpm the head rises in {up} of {len(rise)} steps"
        if ("Hh", 28, 35) in found:
            text += f" (28 → 35: {found[('Hh', 28, 35)][0]})"
    else:
        text += "; from 35 rpm: not run yet"
    return text + "."


def page(studies):
    """The page: `studies` [(name, label, rows)]."""
    found = [(name, label, steps(rows)) for name, label, rows in studies]
    lines = ["# The thesis' trend (Fig. 3.2–3.4) beside the steady studies", "",
             "<!-- Generated by `tools/drum/thesis_trend.py` from the studies' tables; edit the generator. -->", "",
             "## Answer", "", "The thesis: the head rises up to 21 rpm, drops suddenly at 28 rpm with the shoulder "
             "and the centre of mass, and rises again from 35 rpm. " + " ".join(answer(*f) for f in found), "",
             "## Step by step", "",
             "Each study's change between consecutive speeds, run minus the speed before, with its 95 % interval "
             "(Welch); a rise or a drop where the interval excludes zero. Blank: a step the thesis does not describe, "
             "or a speed not yet run.", "",
             "| metric | step [rpm] | thesis | " + " | ".join(f"`{n}` [mm]" for n, _, _ in found) + " |",
             "|---|---|---|" + "---|" * len(found)]
    for key, _ in METRICS:
        for a, b in zip(SPEEDS, SPEEDS[1:]):
            thesis = report.THESIS_FINDINGS[key].get((a, b), "")
            cells = []
            for _, _, f in found:
                v = f.get((key, a, b))
                cells.append(f"{v[0]} {1e3 * v[1]:+.2f} ± {1e3 * v[2]:.2f}" if v else "")
            if thesis or any(cells):
                lines.append(f"| {key} | {a} → {b} | {thesis} | " + " | ".join(cells) + " |")
    lines += ["", "Studies: " + "; ".join(f"`{n}`: {label}" for n, label, _ in found) + ". Their reports: "
              + ", ".join(f"[{n}]({n}.md)" for n, _, _ in found) + ".", ""]
    return "\n".join(lines)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--docs", type=Path, default=DOCS)
    p.add_argument("--out", type=Path, default=DOCS / "thesis_trend.md")
    a = p.parse_args(argv)
    studies = [(name, label, [r for t in tables if (a.docs / f"{t}.csv").exists()
                              for r in harness.read_csv(a.docs / f"{t}.csv")])
               for name, label, tables in STUDIES]
    a.out.write_text(page(studies))
    return 0


if __name__ == "__main__":
    sys.exit(main())
