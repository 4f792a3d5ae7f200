// Pournin et al. (2001) coefficients of the linear spring-dashpot law
// (Eq. 3.22-3.25): the contact constants that make a binary collision last tc
// and restitute en (normal) and et (tangential, sticking), and their inverse.
// Pure C++, no I/O: the LIGGGHTS models, the tools and the tests share it.
#pragma once

#include <cmath>

namespace viscoelastic {

constexpr double kPi = 3.14159265358979323846;

// m_t / meff for two solid spheres (I = 2/5 m R^2), or a solid sphere and a
// wall: (1/meff + R1^2/I1 + R2^2/I2)^-1 = 2/7 meff.
constexpr double kTangentialMassRatio = 2.0 / 7.0;

// The mass the law's spring sees at a contact between solid spheres (I = 2/5
// m r^2) whose force acts at LIGGGHTS' lever arms cri, crj (r - overlap/2).
// The spring is driven by the rate U of collision.h's springDrive: the
// contact point's tangential velocity at the rigid arms ri, rj, its orbital
// part scaled by `orbit` = d / (ri + rj) (d the distance of the centres; 1 on
// a wall). A force F at arms cri, crj changes U at F (orbit/meff + ri cri/Ii +
// rj crj/Ij): that is the mass. At first touch it is 2/7 meff. A wall: mj = 0.
// Over one common denominator (one division: it runs at every step of every
// contact under exactCollision).
inline double rigidArmMass(double meff, double mi, double ri, double cri, double mj, double rj, double crj,
                           double orbit = 1.0)
{
    const double a = meff, b = 0.4 * mi * ri;  // 1/m = orbit/a + cri/b (+ crj/c)
    if (!(mj > 0.0)) return a * b / (orbit * b + a * cri);
    const double c = 0.4 * mj * rj;
    return a * b * c / (orbit * b * c + a * (c * cri + b * crj));
}

// Where the unclipped normal force kn xi + cn dxi/dt changed sign between the
// previous step and this one, the cap mu |Fn| of Eq. 3.18 passed through zero
// in between: the continuous law slid there and reset its spring to zero
// force, whatever mu. With et != en the spring still holds force then (it is
// in phase with Fn only when et = en), so sampling the cap at the steps alone
// keeps part of it and converges slowly (about half order). Returns the time
// since that zero, by linear interpolation of the force (first order, like
// the step), or a negative value when the force kept its sign.
inline double timeSinceCapZero(double previousForce, double force, double dt)
{
    if (!(previousForce * force < 0.0)) return -1.0;
    return dt * force / (force - previousForce);
}

// Material data of one type pair, as given in the input script.
struct ContactParameters {
    double tc;  // contact duration [s]
    double en;  // normal restitution coefficient, (0, 1]
    double et;  // tangential restitution coefficient, (0, 1]
    double mu;  // Coulomb friction coefficient, >= 0
};

// Spring and dashpot constants divided by the contact's effective mass meff:
// kn [1/s^2], cn [1/s], kt [1/s^2], ct [1/s]. They depend on the type pair
// only, so they are computed once at init; a contact multiplies by its meff.
struct UnitCoefficients {
    double kn, cn, kt, ct;
};

// Contact constants of one contact: kn, kt [N/m], cn, ct [N s/m].
struct Coefficients {
    double kn, cn, kt, ct;
};

// Stiffness k [1/s^2] and damping c [1/s] of one oscillator per unit meff.
struct Oscillator {
    double k, c;
};

// Eq. 3.22-3.23 (massRatio 1) and 3.24-3.25 (massRatio m_t/meff):
//     k = m (pi^2 + ln^2 e) / tc^2,   c = -2 m ln e / tc.
// Written in ln e so that the exact-restitution solver may step through
// e > 1 (negative damping) without leaving the formula.
inline Oscillator pourninOscillator(double tc, double lnE, double massRatio = 1.0)
{
    return {massRatio * (kPi * kPi + lnE * lnE) / (tc * tc), -2.0 * massRatio * lnE / tc};
}

// The (tc, ln e) a Pournin oscillator is made of.
struct DurationAndRestitution {
    double tc;   // [s]
    double lnE;  // ln of the restitution coefficient
};

// Inverse of Eq. 3.22-3.23 for k, c per unit mass: the damped frequency
// sqrt(k - c^2/4) is pi/tc, and the decay over tc is e = exp(-c tc / 2).
inline DurationAndRestitution pourninInverse(double k, double c)
{
    const double tc = kPi / std::sqrt(k - 0.25 * c * c);
    return {tc, -0.5 * c * tc};
}

// Eq. 3.22-3.25 per unit effective mass, with m_t = 2/7 meff.
inline UnitCoefficients pourninUnitCoefficients(double tc, double en, double et)
{
    const Oscillator normal = pourninOscillator(tc, std::log(en));
    const Oscillator tangential = pourninOscillator(tc, std::log(et), kTangentialMassRatio);
    return {normal.k, normal.c, tangential.k, tangential.c};
}

inline UnitCoefficients pourninUnitCoefficients(const ContactParameters& p)
{
    return pourninUnitCoefficients(p.tc, p.en, p.et);
}

inline Coefficients scaled(const UnitCoefficients& u, double meff)
{
    return {meff * u.kn, meff * u.cn, meff * u.kt, meff * u.ct};
}

// Mass of a solid sphere of diameter d and density rho [kg].
inline double sphereMass(double d, double rho)
{
    return kPi / 6.0 * d * d * d * rho;
}

// meff = m1 m2 / (m1 + m2) of a contact; a wall (mass 0) contributes no
// inertia, so a sphere-wall contact has the sphere's mass.
inline double effectiveMass(double m1, double m2)
{
    if (m1 > 0 && m2 > 0) return m1 * m2 / (m1 + m2);
    return m1 > 0 ? m1 : m2;
}

}  // namespace viscoelastic
