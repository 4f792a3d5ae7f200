#!/usr/bin/python3
"""The LIGGGHTS side of one peers.py round, run by drum_yade.py (its `before` command, which
appends the round number) before each of YADE's timed rounds: the settled state continued with
the rotating mesh and YADE's mixing rules, its log at NAME_r<ROUND>.log under post/ (peers.py
reads the loop time from it).

  benchmarks/yade/liggghts_round.py STATE TIME PERIOD DT CORES NAME ROUND   (DT: YADE's, the same)

Needs: python3-matplotlib (tools/harness), mpirun; liggghts."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import common  # noqa: E402
import harness  # noqa: E402


def main(state, time, period, dt, cores, name, round_):
    tag = f"{name}_r{round_}"
    harness.drum(harness.post(tag + ".log"), np=int(cores), **common.then(
        start="restart", restart=f"{state}.restart", period=period, dt=dt, rpm=21, wall="moving", conventions="yade",
        time=time, dumpdt=1, name=tag))


if __name__ == "__main__":
    if len(sys.argv) != 8:
        sys.exit(__doc__)
    main(*sys.argv[1:])
