// exactCollision's wall collision with friction, stepped by the core, against
// the independent continuous reference (tools/collide/continuous_law.h, which
// uses nothing of contact_models/): a seeded random sweep of materials,
// friction, incidence, timestep and start phase, limitForce off. (With
// limitForce exactCollision follows a solved cut law whose tangential spring
// lasts as long as the force: not the reference's law.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "continuous_law.h"
#include "core/collision.h"
#include "core/stability.h"

using namespace viscoelastic;

// Tolerance 1e-8 of the incoming speed: both sides locate their events to
// about 1e-10 of the contact (the reference bisects to 1e-10 tc, the steps'
// roots stop within 1e-10 of their brackets), and an event's time error moves
// the exit by about that fraction times the cap's swing (mu up to 1e6 at vt/vn
// up to 5 slides only briefly); worst seen 1e-9.
TEST(ExactCollisionAgainstContinuous, EveryWallCollisionFollowsTheIndependentLaw)
{
    std::mt19937 g(31337);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double worst = 0.0;
    int run = 0;
    for (int i = 0; i < 1500; ++i) {
        const double en = 0.1 + 0.85 * u(g);
        const double et = u(g) < 0.3 ? en : 0.1 + 0.85 * u(g);
        const double mu = 0.05 * std::pow(u(g) < 0.8 ? 2e3 : 2e7, u(g));
        const double slope = u(g) < 0.5 ? 5.0 * u(g) : std::pow(10.0, -2.0 + 2.0 * u(g));
        const double ratio = u(g) < 0.3 ? std::round(5.0 + 95.0 * u(g)) : 5.0 + 95.0 * u(g) * u(g);
        const double phase = 1.0 - u(g);
        const ContactParameters p{1e-4, en, et, mu};
        const auto o = exactCollisionOscillators(p, false);
        const double dt = p.tc / ratio;
        const StepLaw normal = stepLaw(o->normal.k, o->normal.c, dt, false);
        const StepLaw tangential = stepLaw(o->tangential.k, o->tangential.c, dt, false);
        if (dt > stableTimestep(appliedCoefficients(normal, tangential))) continue;
        const FrictionalExit e = exactWallCollisionAtPhase(normal, tangential, phase, slope, mu,
                                                           [](double) { return 2.0 / 7.0; });
        const continuous::Exit r = continuous::wallImpact({p.tc, en, et, mu}, {1.0, slope, false});
        ++run;
        const double dn = std::fabs(e.normal - r.vn), dtan = std::fabs(e.tangential - r.vt);
        worst = std::max({worst, dn, dtan});
        EXPECT_LT(dn, 1e-8) << "en " << en << " et " << et << " mu " << mu << " vt/vn " << slope << " tc/dt " << ratio
                            << " phase " << phase;
        EXPECT_LT(dtan, 1e-8) << "en " << en << " et " << et << " mu " << mu << " vt/vn " << slope << " tc/dt "
                              << ratio << " phase " << phase << ": steps " << e.tangential << ", law " << r.vt;
    }
    std::printf("%d collisions: worst difference from the independent law %.2e of the incoming speed\n", run, worst);
    EXPECT_GT(run, 1200);
}
