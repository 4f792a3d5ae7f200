// Physics core of the viscoelastic (linear spring-dashpot) contact law with
// Pournin et al. (2001) coefficients. Pure C++ (Eigen only): the LIGGGHTS
// models, the validation tool and the tests all call these functions, so each
// formula exists once. Equation numbers refer to the thesis chapter (Eq. 3.x).
//
// Sign conventions follow LIGGGHTS: the contact normal n points from body j
// to body i, the overlap is positive while touching, the overlap rate is
// -(v_i - v_j).n (positive while approaching), and forces are those on i.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace viscoelastic {

using Vec3 = Eigen::Vector3d;

constexpr double kPi = 3.14159265358979323846;

// m_t / meff for two solid spheres (I = 2/5 m R^2), or a solid sphere and a
// wall: (1/meff + R1^2/I1 + R2^2/I2)^-1 = 2/7 meff.
constexpr double kTangentialMassRatio = 2.0 / 7.0;

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

// Eq. 3.22-3.25 per unit effective mass, with m_t = 2/7 meff.
inline UnitCoefficients pourninUnitCoefficients(double tc, double en, double et)
{
    const double ln_en = std::log(en);
    const double ln_et = std::log(et);
    const double m_t = kTangentialMassRatio;
    return {(kPi * kPi + ln_en * ln_en) / (tc * tc), -2.0 * ln_en / tc,
            m_t * (kPi * kPi + ln_et * ln_et) / (tc * tc), -2.0 * m_t * ln_et / tc};
}

inline UnitCoefficients pourninUnitCoefficients(const ContactParameters& p)
{
    return pourninUnitCoefficients(p.tc, p.en, p.et);
}

inline Coefficients scaled(const UnitCoefficients& u, double meff)
{
    return {meff * u.kn, meff * u.cn, meff * u.kt, meff * u.ct};
}

// Eq. 3.20. With limitForce the attractive end of the contact is cut off
// (YADE's convention); without it the nominal en and tc are exact.
inline double normalForce(const Coefficients& c, double overlap, double overlapRate, bool limitForce)
{
    const double f = c.kn * overlap + c.cn * overlapRate;
    return (limitForce && f < 0.0) ? 0.0 : f;
}

// Friction threshold of Eq. 3.18. Without limitForce the end of a contact
// is attractive; bounding friction by |Fn| there (as LIGGGHTS' history model
// does) lets a sticking contact finish its tangential half-oscillation, so
// the nominal et is achieved exactly like en.
inline double frictionLimit(double mu, double normalForce)
{
    return mu * std::fabs(normalForce);
}

// Rotates v by the smallest rotation taking unit vector `from` to unit vector
// `to`: the exact integral of Eq. 3.5's (n x dn/dt) x xi term over a step in
// which the normal turns in one plane.
inline Vec3 rotateWithNormal(const Vec3& v, const Vec3& from, const Vec3& to)
{
    const Vec3 k = from.cross(to);
    const double c = from.dot(to);
    if (c <= -1.0 + 1e-12) return -v;  // reversed normal: cannot happen within one step
    return v + k.cross(v) + k.cross(k.cross(v)) / (1.0 + c);
}

// Per-contact state of the `pournin` tangential law: the tangential overlap
// xi_t (Eq. 3.9) and the normal it was last expressed in.
struct TangentialState {
    Vec3 xi = Vec3::Zero();
    Vec3 normal = Vec3::Zero();  // zero before the first step of a contact
};

// Tangential law of the thesis (Eq. 3.18-3.21) for one step.
// The overlap is carried with the rotating contact frame (rotated, not
// projected, so its length survives a turning normal), then advanced by the
// tangential velocity of i relative to j at the contact point, vt. The
// Coulomb cap applies to the total force kt xi + ct dxi/dt; when it binds the
// spring is reset so that it reproduces the capped force (Luding 2008), which
// keeps the force continuous when sliding stops.
// Returns the tangential force on i. `advance` is false when LIGGGHTS only
// evaluates forces without moving history (e.g. `run 0`).
inline Vec3 pourninTangentialForce(TangentialState& s, const Vec3& n, const Vec3& vt, double kt,
                                   double ct, double limit, double dt, bool advance)
{
    if (advance) {
        if (s.normal.squaredNorm() > 0.0) s.xi = rotateWithNormal(s.xi, s.normal, n);
        s.xi += vt * dt;
        s.xi -= s.xi.dot(n) * n;  // round-off only: the rotation keeps xi in the plane
        s.normal = n;
    }
    Vec3 f = -(kt * s.xi + ct * vt);
    const double fmag = f.norm();
    if (fmag > limit) {
        f *= (fmag > 0.0 ? limit / fmag : 0.0);
        if (advance && kt > 0.0) s.xi = -(f + ct * vt) / kt;
    }
    return f;
}

// ---------------------------------------------------------------------------
// Timestep: stability and accuracy of the integrator LIGGGHTS uses.
//
// LIGGGHTS advances velocities by half steps (velocity Verlet) and evaluates
// the contact force from positions at step n+1 and velocities at n+1/2. For
// one contact this is the leapfrog recurrence
//     v' = (1 - 2 beta dt) v - w0^2 dt x,   x' = x + dt v'
// whose amplification matrix has trace 2 - 2 beta dt - w0^2 dt^2 and
// determinant 1 - 2 beta dt. Both eigenvalues stay inside the unit circle
// (Jury's conditions) iff  w0^2 dt^2 + 4 beta dt < 4, i.e.
//     dt < 2 (sqrt(beta^2 + w0^2) - beta) / w0^2.
// With the Pournin constants w0 tc = sqrt(pi^2 + ln^2 e), beta tc = -ln e, so
//     dt_crit / tc = 2 (sqrt(pi^2 + 2 ln^2 e) + ln e) / (pi^2 + ln^2 e),
// = 2/pi for e = 1. The same holds for the tangential oscillator with et.
// ---------------------------------------------------------------------------

// The same for any oscillator with stiffness k [1/s^2] and damping c [1/s]
// per unit mass (w0^2 = k, beta = c/2).
inline double criticalTimestepOf(double k, double c)
{
    const double beta = 0.5 * c;
    return 2.0 * (std::sqrt(beta * beta + k) - beta) / k;
}

inline double criticalTimestep(double tc, double e)
{
    const double L = -std::log(e);
    return 2.0 * tc * (std::sqrt(kPi * kPi + 2.0 * L * L) - L) / (kPi * kPi + L * L);
}

// Stability limit of a type pair: the stiffer of its normal and tangential
// oscillators.
inline double criticalTimestep(const ContactParameters& p)
{
    return std::min(criticalTimestep(p.tc, p.en), criticalTimestep(p.tc, p.et));
}

// Restitution coefficient of the continuous law. Without limitForce it is en
// by construction; with it the contact ends when the force, not the overlap,
// reaches zero (Schwager & Poeschel 2007, three damping regimes).
inline double continuousRestitution(double tc, double en, bool limitForce)
{
    if (!limitForce || en >= 1.0) return en;
    const double beta = -std::log(en) / tc;
    const double w0 = std::sqrt(kPi * kPi + std::log(en) * std::log(en)) / tc;
    const double w = kPi / tc;  // damped frequency sqrt(w0^2 - beta^2)
    // With the Pournin constants beta < w0 always, so the overdamped branch
    // beta > w0 of Schwager & Poeschel is never reached.
    if (beta < w0 / std::sqrt(2.0))
        return std::exp(-(beta / w) * (kPi - std::atan(2.0 * beta * w / (w * w - beta * beta))));
    return std::exp(-(beta / w) * std::atan(2.0 * beta * w / (beta * beta - w * w)));
}

}  // namespace viscoelastic
