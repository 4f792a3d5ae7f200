#!/usr/bin/python3
"""Stability map: dt/tc swept past failure, for several en (--scenes, default all three):

  binary  the head-on collision: the integrator's recurrence (`collide recurrence`; LIGGGHTS
          follows it to round-off), mean and largest restitution over the contact-start phase;
  column  inputs/column.in settled at tc/10, then --column-time s at each dt: stock
          hooke/stiffness fed our constants (no guard: where does it fail?) and `model viscoelastic`
          (what does the guard say?), under --loads times gravity. Failure: beads leave the box, or
          the kinetic energy ends above --column-energy-factor times that of the same en and load at
          the reference dt/tc (a settled bed's energy scales with its load; the factor does not);
  drum    the settled 6 mm slab (--restart; `settled`: the shipped 24 mm thesis scene) at 21 rpm
          continued for --drum-time s at each dt, the --drum-runs en:model[:law] specs (en `table` =
          Table 3.1 with the thesis conventions; law, with model viscoelastic: nominal,
          exactRestitution or exactCollision, with tangential pournin; without: the nominal law, as
          drum.in's defaults were when the plain rows were measured, common.THEN). Failure:
          the run stops (beads leave through the drum wall), beads are missing at the end, or the
          kinetic energy ends above twice that of the same pair at the reference dt/tc.
The guard's limits come from `contact_law limit`. --append merges the rows into the existing
OUT/stability_column.csv and OUT/DRUM_NAME.csv (a rerun of the same en, dt/tc, model and load
replaces the old row).
Writes OUT/stability_{binary,column,drum,limits}.csv and OUT/stability.json.

Needs: python3-matplotlib (tools/harness), mpirun; liggghts, collide, contact_law."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
import harness  # noqa: E402
import common  # noqa: E402

RUN_COLUMNS = ["en", "dt_over_tc", "model", "status", "beads_kept", "beads", "ke_final_J", "guard", "load"]
MODELS = ("hooke", "viscoelastic")
DRUM_ENERGY_FACTOR = 2  # the drum fails when its kinetic energy ends above this times the reference's
LONG_DRUM_FRACTIONS = "0.2,0.22,0.24,0.26,0.28,0.3,0.32"  # the committed 0.2 s drum runs
# the drum's --drum-runs laws: drum.in's variables (exactCollision needs tangential pournin; so the
# others take it too, to compare like for like)
LAWS = {"nominal": {"exact": "off", "tangential": "pournin"},
        "exactRestitution": {"exact": "on", "tangential": "pournin"},
        "exactCollision": {"collision": "on", "exact": "off", "tangential": "pournin"}}
SLAB_COMMAND = ("mpirun -np 2 liggghts -in inputs/drum.in -var period 0.006 -var start grid "
                + "".join(f"-var {k} {v} " for k, v in common.MESH.items()) + "-var tangential pournin "
                "{flag} -var time 1.0 -var dt 2e-5 -var name stability_drum/slab6_{law}")
EXACT_DRUM_FRACTIONS = "0.2,0.225,0.247,0.25"  # the committed runs of the exact laws; the guard: 0.247-0.248
COLUMN_ENERGY_FACTOR = 10  # the settled column: its energy is 1e-9-1e-4 J where stable, jumps by decades past it


def parser():
    p = harness.options(__doc__, np=2, out=common.RESULTS)
    p.add_argument("--scenes", default="binary,column,drum", help="of binary,column,drum (default: all)")
    p.add_argument("--en", default="0.1,0.3,0.56,0.95", help="binary and column (default: %(default)s)")
    p.add_argument("--fractions", default="0.1,0.125,0.15,0.175,0.2,0.225,0.25,0.275,0.3,0.35,0.4,0.45,0.5,0.55,0.6",
                   help="dt/tc of the binary and column scenes (default: %(default)s)")
    p.add_argument("--column-time", type=float, default=0.05, help="s per column run (default: 0.05)")
    p.add_argument("--settle-time", type=float, default=0.25, help="s to settle the column (default: 0.25)")
    p.add_argument("--column-energy-factor", type=float, default=COLUMN_ENERGY_FACTOR,
                   help="column failure: kinetic energy above this times the reference dt/tc's (default: %(default)s)")
    p.add_argument("--loads", default="1,30", help="column: gravity factors, e.g. 1,30 for a packing under the weight of "
                                                "a 30 times taller column (more, and more loaded, contacts)")
    p.add_argument("--restart", type=Path, help="the settled 6 mm drum slab (drum scene)")
    p.add_argument("--drum-runs", default="0.3:hooke,0.9:hooke,table:hooke,table:viscoelastic", help="en:model pairs")
    p.add_argument("--drum-fractions", default="0.1,0.2,0.25,0.3,0.35,0.4,0.45,0.5", help="dt/tc of the drum scene")
    p.add_argument("--drum-period", help="drum.in's period [m] of the --restart state (default: 0.006, the slab's; "
                                          "with --restart settled: 24 mm)")
    p.add_argument("--drum-time", type=float, default=0.03, help="s per drum run (default: 0.03)")
    p.add_argument("--reference", type=float, default=0.1, help="dt/tc of the drum's energy reference (default: 0.1)")
    p.add_argument("--append", action="store_true", help="merge the rows into OUT/stability_column.csv and OUT/DRUM_NAME.csv")
    p.add_argument("--drum-name", default="stability_drum",
                   help="drum results: OUT/DRUM_NAME.csv (another name: its settings in OUT/DRUM_NAME.json)")
    return p


def classify(ran, kept, total, ke, ke_limit):
    """A run's status from its log's numbers: `stopped` (LIGGGHTS exited with an error), `failed`
    (beads lost, or the kinetic energy ended above ke_limit), or `ok`."""
    if not ran:
        return "stopped"
    return "failed" if kept < total or ke > ke_limit else "ok"


def run_row(en, fraction, model, log, ke_limit, ke):
    kept = log.grep(r"^(?:column|drum): done, (\d+) beads kept", cast=int, default=0)
    total = log.grep(r"^(?:column|drum): (\d+) beads(?:, dt| \(target)", cast=int, default=0)
    return {"en": en, "dt_over_tc": fraction, "model": model, "guard": "error" if common.guard_stopped(log) else "none",
            "status": classify(log.returncode == 0, kept, total, ke, ke_limit), "beads_kept": kept, "beads": total,
            "ke_final_J": ke}


def binary(ens, fractions):
    rows = []
    for en in ens:
        text = harness.tool("collide", "recurrence", "--en", en, "--dt-over-tc", *fractions)
        rows += [dict(en=en, **r) for r in harness.read_csv_text(text)]
    return rows


def column(ens, fractions, args):
    rows = []
    for en, load in [(en, load) for load in common.numbers(args.loads) for en in ens]:
        tag = f"column_en{en:g}" + (f"_load{load:g}" if load != 1 else "")
        harness.say("stability", f"settling the column, en {en:g}, load {load:g} ...")
        harness.liggghts("inputs/column.in", {"en": en, "time": args.settle_time, "name": f"stability/{tag}",
                                              "load": load}, log=harness.post(f"stability/{tag}.log"))
        stock = common.stock_file(harness.post(f"stability/stock_{en:g}.in"), uniform=en)
        ke_ref = {}
        for f in [args.reference] + [f for f in fractions if f != args.reference]:
            for model in MODELS:
                name = f"stability/{tag}_{f:g}_{model}"
                log = harness.liggghts("inputs/column.in", {
                    "start": "restart", "restart": harness.post(f"stability/{tag}.restart"), "en": en,
                    "time": args.column_time, "dt": f"{f * common.tc():.6g}", "model": model, "stock": stock,
                    "name": name, "load": load}, log=harness.post(name + ".log"), check=False)
                ke = log.grep(r"^column: done, .* ke (\S+) J", cast=float, default=float("nan"))
                if f == args.reference and log.returncode == 0:
                    ke_ref[model] = ke
                limit = args.column_energy_factor * ke_ref.get(model, float("inf"))
                rows.append({**run_row(en, f, model, log, limit, ke), "load": load})
                harness.say("stability", f"column en {en:g}, dt/tc {f:g}, {model}: {rows[-1]['status']}")
    return rows


def drum_period(args):
    """drum.in's period for the drum runs: --drum-period, else the shipped scene's or the slab's."""
    return args.drum_period or (0.024 if str(args.restart) == "settled" else common.THEN["period"])


def drum(args):
    fractions = common.numbers(args.drum_fractions)
    fractions = [args.reference] + [f for f in fractions if f != args.reference]
    rows = []
    # drum.in's defaults when the plain rows were measured (common.THEN: the nominal law unless a
    # law says otherwise, the slab's period, the middle cut); the later sets (stability_drum_long,
    # stability_drum_exact) ran with the cut at the beds' median, which changes round-off only
    start = (common.then(start="settled", period=drum_period(args)) if str(args.restart) == "settled" else
             common.then(start="restart", restart=args.restart, period=drum_period(args)))
    for spec in common.words(args.drum_runs):
        en, model, *law = spec.split(":")
        stock = common.stock_file(harness.post(f"stability_drum/stock_{en}.in"),
                                  uniform=None if en == "table" else float(en))
        laws = LAWS.get(law[0]) if law else {}
        if laws is None:
            raise SystemExit(f"stability: --drum-runs {spec}: law {law[0]} is none of {', '.join(LAWS)}")
        if law and model != "viscoelastic":
            raise SystemExit(f"stability: --drum-runs {spec}: a law needs model viscoelastic, not {model}")
        label = model + (f"/{law[0]}" if law else "")
        ke_ref = float("inf")
        for f in fractions:
            tag = f"stability_drum/en{en}_{f:g}_{label.replace('/', '_')}"
            log = harness.drum(harness.post(tag + ".log"), np=args.np, check=False, **{
                **start, "rpm": common.RPM, "dt": f"{f * common.tc():.6g}", "time": args.drum_time, "dumpdt": 1,
                "model": model, "stock": stock, "name": tag, **laws})
            ke = log.thermo().get("KinEng", float("nan"))
            if f == args.reference and log.returncode == 0:
                ke_ref = ke
            rows.append({**run_row(en if en == "table" else float(en), f, label, log, DRUM_ENERGY_FACTOR * ke_ref, ke),
                         "load": 1})
            harness.say("stability", f"drum en {en}, dt/tc {f:g}, {model}: {rows[-1]['status']}")
    return rows


def merge(old, new):
    """Drum or column rows: `new` replaces the rows of `old` with the same en, dt/tc, model and load."""
    key = lambda r: (str(r["en"]), float(r["dt_over_tc"]), r["model"], float(r.get("load", 1)))  # noqa: E731
    merged = {key(r): r for r in old}
    merged.update({key(r): r for r in new})
    return list(merged.values())


def run(args):
    out = Path(args.out)
    scenes = common.words(args.scenes)
    ens, fractions = common.numbers(args.en), common.numbers(args.fractions)
    if "binary" in scenes:
        harness.write_csv(out / "stability_binary.csv", binary(ens, fractions))
    if "column" in scenes:
        rows = column(ens, fractions, args)
        column_csv = out / "stability_column.csv"
        if args.append and column_csv.exists():
            rows = merge(harness.read_csv(column_csv), rows)
        harness.write_csv(column_csv, rows, RUN_COLUMNS)
    if "drum" in scenes:
        if not args.restart:
            raise SystemExit("stability: the drum scene needs --restart FILE (a settled 6 mm drum)")
        rows = drum(args)
        drum_csv = out / f"{args.drum_name}.csv"
        if args.append and drum_csv.exists():
            rows = merge(harness.read_csv(drum_csv), rows)
        harness.write_csv(drum_csv, rows, RUN_COLUMNS)
    m = harness.materials()
    limits_csv = out / "stability_limits.csv"
    kept = {r["en"] for r in harness.read_csv(limits_csv)} if args.append and limits_csv.exists() else set()
    harness.write_csv(limits_csv, [common.limits(en) for en in sorted(set(ens) | kept | {m["drum_en"]})])
    meta = harness.read_json(out / "stability.json") if (out / "stability.json").exists() else {}
    if "column" in scenes:
        meta.pop("column_ke_J", None)
        meta.update({"column_time_s": args.column_time, "column_energy_factor": args.column_energy_factor,
                     "settle_ratio": 10, "reference": args.reference, "loads": args.loads})
    meta.update({"drum_energy_factor": DRUM_ENERGY_FACTOR, "date": common.today()})
    drum_meta = {"drum_time_s": args.drum_time, "drum_restart": str(args.restart),
                 "drum_period": drum_period(args),
                 "reference": args.reference,
                 "drum_energy_factor": DRUM_ENERGY_FACTOR, "date": common.today()}
    if "drum" in scenes and args.drum_name != "stability_drum":
        # a second drum set keeps its own settings, and (appended) the state each of its runs started from
        meta_json = out / f"{args.drum_name}.json"
        starts = harness.read_json(meta_json).get("drum_restarts", {}) if args.append and meta_json.exists() else {}
        starts.update({spec: str(args.restart) for spec in common.words(args.drum_runs)})
        harness.write_json(meta_json, {**drum_meta, "drum_restarts": starts})
    elif "drum" in scenes:
        meta.update(drum_meta)
    harness.write_json(out / "stability.json", meta)


def first(rows, test):
    """The smallest dt/tc of the rows that pass `test` (None if none does)."""
    hits = [r["dt_over_tc"] for r in rows if test(r)]
    return min(hits) if hits else None


def summary(binary_rows, column_rows, drum_rows, limits, bead_en, drum_en):
    """One row per en and load: binary limit, where things fail, where the guard stops (and the
    stiffening Z at which the Jury limit equals the first failing dt), and whether it stops first."""
    rows = []
    for en, load in sorted({(r["en"], r["load"]) for r in column_rows}):
        b = [r for r in binary_rows if r["en"] == en]
        grow = first(b, lambda r: r["restitution_mean"] > 1)
        here = [r for r in column_rows if r["en"] == en and r["load"] == load]
        cfail = first(here, lambda r: r["model"] == "hooke" and r["status"] != "ok")
        guard = first(here, lambda r: r["model"] == "viscoelastic" and r["guard"] == "error")
        # the drum's Table 3.1 runs are the bead en's row; their bead-drum pairs set its guard
        den, dguard_en = ("table", drum_en) if en == bead_en else (en, en)
        dfail = first(drum_rows, lambda r: str(r["en"]) == str(den) and r["model"] == "hooke" and r["status"] != "ok")
        g, gd = limits[en]["guard_tc"], limits[dguard_en]["guard_tc"]
        before = all(x is None or lim < x for lim, x in ((g, cfail), (g, grow), (gd, dfail)))
        rows.append({"en": en, "load": load, "limit": limits[en]["binary_limit_tc"], "grow": grow, "cfail": cfail,
                     "z": None if cfail is None else common.stiffening(en, cfail), "dfail": dfail if load == 1 else None,
                     "guard": f"{g:.4g}" + (f"; drum {gd:.4g} (bead-drum en {dguard_en:g})" if dguard_en != en else ""),
                     "guard_column": guard, "before": "yes" if before else "NO"})
    return rows


def chart(binary_rows, column_rows, drum_rows, meta, path):
    fig, axes = harness.figure(1, 3 if drum_rows else 2, size=(6.3, 5.2))
    a = axes[0]
    for i, en in enumerate(sorted({r["en"] for r in binary_rows})):
        b = [r for r in binary_rows if r["en"] == en]
        a.plot([r["dt_over_tc"] for r in b], [r["restitution_mean"] for r in b], "o-", color=f"C{i}", label=f"mean, en {en:g}")
        a.plot([r["dt_over_tc"] for r in b], [r["restitution_max"] for r in b], "--", color=f"C{i}", label=f"max, en {en:g}")
    a.axhline(1, color="black", lw=1)
    a.set(title="binary collision (the integrator recurrence)", ylabel="restitution, phase-averaged / largest single contact",
          ylim=(0, 2.5))
    c = axes[1]
    for i, (en, load) in enumerate(sorted({(r["en"], r["load"]) for r in column_rows})):
        # runs that lost every bead have no energy to show
        s = sorted((r for r in column_rows if r["en"] == en and r["load"] == load and r["model"] == "hooke"
                    and r["beads_kept"] > 0), key=lambda r: r["dt_over_tc"])
        ref = [r["ke_final_J"] for r in s if r["dt_over_tc"] == meta["reference"]][0]
        c.plot([r["dt_over_tc"] for r in s], [r["ke_final_J"] / ref for r in s], "o-" if load == 1 else "s--",
               color=f"C{i // 2 if len(set(r['load'] for r in column_rows)) > 1 else i}", label=f"en {en:g}, {load:g} g")
    c.axhline(meta["column_energy_factor"], color="black", ls=":", label="failure threshold")
    c.set(title="dense column, stock hooke/stiffness with our constants", yscale="log", ylim=(0.1, 1e9),
          ylabel=f"kinetic energy after {meta['column_time_s']:g} s / that at dt/tc {meta['reference']:g}")
    if drum_rows:
        d = axes[2]
        for en in dict.fromkeys(str(r["en"]) for r in drum_rows):
            s = sorted((r for r in drum_rows if str(r["en"]) == en and r["model"] == "hooke"), key=lambda r: r["dt_over_tc"])
            if s:
                d.plot([r["dt_over_tc"] for r in s], [10 if r["status"] == "stopped" else r["ke_final_J"] for r in s], "o-",
                       label="Table 3.1" if en == "table" else f"en {en}")
        ref = [r["ke_final_J"] for r in drum_rows if r["dt_over_tc"] == meta["reference"] and r["status"] == "ok"]
        d.axhline(meta["drum_energy_factor"] * harness.median(ref), color="black", ls=":",
                  label=f"failure threshold ({meta['drum_energy_factor']}x the dt/tc {meta['reference']:g} energy)")
        d.set(title="drum, stock hooke/stiffness", yscale="log", ylim=(1e-3, 20),
              ylabel=f"kinetic energy after {meta['drum_time_s']:g} s [J]; stopped runs at 10 J")
    for ax in axes:
        ax.set_xlabel("dt / tc")
        ax.legend(fontsize=7)
    harness.save(fig, path)


RUN_TABLE = [("en", lambda r: f"{r['en']:g}" if isinstance(r["en"], float) else r["en"], None),
             ("load [g]", lambda r: f"{r.get('load', 1):g}", None),
             ("dt/tc", "dt_over_tc", "{:g}"), ("model", "model", None), ("status", "status", None),
             ("beads kept", lambda r: f"{r['beads_kept']:.0f}/{r['beads']:.0f}", None),
             ("kinetic energy [J]", "ke_final_J", "{!r}"), ("guard", "guard", None)]


def section(res):
    if not res.has("stability_binary.csv", "stability_column.csv", "stability_limits.csv", "stability.json"):
        return common.not_run("stability")
    meta, binary_rows, column_rows = res.json("stability.json"), res.csv("stability_binary.csv"), res.csv("stability_column.csv")
    column_rows.sort(key=lambda r: (r["load"], r["en"], r["dt_over_tc"], r["model"]))
    drum_rows = res.csv("stability_drum.csv") if res.has("stability_drum.csv") else []
    drum_rows.sort(key=lambda r: (str(r["en"]), r["model"], r["dt_over_tc"]))
    # longer drum runs (stability_drum_long.json: their duration), where they were made
    long_rows = res.csv("stability_drum_long.csv") if res.has("stability_drum_long.csv") else []
    long_meta = res.json("stability_drum_long.json") if long_rows else {}
    limits = {r["en"]: r for r in res.csv("stability_limits.csv")}
    m = harness.materials()
    chart(binary_rows, column_rows, drum_rows, meta, res.path("stability.png"))
    ens = sorted({r["en"] for r in column_rows})
    beads = int(column_rows[0]["beads"])
    rows = summary(binary_rows, column_rows, drum_rows + long_rows, limits, m["bead_en"], m["drum_en"])
    failing = [r for r in rows if r["cfail"] is not None]
    zfail = (min(r["z"] for r in failing), max(r["z"] for r in failing))
    stable = [common.stiffening(en, max(r["dt_over_tc"] for r in column_rows if r["en"] == en and r["load"] == load
                                 and r["model"] == "hooke" and r["status"] == "ok"))
              for en, load in {(r["en"], r["load"]) for r in column_rows}]
    zstable = (min(stable), max(stable))
    frac = (min(r["cfail"] / r["limit"] for r in failing), max(r["cfail"] / r["limit"] for r in failing))
    margin = (min(1 - limits[r["en"]]["guard_tc"] / r["cfail"] for r in failing),
              max(1 - limits[r["en"]]["guard_tc"] / r["cfail"] for r in failing))
    text = (
        f"dt/tc swept past failure for en = {common.fmt_list(ens)} (tc = {common.sci(m['bead_tc'])} s). Binary collision: the\n"
        "integrator's recurrence (LIGGGHTS follows it to round-off). Dense column: `inputs/column.in`,\n"
        f"{beads} beads settled at tc/{meta['settle_ratio']} under gravity times {meta['loads']} (the packing under "
        "the weight of a column that many times taller:\nmore, and more loaded, contacts), then "
        f"{meta['column_time_s']:g} s at each dt, with stock hooke/stiffness fed our constants\n"
        "(no guard) and with `model viscoelastic` (guard); the drum likewise (below). Failure: beads leave the box "
        "or the kinetic\n"
        f"energy ends above {meta['column_energy_factor']:g} times that at dt/tc {meta['reference']:g} (the settled "
        "energy scales with the load).\n"
        "`model viscoelastic` and stock runs are otherwise identical (same kinetic energies below).\n\n"
        "**The guard** (`contact_models/core/stability.h`) stops a run whose timestep exceeds the binary (Jury) "
        "limit of a contact\n"
        f"Z = {common.stiffening(ens[0], limits[ens[0]]['guard_tc']):.3g} times stiffer and more damped than the type pair's, as a bead pressed "
        "by several neighbours at once feels\ntheir springs and dashpots in parallel. Z is fitted to the column: "
        f"at each en and load the first failing dt/tc is\nthe Jury limit of Z = {zfail[0]:.2f}-{zfail[1]:.2f} "
        f"(column *Z at failure*), the last stable one of Z = {zstable[0]:.2f}-{zstable[1]:.2f}, while a fixed "
        f"fraction\nof the binary limit is not one number (the onset lies at {frac[0]:.2f}-{frac[1]:.2f} of it). "
        f"The guard lies {100 * margin[0]:.0f}-{100 * margin[1]:.0f} % below the\nfirst failure of every en and load; "
        "the turning drum fails later (the drum column).\n\n"
        + res.image("stability", "stability.png") + "\n"
        + harness.markdown(rows, [
            ("en", "en", "{:g}"), ("load [g]", "load", "{:g}"), ("binary limit (Jury) dt/tc", "limit", "{:.4g}"),
            ("binary: mean restitution > 1 from dt/tc", lambda r: "none" if r["grow"] is None else f"{r['grow']:.4f}", None),
            ("column (stock) fails from dt/tc", lambda r: "none" if r["cfail"] is None else f"{r['cfail']:g}", None),
            ("Z at failure", lambda r: "–" if r["z"] is None else f"{r['z']:.2f}", None),
            ("drum (stock) fails from dt/tc", lambda r: "–" if r["dfail"] is None else f"{r['dfail']:g}", None),
            ("guard: ERROR above dt/tc", "guard", None),
            ("guard ERROR in the column runs from dt/tc",
             lambda r: "none" if r["guard_column"] is None else f"{r['guard_column']:g}", None),
            ("guard stops before failure", "before", None)])
        + "\n<details><summary>all column runs</summary>\n\n" + harness.markdown(column_rows, RUN_TABLE) + "\n</details>\n\n")
    if drum_rows:
        beads = int(max(r["beads"] for r in drum_rows))
        uniform = sorted({r["en"] for r in drum_rows if r["en"] != "table"})
        uniform = f"en = {common.fmt_list(uniform, ' and ')} for every pair and with " if uniform else ""
        text += (
            f"Drum: the settled 6 mm slab ({beads:,} beads, {common.RPM} rpm) continued for {meta['drum_time_s']:g} s at "
            "each dt, stock\n"
            f"hooke/stiffness with {uniform}Table 3.1 (beads {m['bead_en']:g}, drum {m['drum_en']:g};\n"
            f"the {m['bead_en']:g} row above), and `model viscoelastic` with Table 3.1. Failure: the run stops "
            "(beads leave\n"
            f"through the drum wall), beads are missing, or the kinetic energy ends above "
            f"{'twice' if meta['drum_energy_factor'] == 2 else str(meta['drum_energy_factor']) + ' times'} that at tc/{1 / meta['reference']:g}.\n\n"
            + harness.markdown(drum_rows, RUN_TABLE) + "\n")
    if long_rows:
        text += (f"The same slab for {long_meta['drum_time_s']:g} s (near the boundary the flow's own fluctuation "
                 "makes single runs disagree; the\nkinetic energies are the data):\n\n"
                 + harness.markdown(sorted(long_rows, key=lambda r: (str(r["en"]), r["dt_over_tc"])), RUN_TABLE) + "\n")
    exact_rows = res.csv("stability_drum_exact.csv") if res.has("stability_drum_exact.csv") else []
    if exact_rows:
        exact_meta = res.json("stability_drum_exact.json")
        guards = {law: tuple(common.limits(m[f"{p}_en"], law, et=m[f"{p}_et"])["guard_tc"] for p in ("bead", "drum"))
                  for law in ("exactRestitution", "exactCollision")}
        text += ("**The exact laws on the drum**: for each law a 6 mm slab run for 1 s from the grid at 21 rpm with "
                 "`tangential pournin` and that law (commands below; a state made with another law or tangential model "
                 f"does not restart: its contact history differs), then {exact_meta['drum_time_s']:g} s "
                 "at each dt with Table 3.1 and each law (tangential pournin); failure as above, against the same "
                 f"law at tc/{1 / exact_meta['reference']:g}. The guard admits up to dt/tc "
                 + ", ".join(f"{g[0]:.4f} / {g[1]:.4f} ({law})" for law, g in guards.items())
                 + " for the bead / bead-drum pair; runs above it stop with its ERROR (`guard`). One 0.2 s run per dt, "
                 "from a state 1 s old.\n\n"
                 + harness.markdown(sorted(exact_rows, key=lambda r: (r["model"], r["dt_over_tc"])), RUN_TABLE) + "\n")
    restart = meta.get("drum_restart")
    commands = [common.command("stability.py", scenes="binary,column"),
                common.command("stability.py", scenes="drum", restart=restart),
                common.command("stability.py", scenes="drum", restart=restart, drum_runs="0.3:hooke",
                               drum_fractions="0.21,0.22,0.23,0.24", append=True)]
    if long_rows:
        commands.append(common.command("stability.py", scenes="drum", restart=long_meta["drum_restart"],
                                       drum_runs="0.3:hooke,table:hooke", drum_fractions=LONG_DRUM_FRACTIONS,
                                       drum_time=long_meta["drum_time_s"], drum_name="stability_drum_long"))
    if exact_rows:
        for law, flag in (("exactCollision", "-var collision on"), ("exactRestitution", "-var exact on")):
            commands.append(SLAB_COMMAND.format(flag=flag, law=law))
            commands.append(common.command("stability.py", scenes="drum",
                                           restart=f"post/stability_drum/slab6_{law}.restart",
                                           drum_period=exact_meta.get("drum_period"), drum_runs=f"table:viscoelastic:{law}",
                                           drum_fractions=EXACT_DRUM_FRACTIONS, drum_time=exact_meta["drum_time_s"],
                                           drum_name="stability_drum_exact", append=True))
    return text + common.sh(*commands)


if __name__ == "__main__":
    run(parser().parse_args())
