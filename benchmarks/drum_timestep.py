#!/usr/bin/python3
"""Speed against accuracy on the drum itself: each law at each timestep of the ladder set against
the reference (the plain law at the thesis' tc/81 at 21 rpm; tc/40 at 42 rpm), metric by metric,
with 95 % intervals, beside its cost.

The ladder's runs are drum studies (tools/drum/steady.py, run by tools/drum/campaign.sh) from the
committed steady state of study_thesis at that speed, each to the power rule (95 % half-widths of
Hc 0.0535 mm and angle 0.0535 deg at 10 effective degrees of freedom: a 0.1 mm / 0.1 deg difference
between two of them is found with 80 % power). The exactRestitution tc/5 entry is study_thesis' own
speed (the run that produced the ladder's start state). Each run is read from what is committed:
a finished speed (docs/drum/NAME/<rpm>rpm/series_metrics.csv, its table row's settle_s) or a
checkpoint in progress (partial/metrics_cache.csv, its steady start from `drum_metrics steady`);
its steady window from the steady start to its last snapshot, every metric's interval from
tools/drum/estimator.py over that window.

Written to --out (default benchmarks/results):
- drum_timestep.csv: one row per rpm, law, dt/tc and metric: the value, its 95 % half-width and
  effective dof; the difference from the reference, the difference's 95 % half-width and dof
  (Welch), whether they agree; the power to find a difference of 0.1 mm (lengths) or 0.1 deg
  (angles) at that noise (other metrics: the difference found with 80 % power); wall seconds per
  simulated second on 2 ranks (from --cost's interleaved runs where measured, else the run's least
  disturbed segment: the machine is shared), the steady window and the run's state (done, capped,
  running, not settled);
- with --cost, first drum_timestep_cost.csv: each law and step from the main job's shipped state,
  interleaved over rounds, its wall time per simulated second and its ratio to tc/81 in the same
  round (like for like: the same scene, machine and moment);
- drum_timestep_<rpm>rpm.png: each metric's difference from the reference (95 % intervals) against
  that cost, one line per law, the thesis' timestep marked.

  benchmarks/drum_timestep.py                  # from the committed runs
  benchmarks/drum_timestep.py --cost           # and first the interleaved cost, about 12 minutes
  benchmarks/drum_timestep.py --docs DIR --out DIR

Needs: python3-numpy, python3-scipy, python3-matplotlib; drum_metrics.
"""

import argparse
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools" / "drum"))
import harness  # noqa: E402
import estimator  # noqa: E402

HERE = Path(__file__).resolve().parent
TC = 1e-4  # Table 3.1's contact duration [s]
SNAPSHOT = 0.05  # drum.in's dumpdt [s]
DETECT = {"m": 1e-4, "deg": 0.1}  # the difference the power is stated for, by unit
POWER = 0.8

# The drum.in settings of each law at each step, as the campaign runs them (--cost)
SETTINGS = {
    ("plain", 81.3): {"dt": "1.23e-6", "exact": "off", "skin": "0.1"},
    ("plain", 40): {"dt": "2.5e-6", "exact": "off", "skin": "0.2"},
    ("plain", 20): {"dt": "5e-6", "exact": "off", "skin": "0.3"},
    ("plain", 10): {"dt": "1e-5", "exact": "off", "skin": "0.3"},
    ("exactRestitution", 10): {"dt": "1e-5", "exact": "on", "skin": "0.3"},
    ("exactRestitution", 5): {"dt": "2e-5", "exact": "on", "skin": "0.3"},
    ("exactRestitution", 4.08): {"dt": "2.45e-5", "exact": "on", "skin": "0.3"},
    ("exactCollision", 10): {"dt": "1e-5", "exact": "off", "collision": "on", "tangential": "pournin",
                             "history": "fresh", "skin": "0.3"},
    ("exactCollision", 5): {"dt": "2e-5", "exact": "off", "collision": "on", "tangential": "pournin",
                            "history": "fresh", "skin": "0.3"},
}
# (rpm, law, tc/dt, study name): the ladder as tools/drum/campaign.sh names its studies; the first
# entry of each speed is its reference
LADDER = [
    (21, "plain", 81.3, "dt_tc81"),
    (21, "plain", 40, "dt_tc40"),
    (21, "plain", 20, "dt_tc20"),
    (21, "plain", 10, "dt_tc10"),
    (21, "exactRestitution", 10, "dt_exr_tc10"),
    (21, "exactRestitution", 5, "study_thesis"),
    (21, "exactRestitution", 4.08, "dt_exr_tc4"),
    (21, "exactCollision", 10, "dt_exc_tc10"),
    (21, "exactCollision", 5, "dt_exc_tc5"),
    (42, "plain", 40, "dt42_tc40"),
    (42, "plain", 20, "dt42_tc20"),
    (42, "exactRestitution", 5, "study_thesis"),
    (42, "exactCollision", 5, "dt42_exc_tc5"),
]
LAWS = ("plain", "exactRestitution", "exactCollision")
COLUMNS = ["rpm", "law", "tc_over_dt", "dt_s", "study", "state", "metric", "unit", "value", "hw95", "dof",
           "difference", "difference_hw95", "difference_dof", "agree", "power", "detect_80", "window_s",
           "wall_s_per_simulated_s", "cost_from"]


def cost(loops, dt):
    """Wall seconds per simulated second of the least disturbed segment (LIGGGHTS' loop times on
    2 ranks): a shared machine only ever slows a segment down."""
    rates = [lp["loop_s"] / (lp["steps"] * dt) for lp in loops if lp.get("steps")]
    return min(rates) if rates else math.nan


def read_run(docs, rpm, study):
    """{"dt", "state", "window_s", "cost", "intervals": {column: Interval}} of one ladder run from
    what is committed, or None where nothing is."""
    folder = docs / study / f"{rpm}rpm"
    if (folder / "series_metrics.csv").exists():
        record = harness.read_json(folder / "run.json")
        dt = float(record["settings"]["variables"]["dt"])
        row = next(r for r in harness.read_csv(docs / f"{study}.csv") if round(r["rpm"]) == rpm)
        series = harness.read_csv(folder / "series_metrics.csv")
        start = series[0]["time_s"] + row["settle_s"]
        state = record["outcome"]
        loops = record.get("loops", [])
        if not loops:  # older records: the whole run's CPU over its 2 ranks
            loops = [{"loop_s": record["cpu_s"] / 2.0, "steps": round(record["simulated_s"] / dt)}]
    elif (folder / "partial" / "progress.json").exists():
        progress = harness.read_json(folder / "partial" / "progress.json")
        dt = float(progress["settings"]["variables"]["dt"])
        cache = folder / "partial" / "metrics_cache.csv"
        series = harness.read_csv(cache)
        steady = harness.read_csv_text(harness.tool(
            "drum_metrics", "steady", "--prefix", folder / "partial" / "none", "--dt", dt, "--rpm", rpm,
            "--cache", cache, "--batch-seconds", f"{60.0 / rpm:.10g}"))[0]
        settled = steady["settled"] in (1.0, "1", True) and math.isfinite(float(steady["steady_from_s"]))
        start = float(steady["steady_from_s"]) if settled else math.inf
        state = "running" if settled else "not settled"
        loops = progress.get("loops", [])
    else:
        return None
    window = sum(r["time_s"] >= start - 0.5 * SNAPSHOT for r in series)
    columns = [c for c in series[0] if c not in ("step", "time_s", "beads", "wall_contacts")]
    intervals = estimator.window_intervals(series, start, SNAPSHOT, {c: c for c in columns}) if window else {}
    return {"dt": dt, "state": state, "window_s": window * SNAPSHOT, "cost": cost(loops, dt), "intervals": intervals}


def unit_of(column):
    return column.rsplit("_", 1)[1]


def rows_of(docs, measured=None):
    """The CSV's rows, and the runs as read: {(rpm, law, ratio): run}. `measured`: --cost's rows by
    (law, tc/dt), whose interleaved cost replaces the runs' own where present."""
    rows, runs = [], {}
    for rpm, law, ratio, study in LADDER:
        run = read_run(docs, rpm, study)
        if run is None:
            continue
        dt = run["dt"]
        if (law, ratio) in (measured or {}):
            run["cost"], run["cost_source"] = measured[(law, ratio)]["wall_s_per_simulated_s"], "interleaved"
        else:
            run["cost_source"] = "segments"
        runs[(rpm, law, ratio)] = run
        ref = runs.get((rpm, *first_of(rpm)), {"intervals": {}})
        for column, iv in run["intervals"].items():
            r = {"rpm": rpm, "law": law, "tc_over_dt": ratio, "dt_s": dt, "study": study, "state": run["state"],
                 "metric": column, "unit": unit_of(column), "value": iv.mean, "hw95": iv.half_width, "dof": iv.dof,
                 "window_s": run["window_s"], "wall_s_per_simulated_s": run["cost"], "cost_from": run["cost_source"]}
            other = ref["intervals"].get(column)
            if run is not ref and other is not None and math.isfinite(iv.se) and math.isfinite(other.se):
                d, hw, dof = estimator.compare(iv, other)
                se = math.hypot(iv.se, other.se)
                r.update(difference=d, difference_hw95=hw, difference_dof=dof, agree=abs(d) <= hw)
                if r["unit"] in DETECT:
                    r["power"] = estimator.power(DETECT[r["unit"]], se, dof)
                r["detect_80"] = detectable(se, dof)
            rows.append(r)
    return rows, runs


def detectable(se, dof):
    """The true difference found with 80 % power at this noise."""
    if not (se > 0 and dof > 0):
        return math.nan
    lo, hi = 0.0, 20.0 * se
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if estimator.power(mid, se, dof) < POWER else (lo, mid)
    return hi


def first_of(rpm):
    """(law, tc/dt) of the speed's reference: its first LADDER entry."""
    return next((law, ratio) for r, law, ratio, _ in LADDER if r == rpm)


def chart(rows, rpm, path):
    """Each metric's difference from the reference against cost, one line per law."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    metrics = list(dict.fromkeys(r["metric"] for r in rows if r["rpm"] == rpm))
    if not metrics:
        return False
    reference = next((r for r in rows if r["rpm"] == rpm and (r["law"], r["tc_over_dt"]) == first_of(rpm)), None)
    if reference is None:
        return False
    cols = 3
    fig, axes = plt.subplots(math.ceil(len(metrics) / cols), cols, figsize=(12, 3.2 * math.ceil(len(metrics) / cols)),
                             squeeze=False)
    for ax, metric in zip(axes.flat, metrics):
        ref = next(r for r in rows if r["rpm"] == rpm and r["metric"] == metric and r["study"] == reference["study"])
        ax.axhspan(-ref["hw95"], ref["hw95"], color="0.85", label=f"reference tc/{ref['tc_over_dt']:g} (95 %)")
        ax.axvline(ref["wall_s_per_simulated_s"], color="0.5", ls=":", lw=1)
        for law, marker in zip(LAWS, "osD"):
            pts = sorted((r for r in rows if r["rpm"] == rpm and r["metric"] == metric and r["law"] == law
                          and "difference" in r), key=lambda r: r["wall_s_per_simulated_s"])
            if pts:
                ax.errorbar([p["wall_s_per_simulated_s"] for p in pts], [p["difference"] for p in pts],
                            yerr=[p["difference_hw95"] for p in pts], marker=marker, capsize=3, label=law)
                for p in pts:
                    ax.annotate(f"tc/{p['tc_over_dt']:g}", (p["wall_s_per_simulated_s"], p["difference"]),
                                textcoords="offset points", xytext=(4, 4), fontsize=7)
        ax.axhline(0.0, color="k", lw=0.5)
        ax.set_xscale("log")
        ax.set_title(metric, fontsize=9)
        ax.set_xlabel("wall s per simulated s (2 ranks)", fontsize=8)
        ax.set_ylabel(f"difference from tc/{ref['tc_over_dt']:g} [{ref['unit']}]", fontsize=8)
    for ax in list(axes.flat)[len(metrics):]:
        ax.axis("off")
    axes.flat[0].legend(fontsize=7)
    fig.suptitle(f"The drum at {rpm} rpm: each timestep's answer against the thesis' tc/81 (dotted: its cost)")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return True


def measure_cost(out, rounds, simulated):
    """--cost: each law and step of SETTINGS run for `simulated` seconds from the main job's shipped
    state (the 24 mm scene at 21 rpm, 2 ranks), interleaved over `rounds`: wall seconds of LIGGGHTS'
    loop per simulated second, and the ratio to tc/81 in the same round (the machine is shared: a
    round's runs saw the same load). Written to OUT/drum_timestep_cost.csv."""
    def one(key):
        law, ratio = key
        name = f"drum_timestep_cost/{law}_{ratio:g}"
        variables = {**SETTINGS[key], "time": f"{simulated:.10g}", "dumpdt": f"{simulated:.10g}", "name": name}
        if "history" in variables:
            variables.update(start="restart", restart=shipped_state())
        log = harness.drum(harness.post(name + ".log"), np=2, **variables)
        return log.loop_time / (log.steps * float(SETTINGS[key]["dt"]))
    per_round = harness.interleaved({key: (lambda key=key: one(key)) for key in SETTINGS}, rounds,
                                    progress=lambda text: harness.say("drum_timestep", text))
    reference = per_round[("plain", 81.3)]
    rows = [{"law": law, "tc_over_dt": ratio, "collision": "off", "tangential": "history",
             **{k: v for k, v in SETTINGS[(law, ratio)].items() if k != "history"},
             "wall_s_per_simulated_s": harness.median(v), "low": min(v), "high": max(v),
             "ratio_to_tc81": harness.median_ratio(v, reference), "rounds": rounds, "simulated_s": simulated}
            for (law, ratio), v in per_round.items()]
    harness.write_csv(Path(out) / "drum_timestep_cost.csv", rows)
    return rows


def shipped_state():
    """inputs/drum_L24_21rpm.restart.gz unpacked into post/ (the main job's start, for a fresh start)."""
    import gzip
    import shutil
    plain = harness.post("drum_timestep_cost", "start.restart")
    if not plain.exists():
        with gzip.open(harness.REPO / "inputs" / "drum_L24_21rpm.restart.gz", "rb") as f, open(plain, "wb") as o:
            shutil.copyfileobj(f, o)
    return plain


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--docs", default=str(HERE.parent / "docs" / "drum"), help="the drum studies (default: docs/drum)")
    p.add_argument("--out", default=str(HERE / "results"), help="where the CSV and charts go")
    p.add_argument("--cost", action="store_true", help="first measure each law's cost (measure_cost), about 10 "
                                                       "minutes on 2 cores with the defaults")
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--simulated", type=float, default=0.01, help="--cost: simulated seconds per run")
    a = p.parse_args(argv)
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    if a.cost:
        measure_cost(out, a.rounds, a.simulated)
    measured = {}
    if (out / "drum_timestep_cost.csv").exists():
        measured = {(r["law"], r["tc_over_dt"]): r for r in harness.read_csv(out / "drum_timestep_cost.csv")}
    rows, runs = rows_of(Path(a.docs), measured)
    harness.write_csv(out / "drum_timestep.csv", rows, COLUMNS)
    for rpm in sorted({r["rpm"] for r in rows}):
        if not chart(rows, rpm, out / f"drum_timestep_{rpm}rpm.png"):
            harness.say("drum_timestep", f"{rpm} rpm: nothing to chart")
    for (rpm, law, ratio), run in runs.items():
        harness.say("drum_timestep", f"{rpm} rpm {law} tc/{ratio:g}: {run['state']}, {run['window_s']:g} s steady, "
                                     f"{run['cost']:.4g} wall s per simulated s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
