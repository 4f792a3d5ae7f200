// A binary collision as LIGGGHTS integrates it, and the contact coefficients
// that make it end with the requested restitution and duration
// (`restitution exact`).
//
// LIGGGHTS advances velocities by half steps and evaluates the contact force
// from positions at step n+1 and velocities at n+1/2. For the normal relative
// motion of one contact (overlap x, overlap rate v, per unit meff) that is
//     v' = v - dt (kn x + cn v),   x' = x + dt v'
// and the same for a sticking tangential contact (overlap xi, velocity w, per
// unit tangential mass). The tangential spring starts at the first
// overlapping step with a whole step of displacement (`pournin` and `history`
// both add vt dt on that step), and stops with the normal contact.
//
// A contact starts between two steps: its first overlap is phase * v0 * dt,
// with the phase uniform in (0, 1] over the many contacts of a flow. Every
// outcome below is a mean over that phase. For a fixed phase the outcome jumps
// where the number of contact steps changes (about cn dt, 10 % at tc/10), so
// the mean is computed exactly: between those breakpoints the recurrence is
// linear in the phase.
#pragma once

#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "viscoelastic.h"

namespace viscoelastic {

// Outcome of a collision starting with unit overlap rate and unit tangential
// velocity. Linear law: it depends on neither the speeds nor the mass.
struct DiscreteCollision {
    double restitution = 0;            // -v after / v before
    double tangentialRestitution = 0;  // -w after / w before, sticking (infinite friction)
    double duration = 0;               // steps with overlap > 0, times dt [s]
    double peakOverlap = 0;            // largest sampled overlap per unit approach speed [s]
};

// Per-phase collision, and its signature: the number of contact steps and the
// first step at which limitForce cuts the force. The outcome is linear in the
// phase as long as the signature does not change.
struct PhaseCollision {
    DiscreteCollision outcome;
    int steps = 0;
    int firstCut = -1;
    bool sameRegime(const PhaseCollision& o) const { return steps == o.steps && firstCut == o.firstCut; }
};

inline PhaseCollision discreteCollisionAtPhase(const UnitCoefficients& u, double dt, bool limitForce, double phase)
{
    const double mt = kTangentialMassRatio;
    const int maxSteps = static_cast<int>(50.0 * kPi / (std::sqrt(u.kn) * dt)) + 100;  // 50 tc
    double x = phase * dt, v = 1.0;  // normal overlap and rate (v0 = 1)
    double xi = 0.0, w = 1.0;        // tangential overlap and velocity (w0 = 1)
    PhaseCollision r;
    double peak = x;
    while (x > 0.0 && r.steps < maxSteps) {
        const double f = u.kn * x + u.cn * v;
        const bool cut = limitForce && f < 0.0;
        if (cut && r.firstCut < 0) r.firstCut = r.steps;
        // a cut normal force leaves a zero friction limit: the tangential force stops too
        if (r.firstCut < 0) {
            xi += dt * w;
            w -= dt * (u.kt * xi + u.ct * w) / mt;
        }
        v -= dt * (cut ? 0.0 : f);
        x += dt * v;
        peak = std::max(peak, x);
        ++r.steps;
    }
    r.outcome = {-v, -w, r.steps * dt, peak};
    return r;
}

// The same for the Pournin coefficients of (tc, en, et).
inline DiscreteCollision discreteCollisionAtPhase(double tc, double en, double dt, bool limitForce, double phase,
                                                  double et = 1.0)
{
    return discreteCollisionAtPhase(pourninUnitCoefficients(tc, en, et), dt, limitForce, phase).outcome;
}

namespace detail {

inline void accumulate(DiscreteCollision& sum, const DiscreteCollision& d, double weight)
{
    sum.restitution += weight * d.restitution;
    sum.tangentialRestitution += weight * d.tangentialRestitution;
    sum.duration += weight * d.duration;
    sum.peakOverlap += weight * d.peakOverlap;
}

// Integral over [a, b] of an outcome whose regime is known at both ends:
// one regime -> linear, the midpoint is exact; otherwise bisect towards the
// breakpoint(s).
inline void integrate(const UnitCoefficients& u, double dt, bool limitForce, double a, const PhaseCollision& ra,
                      double b, const PhaseCollision& rb, DiscreteCollision& sum)
{
    if (ra.sameRegime(rb) || b - a < 1e-13) {
        accumulate(sum, discreteCollisionAtPhase(u, dt, limitForce, 0.5 * (a + b)).outcome, b - a);
        return;
    }
    const double m = 0.5 * (a + b);
    const PhaseCollision rm = discreteCollisionAtPhase(u, dt, limitForce, m);
    integrate(u, dt, limitForce, a, ra, m, rm, sum);
    integrate(u, dt, limitForce, m, rm, b, rb, sum);
}

}  // namespace detail

// Mean over the contact-start phase, uniform in (0, 1]. Sixteen initial
// intervals: a regime that starts and ends inside one of them (it would
// need two breakpoints within 1/16 of a step) is not resolved.
inline DiscreteCollision phaseAveragedCollision(const UnitCoefficients& u, double dt, bool limitForce)
{
    constexpr int kIntervals = 16;
    constexpr double kSmallestPhase = 1e-12;  // the phase 0 itself is no contact
    DiscreteCollision sum;
    double a = kSmallestPhase;
    PhaseCollision ra = discreteCollisionAtPhase(u, dt, limitForce, a);
    for (int i = 1; i <= kIntervals; ++i) {
        const double b = static_cast<double>(i) / kIntervals;
        const PhaseCollision rb = discreteCollisionAtPhase(u, dt, limitForce, b);
        detail::integrate(u, dt, limitForce, a, ra, b, rb, sum);
        a = b, ra = rb;
    }
    const double width = 1.0 - kSmallestPhase;
    return {sum.restitution / width, sum.tangentialRestitution / width, sum.duration / width,
            sum.peakOverlap / width};
}

inline DiscreteCollision phaseAveragedCollision(const ContactParameters& p, double dt, bool limitForce)
{
    return phaseAveragedCollision(pourninUnitCoefficients(p), dt, limitForce);
}

// Mean over the phases (k + 0.5) / phases, k = 0..phases-1: what a validation
// run sampling those phases measures.
inline DiscreteCollision sampledCollision(const UnitCoefficients& u, double dt, bool limitForce, int phases)
{
    DiscreteCollision sum;
    for (int k = 0; k < phases; ++k)
        detail::accumulate(sum, discreteCollisionAtPhase(u, dt, limitForce, (k + 0.5) / phases).outcome,
                           1.0 / phases);
    return sum;
}

inline DiscreteCollision discreteCollision(double tc, double en, double dt, bool limitForce, int phases)
{
    return sampledCollision(pourninUnitCoefficients(tc, en, 1.0), dt, limitForce, phases);
}

// ---------------------------------------------------------------------------
// `restitution exact`: coefficients per unit meff for which the phase-averaged
// discrete collision restitutes en and et and lasts tc.
//
// Normal: two unknowns, two conditions. The unknowns are the (tc', en') fed
// to the Pournin formulas, so the continuous solution is the starting point
// and the answer stays readable; Newton's method with a finite-difference
// Jacobian on (ln e, duration).
// Tangential: the tangential oscillator keeps the normal one's discrete
// frequency (the leapfrog's rotation angle per step), as Pournin's constants
// give both the same continuous frequency pi/tc; this leaves the tangential
// damping, found by bisection on et (which falls monotonically with it).
// Without limitForce, requested restitutions near 1 can need negative damping
// (the discrete contact dissipates nothing at cn = 0 but restitutes slightly
// off 1); the solver then switches that dashpot off and says what the
// contact restitutes instead, rather than return an unstable dashpot.
// ---------------------------------------------------------------------------

struct ExactSolution {
    UnitCoefficients unit{};     // per unit meff, like pourninUnitCoefficients
    DiscreteCollision achieved;  // phase-averaged outcome with `unit`
    double tcNormal = 0, enNormal = 0;  // the (tc', en') of the normal solution
    std::string failure;         // empty on success: why no solution was found
    std::string warning;         // a restitution of 1 left slightly unreached (see above)
    bool ok() const { return failure.empty(); }
};

namespace detail {

inline UnitCoefficients normalFrom(double tcPrime, double lnEnPrime)
{
    return {(kPi * kPi + lnEnPrime * lnEnPrime) / (tcPrime * tcPrime), -2.0 * lnEnPrime / tcPrime, 0.0, 0.0};
}

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

}  // namespace detail

inline ExactSolution exactUnitCoefficients(const ContactParameters& p, double dt, bool limitForce)
{
    ExactSolution s;
    char buf[640];
    // -- normal: Newton on r(tc', ln en') = (ln e - ln en, duration / tc - 1)
    auto residual = [&](const double* z, double* r) {
        const DiscreteCollision d = phaseAveragedCollision(detail::normalFrom(z[0], z[1]), dt, limitForce);
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
        if (std::fabs(r[0]) > 1e-6) {
        std::snprintf(buf, sizeof buf,
                      "en %g at dt %g s (tc/dt %.2f) would need a negative normal dashpot (the undamped "
                      "discrete contact restitutes %.6f): the dashpot is off",
                      p.en, dt, p.tc / dt, std::exp(r[0]) * p.en);
        s.warning = buf;
        }
    } else if (!converged) {
        std::snprintf(buf, sizeof buf,
                      "no normal coefficients reach en %g in %g s at dt %g s (tc/dt %.2f)%s; the closest found "
                      "restitutes %+.3g%% off and lasts %+.3g%% off: use a smaller timestep or restitution nominal",
                      p.en, p.tc, dt, p.tc / dt,
                      limitForce ? " with limitForce on (forbidding attraction bounds the restitution from below)" : "",
                      100.0 * std::expm1(r[0]), 100.0 * r[1]);
        s.failure = buf;
        return s;
    }
    s.tcNormal = q[0], s.enNormal = std::exp(q[1]);
    UnitCoefficients u = detail::normalFrom(q[0], q[1]);

    // -- tangential: same step angle as the normal oscillator, damping by bisection
    const double theta = detail::stepAngle(u.kn, u.cn, dt);
    const double mt = kTangentialMassRatio;
    auto tangential = [&](double c) {
        UnitCoefficients v = u;
        v.kt = mt * detail::stiffnessForAngle(theta, c, dt);
        v.ct = mt * c;
        return v;
    };
    auto et = [&](double c) { return phaseAveragedCollision(tangential(c), dt, limitForce).tangentialRestitution; };
    double lo = 0.0, hi = 0.999 / dt;  // damping per unit tangential mass; 1 - c dt > 0
    if (et(lo) <= p.et) {
        if (et(lo) < p.et * (1.0 - 1e-6)) {
        std::snprintf(buf, sizeof buf,
                      "%set %g at dt %g s (tc/dt %.2f) would need a negative tangential dashpot (the undamped "
                      "sticking contact restitutes %.6f): the tangential dashpot is off",
                      s.warning.empty() ? "" : "; ", p.et, dt, p.tc / dt, et(lo));
        s.warning += buf;
        }
        hi = lo;
    }
    if (et(hi) > p.et) {
        std::snprintf(buf, sizeof buf, "et %g is below what any tangential dashpot reaches at dt %g s (tc/dt %.2f)",
                      p.et, dt, p.tc / dt);
        s.failure = buf;
        return s;
    }
    for (int it = 0; it < 100 && hi - lo > 1e-13 * hi; ++it) {
        const double mid = 0.5 * (lo + hi);
        (et(mid) > p.et ? lo : hi) = mid;
    }
    s.unit = tangential(0.5 * (lo + hi));
    s.achieved = phaseAveragedCollision(s.unit, dt, limitForce);
    return s;
}

}  // namespace viscoelastic
