#!/usr/bin/python3
"""Cost of the model: the same settled drum slab with `model viscoelastic` and with stock
`model hooke/stiffness` given identical kn, kt, gamman, gammat (absolute damping) for every type
pair (`contact_law stock`).

  1. the forces agree: both continue from one restart for --check steps, then every bead's
     position and velocity are compared (`drum_metrics compare`);
  2. the time ratio: --rounds rounds, the models interleaved, LIGGGHTS' loop time of each;
     medians and the median of the per-round ratios.
Without --restart a slab is settled first (drum.in from the grid, 1 s at 21 rpm, ~8 min on 2 cores).
Writes OUT/model_cost.csv (one row per round) and OUT/model_cost.json.

Needs: python3-matplotlib (tools/harness), mpirun; liggghts, drum_metrics, contact_law."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
import harness  # noqa: E402
import common  # noqa: E402

MODELS = ("viscoelastic", "hooke")
SETTLE_TIME = 1.0  # s from the grid when no --restart is given
TIMESTEP_RATIO = 10  # dt = tc/10, drum.in's default when measured (common.THEN)


def parser():
    p = harness.options(__doc__, np=2, out=common.RESULTS, rounds=5)
    p.add_argument("--restart", type=Path, help="a settled drum slab (default: settle one)")
    p.add_argument("--steps", type=int, default=2000, help="steps per timed run (default: 2000)")
    p.add_argument("--check", type=int, default=200, help="steps before the force check (default: 200)")
    return p


def settle_slab():
    harness.say("cost", f"settling a slab ({SETTLE_TIME} s at {common.RPM} rpm from the grid) ...")
    harness.drum(harness.post("bench/slab.log"), **common.then(time=SETTLE_TIME, dumpdt=SETTLE_TIME, rpm=common.RPM,
                                                               name="bench/slab"))
    return harness.post("bench/slab.restart")


def run(args):
    restart = args.restart or settle_slab()
    dt = common.dt_of(TIMESTEP_RATIO)
    stock = common.stock_file(harness.post("bench/stock.in"))

    def drum(tag, model, steps, dumps):
        span = steps * dt
        return harness.drum(harness.post(f"bench/{tag}.log"), np=args.np, **common.then(
            start="restart", restart=restart, rpm=common.RPM, dt=dt, time=f"{span:.10g}",
            dumpdt=f"{span if dumps else 10 * span:.10g}", model=model, stock=stock, name=f"bench/{tag}"))

    harness.say("cost", f"force check over {args.check} steps ...")
    for model in MODELS:
        common.remove_snapshots(harness.post(f"bench/check_{model}"))
        drum(f"check_{model}", model, args.check, True)
    check = harness.tool("drum_metrics", "compare", *(harness.last_snapshot(harness.post(f"bench/check_{m}"))
                                                       for m in MODELS)).strip()
    harness.say("cost", check)

    logs = harness.interleaved({m: (lambda m=m: drum(f"time_{m}", m, args.steps, False)) for m in MODELS},
                               args.rounds, progress=lambda s: harness.say("cost", s))
    rows = [{"run": i + 1, "viscoelastic_s": v.loop_time, "hooke_s": h.loop_time, "ratio": v.loop_time / h.loop_time}
            for i, (v, h) in enumerate(zip(logs["viscoelastic"], logs["hooke"]))]
    harness.write_csv(Path(args.out) / "model_cost.csv", rows)
    harness.write_json(Path(args.out) / "model_cost.json", {
        "beads": logs["viscoelastic"][0].atoms, "steps": args.steps, "runs": args.rounds, "ranks": args.np,
        "check": check, "restart": str(restart), "date": common.today()})
    harness.say("cost", f"median ratio ours / stock {harness.median([r['ratio'] for r in rows]):.4f}")


def stock_over_ours(res):
    """Section 1's measured stock / ours time ratio (1 if not measured)."""
    if not res.has("model_cost.csv"):
        return 1.0
    rows = res.csv("model_cost.csv")
    return 1.0 / harness.median_ratio([r["viscoelastic_s"] for r in rows], [r["hooke_s"] for r in rows])


@common.section_of("model_cost", "cost")
def section(res, m, rows):
    ours, stock = [r["viscoelastic_s"] for r in rows], [r["hooke_s"] for r in rows]
    mo, ms = harness.median(ours), harness.median(stock)
    psps = lambda t: f"{m['beads'] * m['steps'] / t:.4g}"  # noqa: E731
    return (
        f"The settled drum slab (`{m['restart']}`, {m['beads']} beads, {common.RPM} rpm, dt = tc/{TIMESTEP_RATIO}, "
        f"{m['ranks']} MPI ranks) with\n"
        "`model viscoelastic tangential history` and with stock `model hooke/stiffness tangential history\n"
        "absolute_damping on` given the same kn, kt, gamman, gammat per type pair (`contact_law stock`).\n\n"
        f"Forces agree: {m['check']} (after continuing both from the restart; `drum_metrics compare`).\n\n"
        f"Time: {m['runs']} runs of {m['steps']} steps each, interleaved (ours, stock, ours, ...), LIGGGHTS loop "
        f"time, {m['date']}:\n\n"
        + harness.markdown(rows, [("run", lambda r: int(r["run"]), None), ("viscoelastic [s]", "viscoelastic_s", "{:g}"),
                                  ("hooke/stiffness [s]", "hooke_s", "{:g}"),
                                  ("ratio", lambda r: r["viscoelastic_s"] / r["hooke_s"], "{:.4f}")])
        + f"\n**Median ratio ours / stock: {harness.median_ratio(ours, stock):.4f}** (per round "
        f"{'–'.join(f'{x:.2f}' for x in harness.spread([o / t for o, t in zip(ours, stock)]))}; medians {mo:g} s and {ms:g} s;\n"
        f"{psps(mo)} and {psps(ms)} particle-steps per second).\n\n"
        + common.sh(common.command("cost.py", restart=m["restart"], steps=m["steps"], rounds=m["runs"], np=m["ranks"])))


if __name__ == "__main__":
    run(parser().parse_args())
