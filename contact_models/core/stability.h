// Timestep stability of the integrator LIGGGHTS uses, for one contact
// (Jury's conditions), and the guard the model applies to it.
//
// LIGGGHTS advances velocities by half steps (velocity Verlet) and evaluates
// the contact force from positions at step n+1 and velocities at n+1/2. For
// one contact this is the leapfrog recurrence
//     v' = (1 - 2 beta dt) v - w0^2 dt x,   x' = x + dt v'
// whose amplification matrix has trace 2 - 2 beta dt - w0^2 dt^2 and
// determinant 1 - 2 beta dt. Both eigenvalues stay inside the unit circle
// (Jury's conditions) iff  w0^2 dt^2 + 4 beta dt < 4, i.e.
//     dt < 2 (sqrt(beta^2 + w0^2) - beta) / w0^2.
// With the Pournin constants (Eq. 3.22-3.25) w0 tc = sqrt(pi^2 + ln^2 e),
// beta tc = -ln e, so
//     dt_crit / tc = 2 (sqrt(pi^2 + 2 ln^2 e) + ln e) / (pi^2 + ln^2 e),
// = 2/pi for e = 1. The same holds for the tangential oscillator with et.
#pragma once

#include <algorithm>
#include <cmath>

#include "pournin.h"

namespace viscoelastic {

// A bead pressed by several neighbours at once feels their springs and
// dashpots in parallel, so a dense packing goes unstable before a binary
// contact does. Measured (benchmarks/README.md, stability map: the settled
// column under its own weight and under 30 times it, stock hooke/stiffness
// with our constants, en 0.1-0.95): the first failing run of each en and
// load is at the binary limit of an oscillator Z = 2.9-3.3 times stiffer and
// more damped (sampled 0.005-0.01 tc apart), the last stable one at Z 3.0-3.5;
// the turning drum fails later (Z 1.8-2.3). The guard takes Z = 3.5, 5 % above
// the largest Z of a failing run: its timestep lies 3.9-13 % below the first
// failing one of each en and load (3.9 %: en 0.1 under 30 g). A fixed fraction
// of the binary limit cannot do this: the onset lies at 0.38 of it for en 0.1
// and 0.57 for en 0.95 (the former guard, half of it, let en 0.1 and 0.3 fail).
constexpr double kCoordinationFactor = 3.5;

// Binary limit of any oscillator with stiffness k [1/s^2] and damping c
// [1/s] per unit mass (w0^2 = k, beta = c/2).
inline double criticalTimestepOf(double k, double c)
{
    const double beta = 0.5 * c;
    return 2.0 * (std::sqrt(beta * beta + k) - beta) / k;
}

// Binary limit of a Pournin oscillator, in closed form.
inline double criticalTimestep(double tc, double e)
{
    const double L = -std::log(e);
    return 2.0 * tc * (std::sqrt(kPi * kPi + 2.0 * L * L) - L) / (kPi * kPi + L * L);
}

// The guard's timestep for an oscillator: the binary limit of one
// kCoordinationFactor times stiffer and more damped.
inline double stableTimestepOf(double k, double c)
{
    return criticalTimestepOf(kCoordinationFactor * k, kCoordinationFactor * c);
}

// The inverse: the stiffening Z for which the binary limit of a contact Z
// times stiffer and more damped is dt (Jury: Z (k dt^2 + 2 c dt) = 4).
inline double stiffeningAt(double k, double c, double dt)
{
    return 4.0 / (k * dt * dt + 2.0 * c * dt);
}

// Binary limit of a type pair: the stiffer of its normal and tangential
// oscillators.
inline double criticalTimestep(const ContactParameters& p)
{
    return std::min(criticalTimestep(p.tc, p.en), criticalTimestep(p.tc, p.et));
}

// The same for any coefficients per unit meff (e.g. exactRestitution's); the
// tangential oscillator is per unit tangential mass m_t.
inline double criticalTimestep(const UnitCoefficients& u)
{
    return std::min(criticalTimestepOf(u.kn, u.cn),
                    criticalTimestepOf(u.kt / kTangentialMassRatio, u.ct / kTangentialMassRatio));
}

// The guard of a type pair (Pournin's coefficients), and of any
// coefficients per unit meff (exactRestitution's, exactCollision's step law).
inline double stableTimestep(const UnitCoefficients& u)
{
    return std::min(stableTimestepOf(u.kn, u.cn),
                    stableTimestepOf(u.kt / kTangentialMassRatio, u.ct / kTangentialMassRatio));
}

inline double stableTimestep(const ContactParameters& p)
{
    return stableTimestep(pourninUnitCoefficients(p));
}

// The stiffening at which a type pair's guard would be dt (what measured
// onsets are expressed in): the guard is its most critical oscillator's, the
// one that reaches dt at the smaller Z. For any applied coefficients per unit
// meff, or for Pournin's of a type pair.
inline double stiffeningAt(const UnitCoefficients& u, double dt)
{
    return std::min(stiffeningAt(u.kn, u.cn, dt),
                    stiffeningAt(u.kt / kTangentialMassRatio, u.ct / kTangentialMassRatio, dt));
}

inline double stiffeningAt(const ContactParameters& p, double dt)
{
    return stiffeningAt(pourninUnitCoefficients(p), dt);
}

}  // namespace viscoelastic
