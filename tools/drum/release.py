#!/usr/bin/python3
"""Where the bed lets go of the drum, ramp by ramp: docs/drum/release.csv and its chart.

Each ramp is a study of tools/drum/steady.py whose speeds run a fixed time each from the end state
of the speed before (the slip test's ramps, and the release study's). Its release is the onset of
tools/drum/slip.py: the first sample from which `bed_turn` (a running median over 5 snapshots)
stays below 0.9 to the end, read on the ramp clock (the speed plus the fraction of its run gone:
26.7 is 70 % into 26 rpm); half-way (below 0.72) beside it. A ramp that never lets go is listed
with its last speed, as a lower bound.

The chart: release speed against the bead-drum friction, one point per history, the mean of each
setting's histories with its 95 % interval (Student's t across histories), and the Froude number
omega^2 R / g at that speed on the right-hand axis. Beside them a friction-based estimate: the bed
as a rigid circular segment (the fill's), its chord at the carried bed's measured angle, held by
Coulomb friction at the wall. What it needs depends on how the wall's forces spread along the
wetted arc, which a rigid bed leaves open: at least `friction_bound` (the least mu for which any
spread of pressure and friction holds it, a linear programme), and `friction_needed` where the
wall's force were all radial (`spread` 1) or its pressure uniform (eps / sin eps). The carried
angle is study_thesis' at 7-28 rpm, a straight line in rpm beyond (read at 21-35 rpm).

The ramps are listed in RAMPS (study, bead-drum mu, conventions, wall, history, seconds per rpm);
a study not yet run is left out.

A ramp lets go somewhere in a speed it spent 1.76 s at; would a bed held steady at one speed let
go at all, or only on the way up? The holds answer that for mu 0.5 and 0.95 (HOLDS): a steady run
(steady.py's power rule, at most 12 s) at the fastest speed every history of the scan at that mu
ran through carried, from the first history's ramp state at that speed, then chained from its end
state one at the slowest speed none of them reached carried (`hold_speeds`; `--hold MU` prints
both and the start state for the campaign). Each held speed's outcome, its bed turn with its 95 %
interval, goes to docs/drum/release_holds.csv.

The answer, what sets the release speed, goes to docs/drum/release.md (`page`): the release
against the bead-drum friction across the scan's histories (the least-squares slope with its 95 %
interval), each of YADE's other conventions at mu 0.5 against the scan's 95 % prediction interval
for one more history at that mu, the surface mesh against the cylinder with the same start states
(Welch), the holds, and what is still to run.

  tools/drum/release.py                  # docs/drum/release.csv, .png, .md, release_holds.csv
  tools/drum/release.py --hold 0.95      # BELOW ABOVE START-STATE of that hold, or exit 1

Needs: python3-numpy, python3-scipy, python3-matplotlib.
"""

import argparse
import math
import re
import statistics
import sys
from pathlib import Path

from scipy import stats

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parent))
import harness  # noqa: E402
import estimator  # noqa: E402
import slip  # noqa: E402

DOCS = harness.REPO / "docs" / "drum"
MATERIALS = harness.materials()
R, G, FILL = MATERIALS["drum_R"], MATERIALS["gravity"], MATERIALS["thesis_fill"]  # inputs/materials.in
# (study, bead-drum mu, conventions, wall, history, seconds per rpm)
RAMPS = [
    ("slip_thesis", 0.95, "thesis", "cylinder", "from study_thesis 21 rpm", 1.5),
    ("slip_thesis_replica", 0.95, "thesis", "cylinder", "from 21 rpm arrived at from 28 rpm", 1.5),
    ("slip_yade", 0.5, "yade", "cylinder", "from study_yade 21 rpm after 8 s", 1.5),
    ("slip_yade_replica", 0.5, "yade", "cylinder", "from study_yade 21 rpm steady end state", 1.5),
    ("slip_tc20", 0.95, "thesis, plain law at tc/20", "cylinder", "from slip_thesis 26 rpm", 1.5),
    # the release study (tools/drum/campaign.sh): the 12 mm period's check against slip_thesis, then
    # the friction scan at the thesis' 1.76 s per rpm from three 21 rpm states of the scan's period
    ("rel_L12_check", 0.95, "thesis, 12 mm period", "cylinder", "from rel_L12_a 21 rpm", 1.5),
] + [(f"rel_mu{round(100 * mu)}_{h}", mu, "thesis", "cylinder", f"from rel_{h} 21 rpm", 1.76)
     for mu in (0.5, 0.65, 0.8, 0.95) for h in ("a", "b", "c")] + [
    # YADE's other conventions one at a time at mu 0.5, and the mesh wall, from rel_a's state
    ("rel_mu50_cut_a", 0.5, "thesis, no attraction", "cylinder", "from rel_a 21 rpm", 1.76),
    ("rel_mu50_en51_a", 0.5, "thesis, bead-drum en 0.51", "cylinder", "from rel_a 21 rpm", 1.76),
    ("rel_mu50_pournin_a", 0.5, "thesis, tangential pournin", "cylinder", "from rel_a 21 rpm", 1.76),
    ("rel_mu50_half_a", 0.5, "thesis, facet meff m/2", "cylinder", "from rel_a 21 rpm", 1.76),
] + [(f"rel_mu{round(100 * mu)}_surface_{h}", mu, "thesis", "surface mesh", f"from rel_{h} 21 rpm", 1.76)
     for mu in (0.5, 0.95) for h in ("a", "b", "c")]
CHECK, AGAINST = "rel_L12_check", ("slip_thesis", "slip_thesis_replica")
HOLDS = [("rel_mu50_hold", 0.5), ("rel_mu95_hold", 0.95)]  # (study, bead-drum mu): see the module note
HOLD_COLUMNS = ["study", "mu", "rpm", "start", "simulated_s", "bed_turn", "bed_turn_hw95", "bed_turn_dof", "outcome"]
COLUMNS = ["study", "mu", "conventions", "wall", "history", "seconds_per_rpm", "release_rpm", "half_way_rpm",
           "froude", "detected"]


def segment(fill):
    """(half-angle eps [rad], centroid distance from the axis over R) of the circular segment that
    fills `fill` of the drum: (2 eps - sin 2 eps) / (2 pi) = fill; s / R = 4 sin^3 eps / (3 (2 eps -
    sin 2 eps))."""
    lo, hi = 0.0, math.pi
    for _ in range(100):
        eps = 0.5 * (lo + hi)
        lo, hi = (eps, hi) if (2 * eps - math.sin(2 * eps)) / (2 * math.pi) < fill else (lo, eps)
    eps = 0.5 * (lo + hi)
    return eps, 4.0 * math.sin(eps) ** 3 / (3.0 * (2 * eps - math.sin(2 * eps)))


def friction_needed(angle_deg, rpm, fill=FILL, spread=None):
    """Friction over normal force at the wall of a rigid carried bed: its weight's torque about the
    axis, M g s sin(theta), held by friction at radius R, over the wall's normal forces, whose sum
    is `spread` (default eps / sin(eps): a pressure uniform along the wetted arc; 1: all radial)
    times their radial part M (g cos(theta) + omega^2 s): mu = (s/R) sin(theta) / (spread
    (cos(theta) + Fr s/R)), Fr = omega^2 R / g. (A uniform pressure and friction do not balance the
    weight's downhill part as well: an estimate, not a bound; see friction_bound.)"""
    eps, s = segment(fill)
    theta = math.radians(angle_deg)
    spread = eps / math.sin(eps) if spread is None else spread
    return s * math.sin(theta) / (spread * (math.cos(theta) + froude(rpm) * s))


def friction_bound(angle_deg, rpm, fill=FILL, points=180):
    """The least wall friction mu for which some spread of pressure p >= 0 and friction |f| <= mu p
    along the wetted arc holds a rigid bed (the fill's segment, chord at angle_deg, turning with the
    drum at rpm) in equilibrium, forces and torque (a linear programme per mu, bisected): below it
    no wall can hold the bed; above it one can, if the wall's forces spread right. Units M g = R = 1."""
    import numpy as np
    from scipy.optimize import linprog
    eps, s = segment(fill)
    theta = math.radians(angle_deg)
    phi = [-eps + 2 * eps * i / (points - 1) for i in range(points)]  # the ends included
    # the bed's frame: its centroid at (0, -s); the wall at (sin phi, -cos phi) pushes inwards,
    # (-sin phi, cos phi), and rubs along (cos phi, sin phi); gravity tilted by theta, centrifugal out
    load = (-math.sin(theta), -math.cos(theta) - froude(rpm) * s)
    torque = -s * math.sin(theta)  # of gravity about the axis (z of (0, -s) x load)
    a_eq = [[-math.sin(f) for f in phi] + [math.cos(f) for f in phi],
            [math.cos(f) for f in phi] + [math.sin(f) for f in phi],
            [0.0] * points + [1.0] * points]
    b_eq = [-load[0], -load[1], -torque]

    eye = np.eye(points)

    def holds(mu):
        a_ub = np.block([[-mu * eye, eye], [-mu * eye, -eye]])  # f - mu p <= 0 and -f - mu p <= 0
        r = linprog(np.zeros(2 * points), A_ub=a_ub, b_ub=np.zeros(2 * points), A_eq=a_eq, b_eq=b_eq,
                    bounds=[(0, None)] * points + [(None, None)] * points, method="highs")
        return r.status == 0
    lo, hi = 0.0, 2.0
    for _ in range(30):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if holds(mid) else (mid, hi)
    return hi


def carried_angle(docs):
    """angle(rpm) of study_thesis' carried speeds (bed turn >= 0.95): the straight line through them
    (least squares), or None without two."""
    path = docs / "study_thesis.csv"
    if not path.exists():
        return None
    rows = [r for r in harness.read_csv(path) if r["bed_turn_1"] >= 0.95]
    if len(rows) < 2:
        return None
    fit = statistics.linear_regression([r["rpm"] for r in rows], [r["angle_deg"] for r in rows])
    return lambda rpm: fit.intercept + fit.slope * rpm


def froude(rpm):
    """omega^2 R / g of the drum at this speed."""
    return (2.0 * math.pi * rpm / 60.0) ** 2 * R / G


def read(docs, ramps=RAMPS):
    """One row per ramp with a series."""
    rows = []
    for study, mu, conventions, wall, history, per_rpm in ramps:
        ramp = slip.ramp_series(docs, study)
        if not ramp:
            continue
        onset, half = slip.lets_go(ramp), slip.lets_go(ramp, slip.HALF_WAY)
        row = {"study": study, "mu": mu, "conventions": conventions, "wall": wall, "history": history,
               "seconds_per_rpm": per_rpm}
        if onset:
            at = slip.ramp_clock(ramp, onset)
            row.update(release_rpm=at, half_way_rpm=slip.ramp_clock(ramp, half) if half else math.nan,
                       froude=froude(at), detected="bed_turn below 0.9 to the end (running median of 5)")
        else:
            last = ramp[-1][1]
            row.update(release_rpm=math.nan, half_way_rpm=math.nan, froude=math.nan,
                       detected=f"carried to {last:g} rpm (the ramp's end): releases above it")
        rows.append(row)
    return rows


def groups(rows):
    """{(mu, conventions, wall, seconds per rpm): [release rpm of each history that let go]}."""
    out = {}
    for r in rows:
        out.setdefault((r["mu"], r["conventions"], r["wall"], r["seconds_per_rpm"]), []).append(r["release_rpm"])
    return {k: [x for x in v if math.isfinite(x)] for k, v in out.items()}


def interval(values, confidence=0.95):
    """(mean, half-width) across histories: Student's t at n - 1 dof; nan half-width below 2."""
    n = len(values)
    if n == 0:
        return math.nan, math.nan
    mean = statistics.fmean(values)
    if n < 2:
        return mean, math.nan
    return mean, float(stats.t.ppf(0.5 + confidence / 2.0, n - 1)) * statistics.stdev(values) / math.sqrt(n)


def chart(rows, path, angle=None):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for k, (key, values) in enumerate(sorted(groups(rows).items(), key=lambda kv: (kv[0][1], kv[0][0]))):
        mu, conventions, wall, per_rpm = key
        mean, hw = interval(values)
        label = f"{conventions}, {wall}, {per_rpm:g} s/rpm (n={len(values)})"
        x = mu + 0.01 * (k % 3 - 1)  # settings at one mu side by side
        line = ax.errorbar([x], [mean], yerr=[hw if math.isfinite(hw) else 0.0], fmt="o", capsize=4, label=label)
        ax.plot([x] * len(values), values, "x", color=line[0].get_color())
    if angle is not None:
        text = "; ".join(f"{rpm} rpm: {friction_bound(angle(rpm), rpm):.2f}-{friction_needed(angle(rpm), rpm, spread=1):.2f}"
                         for rpm in (21, 28, 35))
        ax.text(0.98, 0.02, "wall friction a rigid bed needs (least possible - all wall force radial):\n" + text,
                transform=ax.transAxes, ha="right", va="bottom", fontsize=7)
    ax.set_xlabel("bead-drum friction mu")
    ax.set_ylabel("release speed [rpm] (onset on the ramp clock)")
    right = ax.secondary_yaxis("right", functions=(froude, lambda fr: 60.0 / (2.0 * math.pi) * (abs(fr) * G / R) ** 0.5))
    right.set_ylabel("Froude number omega^2 R / g")
    ax.legend(fontsize=7, loc="upper left")
    ax.set_title("Where the bed lets go of the drum (x: each history; o: mean, 95 % across histories)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def scan_histories(mu):
    """The friction scan's ramps at mu (the first is the one a hold starts from)."""
    return [f"rel_mu{round(100 * mu)}_{h}" for h in "abc"]


def hold_speeds(rows, mu):
    """(below, above) of the hold at mu: below, the fastest whole speed that every history of the
    scan at mu ran through carried (one below the speed the earliest release fell in); above, the
    slowest none of them reached carried (one above the speed the latest fell in). None until all
    three histories have let go."""
    scan = [r for r in rows if r["study"] in scan_histories(mu)]
    if len(scan) < 3 or not all(math.isfinite(r["release_rpm"]) for r in scan):
        return None
    releases = [r["release_rpm"] for r in scan]
    return math.floor(min(releases)) - 1, math.floor(max(releases)) + 1


def hold_outcome(series, rpm):
    """What a held speed's bed did (`series`: its hold study's ramp_series, `rpm`: this speed):
    carried throughout (bed_turn's running median never below slip.LETS_GO), let go (below it to
    the end, from some time into the speed, or already at the start: a bed that came in released),
    or slipping on and off."""
    own = [s for s in series if s[1] == rpm]
    if not own:
        return "no series"
    gone = slip.lets_go(series)
    if gone is not None and gone[1] < rpm:
        return "released throughout (came in released)"
    if gone is not None and gone[1] == rpm:
        return f"let go {gone[2]:.2f} s into the hold"
    if min(slip.running_median([s[3] for s in own])) >= slip.LETS_GO:
        return "carried throughout"
    return f"slipping on and off (running median of bed_turn below {slip.LETS_GO:g} at times, back above)"


def read_holds(docs, holds=HOLDS):
    """One row per held speed that has finished (its run.json and its row in the study's table)."""
    rows = []
    for study, mu in holds:
        table = docs / f"{study}.csv"
        if not table.exists():
            continue
        series, previous = slip.ramp_series(docs, study), None
        for r in harness.read_csv(table):
            rpm = r["rpm"]
            run = harness.read_json(docs / study / f"{rpm:g}rpm" / "run.json")
            start = (f"{scan_histories(mu)[0]}'s {rpm:g} rpm end state (carried)" if previous is None
                     else f"the hold's {previous:g} rpm end state")
            previous = rpm
            rows.append({"study": study, "mu": mu, "rpm": rpm, "start": start,
                         "simulated_s": run["simulated_s"], "bed_turn": r["bed_turn_1"],
                         "bed_turn_hw95": r.get("bed_turn_hw95_1", math.nan), "bed_turn_dof": r.get("bed_turn_dof", math.nan),
                         "outcome": hold_outcome(series, rpm)})
    return rows


SCAN = ("thesis", "cylinder", 1.76)  # (conventions, wall, seconds per rpm) of the friction scan
SCAN_MUS = (0.5, 0.65, 0.8, 0.95)


def scan_points(rows):
    """[(mu, release rpm)] of the friction scan's histories that let go."""
    return [(r["mu"], r["release_rpm"]) for r in rows if (r["conventions"], r["wall"], r["seconds_per_rpm"]) == SCAN
            and r["study"] in {n for mu in SCAN_MUS for n in scan_histories(mu)} and math.isfinite(r["release_rpm"])]


def slope(points, confidence=0.95):
    """(rpm per unit mu, its 95 % half-width, n) of the least-squares line through the scan's
    histories; None with fewer than 3 points or one mu."""
    if len(points) < 3 or len({m for m, _ in points}) < 2:
        return None
    fit = stats.linregress([m for m, _ in points], [x for _, x in points])
    return fit.slope, float(stats.t.ppf(0.5 + confidence / 2.0, len(points) - 2)) * fit.stderr, len(points)


def prediction(values, confidence=0.95):
    """(mean, half-width) of the interval that holds one more history's release with this
    confidence: t(n - 1) sd sqrt(1 + 1/n); nan half-width below 2 histories."""
    n = len(values)
    if n < 2:
        return (statistics.fmean(values) if values else math.nan), math.nan
    return (statistics.fmean(values),
            float(stats.t.ppf(0.5 + confidence / 2.0, n - 1)) * statistics.stdev(values) * math.sqrt(1.0 + 1.0 / n))


def welch(a, b, confidence=0.95):
    """(mean a - mean b, its 95 % half-width) by Welch's t with Satterthwaite's dof; nan with fewer
    than 2 a side."""
    if len(a) < 2 or len(b) < 2:
        return (statistics.fmean(a) - statistics.fmean(b) if a and b else math.nan), math.nan
    side = [estimator.Interval(statistics.fmean(x), math.nan, len(x) - 1, math.nan,
                               statistics.stdev(x) / math.sqrt(len(x))) for x in (a, b)]
    difference, half_width, _ = estimator.compare(*side, confidence)
    return difference, half_width


def page(rows, holds=(), angle=None):
    """docs/drum/release.md: the answer first, in plain words, then the evidence."""
    scan = {mu: [x for m, x in scan_points(rows) if m == mu] for mu in SCAN_MUS}
    ran = {r["study"] for r in rows}
    fit = slope(scan_points(rows))
    answer, evidence = [], []
    if fit:
        k, hw, n = fit
        moves = abs(k) > hw
        ends = [(mu, *interval(scan[mu])) for mu in (SCAN_MUS[0], SCAN_MUS[-1]) if len(scan[mu]) >= 2]
        span = (f", from {ends[0][1]:.1f} ± {ends[0][2]:.1f} rpm at mu {ends[0][0]:g} to {ends[1][1]:.1f} ± "
                f"{ends[1][2]:.1f} at {ends[1][0]:g}" if len(ends) == 2 else "")
        answer.append(f"With the thesis' table otherwise, the bead-drum friction {'moves' if moves else 'does not measurably move'} "
                      f"the release: {0.1 * k:+.2f} ± {0.1 * hw:.2f} rpm per 0.1 of friction (95 %, least squares over "
                      f"{n} ramps at 1.76 s per rpm{span})")
    else:
        answer.append("The friction scan has not run far enough to say how the bead-drum friction moves the release")
    evidence += ["| bead-drum mu | histories | release [rpm], mean ± 95 % | each history [rpm] | Froude number at the mean |",
                 "|---|---|---|---|---|"]
    for mu, values in scan.items():
        mean, hw = interval(values)
        evidence.append(f"| {mu:g} | {len(values)} of 3 | " + (f"{mean:.2f} ± {hw:.2f}" if values else "–") + " | "
                        + (", ".join(f"{x:.2f}" for x in values) or "–") + " | "
                        + (f"{froude(mean):.3f}" if values else "–") + " |")
    base, base_hw = prediction(scan[0.5])
    one_at_a_time = []
    for study, _, conventions, _, _, _ in RAMPS:
        if study.startswith("rel_mu50_") and study[len("rel_mu50_"):-2] in ("cut", "en51", "pournin", "half"):
            r = next((x for x in rows if x["study"] == study), None)
            if r is None:
                continue
            what = conventions.split(", ", 1)[1]
            if not math.isfinite(r["release_rpm"]):
                end = re.search(r"carried to ([0-9.]+) rpm", r["detected"])
                above = float(end.group(1)) + 1.0 if end else math.nan  # the ramp's end on its clock
                beyond = math.isfinite(base_hw) and above - base > base_hw
                one_at_a_time.append(f"{what}: never let go on its ramp, so above {above:g} rpm"
                                     + (f", {'outside' if beyond else 'not yet outside'} the scan's {base:.2f} ± {base_hw:.2f}"
                                        if math.isfinite(base_hw) else ""))
            elif math.isfinite(base_hw):
                outside = abs(r["release_rpm"] - base) > base_hw
                one_at_a_time.append(f"{what}: {r['release_rpm']:.2f} rpm, {r['release_rpm'] - base:+.2f} from the "
                                     f"scan's mean, {'outside' if outside else 'within'} its ± {base_hw:.2f}")
            else:
                one_at_a_time.append(f"{what}: {r['release_rpm']:.2f} rpm (the scan at mu 0.5 not yet run)")
    if one_at_a_time:
        moved = [x.split(":")[0] for x in one_at_a_time if "outside" in x]
        answer.append("of YADE's other conventions, one at a time at mu 0.5 (one history each), "
                      + (" and ".join([", ".join(moved[:-1]), moved[-1]] if len(moved) > 1 else moved) + " move"
                         + ("s" if len(moved) == 1 else "") + " the release beyond the "
                         "spread of three histories" if moved else "none moves the release beyond the spread of three "
                         "histories"))
        evidence += ["", "YADE's other conventions one at a time at mu 0.5, from the first start state, against the "
                     "scan at mu 0.5 (95 % prediction interval for one more history: mean ± t sd sqrt(1 + 1/n)):", ""]
        evidence += [f"- {x}" for x in one_at_a_time]
    walls = []
    for mu in (0.5, 0.95):
        mesh = [r["release_rpm"] for r in rows if r["study"] in (f"rel_mu{round(100 * mu)}_surface_{h}" for h in "abc")
                and math.isfinite(r["release_rpm"])]
        if mesh and scan[mu]:
            d, hw = welch(mesh, scan[mu])
            walls.append((mu, d, hw, len(mesh), len(scan[mu])))
    if walls:
        answer.append("the surface-velocity mesh (a bead's tangential spring restarts at every facet) against the "
                      "primitive cylinder: " + "; ".join(
                          f"at mu {mu:g} {d:+.2f}" + (f" ± {hw:.2f} rpm" if math.isfinite(hw) else " rpm (too few histories "
                                                       "for an interval)") for mu, d, hw, _, _ in walls))
        evidence += ["", "The wall as YADE saw it, the surface-velocity mesh minus the primitive cylinder, from the same "
                     "start states (Welch, 95 %):", ""]
        evidence += [f"- mu {mu:g}: {d:+.2f}" + (f" ± {hw:.2f}" if math.isfinite(hw) else "") +
                     f" rpm ({n} and {m} histories)" for mu, d, hw, n, m in walls]
    if holds:
        evidence += ["", "Held steady (`release_holds.csv`):", ""]
        evidence += [f"- mu {h['mu']:g}, {h['rpm']:g} rpm ({h['start']}, {h['simulated_s']:g} s): {h['outcome']}, bed "
                     f"turn {h['bed_turn']:.3f} ± {h['bed_turn_hw95']:.3f}" for h in holds]
    todo = [n for n, *_ in RAMPS if n.startswith("rel_") and n not in ran]
    if angle is not None:
        evidence += ["", "A rigid bed at its carried angle, held by Coulomb friction at the wall, needs at least "
                     + ", ".join(f"mu {friction_bound(angle(rpm), rpm):.2f} at {rpm} rpm" for rpm in (21, 28, 35))
                     + " (`friction_bound`): every friction scanned would hold it, so the rigid-bed picture does not "
                     "explain the release ([the slip test](slip_test.md) follows the layer at the wall)."]
    text = ["# Where the bed lets go of the drum: what sets the release speed", "",
            "<!-- Generated by `tools/drum/release.py` from docs/drum/release.csv; edit the generator. -->", "",
            "## Answer", "",
            "; ".join(answer) + "." + (f" Still to run: {len(todo)} ramps ({', '.join(todo)})." if todo else ""),
            "", "## Evidence", "",
            "Each ramp raises the speed by one rpm every 1.76 s (the thesis' ramp) from a carried 21 rpm bed; its "
            "release is where the bed turn's running median falls below 0.9 for good, read on the ramp clock "
            "([release.csv](release.csv), [chart](release.png)).", "", *evidence, ""]
    return "\n".join(text)


def scan_period(rows):
    """(period [m], why) for the friction scan: the 12 mm period where its ramp's release (CHECK)
    lies within the 95 % interval of the 24 mm histories' (AGAINST) mean, else the 24 mm period;
    None before the check has run."""
    check = [r["release_rpm"] for r in rows if r["study"] == CHECK]
    full = [r["release_rpm"] for r in rows if r["study"] in AGAINST and math.isfinite(r["release_rpm"])]
    if not check or len(full) < 2:
        return None
    mean, hw = interval(full)
    same = math.isfinite(check[0]) and abs(check[0] - mean) <= hw
    why = (f"the 12 mm period's ramp lets go at {check[0]:.2f} rpm, the 24 mm period's {len(full)} histories at "
           f"{mean:.2f} ± {hw:.2f} rpm (95 %): " + ("within it, so the scan runs on 12 mm (half the beads)" if same
                                                    else "not within it, so the scan runs on the 24 mm period"))
    return (0.012 if same else 0.024), why


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--docs", default=str(DOCS))
    p.add_argument("--out", default=str(DOCS / "release"), help="OUT.csv and OUT.png")
    p.add_argument("--hold", type=float, metavar="MU",
                   help="print the hold's speeds at this bead-drum mu and the state it starts from (BELOW ABOVE "
                        "START; see hold_speeds) and stop; exit 1 before the scan's three histories at mu have let go")
    p.add_argument("--scan-period", action="store_true",
                   help="print the period the friction scan runs on (0.012 or 0.024; see scan_period) and stop; "
                        "exit 1 before the check has run")
    a = p.parse_args(argv)
    rows = read(Path(a.docs))
    if a.hold is not None:
        speeds = hold_speeds(rows, a.hold)
        start = speeds and Path(a.docs) / scan_histories(a.hold)[0] / f"{speeds[0]}rpm" / "state.restart.gz"
        if speeds is None or not start.exists():
            print(f"release: no hold at mu {a.hold:g} yet (" +
                  ("the scan's three histories have not all let go" if speeds is None else f"{start} is missing") + ")",
                  file=sys.stderr)
            return 1
        print(speeds[0], speeds[1], start)
        return 0
    if a.scan_period:
        chosen = scan_period(rows)
        if chosen is None:
            print("release: the 12 mm period's check has not run yet", file=sys.stderr)
            return 1
        print(chosen[0])
        print(f"release: {chosen[1]}", file=sys.stderr)
        return 0
    out = Path(a.out)
    harness.write_csv(out.with_suffix(".csv"), rows, COLUMNS)
    holds = read_holds(Path(a.docs))
    (out.parent / (out.name + ".md")).write_text(page(rows, holds, carried_angle(Path(a.docs))))
    if holds:
        harness.write_csv(out.parent / (out.name + "_holds.csv"), holds, HOLD_COLUMNS)
        for h in holds:
            harness.say("release", f"hold at mu {h['mu']:g}, {h['rpm']:g} rpm: {h['outcome']}, bed turn "
                                   f"{h['bed_turn']:.3f} ± {h['bed_turn_hw95']:.3f} (95 %)")
    angle = carried_angle(Path(a.docs))
    if rows:
        chart(rows, out.with_suffix(".png"), angle)
    if angle is not None:
        harness.say("release", "the wall friction a rigid bed needs, least possible / uniform pressure / all radial: " +
                    "; ".join(f"{rpm} rpm {friction_bound(angle(rpm), rpm):.3f} / {friction_needed(angle(rpm), rpm):.3f}"
                              f" / {friction_needed(angle(rpm), rpm, spread=1):.3f}" for rpm in (21, 28, 35)))
    for key, values in groups(rows).items():
        mean, hw = interval(values)
        harness.say("release", f"mu {key[0]:g}, {key[1]}, {key[2]}, {key[3]:g} s/rpm: {mean:.2f} ± {hw:.2f} rpm "
                               f"({len(values)} histories)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
