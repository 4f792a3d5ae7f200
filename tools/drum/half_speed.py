#!/usr/bin/python3
"""Is a released bed the carried bed at its own, slower rotation? Once the bed lets go of the drum
(35 rpm and up with the thesis' table) it turns at about half the drum's speed (`bed_turn`, the
bed's rotation rate over the drum's). This reads each released speed w of a study against the
carried speeds of the same study at w times that bed turn: per metric, the carried curve is
interpolated there (quadratic through the three carried speeds nearest to it) and the released
bed's value set against it with a 95 % interval.

The interval of the difference combines the released value's and the interpolated value's
standard errors (from the table's 95 % half-widths and effective degrees of freedom, tools/drum/
estimator.py; Welch-Satterthwaite) and, added to its half-width, two terms the statistics do not
hold: the interpolation's own error (the quadratic's distance from the straight line between the
two neighbours) and the bed turn's (the curve's slope times w times the bed turn's half-width).
Released speeds whose w x bed turn lies outside the carried speeds are not read (extrapolation).

Metrics read: the bed's shape and flow (Hc, Hh, Hd, angle, flowing-layer thickness, surface
velocity); the wall's (drum force, bed turn, slip, roll) describe the contact that released, and
are not expected to follow the carried bed.

  tools/drum/half_speed.py                               # study_thesis -> docs/drum/half_speed.{csv,md}
  tools/drum/half_speed.py --name study_yade --out docs/drum/half_speed_yade

Needs: python3-numpy, python3-scipy.
"""

import argparse
import math
import sys
from pathlib import Path

from scipy import stats

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import harness  # noqa: E402

DOCS = harness.REPO / "docs" / "drum"
CARRIED, RELEASED = 0.95, 0.9  # bed turn at least / below
# (key, column, scale, unit, label)
METRICS = [("Hc", "Hc_m", 1e3, "mm", "centre of mass height Hc"), ("Hh", "Hh_m", 1e3, "mm", "head Hh"),
           ("Hd", "Hd_m", 1e3, "mm", "departure shoulder Hd"), ("angle", "angle_deg", 1.0, "deg", "free-surface angle"),
           ("layer_thickness", "layer_thickness_m", 1e3, "mm", "flowing-layer thickness"),
           ("surface_velocity", "surface_velocity_mps", 1.0, "m/s", "surface velocity")]


def se_of(row, key, unit):
    """A table value's standard error from its 95 % half-width and effective dof."""
    hw, dof = float(row[f"{key}_hw95_{unit}"]), float(row[f"{key}_dof"])
    return hw / float(stats.t.ppf(0.975, dof)), dof


def lagrange(xs, x):
    """The weights of the quadratic through the points at xs, evaluated at x."""
    return [math.prod((x - xj) / (xi - xj) for j, xj in enumerate(xs) if j != i) for i, xi in enumerate(xs)]


def compare(table):
    """One dict per released speed and metric (see the module note)."""
    # each carried speed at the bed's own rotation (rpm x bed turn: 0.99-1 of the drum's)
    at = {w * r["bed_turn_1"]: r for w, r in table.items() if r["bed_turn_1"] >= CARRIED}
    carried = sorted(at)
    out = []
    for w, r in sorted(table.items()):
        if r["bed_turn_1"] >= RELEASED:
            continue
        weff = w * r["bed_turn_1"]
        # within the carried speeds, or beyond the last by a tenth of its spacing at most
        reach = 0.1 * (carried[-1] - carried[-2]) if len(carried) >= 2 else 0.0
        if len(carried) < 3 or not carried[0] <= weff <= carried[-1] + reach:
            out.append({"rpm": w, "bed_turn": r["bed_turn_1"], "equivalent_rpm": weff, "metric": None})
            continue
        near = sorted(sorted(carried, key=lambda c: abs(c - weff))[:3])
        lo = max((c for c in carried if c <= weff), default=carried[0])
        hi = min((c for c in carried if c >= weff), default=carried[-1])
        if hi == lo and weff > carried[-1]:
            lo = carried[-2]
        turn_hw = float(r["bed_turn_hw95_1"])  # its own 95 % half-width (at its own dof)
        for key, col, scale, unit, label in METRICS:
            ys = [at[c][col] for c in near]
            weights = lagrange(near, weff)
            predicted = sum(wt * y for wt, y in zip(weights, ys))
            linear = at[lo][col] if hi == lo else at[lo][col] + (weff - lo) / (hi - lo) * (at[hi][col] - at[lo][col])
            slope = (at[near[-1]][col] - at[near[0]][col]) / (near[-1] - near[0])
            parts = [se_of(at[c], key, col.rsplit("_", 1)[1]) for c in near]
            se_pred2 = sum((wt * se) ** 2 for wt, (se, _) in zip(weights, parts))
            dof_pred = se_pred2 ** 2 / sum((wt * se) ** 4 / dof for wt, (se, dof) in zip(weights, parts)) \
                if se_pred2 > 0 else math.inf
            se_obs, dof_obs = se_of(r, key, col.rsplit("_", 1)[1])
            se2 = se_obs ** 2 + se_pred2
            dof = se2 ** 2 / (se_obs ** 4 / dof_obs + se_pred2 ** 2 / dof_pred)
            model = abs(predicted - linear)
            turn = abs(slope) * w * turn_hw
            half_width = float(stats.t.ppf(0.975, dof)) * math.sqrt(se2) + model + turn
            diff = r[col] - predicted
            out.append({"rpm": w, "bed_turn": r["bed_turn_1"], "equivalent_rpm": weff, "metric": key, "label": label,
                        "unit": unit, "released": r[col] * scale, "carried_there": predicted * scale,
                        "difference": diff * scale, "half_width": half_width * scale,
                        "interpolation": model * scale, "bed_turn_term": turn * scale, "dof": dof,
                        "extrapolated": weff > carried[-1],
                        "agree": abs(diff) <= half_width})
    return out


def page(name, rows):
    """The report: the answer first, per metric; then the table."""
    read_rows = [r for r in rows if r["metric"]]
    skipped = sorted({r["rpm"] for r in rows if not r["metric"]})
    speeds = sorted({r["rpm"] for r in read_rows})
    lines = [f"# A released bed against the carried bed at its own rotation ({name})", "",
             "<!-- Generated by `tools/drum/half_speed.py`; do not edit. -->", ""]
    if not read_rows:
        return "\n".join(lines + ["No released speed of this study lies within its carried speeds' range.", ""])
    held = [m for m in METRICS if all(r["agree"] for r in read_rows if r["metric"] == m[0])]
    failed = [m for m in METRICS if m not in held]
    speeds_text = ", ".join(f"{w:g}" for w in speeds)
    lines.append(f"At {speeds_text} rpm the bed turns at "
                 + ", ".join(f"{r['bed_turn']:.3f}" for r in read_rows if r["metric"] == "Hc")
                 + " of the drum's speed. Read at that slower rotation, the carried bed's "
                 + (", ".join(m[4] for m in held) if held else "metrics")
                 + (" match the released bed's within their 95 % intervals at every one of these speeds."
                    if held else " match none of the released bed's at every speed."))
    if failed:
        lines.append("")
        lines.append("They do not for the " + ", ".join(m[4] for m in failed) + ": "
                     + "; ".join(f"{m[4]} {r['difference']:+.3g} ± {r['half_width']:.2g} {r['unit']} at {r['rpm']:g} rpm"
                                 for m in failed for r in read_rows if r["metric"] == m[0] and not r["agree"]) + ".")
    n = len(read_rows)
    lines += ["", f"{n} comparisons at 95 %: about {0.05 * n:.1f} would fall outside by chance alone; a metric "
              "that fails at every speed, by more than its interval, does not."]
    if skipped:
        lines += ["", "Not read (the bed's rotation there lies outside the carried speeds, an extrapolation): "
                  + ", ".join(f"{w:g} rpm" for w in skipped) + "."]
    lines += ["", "Method: tools/drum/half_speed.py (its module note); the intervals combine both values' standard "
              "errors with the interpolation's and the bed turn's own errors.", "",
              "| rpm | bed turn | as if at rpm | metric | released | carried there | difference | 95 % ± | agree |",
              "|---:|---:|---:|---|---:|---:|---:|---:|:---:|"]
    if any(r["extrapolated"] for r in read_rows):
        lines.insert(-2, "(* beyond the fastest carried speed's rotation by less than a tenth of the carried speeds' "
                         "spacing: the quadratic extrapolated.)\n")
    for r in read_rows:
        lines.append(f"| {r['rpm']:g} | {r['bed_turn']:.4f} | {r['equivalent_rpm']:.2f}{'*' if r['extrapolated'] else ''} | "
                     f"{r['label']} [{r['unit']}] | "
                     f"{r['released']:.4g} | {r['carried_there']:.4g} | {r['difference']:+.3g} | {r['half_width']:.2g} | "
                     f"{'yes' if r['agree'] else '**no**'} |")
    return "\n".join(lines) + "\n"


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--name", default="study_thesis", help="the study (docs/drum/NAME.csv)")
    p.add_argument("--docs", default=str(DOCS))
    p.add_argument("--out", help="OUT.csv and OUT.md (default: docs/drum/half_speed, or half_speed_NAME)")
    a = p.parse_args(argv)
    docs = Path(a.docs)
    table = {r["rpm"]: r for r in harness.read_csv(docs / f"{a.name}.csv")}
    out = Path(a.out) if a.out else docs / ("half_speed" if a.name == "study_thesis" else f"half_speed_{a.name}")
    rows = compare(table)
    harness.write_csv(out.with_suffix(".csv"), [r for r in rows if r["metric"]],
                      ["rpm", "bed_turn", "equivalent_rpm", "metric", "unit", "released", "carried_there", "difference",
                       "half_width", "interpolation", "bed_turn_term", "dof", "extrapolated", "agree"])
    out.with_suffix(".md").write_text(page(a.name, rows))
    harness.say("half_speed", f"wrote {out.with_suffix('.md')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
