// End-to-end: `exactCollision on` in LIGGGHTS over a seeded random sweep of
// materials, friction, incidence, speed, timestep and start phase, for a
// pair, a primitive wall and a mesh wall, limitForce off and on, checked by
// invariants that need no reference solution:
//  - no collision ends with more kinetic + rotational energy than it began
//    with (the law's dashpots and friction only dissipate);
//  - on a flat wall the contact point does not leave faster than it came;
//  - every single collision gives what the same mode gives at tc/1000.
// And the failure as first seen: one bead onto a primitive plane, Table
// 3.1's bead-drum pair (en = et = 0.46), mu 5, vn 1 m/s, vt 0.2 m/s, tc/10:
// two of 64 start phases left at +2.08 and +3.41 times vt.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "run_options.h"
#include "runner.h"

using namespace collide;

namespace {

double kineticEnergy(const Case& c, const BodyStates& s)
{
    const double m1 = c.mass1(), i1 = 0.4 * m1 * c.radius1 * c.radius1;
    double e = 0.5 * m1 * s.v1.squaredNorm() + 0.5 * i1 * s.w1.squaredNorm();
    if (!c.isWall()) {
        const double m2 = c.mass2(), i2 = 0.4 * m2 * c.radius2 * c.radius2;
        e += 0.5 * m2 * s.v2.squaredNorm() + 0.5 * i2 * s.w2.squaredNorm();
    }
    return e;
}

std::vector<double> randomPhases(std::mt19937& g, int n)
{
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<double> p;
    for (int i = 0; i < n; ++i) p.push_back(1.0 - u(g));
    return p;
}

}  // namespace

TEST(ExactCollisionSweep, TableBeadDrumPairOnAPlaneSticksAtEveryPhase)
{
    // With en = et the sticking spring's force is vt/vn times the normal
    // force throughout (the same oscillator), so the law sticks (0.2 < mu
    // meff / m_t) and leaves at -et vt; LIGGGHTS' arm R - overlap/2 moves the
    // drive's mass by under 0.2 % of m_t at this speed (0.7 % overlap / R),
    // which changes et by its order at most: 1e-3 of vt.
    Case c;
    c.geometry = Geometry::Wall;
    c.params = {1e-4, 0.46, 0.46, 5.0};
    c.normalSpeed = 1.0;
    c.tangentialSpeed = 0.2;
    c.dt = 1e-5;
    const std::vector<Trajectory> runs = runLiggghts(c, options("sweep_bead_drum", "exactCollision on"), evenPhases(64));
    double worst = 0.0;
    for (const Trajectory& t : runs) {
        const Outcome o = measureTrajectory(c, t);
        worst = std::max(worst, std::fabs(o.tangentialRestitution - c.params.et));
        EXPECT_NEAR(o.restitution, c.params.en, 1e-9);
    }
    std::printf("64 phases: worst et off 0.46 by %.2e\n", worst);
    EXPECT_LT(worst, 1e-3);
}

// 24 random cases of 16 random start phases each (384 collisions), each
// against the same case at tc/1000. Draws: en, et in [0.15, 0.95] (et = en in
// a third), mu log-uniform in [0.05, 1e6], vt/vn in [0, 5], vn in
// [0.01, 2] m/s, tc/dt from the coarsest the guard admits (5, or 6 with
// limitForce) to 40, integer in a third, the geometry and limitForce at random.
// Tolerances: energy 1e-9 of the incoming (round-off); the contact point on a
// wall 1e-3 of vt (LIGGGHTS' arm R - overlap/2 changes the drive's mass by
// up to 0.5 overlap / R: 1e-3 at 2 m/s); step independence: 0.5 % of the
// incoming speed at tc/dt >= 10 and 1 % coarser, the target (the normal
// exit rate against the normal speed, the tangential against the speed).
TEST(ExactCollisionSweep, RandomCollisionsKeepTheirInvariantsAndDoNotDependOnTheStep)
{
    std::mt19937 g(4711);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double worstN10 = 0, worstT10 = 0, worstN5 = 0, worstT5 = 0, worstGain = -1;
    int collisions = 0;
    for (int i = 0; i < 24; ++i) {
        Case c;
        const double pick = u(g);
        c.geometry = pick < 0.4 ? Geometry::Pair : pick < 0.8 ? Geometry::Wall : Geometry::MeshWall;
        c.limitForce = u(g) < 0.5;
        const double en = 0.15 + 0.8 * u(g);
        const double et = u(g) < 0.33 ? en : 0.15 + 0.8 * u(g);
        c.params = {1e-4, en, et, 0.05 * std::pow(2e7, u(g))};
        c.normalSpeed = 0.01 * std::pow(200.0, u(g));
        c.tangentialSpeed = 5.0 * u(g) * c.normalSpeed;
        const double coarsest = c.limitForce ? 6.0 : 5.0;
        double ratio = coarsest + (40.0 - coarsest) * u(g);
        if (u(g) < 0.33) ratio = std::round(ratio);
        if (c.limitForce && en < 0.2) c.params.en = 0.2;  // a cut contact restitutes at least 0.137
        c.dt = c.params.tc / ratio;
        const std::string tag = "sweep_" + std::to_string(i);
        char what[256];
        std::snprintf(what, sizeof what, "%s limitForce %d en %.3f et %.3f mu %.3g vn %.3f vt/vn %.3f tc/dt %.2f",
                      name(c.geometry).c_str(), c.limitForce, c.params.en, c.params.et, c.params.mu, c.normalSpeed,
                      c.tangentialSpeed / c.normalSpeed, ratio);
        const std::vector<double> phases = randomPhases(g, 16);
        std::vector<Trajectory> runs;
        try {
            runs = runLiggghts(c, options(tag, "exactCollision on"), phases);
        } catch (const std::exception& e) {
            // the guard refuses steps beyond the applied law's stable step (a stiff tangential law): say so
            const std::string m = e.what();
            ASSERT_NE(m.find("exceeds the stable timestep"), std::string::npos) << what << ": " << m;
            std::printf("%s: refused by the guard\n", what);
            continue;
        }
        Case fine = c;
        fine.dt = c.params.tc / 1000.0;
        const Outcome ref = measureTrajectory(fine, runLiggghts(fine, options(tag + "_fine", "exactCollision on"), {0.5})[0]);
        for (const Trajectory& t : runs) {
            const Outcome o = measureTrajectory(c, t);
            ++collisions;
            const BodyStates& first = t.frames.front();
            const BodyStates& last = t.frames.back();
            const double gain = kineticEnergy(c, last) / kineticEnergy(c, first) - 1.0;
            worstGain = std::max(worstGain, gain);
            EXPECT_LT(gain, 1e-9) << what;
            if (c.isWall() && c.tangentialSpeed > 0.0)
                EXPECT_LT(std::fabs(o.tangentialRestitution), 1.0 + 1e-3) << "the contact point left faster: " << what;
            const double dn = std::fabs(o.restitution - ref.restitution);
            const double dtan = c.tangentialSpeed > 0.0
                                    ? std::fabs(o.tangentialRestitution - ref.tangentialRestitution) *
                                          c.tangentialSpeed / std::hypot(c.normalSpeed, c.tangentialSpeed)
                                    : 0.0;
            const double tol = ratio >= 10.0 ? 0.005 : 0.01;
            EXPECT_LT(dn, tol) << what;
            EXPECT_LT(dtan, tol) << what;
            double& wn = ratio >= 10.0 ? worstN10 : worstN5;
            double& wt = ratio >= 10.0 ? worstT10 : worstT5;
            wn = std::max(wn, dn), wt = std::max(wt, dtan);
        }
        std::printf("%s: tc/1000 en %.5f et %.5f\n", what, ref.restitution, ref.tangentialRestitution);
    }
    std::printf("%d collisions: worst energy change %+.2e; against tc/1000 (of the incoming speed), tc/dt >= 10: "
                "normal %.2e, tangential %.2e; coarser: %.2e, %.2e\n",
                collisions, worstGain, worstN10, worstT10, worstN5, worstT5);
    EXPECT_GT(collisions, 300);
}

// The two laws, stated: exactCollision's spring turns at the rigid arm R,
// the plain law's at LIGGGHTS' R - overlap/2. For the bead-drum pair sticking
// on a wall (en = et = 0.46, mu 5, vt/vn 0.2) exactCollision restitutes et
// itself at every speed (the closed form above), the plain law at tc/2000
// more, by a part that grows in proportion to the speed (the overlap over R:
// 1.5 % of R at 1 m/s), 0.0063 per m/s measured, on top of the step's own
// error (3e-4 at tc/2000, the same at every speed). So the difference is the
// arm alone: the slope is the same between 0.2 and 1 m/s as between 1 and
// 2 m/s within 2 % (the next order of overlap / R), and positive.
TEST(ExactCollisionSweep, TwoLawsDifferByTheLeverArmAlone)
{
    const auto etAt = [](double vn, double ratio, const std::string& settings, const std::string& tag) {
        Case c;
        c.geometry = Geometry::Wall;
        c.params = {1e-4, 0.46, 0.46, 5.0};
        c.normalSpeed = vn;
        c.tangentialSpeed = 0.2 * vn;
        c.dt = c.params.tc / ratio;
        return measureTrajectory(c, runLiggghts(c, options(tag, settings), {0.5})[0]).tangentialRestitution;
    };
    const double plain02 = etAt(0.2, 2000, "", "arm_plain_02"), plain1 = etAt(1.0, 2000, "", "arm_plain_1"),
                 plain2 = etAt(2.0, 2000, "", "arm_plain_2");
    const double exact1 = etAt(1.0, 10, "exactCollision on", "arm_exact_1");
    const double low = (plain1 - plain02) / 0.8, high = (plain2 - plain1) / 1.0;
    std::printf("plain law at tc/2000: et %.6f, %.6f, %.6f at 0.2, 1, 2 m/s (slopes %.5f, %.5f per m/s); "
                "exactCollision at tc/10, 1 m/s: %.6f\n", plain02, plain1, plain2, low, high, exact1);
    EXPECT_NEAR(exact1, 0.46, 1e-9);
    EXPECT_GT(low, 0.0);
    EXPECT_NEAR(high / low, 1.0, 0.02);
}

// Every single collision against the same mode at tc/1000, 64 random start
// phases per case: Table 3.1's beads (en 0.56, et 0.46, mu 0.5) and bead-drum
// pair (en = et = 0.46, mu 0.95), wall and pair, sticking (vt/vn 0.2) and
// sliding (vt/vn 4), limitForce off and on, at tc/5 (the coarsest the guard
// admits with limitForce: 5.6 for the beads), tc/7.3 and tc/10. The target:
// 0.5 % at tc/10 and 1 % coarser, of en and of the tangential velocity
// change (what friction did), in every case. (A pair sliding at vt/vn 4 missed
// it at tc/5, 1.6 % for the bead-drum pair, while its first step took the pull
// |vt|^2 / d as constant from the touch: core/exact_tangential.h's
// pullRateSinceTouch.)
TEST(ExactCollisionSweep, EverySingleCollisionAtSixtyFourPhasesMatchesTheFineStep)
{
    std::mt19937 g(64);
    struct M { const char* name; viscoelastic::ContactParameters p; };
    double worst10 = 0.0, worstCoarse = 0.0;
    int beyondTarget = 0;
    for (const M& m : {M{"beads", {1e-4, 0.56, 0.46, 0.5}}, M{"bead-drum", {1e-4, 0.46, 0.46, 0.95}}})
    for (Geometry geometry : {Geometry::Wall, Geometry::Pair})
    for (double slope : {0.2, 4.0})
    for (bool limitForce : {false, true}) {
        Case c;
        c.geometry = geometry;
        c.limitForce = limitForce;
        c.params = m.p;
        c.normalSpeed = 1.0;
        c.tangentialSpeed = slope;
        const std::string tag = std::string("phases64_") + m.name + "_" + name(geometry) + (limitForce ? "_lf" : "") +
                                (slope > 1.0 ? "_slide" : "_stick");
        Case fine = c;
        fine.dt = c.params.tc / 1000.0;
        const Outcome ref = measureTrajectory(fine, runLiggghts(fine, options(tag + "_fine", "exactCollision on"), {0.5})[0]);
        for (double ratio : {limitForce ? 5.6 : 5.0, 7.3, 10.0}) {
            c.dt = c.params.tc / ratio;
            const std::vector<Trajectory> runs =
                runLiggghts(c, options(tag + "_" + std::to_string(int(10 * ratio)), "exactCollision on"), randomPhases(g, 64));
            double worst = 0.0;
            for (const Trajectory& t : runs) {
                const Outcome o = measureTrajectory(c, t);
                const double dn = std::fabs(o.restitution / ref.restitution - 1.0);
                const double dtan = std::fabs((1.0 + o.tangentialRestitution) / (1.0 + ref.tangentialRestitution) - 1.0);
                worst = std::max({worst, dn, dtan});
            }
            const double target = ratio >= 10.0 ? 0.005 : 0.01;
            EXPECT_LT(worst, target) << tag << " tc/dt " << ratio;
            std::printf("%s tc/dt %.1f: worst %.2e\n", tag.c_str(), ratio, worst);
            if (worst > target) ++beyondTarget;
            (ratio >= 10.0 ? worst10 : worstCoarse) = std::max(ratio >= 10.0 ? worst10 : worstCoarse, worst);
        }
    }
    std::printf("worst single collision of 64 phases against tc/1000: %.2e at tc/10, %.2e at tc/5-tc/7.3; %d of 48 "
                "cases beyond the 0.5 %% / 1 %% target\n", worst10, worstCoarse, beyondTarget);
}

// exactRestitution's phase mean of a sticking wall collision (vn 0.2 m/s,
// vt/vn 0.2, mu 5: the case; and mu 0.5 for the beads' et != en) at
// tc/5, tc/7.3 and tc/10, 256 phases, against the same mode at tc/1000 (the
// request plus LIGGGHTS' lever arm, +0.27 % at this speed, or the law's own
// et where its spring lets go at the normal force's zero). Within 0.1 %; the
// solve that ignored pournin's spring restart at that zero was +2.2 % off at
// tc/5 and +1.0 % at tc/7.3.
TEST(ExactCollisionSweep, ExactRestitutionsTangentialMeanHoldsAtCoarseSteps)
{
    for (const viscoelastic::ContactParameters& p :
         {viscoelastic::ContactParameters{1e-4, 0.46, 0.46, 5.0}, viscoelastic::ContactParameters{1e-4, 0.56, 0.46, 0.5}}) {
        Case c;
        c.geometry = Geometry::Wall;
        c.exactRestitution = true;
        c.params = p;
        c.normalSpeed = 0.2;
        c.tangentialSpeed = 0.04;
        c.dt = p.tc / 1000.0;
        const double fine = meanOutcome(c, runLiggghts(c, options("exactrest_fine"), {0.25, 0.75})).tangentialRestitution;
        for (double ratio : {5.0, 7.3, 10.0}) {
            c.dt = p.tc / ratio;
            const double mean = meanOutcome(c, runLiggghts(c, options("exactrest_" + std::to_string(int(10 * ratio))),
                                                           evenPhases(256))).tangentialRestitution;
            std::printf("en %.2f et %.2f tc/dt %.1f: mean et %.5f against %.5f at tc/1000 (%+.3f %%)\n", p.en, p.et,
                        ratio, mean, fine, 100.0 * (mean / fine - 1.0));
            EXPECT_NEAR(mean / fine, 1.0, 1e-3) << "en " << p.en << " tc/dt " << ratio;
        }
    }
}
