// exactCollision's pair collisions, stepped by the core as LIGGGHTS steps
// them (tests/contact_models/pair_stepper.h), against the independent
// continuous reference of the law between two spheres
// (tools/collide/continuous_pair.h: uses nothing of contact_models/), over a
// seeded random sweep of drawPair's default ranges (en, et 0.1-0.95, mu
// 0.05-1e6, vn 0.01-2 m/s, vt/vn 0-5, spins to 2 vn / R in half the draws,
// tc/dt 5-100, the start phase uniform) with limitForce off (the reference
// has no cut law).  The reference starts at the touch with the stepper's
// incoming state (its free flight changes no velocity).  Distance of two
// outcomes: pairstepper::apart, max(|dV|, R |dwi|, R |dwj|) over the
// incoming speed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <random>
#include <string>
#include <vector>

#include "continuous_pair.h"
#include "pair_stepper.h"

namespace {

struct Outcome {
    pairstepper::Setup c;  // as drawn (limitForce off), c.ratio the drawn tc/dt
    pairstepper::Run law;  // the reference's outcome (V, wi, wj)
    double fine;           // the step at tc/1000 off the reference
    double coarse;         // the step at c.ratio off the reference
    double pull;           // the largest pull |vt|^2 / d of the fine step over the force scale pi vn / tc
    double reference;      // the reference's change between N and 2N steps, of the incoming speed
};

// The reference's outcome of the stepper's collision c, from its touch
// (the free flight before changes no velocity) between two of its beads; and
// its change between N and 2N steps.
struct Law {
    pairstepper::Run run;
    double change;
};
Law lawOf(const pairstepper::Setup& c)
{
    const double R = pairstepper::kRadius, m = pairstepper::kMass;
    const auto arr = [](const viscoelastic::Vec3& v) { return continuous::Vector{v.x(), v.y(), v.z()}; };
    const continuous::PairTouch touch{{-2.0 * R, 0.0, 0.0}, {c.vn, c.vt, 0.0}, arr(c.spinI), arr(c.spinJ)};
    const continuous::PairExit e = continuous::pairCollision({c.p.tc, c.p.en, c.p.et, c.p.mu}, {m, R}, {m, R}, touch);
    Law law{{}, e.change};
    law.run.V = {e.v[0], e.v[1], e.v[2]}, law.run.wi = {e.wi[0], e.wi[1], e.wi[2]};
    law.run.wj = {e.wj[0], e.wj[1], e.wj[2]};
    return law;
}

// 2000 draws: about 18 s of one core in Release (the reference ~10 ms a draw)
constexpr int kDraws = 2000;

// All draws, stepped and integrated once for the tests below.
const std::vector<Outcome>& outcomes()
{
    static const std::vector<Outcome> all = [] {
        std::mt19937 g(1);
        std::vector<Outcome> out;
        for (int i = 0; i < kDraws; ++i) {
            pairstepper::Setup c = pairstepper::drawPair(g, {});
            c.limitForce = false;
            const auto runs = pairstepper::coarseAndFine(c);
            if (!runs) continue;  // a step the model refuses
            const pairstepper::Run *coarse = &runs->coarse, *fine = &runs->fine;
            const Law law = lawOf(c);
            out.push_back({c, law.run, pairstepper::apart(*fine, law.run, c), pairstepper::apart(*coarse, law.run, c),
                           fine->largestPull / (viscoelastic::kPi * c.vn / c.p.tc),
                           law.change / std::hypot(c.vn, c.vt)});
        }
        return out;
    }();
    return all;
}

bool spinning(const Outcome& o) { return o.c.spinI.squaredNorm() > 0.0 || o.c.spinJ.squaredNorm() > 0.0; }

std::string describe(const Outcome& o)
{
    const double R = pairstepper::kRadius, u = o.c.vn / R;
    char s[400];
    std::snprintf(s, sizeof s,
                  "en %.4f et %.4f mu %.4g vn %.4g vt/vn %.4f spinI (%.3f %.3f %.3f) spinJ (%.3f %.3f %.3f) vn/R "
                  "tc/dt %.3f phase %.3f largest pull %.3g of pi vn/tc: tc/1000 %.2e, coarse %.2e",
                  o.c.p.en, o.c.p.et, o.c.p.mu, o.c.vn, o.c.vt / o.c.vn, o.c.spinI.x() / u, o.c.spinI.y() / u,
                  o.c.spinI.z() / u, o.c.spinJ.x() / u, o.c.spinJ.y() / u, o.c.spinJ.z() / u, o.c.ratio, o.c.phase,
                  o.pull, o.fine, o.coarse);
    return s;
}

// The distribution of one difference over the draws that `take`.
template <class Take, class Of>
void printDistribution(const char* what, Take take, Of of)
{
    std::vector<double> v;
    for (const Outcome& o : outcomes())
        if (take(o)) v.push_back(of(o));
    std::sort(v.begin(), v.end());
    if (v.empty()) return;
    const auto above = [&](double t) { return v.end() - std::upper_bound(v.begin(), v.end(), t); };
    std::printf("%-34s %4zu draws: median %.1e, 99 %% %.1e, worst %.2e; above 1e-6 %ld, 1e-5 %ld, 1e-4 %ld, "
                "1e-3 %ld, 0.5 %% %ld, 1 %% %ld\n",
                what, v.size(), v[v.size() / 2], v[v.size() * 99 / 100], v.back(), above(1e-6), above(1e-5),
                above(1e-4), above(1e-3), above(5e-3), above(1e-2));
}

// One test for the checks below, (a) without and with spin and (b), so that
// ctest (a process per test) steps and integrates the draws once.
//
// The reference is converged far below what is compared: between N = 1e4 and
// 2e4 steps its exit moves by under 1e-6 of the incoming speed (measured
// 4.0e-7 over these draws), and its extrapolation, which these tests use,
// lies within 3.1e-9 of that from 4e4 (continuous_pair.h).
//
// (a) The stepper at tc/1000 follows the law: what is left is its own
// error, first order, plus the reference's (~1e-9).  Tolerance 1e-5 of the
// incoming speed: on the draws without spin the tc/1000 step lies at most
// 1.35e-6 off the law (measured, 997 draws; the worst three halve from
// tc/1000 to tc/2000 and again to tc/4000: the steps converge to the law),
// so 1e-5 leaves that a margin of 7 and admits no departure from the law.
//
// On the draws WITH spin the same holds up to the first-order step error:
// measured, 976 spinning draws, 972 within 1e-5 at tc/1000 (worst 2.46e-5);
// the other 4 lie within 5.3e-6 at tc/4000 (before a sticking spring moved by
// its drive's mean: 17, up to 2.73e-5, within 2.4e-6 to 6.9e-6 at tc/4000, 5e-7
// to 1.6e-6 at tc/16000). So a draw off by 1e-5 or more at tc/1000 is stepped again at
// tc/4000, where it must lie within 1e-5 and at most half as far off. Before a
// slide that the falling cap drives against the slip turned as the law turns
// it (detail::slidingDirection in core/capped_flow.h), 76 spinning draws lay
// 1e-5 or more off, 23 above 1e-4, the worst 2.25e-3 (en 0.747, mu 0.659, vn
// 1.50 m/s, vt/vn 3.10, spins (-0.07 0.32 -0.36) and (1.04 -0.20 -0.92) vn/R,
// tc/dt 8.25), and 65 of the 76 stayed at least half as far off at tc/8000:
// the steps converged to another law. That takes a sideways loading rate (a
// spin about the normal, or across it), hence spinning draws only. The
// reference is not the one off: a literal fine stepper of the law, written
// apart (tests/collide/test_continuous_pair.cpp), agrees with it on the worst
// of these draws to 1e-7.
//
// (b) The coarse step against the law: the project's target, 0.5 % of the
// incoming speed at tc/dt >= 10, 1 % coarser (the same as against its own
// step at tc/1000 in tests/contact_models/test_collision_sweep.cpp, here
// against the law itself).  Measured: at tc/dt >= 10 (1679 draws) at most
// 9.6e-4; coarser (294) at most 1.49e-3, 5 above 1e-3.
TEST(PairAgainstContinuous, StepsFollowTheLawAndMeetTheTarget)
{
    double worst = 0.0;
    for (const Outcome& o : outcomes()) worst = std::max(worst, o.reference);
    std::printf("%zu draws: the reference's change between 1e4 and 2e4 steps at most %.1e of the incoming speed\n",
                outcomes().size(), worst);
    EXPECT_LT(worst, 1e-6);
    EXPECT_GT(outcomes().size(), 0.95 * kDraws);

    int run = 0;  // (a) without spin
    for (const Outcome& o : outcomes()) {
        if (spinning(o)) continue;
        ++run;
        EXPECT_LT(o.fine, 1e-5) << "tc/1000 off the law: " << describe(o);
    }
    EXPECT_GT(run, 0.4 * kDraws);
    printDistribution("tc/1000 off the law, no spin:", [](const Outcome& o) { return !spinning(o); },
                      [](const Outcome& o) { return o.fine; });

    int finer = 0;  // (a) with spin: at tc/4000 where tc/1000's own error is 1e-5 or more
    double worstFiner = 0.0;
    for (const Outcome& o : outcomes()) {
        if (!spinning(o) || o.fine < 1e-5) continue;
        ++finer;
        pairstepper::Setup c = o.c;
        c.ratio = 4000.0;
        const auto run = pairstepper::steppedPair(c);
        ASSERT_TRUE(run) << describe(o);
        const double off = pairstepper::apart(*run, o.law, o.c);
        EXPECT_LT(off, 1e-5) << "spinning, tc/4000 off the law: " << off << ", " << describe(o);
        EXPECT_LT(off, 0.5 * o.fine) << "spinning, tc/4000 off the law: " << off << ", " << describe(o);
        worstFiner = std::max(worstFiner, off);
    }
    printDistribution("tc/1000 off the law, spinning:", spinning, [](const Outcome& o) { return o.fine; });
    std::printf("%d spinning draws 1e-5 or more off at tc/1000; at tc/4000 at most %.2e\n", finer, worstFiner);
    EXPECT_LT(finer, 40);  // (measured 4 of 976, 17 before the drive's mean: the step's own error, rare)

    for (const Outcome& o : outcomes())  // (b)
        EXPECT_LT(o.coarse, o.c.ratio >= 10.0 ? 0.005 : 0.01) << "the coarse step off the law: " << describe(o);
    printDistribution("coarse off the law, tc/dt >= 10:", [](const Outcome& o) { return o.c.ratio >= 10.0; },
                      [](const Outcome& o) { return o.coarse; });
    printDistribution("coarse off the law, tc/dt < 10:", [](const Outcome& o) { return o.c.ratio < 10.0; },
                      [](const Outcome& o) { return o.coarse; });
}

// The smallest case of the above: one bead spinning about the normal alone
// (vn/R = 667 rad/s at 1 m/s), vt/vn 3, en = et 0.7, mu 1: it sticks, then
// the falling cap drives the slide against the slip near the end. Left
// unturned there, the steps met another law: 1.49e-3 of the incoming speed
// off at tc/1000, tc/4000 and tc/16000. Measured now 2.0e-5, 4.8e-6 and
// 1.4e-6: first order, towards the law (1.4e-5, 3.4e-6 and 1.0e-6 before a
// sticking spring moved by its drive's mean; its slide keeps the sampled one).
TEST(PairAgainstContinuous, ATwistOnASlidingPairTurnsItsForceAsTheLawDoes)
{
    pairstepper::Setup c;
    c.p = {1e-4, 0.7, 0.7, 1.0};
    c.vn = 1.0, c.vt = 3.0, c.spinI = viscoelastic::Vec3(c.vn / pairstepper::kRadius, 0.0, 0.0), c.phase = 0.5;
    const pairstepper::Run law = lawOf(c).run;
    std::vector<double> off;
    for (double ratio : {1000.0, 4000.0, 16000.0}) {
        c.ratio = ratio;
        const auto run = pairstepper::steppedPair(c);
        ASSERT_TRUE(run);
        off.push_back(pairstepper::apart(*run, law, c));
    }
    std::printf("a twist alone, sliding: off the law %.2e, %.2e, %.2e at tc/1000, tc/4000, tc/16000\n", off[0], off[1],
                off[2]);
    EXPECT_LT(off[0], 3e-5);
    EXPECT_LT(off[1], 1e-5);
    EXPECT_LT(off[2], 0.5 * off[1]);
}

// For each tc/dt in `ratios`: the worst of `count` start phases (drawn
// uniformly with `seed`, the same at every step) of c stepped at that tc/dt,
// off the reference's outcome. Empty where a step is refused.
std::vector<double> worstOverPhases(pairstepper::Setup c, std::initializer_list<double> ratios, int count, unsigned seed)
{
    const pairstepper::Run law = lawOf(c).run;
    std::mt19937 g(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<double> phases(count);
    for (double& p : phases) p = 1.0 - u(g);
    std::vector<double> worst;
    for (double ratio : ratios) {
        c.ratio = ratio;
        double w = 0.0;
        for (double phase : phases) {
            c.phase = phase;
            const auto run = pairstepper::steppedPair(c);
            if (!run) return {};
            w = std::max(w, pairstepper::apart(*run, law, c));
        }
        worst.push_back(w);
    }
    return worst;
}

// A grazing pair that sticks: vt/vn 4.2 at 1.86 m/s, en 0.41, et 0.80, mu
// 1e6 (the pull |vt|^2 / d a third of the force scale pi vn / tc, falling
// 25-30 % a step at tc/5.3 as the spring slows vt). LIGGGHTS gives the pull
// of the half step before a sample, |vt_{n-1/2}|^2 / d; the sample after the
// step lands with the mean of it and the next step's, which exactCollisionStep
// takes from the speed extrapolated over the step before. Taken as given, the
// pull came half a step late: worst of these phases 1.2 %, 0.59 % and 0.30 % off
// the law at tc/5.3, tc/7.3 and tc/10. With the pull extrapolated from the
// last two steps 0.39 %, 0.16 % and 0.069 %; with the next half step's pull
// from the step's own kicks (exactPairStep's corrector) 0.29 %, 0.13 % and
// 0.083 %, and 0.018 % at tc/20: from tc/10 to tc/20 0.22 of it (second
// order leaves 0.25, first order 0.5). Tolerances: the target (1 % coarser
// than tc/10, 0.5 % there) halved, which the half-step-late pull misses at
// each step, and the step's order: under 0.35 of tc/10's at tc/20.
TEST(PairAgainstContinuous, AGrazingPairIsPulledAsAtItsSamples)
{
    pairstepper::Setup c;
    c.p = {1e-4, 0.4147, 0.7968, 1e6};
    c.vn = 1.864, c.vt = 4.164 * c.vn;
    const std::vector<double> worst = worstOverPhases(c, {5.3, 7.3, 10.0, 20.0}, 16, 5);
    ASSERT_EQ(worst.size(), 4u);
    std::printf("a grazing pair that sticks: worst of 16 phases off the law %.2e, %.2e, %.2e, %.2e at tc/5.3, tc/7.3, "
                "tc/10, tc/20\n", worst[0], worst[1], worst[2], worst[3]);
    EXPECT_LT(worst[0], 0.005);
    EXPECT_LT(worst[1], 0.005);
    EXPECT_LT(worst[2], 0.0025);
    EXPECT_LT(worst[3], 0.35 * worst[2]);
}

// A grazing pair whose beads spin fast and never slide: en = et 0.89, mu 1e6,
// vt/vn 4.3 at 2 m/s, spins of 4 and 6 vn / R (5,300 and 8,000 rad/s) about
// oblique axes. The spins' part of the spring's drive turns with the normal
// without a force, and the drive sampled at a step holds that feed up to the
// sample: the spring moved by it over the step was first order, worst of 8
// phases 0.23 %, 0.079 % and 0.039 % off the law at tc/10, tc/20 and tc/40.
// The spring moved by the drive's mean (half a step's feed off): 0.13 %,
// 0.033 % and 0.0065 % (with the pull's corrector; 0.18 %, 0.033 % and
// 0.0062 % before it), second order. Tolerances: the target halved at
// tc/10, and the step's order from tc/10 to tc/40 (each halving of the step
// to under 0.35 of the error, where first order leaves half; measured 0.24
// and 0.20).
TEST(PairAgainstContinuous, ASpinningPairsSpringMovesByItsDrivesMean)
{
    pairstepper::Setup c;
    c.p = {1e-4, 0.89, 0.89, 1e6};
    c.vn = 2.0, c.vt = 4.3 * c.vn;
    const double u = c.vn / pairstepper::kRadius;
    c.spinI = 4.0 * u * viscoelastic::Vec3(0.5, 0.3, 0.8).normalized();
    c.spinJ = 6.0 * u * viscoelastic::Vec3(-0.6, 0.2, 0.7).normalized();
    const std::vector<double> worst = worstOverPhases(c, {10.0, 20.0, 40.0}, 8, 7);
    ASSERT_EQ(worst.size(), 3u);
    std::printf("a spinning pair that sticks: worst of 8 phases off the law %.2e, %.2e, %.2e at tc/10, tc/20, tc/40\n",
                worst[0], worst[1], worst[2]);
    EXPECT_LT(worst[0], 0.0025);
    EXPECT_LT(worst[1], 0.35 * worst[0]);
    EXPECT_LT(worst[2], 0.35 * worst[1]);
}

// A grazing pair whose contact the normal force rules to the end: en 0.21,
// vt/vn 3.9 at 1.8 m/s, without friction and sliding at mu 0.1. The normal
// turns by vt dt / d a step (0.04 rad at tc/5.7), and the end step's kick acts
// along its own sample's normal: from a sample on the continuous motion the
// flight left on the exit's line turned about the other centre (the worst of
// 16 phases 1.6 %, 0.82 % and 0.37 % off the law at tc/5.7, tc/7.3 and tc/10
// without friction; 1.5 %, 0.68 % and 0.38 % at mu 0.1). The step before
// lands that sample on the exit's line (landOnExitLine): measured 0.043 %,
// 0.025 % and 0.012 % without friction, 0.068 %, 0.041 % and 0.021 % at mu 0.1
// (0.037-0.013 % and 0.068-0.018 % before the pull's corrector).
// Tolerances: a quarter of the target (1 % coarser than tc/10, 0.5 % there),
// which the flight turned off its line misses at every step.
TEST(PairAgainstContinuous, AGrazingPairLeavesOnItsExitLine)
{
    for (const double mu : {0.0, 0.1}) {
        pairstepper::Setup c;
        c.p = {1e-4, 0.21, 0.21, mu};
        c.vn = 1.8, c.vt = 3.9 * c.vn;
        const std::vector<double> worst = worstOverPhases(c, {5.7, 7.3, 10.0}, 16, 3);
        ASSERT_EQ(worst.size(), 3u);
        std::printf("a grazing pair at mu %g: worst of 16 phases off the law %.2e, %.2e, %.2e at tc/5.7, tc/7.3, tc/10\n",
                    mu, worst[0], worst[1], worst[2]);
        EXPECT_LT(worst[0], 0.0025) << "mu " << mu;
        EXPECT_LT(worst[1], 0.0025) << "mu " << mu;
        EXPECT_LT(worst[2], 0.00125) << "mu " << mu;
    }
}

}  // namespace
