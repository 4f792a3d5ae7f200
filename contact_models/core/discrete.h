// A binary collision as LIGGGHTS integrates it, averaged over the phase at
// which the contact starts within a step.
//
// LIGGGHTS advances velocities by half steps and evaluates the contact force
// from positions at step n+1 and velocities at n+1/2. For the normal relative
// motion of one contact (overlap x, overlap rate v, per unit meff) that is
//     v' = v - dt (kn x + cn v),   x' = x + dt v'
// and the same for a sticking tangential contact (overlap xi, velocity w, per
// unit tangential mass). At the first overlapping step stock `history` adds a
// whole step of tangential displacement, vt dt; `pournin` adds only the part
// of the step since the first touch (SpringStart), and restarts its spring
// from zero force where the unclipped normal force changed sign since the
// last step (the cap mu |Fn| passed through zero: timeSinceCapZero). The
// spring stops with the normal contact.
//
// A contact starts between two steps: its first overlap is phase * v0 * dt,
// with the phase uniform in (0, 1] over the many contacts of a flow. Every
// outcome below is a mean over that phase. For a fixed phase the outcome jumps
// where the number of contact steps changes (about cn dt, 10 % at tc/10), so
// the mean is computed exactly: between those breakpoints the recurrence is
// linear in the phase.
#pragma once

#include <algorithm>
#include <cmath>

#include "pournin.h"

namespace viscoelastic {

// How the tangential spring of a contact begins: stock `history` adds vt dt
// at the first overlapping step; `pournin` adds vt times the time since the
// first touch (law.h, timeSinceTouch), in phase with the normal overlap.
enum class SpringStart { wholeStep, atTouch };

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
    int capZero = -1;  // `pournin`: the step at which its spring restarted
    bool sameRegime(const PhaseCollision& o) const
    {
        return steps == o.steps && firstCut == o.firstCut && capZero == o.capZero;
    }
};

inline PhaseCollision discreteCollisionAtPhase(const UnitCoefficients& u, double dt, bool limitForce, double phase,
                                               SpringStart start = SpringStart::wholeStep)
{
    const double mt = kTangentialMassRatio;
    const int maxSteps = static_cast<int>(50.0 * kPi / (std::sqrt(u.kn) * dt)) + 100;  // 50 tc
    double x = phase * dt, v = 1.0;  // normal overlap and rate (v0 = 1)
    // tangential overlap and velocity (w0 = 1); the first step adds dt w
    double xi = start == SpringStart::atTouch ? (phase - 1.0) * dt : 0.0, w = 1.0;
    PhaseCollision r;
    double peak = x, before = 0.0;  // the unclipped normal force at the step before
    while (x > 0.0 && r.steps < maxSteps) {
        const double f = u.kn * x + u.cn * v;
        const bool cut = limitForce && f < 0.0;
        if (cut && r.firstCut < 0) r.firstCut = r.steps;
        // a cut normal force leaves a zero friction limit: the tangential force stops too
        if (r.firstCut < 0) {
            xi += dt * w;
            const double since = start == SpringStart::atTouch ? timeSinceCapZero(before, f, dt) : -1.0;
            if (since >= 0.0 && u.kt > 0.0) xi = -(u.ct / u.kt) * w + w * since, r.capZero = r.steps;
            w -= dt * (u.kt * xi + u.ct * w) / mt;
        }
        before = f;
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

// Adds the integral over the phases [a, b] of an outcome whose regime is
// known at both ends: one regime -> linear, the midpoint is exact; otherwise
// bisect towards the breakpoint(s).
inline void integrateOverPhase(const UnitCoefficients& u, double dt, bool limitForce, SpringStart start, double a,
                               const PhaseCollision& ra, double b, const PhaseCollision& rb, DiscreteCollision& sum)
{
    if (ra.sameRegime(rb) || b - a < 1e-13) {
        accumulate(sum, discreteCollisionAtPhase(u, dt, limitForce, 0.5 * (a + b), start).outcome, b - a);
        return;
    }
    const double m = 0.5 * (a + b);
    const PhaseCollision rm = discreteCollisionAtPhase(u, dt, limitForce, m, start);
    integrateOverPhase(u, dt, limitForce, start, a, ra, m, rm, sum);
    integrateOverPhase(u, dt, limitForce, start, m, rm, b, rb, sum);
}

}  // namespace detail

// Mean over the contact-start phase, uniform in (0, 1]. Sixteen initial
// intervals: a regime that starts and ends inside one of them (it would
// need two breakpoints within 1/16 of a step) is not resolved.
inline DiscreteCollision phaseAveragedCollision(const UnitCoefficients& u, double dt, bool limitForce,
                                                SpringStart start = SpringStart::wholeStep)
{
    constexpr int kIntervals = 16;
    constexpr double kSmallestPhase = 1e-12;  // the phase 0 itself is no contact
    DiscreteCollision sum;
    double a = kSmallestPhase;
    PhaseCollision ra = discreteCollisionAtPhase(u, dt, limitForce, a, start);
    for (int i = 1; i <= kIntervals; ++i) {
        const double b = static_cast<double>(i) / kIntervals;
        const PhaseCollision rb = discreteCollisionAtPhase(u, dt, limitForce, b, start);
        detail::integrateOverPhase(u, dt, limitForce, start, a, ra, b, rb, sum);
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
inline DiscreteCollision sampledCollision(const UnitCoefficients& u, double dt, bool limitForce, int phases,
                                          SpringStart start = SpringStart::wholeStep)
{
    DiscreteCollision sum;
    for (int k = 0; k < phases; ++k)
        detail::accumulate(sum, discreteCollisionAtPhase(u, dt, limitForce, (k + 0.5) / phases, start).outcome,
                           1.0 / phases);
    return sum;
}

inline DiscreteCollision discreteCollision(double tc, double en, double dt, bool limitForce, int phases)
{
    return sampledCollision(pourninUnitCoefficients(tc, en, 1.0), dt, limitForce, phases);
}

}  // namespace viscoelastic
