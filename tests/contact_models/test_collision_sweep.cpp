// exactCollision's wall collision with friction, stepped by the core, over a
// seeded random sweep of materials, friction, incidence, timestep and start
// phase, checked by invariants that need no reference solution:
//  - a flat wall's tangential motion is passive: the contact point never
//    leaves faster than it came (with the spring's mass constant, 2/7 meff,
//    the bead's kinetic energy is a growing function of |vt|), nor normally;
//  - the result does not depend on the step: against the same mode at
//    tc/1000 from the same start phase;
// and, where the law has a closed answer independent of the code, against it:
//  - en = et (limitForce off): the tangential and normal oscillators are the
//    same, so the sticking spring's force is vt/vn times the normal force at
//    every instant; below the cap (vt/vn < mu meff / m_t) the contact sticks
//    throughout and the contact point leaves at exactly -et vt. Its force and
//    cap vanish together at the normal force's zero, where the old event loop
//    stalled and then slid through the rest of the step (up to 87 times the
//    incoming speed, forward).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "core/collision.h"
#include "core/stability.h"
#include "pair_stepper.h"

using namespace viscoelastic;

namespace {

constexpr double kMassRatio = 2.0 / 7.0;  // the spring's mass per unit meff: a sphere on a wall

struct Draw {
    ContactParameters p;
    double slope;  // vt / vn
    bool limitForce;
    double ratio;  // tc / dt
    double phase;
};

// nullopt: the draw's step exceeds the applied law's stable step (the model
// refuses it), or limitForce cannot restitute its en.
std::optional<FrictionalExit> wallExit(const Draw& d, double ratio, double phase)
{
    const auto o = exactCollisionOscillators(d.p, d.limitForce);
    if (!o) return std::nullopt;
    const double dt = d.p.tc / ratio;
    const StepLaw normal = stepLaw(o->normal.k, o->normal.c, dt, d.limitForce);
    const StepLaw tangential = stepLaw(o->tangential.k, o->tangential.c, dt, false);  // as the model builds it
    if (dt > stableTimestep(appliedCoefficients(normal, tangential))) return std::nullopt;
    return exactWallCollisionAtPhase(normal, tangential, phase, d.slope, d.p.mu,
                                     [](double) { return kMassRatio; });
}

// The worst of these start phases against tc/1000 (pair_stepper.h); NaN
// where the model refuses the step.
double worstOverPhases(pairstepper::Setup c, const std::vector<double>& phases)
{
    double worst = 0.0;
    for (double phase : phases) {
        c.phase = phase;
        const auto off = pairstepper::offTheFineStep(c);
        if (!off) return std::nan("");
        worst = std::max(worst, *off);
    }
    return worst;
}

// The worst of 64 evenly spread start phases, printed, against the target
// at c's step (0.5 % of the incoming speed at tc/dt >= 10, 1 % coarser).
void meetsTheTargetAtSixtyFourPhases(const pairstepper::Setup& c)
{
    std::vector<double> phases;
    for (int k = 0; k < 64; ++k) phases.push_back((k + 0.5) / 64.0);
    const double worst = worstOverPhases(c, phases);
    std::printf("worst of 64 phases against tc/1000: %.2e of the incoming speed\n", worst);
    EXPECT_LT(worst, c.ratio >= 10.0 ? 0.005 : 0.01);
}

}  // namespace

// en, et in [0.1, 0.95] (et = en in 30 % of draws: the case above), mu
// log-uniform in [0.05, 100] (80 %) or [0.05, 1e6], vt/vn uniform in [0, 5] or
// log-uniform in [0.01, 1], limitForce on or off, tc/dt in [5, 100] (integer
// in 30 %), the start phase uniform. Tolerances: 1e-9 of the incoming speed
// for the invariants (round-off); 1e-6 for the step independence and the
// closed form: the scheme is exact up to its root finders, which stop within
// 1e-10 of their brackets (worst seen over 15,000 draws: 2.1e-8).
TEST(ExactCollisionSweep, WallCollisionsNeverGainEnergyAndDoNotDependOnTheStep)
{
    std::mt19937 g(20261206);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int run = 0, enEqualsEt = 0;
    double worstStep = 0.0, worstClosed = 0.0;
    for (int i = 0; i < 4000; ++i) {
        Draw d;
        d.p.tc = 1e-4;
        d.p.en = 0.1 + 0.85 * u(g);
        d.p.et = u(g) < 0.3 ? d.p.en : 0.1 + 0.85 * u(g);
        d.p.mu = 0.05 * std::pow(u(g) < 0.8 ? 2e3 : 2e7, u(g));
        d.slope = u(g) < 0.5 ? 5.0 * u(g) : std::pow(10.0, -2.0 + 2.0 * u(g));
        d.limitForce = u(g) < 0.5;
        d.ratio = u(g) < 0.3 ? std::round(5.0 + 95.0 * u(g)) : 5.0 + 95.0 * u(g) * u(g);
        d.phase = 1.0 - u(g);
        const auto coarse = wallExit(d, d.ratio, d.phase);
        if (!coarse) continue;
        const auto fine = wallExit(d, 1000.0, d.phase);
        ASSERT_TRUE(fine);
        ++run;
        const std::string what = "en " + std::to_string(d.p.en) + " et " + std::to_string(d.p.et) + " mu " +
                                 std::to_string(d.p.mu) + " vt/vn " + std::to_string(d.slope) + " limitForce " +
                                 std::to_string(d.limitForce) + " tc/dt " + std::to_string(d.ratio) + " phase " +
                                 std::to_string(d.phase);
        EXPECT_LE(std::fabs(coarse->tangential), d.slope + 1e-9) << "the contact point left faster: " << what;
        EXPECT_LE(std::fabs(coarse->normal), 1.0 + 1e-9) << what;
        const double stepN = std::fabs(coarse->normal - fine->normal);
        const double stepT = std::fabs(coarse->tangential - fine->tangential) / std::max(d.slope, 1e-2);
        worstStep = std::max({worstStep, stepN, stepT});
        EXPECT_LT(stepN, 1e-6) << what;
        EXPECT_LT(stepT, 1e-6) << what;
        if (d.p.en == d.p.et && !d.limitForce && d.slope < d.p.mu / kMassRatio) {
            ++enEqualsEt;
            const double closed = std::fabs(coarse->tangential + d.p.et * d.slope) / std::max(d.slope, 1e-2);
            worstClosed = std::max(worstClosed, closed);
            EXPECT_LT(closed, 1e-6) << "en = et sticks throughout: " << what;
        }
    }
    std::printf("%d collisions (%d with en = et, sticking): worst change against tc/1000 %.2e, against -et vt %.2e\n",
                run, enEqualsEt, worstStep, worstClosed);
    EXPECT_GT(run, 3000);
    EXPECT_GT(enEqualsEt, 150);
}

// Two spheres at incidence, stepped by the core as LIGGGHTS steps them
// (pair_stepper.h), over a seeded random sweep of drawPair's default ranges
// (mu 0.05-1e6, vt/vn 0-5, vn 0.01-2 m/s, spins to 2 vn / R, tc/5-tc/100,
// limitForce on and off, the start phase uniform). Between
// two spheres the normal turns within a step and the pull |vt|^2 / d is
// taken per step, so the scheme is not exact to round-off as on a wall; the
// claim is the target: against the same mode at tc/1000 from the same touch,
// the relative velocity and the contact speeds of the spins (R w) after the
// contact within 0.5 % of the incoming speed at tc/dt >= 10 and 1 % coarser.
// No collision ends with more kinetic and rotational energy than it began
// with (1e-9 of it: round-off). A fast sliding pair's first step took the
// pull as constant from the touch, while friction turned vt: 1.6 % at tc/5
// for the bead-drum pair at vt/vn 4.
TEST(ExactCollisionSweep, PairCollisionsNeverGainEnergyAndMeetTheTargetAgainstTheFineStep)
{
    std::mt19937 g(4712);
    int run = 0;
    double worstGain = -1.0, worst10 = 0.0, worstCoarse = 0.0;
    for (int i = 0; i < 3000; ++i) {
        pairstepper::Setup c = pairstepper::drawPair(g, {});
        const double ratio = c.ratio;
        const auto coarse = pairstepper::steppedPair(c);
        if (!coarse) continue;
        c.ratio = 1000.0;
        const auto fine = pairstepper::steppedPair(c);
        ASSERT_TRUE(fine);
        ++run;
        char what[256];
        std::snprintf(what, sizeof what, "en %.3f et %.3f mu %.3g vn %.3f vt/vn %.3f spin %d limitForce %d tc/dt %.2f "
                      "phase %.3f", c.p.en, c.p.et, c.p.mu, c.vn, c.vt / c.vn, c.spinI.squaredNorm() > 0.0,
                      c.limitForce, ratio, c.phase);
        const double gain = coarse->energyOut / coarse->energyIn - 1.0;
        worstGain = std::max(worstGain, gain);
        EXPECT_LT(gain, 1e-9) << what;
        const double off = pairstepper::apart(*coarse, *fine, c);
        const double target = ratio >= 10.0 ? 0.005 : 0.01;
        EXPECT_LT(off, target) << what;
        double& worst = ratio >= 10.0 ? worst10 : worstCoarse;
        worst = std::max(worst, off);
    }
    std::printf("%d pair collisions: worst energy change %+.2e; against tc/1000 (of the incoming speed): %.2e at "
                "tc/dt >= 10, %.2e coarser\n", run, worstGain, worst10, worstCoarse);
    EXPECT_GT(run, 2250);
}

// A spinning pair sliding on the cap (en 0.1747, et 0.1106, mu 0.7007, vn
// 1.509 m/s, vt/vn 3.93, spins of 110 and 5,939 rad/s, tc/10.45, limitForce
// off; a draw of the sweep above with spins up to 6 vn / R). The tangential
// force turns vt so that the pull, and with it the normal force, leaves the
// last step's forecast every step. Restarting the slide as a free spring on
// every such miss left it 2.9-4.6 % of the incoming speed off at all 64
// phases; going on on the cap unless the cap more than doubled: 0.1-0.27 %.
TEST(ExactCollisionSweep, ASpinningPairsSlideGoesOnOnTheCapWhileThePullMovesTheForce)
{
    pairstepper::Setup c;
    c.p = {1e-4, 0.1747, 0.1106, 0.7007};
    c.vn = 1.5091, c.vt = 3.9301 * 1.5091;
    c.spinI = Vec3(100.14031978701904, -17.542133544318137, 42.860406929636852);
    c.spinJ = Vec3(1881.4631166999461, -4307.9997669497079, 3629.2943303175339);
    c.ratio = 10.4544;
    meetsTheTargetAtSixtyFourPhases(c);
}

// A grazing pair (en 0.2643, et 0.8674, mu 1e6, vn 1.865 m/s, vt/vn 2,
// tc/6, limitForce off) whose overlap, forecast to be just positive one step
// on, landed 1.6e-9 m outside the surface: the pull that lands it is the one
// after the step's kick, and the tangential force had changed it. The
// contact went without its end step and left with the leapfrog's rate, 3.1 %
// of the incoming speed off at start phases 0.29-0.31. An end step is now
// taken within dt^2 times the pull's change of the surface (StepLaw's
// endPullMargin): within the 1 % target at tc/6.
TEST(ExactCollisionSweep, AContactWhoseLastSampleLandsOutsideByThePullsChangeTakesItsEndStep)
{
    pairstepper::Setup c;
    c.p = {1e-4, 0.2643, 0.8674, 1e6};
    c.vn = 1.8651, c.vt = 2.0 * 1.8651;
    c.ratio = 6.0;
    std::vector<double> phases;
    for (int k = 0; k <= 40; ++k) phases.push_back(0.28 + 0.001 * k);
    const double worst = worstOverPhases(c, phases);
    std::printf("worst of 41 phases in 0.28-0.32 against tc/1000: %.2e of the incoming speed\n", worst);
    EXPECT_LT(worst, 0.01);
}

// A draw of that sweep (en 0.721, et 0.931, mu 2.48, vn 1.094 m/s, vt/vn
// 3.159, spins of 944 and 1,397 rad/s), at tc/5 with limitForce off where
// the draw had tc/5.55 and on; 64 start phases. The tangential force turns
// vt so that the pull falls by
// 90 % within a step, and the normal force moves off its forecast by 7 % of
// that fall. Bounded by this step's pull alone, the contact was taken for
// one in a packing and got the per-step bound: 2.7 % off the fine step.
// Within the target now.
TEST(ExactCollisionSweep, FastSpinningPairKeepsFollowingItsForecastWhenThePullFalls)
{
    pairstepper::Setup c;
    c.p = {1e-4, 0.721, 0.931, 2.48};
    c.vn = 1.094, c.vt = 3.159 * 1.094;
    c.spinI = Vec3(-32.917340091687784, -454.01563282534369, 826.73801536325175);
    c.spinJ = Vec3(627.99970313889935, 900.52052274461471, 865.09242471695575);
    c.ratio = 5.0;
    meetsTheTargetAtSixtyFourPhases(c);
}

// A grazing pair whose normal force near the end of the contact missed its
// forecast (the pull changed within the step): the last step had slid on the
// cap of the forecast force, 18 per unit mass, and the step put the spring
// onto the cap of the force it found, 799, where it stuck: 14 % of the
// incoming speed off the fine step (en 0.5062, et 0.8901, mu 4278, vn
// 1.995 m/s, vt/vn 5, limitForce on, tc/10.3756, start phases 0.995 to
// 0.999, where the force ends just after a sample). Within the 0.5 % target
// now, 0.10-0.14 %. (At 0.99 this grazing pair is 0.51 % off, before as now:
// its normal turns by 0.032 rad a step, docs/law.md (iv).)
TEST(ExactCollisionSweep, ASlideDoesNotClimbACapThatMovedWithAMissedForecast)
{
    pairstepper::Setup c;
    c.p = {1e-4, 0.5062, 0.8901, 4278.0};
    c.vn = 1.995, c.vt = 5.0 * 1.995;
    c.limitForce = true;
    c.ratio = 10.3756;
    const double worst = worstOverPhases(c, {0.995, 0.995625, 0.996, 0.997, 0.999});
    std::printf("worst of 5 phases against tc/1000: %.2e of the incoming speed\n", worst);
    EXPECT_LT(worst, 0.005);
}

// The failure as first seen, at Table 3.1's bead-drum pair (en = et = 0.46),
// vt/vn 0.2, tc/10: 64 start phases, mu 0.5 to 10 (the worst phase left at
// -0.11, then +1.1, +3.7 and +7.9 times vt for mu 0.5, 2, 5, 10).
TEST(ExactCollisionSweep, TableBeadDrumPairSticksToMinusEtAtEveryPhase)
{
    for (double mu : {0.5, 2.0, 5.0, 10.0}) {
        Draw d{{1e-4, 0.46, 0.46, mu}, 0.2, false, 10.0, 0.0};
        double worst = 0.0;
        for (int k = 0; k < 64; ++k) {
            const auto e = wallExit(d, d.ratio, (k + 0.5) / 64.0);
            ASSERT_TRUE(e);
            worst = std::max(worst, std::fabs(e->tangential / d.slope + d.p.et));
        }
        EXPECT_LT(worst, 1e-6) << "mu " << mu;
        std::printf("mu %g: worst phase off -et by %.2e of vt\n", mu, worst);
    }
}

// The guard's advice holds when used: the coarsest step it names is admitted
// and a step 0.1 % coarser is refused (the applied laws change with the step:
// the bound seen at a refused step was refused again, e.g. en 0.3 / et 0.8
// with limitForce: 1.789e-5 s at tc/5, 1.740e-5 s at 1.786e-5 s).
TEST(ExactCollisionSweep, TheGuardsCoarsestStepIsAdmittedAndNothingCoarser)
{
    for (const ContactParameters& p : {ContactParameters{1e-4, 0.3, 0.8, 0.5}, ContactParameters{1e-4, 0.46, 0.46, 0.95},
                                       ContactParameters{1e-4, 0.9, 0.2, 0.5}, ContactParameters{2e-5, 0.56, 0.95, 1e6}})
        for (bool limitForce : {false, true}) {
            const auto o = exactCollisionOscillators(p, limitForce);
            ASSERT_TRUE(o);
            const double step = coarsestStableStep(o->normal, o->tangential, p.tc, limitForce);
            EXPECT_TRUE(stableAt(o->normal, o->tangential, step, limitForce));
            EXPECT_FALSE(stableAt(o->normal, o->tangential, 1.001 * step, limitForce));
            std::printf("en %.2f et %.2f limitForce %d: coarsest tc/%.3f\n", p.en, p.et, limitForce, p.tc / step);
        }
}

// At the sticking threshold (en = et, vt/vn = mu meff / m_t to round-off) the
// spring rides the cap from the first touch through the normal force's zero,
// where stick and slide alternate at every instant and the events run out:
// the law still leaves at -et vt (sticking and sliding are the same motion
// there). A slide held in its last direction past the zero left up to 14 %
// of vt faster (Table 3.1's bead-drum pair, mu 0.95, vt/vn 3.325, tc/5: 13 of
// 256 phases at -0.577 vt). Random en and mu, 64 phases each, the
// threshold computed as the test computes it and one unit in the last place
// on either side.
TEST(ExactCollisionSweep, AtTheStickingThresholdEnEqualsEtStillLeavesAtMinusEt)
{
    std::mt19937 g(3325);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double worst = 0.0;
    for (int i = 0; i < 60; ++i) {
        const double e = 0.1 + 0.85 * u(g), mu = 0.05 * std::pow(100.0, u(g));
        double slope = mu / kMassRatio;
        if (i % 3 == 1) slope = std::nextafter(slope, 0.0);
        if (i % 3 == 2) slope = std::nextafter(slope, 1e300);
        Draw d{{1e-4, e, e, mu}, slope, false, i == 0 ? 5.0 : 5.0 + 15.0 * u(g), 0.0};
        if (i == 0) d.p = {1e-4, 0.46, 0.46, 0.95}, d.slope = 3.325;
        for (int k = 0; k < 64; ++k) {
            const auto exit = wallExit(d, d.ratio, (k + 0.5) / 64.0);
            if (!exit) break;
            const double off = std::fabs(exit->tangential / d.slope + d.p.et);
            worst = std::max(worst, off);
            EXPECT_LT(off, 1e-6) << "en = et " << e << " mu " << mu << " vt/vn " << d.slope << " tc/dt " << d.ratio
                                 << " phase " << (k + 0.5) / 64.0 << ": " << exit->tangential / d.slope;
        }
    }
    std::printf("at the threshold: worst phase off -et by %.2e of vt\n", worst);
}
