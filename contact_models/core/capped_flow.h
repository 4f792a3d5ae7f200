// The tangential law with its instantaneous Coulomb cap mu |Fn(t)|, followed
// exactly through a step: the free spring while it sticks, the slide on the
// cap, and the events that join them (cappedFlow). The normal motion comes in
// as a CapSource, no step law. Part of exactCollision (collision.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "free_flow.h"
#include "law.h"
#include "roots.h"

namespace viscoelastic {

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
// of that turn over it, and ends the step on the cap in the direction the
// turn reaches at its end. (Keeping forceBefore's direction plus the jump,
// the force never turned toward the slip: two spinning beads, mu 0.01, got
// 13 times the law's sideways friction at every step.) The turn holds at any
// angle, also where F is more than a right angle from g: a slide the falling
// cap drives against the slip (near a contact's end) turns away from -g.
// Unturned there, pairs with a sideways g (a spin about the normal: a; or
// across it: u) converged to another law, up to 2.3e-3 of the incoming speed
// off at tc/1000 and at tc/16000. On one line (a slide on a flat wall with
// no sideways force on the bead: u, a and F collinear, to round-off) there is
// no side to turn to; a sine below 1e-9 counts as one line, and a force
// within that of antiparallel to g is not turned.
struct SlideTurn {
    Vec3 mean, end;
};
inline std::optional<SlideTurn> slidingDirection(const FreeOscillator& o, const Vec3& u, const Vec3& phi,
                                                 const Vec3& forceBefore, double cap, double dt, double span)
{
    const Vec3 jump = (phi - forceBefore) * (1.0 / (o.k * dt + o.c));
    const Vec3 g = o.k * (u + 0.5 * jump) + o.c * jump * (1.0 / dt);  // the slip at mid-step
    const double gn = g.norm(), fn = forceBefore.norm();
    if (!(gn > 0.0) || !(cap > 0.0)) return std::nullopt;
    const double decay = gn * span / cap;  // (span: a last step's, up to the end)
    const Vec3 target = g / gn, before = forceBefore / fn;
    const Vec3 across = before - before.dot(target) * target;
    const double sine = across.norm();
    if (!(sine > 1e-9)) {  // on one line (to round-off: a wall's slides show up to 3e-10)
        if (g.dot(forceBefore) <= 0.0) return std::nullopt;
        const double mean = decay > 1e-8 ? -std::expm1(-decay) / decay : 1.0 - 0.5 * decay;
        return SlideTurn{(target + mean * (before - target)).normalized(),
                         (target + std::exp(-decay) * (before - target)).normalized()};
    }
    // the angle from g: A = 2 atan(T), T = T0 exp(-|g| t / cap), down to T1 at
    // the span's end; over the span the mean of cos A is
    // 1 + ln((1 + T1^2) / (1 + T0^2)) / decay, that of sin A (A0 - A1) / decay
    const Vec3 side = across * (1.0 / sine);
    const double half2 = 0.25 * (before - target).squaredNorm();  // sin^2(A0 / 2)
    const double rest2 = 0.25 * (before + target).squaredNorm();  // cos^2(A0 / 2)
    const double t0 = std::sqrt(half2 / rest2), e = std::exp(-decay), t1 = t0 * e;
    double meanCos = before.dot(target), meanSin = sine;  // (decay 0)
    if (decay > 0.0) {
        const double drop = half2 * -std::expm1(-2.0 * decay);  // 1 - (1 + T1^2) / (1 + T0^2)
        meanCos = 1.0 + (drop < 0.5 ? std::log1p(-drop) : std::log(rest2 + half2 * e * e)) / decay;
        meanSin = 2.0 * std::atan(t0 * -std::expm1(-decay) / (1.0 + t0 * t1)) / decay;
    }
    const double q = 1.0 / (1.0 + t1 * t1);
    // (normalised: near antiparallel `side` keeps round-off along g, 1e-16 / sine)
    return SlideTurn{(meanCos * target + meanSin * side).normalized(),
                     (((1.0 - t1 * t1) * q) * target + (2.0 * t1 * q) * side).normalized()};
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
        // A slide from the last step goes on on the cap unless the cap more
        // than doubled since: a pair's pull changed within the step and the
        // normal force missed its forecast, and the spring keeps its own
        // force (put onto a cap 44 times its force near a contact's end, a
        // grazing pair, mu 4278, vt/vn 5, 2 m/s, tc/10.4, stuck there and
        // left 14 % off; restarting the slide on any miss of the forecast,
        // a pull's change moved spinning pairs up to 2.9 % off at tc/10).
        if (onCap && p < 0.5 * cap) onCap = false;
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
        // an event found within round-off short of Fn's zero is at the zero:
        // otherwise the cap there (round-off, of either sign) leaves a span of
        // round-off on which stick and slide alternate until the events run
        // out (en = et, where the spring's force and Fn vanish together: the
        // fallback below then slid through the rest of the step, out of the
        // re-stick condition, and threw the contact point forward at up to 87
        // times its incoming speed)
        if (t < zero && zero - t <= rest) t = zero;
        mn = normalAt(t);
        fn = t == zero ? 0.0 : src.force(mn);  // exactly at the zero: the cap is zero there
    }
    if (t < b && dir.squaredNorm() > 0.0) {
        // events ran out (stick and slide alternating at one instant, seen
        // between two spinning spheres: the free spring's sideways rate
        // takes it over the cap at once): the rest slides on the cap in the
        // last direction, so the step's force stays within the cap (a free
        // spring here gave 16 times the step's bound). Friction only slows
        // the slip along dir: a slide that would reverse it stops there, one
        // against it does not start, and none goes on past Fn's zero, where
        // the cap's direction is the spring's again (en = et at the sticking
        // threshold mu = (m_t / meff) vt / vn: the spring rides the cap
        // through the zero, and a slide held in its direction past it left
        // up to 14 % of vt faster than the law); the rest is the free spring
        // below.
        bool stopped = false;
        const double last = t < zero && zero < b ? zero : b;
        const Motion from = src.at(t);
        const double u0 = m.u.dot(dir);
        const auto slipAt = [&](double tau) {  // m.u.dir after sliding from t to tau
            return u0 - src.kappa * std::fabs(from.u - src.at(tau).u - src.pull * (tau - t));
        };
        if (u0 < 0.0) {
            stopped = true;
        } else {
            double to = last;
            if (slipAt(last) < 0.0) to = detail::bracketedRoot(slipAt, t, last);
            const Motion q = to == b ? mb : src.at(to);
            slide(from, q, to - t);
            stopped = to < b;
            t = to;
            if (stopped) m.xi = ((t == zero ? 0.0 : capAt(src.force(q))) * dir - o.c * m.u) / o.k;  // on the cap there
        }
        if (!stopped) m.xi = (capAt(fb) * dir - o.c * m.u) / o.k, r.sliding = true;
        r.stuck = false;
    }
    if (t < b) {  // (no direction, or a slide that stopped: a free spring, capped at the end)
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

}  // namespace viscoelastic
