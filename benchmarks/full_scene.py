#!/usr/bin/python3
"""Speed of the full thesis scene: each lever measured on the 65k-bead drum from one settled state.

From --restart (the 24 mm scene, settled), at the recommended settings (dt = tc/5 with
exactRestitution on; --ratio and --exact for another timestep), short runs of --time simulated
seconds, the variants interleaved over --rounds (A B C ... A B C ...):
  mesh            static mesh with a surface velocity, rank cut in the middle of the box (the old default)
  balance         the same with the rank cut at the beads' median (-var balance on)
  cylinder        balance, and the drum as a primitive cylinder (-var wall cylinder)
  skin 0.3, 0.7   balance with a neighbour skin of 0.3 / 0.7 bead diameters (default 0.5)
  stock           balance with stock hooke/stiffness fed the same (exact) constants: the peer
  fast            balance, cylinder and skin 0.3 together (the study's settings)
  stock fast      fast with stock hooke/stiffness: the peer on the same settings
  fast 0.2, 0.1, 0.05  fast with a neighbour skin of 0.2 / 0.1 / 0.05 bead diameters: at a smaller timestep a
                  bead moves less per step, so a thinner skin (fewer pairs to check every step)
                  costs fewer extra neighbour-list builds than at tc/5
  sort 100, 25    fast with the beads re-sorted in memory by position every 100 / 25 steps
                  (LIGGGHTS' default, which fast keeps: 1000), so that neighbours sit close in memory;
                  LIGGGHTS sorts at a neighbour build, so at the first build after that many steps
  1 rank          the mesh variant on one rank: the parallel efficiency t(1) / (2 t(2)) per round
                  of mesh and balance (on one rank the same work)
  1 rank fast     fast on one rank: the parallel efficiency of fast
  2 at once       two runs of fast on one rank each, started together (the study's independent
                  runs, e.g. two speeds, side by side instead of one after the other on 2 ranks):
                  their combined particle-steps over the later one's loop time, against fast's
Cost: LIGGGHTS loop time (median, and the range over rounds), particle-steps per second, beads,
ghosts and neighbour pairs per rank (LIGGGHTS' Nlocal/Nghost/Neighs), neighbour-list builds.
Writes OUT/full_scene.csv (one row per run) and OUT/full_scene.json.

Needs: python3-matplotlib (tools/harness), python3-scipy, mpirun; liggghts, contact_law."""

import gzip
import shutil
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from scipy import stats

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
import harness  # noqa: E402
import common  # noqa: E402

RATIO = 5  # dt = tc/5 with exactRestitution on: the recommended setting (the defaults)
# name: (ranks, drum.in -var overrides)
BASE = {"balance": "off", "wall": "surface", "skin": 0.5, "model": "viscoelastic", "sort": 1000}  # explicit: defaults change
VARIANTS = {
    "mesh": (2, BASE),
    "balance": (2, {**BASE, "balance": "on"}),
    "cylinder": (2, {**BASE, "balance": "on", "wall": "cylinder"}),
    "skin 0.3": (2, {**BASE, "balance": "on", "skin": 0.3}),
    "skin 0.7": (2, {**BASE, "balance": "on", "skin": 0.7}),
    "stock": (2, {**BASE, "balance": "on", "model": "hooke"}),
    "fast": (2, {**BASE, "balance": "on", "wall": "cylinder", "skin": 0.3}),
    "stock fast": (2, {**BASE, "balance": "on", "wall": "cylinder", "skin": 0.3, "model": "hooke"}),
    "fast 0.2": (2, {**BASE, "balance": "on", "wall": "cylinder", "skin": 0.2}),
    "fast 0.1": (2, {**BASE, "balance": "on", "wall": "cylinder", "skin": 0.1}),
    "fast 0.05": (2, {**BASE, "balance": "on", "wall": "cylinder", "skin": 0.05}),
    "sort 100": (2, {**BASE, "balance": "on", "wall": "cylinder", "skin": 0.3, "sort": 100}),
    "sort 25": (2, {**BASE, "balance": "on", "wall": "cylinder", "skin": 0.3, "sort": 25}),
    "1 rank": (1, BASE),
    "1 rank fast": (1, {**BASE, "wall": "cylinder", "skin": 0.3}),
    "2 at once": (1, {**BASE, "wall": "cylinder", "skin": 0.3}),  # two of these together
}
AT_ONCE = {"2 at once": 2}  # variant: how many one-rank runs start together
# the one-rank run doing the same work as a two-rank variant (balance only moves the cut)
SERIAL = {"mesh": "1 rank", "balance": "1 rank", "fast": "1 rank fast"}


class Together:
    """Runs started together, read as one measurement: their beads and cores add up, and the
    work is done when the later one ends (its loop time)."""

    def __init__(self, logs):
        self.logs = logs
        self.procs = sum(lg.procs for lg in logs)
        self.loop_time = max(lg.loop_time for lg in logs)
        self.steps = logs[0].steps
        self.atoms = sum(lg.atoms for lg in logs)
        self.per_rank = logs[0].per_rank
        self.neighbor_builds = logs[0].neighbor_builds
        self.particle_steps_per_s = sum(lg.atoms * lg.steps for lg in logs) / self.loop_time


def parser():
    p = harness.options(__doc__, out=common.RESULTS, rounds=3, restart=None)
    p.add_argument("--time", type=float, default=0.02, help="simulated s per run (default: 0.02)")
    p.add_argument("--ratio", type=float, default=RATIO, help="dt = tc / RATIO (default: %(default)s)")
    p.add_argument("--exact", choices=("on", "off"), default="on",
                   help="exactRestitution (default: %(default)s; off: the nominal law, as the timestep study runs it)")
    p.add_argument("--period", type=float, default=0.024, help="axial period of the state [m] (default: 0.024)")
    p.add_argument("--variants", default=",".join(VARIANTS), help="which variants (default: all)")
    p.add_argument("--stem", default="full_scene",
                   help="results OUT/STEM.csv and .json (default: %(default)s; full_scene_long: the long windows)")
    return p


def run(args):
    if not args.ratio > 0:
        raise SystemExit(f"full_scene: --ratio {args.ratio:g}: dt = tc / ratio needs ratio > 0")
    dt = common.dt_of(args.ratio)
    stock = common.stock_file(harness.post("full_scene/stock.in"), exact_dt=dt if args.exact == "on" else None)
    names = [v.strip() for v in args.variants.split(",")]
    unknown = [n for n in names if n not in VARIANTS]
    if unknown:
        raise SystemExit(f"full_scene: unknown variant(s) {', '.join(unknown)} (of {', '.join(VARIANTS)})")

    restart = Path(args.restart)
    restart = restart if restart.is_absolute() else harness.REPO / restart
    if restart.suffix == ".gz":  # a shipped state: LIGGGHTS reads restart files uncompressed
        plain = harness.post("full_scene", restart.stem)
        with gzip.open(restart, "rb") as f, open(plain, "wb") as g:
            shutil.copyfileobj(f, g)
        restart = plain

    def one(tag, ranks, extra):
        return harness.drum(harness.post(tag + ".log"), np=ranks, period=args.period, rpm=common.RPM, dt=dt,
                            exact=args.exact, time=args.time, dumpdt=1000, start="restart", restart=restart,
                            stock=stock, name=tag, **extra)

    def variant(name):
        ranks, extra = VARIANTS[name]
        tag = "full_scene/" + name.replace(" ", "_")
        if name not in AT_ONCE:
            return lambda: one(tag, ranks, extra)

        def together():
            with ThreadPoolExecutor(AT_ONCE[name]) as pool:
                runs = [pool.submit(one, f"{tag}_{i + 1}", ranks, extra) for i in range(AT_ONCE[name])]
                return Together([r.result() for r in runs])
        return together

    logs = harness.interleaved({n: variant(n) for n in names}, args.rounds,
                               progress=lambda s: harness.say("full_scene", s))
    rows = [{"variant": n, "round": i + 1, "ranks": lg.procs, "loop_s": lg.loop_time, "steps": lg.steps,
             "beads": lg.atoms, "particle_steps_per_s": lg.particle_steps_per_s,
             "nlocal_max": lg.per_rank["Nlocal"][1], "nlocal_min": lg.per_rank["Nlocal"][2],
             "nghost_max": lg.per_rank["Nghost"][1], "neighs_max": lg.per_rank["Neighs"][1],
             "neighs_min": lg.per_rank["Neighs"][2], "neighbor_builds": lg.neighbor_builds}
            for n in names for i, lg in enumerate(logs[n])]
    harness.write_csv(Path(args.out) / f"{args.stem}.csv", rows)
    harness.write_json(Path(args.out) / f"{args.stem}.json", {
        "restart": str(args.restart), "time_s": args.time, "rounds": args.rounds, "period_m": args.period,
        "dt_s": dt, "tc_over_dt": args.ratio, "exact": args.exact, "cores": harness.machine()["cores"], "date": common.today(),
        "variants": args.variants, "stem": args.stem})


def summary(rows):
    """One row per variant: median loop time and its range, rate, ratio to `mesh` per round."""
    by = {}
    for r in rows:
        by.setdefault(r["variant"], []).append(r)
    mesh = [r["loop_s"] for r in by.get("mesh", [])]
    table = []
    for name, runs in by.items():
        loops = [r["loop_s"] for r in runs]
        row = {"variant": name, "ranks": int(runs[0]["ranks"]), "loop": harness.median(loops),
               "range": "–".join(f"{x:.1f}" for x in harness.spread(loops)),
               "psps": harness.median([r["particle_steps_per_s"] for r in runs]),
               "beads": f"{runs[0]['nlocal_max']:.0f} / {runs[0]['nlocal_min']:.0f}",
               "neighs": f"{runs[0]['neighs_max']:.0f} / {runs[0]['neighs_min']:.0f}",
               "builds": f"{runs[0]['neighbor_builds']:.0f}",
               "vs_mesh": harness.median_ratio(mesh, loops) if mesh else float("nan")}
        if SERIAL.get(name) in by:
            one = [r["loop_s"] for r in by[SERIAL[name]]]
            row["efficiency"] = harness.median([a / (row["ranks"] * b) for a, b in zip(one, loops)])
        else:
            row["efficiency"] = float("nan")
        table.append(row)
    return table


def render(res, m, rows):
    table = summary(rows)
    beads = int(rows[0]["beads"])
    ran = m.get("variants") or ",".join(dict.fromkeys(r["variant"] for r in rows))  # older results: from the rows
    return (
        f"The thesis scene ({1e3 * m['period_m']:.0f} mm period, {beads:,} beads) from `{m['restart']}` at "
        f"{common.RPM} rpm, dt = tc/{m['tc_over_dt']:g} with exactRestitution {m.get('exact', 'on')}, {m['time_s']:g} s per run,\n"
        f"{m['rounds']} interleaved rounds, {m['date']} ({m['cores']} cores). Speed-up: the median over rounds of "
        "t(mesh) / t(variant); parallel efficiency: t(1 rank, same work) / (2 t(variant)), per round: `1 rank` "
        "for mesh and balance, `1 rank fast` for fast.\n\n"
        + harness.markdown(table, [("variant", "variant", None), ("ranks", "ranks", None),
                                   ("loop time [s] (median, range)", lambda r: f"{r['loop']:.1f} ({r['range']})", None),
                                   ("particle-steps/s", "psps", "{:.3g}"), ("speed-up vs mesh", "vs_mesh", "{:.2f}"),
                                   ("parallel efficiency", "efficiency", "{:.2f}"),
                                   ("beads per rank (max / min)", "beads", None),
                                   ("neighbour pairs per rank (max / min)", "neighs", None),
                                   ("neighbour builds", "builds", None)])
        + "\n" + verdict(table, rows)
        + common.sh(common.command("full_scene.py", restart=m["restart"], time=m["time_s"], rounds=m["rounds"],
                                   ratio=None if m["tc_over_dt"] == RATIO else f"{m['tc_over_dt']:g}",
                                   exact=None if m.get("exact", "on") == "on" else m["exact"],
                                   variants=None if ran == ",".join(VARIANTS) else ran,
                                   stem=None if m.get("stem", "full_scene") == "full_scene" else m["stem"])))


# the sections after the short runs, each shown where its results exist: (stem, what it measures,
# what follows its table)
MORE = (
    ("full_scene_long", "\nLong windows: the study's settings (`fast`) against stock on them and on one rank, "
                        "runs five times longer:\n\n", None),
    ("full_scene_steady", "\nSteady flow: the same long windows from the chain's steady 21 rpm state, the bed "
                          "carried by the drum (the main job's shipped state). The long windows above start from "
                          "the earlier 3 s state (`inputs/drum_L24_21rpm_3s.restart.gz`), whose bed rides on "
                          "rolling beads and barely turns: fewer neighbour-list builds, a faster loop than a "
                          "study's speeds see. This is the rate `tools/drum/report.py` converts a study's "
                          "particle-steps to minutes with:\n\n", None),
    ("full_scene_at_once", "\nSeveral runs at once: the study's settings on 2 ranks against two one-rank runs "
                           "started together, long windows, from the main job's shipped state (`gunzip -c "
                           "inputs/drum_L24_21rpm.restart.gz > post/full_scene/steady_21rpm.restart`):\n\n", None),
    ("full_scene_efficiency", "\nParallel efficiency in steady flow, more rounds: the study's settings on 2 ranks "
                              "and on one, from the main job's shipped state (the 3 rounds above range over "
                              "0.66–1.22):\n\n", None),
    ("full_scene_sort", "\nSorting: the study's settings (`fast`, LIGGGHTS' default re-sort every 1000 steps) "
                        "against re-sorting the beads by position every 100 and 25 steps (neighbours closer in "
                        "memory; LIGGGHTS sorts at the first neighbour build after that many steps, here builds "
                        "come every 18 steps or so), from the main job's shipped state:\n\n", None),
    ("full_scene_tc81", "\nNeighbour skin at the thesis' tc/81 with the nominal law (the timestep study's "
                        "settings), from the main job's shipped state: a bead moves 16 times less per step than "
                        "at tc/5, so a thinner skin (fewer pairs checked every step) costs fewer extra "
                        "neighbour-list builds. A screen of skins:\n\n", None),
    ("full_scene_tc81_confirm", "\nThe screen's best skin against the study's, more rounds, on their own (the "
                                "screen chose it, so its rounds are no evidence for it):\n\n",
     lambda rows: sign_test(rows, "fast", "fast 0.1")),
)


def section(res):
    """Every lever in short runs; then, where measured, the study's settings in long windows and
    the other sections of MORE."""
    text = common.section_of("full_scene", "full_scene")(render)(res)
    for stem, intro, after in MORE:
        if res.has(stem + ".csv", stem + ".json"):
            text += intro + common.section_of(stem, "full_scene")(render)(res)
            if after:
                text += after(res.csv(stem + ".csv"))
    return text


def sign_test(rows, a, b):
    """In how many rounds `b` is faster than `a`, and the two-sided sign-test chance of so lopsided a
    count if neither were (where the rounds disagree, how far they lean one way)."""
    loops = {n: [r["loop_s"] for r in rows if r["variant"] == n] for n in (a, b)}
    ratios = [x / y for x, y in zip(loops[a], loops[b])]
    faster = sum(r > 1 for r in ratios)
    chance = min(1.0, 2 * stats.binom.sf(max(faster, len(ratios) - faster) - 1, len(ratios), 0.5))
    reading = ("a gap" if chance < 0.05 else
               "no gap established at this noise")
    return (f"Sign test: `{b}` is faster than `{a}` in {faster} of {len(ratios)} rounds; a count this lopsided "
            f"comes by chance with probability {chance:.2g} (two-sided) if neither is faster: {reading}.\n\n")


def read_rounds(lo, hi, above, below):
    """What per-round ratios spanning lo..hi say: `above` when every round is above 1, `below` when
    every one is below, else that the rounds disagree."""
    return above if lo > 1 else below if hi < 1 else "the rounds disagree: no difference measurable at this noise"


def verdict(table, rows):
    """The fastest two-rank variant, and ours against stock on the same scene and settings."""
    two = [r for r in table if r["ranks"] == 2 and not r["variant"].startswith("stock") and r["variant"] not in AT_ONCE]
    best = max(two, key=lambda r: r["psps"])
    efficiency = f" (parallel efficiency {best['efficiency']:.2f})" if best["efficiency"] == best["efficiency"] else ""
    text = (f"Fastest of ours by median rate: {best['variant']}, {best['psps']:.3g} particle-steps/s on 2 ranks{efficiency} (the per-round ratios below say whether a gap is measurable). cylinder and the skins were measured alone on top of `balance`, fast "
            f"combines them; runs of {int(rows[0]['steps'])} steps (the drum study's segment logs give the "
            "long-window rate).\n")
    loops = {n: [r["loop_s"] for r in rows if r["variant"] == n] for n in {r["variant"] for r in rows}}
    for ours, stock in (("balance", "stock"), ("fast", "stock fast")):
        if loops.get(ours) and loops.get(stock):
            text += (f"Ours (`{ours}`) against stock `hooke/stiffness` given the same constants, same scene and "
                     f"settings (`{stock}`): loop-time ratio ours / stock "
                     f"{harness.median_ratio(loops[ours], loops[stock]):.3f} (median over rounds).\n")
    at_once = {n: [r["particle_steps_per_s"] for r in rows if r["variant"] == n] for n in ("fast", "2 at once")}
    if all(at_once.values()):
        ratios = [a / b for a, b in zip(at_once["2 at once"], at_once["fast"])]
        lo, hi = harness.spread(ratios)
        reading = read_rounds(lo, hi, "two at once pay in every round", "one after the other on 2 ranks pays in every round")
        text += ("Two runs at once, one rank each (`2 at once`), against one after the other on 2 ranks (`fast`): "
                 f"throughput ratio {harness.median(ratios):.3f} (median over rounds; per round {lo:.2f}–{hi:.2f}): "
                 f"{reading}.\n")
    if loops.get("fast") and loops.get("1 rank fast"):
        per_round = [one / (2 * two) for one, two in zip(loops["1 rank fast"], loops["fast"])]
        lo, hi = harness.spread(per_round)
        text += (f"Parallel efficiency of `fast`, t(1 rank fast) / (2 t(fast)): median {harness.median(per_round):.2f} "
                 f"over {len(per_round)} rounds, per round {lo:.2f}–{hi:.2f}"
                 f"{'; every round below 0.95' if hi < 0.95 else '; every round at 0.95 or above' if lo >= 0.95 else ''}.\n")
    for name in ("fast 0.2", "fast 0.1", "fast 0.05", "sort 100", "sort 25"):
        if loops.get("fast") and loops.get(name):
            ratios = [a / b for a, b in zip(loops["fast"], loops[name])]
            lo, hi = harness.spread(ratios)
            reading = read_rounds(lo, hi, "faster in every round", "slower in every round")
            text += (f"`{name}` against `fast`: speed-up t(fast) / t({name}) {harness.median(ratios):.3f} (median "
                     f"over rounds; per round {lo:.2f}–{hi:.2f}): {reading}.\n")
    return text + "\n"


if __name__ == "__main__":
    run(parser().parse_args())
