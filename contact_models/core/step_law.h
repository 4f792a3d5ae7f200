// exactCollision's normal step law (collision.h says why): the leapfrog-exact
// law inside a contact (StepLaw), the first and last steps taken from the
// continuous motion (exactCollisionStep), and what the step laws stand on: the
// continuous collision they follow, the coefficients they apply, the timestep
// guard, the oscillators for a requested en and tc.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "free_flow.h"
#include "pournin.h"
#include "roots.h"
#include "stability.h"

namespace viscoelastic {

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
    // What ends the contact, one step on, must exceed endMargin x_n (and,
    // where the overlap's zero ends it, endPullMargin times the pull's
    // change over the last step) to go on: a next sample that close to the
    // surface may fall to or below zero in the leapfrog, and the end step
    // (its exit rate, its friction) would never run. Round-off does that at
    // endMargin. Between two spheres the next sample lands with the next half
    // step's pull, which the tangential force changes: the pull at this
    // sample (exactCollisionStep's extrapolation) misses it by a fraction of
    // that change; dt^2 / 2 times the change allowed twice (set when the
    // pull was taken as given, half a step late; a grazing pair landed
    // 1.6e-9 m outside, the pull falling 650 m/s^2 a step: it left without
    // its exit rate, 3.1 % off at tc/6; a margin of dt^2 times the pull
    // itself ended a contact whose pull was 1.5 times its force 1.4 steps
    // early, 8 % off). The common step tests endX - endMargin (endGoX).
    double endMargin = 0, endGoX = 0, endPullMargin = 0;
    // What ends the contact kExitPlanned steps on (endPlanX x_n + endPlanV
    // v_{n-1/2} + endPlanA pull): a pair whose contact ends in the next step
    // (within kExitPlanned steps) lands its next sample on the continuous
    // exit line (exactCollisionEnds).
    double endPlanX = 0, endPlanV = 0, endPlanA = 0;
    // The force's rate one step on along a free motion m (of x + pull / k):
    // rateStepX m.x + rateStepU m.u.
    double rateStepX = 0, rateStepU = 0;
    double inverseDt = 0;
    // The flows over -dt/2, dt/2, dt and kExitPlanned dt: a contact's start
    // and end take the motion there without a transcendental evaluation.
    FreeOscillator::Flow flowBack{}, flowHalf{}, flowStep{}, flowPlan{};
    // An ended contact whose overlap would take longer than this to close at
    // its rate is held by other contacts (set by stepLaw from binary
    // collisions at 65 start phases: 1.5 times the longest they take, and at
    // least half a step).
    double heldAfter = 1e300;
};

// The laws of a contact at this timestep; defined below exactCollisionStep,
// which it runs to bound how long an ended binary contact takes to close.
inline StepLaw stepLaw(double k, double c, double dt, bool forceEnds);

// A pair's sample landed on the exit line (landOnExitLine) ends its contact if
// the continuous end lies within kLandedEnd steps of it; else, pushed by other
// contacts, it goes on. The landing is planned where the exit lies within
// kExitPlanned steps of the sample before, and landed where the exit
// landOnExitLine finds (with the pull's change) lies within kExitLanded:
// between the plan, which takes the pull as constant, and the landed step the
// end moved by -0.007 to +0.055 step over 9,640 landings of random grazing
// pairs (benchmarks/pair_sweep.py's grazing set, 16 phases each); landed ends
// lie up to 1.2 steps on, and a little past that where the end moved (1.248 the
// most seen, a sticking pair at tc/8 with limitForce on), so a landed end is
// looked for to 1.4 steps: 0.15 step of room before a landed binary contact
// would go on off its continuous motion. Planned and landed only up to 2 steps,
// a contact ending just past the sample after next was not landed: its end
// step's flight left the exit line by the angle it did not sweep (a sliding
// pair at tc/5 1.6 % off at the worst of 64 phases, a sticking one 1.2 %);
// planned up to 2.25 steps (the landed end looked for to 1.25), some landed
// samples went on, and 11 of 820 grazing draws missed (3 before).
constexpr double kLandedEnd = 1.4, kExitPlanned = 2.1, kExitLanded = 2.2;

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
    s.flowPlan = s.o.flow(kExitPlanned * dt);
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
    s.endPullMargin = forceEnds ? 0.0 : dt * dt;
    s.endPlanX = s.o.ending(s.o.after({1.0, s.uX}, s.flowPlan), forceEnds);
    s.endPlanV = s.o.ending(s.o.after({0.0, s.uV}, s.flowPlan), forceEnds);
    s.endPlanA = (s.endPlanX - (forceEnds ? k : 1.0)) / k;
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
// `landing`: a pair's sample placed on the continuous exit line (its end
// step next).
enum class CollisionPhase { fresh = 0, touching = 1, ended = 2, attractive = 3, held = 4, leaving = 5, landing = 6 };

// What a contact keeps between steps.
struct CollisionState {
    CollisionPhase phase = CollisionPhase::fresh;
    // After the first step: the continuous overlap at that step minus the
    // actual one (the free flight into the contact felt no force); the
    // second step takes it as its previous sample. After the end step: the
    // time the free flight it set had left to part the bodies.
    double previousOffset = 0;
    // The pull the last step was given (of the half step before it); after a
    // first step, the pull half a step before its sample (from the touch's and
    // its rate since).
    double previousPull = 0;
};

// A pair whose contact ends in the next step (within kExitPlanned steps of
// this sample) leaves on a straight line from the continuous exit. The end step's kick acts along its own sample's
// normal: it puts the flight on the exit's line only from a sample on that
// line (from the sample on the continuous motion the flight came out turned
// by the angle it swept to the surface less the one the contact swept: a
// frictionless grazing pair 1.6 % off at tc/5.7). What landing the next
// sample on the line takes, in the plane of the motion (this sample's normal
// and the centres' tangential velocity): landOnExitLine.
struct ExitPlan {
    double sigma = -1;               // the continuous exit, after this sample [s] (< 0: no plan)
    double distance = 0, dEnd = 0;   // the centres' distance at this sample and at the exit
    double x = 0, v = 0, turn = 0;   // the overlap, rate and turn exactCollisionStep took
    Motion now{0.0, 0.0};            // the continuous motion at this sample (of x + pull / k)
    double pull = 0;
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
    ExitPlan exit;    // a pair's contact ending in the next step (within kExitPlanned steps)
};

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
inline void partingKick(const StepLaw& law, CollisionState& state, double x, double v, double pull, double turn,
                        double target, CollisionStep& r)
{
    const double leave = std::sqrt(std::max(target - 2.0 * pull * x, 0.0));
    r.force = (v - turn + leave) / law.dt;
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
                                                          double pull, double pullRate, double pullChange, double turn,
                                                          double distance)
{
    const double dt = law.dt;
    CollisionStep r;
    // the sample as it is (the kicks act on it); x and v below: the
    // continuous motion's, which a landing sample left by previousOffset
    const double xAt = x, vAt = v;
    const bool landed = state.phase == CollisionPhase::landing;
    if (landed) {
        x -= state.previousOffset, v -= state.previousOffset * law.inverseDt;
        state.previousOffset = 0.0;
        state.phase = CollisionPhase::touching;
    }
    if (state.phase == CollisionPhase::leaving) {
        // the end step's second kick (below): previousOffset holds the
        // parting rate squared
        partingKick(law, state, x, v, pull, turn, state.previousOffset, r);
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
        const double closing = turn - v;
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
        const double vh = v - turn;
        const double s = freeFlightTime(x, vh, pull);
        r.sinceStart = s;
        touch = {shift, vh + pull * s};
        now = law.o.after(touch, s);
        if (pullRate != 0.0) {
            // From touch to this sample the pull ran at pull + pullRate t (t
            // since touch): x_p = -(pull + pullRate t) / k + c pullRate / k^2
            // solves the forced law, so x - x_p is free; from this sample on
            // the pull given holds (over the next step exactCollisionStep
            // takes the pull at its sample, as inside the contact).
            const double k = law.o.k, q = pullRate / k;
            const Motion forced = law.o.after({-law.o.c * q / k, q}, s);
            now = {now.x + forced.x - q * s + law.o.c * q / k, now.u + forced.u - q};
            // (the impulse the pull's change took from the contact's start)
            touch.u -= 0.5 * pullRate * s * s;
        }
        // (the next step's pull is that of the half step after this sample)
        state.previousPull = pull + pullRate * (s - 0.5 * dt);
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
    // (within the margin the continuous contact ends just after the next
    // sample: its end is looked for up to a step later; not ended there, it
    // goes on)
    double hi = dt, endHi = endAhead;
    bool goesOn = endAhead > law.endMargin * x + law.endPullMargin * pullChange;
    if (landed || (!goesOn && endAhead > law.endMargin * x)) {
        // (a landed sample ends here unless its end lies past kLandedEnd:
        // pushed by other contacts it goes on)
        hi = (landed ? kLandedEnd : 2.0) * dt, endHi = endingAndSlope(law.o.after(now, hi)).first;
        goesOn = endHi > 0.0;
    }
    if (goesOn) {  // on along the continuous motion: the next sample lies on it
        r.force = (vAt - (ahead.x - shift - xAt) / dt) / dt - pull;
        r.friction = frictionBetween(law, state, now, start, law.o.after(now, law.flowHalf), from, 0.5 * dt, pull);
        // A pair whose contact ends in the next step (within kExitPlanned
        // steps): the plan of its landing on the exit line (landOnExitLine, which the caller runs
        // with this step's friction). Not from a first step, whose state
        // holds the start's offset for the next.
        if (hi == dt && r.sinceStart < 0.0 && distance > 0.0 && pull > 0.0) {
            const double endPlan = endingAndSlope(law.o.after(now, law.flowPlan)).first;
            if (!(endPlan > 0.0)) {
                const double sigma = detail::bracketedNewton(
                    [&](double t) { return endingAndSlope(law.o.after(now, t)); }, dt, kExitPlanned * dt, endAhead,
                    dt + (kExitPlanned - 1.0) * dt * endAhead / (endAhead - endPlan));
                const double dEnd = distance + xAt - (law.o.after(now, sigma).x - shift);
                r.exit = {sigma, distance, dEnd, xAt, vAt, turn, now, pull};
            }
        }
        return r;
    }
    // The contact ends within this step: leave at the continuous exit rate.
    const double endNow = endingAndSlope(now).first;
    const double tau = endNow <= 0.0 ? 0.0
                                     : detail::bracketedNewton([&](double t) { return endingAndSlope(law.o.after(now, t)); },
                                                               0.0, hi, endNow, hi * endNow / (endNow - endHi));
    r.endsAfter = tau;
    // The continuous contact parts with u_end^2 + 2 pull x_end (x_end: the
    // overlap left at the end of the force, zero for the overlap's end; to
    // x / d): the kick gives that rate where the overlap closes.
    const Motion end = law.o.after(now, tau);
    r.friction = frictionBetween(law, state, now, start, end, from, tau, pull);
    const double target = end.u * end.u + 2.0 * pull * (end.x - shift);
    if (target < 2.0 * pull * xAt) {
        // The pull alone parts the bodies from x faster than the law: no kick
        // here can give that rate. Land the next sample where it does,
        // target / (2 pull), and kick again there (phase `leaving`).
        const double x1 = target / (2.0 * pull);
        const double up = (xAt - x1 - 0.5 * pull * dt * dt) / dt;  // separating rate after this kick
        r.force = (vAt - turn + up) / dt;
        state.previousOffset = target;
        state.phase = CollisionPhase::leaving;
        return r;
    }
    partingKick(law, state, xAt, vAt, pull, turn, target, r);
    return r;
}

}  // namespace detail

// One step of a contact under `exactCollision`: x the overlap at this step,
// v the overlap rate at the half step before (positive while approaching),
// `pull` what else decelerates the overlap (x'' = -F - pull): between two
// spheres the centrifugal |vt|^2 / d of their relative tangential motion
// (vt of the centres, d their distance), which ends a fast oblique contact
// earlier than the law alone; zero on a flat wall. `pullRate`: at a
// contact's first step, how fast the pull changed between first touch and
// this sample (the tangential force turns vt from the touch on; the pull is
// that of the velocities before it: pullRateSinceTouch). `distance`: the
// centres' distance between two spheres (0 on a wall), for the plan of a
// landing on the exit line (CollisionStep::exit). `pullNext` (>= 0, inside
// a contact): the pull of the half step after this sample as this step's
// own kicks give it (exactPairStep's corrector), in place of its
// extrapolation from the last two.
inline CollisionStep exactCollisionStep(const StepLaw& law, CollisionState& state, double x, double v,
                                        double pull = 0.0, double pullRate = 0.0, double distance = 0.0,
                                        double pullNext = -1.0)
{
    // The rate LIGGGHTS gives is -(vi - vj).n with the normal of this step,
    // the velocities of the half step before: with a turning normal that is
    // the samples' rate (x_n - x_{n-1}) / dt less pull dt / 2.
    const double turn = 0.5 * law.dt * pull;
    v += turn;
    // (at a first step: the change pullRate gives over a step)
    const double pullChange = state.phase == CollisionPhase::fresh ? std::fabs(pullRate) * law.dt
                                                                     : std::fabs(pull - state.previousPull);
    const bool attractive = state.phase == CollisionPhase::attractive;
    const bool underWay = attractive || state.phase == CollisionPhase::touching;
    // That pull is the half step before's, |vt_{n-1/2}|^2 / d. The sample
    // after this step lands with the mean of it and the next half step's (the
    // normal turns with each), which is the pull at this sample to second
    // order: the next one's speed |vt| extrapolated linearly from the last two
    // (through zero it comes back, as vt does where friction reverses it; the
    // pull itself extrapolated fails there). Taken as given, a grazing pair
    // whose friction slowed vt fast was pulled half a step late: 1.2 % off at
    // tc/5.3 (PairAgainstContinuous.AGrazingPairIsPulledAsAtItsSamples).
    // Where the friction slows vt ever faster (its cap mu |Fn| growing) the
    // extrapolation lags: a grazing pair at mu 48, tc/7.3, was pulled 25 %
    // too hard over its second step (10,900 for 8,700 m/s^2), its sample
    // 1.2e-7 m off the continuous motion, its exit 0.035 step late: 1.4 %
    // off. Given, the next half step's pull as the step's own kicks make it
    // (pullNext) takes the extrapolation's place.
    const double given = pull;
    if ((underWay || state.phase == CollisionPhase::landing) && (pull > 0.0 || state.previousPull > 0.0)) {
        const double ahead = 2.0 * std::sqrt(pull) - std::sqrt(std::max(state.previousPull, 0.0));
        pull = 0.5 * (pull + (pullNext >= 0.0 ? pullNext : ahead * ahead));
    }
    state.previousPull = given;
    // A contact under way that goes on past this step: the previous sample
    // and this one define the motion. It costs nine products (five more with a
    // pull, and two square roots) and two comparisons over the plain law;
    // between two spheres three more and a comparison: the step before the
    // end step (the end within kExitPlanned steps) goes out of line, to plan
    // a landing.
    if (underWay) {
        const double vUsed = v - state.previousOffset * law.inverseDt;
        if (law.endGoX * x + law.endV * vUsed + law.endA * pull > law.endPullMargin * pullChange &&
            !(distance > 0.0 && pull > 0.0 && !(law.endPlanX * x + law.endPlanV * vUsed + law.endPlanA * pull > 0.0))) {
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
    return detail::exactCollisionEnds(law, state, x, v, pull, pullRate, pullChange, turn, distance);
}

// The force (per unit mass, along this sample's normal) that lands the next
// sample on the exit line of plan p (exactCollisionStep's, whose own force
// lands it on the continuous motion), and the state the end step then takes
// (the landed sample's offset from the continuous motion); nullopt where the
// exit is not past the next sample and within kExitLanded steps, or that sample
// would not touch. vtBefore, vtAfter: the centres' tangential speed before and
// after this step's kicks (the friction's included), vtExit: at the continuous
// exit. The line's angular momentum is dEnd vtExit; the end step's kick, along
// its sample's normal, keeps the sample's plus what its friction adds.
inline std::optional<double> landOnExitLine(const StepLaw& law, CollisionState& state, const ExitPlan& p,
                                            double vtBefore, double vtAfter, double vtExit)
{
    const double dt = law.dt, d = p.distance, k = law.o.k, c = law.o.c;
    // The plan took the pull as constant; the friction changes vt up to the
    // exit, the pull with it: at its mean rate q k to the exit, x = y -
    // (pull + q k t) / k + c q / k with y free (the exit moves: found again).
    const double q = (vtExit * vtExit / p.dEnd - p.pull) / (p.sigma * k);
    const Motion y{p.now.x - c * q / k, p.now.u + q};
    const auto motion = [&](double t) {
        const Motion m = law.o.after(y, t);
        return Motion{m.x - (p.pull + q * k * t) / k + c * q / k, m.u - q};
    };
    const auto ending = [&](double t) {
        const Motion m = motion(t);
        return law.forceEnds ? std::make_pair(k * m.x + c * m.u, law.o.forceRate(law.o.after(y, t)) - q * k)
                             : std::make_pair(m.x, m.u);
    };
    const double reach = kExitLanded * dt, endStep = ending(dt).first, endReach = ending(reach).first;
    if (!(endStep > 0.0 && endReach <= 0.0)) return std::nullopt;
    const double sigma =
        detail::bracketedNewton(ending, dt, reach, endStep, dt + (reach - dt) * endStep / (endStep - endReach));
    const Motion end = motion(sigma), mid = motion(0.5 * sigma);
    const double dEnd = d + p.x - end.x, dMid = d + p.x - mid.x, out = -end.u;
    // the angle the normal turns to the exit (Simpson's rule on vt / d)
    const double atSample = 0.5 * (vtBefore + vtAfter);
    const double angle = sigma / 6.0 * (atSample / d + 2.0 * (atSample + vtExit) / dMid + vtExit / dEnd);
    const double ca = std::cos(angle), sa = std::sin(angle);
    const double wx = out * ca - vtExit * sa, wy = out * sa + vtExit * ca;  // the exit velocity, in this frame
    if (!(wy > 0.0)) return std::nullopt;
    // the next sample (d + dt vr, dt vtAfter) on the line: (d + dt vr) wy - dt vtAfter wx = dEnd vtExit
    const double vr = ((dEnd * vtExit + dt * vtAfter * wx) / wy - d) / dt;
    const double xLanded = d + p.x - std::hypot(d + dt * vr, dt * vtAfter);
    if (!(xLanded > 0.0)) return std::nullopt;
    state.previousOffset = xLanded - motion(dt).x;
    state.phase = CollisionPhase::landing;
    return (p.v - p.turn + vr) / dt;
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

// The coefficients a contact under way applies (the step laws), per unit
// meff like pourninUnitCoefficients (the tangential per unit m_t = 2/7 meff):
// what the multi-contact timestep guard and a stock run standing in for the
// law in a packing need.
inline UnitCoefficients appliedCoefficients(const StepLaw& normal, const StepLaw& tangential)
{
    return {normal.kStep, normal.cStep, kTangentialMassRatio * tangential.kStep,
            kTangentialMassRatio * tangential.cStep};
}

// The multi-contact guard on the laws a contact applies at step dt.
inline bool stableAt(const FreeOscillator& normal, const FreeOscillator& tangential, double dt, bool limitForce)
{
    return dt <= stableTimestep(appliedCoefficients(stepLaw(normal.k, normal.c, dt, limitForce),
                                                    stepLaw(tangential.k, tangential.c, dt, false)));
}

// The coarsest step the guard admits: the applied laws change with the step,
// so the bound at one step is not the bound at another (advice to use the
// bound seen at a refused step was refused again). Bisection from a refused
// step `above` down to the continuous laws' own bound, which is admitted
// (applied laws stiffen with the step); the result is admitted.
inline double coarsestStableStep(const FreeOscillator& normal, const FreeOscillator& tangential, double above,
                                 bool limitForce)
{
    double lo = 0.5 * stableTimestep(UnitCoefficients{normal.k, normal.c, kTangentialMassRatio * tangential.k,
                                                      kTangentialMassRatio * tangential.c}),
           hi = above;
    while (!stableAt(normal, tangential, lo, limitForce)) lo *= 0.5;
    for (int it = 0; it < 60 && hi - lo > 1e-12 * hi; ++it) {
        const double mid = 0.5 * (lo + hi);
        (stableAt(normal, tangential, mid, limitForce) ? lo : hi) = mid;
    }
    return lo;
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

}  // namespace viscoelastic
