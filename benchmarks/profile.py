#!/usr/bin/python3
"""Where the main job's time goes: a sampled profile (perf) of `inputs/drum.in` as the README runs it
(the thesis scene from the shipped steady state, tc/5 with exactRestitution, primitive cylinder,
2 ranks), its samples grouped by what they do.

perf records the whole launch (mpirun and both ranks, at --frequency samples per second of CPU);
only the ranks' samples (command `liggghts`) count. Each sample goes to the function it was taken in
(no callers: `--no-children`), and each function to the first group whose pattern matches its
library and name (GROUPS, in order): our normal model, LIGGGHTS' tangential model, the primitive wall, the
integrator, the neighbour lists, MPI and the exchange of ghost beads, the snapshots' output, the
rest of the pair loop, then everything else (the kernel, libc, ...). Shares are of CPU samples, not wall time: a rank that
waits for the other in MPI burns CPU polling, which counts as MPI. On a shared machine another job
lengthens the wall time more than it moves the shares.

Written: benchmarks/results/profile.csv (group, share of samples, the functions in it) and
profile_functions.csv (every function above --min-share, its group).

  benchmarks/profile.py                   # 5000 steps, about 1-2 minutes on 2 cores
  benchmarks/profile.py --steps 1000 --out /tmp/p

Needs: perf (linux-perf), the project's liggghts.
"""

import argparse
import re
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
import harness  # noqa: E402

HERE = Path(__file__).resolve().parent
# (group, pattern on the demangled function name), first match wins
GROUPS = [
    ("normal model (ours)", r"NormalModel<|viscoelastic::"),
    ("tangential model (LIGGGHTS' history)", r"TangentialModel<"),
    ("primitive wall", r"FixWallGran|PrimitiveWall|Cylinder"),
    ("integration", r"FixNVESphere|FixNVE|Verlet::|initial_integrate|final_integrate"),
    ("neighbour lists", r"Neigh|NPair|NBin|NStencil|half_bin|full_bin|binatoms|bin_atoms|FixContactHistory|coord2bin"),
    ("MPI and ghost exchange", r"ompi_|opal_|pmix|MPI_|Comm::|CommBrick|AtomVec.*pack|AtomVec.*unpack|borders|"
                               r"exchange|reverse_comm|forward_comm"),
    ("output (VTK, compression)", r"Dump|vtk|deflate|inflate"),
    ("pair loop (LIGGGHTS' granular template)", r"PairGran|Granular|ContactModel|SurfaceModel|compute_force|"
                                                r"CohesionModel|RollingModel"),
]
OTHER = "other (kernel, libc, ...)"
# a function without symbols goes by its library
LIBRARIES = [("MPI and ghost exchange", r"mca_|libmpi|libopen-pal|libpmix|libucp|libuct|libevent"),
             ("output (VTK, compression)", r"libz\.|libvtk")]


def group_of(entry):
    """The group of "library: function"."""
    library, _, name = entry.partition(": ")
    for group, pattern in (LIBRARIES if name.startswith("0x") else GROUPS):
        if re.search(pattern, library if name.startswith("0x") else name):
            return group
    return OTHER


def parse_report(text):
    """[(share %, "library: function")] from `perf report --stdio --no-children --sort dso,sym`
    output (a function without symbols is its address in its library)."""
    out = []
    for line in text.splitlines():
        m = re.match(r"\s*([0-9.]+)%\s+(\S+)\s+\[[.k]\]\s+(.+?)\s*$", line)
        if m:
            out.append((float(m.group(1)), f"{m.group(2)}: {m.group(3)}"))
    return out


def summarise(functions):
    """{group: (share %, [functions])}, shares renormalised to the listed functions' total."""
    total = sum(s for s, _ in functions) or 1.0
    out = {}
    for share, name in functions:
        g = group_of(name)
        s, names = out.get(g, (0.0, []))
        out[g] = (s + 100.0 * share / total, names + [name])
    return out


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--steps", type=int, default=5000)
    p.add_argument("--frequency", type=int, default=499, help="samples per CPU second")
    p.add_argument("--min-share", type=float, default=0.05, help="per cent: functions listed from this share")
    p.add_argument("--out", default=str(HERE / "results"))
    a = p.parse_args(argv)
    dt = 2e-5
    data = harness.post("profile", "perf.data")
    log = harness.post("profile", "main.log")
    cmd = ["perf", "record", "-q", "-F", str(a.frequency), "-o", str(data), "--"] + harness.mpirun(2) + [
        harness.tool_path("liggghts"), "-in", "inputs/drum.in", "-var", "time", f"{a.steps * dt:.10g}",
        "-var", "dumpdt", f"{a.steps * dt:.10g}", "-var", "name", "profile/main", "-log", str(log)]
    harness.say("profile", " ".join(cmd))
    subprocess.run(cmd, cwd=harness.REPO, check=True, stdout=subprocess.DEVNULL)
    report = subprocess.run(["perf", "report", "-i", str(data), "--stdio", "--no-children", "--sort", "dso,sym",
                             "--comm", "liggghts", "--percent-limit", str(a.min_share)],
                            capture_output=True, text=True, check=True).stdout
    functions = parse_report(report)
    groups = summarise(functions)
    out = Path(a.out)
    rows = [{"group": g, "share_percent": s, "functions": len(n), "largest": n[0]}
            for g, (s, n) in sorted(groups.items(), key=lambda kv: -kv[1][0])]
    harness.write_csv(out / "profile.csv", rows)
    harness.write_csv(out / "profile_functions.csv",
                      [{"share_percent": s, "function": n, "group": group_of(n)} for s, n in functions])
    loop = harness.Log(log)
    for r in rows:
        harness.say("profile", f"{r['share_percent']:5.1f} %  {r['group']} ({r['functions']} functions; largest "
                               f"{r['largest'][:60]})")
    harness.say("profile", f"{loop.steps} steps of {loop.atoms} beads in {loop.loop_time:.1f} s of loop: "
                           f"{loop.steps * loop.atoms / loop.loop_time:.3g} particle-steps/s (under perf, on a "
                           "machine shared with whatever else ran)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
