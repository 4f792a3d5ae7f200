// The reference solver itself: its RK4 integration of the contact ODE must
// reproduce every closed form the physics offers, so it can be trusted where
// none exists. Tolerances: RK4 at tc/20000 is accurate to ~1e-9 on the smooth
// normal motion; the end of contact is located by linear interpolation and
// the Coulomb switch is applied once per step, both O(h) = 5e-5 tc.
#include <gtest/gtest.h>

#include <cmath>

#include "reference.h"

using namespace collide;

namespace {

Case wallCase(double en, double et, double mu, double vn, double vt, bool limit = false)
{
    Case c;
    c.geometry = Geometry::Wall;
    c.tangential = Tangential::Pournin;
    c.params = {1e-4, en, et, mu};
    c.normalSpeed = vn;
    c.tangentialSpeed = vt;
    c.limitForce = limit;
    return c;
}

}  // namespace

TEST(Reference, HeadOnPairMatchesClosedFormForAnySizesAndDensities)
{
    for (bool limit : {false, true}) {
        Case c;
        c.radius2 = 2.5e-3;
        c.density2 = 7800.0;
        c.limitForce = limit;
        const Outcome ode = integrateContactOde(c);
        const ClosedForm cf = *closedForm(c);
        EXPECT_NEAR(ode.restitution, cf.outcome.restitution, 1e-5);
        EXPECT_NEAR(ode.duration, cf.outcome.duration, 1e-4 * c.params.tc);
        EXPECT_NEAR(ode.peakOverlap, cf.outcome.peakOverlap, 1e-6 * cf.outcome.peakOverlap);
    }
}

TEST(Reference, LimitForceRestitutionIsSchwagerPoeschel)
{
    const Case c = wallCase(0.5, 0.5, 0.3, 1.0, 0.0, true);
    EXPECT_NEAR(integrateContactOde(c).restitution, 0.550, 6e-4);
}

// Oblique closed forms assume the rigid lever arm R; the law acts at
// R - overlap/2, a relative difference of order overlap/R. At 1 cm/s the
// peak overlap is 2e-7 m = 1.6e-4 R, so they must agree to a few 1e-4.
TEST(Reference, StickingImpactOnWallReversesContactPointVelocityByEt)
{
    const Case c = wallCase(0.5, 0.5, 0.3, 0.01, 0.002);
    const ClosedForm cf = *closedForm(c);
    ASSERT_EQ(cf.regime, "sticking");
    const Outcome ode = integrateContactOde(c);
    EXPECT_NEAR(ode.tangentialRestitution, 0.5, 5e-4);
    EXPECT_NEAR(ode.spin1, cf.outcome.spin1, 5e-4 * std::fabs(cf.outcome.spin1));
}

TEST(Reference, GrossSlidingOnWallFollowsWalton)
{
    for (bool limit : {false, true}) {
        const Case c = wallCase(0.5, 0.5, 0.3, 0.01, 0.04, limit);
        const ClosedForm cf = *closedForm(c);
        ASSERT_EQ(cf.regime, "sliding");
        const Outcome ode = integrateContactOde(c);
        EXPECT_NEAR(ode.tangentialRestitution, cf.outcome.tangentialRestitution, 5e-4);
        EXPECT_NEAR(ode.spin1, cf.outcome.spin1, 5e-4 * std::fabs(cf.outcome.spin1));
        EXPECT_NEAR(ode.reboundAngle, cf.outcome.reboundAngle, 0.05);
    }
}

TEST(Reference, FrictionlessObliquePairKeepsSpinAndNormalRestitution)
{
    Case c;
    c.radius2 = 2e-3;
    c.density2 = 4000.0;
    c.tangentialSpeed = 0.05;
    c.spin1 = Vec3(0, 0, 300.0);
    c.params.mu = 0.0;
    const Outcome a = integrateContactOde(c);
    // The turning normal adds a centrifugal term (vt^2/r)/(kn overlap/meff)
    // ~ 4e-5 to the normal motion; no friction means no torque.
    EXPECT_NEAR(a.restitution, c.params.en, 1e-4);
    EXPECT_DOUBLE_EQ(a.spin1, 300.0);
}
