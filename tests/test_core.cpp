// Unit tests of the physics core against the closed-form properties of the
// linear spring-dashpot with Pournin coefficients.
#include <gtest/gtest.h>

#include <cmath>

#include "core/viscoelastic.h"

using namespace viscoelastic;

namespace {

// Table 3.1: glass beads, and bead-drum.
const ContactParameters kBeads{1e-4, 0.56, 0.46, 0.5};
const ContactParameters kDrum{1e-4, 0.46, 0.46, 0.95};

double beadMass() { return 4.0 / 3.0 * kPi * std::pow(1.5e-3, 3) * 2500.0; }


}  // namespace

TEST(Coefficients, MatchEquations322To325)
{
    // Eq. 3.22-3.25 written out independently for a bead pair.
    const double meff = beadMass() / 2.0, tc = kBeads.tc, en = kBeads.en, et = kBeads.et;
    const double mt = 1.0 / (1.0 / meff + 2.0 * (1.5e-3 * 1.5e-3) / (0.4 * beadMass() * 1.5e-3 * 1.5e-3));
    const Coefficients c = scaled(pourninUnitCoefficients(kBeads), meff);
    EXPECT_NEAR(c.kn, meff / (tc * tc) * (kPi * kPi + std::log(en) * std::log(en)), 1e-12 * c.kn);
    EXPECT_NEAR(c.cn, -2.0 * meff / tc * std::log(en), 1e-12 * c.cn);
    EXPECT_NEAR(c.kt, mt / (tc * tc) * (kPi * kPi + std::log(et) * std::log(et)), 1e-12 * c.kt);
    EXPECT_NEAR(c.ct, -2.0 * mt / tc * std::log(et), 1e-12 * c.ct);
}

TEST(Coefficients, TangentialMassIsTwoSeventhsForSpheresAndWalls)
{
    // 1/m_t = 1/meff + R1^2/I1 + R2^2/I2 with I = 2/5 m R^2, any sizes and densities.
    for (double m1 : {1.0, 3.0})
        for (double m2 : {1.0, 0.2, 1e300}) {  // 1e300: a wall
            const double meff = 1.0 / (1.0 / m1 + 1.0 / m2);
            const double mt = 1.0 / (1.0 / meff + 2.5 / m1 + 2.5 / m2);
            EXPECT_NEAR(mt / meff, kTangentialMassRatio, 1e-12);
        }
}

TEST(Coefficients, DampedFrequencyIsPiOverTcAndDecayPerContactIsEn)
{
    for (double en : {0.1, 0.46, 0.56, 0.9, 1.0}) {
        const UnitCoefficients u = pourninUnitCoefficients(2e-4, en, en);
        const double beta = u.cn / 2.0;  // meff = 1
        EXPECT_NEAR(std::sqrt(u.kn - beta * beta), kPi / 2e-4, 1e-9 * kPi / 2e-4);
        EXPECT_NEAR(std::exp(-beta * 2e-4), en, 1e-12);  // amplitude decay over tc
        // tangential oscillator (mass 2/7): same frequency and decay
        const double bt = u.ct / (2.0 * kTangentialMassRatio);
        EXPECT_NEAR(std::sqrt(u.kt / kTangentialMassRatio - bt * bt), kPi / 2e-4, 1e-9 * kPi / 2e-4);
        EXPECT_NEAR(std::exp(-bt * 2e-4), en, 1e-12);
    }
}

TEST(NormalForce, SpringPlusDashpotAndLimitForceClipsAttraction)
{
    const Coefficients c{1000.0, 2.0, 0.0, 0.0};
    EXPECT_DOUBLE_EQ(normalForce(c, 1e-3, 0.5, false), 1.0 + 1.0);
    EXPECT_DOUBLE_EQ(normalForce(c, 1e-3, -1.0, false), 1.0 - 2.0);
    EXPECT_DOUBLE_EQ(normalForce(c, 1e-3, -1.0, true), 0.0);
    EXPECT_DOUBLE_EQ(normalForce(c, 1e-3, 0.5, true), 2.0);
}

TEST(Timestep, CriticalStepOfUndampedContactIsTwoTcOverPi)
{
    EXPECT_NEAR(criticalTimestep(1e-4, 1.0), 2e-4 / kPi, 1e-18);
    EXPECT_LT(criticalTimestep(1e-4, 0.5), 2e-4 / kPi);  // damping with lagged velocity lowers it
}

// Brute force: the recurrence of one contact (no separation) grows without
// bound just above the derived limit and stays bounded just below it.
TEST(Timestep, DerivedLimitSeparatesBoundedFromDivergentRecurrence)
{
    for (double e : {1.0, 0.9, 0.56, 0.46, 0.2}) {
        const double tc = 1e-4, dtc = criticalTimestep(tc, e);
        const UnitCoefficients u = pourninUnitCoefficients(tc, e, 1.0);
        auto amplitude = [&](double dt) {
            double x = 1.0, v = 0.0, peak = 0.0;
            for (int n = 0; n < 20000 && peak < 1e6; ++n) {
                v -= dt * (u.kn * x + u.cn * v);
                x += dt * v;
                peak = std::max(peak, std::fabs(x));
            }
            return peak;
        };
        EXPECT_LT(amplitude(0.98 * dtc), 10.0) << "e = " << e;
        EXPECT_GT(amplitude(1.01 * dtc), 1e3) << "e = " << e;
    }
}

TEST(Restitution, SchwagerPoeschelValuesForForbiddenAttraction)
{
    // requested -> achieved, Schwager & Poeschel (2007)
    const double pairs[][2] = {{0.9, 0.902}, {0.8, 0.808}, {0.5, 0.550}, {0.3, 0.397}, {0.1, 0.253}};
    for (auto& p : pairs) EXPECT_NEAR(continuousRestitution(1e-4, p[0], true), p[1], 6e-4) << p[0];
    EXPECT_DOUBLE_EQ(continuousRestitution(1e-4, 0.56, false), 0.56);
}

// Velocity Verlet is second order for the smooth oscillation, but a contact
// starts and ends between steps and the force there is finite (-cn v at the
// end without limitForce), so the phase-averaged error is first order.
TEST(Restitution, DiscreteCollisionConvergesToContinuousAtFirstOrder)
{
    for (bool limit : {false, true}) {
        const double eCont = continuousRestitution(1e-4, 0.56, limit);
        const double err50 = std::fabs(discreteCollision(1e-4, 0.56, 1e-4 / 50, limit, 256).restitution - eCont);
        const double err200 = std::fabs(discreteCollision(1e-4, 0.56, 1e-4 / 200, limit, 256).restitution - eCont);
        EXPECT_LT(err200, 1e-3 * eCont);
        EXPECT_NEAR(err50 / err200, 4.0, 0.4) << "limitForce " << limit;  // 4x smaller dt, 4x smaller error
    }
    // the contact lasts tc to within a step
    EXPECT_NEAR(discreteCollision(1e-4, 0.56, 1e-4 / 200, false, 256).duration, 1e-4, 1e-4 / 200);
}

TEST(Tangential, RotationCarriesOverlapWithTheFrameWithoutShrinking)
{
    const Vec3 from(1, 0, 0), to = Vec3(1, 0.3, 0).normalized();
    for (const Vec3& xi : {Vec3(0, 2e-5, 1e-5), Vec3(0, 2e-5, 0)}) {
        const Vec3 r = rotateWithNormal(xi, from, to);
        EXPECT_NEAR(r.norm(), xi.norm(), 1e-18);
        EXPECT_NEAR(r.dot(to), 0.0, 1e-18);
    }
    EXPECT_NEAR(rotateWithNormal(from, from, to).dot(to), 1.0, 1e-15);
    // a projection (stock `history`) shortens the in-plane part by cos(angle)
    const Vec3 inPlane(0, 2e-5, 0);
    const Vec3 projected = inPlane - inPlane.dot(to) * to;
    EXPECT_NEAR(projected.norm(), inPlane.norm() * from.dot(to), 1e-18);
}

TEST(Tangential, StickingForceIsSpringPlusDashpot)
{
    TangentialState s;
    const Vec3 n(1, 0, 0), vt(0, 0.01, 0);
    const Vec3 f = pourninTangentialForce(s, n, vt, 1e4, 2.0, 1e9, 1e-6, true);
    EXPECT_NEAR(s.xi.y(), 1e-8, 1e-20);
    EXPECT_NEAR(f.y(), -(1e4 * 1e-8 + 2.0 * 0.01), 1e-15);
    // without advancing, the overlap stays
    pourninTangentialForce(s, n, vt, 1e4, 2.0, 1e9, 1e-6, false);
    EXPECT_NEAR(s.xi.y(), 1e-8, 1e-20);
}

TEST(Tangential, CoulombCapBindsTotalForceAndSpringReproducesIt)
{
    TangentialState s;
    s.xi = Vec3(0, 1e-4, 0);
    s.normal = Vec3(1, 0, 0);
    const Vec3 n(1, 0, 0), vt(0, 0.5, 0.2);
    const double kt = 1e4, ct = 3.0, limit = 0.7;
    const Vec3 f = pourninTangentialForce(s, n, vt, kt, ct, limit, 1e-6, true);
    EXPECT_NEAR(f.norm(), limit, 1e-12);
    // force direction: that of the trial force
    const Vec3 trial = -(kt * Vec3(0, 1e-4 + 0.5e-6, 0.2e-6) + ct * vt);
    EXPECT_NEAR(f.normalized().dot(trial.normalized()), 1.0, 1e-12);
    // the reset spring gives back the capped force with the same velocity
    EXPECT_NEAR((-(kt * s.xi + ct * vt) - f).norm(), 0.0, 1e-12);
    EXPECT_DOUBLE_EQ(frictionLimit(0.5, -2.0), 1.0);  // |Fn| bounds friction at the attractive end
}

TEST(Tangential, TurningNormalKeepsOverlapLength)
{
    TangentialState s;
    s.xi = Vec3(0, 1e-5, 0);
    s.normal = Vec3(1, 0, 0);
    const Vec3 n = Vec3(1, 0.2, 0).normalized();
    pourninTangentialForce(s, n, Vec3::Zero(), 1.0, 0.0, 1e9, 1e-6, true);
    EXPECT_NEAR(s.xi.norm(), 1e-5, 1e-18);
    EXPECT_NEAR(s.xi.dot(n), 0.0, 1e-20);
    EXPECT_EQ(s.normal, n);
}
