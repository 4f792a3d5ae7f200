// `exactCollision on`: every single binary collision restitutes what the
// continuous law restitutes, whatever the phase at which it starts within a
// step and whatever the timestep (below the stability limit).
//
// The error of a single collision comes from three places, each removed here:
//  - inside the contact the leapfrog map of the linear law is not the exact
//    flow over a step. The linear law F = kStep x_n + cStep v_{n-1/2} (per
//    unit mass) whose leapfrog map IS the exact flow exists in closed form:
//    two samples of a damped oscillator obey x_{n+1} = a x_n - b x_{n-1}
//    with a = 2 e^(-c dt/2) cos(w dt), b = e^(-c dt), so
//    kStep = (1 + b - a) / dt^2 and cStep = (1 - b) / dt;
//  - the contact starts between two steps: at its first overlapping step
//    the overlap x1 and the approach rate v0 give the time since first
//    touch, s = x1 / v0 (free flight), and the continuous contact X from
//    (0, v0) is at X(s), not x1, as the flight felt no force. The first
//    force puts the next sample on X(s + dt); the second step takes X(s) as
//    its previous sample (one number kept for one step);
//  - it ends between two steps: the samples give the continuous state, and
//    when the overlap (or, with limitForce, the force) reaches zero within the
//    coming step at s_e, the last force makes the rate after the step the
//    exit rate X'(s_e).
// Friction follows the law's instantaneous cap mu |Fn(t)| through the step
// (cappedFlow, below): where the spring stays clear of the cap one step on,
// and its excess over the cap, extrapolated from either end of the step at
// its rate there, too, the step is the plain law and a check; a step that
// may reach the cap runs out of line and finds every event inside it. A
// contact between two steps is otherwise untouched: a few multiplications
// and comparisons per step more than the plain law (more with a pull,
// between two spheres); the start and end need a few transcendental
// evaluations, once per contact.
//
// Per unit mass; the LIGGGHTS model multiplies by meff. State per contact:
// its phase (fresh, touching, ended), kept in the contact history.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "exact.h"
#include "law.h"
#include "pournin.h"

namespace viscoelastic {

// a x + b y, component-wise: as an Eigen expression in the per-step code the
// compiler calls its loop out of line (about 15 instructions a call).
inline Vec3 combine(double a, const Vec3& x, double b, const Vec3& y)
{
    return Vec3(a * x[0] + b * y[0], a * x[1] + b * y[1], a * x[2] + b * y[2]);
}

// Position and rate of a free damped oscillator x'' = -k x - c x'.
struct Motion {
    double x, u;
};

struct FreeOscillator {
    double k = 0, c = 0, lambda = 0, omega = 0;  // omega: damped frequency, sqrt(k - c^2/4)

    FreeOscillator() = default;
    FreeOscillator(double k_, double c_) : k(k_), c(c_), lambda(0.5 * c_), omega(std::sqrt(k_ - 0.25 * c_ * c_)) {}

    // The flow over tau (tau may be negative): its transcendental part, shared
    // by every motion taken over the same tau.
    struct Flow {
        double e, co, si;  // e^(-lambda tau), cos(omega tau), sin(omega tau) / omega
    };
    Flow flow(double tau) const { return {std::exp(-lambda * tau), std::cos(omega * tau), std::sin(omega * tau) / omega}; }
    Motion after(Motion m, const Flow& f) const
    {
        return {f.e * (m.x * f.co + (m.u + lambda * m.x) * f.si), f.e * (m.u * f.co - (lambda * m.u + k * m.x) * f.si)};
    }
    // The motion tau later.
    Motion after(Motion m, double tau) const { return after(m, flow(tau)); }
    // What ends a contact: the overlap, or with limitForce the force k x + c u.
    double ending(Motion m, bool force) const { return force ? k * m.x + c * m.u : m.x; }
    // The rate of the force k x + c u along the motion (x'' = -k x - c u).
    double forceRate(Motion m) const { return k * m.u + c * (-k * m.x - c * m.u); }
    // The first zero of the force at or after `from` along the motion through
    // m (at 0). The force of a free damped oscillator is itself one,
    // e^(-lambda t) (F0 cos w t + G sin w t) with G = (F0' + lambda F0) / w:
    // its zeros lie at w t = atan2(-F0, G) + n pi.
    double forceZeroFrom(Motion m, double from) const
    {
        const double f0 = ending(m, true), half = kPi / omega;
        const double zero = std::atan2(-f0, (forceRate(m) + lambda * f0) / omega) / omega;
        return zero + half * std::ceil((from - zero) / half);
    }
};

// One oscillator at one timestep: everything a contact needs per step.
struct StepLaw {
    FreeOscillator o;
    double dt = 0;
    bool forceEnds = false;     // limitForce: the contact ends when k x + c u reaches 0
    double kStep = 0, cStep = 0;  // the leapfrog-exact law inside the contact
    double uX = 0, uV = 0;      // continuous rate at a sample: u = uX x_n + uV v_{n-1/2}
    double endX = 0, endV = 0;  // what ends the contact, one step on: endX x_n + endV v_{n-1/2}
    // Inside the contact: the continuous force half a step on (aheadX x_n +
    // aheadV v_{n-1/2}), and its mean over the step's half-step interval,
    // (u(-dt/2) - u(dt/2)) / dt = frictionX x_n + frictionV v_{n-1/2}.
    double aheadX = 0, aheadV = 0, frictionX = 0, frictionV = 0;
    // The same with a pull: x'' = -F - pull, F the law's force. The motion of
    // x + pull / k is then free, so each of the four above gains a term in
    // the pull (endA, aheadA, frictionA), and the leapfrog-exact force one,
    // forceA pull (kStep / k - 1: -3 % of the pull at tc/5).
    double endA = 0, aheadA = 0, frictionA = 0, forceA = 0;
    // The law's force along the continuous motion at this sample and one step
    // on (X x_n + V v_{n-1/2} + A pull): where the tangential cap mu |Fn| stands.
    double nowX = 0, nowV = 0, nowA = 0, nextX = 0, nextV = 0, nextA = 0;
    // As a tangential oscillator: the force k xi + c u one step on from the
    // spring and rate the step law gives there (phiX xi_{n+1} + phiV w_{n+1/2}),
    // and its rate k u - c (k xi + c u) (phiRateX xi_{n+1} + phiRateV w_{n+1/2}).
    double phiX = 0, phiV = 0, phiRateX = 0, phiRateV = 0;
    // What ends the contact, one step on, must exceed endMargin x_n to go on:
    // a next sample on the surface within round-off would fall to or below
    // zero in the leapfrog, and the end step (its exit rate, its friction)
    // would never run. The common step tests endX - endMargin (endGoX).
    double endMargin = 0, endGoX = 0;
    // The force's rate one step on along a free motion m (of x + pull / k):
    // rateStepX m.x + rateStepU m.u.
    double rateStepX = 0, rateStepU = 0;
    double inverseDt = 0;
    // The flows over -dt/2, dt/2 and dt: a contact's start and end take the
    // motion there without a transcendental evaluation.
    FreeOscillator::Flow flowBack{}, flowHalf{}, flowStep{};
    // An ended contact whose overlap would take longer than this to close at
    // its rate is held by other contacts (set by stepLaw from binary
    // collisions at 65 start phases: 1.5 times the longest they take, and at
    // least half a step).
    double heldAfter = 1e300;
};

// The laws of a contact at this timestep; defined below exactCollisionStep,
// which it runs to bound how long an ended binary contact takes to close.
inline StepLaw stepLaw(double k, double c, double dt, bool forceEnds);

namespace detail {

inline StepLaw stepLawCoefficients(double k, double c, double dt, bool forceEnds)
{
    StepLaw s;
    s.o = FreeOscillator(k, c);
    s.dt = dt, s.forceEnds = forceEnds;
    const double e = std::exp(-s.o.lambda * dt), co = std::cos(s.o.omega * dt), si = std::sin(s.o.omega * dt);
    const double a = 2.0 * e * co, b = e * e;
    s.kStep = (1.0 + b - a) / (dt * dt);
    s.cStep = (1.0 - b) / dt;
    // The sample before is x_n - dt v; the oscillator through both samples
    // has, at x_n, the rate u = -lambda x_n + omega (x_n cos - x_{n-1} e) / sin.
    s.uX = -s.o.lambda + s.o.omega * (co - e) / si;
    s.uV = s.o.omega * e * dt / si;
    const double h = 0.5 * dt;
    s.flowBack = s.o.flow(-h), s.flowHalf = s.o.flow(h), s.flowStep = s.o.flow(dt);
    // One step on, by linearity: the motion from (1, uX) and from (0, uV).
    const Motion fromX = s.o.after({1.0, s.uX}, s.flowStep), fromV = s.o.after({0.0, s.uV}, s.flowStep);
    s.endX = s.o.ending(fromX, forceEnds);
    s.endV = s.o.ending(fromV, forceEnds);
    const Motion aheadX = s.o.after({1.0, s.uX}, s.flowHalf), aheadV = s.o.after({0.0, s.uV}, s.flowHalf);
    const Motion backX = s.o.after({1.0, s.uX}, s.flowBack), backV = s.o.after({0.0, s.uV}, s.flowBack);
    s.aheadX = s.o.ending(aheadX, true), s.aheadV = s.o.ending(aheadV, true);
    s.frictionX = (backX.u - aheadX.u) / dt, s.frictionV = (backV.u - aheadV.u) / dt;
    s.endA = (s.endX - (forceEnds ? k : 1.0)) / k;
    s.aheadA = s.aheadX / k - 1.0;
    s.frictionA = s.frictionX / k - 1.0;
    s.forceA = s.kStep / k - 1.0;
    s.nowX = k + c * s.uX, s.nowV = c * s.uV, s.nowA = s.nowX / k - 1.0;
    s.nextX = s.o.ending(fromX, true), s.nextV = s.o.ending(fromV, true), s.nextA = s.nextX / k - 1.0;
    s.phiX = s.nowX, s.phiV = s.nowV;
    s.phiRateX = k * s.uX - c * s.phiX, s.phiRateV = k * s.uV - c * s.phiV;
    s.endMargin = 1e-9 * (forceEnds ? k : 1.0);
    s.endGoX = s.endX - s.endMargin;
    s.rateStepX = s.o.forceRate(s.o.after({1.0, 0.0}, s.flowStep));
    s.rateStepU = s.o.forceRate(s.o.after({0.0, 1.0}, s.flowStep));
    s.inverseDt = 1.0 / dt;
    return s;
}

}  // namespace detail

// `attractive`: still touching, past the zero of the force (limitForce off).
// `held`: ended by the binary law but pressed on by other contacts (a
// packing): the plain step law until the bodies part. `leaving`: ended, with
// a second kick due (a pull that alone parts the bodies faster than the law).
enum class CollisionPhase { fresh = 0, touching = 1, ended = 2, attractive = 3, held = 4, leaving = 5 };

// What a contact keeps between steps.
struct CollisionState {
    CollisionPhase phase = CollisionPhase::fresh;
    // After the first step: the continuous overlap at that step minus the
    // actual one (the free flight into the contact felt no force); the
    // second step takes it as its previous sample. After the end step: the
    // time the free flight it set had left to part the bodies.
    double previousOffset = 0;
};

struct CollisionStep {
    double force = 0;        // per unit mass, along the normal (positive: repulsive)
    double sinceStart = -1;  // first step: time since first touch [s] (else < 0)
    double endsAfter = -1;   // last step: time from this step to the end of the contact [s] (else < 0)
    // A held contact's friction bound (the others follow the cap through the
    // step): mu times `friction`, the mean of |Fn| (per unit mass) over the
    // part of the continuous contact the step stands for (first touch or the half step before, to the half
    // step after or the end). The steps' parts tile the contact, so in gross
    // sliding the friction impulse is mu times the integral of |Fn| exactly.
    // (The step's own force is not that mean: it nets the repulsive and
    // attractive parts where the force turns, and it corrects the start.)
    double friction = 0;
    // For the tangential cap: whether the contact follows the continuous
    // motion (not held, not ended), that motion at this sample (of x + pull /
    // k, free), the pull, and the law's force (per unit mass) at this sample
    // and one step on.
    bool continuous = false;
    Motion now{0.0, 0.0};
    double pull = 0, forceNow = 0, forceNext = 0;
    double forceScale = 0;  // the size of forceNow's terms, for comparing it with a forecast
    double meff = 1;  // the mass the caller scales these by (the cap is mu meff |Fn|)
};

namespace detail {

// tau in [lo, hi] with f(tau) = 0, f(lo) and f(hi) of opposite signs or zero:
// secant steps kept inside the bracket, every third step a bisection.
template <class F>
double bracketedRoot(F f, double lo, double hi)
{
    double flo = f(lo), fhi = f(hi);
    if (flo == 0.0) return lo;
    if (fhi == 0.0) return hi;
    for (int it = 0; it < 60 && hi - lo > 1e-14 * (std::fabs(lo) + std::fabs(hi)); ++it) {
        double t = lo - flo * (hi - lo) / (fhi - flo);
        if (!(t > lo && t < hi) || it % 3 == 2) t = 0.5 * (lo + hi);
        const double ft = f(t);
        if (ft == 0.0) return t;
        if ((ft > 0) == (flo > 0)) lo = t, flo = ft;
        else hi = t, fhi = ft;
    }
    return 0.5 * (lo + hi);
}

// The same for f with its slope: (f, f') = fs(tau), given f(lo) and a first
// guess (the secant's, from f at both ends, saves a step or two). Newton
// steps kept inside the bracket, bisection when one leaves it. A Newton step
// of 1e-10 of the bracket leaves an error of order its square (the roots are
// simple, f'' / f' ~ 1 / tc): round-off. Asking for the step itself to reach
// round-off cost two to three more evaluations per root (each an exp and a
// sincos) on the dense column.
template <class FS>
double bracketedNewton(FS fs, double lo, double hi, double flo, double t)
{
    if (flo == 0.0) return lo;
    if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);
    const double tolerance = 1e-10 * (hi - lo), collapsed = 1e-15 * (std::fabs(lo) + std::fabs(hi));
    for (int it = 0; it < 60; ++it) {
        const auto [f, df] = fs(t);
        if (f == 0.0) return t;
        if ((f > 0) == (flo > 0)) lo = t, flo = f;
        else hi = t;
        const double next = t - f / df;
        if (next > lo && next < hi) {
            if (std::fabs(next - t) < tolerance) return next;
            t = next;
        } else {
            t = 0.5 * (lo + hi);
        }
        if (hi - lo < collapsed) return t;
    }
    return t;
}

// tau in [lo, hi] with f(tau) = 0, f(lo) <= 0 < f(hi): regula falsi with
// the Illinois modification (superlinear), until a step moves tau by less
// than 1e-10 of the bracket (an error of order its square: round-off).
// f(lo) = 0 (on the cap, leaving it below) bisects until f is negative.
template <class F>
double illinoisRoot(F f, double lo, double hi, double flo, double fhi)
{
    const double tolerance = 1e-10 * (hi - lo);
    double t = lo;
    int side = 0;
    for (int it = 0; it < 80; ++it) {
        double next = (flo == 0.0 || flo == fhi) ? 0.5 * (lo + hi) : lo - flo * (hi - lo) / (fhi - flo);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        const double moved = std::fabs(next - t);
        t = next;
        const double ft = f(t);
        if (ft == 0.0) return t;
        if (ft > 0.0) {
            hi = t, fhi = ft;
            if (side == -1) flo *= 0.5;
            side = -1;
        } else {
            lo = t, flo = ft;
            if (side == 1) fhi *= 0.5;
            side = 1;
        }
        if ((it > 0 && moved < tolerance) || hi - lo < tolerance) return t;
    }
    return t;
}

}  // namespace detail

// A contact first seen with overlap x1 and approach rate v0 touched x1 / v0
// ago: before this step it flew freely. More than this bound of a step ago
// means it did not just touch (a contact created overlapping, at the start of
// a run or after a restart without contact history): it is then taken as
// under way, uncorrected.
constexpr double kFreshTouchSteps = 1.5;

// The mean of |F| over [lo, hi] along the continuous motion `now` (of
// x + pull / k, which is free; F = k x + c u - pull along it), per step:
// |u(lo) - u(hi) - pull (hi - lo)| / dt, split where the force turns
// attractive (limitForce off), which marks the contact `attractive` from then
// on; [lo, hi] (under half a period) holds one zero of the force. a and b:
// the motion at lo and hi (the caller often has them).
inline double frictionBetween(const StepLaw& law, CollisionState& state, const Motion& now, const Motion& a,
                              const Motion& b, double lo, double hi, double pull)
{
    const FreeOscillator& o = law.o;
    const auto impulse = [&](const Motion& p, const Motion& q, double span) { return std::fabs(p.u - q.u - pull * span); };
    const double meanForce = impulse(a, b, hi - lo) / law.dt;
    const double fb = o.ending(b, true) - pull;  // the force at hi
    if (law.forceEnds || state.phase == CollisionPhase::attractive || !(fb < 0.0)) return meanForce;
    state.phase = CollisionPhase::attractive;
    const double fa = o.ending(a, true) - pull;
    if (!(fa > 0.0)) return meanForce;
    double zero = pull == 0.0 ? o.forceZeroFrom(now, lo) : hi + 1.0;
    if (!(zero <= hi)) {
        const auto forceAndRate = [&](double t) {
            const Motion m = o.after(now, t);
            return std::make_pair(o.ending(m, true) - pull, o.forceRate(m));
        };
        zero = detail::bracketedNewton(forceAndRate, lo, hi, fa, lo + (hi - lo) * fa / (fa - fb));
    }
    const Motion least = o.after(now, zero);  // where the force turns
    return (impulse(a, least, zero - lo) + impulse(least, b, hi - zero)) / law.dt;
}

// The same over this step's half-step interval [-dt/2, dt/2]. Out of line:
// the common step calls it only where the force turns.
[[gnu::noinline]] inline double frictionOverStep(const StepLaw& law, CollisionState& state, const Motion& now,
                                                 double pull)
{
    const double h = 0.5 * law.dt;
    return frictionBetween(law, state, now, law.o.after(now, law.flowBack), law.o.after(now, law.flowHalf), -h, h, pull);
}

namespace detail {

// Free flight under the pull: the time to cover overlap x at rate c at its
// near end (c + pull t at time t), x = c t + pull t^2 / 2 -- the time since
// first touch at a contact's first step, the time an ended contact takes to
// part. 0 at x = 0; infinite if nothing closes it.
inline double freeFlightTime(double x, double c, double pull)
{
    if (!(x > 0.0)) return 0.0;
    const double closing = c + std::sqrt(c * c + 2.0 * pull * x);
    return closing > 0.0 ? 2.0 * x / closing : HUGE_VAL;
}

// The end kick (on this step's normal) after which the free flight parts the
// bodies at rate sqrt(target): with |v| and the pair's angular momentum kept,
// where the overlap x closes the rate has grown to sqrt(u+^2 + 2 pull x).
// The contact is then `ended`, keeping the time that flight takes to part.
inline void partingKick(const StepLaw& law, CollisionState& state, double x, double v, double pull, double target,
                        CollisionStep& r)
{
    const double leave = std::sqrt(std::max(target - 2.0 * pull * x, 0.0));
    r.force = (v - 0.5 * law.dt * pull + leave) / law.dt;
    const double parting = freeFlightTime(x, leave, pull);
    state.previousOffset = std::isfinite(parting) ? parting : 0.0;
    state.phase = CollisionPhase::ended;
}

// A held contact's step: the plain step law through this sample and the one
// before, its friction bound the law's mean force over the step.
inline CollisionStep heldStep(const StepLaw& law, double x, double v)
{
    CollisionStep r;
    r.force = law.kStep * x + law.cStep * v;
    r.friction = std::fabs(law.frictionX * x + law.frictionV * v);
    return r;
}

// exactCollisionStep's other steps: a contact's first and last, one that
// starts again after it ended, one created overlapping. Kept out of the
// common step, which they would otherwise crowd with their transcendental
// evaluations.
[[gnu::noinline]] inline CollisionStep exactCollisionEnds(const StepLaw& law, CollisionState& state, double x, double v,
                                                          double pull)
{
    const double dt = law.dt;
    CollisionStep r;
    if (state.phase == CollisionPhase::leaving) {
        // the end step's second kick (below): previousOffset holds the
        // parting rate squared
        partingKick(law, state, x, v, pull, state.previousOffset, r);
        return r;
    }
    if (state.phase == CollisionPhase::ended) {
        // The continuous contact is over: no force while the overlap closes as
        // a binary contact's does after its end. One that would take longer
        // than heldAfter to close is held by other contacts (a packing): from
        // then on it is no binary contact, and the plain step law applies
        // until the bodies part, with no end step (its exit kick would
        // start the cycle again: ended, held, ended, thousands of times in a
        // settled column at en 0.95 and dt/tc 0.3, which gained 30-70 times
        // its kinetic energy; with no force while held, 150 times at 0.25).
        // (the rate at this step: the pull turns it from the samples' rate.)
        // A binary contact with a pull parts in the free flight its end step
        // set (previousOffset: the time it had left); it is held only if it
        // takes longer than half as much again, or than heldAfter.
        const double closing = 0.5 * dt * pull - v;
        state.previousOffset -= dt;
        if (!(closing < 0.0)) {
            if (freeFlightTime(x, closing, pull) <= std::max(law.heldAfter, 1.5 * state.previousOffset)) return r;
            state.phase = CollisionPhase::held;
            return heldStep(law, x, v);
        }
        state.phase = CollisionPhase::fresh;  // approaching again: a new contact
        state.previousOffset = 0.0;           // (it held the parting time)
    }
    // The continuous motion at this step, of x + shift: free (x'' = -F - pull).
    const double shift = pull / law.o.k;
    Motion now, touch;
    if (state.phase == CollisionPhase::fresh && v > 0.0 && x <= kFreshTouchSteps * v * dt) {
        // free flight before: x = vh s + pull s^2 / 2 with vh the rate
        // LIGGGHTS gives, and the rate at touch vh + pull s
        const double vh = v - 0.5 * dt * pull;
        const double s = freeFlightTime(x, vh, pull);
        r.sinceStart = s;
        touch = {shift, vh + pull * s};
        now = law.o.after(touch, s);
        state.previousOffset = now.x - shift - x;
    } else {
        // under way: the previous sample and this one define the motion
        const double vUsed = v - state.previousOffset * law.inverseDt;
        state.previousOffset = 0.0;
        now = {x + shift, law.uX * (x + shift) + law.uV * vUsed};
    }
    if (state.phase != CollisionPhase::attractive) state.phase = CollisionPhase::touching;
    r.continuous = true, r.now = now, r.pull = pull;
    r.forceNow = law.o.ending(now, true) - pull;
    r.forceScale = std::fabs(law.o.k * now.x) + std::fabs(law.o.c * now.u);
    // this step's part of the contact: from the touch, or half a step back
    const double from = r.sinceStart >= 0.0 ? -r.sinceStart : -0.5 * dt;
    const Motion start = r.sinceStart >= 0.0 ? touch : law.o.after(now, law.flowBack);
    const auto endingAndSlope = [&](const Motion& m) {
        return law.forceEnds ? std::make_pair(law.o.ending(m, true) - pull, law.o.forceRate(m))
                             : std::make_pair(m.x - shift, m.u);
    };
    // (the leapfrog moves the rate by -dt (force + pull))
    const Motion ahead = law.o.after(now, law.flowStep);
    const double endAhead = endingAndSlope(ahead).first;
    r.forceNext = law.o.ending(ahead, true) - pull;
    if (endAhead > law.endMargin * x) {  // on along the continuous motion: the next sample lies on it
        r.force = (v - (ahead.x - shift - x) / dt) / dt - pull;
        r.friction = frictionBetween(law, state, now, start, law.o.after(now, law.flowHalf), from, 0.5 * dt, pull);
        return r;
    }
    // The contact ends within this step: leave at the continuous exit rate.
    const double endNow = endingAndSlope(now).first;
    const double tau = endNow <= 0.0 ? 0.0
                                     : detail::bracketedNewton([&](double t) { return endingAndSlope(law.o.after(now, t)); },
                                                               0.0, dt, endNow, dt * endNow / (endNow - endAhead));
    r.endsAfter = tau;
    // The continuous contact parts with u_end^2 + 2 pull x_end (x_end: the
    // overlap left at the end of the force, zero for the overlap's end; to
    // x / d): the kick gives that rate where the overlap closes.
    const Motion end = law.o.after(now, tau);
    r.friction = frictionBetween(law, state, now, start, end, from, tau, pull);
    const double target = end.u * end.u + 2.0 * pull * (end.x - shift);
    if (target < 2.0 * pull * x) {
        // The pull alone parts the bodies from x faster than the law: no kick
        // here can give that rate. Land the next sample where it does,
        // target / (2 pull), and kick again there (phase `leaving`).
        const double x1 = target / (2.0 * pull);
        const double up = (x - x1 - 0.5 * pull * dt * dt) / dt;  // separating rate after this kick
        r.force = (v - 0.5 * dt * pull + up) / dt;
        state.previousOffset = target;
        state.phase = CollisionPhase::leaving;
        return r;
    }
    partingKick(law, state, x, v, pull, target, r);
    return r;
}

}  // namespace detail

// One step of a contact under `exactCollision`: x the overlap at this step,
// v the overlap rate at the half step before (positive while approaching),
// `pull` what else decelerates the overlap (x'' = -F - pull): between two
// spheres the centrifugal |vt|^2 / d of their relative tangential motion
// (vt of the centres, d their distance), which ends a fast oblique contact
// earlier than the law alone; zero on a flat wall.
inline CollisionStep exactCollisionStep(const StepLaw& law, CollisionState& state, double x, double v,
                                        double pull = 0.0)
{
    // The rate LIGGGHTS gives is -(vi - vj).n with the normal of this step,
    // the velocities of the half step before: with a turning normal that is
    // the samples' rate (x_n - x_{n-1}) / dt less pull dt / 2.
    v += 0.5 * law.dt * pull;
    // A contact under way that goes on past this step: the previous sample
    // and this one define the motion. It costs nine products (five more with a
    // pull) and two comparisons over the plain law.
    const bool attractive = state.phase == CollisionPhase::attractive;
    if (attractive || state.phase == CollisionPhase::touching) {
        const double vUsed = v - state.previousOffset * law.inverseDt;
        if (law.endGoX * x + law.endV * vUsed + law.endA * pull > 0.0) {
            state.previousOffset = 0.0;
            CollisionStep r;
            r.force = (v - vUsed) * law.inverseDt + law.kStep * x + law.cStep * vUsed + law.forceA * pull;
            r.continuous = true, r.pull = pull;
            const double shifted = x + pull / law.o.k;
            r.now = {shifted, law.uX * shifted + law.uV * vUsed};
            r.forceNow = law.nowX * x + law.nowV * vUsed + law.nowA * pull;
            r.forceScale = std::fabs(law.nowX * x) + std::fabs(law.nowV * vUsed);
            r.forceNext = law.nextX * x + law.nextV * vUsed + law.nextA * pull;
            // of the force over the step
            const double mean = law.frictionX * x + law.frictionV * vUsed + law.frictionA * pull;
            if (attractive) r.friction = -mean;
            else if (law.forceEnds || law.aheadX * x + law.aheadV * vUsed + law.aheadA * pull >= 0.0) r.friction = mean;
            else r.friction = frictionOverStep(law, state, r.now, pull);
            return r;
        }
    }
    // a contact held in a packing: the plain step law (no call out of line)
    if (state.phase == CollisionPhase::held) return detail::heldStep(law, x, v);
    return detail::exactCollisionEnds(law, state, x, v, pull);
}

inline StepLaw stepLaw(double k, double c, double dt, bool forceEnds)
{
    StepLaw law = detail::stepLawCoefficients(k, c, dt, forceEnds);
    // After a binary contact's end its overlap closes force-free (limitForce:
    // the whole force-free end; without: what the start's offset and the last
    // part-step leave, at most 2 steps at en 0.02, 0.0004 at en 0.95): the
    // longest this takes over start phases, at the exit rate.
    double longest = 0.0;
    for (int k = 0; k <= 64; ++k) {
        CollisionState state;
        double x = (k < 64 ? (k + 0.5) / 64.0 : 1e-9) * dt, v = 1.0;
        for (int n = 0; x > 0.0 && n < 100000; ++n) {
            if (state.phase == CollisionPhase::ended && v < 0.0) longest = std::max(longest, x / -v);
            v -= dt * exactCollisionStep(law, state, x, v).force;
            x += dt * v;
        }
    }
    law.heldAfter = std::max(1.5 * longest, 0.5 * dt);
    return law;
}

// What one continuous collision does, from first touch with unit approach
// rate: restitution, the time the overlap lasts and the time the force lasts
// (with limitForce the bodies still overlap, force-free, for a while after
// the force ends).
struct ContinuousCollision {
    double restitution, duration, forceDuration;
};

inline ContinuousCollision continuousCollision(const FreeOscillator& o, bool limitForce)
{
    const double half = kPi / o.omega;  // the overlap's zero: exactly tc
    if (!limitForce) return {-o.after({0.0, 1.0}, half).u, half, half};
    // the force k x + c u turns negative after the peak overlap (u < 0), before x returns to 0
    const double peak = std::atan2(o.omega, o.lambda) / o.omega;
    const double tf = o.forceZeroFrom({0.0, 1.0}, peak);
    const Motion m = o.after({0.0, 1.0}, tf);
    return {-m.u, tf + m.x / -m.u, tf};
}

// The tangential spring of a contact under exactCollision: pournin's xi and
// contact-point rate w (the same vector algebra for xi as the normal's x).
// Returns the acceleration of w per step (the tangential force per unit
// tangential mass) and sets xi. First step (normal.sinceStart >= 0): the
// spring the continuous contact has after sinceStart, from (0, w) (the free
// flight's rate), and the force that puts the next sample on it; last step
// (normal.endsAfter >= 0): the force that leaves at the continuous rate at
// the end; otherwise the step-exact law. Sticking: the Coulomb cap is the
// caller's.
namespace detail {

// exactTangentialStep's first and last steps (once per contact each).
template <class V>
V exactTangentialEnds(const StepLaw& law, const CollisionStep& normal, V& xi, const V& w)
{
    const double dt = law.dt;
    if (normal.sinceStart >= 0.0) {
        const double s = normal.sinceStart;
        const Motion atTouch = law.o.after({0.0, 1.0}, s);
        xi = w * atTouch.x;
        const V next = w * law.o.after(atTouch, law.flowStep).x;
        return ((next - xi) / dt - w) / dt;
    }
    // the motion through this sample and the one before, per component;
    // by linearity its rate at the end from the motions from (1, 0) and (0, 1)
    const V rate = law.uX * xi + law.uV * w;
    const FreeOscillator::Flow flow = law.o.flow(normal.endsAfter);
    const V exit = law.o.after({1.0, 0.0}, flow).u * xi + law.o.after({0.0, 1.0}, flow).u * rate;
    return (exit - w) / dt;
}

}  // namespace detail

template <class V>
inline V exactTangentialStep(const StepLaw& law, const CollisionStep& normal, V& xi, const V& w)
{
    // (either, in one test)
    if (std::max(normal.sinceStart, normal.endsAfter) >= 0.0) return detail::exactTangentialEnds(law, normal, xi, w);
    return -(law.kStep * xi + law.cStep * w);  // the common case: inside the contact
}

// What drives exactCollision's tangential spring: a rate U whose change over
// a step is the tangential force alone divided by a mass (so that the spring
// and U are Pournin's oscillator, whose et is exact), and that mass.
// U = s vt - (ri wi + rj wj) x n with s = d / (ri + rj), d the distance of
// the centres:
//  - the spins at the rigid arms r (not LIGGGHTS' r - overlap/2, whose
//    change during the contact would move the contact point of a spinning
//    sphere without any force);
//  - the orbital part vt scaled by s: the orbital angular momentum of the
//    pair, d vt, changes by the tangential force's torque alone (d Ft /
//    meff), while vt itself is fed by the turning normal (vt vn / d: +1.6 %
//    on et for a pair at 1 m/s). Leapfrog keeps that angular momentum
//    exactly, with the positions of one step and the velocities of the half
//    step before (what LIGGGHTS samples), so the steps keep the oscillator.
// Before and after a contact s = 1: U is the contact point's velocity that
// et is measured on. (A spin about the normal still feeds U through the
// turning normal: -6e-5 on et at 500 rad/s in the reference; not corrected.)
// vtr is LIGGGHTS' contact-point velocity, vt - (cri wi + crj wj) x n; a wall
// has mj = 0 (wj, rj, crj unused, s = 1: exact for a flat face; on a mesh
// edge or corner, or a curved wall, the normal turns and U keeps a small
// feed, not corrected).
struct SpringDrive {
    Vec3 rate;    // U [m/s]
    double mass;  // [kg]
};

inline SpringDrive springDrive(const Vec3& vtr, const Vec3& n, double overlap, double meff, double mi, double ri,
                               double cri, const Vec3& wi, double mj, double rj, double crj, const Vec3& wj)
{
    if (!(mj > 0.0)) return {vtr - ((ri - cri) * wi).cross(n), rigidArmMass(meff, mi, ri, cri, 0.0, 0.0, 0.0)};
    const double s = 1.0 - overlap / (ri + rj);
    return {s * vtr - combine(ri - s * cri, wi, rj - s * crj, wj).cross(n), rigidArmMass(meff, mi, ri, cri, mj, rj, crj, s)};
}

// `tangential pournin` under exactCollision: law.h's pourninTangentialForce
// with the first and last steps of exactTangentialStep and the step-exact
// law between. `mt` is the contact's tangential mass, `law` the tangential
// oscillator per unit mt, `normal` what the normal step decided.
inline Vec3 pourninExactTangentialForce(TangentialState& s, const Vec3& n, const Vec3& vt, double mt,
                                        const StepLaw& law, const CollisionStep& normal, double limit, bool advance)
{
    Vec3 xi = s.normal.squaredNorm() > 0.0 ? rotateWithNormal(s.xi, s.normal, n) : s.xi;
    xi += vt * law.dt;
    xi -= xi.dot(n) * n;
    Vec3 f = mt * exactTangentialStep(law, normal, xi, vt);
    const double fmag = f.norm();
    if (fmag > limit) {
        f *= (fmag > 0.0 ? limit / fmag : 0.0);
        // the spring that gives the capped force (scalar reciprocals: one
        // division each instead of one per component)
        xi = -(f * (1.0 / mt) + law.cStep * vt) * (1.0 / law.kStep);
    }
    if (advance) s.xi = xi, s.normal = n;
    return f;
}

// The tangential law with its instantaneous Coulomb cap, followed exactly
// over a step. The continuous law caps the spring's force k xi + c u (per
// unit tangential mass) at kappa |Fn(t)|, Fn the normal force along the
// continuous normal motion (kappa = mu meff / m_t): sticking, (xi, u) is a
// free damped oscillator; sliding in direction s, u' = -kappa |Fn| s and the
// spring sits on the cap, xi = (kappa |Fn| s - c u) / k. Sliding starts where
// |k xi + c u| reaches the cap (before a zero of Fn, which takes the cap to
// zero: without limitForce the spring lets go near the end of every contact
// whatever mu), and stops where the free spring would unload faster than the
// cap falls: k u.s - c cap < cap'. Both pieces are closed forms (the free
// flow; the integrals of Fn along the normal's free motion), joined at the
// roots of those two conditions.
struct TangentialMotion {
    Vec3 xi, u;
};

// The normal contact's continuous motion as the cap sees it.
struct CapSource {
    const FreeOscillator* normal;
    Motion now;    // at 0, of x + pull / k (free)
    double pull;   // Fn = k x + c u - pull along it
    double kappa;  // the cap is kappa |Fn|
    // The step's span and the normal's flow over it, kept per type pair: a
    // step without events takes no transcendental evaluation.
    double span = -1;
    FreeOscillator::Flow spanFlow{};
    Motion at(double t) const
    {
        if (t == 0.0) return now;
        return t == span ? normal->after(now, spanFlow) : normal->after(now, t);
    }
    double force(const Motion& m) const { return normal->ending(m, true) - pull; }
    // The sign of Fn on the interval that starts at m (Fn there): at a zero
    // of Fn, the side it leaves to. A slide keeps the sign of its start up
    // to its end, so at a zero it ends on it takes the side it arrives from.
    double side(const Motion& m, double fn) const { return fn != 0.0 ? fn : normal->forceRate(m); }
    // The cap's rate kappa |Fn|' on the side `side`.
    double capRate(const Motion& m, double side) const
    {
        const double rate = kappa * normal->forceRate(m);
        return side > 0.0 ? rate : -rate;
    }
};

struct CappedFlow {
    TangentialMotion end;
    Vec3 displacement;  // the integral of u: how far the contact point moved
    bool stuck;         // free throughout: the cap never bound
    bool sliding = false;  // sliding at the end
};

namespace detail {

inline TangentialMotion freeTangential(const FreeOscillator& o, const TangentialMotion& m, const FreeOscillator::Flow& f)
{
    return {f.e * (m.xi * f.co + (m.u + o.lambda * m.xi) * f.si), f.e * (m.u * f.co - (o.lambda * m.u + o.k * m.xi) * f.si)};
}

}  // namespace detail

// The rate of the spring's excess over the cap, |phi| - cap, from phi, its
// norm n, its rate and the cap's rate.
inline double excessRate(const Vec3& phi, double n, const Vec3& rate, double capRate)
{
    return (n > 0.0 ? phi.dot(rate) / n : rate.norm()) - capRate;
}

// Whether a function below zero at both ends of a span h (`f` <= 0, `rate`
// its rate there) may reach zero inside: extrapolated from either end at its
// rate there it would (reachesAhead from the start, reachesBack from the
// end). Below both tangents, a hump that is concave (as near its top) stays
// below zero.
inline bool reachesAhead(double f0, double rate0, double h) { return f0 + std::max(rate0, 0.0) * h > 0.0; }
inline bool reachesBack(double f1, double rate1, double h) { return f1 - std::min(rate1, 0.0) * h > 0.0; }
inline bool mayPeak(double f0, double rate0, double f1, double rate1, double h)
{
    return reachesAhead(f0, rate0, h) || reachesBack(f1, rate1, h);
}

namespace detail {

// The first maximum in (t, end) of a function with the given rate (rate0 at
// t), from its rate at the eighths: a root of the rate between a rising and
// the next falling sample; NaN if none. (At the quarters a hump of a quarter
// step next to |phi|'s corner at zero fell between two rising samples: a
// slide and a re-stick inside one step, 1.7e-2 of vt off.)
template <class Rate>
double firstPeak(Rate rate, double t, double end, double rate0)
{
    double before = t, rateBefore = rate0;
    for (int i = 1; i <= 8; ++i) {
        const double tau = i == 8 ? end : t + 0.125 * i * (end - t), r = rate(tau);
        if (rateBefore > 0.0 && r < 0.0)
            return illinoisRoot([&](double s) { return -rate(s); }, before, tau, -rateBefore, -r);
        before = tau, rateBefore = r;
    }
    return std::nan("");
}

// A slide that goes on from the last step: the direction the law's force
// takes over this step. On the cap the law's force F turns toward its loading
// rate g = k u + c a (u the slip, a the change of the drive that no force
// made: a spinning sphere's contact point on the turning normal; over the
// step a = jump / dt, and u its value at mid-step), at the rate
// |g| / cap: tan(angle / 2) falls as exp(-|g| t / cap). The steps see that
// change only as the drive's jump between samples, delta, which the spring's
// force at the step's start shows against the last step's end force:
// phi = forceBefore + (k dt + c) delta. The step slides in the mean direction
// over it, between forceBefore's and g's by the mean of that decay, and ends
// the step on the cap in the direction the decay reaches at its end.
// (Keeping forceBefore's direction plus the jump, the force never turned
// toward the slip: two spinning beads, mu 0.01, got 13 times the law's
// sideways friction at every step.)
struct SlideTurn {
    Vec3 mean, end;
};
inline std::optional<SlideTurn> slidingDirection(const FreeOscillator& o, const Vec3& u, const Vec3& phi,
                                                 const Vec3& forceBefore, double cap, double dt, double span)
{
    const Vec3 jump = (phi - forceBefore) * (1.0 / (o.k * dt + o.c));
    const Vec3 g = o.k * (u + 0.5 * jump) + o.c * jump * (1.0 / dt);  // the slip at mid-step
    const double gn = g.norm(), fn = forceBefore.norm();
    if (!(gn > 0.0) || !(cap > 0.0) || g.dot(forceBefore) <= 0.0) return std::nullopt;
    const double decay = gn * span / cap;  // (span: a last step's, up to the end)
    const double mean = decay > 1e-8 ? -std::expm1(-decay) / decay : 1.0 - 0.5 * decay;  // of exp(-|g| t / cap)
    const Vec3 target = g / gn, before = forceBefore / fn;
    return SlideTurn{(target + mean * (before - target)).normalized(),
                     (target + std::exp(-decay) * (before - target)).normalized()};
}

}  // namespace detail

// The tangential motion from `m` at time a to time b (a <= b, b - a under
// half the normal's period: Fn turns at most once in between). `spanFlow`:
// the tangential flow over src.span, used from a = 0 (a step without events
// then takes no transcendental evaluation).
inline CappedFlow cappedFlow(const FreeOscillator& o, TangentialMotion m, const CapSource& src, double a, double b,
                             const FreeOscillator::Flow* spanFlow = nullptr, bool wasSliding = false,
                             const Vec3& forceBefore = Vec3::Zero())
{
    CappedFlow r{m, Vec3::Zero(), true};
    double t = a;
    Motion mn = src.at(a);
    double fn = src.force(mn);
    const Motion mb = src.at(b);
    const double fb = src.force(mb);
    const auto capAt = [&](double f) { return src.kappa * std::fabs(f); };
    // where Fn turns in (a, b]: b + 1 if it does not
    double zero = b + 1.0;
    if (fn * fb < 0.0) {
        const auto fs = [&](double tau) {
            const Motion q = src.at(tau);
            return std::make_pair(src.force(q), src.normal->forceRate(q));
        };
        zero = detail::bracketedNewton(fs, a, b, fn, a + (b - a) * fn / (fn - fb));
    }
    Vec3 dir = Vec3::Zero();  // the sliding direction, kept through the cap's zero
    Vec3 endDir = Vec3::Zero();  // a slide that goes on: the law's direction at the step's end
    // just stuck again, or just reached the cap: sticking, or sliding,
    // whatever round-off says (a root in time leaves the force off the cap
    // by the root's tolerance times the cap's rate, large for a large mu)
    // A contact that slid at the end of its last step starts on the cap: in a
    // packing the normal motion is sampled afresh each step, and the cap
    // moves with it (a binary contact's does not: the same motion).
    bool restuck = false, onset = false, onCap = wasSliding;
    // sticking again met the cap at once: the slide only grazed the re-stick
    // condition, and goes on to where it really unloads
    bool grazing = false;
    // Sliding on the cap in `dir` while the normal motion goes from `from` to
    // `q`, span later (Fn of one sign): the contact point's rate falls by
    // kappa |int Fn|, its displacement by kappa times the double integral
    // u_n(from) span - (x(q) - x(from)) - pull span^2 / 2.
    const auto slide = [&](const Motion& from, const Motion& q, double span) {
        const double twice = std::fabs(from.u * span - (q.x - from.x) - 0.5 * src.pull * span * span);
        r.displacement += m.u * span - src.kappa * twice * dir;
        m.u -= src.kappa * std::fabs(from.u - q.u - src.pull * span) * dir;
    };
    // (events end where under 1e-12 of the span is left: Fn's zero found
    // within round-off of the span's end otherwise leaves an interval of
    // round-off on which stick and slide alternate)
    const double rest = 1e-12 * (b - a);
    // round-off of the spring's force at the cap's scale over the span
    const double noise = 1e-12 * src.kappa * std::max(std::fabs(fn), std::fabs(fb));
    for (int event = 0; event < 6 && b - t > rest; ++event) {
        const double cap = capAt(fn);
        const Vec3 phi = o.k * m.xi + o.c * m.u;
        const double p = phi.norm();
        bool sliding = false, leaves = false;
        if (onset || onCap || (!restuck && p >= cap * (1.0 - 1e-9))) {
            // at the cap's zero the force is zero up to round-off, whose
            // direction is noise: the slide keeps its direction through it;
            // one that starts there (onset) takes the direction the spring
            // loads in, k u - c phi (with mu = 0 on a spinning sphere, a
            // direction kept from before could face u: the slide stopped
            // at once, stick and slide alternating at one instant)
            // (a direction from round-off, as a head-on contact's at Fn's
            // zero, would slide it along the normal: below `noise`, none)
            if (p > std::max(1e-9 * (o.k * m.xi.norm() + o.c * m.u.norm()), noise)) dir = phi / p;
            else if (onset || dir.squaredNorm() == 0.0) {
                const Vec3 loads = o.k * m.u - o.c * phi;
                if (loads.norm() * (b - a) > noise) dir = loads.normalized();
            }
            endDir = Vec3::Zero();  // (a later slide in the step has its own direction)
            if (onCap && forceBefore.squaredNorm() > 0.0) {
                if (const auto turn = detail::slidingDirection(o, m.u, phi, forceBefore, cap, src.span, b - a))
                    dir = turn->mean, endDir = turn->end;
            }
            if (p > cap || (onCap && dir.squaredNorm() > 0.0)) m.xi = (cap * dir - o.c * m.u) / o.k, r.stuck = false;  // onto the cap
            sliding = onset || o.k * m.u.dot(dir) - o.c * cap > src.capRate(mn, src.side(mn, fn));
            leaves = !sliding;
        }
        // on the cap and leaving it (stuck again, or the spring unloads from
        // it: at Fn's zero, where the cap then grows faster than the spring
        // loads, it sticks there; without this it slid on at once)
        const bool justRestuck = restuck || leaves;
        restuck = onset = onCap = false;
        const double end = t < zero ? std::min(zero, b) : b;
        // the normal motion at `end` (b's is at hand)
        const auto normalAt = [&](double tau) { return tau == b ? mb : src.at(tau); };
        if (!sliding) {
            const double t0 = t;
            const auto free = [&](double tau) {
                return detail::freeTangential(o, m, (spanFlow && t0 == 0.0 && tau == src.span) ? *spanFlow : o.flow(tau - t0));
            };
            // the cap at tau: exactly zero at Fn's zero (where the root's
            // round-off times a large mu could otherwise exceed the spring)
            const auto capThen = [&](double tau) { return tau == zero ? 0.0 : capAt(src.force(normalAt(tau))); };
            const auto over = [&](double tau) {  // |k xi + c u| over the cap at tau
                const TangentialMotion q = free(tau);
                return (o.k * q.xi + o.c * q.u).norm() - capThen(tau);
            };
            const TangentialMotion q = free(end);
            const double overEnd = (o.k * q.xi + o.c * q.u).norm() - capThen(end);
            double to = end;
            // The spring may meet the cap inside the step and leave it again
            // before the end (a wall contact at tc/4.5 sliding from 0.55 to
            // 0.73 of its duration, then again from 0.94): the excess then
            // peaks inside. Where it might (mayPeak; after a re-stick it first
            // falls, then may rise), its rate at the eighths brackets the
            // first peak: a slide from before it, or, below the cap there,
            // the rest from it. (Times are relative to the step: the first
            // step's span is negative, hence NaN for "none".)
            double from = t, overFrom = justRestuck ? 0.0 : std::min(p - cap, 0.0);
            double peak = std::nan(""), overPeak = 0.0;
            {  // (up to Fn's zero too, where over is |phi|)
                const double side = src.side(mn, fn);
                const auto overRate = [&](double tau) {  // d/dtau of `over`
                    const TangentialMotion w = free(tau);
                    const Vec3 f = o.k * w.xi + o.c * w.u;
                    return excessRate(f, f.norm(), o.k * w.u - o.c * f, src.capRate(normalAt(tau), side));
                };
                const double rate0 = justRestuck ? 0.0 : overRate(t);
                if (justRestuck || mayPeak(overFrom, rate0, overEnd, overRate(end), end - t) ||
                    phi.dot(o.k * q.xi + o.c * q.u) < 0.0) {  // |phi| has a corner at zero
                    peak = detail::firstPeak(overRate, t, end, rate0);
                    if (!std::isnan(peak)) overPeak = over(peak);
                }
                if (!std::isnan(peak) && !(overPeak > 1e-12 * capThen(peak)))  // below the cap there
                    from = peak, overFrom = std::min(overPeak, 0.0), peak = std::nan("");
            }
            if (!std::isnan(peak)) {
                to = detail::illinoisRoot(over, t, peak, overFrom, overPeak);
                r.stuck = false, onset = true;
            } else if (overEnd > 0.0) {
                // already at the cap (round-off): sliding from here, without a
                // root -- but not just after sticking again, where the free
                // spring first unloads and meets the cap later in the step.
                // There the spring starts on the cap, its excess over it
                // second order in time and, within the re-stick root's
                // tolerance, round-off of either sign (1e-16 of the cap): the
                // root starts from zero, bisecting to the first negative
                // excess, not from that round-off (a root at the start, then
                // sliding again: 3.2e-3 of vt off at one phase of 7,680 in
                // tests/contact_models/test_collision)
                to = (!justRestuck && from == t && p >= cap * (1.0 - 1e-9))
                         ? t
                         : detail::illinoisRoot(over, from, end, overFrom, overEnd);
                r.stuck = false, onset = true;
                grazing = justRestuck && to - t <= 1e-9 * (end - t);
            }
            r.sliding = false;
            const TangentialMotion next = to == end ? q : free(to);
            r.displacement += next.xi - m.xi;
            m = next, t = to;
        } else {
            // sliding: u(tau) = u(t) - kappa s I1, I1 = |int_t^tau Fn| (Fn of one sign)
            r.stuck = false;
            const Motion from = mn;
            const double t0 = t;
            const auto impulse = [&](const Motion& q, double tau) { return std::fabs(from.u - q.u - src.pull * (tau - t0)); };
            // Fn keeps one sign over the slide (t, end]: at its end (Fn's zero, or
            // the force's end with limitForce) the cap's rate is the one it
            // arrives with, falling, not the one it leaves zero with
            const double side = src.side(mn, fn);
            const auto unloadAt = [&](const Motion& q, double tau) {  // > 0: still sliding at tau
                const double f = tau == zero ? 0.0 : src.force(q);
                const double u = m.u.dot(dir) - src.kappa * impulse(q, tau);
                return o.k * u - o.c * capAt(f) - src.capRate(q, side);
            };
            const auto unload = [&](double tau) { return unloadAt(normalAt(tau), tau); };
            double to = end;
            Motion q = normalAt(end);
            const double unloadEnd = unloadAt(q, end);
            const double here = grazing ? 0.0 : unloadAt(mn, t);
            // Still sliding at the end, the spring may have stuck in between
            // (a cap falling fast near the end holds a spring that stuck
            // before): the condition then dips inside (as the excess peaks).
            double dip = std::nan(""), unloadDip = 0.0;
            if (unloadEnd > 0.0 && here > 0.0) {
                const auto unloadRate = [&](double tau) {  // d/dtau of `unload`
                    const Motion n = normalAt(tau);
                    const double f = tau == zero ? 0.0 : src.force(n), df = src.normal->forceRate(n);
                    const double ddf = -src.normal->k * (f + src.pull) - src.normal->c * df;
                    return -o.k * capAt(f) - (side > 0.0 ? src.kappa : -src.kappa) * (o.c * df + ddf);
                };
                const double rate0 = unloadRate(t);
                if (mayPeak(-here, -rate0, -unloadEnd, -unloadRate(end), end - t)) {
                    dip = detail::firstPeak([&](double tau) { return -unloadRate(tau); }, t, end, -rate0);
                    if (!std::isnan(dip) && !((unloadDip = unload(dip)) < 0.0)) dip = std::nan("");
                }
            }
            if (!std::isnan(dip) || !(unloadEnd > 0.0)) {
                const double until = std::isnan(dip) ? end : dip, last = std::isnan(dip) ? unloadEnd : unloadDip;
                to = (here > 0.0 || grazing)
                         ? detail::illinoisRoot([&](double tau) { return -unload(tau); }, t, until, -here, -last)
                         : t;
                if (to != end) q = src.at(to);
                restuck = true;
            }
            r.sliding = !restuck;
            grazing = false;
            if (to > t) {
                slide(from, q, to - t);
                const Vec3& along = to == b && endDir.squaredNorm() > 0.0 ? endDir : dir;
                m.xi = ((to == zero ? 0.0 : capAt(src.force(q))) * along - o.c * m.u) / o.k;
                t = to;
            }
        }
        mn = normalAt(t);
        fn = t == zero ? 0.0 : src.force(mn);  // exactly at the zero: the cap is zero there
    }
    if (t < b && dir.squaredNorm() > 0.0) {
        // events ran out (stick and slide alternating at one instant, seen
        // between two spinning spheres: the free spring's sideways rate
        // takes it over the cap at once): the rest slides on the cap in the
        // last direction, so the step's force stays within the cap (a free
        // spring here gave 16 times the step's bound)
        for (double until = t < zero && zero < b ? zero : b; t < b; until = b) {
            slide(src.at(t), until == b ? mb : src.at(until), until - t);
            t = until;
        }
        m.xi = (capAt(fb) * dir - o.c * m.u) / o.k, r.stuck = false, r.sliding = true;
    } else if (t < b) {  // (no direction: a free spring, capped at the end)
        const TangentialMotion q = detail::freeTangential(o, m, o.flow(b - t));
        r.displacement += q.xi - m.xi;
        m = q;
        const double cap = capAt(fb);
        const Vec3 phi = o.k * m.xi + o.c * m.u;
        if (phi.norm() > cap) m.xi = (cap * phi.normalized() - o.c * m.u) / o.k, r.stuck = false;
    }
    r.end = m;
    return r;
}

// `tangential pournin` under exactCollision with the cap followed exactly:
// what pourninExactTangentialForce does, where the contact follows the
// continuous normal motion (normal.continuous). The leapfrog's rate over the
// step is the contact point's mean rate, so the next sample lies on the
// continuous spring; where the cap bound within the step the samples no
// longer define the continuous rate, and the state keeps its difference from
// the drive's rate (rateOffset, offPath) for the next step: what moves the
// drive between steps without a force (a spinning sphere's contact point on
// the turning normal) then moves the contact point too, not a force. The
// common step (sticking, on the samples' oscillator, the cap clear one step
// on) costs the plain step law and a check. `muMeff`: mu times the contact's
// meff (the cap per unit Fn).
struct ExactTangentialState {
    Vec3 rateOffset = Vec3::Zero();
    Vec3 force = Vec3::Zero();  // sliding at the end of the last step: the spring's force there (per unit m_t)
    bool offPath = false;
    bool sliding = false;  // on the cap at the end of the last step
    double forecast = 0;   // the normal force the last step's motion gave for this step
};

// Whether the contact's normal force follows the motion its last step
// foresaw: a binary contact does (to round-off); in a packing other contacts move it every step, and the
// continuous motion each step samples afresh is no binary collision's. Such
// a contact gets the per-step bound (cheap), not the cap followed through
// the step, whose events a packing would trigger at every other step (a
// settling column: an event in 17 % of its contact-steps, 1.7 times the
// pair computation's cost).
inline bool followsItsForecast(const CollisionStep& normal, double forecast)
{
    // (a pair's pull, which its friction changes from step to step, moves the
    // force one step on by a fraction of the pull's change: allowed up to half
    // the pull)
    return normal.sinceStart >= 0.0 ||
           std::fabs(normal.forceNow - forecast) <= 1e-3 * normal.forceScale + 0.5 * normal.pull;
}

[[gnu::noinline]] inline Vec3 cappedTangentialStep(ExactTangentialState& e, Vec3& xi, const Vec3& w, const StepLaw& law,
                                                   const StepLaw& normalLaw, const CollisionStep& normal, double kappa)
{
    const double dt = law.dt;
    const CapSource src{&normalLaw.o, normal.now, normal.pull, kappa, dt, normalLaw.flowStep};
    TangentialMotion at;
    bool stuck = true;
    if (normal.sinceStart >= 0.0) {  // from first touch, at the free flight's rate
        const CappedFlow before = cappedFlow(law.o, {Vec3::Zero(), w}, src, -normal.sinceStart, 0.0);
        at = before.end, stuck = before.stuck, e.sliding = before.sliding;
        e.force = law.o.k * at.xi + law.o.c * at.u;
    } else {
        at = {xi, e.offPath ? Vec3(w + e.rateOffset) : Vec3(law.uX * xi + law.uV * w)};
    }
    if (normal.endsAfter >= 0.0) {  // leave at the continuous rate at the end
        const CappedFlow last = cappedFlow(law.o, at, src, 0.0, normal.endsAfter, nullptr, e.sliding, e.force);
        e = {};
        return (last.end.u - w) / dt;
    }
    const CappedFlow step = cappedFlow(law.o, at, src, 0.0, dt, &law.flowStep, e.sliding, e.force);
    e.sliding = step.sliding;
    e.force = step.sliding ? Vec3(law.o.k * step.end.xi + law.o.c * step.end.u) : Vec3::Zero();
    const Vec3 next = step.displacement / dt;  // w_{n+1/2}
    xi = step.end.xi - step.displacement;      // the next step adds dt w_{n+1/2}
    e.offPath = !(stuck && step.stuck);
    e.rateOffset = e.offPath ? Vec3(step.end.u - next) : Vec3::Zero();
    return (next - w) / dt;
}

// The tangential force of a contact under exactCollision. Where the normal
// contact follows its continuous motion, the cap is the law's instantaneous
// mu |Fn(t)| (cappedTangentialStep; the common step inline); held or ended,
// the per-step bound `limit` (mu times the step's mean |Fn|) caps the step
// law's force.
inline Vec3 exactTangentialForce(TangentialState& s, ExactTangentialState& e, const Vec3& n, const Vec3& vt, double mt,
                                 const StepLaw& law, const StepLaw& normalLaw, const CollisionStep& normal,
                                 double muMeff, double limit, bool advance)
{
    if (!normal.continuous || !followsItsForecast(normal, e.forecast)) {
        if (advance) e = {}, e.forecast = normal.forceNext;
        return pourninExactTangentialForce(s, n, vt, mt, law, normal, limit, advance);
    }
    const bool turned = s.normal.squaredNorm() > 0.0;
    Vec3 xi = turned ? rotateWithNormal(s.xi, s.normal, n) : s.xi;
    xi += vt * law.dt;
    xi -= xi.dot(n) * n;
    const double kappa = muMeff / mt;
    Vec3 a;
    bool common = !e.offPath && std::max(normal.sinceStart, normal.endsAfter) < 0.0 && normal.forceNow * normal.forceNext > 0.0;
    if (common) {
        a = -(law.kStep * xi + law.cStep * vt);
        const Vec3 next = vt + law.dt * a, xi1 = xi + law.dt * next;
        const Vec3 phi = combine(law.phiX, xi1, law.phiV, next);
        const double cap = kappa * normal.forceNext;
        common = phi.squaredNorm() <= cap * cap;
        if (common) {
            // clear of the cap at the end, and in between (mayPeak, from the
            // end first; else cappedFlow looks inside)
            const double side = normal.forceNext > 0.0 ? kappa : -kappa, h = law.dt;
            const double n1 = phi.norm();
            const double capRate1 = side * (normalLaw.rateStepX * normal.now.x + normalLaw.rateStepU * normal.now.u);
            const double rate1 = excessRate(phi, n1, combine(law.phiRateX, xi1, law.phiRateV, next), capRate1);
            common = !reachesBack(n1 - std::fabs(cap), rate1, h);
            if (common) {
                const Vec3 phi0 = combine(law.phiX, xi, law.phiV, vt);
                const double n0 = phi0.norm(), capRate0 = side * normalLaw.o.forceRate(normal.now);
                const double rate0 = excessRate(phi0, n0, combine(law.phiRateX, xi, law.phiRateV, vt), capRate0);
                common = !reachesAhead(n0 - std::fabs(kappa * normal.forceNow), rate0, h) && phi0.dot(phi) >= 0.0;
            }
        }
    }
    ExactTangentialState ee = e;
    if (!common) {
        if (turned && ee.offPath) ee.rateOffset = rotateWithNormal(ee.rateOffset, s.normal, n);
        if (turned && ee.sliding) ee.force = rotateWithNormal(ee.force, s.normal, n);
        a = cappedTangentialStep(ee, xi, vt, law, normalLaw, normal, kappa);
    }
    ee.forecast = normal.forceNext;
    if (advance) s.xi = xi, s.normal = n, e = ee;
    return mt * a;
}

// The coefficients a contact under way applies (the step laws), per unit
// meff like pourninUnitCoefficients (the tangential per unit m_t = 2/7 meff):
// what the multi-contact timestep guard and a stock run standing in for the
// law in a packing need.
inline UnitCoefficients appliedCoefficients(const StepLaw& normal, const StepLaw& tangential)
{
    return {normal.kStep, normal.cStep, kTangentialMassRatio * tangential.kStep,
            kTangentialMassRatio * tangential.cStep};
}

// The oscillators whose continuous collision restitutes en and lasts tc
// (overlap), and restitutes et while sticking. Without limitForce those are
// Pournin's (Eq. 3.22-3.25); with it the force ends early, so (tc', en') are
// solved for en and tc, and the tangential oscillator lasts as long as the
// force. Normal per unit meff, tangential per unit tangential mass.
// nullopt: en below what a cut contact restitutes (limitForce).
// The least restitution a cut contact of Pournin's form reaches: its value
// as en' -> 0 (still underdamped), about 0.1365.
constexpr double kLeastEnPrime = 1e-12;
inline double leastCutRestitution()
{
    const Oscillator o = pourninOscillator(1.0, std::log(kLeastEnPrime));
    return continuousCollision(FreeOscillator(o.k, o.c), true).restitution;
}

struct CollisionOscillators {
    FreeOscillator normal, tangential;
};

inline std::optional<CollisionOscillators> exactCollisionOscillators(const ContactParameters& p, bool limitForce)
{
    const auto pair = [](const Oscillator& n) { return FreeOscillator(n.k, n.c); };
    if (!limitForce || p.en >= 1.0) {
        const Oscillator t = pourninOscillator(p.tc, std::log(p.et));
        return CollisionOscillators{pair(pourninOscillator(p.tc, std::log(p.en))), pair(t)};
    }
    // The cut law's restitution depends on en' only (time scales out): solve
    // it, then scale tc' so that the overlap lasts tc. Pournin's oscillator
    // stays underdamped, and its cut restitution falls to about 0.14 only.
    const auto cut = [](double lnE) {
        const Oscillator o = pourninOscillator(1.0, lnE);
        return continuousCollision(FreeOscillator(o.k, o.c), true);
    };
    const double lo = std::log(kLeastEnPrime);
    if (!(cut(lo).restitution < p.en)) return std::nullopt;
    const double lnE = detail::bracketedRoot([&](double z) { return cut(z).restitution - p.en; }, lo, std::log(p.en));
    const FreeOscillator normal = pair(pourninOscillator(p.tc / cut(lnE).duration, lnE));
    // Sticking, the spring runs while the force does: Pournin's tangential
    // oscillator with the force's duration in place of tc restitutes et.
    const double tf = continuousCollision(normal, true).forceDuration;
    return CollisionOscillators{normal, pair(pourninOscillator(tf, std::log(p.et)))};
}

// The single collision as LIGGGHTS integrates it under exactCollision: the
// first overlap phase * v0 * dt (v0 = 1, tangential rate 1, sticking), leapfrog
// steps until the overlap is gone. `followed` is the duration of the
// continuous contact the steps followed: first touch to the end of its force.
struct SteppedCollision {
    double restitution = 0, tangentialRestitution = 0, followed = 0;
    int steps = 0;
};

inline SteppedCollision exactCollisionAtPhase(const StepLaw& normal, const StepLaw& tangential, double phase)
{
    CollisionState state;
    double x = phase * normal.dt, v = 1.0, t = 0, xi = 0.0, w = 1.0;
    const double dt = normal.dt;
    SteppedCollision r;
    while (x > 0.0 && r.steps < 100000) {
        const bool over = state.phase == CollisionPhase::ended;
        const CollisionStep s = exactCollisionStep(normal, state, x, v);
        if (s.sinceStart >= 0.0) t = s.sinceStart;  // the contact began s before this step
        if (s.endsAfter >= 0.0) r.followed = t + r.steps * dt + s.endsAfter;
        xi += dt * w;
        const double a = over ? 0.0 : exactTangentialStep(tangential, s, xi, w);
        w += dt * a;
        v -= dt * s.force;
        x += dt * v;
        ++r.steps;
    }
    r.restitution = -v;
    r.tangentialRestitution = -w;
    return r;
}

// A wall collision with friction under exactCollision, stepped as LIGGGHTS
// steps it: first overlap phase * dt at unit approach rate (normal per unit
// meff), the contact point's tangential rate vt along x, the spring's mass
// mass(x) at overlap x, the cap muMeff |Fn|. Returns the normal and the
// tangential rate after the contact.
struct FrictionalExit {
    double normal, tangential;
};

template <class Mass>
FrictionalExit exactWallCollisionAtPhase(const StepLaw& normal, const StepLaw& tangential, double phase, double vt,
                                         double muMeff, Mass mass)
{
    const double dt = normal.dt;
    CollisionState state;
    TangentialState spring;
    ExactTangentialState exact;
    double x = phase * dt, v = 1.0;
    Vec3 w(vt, 0.0, 0.0);
    const Vec3 n(0.0, 0.0, 1.0);
    for (int steps = 0; x > 0.0 && steps < 100000; ++steps) {
        const CollisionStep s = exactCollisionStep(normal, state, x, v);
        const double mt = mass(x);
        w += dt * exactTangentialForce(spring, exact, n, w, mt, tangential, normal, s, muMeff, muMeff * s.friction, true) / mt;
        v -= dt * s.force;
        x += dt * v;
    }
    return {-v, w[0]};
}

}  // namespace viscoelastic
