#!/usr/bin/python3
"""exactCollision's friction over the whole parameter range: random wall collisions (en 0.05-0.98,
et 0.1-0.98 or et = en in a third, mu 0.05-1e6, vt/vn 0.02-6, tc/dt 4.2-40, limitForce off and on;
log-uniform where the range spans decades), stepped by the physics core at random start phases,
against the continuous law with its instantaneous Coulomb cap: without limitForce the independent
reference tools/collide/continuous_law (written from the equations, nothing of contact_models/),
with it exactCollision's own cut law solved by collide::cappedLawExit (every event found by a scan
of the whole contact and bisection); and whether any phase left the wall faster than it came.
Runs build/benchmarks/friction_sweep (about 6 minutes). Writes OUT/friction_sweep.csv (per case:
its worst phase, in units of vt) and OUT/friction_sweep.json. Needs python3-matplotlib."""

import math
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
import harness  # noqa: E402
import common  # noqa: E402

LEVELS = (1e-9, 1e-6, 1e-3)


def parser():
    p = harness.options(__doc__, out=common.RESULTS)
    common.program_option(p, "friction_sweep", "the sweep program")
    p.add_argument("--cases", type=int, default=20000, help="random cases (default: %(default)s)")
    p.add_argument("--phases", type=int, default=64, help="random start phases per case (default: %(default)s)")
    p.add_argument("--seed", type=int, default=1, help="seed of the cases (default: %(default)s)")
    return p


def run(args):
    common.require_program(args.binary, "-DBUILD_BENCHMARKS=ON -DBUILD_TOOLS=ON")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    harness.say("friction_sweep", f"{args.cases} cases x {args.phases} phases ...")
    with open(out / "friction_sweep.csv", "w") as csv_out:
        subprocess.run([str(args.binary), "--cases", str(args.cases), "--phases", str(args.phases),
                        "--seed", str(args.seed)], stdout=csv_out, check=True)
    harness.write_json(out / "friction_sweep.json", {"cases": args.cases, "phases": args.phases, "seed": args.seed,
                                                     "date": common.today()})


def chart(rows, path):
    fig, (ax,) = harness.figure(title="exactCollision's friction: worst start phase of each random case")
    for lf, color in ((0, "C0"), (1, "C3")):
        rs = [r for r in rows if int(r["limitForce"]) == lf and not math.isnan(r["worst_err"])]
        ax.scatter([r["tc_over_dt"] for r in rs], [max(r["worst_err"], 1e-17) for r in rs], s=2, color=color,
                   alpha=0.4, label=f"limitForce {'on' if lf else 'off'}")
    ax.axhline(1e-6, color="grey", lw=0.8)
    ax.set(xscale="log", yscale="log", xlabel="tc / dt", ylabel="worst |vt_exit - law| / vt", ylim=(1e-17, 1))
    ax.legend(fontsize=8, markerscale=4)
    harness.save(fig, path)


@common.section_of("friction_sweep", "friction_sweep")
def section(res, m, rows):
    chart(rows, res.path("friction_sweep.png"))
    unsolved = [r for r in rows if math.isnan(r["worst_err"])]
    solved = [r for r in rows if not math.isnan(r["worst_err"])]
    worst = max(solved, key=lambda r: r["worst_err"])
    counts = ", ".join(f"{sum(r['worst_err'] > level for r in solved)} beyond {level:g}" for level in LEVELS)
    return (
        f"Friction over the whole range: {len(rows)} random wall collisions (en 0.05–0.98, et 0.1–0.98 or et = en, "
        "mu 0.05–1e6,\nvt/vn 0.02–6, tc/dt 4.2–40, limitForce off and on) at "
        f"{m['phases']} random start phases each, the contact point's exit rate against the\ncontinuous law "
        "(limitForce off: the independent `tools/collide/continuous_law`; on: the cut law by\n"
        "`collide::cappedLawExit`), in units of vt. Phases that left faster than they came: "
        f"{sum(int(r.get('gains', 0)) for r in rows)}. Cases with their worst phase\n"
        f"{counts}; the worst {worst['worst_err']:.1e} (en {worst['en']:.3g}, et {worst['et']:.3g}, "
        f"mu {worst['mu']:.3g}, vt/vn {worst['vt_over_vn']:.3g}, tc/dt {worst['tc_over_dt']:.3g}, "
        f"limitForce {'on' if worst['limitForce'] else 'off'}).\n"
        + (f"The exact solution did not finish for {len(unsolved)} case(s), stick and slide alternating without end "
           "(over 1,000 events): "
           + "; ".join(f"en {r['en']:.3g}, et {r['et']:.3g}, mu {r['mu']:.3g}, vt/vn {r['vt_over_vn']:.3g}, "
                       f"tc/dt {r['tc_over_dt']:.3g}, limitForce {'on' if r['limitForce'] else 'off'}"
                       for r in unsolved) + ".\n" if unsolved else "")
        + "The grey line is 1e-6, the tests' tolerance.\n\n"
        + res.image("friction sweep", "friction_sweep.png") + "\n"
        + common.sh(common.command("friction_sweep.py", cases=m["cases"] if m["cases"] != 20000 else None,
                                   phases=m["phases"] if m["phases"] != 64 else None,
                                   seed=m["seed"] if m["seed"] != 1 else None)))


if __name__ == "__main__":
    run(parser().parse_args())
