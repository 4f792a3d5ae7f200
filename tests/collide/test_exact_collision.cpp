// End-to-end: `exactCollision on` in LIGGGHTS. Every single collision, at
// start phases drawn at random and at integer and non-integer tc/dt, for a
// pair, a primitive wall and a mesh wall, with limitForce off and on.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>

#include "core/collision.h"
#include "run_options.h"
#include "runner.h"

using namespace collide;

namespace {

std::vector<double> randomPhases(int n, unsigned seed)
{
    std::mt19937 g(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<double> p;
    for (int i = 0; i < n; ++i) p.push_back(1.0 - u(g));
    return p;
}

// The farthest of a pair's runs from the outcome `law` (the same mode at
// tc/1000): the largest change of the relative velocity or of a spin's
// contact speed R w, over the incoming speed (pairstepper::apart's measure).
double worstApart(const std::vector<Trajectory>& runs, const BodyStates& law, const Case& c)
{
    double worst = 0.0;
    for (const Trajectory& t : runs) {
        const BodyStates& s = t.frames.back();
        worst = std::max({worst, ((s.v1 - s.v2) - (law.v1 - law.v2)).norm(), c.radius1 * (s.w1 - law.w1).norm(),
                          c.radius1 * (s.w2 - law.w2).norm()});
    }
    return worst / std::hypot(c.normalSpeed, c.tangentialSpeed);
}

struct Worst {
    double normal = 0, tangential = 0;
};

// Worst relative deviation over random phases from the normal and tangential
// restitution wanted (NaN: not checked).
Worst worstOverPhases(const Case& c, const std::string& tag, unsigned seed, double enWant, double etWant)
{
    const std::vector<double> phases = randomPhases(12, seed);
    const std::vector<Trajectory> runs = runLiggghts(c, options(tag, "exactCollision on"), phases);
    Worst w;
    for (size_t k = 0; k < runs.size(); ++k) {
        const Outcome o = measureTrajectory(c, runs[k]);
        if (std::getenv("SHOW")) std::printf("  phase %.4f: en %.8f et %.8f\n", phases[k], o.restitution, o.tangentialRestitution);
        w.normal = std::max(w.normal, std::fabs(o.restitution / enWant - 1.0));
        if (!std::isnan(etWant)) w.tangential = std::max(w.tangential, std::fabs(o.tangentialRestitution / etWant - 1.0));
    }
    return w;
}

// The continuous law exactCollision follows (reference ODE, rigid-arm spring,
// tc/20000).
Outcome continuousLaw(Case c)
{
    c.rigidArmSpring = true;
    return integrateContactOde(c, 20000);
}

// An oblique impact at 1 m/s: vt the tangential speed, tc/dt `ratio`.
Case oblique(Geometry g, bool limitForce, const viscoelastic::ContactParameters& params, double vt, double ratio)
{
    Case c;
    c.geometry = g;
    c.limitForce = limitForce;
    c.params = params;
    c.normalSpeed = 1.0;
    c.tangentialSpeed = vt;
    c.dt = params.tc / ratio;
    return c;
}

// The law's et on a wall for a contact that sticks but where its cap mu |Fn|
// passes through zero (limitForce off, et != en): Pournin's tangential
// oscillator from (0, 1) until the normal force's zero, where the spring lets
// go of its force (xi = -c u / k), then free until the overlap ends at tc. A
// closed form, independent of the steps.
double etWithSpringLetGo(const viscoelastic::ContactParameters& p)
{
    using namespace viscoelastic;
    const auto o = exactCollisionOscillators(p, false);
    const double zero = o->normal.forceZeroFrom({0.0, 1.0}, 0.0);
    Motion t = o->tangential.after({0.0, 1.0}, zero);
    t.x = -o->tangential.c * t.u / o->tangential.k;
    return -o->tangential.after(t, p.tc - zero).u;
}

}  // namespace

TEST(ExactCollision, EverySingleHeadOnCollisionRestitutesEn)
{
    // The scheme is exact for a binary contact: what remains is LIGGGHTS'
    // round-off and the dump's 17 digits. 1e-7 leaves room for that and is
    // 1e5 below the plain law's phase scatter at these steps (5-25 %).
    unsigned seed = 1;
    for (Geometry g : {Geometry::Pair, Geometry::Wall, Geometry::MeshWall})
        for (bool limitForce : {false, true})
            for (double ratio : {5.0, 7.3, 10.0}) {
                Case c;
                c.geometry = g;
                c.limitForce = limitForce;
                c.params = {1e-4, 0.46, 0.46, 0.5};
                c.dt = c.params.tc / ratio;
                const Worst w = worstOverPhases(c, "headon_" + name(g) + (limitForce ? "_lf" : "") +
                                                       std::to_string(int(ratio * 10)), seed++, c.params.en, NAN);
                EXPECT_LT(w.normal, 1e-7) << name(g) << " limitForce " << limitForce << " tc/dt " << ratio;
            }
}

TEST(ExactCollision, EverySingleStickingCollisionOnAWallFollowsItsLaw)
{
    // Sticking (mu 1e6; vt/vn 0.2) on a wall, at vn 0.1 and 1 m/s. Without
    // limitForce the cap mu |Fn| passes through zero at the normal force's
    // zero, where the spring (et 0.3 != en 0.56) lets go of its force whatever
    // mu: against etWithSpringLetGo (0.344), a closed form. With it the
    // force and its cap end together: et. Tolerance 1e-7: the slide before the
    // cap's zero lasts about 1 / mu of the contact (2.3e-8 seen).
    // The spring follows the contact point at the rigid arm R: LIGGGHTS' arm
    // R - overlap/2 shortens during the contact and would move the contact
    // point of the spinning sphere without any force (driven at that arm:
    // +0.14 % at 0.1 m/s, +1.3 % at 1 m/s). The normal does not turn, so the
    // scheme is exact: round-off (1e-13 seen for en).
    // With limitForce on the spring runs as long as the force (exactCollision
    // solves it for that duration), and the multi-contact guard admits
    // tc/5.6 at the coarsest for et 0.3 (its stiffer tangential law).
    unsigned seed = 100;
    for (Geometry g : {Geometry::Wall, Geometry::MeshWall})
    for (bool limitForce : {false, true})
        for (double vn : {0.1, 1.0})
            for (double ratio : {limitForce ? 5.6 : 5.0, 7.3, 10.0}) {
                Case c;
                c.geometry = g;
                c.limitForce = limitForce;
                c.params = {1e-4, 0.56, 0.3, 1e6};
                c.normalSpeed = vn;
                c.tangentialSpeed = 0.2 * vn;
                c.dt = c.params.tc / ratio;
                const double etLaw = limitForce ? c.params.et : etWithSpringLetGo(c.params);
                const Worst w = worstOverPhases(c, "stick_" + name(g) + std::string(limitForce ? "_lf" : "") +
                                                       std::to_string(int(ratio * 10)) + "_" + std::to_string(int(vn * 10)),
                                                seed++, c.params.en, etLaw);
                EXPECT_LT(w.normal, 1e-9) << name(g) << " limitForce " << limitForce << " tc/dt " << ratio << " vn " << vn;
                EXPECT_LT(w.tangential, 1e-7) << name(g) << " limitForce " << limitForce << " tc/dt " << ratio << " vn "
                                              << vn;
                std::printf("%s limitForce %d vn %.1f tc/dt %.1f: worst normal %.2e, tangential %.2e\n",
                            name(g).c_str(), limitForce, vn, ratio, w.normal, w.tangential);
            }
}

TEST(ExactCollision, EverySingleStickingPairCollisionFollowsItsLaw)
{
    // Two spheres: their common normal turns during the contact. The spring
    // is driven by springDrive's U (the orbital part scaled by d / 2R), which
    // the tangential force alone changes, so the law is Pournin's oscillator
    // up to the pair's centrifugal shortening of the contact (the reference
    // test below), and the steps keep it: leapfrog keeps the orbital angular
    // momentum exactly. Measured worst phase against the law (reference ODE,
    // tc/20000, itself within about 4e-5; 8e-6 at tc/100000): 4e-5 for en and et at tc/5 and
    // 1 m/s, 2e-6 at 0.1 m/s. Tolerance 1e-4 + 0.01 vn dt / R (2.3e-4 at tc/5
    // and 1 m/s): the spring driven at the plain contact point (no orbital
    // factor) missed its own law by 0.3 to 1.2 vn dt / R (9.5e-4 at tc/10),
    // and, worse, restituted et + 1.6 % at 1 m/s.
    // Against the requested et (limitForce on): the 0.5 % target at tc/10 and
    // 1 % at tc/5. Without limitForce the law's cap mu |Fn| passes through zero
    // near the end, where the spring (et 0.3 != en 0.56) still holds force and
    // lets go of it whatever mu: the law restitutes 0.344, not 0.3.
    // limitForce on: the reference is exactCollision's cut law (the
    // oscillators solved for en and tc, the spring as long as the force);
    // tc/5.6 is the coarsest step the guard admits.
    unsigned seed = 200;
    for (bool limitForce : {false, true})
    for (double vn : {0.1, 1.0})
        for (double ratio : {limitForce ? 5.6 : 5.0, 7.3, 10.0, 40.0, 80.0}) {
            if ((vn < 1.0 || limitForce) && ratio > 10.0) continue;
            Case c;
            c.geometry = Geometry::Pair;
            c.limitForce = limitForce;
            c.params = {1e-4, 0.56, 0.3, 1e6};
            c.normalSpeed = vn;
            c.tangentialSpeed = 0.2 * vn;
            c.dt = c.params.tc / ratio;
            const Outcome ode = continuousLaw(c);
            const std::string tag = "stick_pair" + std::string(limitForce ? "_lf" : "") + std::to_string(int(ratio * 10)) +
                                    "_" + std::to_string(int(vn * 10));
            const Worst w = worstOverPhases(c, tag, seed, ode.restitution, ode.tangentialRestitution);
            const Worst wanted = worstOverPhases(c, tag, seed++, c.params.en, c.params.et);
            const double scale = vn * c.dt / c.radius1, bound = 1e-4 + 0.01 * scale;
            EXPECT_LT(w.normal, bound) << "limitForce " << limitForce << " tc/dt " << ratio << " vn " << vn;
            EXPECT_LT(w.tangential, bound) << "limitForce " << limitForce << " tc/dt " << ratio << " vn " << vn;
            if (limitForce)
                EXPECT_LT(wanted.tangential, ratio < 9.0 ? 0.01 : 0.005)
                    << "limitForce " << limitForce << " tc/dt " << ratio << " vn " << vn;
            std::printf("pair limitForce %d vn %.1f tc/dt %.1f: law en %.6f et %.6f; worst normal %.2e, tangential %.2e "
                        "(vn dt / R %.2e); against the requested en, et: %.2e, %.2e\n",
                        limitForce, vn, ratio, ode.restitution, ode.tangentialRestitution, w.normal, w.tangential, scale,
                        wanted.normal, wanted.tangential);
        }
}

TEST(ExactCollision, ReferenceRigidArmSpringIsPourninsOscillatorOnAWall)
{
    // The pair test's reference: on a wall (no turning frame) its law is
    // Pournin's tangential oscillator letting go of its force at the normal
    // force's zero (etWithSpringLetGo: 0.344 for et 0.3), at any speed.
    // Tolerance: the ODE's contact start between its steps (1.2e-5 seen at
    // tc/20000).
    for (double vn : {0.1, 1.0}) {
        Case c;
        c.geometry = Geometry::Wall;
        c.params = {1e-4, 0.56, 0.3, 1e6};
        c.normalSpeed = vn;
        c.tangentialSpeed = 0.2 * vn;
        c.rigidArmSpring = true;
        EXPECT_NEAR(integrateContactOde(c, 20000).tangentialRestitution, etWithSpringLetGo(c.params), 3e-5) << "vn " << vn;
    }
}

TEST(ExactCollision, ReferenceRigidArmSpringOnAPairMissesEtOnlyByTheCentrifugalShortening)
{
    // A pair's tangential motion pulls the centres apart (vt^2 / d), so its
    // contact ends earlier than tc and cuts the tangential oscillator short:
    // et rises above the wall's law by about K (vt^2 / vn) tc / R, measured
    // K = 0.05-0.08 (0.1 and 1 m/s, vt/vn 0.2 and 1; vt the relative
    // tangential speed of the centres; the same law without letting go at
    // the force's zero gave K = 0.15, and up to 0.23 with R2 = R1/3, denser).
    // Bound: K = 0.25, plus the ODE's 3e-5. The spring driven at the plain
    // contact point (no orbital factor) is off by 1.6 % at vn 1 m/s, vt/vn
    // 0.2, 24 times this bound.
    for (double vn : {0.1, 1.0})
        for (double slope : {0.2, 1.0}) {
            Case c;
            c.geometry = Geometry::Pair;
            c.params = {1e-4, 0.56, 0.3, 1e6};
            c.normalSpeed = vn;
            c.tangentialSpeed = slope * vn;
            c.rigidArmSpring = true;
            const double centrifugal = c.tangentialSpeed * c.tangentialSpeed / vn * c.params.tc / c.radius1;
            const double et = integrateContactOde(c, 20000).tangentialRestitution;
            const double wall = etWithSpringLetGo(c.params);
            EXPECT_LT(std::fabs(et / wall - 1.0), 3e-5 + 0.25 * centrifugal) << "vn " << vn << " vt/vn " << slope;
            std::printf("pair law vn %.1f vt/vn %.1f: et %.6f, (et/%.6f - 1) / ((vt^2/vn) tc/R) = %.3f\n", vn, slope, et,
                        wall, (et / wall - 1.0) / centrifugal);
        }
}

TEST(ExactCollision, EverySingleSlidingCollisionFollowsWalton)
{
    // Gross sliding on a wall (vt/vn 4, mu 0.3): the tangential impulse is
    // mu times the integral of |Fn| (Walton). exactCollision bounds friction
    // per step by the law's mean |Fn| over the step's part of the contact
    // (the steps' own forces would miss it by 6 % at tc/5 for the worst phase).
    // Against the continuous law (reference ODE, LIGGGHTS' lever arm
    // R - overlap/2): the 0.5 % target at tc/10 and 1 % at tc/5 (measured
    // 0.008-0.08 %). Against Walton's rigid lever arm R the same 0.4-0.5 % at
    // every step (the arm is shorter by up to overlap / 2R = 0.7 % at 1 m/s):
    // within 1 %, and the worst phase moves by less than 0.1 % from tc/10 to
    // tc/5 (no step error left).
    unsigned seed = 300;
    for (Geometry g : {Geometry::Wall, Geometry::MeshWall})
    for (bool limitForce : {false, true}) {
        std::vector<double> worstAt;
        for (double ratio : {5.0, 7.3, 10.0}) {
            Case c;
            c.geometry = g;
            c.limitForce = limitForce;
            c.params = {1e-4, 0.5, 0.5, 0.3};
            c.normalSpeed = 1.0;
            c.tangentialSpeed = 4.0;
            c.dt = c.params.tc / ratio;
            const std::optional<ClosedForm> cf = closedForm(c);
            ASSERT_TRUE(cf && cf->regime == "sliding");
            // limitForce on: exactCollision's cut contact restitutes en itself (not
            // Pournin's cut law, which the closed form describes); its force never
            // turns, so the integral of |Fn| is (1 + en) vn
            const double duWalton = limitForce ? 3.5 * c.params.mu * (1.0 + c.params.en) * c.normalSpeed
                                               : (1.0 + cf->outcome.tangentialRestitution) * c.tangentialSpeed;
            const double duLaw = (1.0 + continuousLaw(c).tangentialRestitution) * c.tangentialSpeed;
            const std::vector<double> phases = randomPhases(12, seed++);
            const std::vector<Trajectory> runs =
                runLiggghts(c, options("sliding_" + name(g) + std::to_string(int(ratio * 10)) + (limitForce ? "_lf" : ""),
                                       "exactCollision on"),
                            phases);
            double worst = 0.0, worstLaw = 0.0;
            for (const Trajectory& t : runs) {
                const double du = (1.0 + measureTrajectory(c, t).tangentialRestitution) * c.tangentialSpeed;
                worst = std::max(worst, std::fabs(du / duWalton - 1.0));
                worstLaw = std::max(worstLaw, std::fabs(du / duLaw - 1.0));
            }
            std::printf("sliding, %s, limitForce %d, tc/dt %.1f: worst against the law %.3e, Walton %.3e\n",
                        name(g).c_str(), limitForce, ratio, worstLaw, worst);
            EXPECT_LT(worstLaw, ratio < 9.0 ? 0.01 : 0.005) << name(g) << " limitForce " << limitForce << " tc/dt " << ratio;
            EXPECT_LT(worst, 0.01) << name(g) << " limitForce " << limitForce << " tc/dt " << ratio;
            worstAt.push_back(worst);
        }
        EXPECT_LT(std::fabs(worstAt.front() - worstAt.back()), 1e-3) << name(g) << " limitForce " << limitForce;
    }
}


TEST(ExactCollision, EverySingleSlidingPairCollisionFollowsItsLaw)
{
    // Gross sliding between two spheres: the reference is the continuous law
    // (reference ODE, Coulomb cap at every instant, the same lever arms as
    // LIGGGHTS), not Walton's rigid relation: the common normal turns by
    // about vt tc / d during the contact and the tangential motion pulls the
    // centres apart (vt^2 / d), which moves both en and the friction impulse
    // (Walton's relation is 4 % off at vn 0.1 m/s, vt/vn 4). Compared: en and
    // the change of the contact point's tangential velocity, du. The claim
    // (docs/tests.md), well inside the 0.5 % target at tc/10 and 1 % up to
    // tc/9: at most 0.1 % (en) and 0.25 % (du) at the coarsest steps, 0.04 %
    // and 0.2 % at tc/10, the steps' own error in sliding (the pull's fall
    // within a step is not followed; en at tc/10 0.029 % before the phases
    // whose exit lies 2.0-2.2 steps after the sample before landed on the exit
    // line, now 0.035 %).
    // Without the pull on the overlap (exactCollisionStep) one phase in six
    // missed en by 7 % at tc/5 (vn 1 m/s): the end step never ran.
    unsigned seed = 400;
    struct Impact {
        double vn, slope, mu, en;
    };
    for (bool limitForce : {false, true})
        for (const Impact& im : {Impact{0.1, 4.0, 0.3, 0.5}, Impact{1.0, 2.0, 0.1, 0.5}, Impact{1.0, 2.0, 0.1, 0.2}})
            // from the coarsest step the guard admits (en 0.2 with limitForce: tc/7.8)
            for (double ratio : limitForce && im.en < 0.3 ? std::vector<double>{8.0, 9.0, 10.0}
                                : std::vector<double>{im.en < 0.3 ? 6.0 : limitForce ? 5.6 : 5.0, 7.3, 10.0}) {
                Case c;
                c.geometry = Geometry::Pair;
                c.limitForce = limitForce;
                c.params = {1e-4, im.en, 0.5, im.mu};
                c.normalSpeed = im.vn;
                c.tangentialSpeed = im.slope * im.vn;
                c.dt = c.params.tc / ratio;
                const Outcome ode = continuousLaw(c);
                const double duLaw = (1.0 + ode.tangentialRestitution) * c.tangentialSpeed;
                // gross sliding: the contact point's tangential velocity keeps its sign
                ASSERT_GT(ode.tangentialRestitution, -1.0 + 0.2) << "not sliding throughout";
                const std::vector<double> phases = randomPhases(12, seed++);
                const std::string tag = "slide_pair" + std::string(limitForce ? "_lf" : "") +
                                        std::to_string(int(ratio * 10)) + "_" + std::to_string(int(im.vn * 10)) + "_" +
                                        std::to_string(int(im.en * 10));
                double worstDu = 0.0, worstEn = 0.0;
                for (const Trajectory& t : runLiggghts(c, options(tag, "exactCollision on"), phases)) {
                    const Outcome o = measureTrajectory(c, t);
                    worstDu = std::max(worstDu, std::fabs((1.0 + o.tangentialRestitution) * c.tangentialSpeed / duLaw - 1.0));
                    worstEn = std::max(worstEn, std::fabs(o.restitution / ode.restitution - 1.0));
                }
                const bool coarse = ratio < 9.0;
                EXPECT_LT(worstDu, coarse ? 2.5e-3 : 2e-3) << "limitForce " << limitForce << " vn " << im.vn << " tc/dt " << ratio;
                EXPECT_LT(worstEn, coarse ? 1e-3 : 4e-4) << "limitForce " << limitForce << " vn " << im.vn << " tc/dt " << ratio;
                std::printf("sliding pair, limitForce %d, en %.1f vn %.1f vt/vn %.0f mu %.1f, tc/dt %.1f: law en %.5f du "
                            "%.5f m/s (Walton %.5f); worst en %.2e, du %.2e\n",
                            limitForce, im.en, im.vn, im.slope, im.mu, ratio, ode.restitution, duLaw,
                            3.5 * im.mu * (1.0 + c.params.en) * im.vn, worstEn, worstDu);
            }
}


TEST(ExactCollision, FiniteFrictionWithEtOtherThanEn)
{
    // Table 3.1's friction (mu 0.5) at small incidence (vt/vn 0.2, 1 m/s), et
    // != en, against the continuous law (reference ODE, rigid-arm spring).
    // The law slides near the end of such a contact: its cap mu |Fn| passes
    // through zero while the spring holds force (limitForce off), and it
    // restitutes 0.481 for Table 3.1's et 0.46 and 0.476 for en 0.3 / et 0.8;
    // with limitForce the cap falls with the force, more slowly than the
    // spring's force, and the law gives 0.466 and 0.803. exactCollision follows
    // the instantaneous cap through the step (cappedFlow): every start phase
    // within 3e-4 of the law for en and et at every step (the claim, docs/law.md,
    // Tests; far inside the 0.5 % target at tc/10 and 1 % at tc/5), pair and
    // wall, limitForce off and on.
    unsigned seed = 600;
    struct P { double en, et, mu; };
    for (P p : {P{0.56, 0.46, 0.5}, P{0.3, 0.8, 0.5}})
    for (Geometry g : {Geometry::Wall, Geometry::Pair})
    for (bool limitForce : {false, true})
        for (double ratio : limitForce ? std::vector<double>{p.en < 0.5 ? 6.0 : 5.6, 7.3, 10.0}
                                       : std::vector<double>{5.0, 7.3, 10.0, 20.0, 40.0, 100.0}) {
            const Case c = oblique(g, limitForce, {1e-4, p.en, p.et, p.mu}, 0.2, ratio);
            const Outcome ode = continuousLaw(c);
            const std::string tag = "fric_" + name(g) + (limitForce ? "_lf" : "") + std::to_string(int(ratio * 10)) +
                                    "_" + std::to_string(int(p.et * 10));
            const Worst law = worstOverPhases(c, tag, seed++, ode.restitution, ode.tangentialRestitution);
            std::printf("en %.2f et %.2f mu %.1f, %s, limitForce %d, tc/dt %.1f: the law's en %.5f et %.5f; worst "
                        "against the law: en %.2e, et %.2e\n",
                        p.en, p.et, p.mu, name(g).c_str(), limitForce, ratio, ode.restitution,
                        ode.tangentialRestitution, law.normal, law.tangential);
            const double tolerance = 3e-4;
            EXPECT_LT(law.normal, tolerance) << name(g) << " en " << p.en << " limitForce " << limitForce << " tc/dt " << ratio;
            EXPECT_LT(law.tangential, tolerance)
                << name(g) << " et " << p.et << " limitForce " << limitForce << " tc/dt " << ratio;
        }
}

TEST(ExactCollision, SlidingWithEtOtherThanEnFollowsItsLaw)
{
    // Gross sliding (vt/vn 4, mu 0.3, 1 m/s) with et != en, against the
    // continuous law (reference ODE, rigid-arm spring; between two spheres the
    // law's en is not the request: the pull of the tangential motion). Within
    // the claim (docs/tests.md: 0.8 % at the coarsest steps, 0.25 % at tc/10;
    // inside the 1 % and 0.5 % targets), for en and the
    // contact point's change of tangential velocity du, Table 3.1's beads and
    // en 0.3 / et 0.8 (where the lightly damped spring sticks again and slides
    // again at the end of the contact: cappedFlow's events).
    unsigned seed = 700;
    struct P { double en, et; };
    for (P p : {P{0.56, 0.46}, P{0.3, 0.8}})
    for (Geometry g : {Geometry::Wall, Geometry::Pair})
    for (bool limitForce : {false, true})
        for (double ratio : {limitForce ? 6.0 : 5.0, 10.0}) {
            const Case c = oblique(g, limitForce, {1e-4, p.en, p.et, 0.3}, 4.0, ratio);
            const Outcome ode = continuousLaw(c);
            const std::vector<double> phases = randomPhases(12, seed++);
            const std::vector<Trajectory> runs = runLiggghts(
                c, options("slide_etne_" + name(g) + std::to_string(int(ratio * 10)) + (limitForce ? "_lf" : "") +
                               std::to_string(int(p.et * 10)),
                           "exactCollision on"),
                phases);
            double worstEn = 0, worstDu = 0;
            const double duLaw = (1.0 + ode.tangentialRestitution) * c.tangentialSpeed;
            for (const Trajectory& t : runs) {
                const Outcome o = measureTrajectory(c, t);
                if (std::getenv("SHOW")) std::printf("  en %.8f du %.8f\n", o.restitution, (1.0 + o.tangentialRestitution) * c.tangentialSpeed);
                worstEn = std::max(worstEn, std::fabs(o.restitution / ode.restitution - 1.0));
                worstDu = std::max(worstDu, std::fabs((1.0 + o.tangentialRestitution) * c.tangentialSpeed / duLaw - 1.0));
            }
            std::printf("sliding, en %.2f et %.2f, %s, limitForce %d, tc/dt %.1f: the law's en %.5f; worst against "
                        "the law: en %.2e, du %.2e\n",
                        p.en, p.et, name(g).c_str(), limitForce, ratio, ode.restitution, worstEn, worstDu);
            const double tolerance = ratio < 9.0 ? 8e-3 : 2.5e-3;
            EXPECT_LT(worstEn, tolerance) << name(g) << " limitForce " << limitForce << " tc/dt " << ratio;
            EXPECT_LT(worstDu, tolerance) << name(g) << " limitForce " << limitForce << " tc/dt " << ratio;
        }
}

TEST(ExactCollision, ASlideBetweenSpinningSpheresTurnsWithTheLaw)
{
    // Two beads sliding throughout (mu 0.01 and 0.1, vn = vt = 0.1 m/s), one
    // spinning at 1000 rad/s about the normal: as the normal turns, the spin
    // moves the contact point sideways, and the law's friction turns toward
    // the spring's loading rate k u + c a within a small fraction of a step
    // (cap / (k |u|)). Compared with the reference ODE: the change of the
    // spinning bead's spin, along the friction's main torque (z) and the
    // sideways part (y, 2.5 % of it), over random phases. The sideways part
    // comes from a drive the steps sample once per step, so it converges at
    // first order: worst phase measured 6.5 % below the law at tc/10 and
    // 1.0 % at tc/40 (0.4 % at tc/80). Tolerances 0.1 and 0.025 (the first-
    // order error's constant, about 0.65 dt / tc, with room for the phases),
    // and the error at tc/40 under half the one at tc/10. A slide that kept its
    // direction plus the drive's jump at each step got 13 times the law's
    // sideways part (mu 0.01) and 1.8-2.4 times (mu 0.1), at every step.
    // The main part: within 1e-4 (measured 3.4e-5).
    unsigned seed = 800;
    for (double mu : {0.01, 0.1}) {
        Case c;
        c.geometry = Geometry::Pair;
        c.params = {1e-4, 0.5, 0.5, mu};
        c.normalSpeed = 0.1;
        c.tangentialSpeed = 0.1;
        c.spin1 = Vec3(1000.0, 0.0, 0.0);
        c.rigidArmSpring = true;
        BodyStates after;
        integrateContactOde(c, 20000, &after);
        const Vec3 law = after.w1 - c.spin1;
        ASSERT_GT(std::fabs(law.y()), 0.01 * std::fabs(law.z()));  // a sideways part worth testing
        std::vector<double> worstAt;
        for (double ratio : {10.0, 40.0}) {
            c.dt = c.params.tc / ratio;
            const std::vector<double> phases = randomPhases(4, seed++);
            const std::vector<Trajectory> runs = runLiggghts(
                c, options("spin_slide_" + std::to_string(int(mu * 100)) + "_" + std::to_string(int(ratio)), "exactCollision on"),
                phases);
            double worstSide = 0.0, worstMain = 0.0;
            for (const Trajectory& t : runs) {
                const Vec3 dw = t.frames.back().w1 - c.spin1;
                worstSide = std::max(worstSide, std::fabs(dw.y() / law.y() - 1.0));
                worstMain = std::max(worstMain, std::fabs(dw.z() / law.z() - 1.0));
            }
            std::printf("spinning pair, mu %.2f, tc/dt %.0f: the law's change of spin (y, z) %.5e %.5e; worst "
                        "against it: sideways %.2e, main %.2e\n",
                        mu, ratio, law.y(), law.z(), worstSide, worstMain);
            EXPECT_LT(worstSide, ratio < 20.0 ? 0.1 : 0.025) << "mu " << mu << " tc/dt " << ratio;
            EXPECT_LT(worstMain, 1e-4) << "mu " << mu << " tc/dt " << ratio;
            worstAt.push_back(worstSide);
        }
        EXPECT_LT(worstAt.back(), 0.5 * worstAt.front()) << "mu " << mu << ": not converging";
    }
}

// The landing on the exit's line in LIGGGHTS (the tangential model `pournin`
// adds the landing's normal force and writes the normal model's history): a
// frictionless grazing pair (en 0.21, vt/vn 3.9 at 1.8 m/s, `limitForce
// off`) at tc/5.7 and 8 random phases, its relative velocity after the
// collision in the lab frame against the same mode at tc/1000 (one phase).
// With the last sample on the continuous motion the flight left turned about
// the other centre: the previous library 0.04-1.2 % of the incoming speed off
// at 8 evenly spread phases, 1.7 % at another (the core's stepper gives the
// same to all printed digits). Landed: 0.043 % (0.037 % before the pull's
// corrector). Tolerance: a quarter of the
// 1 % target, as the core's test (tests/collide/test_pair_against_continuous).
TEST(ExactCollision, AGrazingPairLeavesOnItsExitLineInLiggghts)
{
    Case c;
    c.geometry = Geometry::Pair;
    c.params = {1e-4, 0.21, 0.21, 0.0};
    c.normalSpeed = 1.8, c.tangentialSpeed = 3.9 * 1.8;
    const auto after = [](const Trajectory& t) {
        const BodyStates& s = t.frames.back();
        return Vec3(s.v1 - s.v2);
    };
    Case fine = c;
    fine.dt = c.params.tc / 1000.0;
    const Vec3 law = after(runLiggghts(fine, options("grazing_exit_fine", "exactCollision on")));
    c.dt = c.params.tc / 5.7;
    const auto runs = runLiggghts(c, options("grazing_exit", "exactCollision on"), randomPhases(8, 11));
    double worst = 0.0;
    for (const Trajectory& t : runs) worst = std::max(worst, (after(t) - law).norm() / std::hypot(1.8, 3.9 * 1.8));
    std::printf("a frictionless grazing pair in LIGGGHTS at tc/5.7: worst of 8 phases %.2e of its speed off tc/1000\n",
                worst);
    EXPECT_LT(worst, 0.0025);
}

namespace {

// A pair under exactCollision at tc/ratio and n evenly spread phases in
// LIGGGHTS, its worst against the same at tc/1000 (worstApart).
double worstOfEvenPhases(Case c, double ratio, const std::string& name, int n)
{
    Case fine = c;
    fine.dt = c.params.tc / 1000.0;
    const BodyStates law = runLiggghts(fine, options(name + "_fine", "exactCollision on")).frames.back();
    c.dt = c.params.tc / ratio;
    return worstApart(runLiggghts(c, options(name, "exactCollision on"), evenPhases(n)), law, c);
}

}  // namespace

// The pull's corrector in LIGGGHTS (the tangential model `pournin` takes the
// normal step again with the next half step's pull its kicks give, and adds
// the change of the normal force): ExactCollision.AGrazingPairIsPulledAsItsOwnKicksGive
// (tests/contact_models/test_collision.cpp), en 0.235, et 0.942, mu 48, vt/vn
// 4.86 at 1.28 m/s, `limitForce on`, tc/7.34, at 16 evenly spread phases
// against the same mode at tc/1000, relative velocity and spins. With the
// pull extrapolated the core's stepper is 1.52 % off at the worst of those
// phases, with the corrector 0.91 %; LIGGGHTS gives the same, 1.516 % with
// the previous library and 0.913 % now. Target: the sweep's (1 % coarser
// than tc/10).
TEST(ExactCollision, AGrazingPairIsPulledAsItsOwnKicksGiveInLiggghts)
{
    Case c;
    c.geometry = Geometry::Pair;
    c.limitForce = true;
    c.params = {1e-4, 0.23527368273602051, 0.94228151251440029, 48.121930384653723};
    c.normalSpeed = 1.2833319009983311, c.tangentialSpeed = 6.2384890230356431;
    const double worst = worstOfEvenPhases(c, 7.3428064907261374, "pulled", 16);
    std::printf("a grazing pair whose friction grows, in LIGGGHTS at tc/7.34: worst of 16 phases %.3f %% off tc/1000\n",
                100.0 * worst);
    EXPECT_LT(worst, 0.01);
}

// The landing's reach in LIGGGHTS: ExactCollision.AGrazingPairEndingPastTheSampleAfterNextLands
// (tests/contact_models/test_collision.cpp), its sliding pair, en 0.30, et
// 0.59, mu 0.92, vt/vn 4.53 at 2.0 m/s, `limitForce off`, tc/5.05, at 16
// evenly spread phases against the same mode at tc/1000. Landed only where the
// exit lay within two steps, the core's stepper was 1.50 % off at the worst
// of those phases, now 0.44 %; LIGGGHTS gives the same. Target: the sweep's.
TEST(ExactCollision, AGrazingPairEndingPastTheSampleAfterNextLandsInLiggghts)
{
    Case c;
    c.geometry = Geometry::Pair;
    c.params = {1e-4, 0.3035359177255651, 0.58559942836031209, 0.91506808761436198};
    c.normalSpeed = 1.9978051606731193, c.tangentialSpeed = 9.0588894808963225;
    const double worst = worstOfEvenPhases(c, 5.047552792191758, "reach", 16);
    std::printf("a grazing pair ending past the sample after next, in LIGGGHTS at tc/5.05: worst of 16 phases %.3f %% "
                "off tc/1000\n",
                100.0 * worst);
    EXPECT_LT(worst, 0.01);
}

// ExactCollision.ASpringLetsGoWhereTheCapPassesZeroBetweenTwoSteps
// (tests/contact_models/test_collision.cpp) in LIGGGHTS, whose history keeps
// the forecast the check reads: the spinning pair (the core's frame turned
// half a turn about y: collide's bead 1 comes in along -x), 256 phases at
// tc/7, tc/10 and tc/14, against the same mode at tc/1000. The previous
// library left it 21 % off at a phase or two of each. Target: the sweep's.
TEST(ExactCollision, ASpringLetsGoWhereTheCapPassesZeroInLiggghts)
{
    Case c;
    c.geometry = Geometry::Pair;
    c.params = {1e-4, 0.2097, 0.5817, 3.07e4};
    c.normalSpeed = 1.294, c.tangentialSpeed = 1.243;
    c.spin1 = Vec3(49.9, 1110.2, -1391.8), c.spin2 = Vec3(-579.7, 1228.6, 2886.2);
    Case fine = c;
    fine.dt = c.params.tc / 1000.0;
    const BodyStates law = runLiggghts(fine, options("cap_zero_fine", "exactCollision on")).frames.back();
    const std::vector<double> phases = evenPhases(256);
    for (const double ratio : {7.0, 10.0, 14.0}) {
        c.dt = c.params.tc / ratio;
        const double worst = worstApart(
            runLiggghts(c, options("cap_zero_" + std::to_string(int(ratio)), "exactCollision on"), phases), law, c);
        std::printf("the spinning pair in LIGGGHTS at tc/%g: worst of 256 phases %.3f %% off tc/1000\n", ratio,
                    100.0 * worst);
        EXPECT_LT(worst, ratio >= 10.0 ? 0.005 : 0.01) << "tc/dt " << ratio;
    }
}
