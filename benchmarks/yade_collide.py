#!/usr/bin/python3
"""YADE against this model on the same head-on collisions of two glass beads (Table 3.1: en 0.56,
tc 1e-4 s, 1 m/s, --phases contact-start phases each): YADE (yade/collide_yade.py) clips the
normal force at zero (no attraction), as `limitForce on` does; `collide sweep-dt` with limitForce
on, off, and on with exactRestitution.
Needs yade (Debian package) besides collide and python3-matplotlib (tools/harness).
Writes OUT/yade_collide.csv (one row per tc/dt) and OUT/yade_collide.json."""

import math
import shutil
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
import harness  # noqa: E402
import common  # noqa: E402

HERE = Path(__file__).resolve().parent
# ours: (column of yade_collide.csv, collide sweep-dt options)
OURS = (("ours_limitForce_on", ["--limit-force", "on"]), ("ours_limitForce_off", ["--limit-force", "off"]),
        ("ours_limitForce_on_exact", ["--limit-force", "on", "--exact-restitution", "on"]))


def parser():
    p = harness.options(__doc__, out=common.RESULTS)
    p.add_argument("--ratios", default="5,10,20,40,81", help="tc/dt (default: 5,10,20,40,81)")
    p.add_argument("--phases", type=int, default=128, help="contact-start phases (default: 128)")
    return p


def run(args):
    if not shutil.which("yade"):
        raise SystemExit("yade_collide: needs yade (Debian: apt-get install yade)")
    m = harness.materials()
    yade_csv = harness.post("yade_collide/yade.csv")
    harness.post("yade_collide/yade.log").write_text(harness.tool(
        "yade", "-n", "-x", HERE / "yade/collide_yade.py", yade_csv, f"ratios={args.ratios}", f"phases={args.phases}"))
    ours = {}
    for column, options in OURS:
        path = harness.post(f"yade_collide/{column}.csv")
        harness.tool("collide", "sweep-dt", "--geometry", "pair", "--en", m["bead_en"], "--et", m["bead_et"], "--vn", 1,
                     "--ratios", *common.numbers(args.ratios), "--phases", args.phases, *options, "--csv", path)
        ours[column] = {r["tc_over_dt"]: r for r in harness.read_csv(path)}
    rows = [{"tc_over_dt": y["tc_over_dt"], "yade_restitution": y["restitution_mean"], "yade_min": y["restitution_min"],
             "yade_max": y["restitution_max"], **{c: ours[c][y["tc_over_dt"]]["restitution"] for c, _ in OURS},
             "yade_duration_steps": y["duration_steps_mean"],
             "ours_limitForce_on_duration_err_steps": ours["ours_limitForce_on"][y["tc_over_dt"]]["duration_err_steps"]}
            for y in harness.read_csv(yade_csv)]
    harness.write_csv(Path(args.out) / "yade_collide.csv", rows)
    harness.write_json(Path(args.out) / "yade_collide.json", {"phases": args.phases, "en": m["bead_en"],
                                                               "tc_s": m["bead_tc"], "vn_mps": 1, "date": common.today()})


def chart(rows, m, path):
    fig, (ax,) = harness.figure(size=(8.2, 5.1))
    x = [r["tc_over_dt"] for r in rows]
    ax.axhline(m["en"], color="black", ls="--", label="requested en")
    ax.errorbar(x, [r["yade_restitution"] for r in rows],
                yerr=[[r["yade_restitution"] - r["yade_min"] for r in rows], [r["yade_max"] - r["yade_restitution"] for r in rows]],
                fmt="o-", capsize=3, label="YADE (bars: min-max over phases)")
    for (column, _), marker, label in zip(OURS, "s^D", ("limitForce on", "limitForce off", "limitForce on, exactRestitution on")):
        ax.plot(x, [r[column] for r in rows], marker + "-", label=f"viscoelastic, {label}")
    ax.set(xscale="log", xlabel="tc / dt", ylabel=f"normal restitution, head-on pair (mean of {m['phases']} start phases)",
           title=f"YADE ViscElMat against viscoelastic (requested en = {m['en']:g})")
    ax.legend(fontsize=8)
    harness.save(fig, path)


@common.section_of("yade_collide", "yade_collide")
def section(res, m, rows):
    chart(rows, m, res.path("yade_collide.png"))
    clipped = [r[k] for r in rows for k in ("yade_restitution", "ours_limitForce_on")]
    above = [100 * (e / m["en"] - 1) for e in clipped]
    return (
        f"Head-on collisions of two Table 3.1 glass beads (en = {m['en']:g}, tc = {common.sci(m['tc_s'])} s, "
        f"{m['vn_mps']:g} m/s), {m['phases']} contact-start\n"
        "phases per dt, in YADE (`benchmarks/yade/collide_yade.py`) and with this model (`collide`).\n"
        f"YADE clips the normal force at zero, as `limitForce on` does: both end near {min(clipped):.2f}, "
        f"{math.floor(min(above))}-{math.ceil(max(above))} % above\n"
        "the requested en, at every dt (Schwager & Pöschel's no-attraction shift, not a discretisation error).\n\n"
        + res.image("YADE collisions", "yade_collide.png") + "\n"
        + harness.markdown(rows, [
            ("tc/dt", "tc_over_dt", "{:g}"), ("YADE", "yade_restitution", "{:.4f}"),
            ("viscoelastic, limitForce on", "ours_limitForce_on", "{:.4f}"),
            ("on − YADE", lambda r: r["ours_limitForce_on"] - r["yade_restitution"], "{:+.4f}"),
            ("limitForce off", "ours_limitForce_off", "{:.4f}"),
            ("limitForce on, exactRestitution on", "ours_limitForce_on_exact", "{:.4f}")])
        + "\n" + common.sh(common.command("yade_collide.py")))


if __name__ == "__main__":
    run(parser().parse_args())
