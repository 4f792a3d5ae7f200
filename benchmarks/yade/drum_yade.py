# The drum slab in YADE (ViscElMat + Law2_ScGeom_ViscElPhys_Basic, YADE's own
# mixing rules), from a LIGGGHTS state: same beads, same drum (180 facets,
# 450 mm), same dt; times `rounds` segments of `steps` steps.
#
#   yade -n -x -jTHREADS benchmarks/yade/drum_yade.py BEADS.csv period=0.012 steps=500 rpm=21 dt=1e-5 \
#        [rounds=1] [before=COMMAND]
#
# BEADS.csv: from benchmarks/yade/vtp_to_csv.py. Prints per round
# "yade: round I, N beads, S steps, T s, P particle-steps/s, K outside the drum".
# COMMAND (run through the shell with the round number appended, before each
# round) lets a peer run interleave with YADE's rounds: YADE's first step in a
# periodic cell insertion-sorts every bound (minutes for 30,000 beads), so
# one YADE process serves all rounds. YADE's periodic collider
# needs bodies under half the period: 3 mm beads need a period above 6 mm,
# and the drum facets are cut along the axis into pieces of at most period/3.
import csv
import math
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(sys.argv[0]).resolve().parents[2] / "tools"))  # yade -x: argv[0] is this script
from harness.core import materials  # noqa: E402  (inputs/materials.in: Table 3.1)

M = materials()

args = sys.argv[1:]
kv = dict(a.split("=", 1) for a in args[1:])
period = float(kv.get("period", "0.012"))
steps = int(kv.get("steps", "500"))
rpm = float(kv.get("rpm", "21"))
dt = float(kv.get("dt", "1e-5"))
R, segments, c = M["drum_R"], 180, 0.5  # drum radius, facets around, drum axis at y = z = c

O.periodic = True
O.cell.setBox(period, 2 * c, 2 * c)
# Table 3.1; YADE averages tc, en, et of the two materials and takes the smaller friction angle
glass = O.materials.append(ViscElMat(tc=M["bead_tc"], en=M["bead_en"], et=M["bead_et"],
                                     frictionAngle=math.atan(M["bead_mu"]), density=M["bead_rho"]))
steel = O.materials.append(ViscElMat(tc=M["drum_tc"], en=M["drum_en"], et=M["drum_et"],
                                     frictionAngle=math.atan(M["drum_mu"]), density=M["bead_rho"]))

pieces = 3
drum = []
for k in range(segments):
    a0, a1 = 2 * math.pi * k / segments, 2 * math.pi * (k + 1) / segments
    for j in range(pieces):
        x0, x1 = period * j / pieces, period * (j + 1) / pieces
        p = [Vector3(x, c + R * math.cos(a), c + R * math.sin(a)) for x, a in ((x0, a0), (x1, a0), (x1, a1), (x0, a1))]
        drum.append(O.bodies.append(facet([p[0], p[1], p[2]], material=steel, fixed=True)))
        drum.append(O.bodies.append(facet([p[0], p[2], p[3]], material=steel, fixed=True)))

# one append of the whole list: appending bodies one by one is quadratic here
beads = []
with open(args[0]) as f:
    for row in csv.DictReader(f):  # columns of vtp_to_csv.py, by name
        q = {k: float(v) for k, v in row.items()}
        b = sphere((q["x"], q["y"] + c, q["z"] + c), q["r"], material=glass)
        b.state.vel = Vector3(q["vx"], q["vy"], q["vz"])
        b.state.angVel = Vector3(q["wx"], q["wy"], q["wz"])
        beads.append(b)
O.bodies.append(beads)
n = len(beads)

O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()],
                    [Ip2_ViscElMat_ViscElMat_ViscElPhys()], [Law2_ScGeom_ViscElPhys_Basic()]),
    RotationEngine(rotationAxis=(1, 0, 0), rotateAroundZero=True, zeroPoint=(0, c, c),
                   angularVelocity=2 * math.pi * rpm / 60, ids=drum),
    NewtonIntegrator(damping=0, gravity=(0, 0, -M["gravity"])),
]
O.dt = dt
O.run(20, True)  # first steps build the collider's lists
for i in range(1, int(kv.get("rounds", "1")) + 1):
    if "before" in kv:
        subprocess.run("%s %d" % (kv["before"], i), shell=True, check=True)
    t0 = time.time()
    O.run(steps, True)
    elapsed = time.time() - t0
    lost = sum(1 for b in O.bodies if isinstance(b.shape, Sphere) and
               math.hypot(b.state.pos[1] - c, b.state.pos[2] - c) > R)
    print("yade: round %d, %d beads, %d steps, %.3f s, %.4g particle-steps/s, %d outside the drum"
          % (i, n, steps, elapsed, n * steps / elapsed, lost), flush=True)
