#!/usr/bin/python3
"""LIGGGHTS with this model against YADE (Debian's yade: ViscElMat + Law2_ScGeom_ViscElPhys_Basic,
the thesis' own law) on the same drum state: the settled 12 mm slab of reductions.py (YADE's
periodic collider needs a period above two bead diameters), same dt, same steps, rotating drum
mesh and YADE's mixing rules on both sides (`-var wall moving -var conventions yade`). 1 core
(1 MPI rank, yade -j1) and 2 cores (2 ranks, yade -j2), interleaved L Y L Y ... over --rounds;
each side times its own stepping loop only (LIGGGHTS' loop time, YADE's O.run after 20 warm-up
steps). One YADE process per core count serves all rounds (its first step costs minutes, see
yade/drum_yade.py); before each timed round it runs the LIGGGHTS side (yade/liggghts_round.py).
Needs yade and pvpython (Debian: apt-get install yade paraview) besides python3-matplotlib (tools/harness)
and liggghts.
Writes OUT/peers.csv (one row per core count and round) and OUT/peers.json."""

import re
import shutil
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
import harness  # noqa: E402
import common  # noqa: E402

HERE = Path(__file__).resolve().parent
YADE_ROUND = re.compile(r"^yade: round (\d+), (\d+) beads, .* s, (\S+) particle-steps/s, (\d+) outside the drum", re.M)


def parser():
    p = harness.options(__doc__, out=common.RESULTS, rounds=5)
    p.add_argument("--state", default="post/reduce/drum_L12", help="prefix of the settled state (default: post/reduce/drum_L12)")
    p.add_argument("--period", type=float, default=0.012, help="its axial period [m] (default: 0.012)")
    p.add_argument("--steps", type=int, default=200, help="steps per round (default: 200)")
    p.add_argument("--cores", default="1,2", help="core counts (default: 1,2)")
    return p


def need(*programs):
    missing = [p for p in programs if not shutil.which(p)]
    if missing:
        raise SystemExit(f"needs {', '.join(missing)} (Debian: apt-get install yade paraview)")


def yade_rounds(output):
    """YADE's per-round lines: [(round, beads, particle-steps/s, beads outside the drum)]."""
    return [(int(r), int(n), float(p), int(lost)) for r, n, p, lost in YADE_ROUND.findall(output)]


def run(args):
    need("yade", "pvpython")
    state = harness.REPO / args.state
    if not Path(f"{state}.restart").exists():
        raise SystemExit(f"peers: {args.state}.restart missing (run benchmarks/reductions.py first)")
    beads_csv = harness.post("peers/beads.csv")
    # the restart and the last snapshot hold the same state (drum.in dumps at its end)
    harness.tool("pvpython", HERE / "yade/vtp_to_csv.py", harness.last_snapshot(state), beads_csv)
    dt = common.dt_of(10)
    time = f"{args.steps * dt:.10g}"
    rows = []
    for c in (int(x) for x in common.numbers(args.cores)):
        harness.say("peers", f"{c} core(s), {args.rounds} interleaved rounds (YADE's first step takes minutes) ...")
        name = f"peers/liggghts_np{c}"
        before = f"{HERE / 'yade/liggghts_round.py'} {args.state} {time} {args.period:g} {dt:g} {c} {name}"
        output = harness.tool("yade", "-n", "-x", f"-j{c}", HERE / "yade/drum_yade.py", beads_csv, f"period={args.period:g}",
                              f"steps={args.steps}", f"rpm={common.RPM}", f"dt={dt:g}", f"rounds={args.rounds}",
                              f"before={before}")
        harness.post(f"peers/yade_j{c}.log").write_text(output)
        yade = yade_rounds(output)
        if len(yade) != args.rounds or any(lost for *_, lost in yade):
            raise harness.RunFailed(f"peers: YADE rounds incomplete or beads lost (post/peers/yade_j{c}.log)")
        for r, _, yade_psps, _ in yade:
            ours = harness.Log(harness.post(f"{name}_r{r}.log")).particle_steps_per_s
            rows.append({"cores": c, "round": r, "liggghts_psps": ours, "yade_psps": yade_psps, "ratio": ours / yade_psps})
    harness.write_csv(Path(args.out) / "peers.csv", rows)
    version = re.search(r"^Version: (\S+)", harness.tool("dpkg", "-s", "yade", check=False), re.M)
    harness.write_json(Path(args.out) / "peers.json", {
        "beads": yade[0][1], "steps": args.steps, "dt": dt, "runs": args.rounds, "state": args.state,
        "yade_version": version.group(1) if version else "?", "date": common.today()})


@common.section_of("peers", "peers")
def section(res, m, rows):
    cores = sorted({int(r["cores"]) for r in rows})
    ratio = {c: harness.median([r["ratio"] for r in rows if r["cores"] == c]) for c in cores}
    return (
        f"The settled 12 mm slab of section 6 ({m['beads']} beads, {common.RPM} rpm), the same state loaded into YADE "
        f"{m['yade_version']}\n"
        "(ViscElMat, Law2_ScGeom_ViscElPhys_Basic, the drum as 1080 facets; YADE's periodic collider needs a period\n"
        "above two bead diameters, so not the 6 mm slab) and continued by LIGGGHTS with `model viscoelastic`;\n"
        "both rotate the drum mesh and use YADE's mixing rules (`-var wall moving -var conventions yade`),\n"
        f"dt = {common.sci(m['dt'])} s, {m['steps']} steps per round, {m['runs']} rounds, each LIGGGHTS run followed by a "
        f"YADE round, {m['date']}.\n"
        "1 core: 1 MPI rank / `yade -j1`; 2 cores: 2 MPI ranks / `yade -j2` (OpenMP). Each side's stepping loop only.\n\n"
        + harness.markdown(rows, [("cores", "cores", "{:.0f}"), ("round", "round", "{:.0f}"),
                                  ("LIGGGHTS particle-steps/s", "liggghts_psps", "{:.3g}"),
                                  ("YADE particle-steps/s", "yade_psps", "{:.3g}"), ("ratio", "ratio", "{:.2f}")])
        + "\n**LIGGGHTS with this model runs "
        + " and ".join(f"{ratio[c]:.1f}× YADE's particle-steps per second on {c} core" if i == 0 else f"{ratio[c]:.1f}× on {c}"
                       for i, c in enumerate(cores)) + "**\n"
        "(medians of the per-round ratios). YADE as a user gets it: default collider settings (Verlet\n"
        "distance half the smallest radius), whose potential interactions outnumber real contacts about 9:1.\n\n"
        + common.sh(common.command("peers.py", steps=m["steps"], rounds=m["runs"])))


if __name__ == "__main__":
    run(parser().parse_args())
