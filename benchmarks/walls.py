#!/usr/bin/python3
"""Drum wall: how should it be driven, and how fine must its mesh be? ("Model no more than a
scene needs".) From one settled state (--restart), runs
  surface/180  static mesh with a surface velocity, 180 facets (the benchmarks' drum, MESH in common.py)
  moving/180   the mesh itself rotated (fix move/mesh)
  surface/90, surface/360   coarser and finer meshes
interleaved over --rounds; cost: loop time, median, and its ratio to surface/180 per round
(median); metrics: time averages over round 1's run (`drum_metrics series --average all`).
Writes OUT/walls.csv (one row per variant) and OUT/walls.json.

Needs: python3-matplotlib (tools/harness), mpirun; liggghts, drum_metrics."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
import harness  # noqa: E402
import common  # noqa: E402

VARIANTS = (("surface", 180), ("moving", 180), ("surface", 90), ("surface", 360))
KEYS = ("Hh_m", "Hh_se_m", "Hd_m", "Hd_se_m", "Hc_m", "Hc_se_m", "angle_deg", "angle_se_deg")


def parser():
    p = harness.options(__doc__, np=2, out=common.RESULTS, rounds=2, restart=None)
    p.add_argument("--time", type=float, default=0.4, help="simulated s per run (default: 0.4)")
    p.add_argument("--period", type=float, default=0.006, help="axial period [m] (default: 0.006)")
    p.add_argument("--snapshot-dt", type=float, default=0.02, help="s between snapshots (default: 0.02)")
    return p


def run(args):
    dt = common.dt_of(10)

    def drum(wall, segments):
        tag = f"walls/{wall}_{segments}"
        common.remove_snapshots(harness.post(tag))
        return harness.drum(harness.post(tag + ".log"), np=args.np, **common.then(
            period=args.period, rpm=common.RPM, dt=dt, time=args.time, dumpdt=args.snapshot_dt, start="restart",
            restart=args.restart, wall=wall, segments=segments, name=tag))

    averages = {}

    def variant(wall, segments):
        def once():
            log = drum(wall, segments)
            if (wall, segments) not in averages:  # round 1: the rounds are identical runs
                averages[wall, segments] = common.window_average(harness.post(f"walls/{wall}_{segments}"), dt)
            return log.loop_time
        return once

    loops = harness.interleaved({f"{w}/{n}": variant(w, n) for w, n in VARIANTS}, args.rounds,
                                progress=lambda s: harness.say("walls", s))
    rows = [{"wall": w, "segments": n, "loop_s_median": harness.median(loops[f"{w}/{n}"]),
             "cost_ratio": harness.median_ratio(loops[f"{w}/{n}"], loops["surface/180"]),
             **{k: averages[w, n][k] for k in KEYS}} for w, n in VARIANTS]
    harness.write_csv(Path(args.out) / "walls.csv", rows)
    harness.write_json(Path(args.out) / "walls.json", {"restart": str(args.restart), "time_s": args.time,
                                                        "rounds": args.rounds, "ranks": args.np, "period_m": args.period,
                                                        "snapshot_dt_s": args.snapshot_dt,
                                                        "date": common.today()})


def section(res):
    """The paragraph closing section 6: what the default wall is, and why."""
    if not res.has("walls.csv", "walls.json"):
        return "Drum wall: " + common.not_run("walls")
    m = res.json("walls.json")
    v = {(r["wall"], int(r["segments"])): r for r in res.csv("walls.csv")}
    ref, moving, coarse, fine = (v[k] for k in VARIANTS)
    mm = lambda a, b: 1e3 * abs(a["Hc_m"] - b["Hc_m"])  # noqa: E731
    return (
        "Drum wall (docs/drum/README.md, `benchmarks/walls.py`): a static mesh with a surface velocity\n"
        f"gives the metrics of a rotating mesh (Hc within {mm(ref, moving):.1f} mm, angle within "
        f"{abs(ref['angle_deg'] - moving['angle_deg']):.1f}°) at {1 / moving['cost_ratio']:.2f}× its cost, and "
        f"{ref['segments']:.0f}\n"
        f"facets match {fine['segments']:.0f} (Hc within {mm(ref, fine):.2f} mm) where {coarse['segments']:.0f} move Hc "
        f"by {mm(ref, coarse):.1f} mm: the benchmarks' drum is surface velocity, {ref['segments']:.0f} facets\n(drum.in's default is now the primitive cylinder, \"Speed of the full scene\").\n\n"
        + common.sh(common.command("walls.py", restart=m["restart"], time=m["time_s"], rounds=m["rounds"])))


if __name__ == "__main__":
    run(parser().parse_args())
