// The free damped oscillator x'' = -k x - c x' and its closed-form flow over
// any time (FreeOscillator, Motion): the normal contact between its events, the
// tangential spring while it sticks; what one continuous collision of it does
// (continuousCollision). Also combine(), a x + b y on Vec3.
// Part of exactCollision (collision.h).
#pragma once

#include <cmath>

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

// What one continuous collision does, from first touch with unit approach
// rate: restitution, the time the overlap lasts and the time the force lasts
// (with limitForce the bodies still overlap, force-free, for a while after
// the force ends).
struct ContinuousCollision {
    double restitution, duration, forceDuration;
};

inline ContinuousCollision continuousCollision(const FreeOscillator& o, bool limitForce)
{
    const double half = kPi / o.omega;  // the overlap's zero, half a period (Pournin's: tc)
    if (!limitForce) return {-o.after({0.0, 1.0}, half).u, half, half};
    // the force k x + c u turns negative after the peak overlap (u < 0), before x returns to 0
    const double peak = std::atan2(o.omega, o.lambda) / o.omega;
    const double tf = o.forceZeroFrom({0.0, 1.0}, peak);
    const Motion m = o.after({0.0, 1.0}, tf);
    return {-m.u, tf + m.x / -m.u, tf};
}

}  // namespace viscoelastic
