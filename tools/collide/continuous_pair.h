// Independent reference for exactCollision's CONTINUOUS law between two solid
// spheres (limitForce off): the full 3D motion of the pair through one
// collision, the normal turning, the spins at rigid arms, the tangential
// spring carried along with the normal, and the Coulomb cap with Luding's
// spring reset.  Written from the equations only: it uses nothing from
// contact_models/ or the other tools (standard library only), so it can check
// the time-stepped implementation.
//
// The law (spheres i, j; all SI; meff = mi mj/(mi + mj), Ii = 0.4 mi Ri^2):
//  * d = |xi - xj|, n = (xi - xj)/d (from j to i), overlap x = Ri + Rj - d.
//    The contact lasts while x > 0: from the touch (x = 0) until the overlap
//    closes again; nothing acts outside.
//  * Normal force on i: meff F n with F = kn x + cn x', x' = -(vi - vj).n,
//    kn = (pi^2 + ln^2 en)/tc^2, cn = -2 ln(en)/tc (per unit meff; F may turn
//    negative, attractive, near the end: no clipping).
//  * Spring drive U = s vt - (Ri wi + Rj wj) x n, vt the tangential part of
//    vi - vj, s = d/(Ri + Rj); tangential mass 1/mt = s/meff + Ri ci/Ii +
//    Rj cj/Ij with the arms ci = Ri - x/2, cj = Rj - x/2.
//  * Spring xi (tangent plane, 0 at the touch), parallel-transported with the
//    normal: xi' = U - (xi.n') n.  Per unit mt: kt = (pi^2 + ln^2 et)/tc^2,
//    ct = -2 ln(et)/tc, trial phi = kt xi + ct U, cap kappa |F| with
//    kappa = mu meff/mt.  |phi| <= cap: sticking.  Otherwise sliding: phi is
//    held on the cap along its own direction and the spring slaved to it,
//    xi = (phi - ct U)/kt.  Ft = -mt phi acts on i at -ci n from its centre,
//    -Ft on j at +cj n: torques (-ci n) x Ft on i and -cj n x Ft on j.
// Only relative quantities enter (the forces are equal and opposite), so the
// state is r = xi - xj, V = vi - vj, wi, wj and the spring.  The law keeps
// the angular momentum meff r x V + Ii wi + Ij wj: Ft's moment on the orbit,
// d n x Ft, and its torques on the spins, -(ci + cj) n x Ft, cancel
// (ci + cj = d).
//
// Method: classic RK4 with a fixed step h = tc/N from the touch.  The
// right-hand side is the law above with the force projected onto the cap (a
// continuous function of the state); after every step the spring is reset to
// the projected force (Luding's reset: the return mapping of a fine stepper).
// Three events end a step where they fall, each located on the RK4 step map
// (a bracketed secant on the step length, to 1e-15 h): the overlap closing
// (the exit, so no interpolation error); a zero of F, where the cap is 0 and
// the law unloads the spring to phi = 0 however briefly it slides there (at
// mu 1e6 for ~1e-7 tc, far below any step; the reset there takes the cap as
// exactly 0, since F's round-off times a large kappa would leave a spring
// force); and the spring reaching the cap, where the force's rate jumps by up
// to kappa |F'| (unlocated, that corner moved exits by up to 1e-6 of the
// incoming speed between N = 1e4 and 2e4 at large mu).
// The reset is a backward-Euler update of a sliding force's direction, so a
// slide whose direction turns (spinning spheres) converges at first order;
// everything else at higher order.  pairCollision therefore runs N and 2N
// steps and returns the Richardson extrapolation 2 y(2N) - y(N).
//
// Convergence, measured over 1000 draws of the tests' random pair collisions
// (pair_stepper.h's drawPair: en, et 0.1-0.95, mu 0.05-1e6, vn 0.01-2 m/s,
// vt/vn 0-5, spins to 2 vn/R in half the draws; glass beads, R 1.5 mm), as
// max(|dV|, R |dwi|, R |dwj|) over the incoming speed |V|: between N = 1e4
// and 2e4 steps (the `change` field) at most 3.8e-7 (median 1e-14); the
// extrapolation from N = 1e4 against the one from 4e4: at most 3.1e-9.  A
// literal explicit-Euler return-mapping stepper of the same law, written
// apart with Eigen (tests/collide/test_continuous_pair.cpp), agrees to its
// own first-order error.  N = 1e4 takes about 10 ms per collision.
#pragma once

#include <array>

#include "continuous_law.h"  // Material

namespace continuous {

using Vector = std::array<double, 3>;

struct Sphere {
  double m;  // mass [kg]
  double r;  // radius [m]; inertia 0.4 m r^2
};

// The pair at the touch.
struct PairTouch {
  Vector r;       // xi - xj, |r| = ri + rj (relative 1e-9)
  Vector v;       // vi - vj, approaching: v.r < 0
  Vector wi, wj;  // spins [rad/s]
};

struct PairExit {
  Vector r;         // xi - xj where the overlap closes (|r| = ri + rj)
  Vector v;         // vi - vj after the collision (constant in free flight)
  Vector wi, wj;    // spins after the collision
  double duration;  // time from the touch until the overlap is 0 again
  int slides;       // stick -> slide onsets at the steps (a slide from the touch counts)
  double change;    // pairCollision: max(|dV|, ri |dwi|, rj |dwj|) between N and 2N steps
};

// One run of N steps per tc (no extrapolation; change = 0).  Throws
// std::invalid_argument on bad input (material, masses, a state not at the
// touch or not approaching, N < 100) and std::runtime_error if the contact has
// not ended after 100 tc.  mu may be +infinity (no cap).
PairExit pairCollisionSteps(const Material&, const Sphere& i, const Sphere& j, const PairTouch&, long steps);

// The converged exit: 2 y(2N) - y(N) from runs of N and 2N steps per tc; its
// change field holds the difference between those two runs (the error of the
// plain 2N run; the extrapolation's is far smaller, see above).
PairExit pairCollision(const Material&, const Sphere& i, const Sphere& j, const PairTouch&, long steps = 10000);

}  // namespace continuous
