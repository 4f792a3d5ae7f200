# Head-on collisions of two equal glass beads in YADE (ViscElMat +
# Law2_ScGeom_ViscElPhys_Basic, the thesis' law), averaged over the phase at
# which contact starts within a step, as `collide sweep-dt --phases N` does
# for LIGGGHTS: N pairs side by side, pair k starting k/N of a step further apart.
#
#   yade -n -x benchmarks/yade/collide_yade.py OUT.csv [ratios=5,10,20,40,81] [phases=128]
#
# Writes tc_over_dt, restitution (mean, min, max) and contact duration in steps.
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(sys.argv[0]).resolve().parents[2] / "tools"))  # yade -x: argv[0] is this script
from harness.core import materials  # noqa: E402  (inputs/materials.in: Table 3.1)

M = materials()

args = sys.argv[1:]
out = args[0]
kv = dict(a.split("=", 1) for a in args[1:])
ratios = [float(r) for r in kv.get("ratios", "5,10,20,40,81").split(",")]
phases = int(kv.get("phases", "128"))
tc, en, et, mu = M["bead_tc"], M["bead_en"], M["bead_et"], M["bead_mu"]
r, rho, vn = M["bead_d"] / 2, M["bead_rho"], 1.0  # as collide's defaults


def run(ratio):
    O.reset()
    dt = tc / ratio
    mat = O.materials.append(ViscElMat(tc=tc, en=en, et=et, frictionAngle=math.atan(mu), density=rho))
    pairs = []
    for k in range(phases):
        gap = vn * dt * (1.0 + k / phases)  # first touch after 1 + k/N steps
        y = 4 * r * k                     # pairs far apart from each other
        a = O.bodies.append(sphere((-r - gap / 2, y, 0), r, material=mat))
        b = O.bodies.append(sphere((r + gap / 2, y, 0), r, material=mat))
        O.bodies[a].state.vel = Vector3(vn / 2, 0, 0)
        O.bodies[b].state.vel = Vector3(-vn / 2, 0, 0)
        pairs.append((a, b))
    O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb()]),
        InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_ViscElMat_ViscElMat_ViscElPhys()],
                        [Law2_ScGeom_ViscElPhys_Basic()]),
        NewtonIntegrator(damping=0, gravity=(0, 0, 0)),
    ]
    O.dt = dt
    steps = [0] * phases
    for _ in range(int(3 * ratio) + 10):
        O.step()
        for k, (a, b) in enumerate(pairs):
            i = O.interactions[a, b] if O.interactions.has(a, b) else None
            if i is not None and i.isReal:
                steps[k] += 1
    e = [(O.bodies[b].state.vel[0] - O.bodies[a].state.vel[0]) / vn for a, b in pairs]
    return sum(e) / phases, min(e), max(e), sum(steps) / phases


with open(out, "w") as f:
    f.write("tc_over_dt,restitution_mean,restitution_min,restitution_max,duration_steps_mean\n")
    for ratio in ratios:
        m, lo, hi, d = run(ratio)
        f.write("%g,%.6f,%.6f,%.6f,%.3f\n" % (ratio, m, lo, hi, d))
        print("yade tc/dt %g: restitution %.4f (%.4f .. %.4f), contact %.2f steps" % (ratio, m, lo, hi, d))
