// `exactRestitution on`: coefficients per unit meff for which the
// phase-averaged discrete collision (discrete.h) restitutes en and et and
// lasts tc at a given timestep.
//
// Normal: two unknowns, two conditions. The unknowns are the (tc', en') fed
// to the Pournin formulas (Eq. 3.22-3.23), so the continuous solution is the
// starting point and the answer stays readable; Newton's method with a
// finite-difference Jacobian on (ln e, duration).
// Tangential: the tangential oscillator keeps the normal one's discrete
// frequency (the leapfrog's rotation angle per step), as Pournin's constants
// give both the same continuous frequency pi/tc; this leaves the tangential
// damping, found by bisection on et (which falls monotonically with it).
// Without limitForce, requested restitutions near 1 can need negative damping
// (the discrete contact dissipates nothing at cn = 0 but restitutes slightly
// off 1); the solver then switches that dashpot off and reports what the
// contact restitutes instead, rather than return an unstable dashpot.
//
// Results are numbers only; contact_models/messages.h words them.
#pragma once

#include <array>
#include <cmath>
#include <optional>

#include "discrete.h"
#include "free_flow.h"
#include "pournin.h"

namespace viscoelastic {

enum class ExactFailure {
    none,
    normalUnreachable,     // Newton found no (tc', en') reaching en and tc
    tangentialUnreachable  // et is below what any tangential dashpot reaches
};

struct ExactSolution {
    UnitCoefficients unit{};            // per unit meff, like pourninUnitCoefficients
    DiscreteCollision achieved;         // phase-averaged outcome with `unit`
    double tcNormal = 0, enNormal = 0;  // the (tc', en') of the normal solution
    double tangentialTarget = 0;       // the sticking contact's et the solution restitutes

    // The request, so the result can be described on its own.
    ContactParameters requested{};
    // halvedMassCoefficients: the user's request, whose halved law `requested` is.
    std::optional<ContactParameters> halvedFrom;
    double dt = 0;
    bool limitForce = false;

    ExactFailure failure = ExactFailure::none;
    // normalUnreachable: the closest solution's ln(e / en) and duration / tc - 1
    double closestLnRestitutionError = 0, closestDurationError = 0;
    // Set when a request needed a negative dashpot, which is then off, and
    // the undamped contact restitutes this instead of en (et) (see above).
    std::optional<double> undampedRestitution, undampedTangentialRestitution;

    bool ok() const { return failure == ExactFailure::none; }
};

namespace detail {

// Rotation angle per step of the leapfrog amplification matrix of an
// oscillator with stiffness k and damping c per unit mass (trace
// 2 - c dt - k dt^2, determinant 1 - c dt); NaN when not oscillatory.
inline double stepAngle(double k, double c, double dt)
{
    const double r = std::sqrt(1.0 - c * dt);
    return std::acos((2.0 - c * dt - k * dt * dt) / (2.0 * r));
}

// Tangential stiffness per unit tangential mass that gives damping c the step angle theta.
inline double stiffnessForAngle(double theta, double c, double dt)
{
    return (2.0 - c * dt - 2.0 * std::sqrt(1.0 - c * dt) * std::cos(theta)) / (dt * dt);
}

// Damped Newton iteration with a central-difference Jacobian on n <= 2
// unknowns z, residual(z, r); true when |r| falls below 1e-9.
template <class Residual>
bool newton(Residual residual, double* z, double* r, std::array<double, 2> h, int n)
{
    auto norm = [n](const double* v) { return n == 1 ? std::fabs(v[0]) : std::hypot(v[0], v[1]); };
    residual(z, r);
    for (int it = 0; it < 60 && norm(r) > 1e-9; ++it) {
        double J[2][2] = {{1, 0}, {0, 1}};
        for (int k = 0; k < n; ++k) {
            double zp[2] = {z[0], z[1]}, zm[2] = {z[0], z[1]}, rp[2], rm[2];
            zp[k] += h[k], zm[k] -= h[k];
            residual(zp, rp);
            residual(zm, rm);
            for (int i = 0; i < n; ++i) J[i][k] = (rp[i] - rm[i]) / (2.0 * h[k]);
        }
        const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
        if (!(std::fabs(det) > 0.0)) return false;
        const double step[2] = {n == 1 ? -r[0] / J[0][0] : -(J[1][1] * r[0] - J[0][1] * r[1]) / det,
                                n == 1 ? 0.0 : -(J[0][0] * r[1] - J[1][0] * r[0]) / det};
        // halve the step until the residual falls and z[0] (a duration) stays positive
        bool moved = false;
        for (double lambda = 1.0; lambda > 1e-4 && !moved; lambda *= 0.5) {
            double zz[2] = {z[0] + lambda * step[0], z[1] + lambda * step[1]}, rz[2];
            if (zz[0] <= 0.0) continue;
            residual(zz, rz);
            if (norm(rz) < norm(r)) {
                for (int i = 0; i < n; ++i) z[i] = zz[i], r[i] = rz[i];
                moved = true;
            }
        }
        if (!moved) return false;
    }
    return norm(r) <= 1e-9;
}

// Normal coefficients per unit meff of Pournin's formulas for (tc', ln en').
inline UnitCoefficients normalOnly(double tcPrime, double lnEnPrime)
{
    const Oscillator n = pourninOscillator(tcPrime, lnEnPrime);
    return {n.k, n.c, 0.0, 0.0};
}

}  // namespace detail

// The tangential restitution of the continuous law `pournin` integrates, for
// a sticking contact on a wall: its spring restarts from zero force where the
// cap mu |Fn| passes through zero, whatever mu (limitForce off: the normal
// force's zero near the end; with limitForce the contact ends there). In
// closed form: Pournin's tangential oscillator from (0, 1) up to that zero t0,
// its spring then at zero force (xi = -c w / k), free until the overlap ends
// at tc. It is et where the spring holds no force at t0 (et = en).
inline double letGoRestitution(const ContactParameters& p)
{
    const Oscillator n = pourninOscillator(p.tc, std::log(p.en)), t = pourninOscillator(p.tc, std::log(p.et));
    const FreeOscillator normal(n.k, n.c), spring(t.k, t.c);
    const double zero = normal.forceZeroFrom({0.0, 1.0}, 0.0);
    Motion m = spring.after({0.0, 1.0}, zero);
    m.x = -t.c * m.u / t.k;
    return -spring.after(m, p.tc - zero).u;
}

// `start`: how the tangential model in use begins its spring (discrete.h);
// `pournin` (atTouch) also restarts it at the cap's zero, so without
// limitForce the tangential target is the law's letGoRestitution, not et.
// A `tangentialTarget` replaces that target (halvedMassCoefficients).
inline ExactSolution exactUnitCoefficients(const ContactParameters& p, double dt, bool limitForce,
                                           SpringStart start = SpringStart::wholeStep,
                                           std::optional<double> tangentialTarget = std::nullopt)
{
    ExactSolution s;
    s.requested = p, s.dt = dt, s.limitForce = limitForce;
    // -- normal: Newton on r(tc', ln en') = (ln e - ln en, duration / tc - 1)
    auto residual = [&](const double* z, double* r) {
        const DiscreteCollision d = phaseAveragedCollision(detail::normalOnly(z[0], z[1]), dt, limitForce);
        r[0] = std::log(d.restitution) - std::log(p.en);
        r[1] = d.duration / p.tc - 1.0;
    };
    double q[2] = {p.tc, std::log(p.en)}, r[2];
    const bool converged = detail::newton(residual, q, r, {1e-7 * p.tc, 1e-7}, 2);
    if (converged && q[1] > 0.0) {
        // negative damping: keep the dashpot off, match the duration only
        q[1] = 0.0;
        auto durationOnly = [&](const double* z, double* rr) {
            double full[2];
            const double zz[2] = {z[0], 0.0};
            residual(zz, full);
            rr[0] = full[1];
        };
        double r1[1];
        detail::newton(durationOnly, q, r1, {1e-7 * p.tc, 0.0}, 1);
        residual(q, r);
        if (std::fabs(r[0]) > 1e-6) s.undampedRestitution = std::exp(r[0]) * p.en;
    } else if (!converged) {
        s.failure = ExactFailure::normalUnreachable;
        s.closestLnRestitutionError = r[0], s.closestDurationError = r[1];
        return s;
    }
    s.tcNormal = q[0], s.enNormal = std::exp(q[1]);
    const UnitCoefficients u = detail::normalOnly(q[0], q[1]);

    // -- tangential: same step angle as the normal oscillator, damping by bisection
    const double theta = detail::stepAngle(u.kn, u.cn, dt);
    const double mt = kTangentialMassRatio;
    auto tangential = [&](double c) {
        UnitCoefficients v = u;
        v.kt = mt * detail::stiffnessForAngle(theta, c, dt);
        v.ct = mt * c;
        return v;
    };
    const double target = tangentialTarget                                ? *tangentialTarget
                          : start == SpringStart::atTouch && !limitForce ? letGoRestitution(p)
                                                                         : p.et;
    s.tangentialTarget = target;
    auto et = [&](double c) {
        return phaseAveragedCollision(tangential(c), dt, limitForce, start).tangentialRestitution;
    };
    double lo = 0.0, hi = 0.999 / dt;  // damping per unit tangential mass; 1 - c dt > 0
    if (et(lo) <= target) {
        if (et(lo) < target * (1.0 - 1e-6)) s.undampedTangentialRestitution = et(lo);
        hi = lo;
    }
    if (et(hi) > target) {
        s.failure = ExactFailure::tangentialUnreachable;
        return s;
    }
    for (int it = 0; it < 100 && hi - lo > 1e-13 * hi; ++it) {
        const double mid = 0.5 * (lo + hi);
        (et(mid) > target ? lo : hi) = mid;
    }
    s.unit = tangential(0.5 * (lo + hi));
    s.achieved = phaseAveragedCollision(s.unit, dt, limitForce, start);
    return s;
}

// YADE 1.12's facet mass (`wallMassAsParticle on`, walls only): a wall
// contact takes the bead's own mass as the wall's, meff/2, so per unit of its
// true meff the law's coefficients are Pournin's halved. That law is softer
// and less damped than the requested one: its collision lasts about sqrt(2)
// tc and restitutes more than en and et (Table 3.1's bead-drum pair, en = et
// 0.46: 0.582 over 1.39 tc). What it does, in closed form: the normal
// oscillator's collision (with limitForce cut where the force ends), and
// the tangential spring from (0, 1) while the force lasts; `pournin`
// without limitForce lets go of it at the force's zero (letGoRestitution).
// These are the limit dt -> 0 of the discrete collision (discrete.h).
// The coefficients per unit of the true meff: Pournin's halved.
inline UnitCoefficients halvedMassUnit(const ContactParameters& p)
{
    const UnitCoefficients u = pourninUnitCoefficients(p);
    return {0.5 * u.kn, 0.5 * u.cn, 0.5 * u.kt, 0.5 * u.ct};
}

inline DiscreteCollision halvedMassLaw(const ContactParameters& p, bool limitForce, SpringStart start)
{
    const UnitCoefficients u = halvedMassUnit(p);
    const FreeOscillator normal(u.kn, u.cn);
    const FreeOscillator spring(u.kt / kTangentialMassRatio, u.ct / kTangentialMassRatio);
    const ContinuousCollision n = continuousCollision(normal, limitForce);
    DiscreteCollision d;
    d.restitution = n.restitution, d.duration = n.duration;
    Motion m{0.0, 1.0};
    double t = 0.0;
    if (start == SpringStart::atTouch && !limitForce) {
        t = normal.forceZeroFrom({0.0, 1.0}, 0.0);
        m = spring.after(m, t);
        m.x = -spring.c * m.u / spring.k;
    }
    d.tangentialRestitution = -spring.after(m, n.forceDuration - t).u;
    return d;
}

// exactRestitution under YADE's facet mass: coefficients per unit of the
// contact's true meff for which the collision at step dt restitutes what
// halvedMassLaw gives and lasts as long (the glue, which scales by meff/2,
// applies twice these). Its `requested` holds that law's duration and
// restitution, `tangentialTarget` its et, `halvedFrom` the request p. A law
// whose sticking contact point does not even reverse (et <= 0: a small en
// with a large et and limitForce off, whose spring lets go early) has none:
// tangentialUnreachable.
inline ExactSolution halvedMassCoefficients(const ContactParameters& p, double dt, bool limitForce, SpringStart start)
{
    const DiscreteCollision law = halvedMassLaw(p, limitForce, start);
    const ContactParameters q{law.duration, law.restitution, law.tangentialRestitution, p.mu};
    ExactSolution s;
    if (law.tangentialRestitution > 0.0) {
        s = exactUnitCoefficients(q, dt, limitForce, start, law.tangentialRestitution);
    } else {
        s.requested = q, s.dt = dt, s.limitForce = limitForce;
        s.tangentialTarget = law.tangentialRestitution;
        s.failure = ExactFailure::tangentialUnreachable;
    }
    s.halvedFrom = p;
    return s;
}

}  // namespace viscoelastic
