#!/usr/bin/python3
"""Many simultaneous contacts with exactRestitution: the dense column (inputs/column.in, beads
dropped onto a floor, Table 3.1's en) at each --ratios tc/dt with nominal and with exact
coefficients, against the finest timestep with nominal coefficients (the reference): the kinetic
energy over time, the time the column needs to come to rest and its final height.
Writes OUT/multicontact.csv (one row per run), OUT/multicontact_<run>.csv (the series) and
OUT/multicontact.json.

Needs: python3-matplotlib (tools/harness), mpirun; liggghts."""

import shutil
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
import harness  # noqa: E402
import common  # noqa: E402

REST_KE_J = 1e-6  # at rest: kinetic energy below this for good


def parser():
    p = harness.options(__doc__, out=common.RESULTS)
    p.add_argument("--ratios", default="10,20", help="tc/dt, nominal and exact (default: 10,20)")
    p.add_argument("--reference", type=float, default=100, help="tc/dt of the reference, nominal (default: 100)")
    p.add_argument("--time", type=float, default=0.3, help="simulated s (default: 0.3)")
    return p


def runs(ratios, reference):
    """[(tag, tc/dt, exactRestitution)] in the table's order, the reference last."""
    return [(f"{mode}_{r:g}", r, exact) for r in ratios for mode, exact in (("nominal", "off"), ("exact", "on"))] \
        + [(f"reference_{reference:g}", reference, "off")]


def summary(series):
    """(peak kinetic energy, time to rest, final centre height) of a column series (rows with time, ke,
    rke, zc): rest = the start of the final stretch below REST_KE_J (the last time if it never gets there)."""
    ke = [r["ke"] + r["rke"] for r in series]
    rest = series[-1]["time"]
    for r, k in zip(reversed(series), reversed(ke)):
        if k >= REST_KE_J:
            break
        rest = r["time"]
    return max(ke), rest, series[-1]["zc"]


def run(args):
    out = Path(args.out)
    table = []
    for tag, ratio, exact in runs(common.numbers(args.ratios), args.reference):
        harness.say("multicontact", f"{tag} (dt = tc/{ratio:g}, exactRestitution {exact}) ...")
        harness.liggghts("inputs/column.in", {"dt": f"{common.dt_of(ratio):.6g}", "exact": exact, "time": args.time,
                                              "name": f"multicontact/{tag}"}, log=harness.post(f"multicontact/{tag}.log"))
        out.mkdir(parents=True, exist_ok=True)
        shutil.copy(harness.post(f"multicontact/{tag}_series.csv"), out / f"multicontact_{tag}.csv")
        table.append((tag, summary(harness.read_csv(out / f"multicontact_{tag}.csv"))))
    rp, rt, rz = table[-1][1]
    harness.write_csv(out / "multicontact.csv", [
        {"run": tag, "peak_kinetic_energy_J": p, "time_to_rest_s": t, "final_centre_height_m": z,
         "peak_vs_reference": p / rp - 1, "rest_time_vs_reference_s": t - rt, "height_vs_reference_m": z - rz}
        for tag, (p, t, z) in table])
    harness.write_json(out / "multicontact.json", {"ratios": args.ratios, "reference": args.reference,
                                                    "time_s": args.time, "rest_ke_J": REST_KE_J,
                                                    "beads": int(harness.read_csv(out / f"multicontact_{table[-1][0]}.csv")[-1]["beads"]),
                                                    "date": common.today()})


def chart(res, rows, path):
    fig, (ax,) = harness.figure(size=(9, 5.4), title=None)
    for r in rows:
        s = res.csv(f"multicontact_{r['run']}.csv")
        ref, fine = r["run"].startswith("reference"), r["run"].endswith("_10")
        label = f"tc/{r['run'].split('_')[1]} " + ("nominal (reference)" if ref else
                                                   "exactRestitution" if r["run"].startswith("exact") else "nominal")
        ax.plot([x["time"] for x in s], [x["ke"] + x["rke"] for x in s], label=label,
                color="black" if ref else None, lw=3 if ref else 2 if fine else 1, ls="-" if ref or fine else "--",
                zorder=1 if ref else 2)
    ax.set(yscale="log", xlabel="time [s]", ylabel="kinetic energy [J]",
           title="dense column: kinetic energy (translation + rotation)")
    ax.legend()
    harness.save(fig, path)


@common.section_of("multicontact", "multicontact")
def section(res, m, rows):
    chart(res, rows, res.path("multicontact.png"))
    ratios = " and ".join(f"tc/{r:g}" for r in common.numbers(m["ratios"]))
    return (
        f"The dense column (`inputs/column.in`, {m['beads']} beads dropped onto a floor, en = "
        f"{harness.materials()['bead_en']:g}) at {ratios},\n"
        f"nominal and exact coefficients, against tc/{m['reference']:g} nominal: peak kinetic energy, the time to come "
        "to rest\n"
        f"(kinetic energy below {common.sci(m['rest_ke_J'])} J for good) and the final centre-of-mass height.\n\n"
        + res.image("column", "multicontact.png") + "\n"
        + harness.markdown(rows, [
            ("run", "run", None), ("peak kinetic energy [J]", "peak_kinetic_energy_J", "{:.6g}"),
            ("time to rest [s]", "time_to_rest_s", "{:.4f}"), ("final centre height [m]", "final_centre_height_m", "{:.6f}"),
            ("peak vs reference", "peak_vs_reference", "{:+.4f}"),
            ("rest time vs reference [s]", "rest_time_vs_reference_s", "{:+.4f}"),
            ("height vs reference [m]", "height_vs_reference_m", "{:+.6f}")])
        + "\n" + common.sh(common.command("multicontact.py")))


if __name__ == "__main__":
    run(parser().parse_args())
