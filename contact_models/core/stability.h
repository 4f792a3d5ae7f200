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

// A bead with many simultaneous contacts oscillates faster than a binary
// contact: a settled column fails from 0.72-0.77 of the binary limit, the
// turning drum from 0.55-0.62 of it (benchmarks/README.md, stability map).
// Runs stop above this fraction of the binary limit.
constexpr double kMultiContactFactor = 0.5;

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

}  // namespace viscoelastic
