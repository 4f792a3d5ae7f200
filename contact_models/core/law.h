// The viscoelastic contact law per step (Cundall's linear spring-dashpot):
// normal force (Eq. 3.20), Coulomb limit (Eq. 3.18) and the thesis'
// tangential law (Eq. 3.5, 3.18-3.21).
//
// Sign conventions follow LIGGGHTS: the contact normal n points from body j
// to body i, the overlap is positive while touching, the overlap rate is
// -(v_i - v_j).n (positive while approaching), and forces are those on i.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

#include "pournin.h"

namespace viscoelastic {

using Vec3 = Eigen::Vector3d;

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
// xi_t (Eq. 3.9), the normal it was last expressed in, and the normal force
// of Eq. 3.20 (not clipped by limitForce) at that step.
struct TangentialState {
    Vec3 xi = Vec3::Zero();
    Vec3 normal = Vec3::Zero();  // zero before the first step of a contact
    double normalForce = 0.0;
};

// The time since a contact's first touch at its first overlapping step:
// overlap over approach rate (free flight before it), at most a step. Its
// tangential overlap grew for that long, not a whole step: with a whole step
// the spring leads the normal overlap by up to vt dt, and with et = en the
// tangential force is no longer in phase with the normal one.
inline double timeSinceTouch(double overlap, double overlapRate, double dt)
{
    return (overlapRate > 0.0 && overlap < overlapRate * dt) ? overlap / overlapRate : dt;
}

// Tangential law of the thesis (Eq. 3.18-3.21) for one step.
// The overlap is carried with the rotating contact frame (rotated, not
// projected, so its length survives a turning normal), then advanced by the
// tangential velocity of i relative to j at the contact point, vt. The
// Coulomb cap applies to the total force kt xi + ct dxi/dt; when it binds the
// spring is reset so that it reproduces the capped force (Luding 2008), which
// keeps the force continuous when sliding stops.
// `unclippedNormalForce` (kn xi + cn dxi/dt) locates the cap's zeros between
// steps (timeSinceCapZero): there the spring restarts from zero force.
// `sinceTouch` (timeSinceTouch) is the part of the step in contact, used at
// the contact's first step. Returns the tangential force on i. `advance` is
// false when LIGGGHTS only evaluates forces without moving history (`run 0`).
inline Vec3 pourninTangentialForce(TangentialState& s, const Vec3& n, const Vec3& vt, double kt,
                                   double ct, double limit, double dt, bool advance,
                                   double unclippedNormalForce, double sinceTouch)
{
    // The spring is worked on in a local and stored once: updated in place
    // through `s`, it was stored and reloaded between the updates (about 4 %
    // of the step in benchmarks/bench_core.cpp).
    Vec3 xi = s.xi;
    if (advance) {
        const bool under_way = s.normal.squaredNorm() > 0.0;
        if (under_way) xi = rotateWithNormal(xi, s.normal, n);
        xi += vt * (under_way ? dt : sinceTouch);
        xi -= xi.dot(n) * n;  // round-off only: the rotation keeps xi in the plane
        const double since = under_way ? timeSinceCapZero(s.normalForce, unclippedNormalForce, dt) : -1.0;
        if (since >= 0.0 && kt > 0.0) xi = -(ct / kt) * vt + vt * since;
    }
    Vec3 f = -(kt * xi + ct * vt);
    const double fmag = f.norm();
    if (fmag > limit) {
        f *= (fmag > 0.0 ? limit / fmag : 0.0);
        if (advance && kt > 0.0) xi = -(f + ct * vt) * (1.0 / kt);
    }
    if (advance) s.xi = xi, s.normal = n, s.normalForce = unclippedNormalForce;
    return f;
}

}  // namespace viscoelastic
