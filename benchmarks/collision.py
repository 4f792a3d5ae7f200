#!/usr/bin/python3
"""Single collisions: the error of one collision against dt/tc, for Pournin's coefficients
(nominal), exactRestitution (exact on average over start phases) and exactCollision (every
collision exact), worst over 256 start phases, integer and non-integer tc/dt (`contact_law
single`: the integrator's recurrence, which LIGGGHTS follows to round-off, tests/collide);
and what exactCollision costs in LIGGGHTS: the dense column (inputs/column.in, tangential
pournin; beads dropped from a lattice: collisions and lasting contacts) with exactRestitution and
with exactCollision, interleaved rounds, loop-time ratio; and, as a measure no other job on the
machine can move, the instructions each run executes (valgrind's callgrind: the whole run, the pair
force computation, LIGGGHTS' loop over neighbours with the contact model called in it, and the contact
model's own instructions per contact-step, like for like).
Writes OUT/collision.csv (errors), OUT/collision_cost.csv (rounds) and OUT/collision.json.

Needs: python3-matplotlib (tools/harness), mpirun, valgrind; liggghts, contact_law."""

import argparse
import shutil
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
import harness  # noqa: E402
import common  # noqa: E402

RATIOS = "4,4.5,5,5.5,6,7.3,8.5,10,12.5,15,20,27.5,40,60,81,100"
MODES = ("nominal", "exactRestitution", "exactCollision")


def cases():
    """(label, en, et, limitForce): Table 3.1's bead pair and bead-drum, and a strongly different pair."""
    m = harness.materials()
    pairs = [("beads", m["bead_en"], m["bead_et"]), ("bead-drum", m["drum_en"], m["drum_et"]), ("en 0.3 et 0.8", 0.3, 0.8)]
    return [(label, en, et, lf) for label, en, et in pairs for lf in (False, True)]


def parser():
    p = harness.options(__doc__, out=common.RESULTS, rounds=5)
    p.add_argument("--ratios", default=RATIOS, help="tc/dt (default: %(default)s)")
    p.add_argument("--phases", type=int, default=256, help="start phases per collision (default: %(default)s)")
    p.add_argument("--cost-time", type=float, default=0.1, help="simulated s per column run (default: %(default)s)")
    p.add_argument("--instructions", action=argparse.BooleanOptionalAction, default=True,
                   help="also count instructions under callgrind (needs valgrind; about 4 min per mode; default: on)")
    return p


def column_variables(mode, time, name):
    return {"tangential": "pournin", "exact": "on" if mode == "exactRestitution" else "off",
            "collision": "on" if mode == "exactCollision" else "off", "time": time, "name": name}


def instructions(mode, time):
    """The column run of `mode` under callgrind: instructions of the whole run and of the pair force
    computation (inclusive: the contact model runs inside it)."""
    valgrind = shutil.which("valgrind")
    if not valgrind:
        raise harness.RunFailed("--instructions needs valgrind (apt-get install valgrind), or pass --no-instructions")
    counts = harness.post(f"collision/{mode}.callgrind")
    harness.liggghts("inputs/column.in", column_variables(mode, time, f"collision/{mode}_callgrind"),
                     log=harness.post(f"collision/{mode}_callgrind.log"),
                     launcher=(valgrind, "--tool=callgrind", f"--callgrind-out-file={counts}"))
    text = subprocess.run(["callgrind_annotate", "--inclusive=yes", str(counts)], capture_output=True, text=True,
                          check=True).stdout
    number = lambda line: int(line.split()[0].replace(",", ""))  # noqa: E731
    total = next(number(line) for line in text.splitlines() if "PROGRAM TOTALS" in line)
    pair = next(number(line) for line in text.splitlines()
                if "PairStyles::Granular<" in line and "::compute_force(" in line)
    return {"total": total, "pair": pair, **model_per_contact(counts)}


def model_per_contact(counts):
    """The contact model's instructions in the pair loop and its calls there (the pair contact-steps):
    the normal and tangential models' surfacesIntersect (kept out of line for this count), inclusive,
    as called from the pair style. The two modes' runs diverge (exactCollision changes the
    dissipation) and make different numbers of contact-steps (3 % apart seen), so the pair totals
    alone do not compare like for like; per contact-step they do."""
    text = subprocess.run(["callgrind_annotate", "--tree=caller", "--inclusive=yes", str(counts)],
                          capture_output=True, text=True, check=True).stdout.splitlines()
    found = {}
    for k, line in enumerate(text):
        for model, cls in (("normal", "ContactModels::NormalModel<"), ("tangential", "ContactModels::TangentialModel<")):
            if line.lstrip(" 0123456789,().%").startswith("*  ") and cls in line and "::surfacesIntersect(" in line:
                # the caller lines above it, up to the previous blank line: the pair style's
                for above in reversed(text[max(0, k - 8):k]):
                    if not above.strip():
                        break
                    if "PairStyles::Granular<" in above:
                        calls = int(above.rsplit("(", 1)[1].split("x)")[0].replace(",", ""))
                        found[model] = (int(above.split()[0].replace(",", "")), calls)
    if set(found) != {"normal", "tangential"} or found["normal"][1] != found["tangential"][1]:
        raise harness.RunFailed(f"callgrind: the contact models' calls from the pair style not found: {found}")
    return {"model": found["normal"][0] + found["tangential"][0], "contact_steps": found["normal"][1]}


def run(args):
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for label, en, et, lf in cases():
        harness.say("collision", f"{label}, limitForce {'on' if lf else 'off'} ...")
        text = harness.tool("contact_law", "single", "--en", en, "--et", et, "--ratios", args.ratios,
                            "--phases", args.phases, *(["--limit-force"] if lf else []))
        rows += [{"pair": label, "limitForce": "on" if lf else "off", **r} for r in harness.read_csv_text(text)]
    harness.write_csv(out / "collision.csv", rows)

    # cost: the settled column is what a dense flow asks of a contact; both with tangential pournin
    variants = {mode: (lambda mode=mode: harness.liggghts(
        "inputs/column.in", column_variables(mode, args.cost_time, f"collision/{mode}"),
        log=harness.post(f"collision/{mode}.log")).loop_time) for mode in ("exactRestitution", "exactCollision")}
    times = harness.interleaved(variants, args.rounds, progress=lambda text: harness.say("collision", text))
    rounds = [{"round": k + 1, **{mode: times[mode][k] for mode in times}} for k in range(args.rounds)]
    harness.write_csv(out / "collision_cost.csv", rounds)
    counts = None
    if args.instructions:
        counts = {}
        for mode in ("exactRestitution", "exactCollision"):
            harness.say("collision", f"{mode} under callgrind ...")
            counts[mode] = instructions(mode, args.cost_time)
    harness.write_json(out / "collision.json", {
        "ratios": args.ratios, "phases": args.phases, "cost_time_s": args.cost_time, "rounds": args.rounds,
        "ratio": harness.median_ratio([r["exactCollision"] for r in rounds], [r["exactRestitution"] for r in rounds]),
        "instructions": counts,
        "date": common.today()})


def chart(rows, path):
    fig, axes = harness.figure(2, 3, size=(5, 4.2), title="single collisions: worst relative error over start phases")
    for i, (label, _, _, lf) in enumerate(cases()):
        ax = axes[(i % 2) * 3 + i // 2]  # pairs across, limitForce off / on down
        for mode, color, marker in zip(MODES, ("C3", "C0", "C2"), ("o", "s", "^")):
            rs = [r for r in rows if r["pair"] == label and r["limitForce"] == ("on" if lf else "off") and r["mode"] == mode]
            for key, ls in (("worst_en_err", "-"), ("worst_et_err", ":")):
                ys = [max(r[key], 1e-16) for r in rs]
                ax.plot([r["tc_over_dt"] for r in rs], ys, color=color, marker=marker, ls=ls, ms=3,
                        label=f"{mode}, {'en' if key.startswith('worst_en') else 'et'}")
        ax.axhline(5e-3, color="grey", lw=0.8)
        ax.set(xscale="log", yscale="log", xlabel="tc / dt", ylabel="worst |e / e_requested - 1|",
               title=f"{label}, limitForce {'on' if lf else 'off'}", ylim=(1e-16, 2))
    axes[0].legend(fontsize=7)
    harness.save(fig, path)


def instruction_text(counts):
    if not counts:
        return ""
    r, c = counts["exactRestitution"], counts["exactCollision"]
    text = ("Instructions executed (callgrind; the same column run, once per mode: a count no other job on the "
            f"machine moves):\nwhole run {c['total'] / r['total']:.3f}, pair force computation (every contact's "
            f"step, LIGGGHTS' loop included) {c['pair'] / r['pair']:.3f} "
            f"({c['pair'] / 1e9:.2f} against {r['pair'] / 1e9:.2f} billion).\n")
    if "contact_steps" not in r or "contact_steps" not in c:
        return text
    model = {mode: counts[mode]["model"] / counts[mode]["contact_steps"] for mode in counts}
    whole = r["pair"] / r["contact_steps"]
    return text + (
        "The two runs diverge and make different numbers of pair contact-steps "
        f"({c['contact_steps'] / 1e6:.2f} against {r['contact_steps'] / 1e6:.2f} million), so per contact-step, "
        "like for like: the contact model (normal and tangential, inclusive) executes "
        f"{model['exactCollision']:.0f} instructions per contact-step under exactCollision against "
        f"{model['exactRestitution']:.0f}, on a pair computation of {whole:.0f} per contact-step under "
        f"exactRestitution (its loop over neighbours included): exactCollision's per-contact cost "
        f"**{1 + (model['exactCollision'] - model['exactRestitution']) / whole:.3f}** times exactRestitution's. "
        "That sets the rest of the pair computation (LIGGGHTS' loop over the neighbour pairs, touching or not) "
        "equal per contact-step; in total it is "
        f"{(c['pair'] - c['model']) / 1e9:.2f} against {(r['pair'] - r['model']) / 1e9:.2f} billion "
        f"({(c['pair'] - c['model']) / (r['pair'] - r['model']) - 1:+.1%}), per contact-step of each run "
        f"{(c['pair'] - c['model']) / c['contact_steps']:.0f} against {(r['pair'] - r['model']) / r['contact_steps']:.0f}; "
        "the whole pair computation per contact-step of each run, which counts that loop's work spread over each "
        f"run's own contact-steps, is {(c['pair'] / c['contact_steps']):.0f} against {whole:.0f}: "
        f"{(c['pair'] / c['contact_steps']) / whole:.3f}. The baseline is exactRestitution with the same "
        "`tangential pournin`, whose own per-step work (the cap's zero between steps, the start at first touch) "
        "both modes share.\n")


@common.section_of("collision", "collision")
def section(res, m, rows):
    chart(rows, res.path("collision.png"))
    table = []
    for label, _, _, lf in cases():
        for ratio in (5, 10):
            row = {"pair": label, "limitForce": "on" if lf else "off", "tc/dt": ratio}
            for mode in MODES:
                r = [x for x in rows if x["pair"] == label and x["limitForce"] == row["limitForce"]
                     and x["mode"] == mode and x["tc_over_dt"] == ratio]
                row[mode] = (f"{100 * r[0]['worst_en_err']:.2g} % / {100 * r[0]['worst_et_err']:.2g} %" if r
                             else "none (ERROR)")
            table.append(row)
    cost = res.csv("collision_cost.csv")
    return (
        f"One binary collision, worst relative error of en / et (sticking) over {m['phases']} start phases "
        "(the\nintegrator's recurrence, which LIGGGHTS follows to round-off; the LIGGGHTS runs of "
        "`tests/collide/test_exact_collision.cpp`\ncheck exactCollision per collision at random phases). "
        "The grey line is 0.5 %.\n\n" + res.image("single collisions", "collision.png") + "\n"
        + harness.markdown(table, [("pair", "pair", None), ("limitForce", "limitForce", None),
                                   ("tc/dt", "tc/dt", "{:d}")] + [(f"{m_} en / et", m_, None) for m_ in MODES])
        + f"\nCost in LIGGGHTS: the dense column (2009 beads dropped from a lattice onto a floor: collisions and lasting contacts), {m['rounds']} interleaved rounds of {m['cost_time_s']:g} s "
        f"(tangential pournin):\nexactCollision / exactRestitution loop time, median of the per-round ratios: "
        f"**{m['ratio']:.3f}** (per round: "
        + ", ".join(f"{r['exactCollision'] / r['exactRestitution']:.3f}" for r in cost) + ").\n"
        + instruction_text(m.get("instructions")) + "\n"
        + common.sh(common.command("collision.py", rounds=m["rounds"] if m["rounds"] != 5 else None)))


if __name__ == "__main__":
    run(parser().parse_args())
