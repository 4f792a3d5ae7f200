// Two glass beads (radius 1.5 mm, 2500 kg/m^3) stepped as LIGGGHTS steps a
// pair under exactCollision: leapfrog, normal j to i, LIGGGHTS' arms
// R - overlap/2, the pull |vt|^2 / d, the spring driven by springDrive, the
// first step by exactPairStep. Bead i comes in at (vn, vt, 0) towards bead j
// at rest, and touches it at (-2R, 0, 0) `phase` of a step before a sample
// (three steps of free flight before); or, `overlapping`, starts at
// (-2R + phase dt vn, 0, 0), overlapping by phase dt vn (the regression cases
// of test_collision were found so).
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>

#include "core/collision.h"
#include "core/stability.h"

namespace pairstepper {

using viscoelastic::Vec3;

struct Setup {
    viscoelastic::ContactParameters p;
    bool limitForce = false;
    double ratio = 10;  // tc / dt
    double vn = 1, vt = 0;
    Vec3 spinI = Vec3::Zero(), spinJ = Vec3::Zero();
    double phase = 0.5;
    bool overlapping = false;
};

struct Run {
    Vec3 V, wi, wj;                     // after the contact: the relative velocity and the spins (constant in flight)
    double energyIn = 0, energyOut = 0;  // kinetic and rotational, both beads
    double largestFt = 0, peakFn = 0;    // the largest tangential and normal force of a step
    double largestPull = 0;              // the largest pull |vt|^2 / d of a step
};

constexpr double kRadius = 1.5e-3;
constexpr double kMass = 2500.0 * 4.0 / 3.0 * viscoelastic::kPi * kRadius * kRadius * kRadius;  // glass

// nullopt: the step exceeds the applied law's stable step (the model refuses
// it), or limitForce cannot restitute en.
inline std::optional<Run> steppedPair(const Setup& c)
{
    using namespace viscoelastic;
    const double R = kRadius, m = kMass, I = 0.4 * m * R * R, meff = 0.5 * m;
    const auto o = exactCollisionOscillators(c.p, c.limitForce);
    if (!o) return std::nullopt;
    const double dt = c.p.tc / c.ratio;
    const StepLaw normal = stepLaw(o->normal.k, o->normal.c, dt, c.limitForce);
    const StepLaw tangential = stepLaw(o->tangential.k, o->tangential.c, dt, false);
    if (dt > stableTimestep(appliedCoefficients(normal, tangential))) return std::nullopt;
    Vec3 vi(c.vn, c.vt, 0.0), vj = Vec3::Zero(), wi = c.spinI, wj = c.spinJ;
    Vec3 xi = c.overlapping ? Vec3(-2.0 * R + c.phase * dt * c.vn, 0.0, 0.0)
                            : Vec3(Vec3(-2.0 * R, 0.0, 0.0) - (3.0 + c.phase) * dt * vi),
         xj = Vec3::Zero();
    const auto energy = [&] {
        return 0.5 * m * (vi.squaredNorm() + vj.squaredNorm()) + 0.5 * I * (wi.squaredNorm() + wj.squaredNorm());
    };
    Run r;
    r.energyIn = energy();
    CollisionState state;
    TangentialState spring;
    ExactTangentialState exact;
    bool touched = false;
    for (int step = 0; step < 1000000; ++step) {
        const Vec3 d = xi - xj;
        const Vec3 n = d.normalized();
        const double overlap = 2.0 * R - d.norm();
        if (overlap > 0.0) {
            touched = true;
            const Vec3 v = vi - vj, vt = v - v.dot(n) * n;
            const double cr = R - 0.5 * overlap;
            const Vec3 vtr = vt - (cr * (wi + wj)).cross(n);
            const double pull = std::max(v.squaredNorm() - v.dot(n) * v.dot(n), 0.0) / d.norm();
            const SpringDrive drive = springDrive(vtr, n, overlap, meff, m, R, cr, wi, m, R, cr, wj);
            const auto atTouch = [&] { return PairAtTouch{drive, vt, meff, c.p.mu, 1.0 / d.norm()}; };
            const CollisionState before = state;
            CollisionStep s = exactPairStep(normal, tangential, state, overlap, -v.dot(n), pull, d.norm(), atTouch);
            s.friction *= meff, s.meff = meff;
            CollisionStep corrected;
            const auto forecast = [&](const CollisionStep& step) {
                TangentialState springAhead = spring;
                ExactTangentialState exactAhead = exact;
                return exactTangentialForce(springAhead, exactAhead, n, drive.rate, drive.mass, tangential, normal, step,
                                            c.p.mu * meff, frictionLimit(c.p.mu, step.friction), false, drive.feed);
            };
            if (correctPull(normal, tangential, before, state, s, corrected, overlap, -v.dot(n), pull, d.norm(), v, n,
                            atTouch, forecast))
                s = corrected;
            Vec3 exitChange;
            const Vec3 ft = exactTangentialForce(spring, exact, n, drive.rate, drive.mass, tangential, normal, s,
                                                 c.p.mu * meff, frictionLimit(c.p.mu, s.friction), true, drive.feed,
                                                 &exitChange);
            const Vec3 f = (meff * s.force + exitLineForce(normal, state, s, vt, ft, drive.mass, exitChange)) * n + ft;
            r.largestFt = std::max(r.largestFt, ft.norm()), r.peakFn = std::max(r.peakFn, std::fabs(meff * s.force));
            r.largestPull = std::max(r.largestPull, pull);
            vi += dt * f / m, vj -= dt * f / m;
            wi -= dt * cr * n.cross(ft) / I, wj -= dt * cr * n.cross(ft) / I;
        } else if (touched) {
            break;  // apart: nothing acts any more
        }
        xi += dt * vi, xj += dt * vj;
    }
    r.V = vi - vj, r.wi = wi, r.wj = wj;
    r.energyOut = energy();
    return r;
}

// The ranges of a random pair collision (drawPair): en, et in [0.1, 0.95]
// (et = en in 30 %), mu log-uniform from muMin to 100 (80 %) or to 1e6, vn
// log-uniform from vnMin to 2 m/s, vt/vn uniform from slopeMin to 5, in half
// the draws a spin on each bead up to `spin` vn / R about a random axis,
// limitForce on or off, tc/dt from 5 to ratioMax (integer in 30 %), the start
// phase uniform; tc 1e-4 s.
struct Ranges {
    double spin = 2.0, slopeMin = 0.0, vnMin = 0.01, ratioMax = 100.0, muMin = 0.05;
};

inline Setup drawPair(std::mt19937& g, const Ranges& r)
{
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const auto spinOf = [&](double size) {
        Vec3 axis(u(g) - 0.5, u(g) - 0.5, u(g) - 0.5);
        return Vec3(size * u(g) * axis.normalized());
    };
    Setup c;
    c.p.tc = 1e-4;
    c.p.en = 0.1 + 0.85 * u(g);
    c.p.et = u(g) < 0.3 ? c.p.en : 0.1 + 0.85 * u(g);
    c.p.mu = r.muMin * std::pow((u(g) < 0.8 ? 100.0 : 1e6) / r.muMin, u(g));
    c.vn = r.vnMin * std::pow(2.0 / r.vnMin, u(g));
    c.vt = (r.slopeMin + (5.0 - r.slopeMin) * u(g)) * c.vn;
    if (u(g) < 0.5) {
        const double size = r.spin * c.vn / kRadius;
        c.spinI = spinOf(size), c.spinJ = spinOf(size);
    }
    c.limitForce = u(g) < 0.5;
    c.ratio = u(g) < 0.3 ? std::round(5.0 + (r.ratioMax - 5.0) * u(g)) : 5.0 + (r.ratioMax - 5.0) * u(g) * u(g);
    c.phase = 1.0 - u(g);
    return c;
}

// How far one outcome of c leaves from another: the largest change of the
// relative velocity or of a spin's contact speed R w, over the incoming speed.
inline double apart(const Run& a, const Run& b, const Setup& c)
{
    const double off = std::max({(a.V - b.V).norm(), kRadius * (a.wi - b.wi).norm(), kRadius * (a.wj - b.wj).norm()});
    return off / std::hypot(c.vn, c.vt);
}

// The collision at c.ratio and the same at tc/1000 (same touch). nullopt:
// a step the model refuses.
struct CoarseAndFine {
    Run coarse, fine;
};
inline std::optional<CoarseAndFine> coarseAndFine(Setup c)
{
    const auto coarse = steppedPair(c);
    if (!coarse) return std::nullopt;
    c.ratio = 1000.0;
    const auto fine = steppedPair(c);
    if (!fine) return std::nullopt;
    return CoarseAndFine{*coarse, *fine};
}

// The collision at c.ratio against the same at tc/1000.
inline std::optional<double> offTheFineStep(const Setup& c)
{
    const auto runs = coarseAndFine(c);
    if (!runs) return std::nullopt;
    return apart(runs->coarse, runs->fine, c);
}

}  // namespace pairstepper
