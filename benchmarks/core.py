#!/usr/bin/python3
"""Per-contact force of the physics core: Google Benchmark (build/benchmarks/bench_core, from
benchmarks/bench_core.cpp) with repetitions, aggregates only.
Writes OUT/core.csv (Google Benchmark's CSV), OUT/core.context (its machine report) and
OUT/core.json (the contacts per iteration, bench_core.cpp's kContacts).

Needs: python3-matplotlib (tools/harness); build/benchmarks/bench_core (-DBUILD_BENCHMARKS=ON)."""

import re
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
import harness  # noqa: E402
import common  # noqa: E402


def parser():
    p = harness.options(__doc__, out=common.RESULTS)
    common.program_option(p, "bench_core", "the Google Benchmark binary")
    p.add_argument("--repetitions", type=int, default=5, help="repetitions (default: 5)")
    return p


def run(args):
    common.require_program(args.binary, "-DBUILD_BENCHMARKS=ON")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    harness.say("core", f"{args.binary.name}, {args.repetitions} repetitions ...")
    with open(out / "core.csv", "w") as csv_out, open(out / "core.context", "w") as context:
        subprocess.run([str(args.binary), f"--benchmark_repetitions={args.repetitions}",
                        "--benchmark_report_aggregates_only=true", "--benchmark_format=csv"],
                       cwd=harness.REPO, stdout=csv_out, stderr=context, check=True)
    source = (common.HERE / "bench_core.cpp").read_text()
    harness.write_json(out / "core.json", {"contacts_per_iteration": int(re.search(r"kContacts = (\d+);", source).group(1)),
                                           "repetitions": args.repetitions, "date": common.today()})


@common.section_of("core", "core")
def section(res, m, rows):
    medians = [dict(r, name=r["name"][:-len("_median")]) for r in rows if r["name"].endswith("_median")]
    contacts, reps = m["contacts_per_iteration"], m["repetitions"]
    pournin = next(float(r["cpu_time"]) for r in medians if r["name"] == "ContactPournin")
    return (
        f"{contacts} random contacts per iteration, {reps} repetitions, median; `NormalAbsoluteConstants` is the\n"
        "same normal force with precomputed absolute constants (what hooke/stiffness does), in the same binary;\n"
        "`ContactExactCollision` is `ContactPournin`'s contacts under exactCollision (normal step law, the exact\n"
        "tangential spring driven at the rigid arms from the spins, and the mass it sees, per step).\n"
        "CPU time (the process's own: on a shared machine wall time counts the other jobs' share too):\n\n"
        + harness.markdown(medians, [("benchmark", "name", None),
                                     ("CPU ns per contact (median)", lambda r: float(r["cpu_time"]) / contacts,
                                      "{:.2f}"),
                                     ("ratio to ContactPournin",
                                      lambda r: float(r["cpu_time"]) / pournin, "{:.2f}")])
        + "\n" + common.sh(common.command("core.py", repetitions=reps)))


if __name__ == "__main__":
    run(parser().parse_args())
