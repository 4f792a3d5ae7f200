#!/usr/bin/python3
"""One wall collision with friction under each exactness mode (nominal, exactRestitution,
exactCollision; tangential pournin) in LIGGGHTS against dt/tc: the worst of 64 random start
phases and their mean, each against the same mode at tc/2000 (its own law, LIGGGHTS' lever arm
included). Table 3.1's beads (en 0.56, et 0.46) sticking at first on a flat wall (vn 0.2 m/s,
vt/vn 0.2), mu 0.5, 5 and 1e6. Runs build/benchmarks/exact_modes (about 3 minutes).
Writes OUT/exact_modes.csv and OUT/exact_modes.json. Needs python3-matplotlib."""

import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
import harness  # noqa: E402
import common  # noqa: E402

MODES = ("nominal", "exactRestitution", "exactCollision")
MUS = (0.5, 5.0, 1e6)


def parser():
    p = harness.options(__doc__, out=common.RESULTS)
    common.program_option(p, "exact_modes", "the collision program")
    p.add_argument("--phases", type=int, default=64, help="random start phases per run (default: %(default)s)")
    return p


def run(args):
    common.require_program(args.binary, "-DBUILD_BENCHMARKS=ON -DBUILD_TOOLS=ON")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    harness.say("exact_modes", f"3 modes x 3 frictions x 8 steps, {args.phases} phases each ...")
    with open(out / "exact_modes.csv", "w") as csv_out:
        subprocess.run([str(args.binary), "--liggghts", str(harness.tool_path("liggghts")), "--phases",
                        str(args.phases), "--workdir", str(harness.post("exact_modes"))], stdout=csv_out, check=True)
    harness.write_json(out / "exact_modes.json", {"phases": args.phases, "date": common.today()})


def chart(rows, path):
    fig, axes = harness.figure(1, 3, size=(4.2, 4), title="one wall collision with friction: error against the same "
                                                          "mode at tc/2000 (Table 3.1's beads)")
    for ax, mu in zip(axes, MUS):
        for mode, color in zip(MODES, ("C3", "C0", "C2")):
            rs = [r for r in rows if r["mode"] == mode and r["mu"] == mu]
            x = [r["tc_over_dt"] for r in rs]
            worst = [max(r["worst_en_err"], r["worst_et_err"], 1e-12) for r in rs]
            mean = [max(r["mean_en_err"], r["mean_et_err"], 1e-12) for r in rs]
            ax.plot(x, worst, color=color, marker="o", ms=3, label=f"{mode}, worst phase")
            ax.plot(x, mean, color=color, marker="s", ms=3, ls=":", label=f"{mode}, mean")
        ax.axhline(5e-3, color="grey", lw=0.8)
        ax.set(xscale="log", yscale="log", xlabel="tc / dt", ylabel="relative error of en or et", ylim=(1e-12, 1),
               title=f"mu {mu:g}")
    axes[0].legend(fontsize=6)
    harness.save(fig, path)


@common.section_of("exact_modes", "exact_modes")
def section(res, m, rows):
    chart(rows, res.path("exact_modes.png"))
    table = []
    for mu in MUS:
        for ratio in (5, 10):
            row = {"mu": f"{mu:g}", "tc/dt": ratio}
            for mode in MODES:
                r = [x for x in rows if x["mode"] == mode and x["mu"] == mu and x["tc_over_dt"] == ratio]
                row[mode] = (f"{100 * max(r[0]['worst_en_err'], r[0]['worst_et_err']):.2g} % / "
                             f"{100 * max(r[0]['mean_en_err'], r[0]['mean_et_err']):.2g} %" if r else "refused")
            table.append(row)
    return (
        f"One wall collision with friction, each mode against itself at tc/2000: worst of {m['phases']} random\n"
        "start phases / their mean, the larger of en's and et's relative error (Table 3.1's beads, vn 0.2 m/s,\n"
        "vt/vn 0.2). The grey line is 0.5 %.\n\n" + res.image("exactness modes", "exact_modes.png") + "\n"
        + harness.markdown(table, [("mu", "mu", None), ("tc/dt", "tc/dt", "{:d}")]
                           + [(f"{mode} worst / mean", mode, None) for mode in MODES])
        + "\n" + common.sh(common.command("exact_modes.py", phases=m["phases"] if m["phases"] != 64 else None)))


if __name__ == "__main__":
    run(parser().parse_args())
