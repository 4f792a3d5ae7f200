#!/usr/bin/python3
"""Regenerates the benchmarks: runs the named sections (default: all, in this order), their
results in --out, then writes the README from the results alone.

sections (each is also a script of its own: benchmarks/<section>.py --help; times on 2 cores):
  core          Google Benchmark of the physics core's per-contact force (build/benchmarks/bench_core)
  cost          viscoelastic vs stock hooke/stiffness on a settled drum slab
                (--restart: a settled 6 mm drum; otherwise one is settled, ~8 min)
  accuracy      dt = tc/5 ... tc/81, cost against two-body and drum errors (same slab), ~40 min
  multicontact  the dense column with exactRestitution, ~10 min
  collision     single collisions against dt/tc: nominal, exactRestitution, exactCollision; its cost, ~3 min
  friction_sweep  exactCollision's friction on 20,000 random wall collisions against the law, ~6 min
  pair_sweep    exactCollision between two spheres: 5 sets x 2 seeds x 10,000 random draws against tc/1000, ~4 min
  exact_modes   one wall collision with friction per mode against dt/tc, mu 0.5, 5, 1e6, ~3 min
  stability     dt/tc swept past failure: binary collision, dense column, drum (same slab), ~40 min
  stability_exact  the dense column under exactRestitution's and exactCollision's coefficients, ~1 h
  reductions    6 / 12 / 24 mm periods from the grid, ~1 h
  walls         the drum wall: surface velocity or rotating mesh, 90 / 180 / 360 facets (same slab)
  yade_collide  YADE on the same two-body collisions (needs yade)
  peers         YADE on the same drum state (the 12 mm state of reductions; needs yade, pvpython), ~15 min
  scaling       the full drum (the 24 mm state of reductions) on 1 and 2 ranks, ~5 min
The README goes to benchmarks/README.md when --out is benchmarks/results, else to OUT/README.md.

Needs: python3-matplotlib (tools/harness), and what each section's script names."""

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
import harness  # noqa: E402
import common  # noqa: E402
import accuracy  # noqa: E402
import collision  # noqa: E402
import exact_modes  # noqa: E402
import friction_sweep  # noqa: E402
import pair_sweep  # noqa: E402
import core  # noqa: E402
import cost  # noqa: E402
import full_scene  # noqa: E402
import multicontact  # noqa: E402
import peers  # noqa: E402
import reductions  # noqa: E402
import scaling  # noqa: E402
import stability  # noqa: E402
import stability_exact  # noqa: E402
import walls  # noqa: E402
import yade_collide  # noqa: E402


def settings(restart):
    """{section: (module, [argument lists, one per invocation])}: the settings of the committed results."""
    slab = str(restart or harness.post("bench/slab.restart"))
    return {
        "core": (core, [[]]),
        "cost": (cost, [["--steps", "2000", "--rounds", "5"] + (["--restart", str(restart)] if restart else [])]),
        "accuracy": (accuracy, [["--restart", slab]]),
        "multicontact": (multicontact, [[]]),
        "collision": (collision, [["--rounds", "15"]]),
        "friction_sweep": (friction_sweep, [[]]),
        "pair_sweep": (pair_sweep, [[]]),
        "exact_modes": (exact_modes, [[]]),
        "stability": (stability, [["--scenes", "binary,column"],
                                  ["--scenes", "drum", "--restart", slab],
                                  ["--scenes", "drum", "--restart", slab, "--drum-runs", "0.3:hooke",
                                   "--drum-fractions", "0.21,0.22,0.23,0.24", "--append"],
                                  ["--scenes", "drum", "--restart", str(harness.post("reduce/drum_L6.restart")),
                                   "--drum-runs", "0.3:hooke,table:hooke", "--drum-fractions",
                                   stability.LONG_DRUM_FRACTIONS, "--drum-time", "0.2",
                                   "--drum-name", "stability_drum_long"]]),
        "stability_exact": (stability_exact, [[]]),
        "reductions": (reductions, [[]]),
        "walls": (walls, [["--restart", slab]]),
        "yade_collide": (yade_collide, [[]]),
        "peers": (peers, [["--steps", "300", "--rounds", "5"]]),
        "full_scene": (full_scene, [["--restart", str(harness.post("settle24/L24_21rpm.restart"))],
                                    ["--restart", str(harness.post("settle24/L24_21rpm.restart")), "--time", "0.1",
                                     "--variants", "fast,stock fast,1 rank fast", "--stem", "full_scene_long"],
                                    ["--restart", "inputs/drum_L24_21rpm.restart.gz", "--time", "0.1",
                                     "--variants", "fast,stock fast,1 rank fast", "--stem", "full_scene_steady"]]),
        "scaling": (scaling, [["--restart", str(harness.post("reduce/drum_L24.restart")), "--period", "0.024",
                               "--ranks", "1,2", "--rounds", "5", "--time", "0.003"]]),
    }


# The README: (heading, the sections rendered under it)
PAGE = (("## 1. Cost of the model", [cost]),
        ("### Per-contact force of the physics core (Google Benchmark)", [core]),
        ("## 2. Peers", []),
        ("### YADE on the same drum", [peers]),
        ("### Two-body collisions: YADE and `limitForce on`", [yade_collide]),
        ("## 3. Accuracy against cost", [accuracy]),
        ("### Many simultaneous contacts with exactRestitution", [multicontact]),
        ("### Every single collision exact: exactCollision", [collision, friction_sweep, pair_sweep, exact_modes]),
        ("## 4. Stability map", [stability]),
        ("### The guard under the exact laws", [stability_exact]),
        ("## 5. Scaling: the full drum", [scaling]),
        ("### Speed of the full scene: decomposition, wall, skin, stock", [full_scene]),
        ("## 6. Scene reductions", [reductions, walls]))


def readme(res, note):
    """The whole page from a results directory (sections without results say how to run them)."""
    names = ", ".join(settings(None))
    m = res.json("machine.json") if res.has("machine.json") else None
    machine = (f"Machine: {m['cores']} cores, {m['arch']},\n{m['cpu']}; LIGGGHTS {m['liggghts']}." if m
               else "Machine: not recorded.")
    text = (note + "# Benchmarks\n\n"
            f"Regenerated by `benchmarks/run.py` (sections: {names}; each section\n"
            "alone by name, or by its own script `benchmarks/<section>.py`); this page, from the results alone,\n"
            "by `benchmarks/run.py --readme-only`. " + machine + "\n"
            "These machines are shared: every comparison is a ratio of runs interleaved in one invocation.\n"
            "The reduced-scene start states (`post/ramp/ramp_21rpm.restart`, `post/sweep/sweep_21rpm.restart`)\n"
            "are made by `tools/drum/study.py` with the commands listed in `tools/drum/collect.py`; those\n"
            "benchmarks pass drum.in's defaults of the day they were measured (`THEN` in\n"
            "`benchmarks/common.py`: the slab at tc/10, nominal, on the surface-velocity mesh), so a rerun repeats them;\n"
            "the other sections name theirs (the newest full-scene one is the shipped\n"
            "`inputs/drum_L24_21rpm.restart.gz`, gunzipped).\n")
    for heading, modules in PAGE:
        text += f"\n{heading}\n" + "".join("\n" + mod.section(res) for mod in modules)
    return text


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0], epilog=__doc__.split("\n", 1)[1],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("sections", nargs="*", help="sections to run (default: all)")
    p.add_argument("--out", type=Path, default=common.RESULTS, help="results directory (default: benchmarks/results)")
    p.add_argument("--restart", type=Path, help="a settled 6 mm drum slab for cost, accuracy, stability, walls")
    p.add_argument("--readme-only", action="store_true", help="only regenerate the README from the results")
    args = p.parse_args(argv)
    known = settings(args.restart)
    unknown = [s for s in args.sections if s not in known]
    if unknown:
        p.error(f"unknown section(s) {', '.join(unknown)} (of {', '.join(known)})")
    out = args.out.resolve()
    if not args.readme_only:
        out.mkdir(parents=True, exist_ok=True)
        harness.write_json(out / "machine.json", harness.machine())
        for name in args.sections or list(known):
            module, invocations = known[name]
            start = time.time()
            for arguments in invocations:
                harness.say("benchmarks", f"{name} {' '.join(arguments)} ...")
                module.run(module.parser().parse_args(arguments + ["--out", str(out)]))
            harness.say("benchmarks", f"{name} done in {time.time() - start:.0f} s")
    page = common.HERE / "README.md" if out == common.RESULTS.resolve() else out / "README.md"
    command = "benchmarks/run.py " + " ".join(argv if argv is not None else sys.argv[1:])
    page.write_text(readme(common.Results(out, page.parent), harness.generated_note(command.strip())))
    harness.say("benchmarks", f"wrote {page}")


if __name__ == "__main__":
    main()
