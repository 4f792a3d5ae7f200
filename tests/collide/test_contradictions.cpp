// End-to-end: settings that contradict the request stop with an ERROR naming
// the setting and what it would achieve; limitForce's shift of en is said.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "core/restitution.h"
#include "runner.h"

using namespace collide;
namespace fs = std::filesystem;

namespace {

RunOptions options(const std::string& tag, const std::string& settings = "")
{
    RunOptions o;
    o.liggghts = LIGGGHTS_LAUNCHER;
    o.workdir = (fs::path(TEST_WORK_DIR) / tag).string();
    o.settings = settings;
    return o;
}

// LIGGGHTS' output: the exception's text when it fails, else what it printed.
std::string outputOf(const Case& c, const std::string& tag, const std::string& settings = "")
{
    try {
        return runScript(collisionInput(c, options(tag, settings), "run 1\n"), options(tag, settings));
    } catch (const std::runtime_error& e) {
        return e.what();
    }
}

Case headOn(Geometry g, bool limitForce, double en, double et, double ratio)
{
    Case c;
    c.geometry = g;
    c.limitForce = limitForce;
    c.params = {1e-4, en, et, 0.5};
    c.dt = c.params.tc / ratio;
    return c;
}

}  // namespace

// limitForce on + exactRestitution on with a small en: the friction limit is
// cut with the force, and the sticking spring cannot restitute et (at tc/10:
// en 0.15 / et 0.46 leaves the contact point unreversed, -0.81; en 0.2 / et
// 0.2 gives 0.015). An ERROR naming the setting and the value.
TEST(Contradictions, LimitForceExactRestitutionSmallEnStops)
{
    for (auto [en, et] : {std::pair{0.15, 0.46}, std::pair{0.2, 0.2}}) {
        Case c = headOn(Geometry::Pair, true, en, et, 10.0);
        c.exactRestitution = true;
        const std::string out = outputOf(c, "contra_lf_exact");
        EXPECT_NE(out.find("ERROR"), std::string::npos) << out;
        char expected[80];
        std::snprintf(expected, sizeof expected, "exactRestitution on: type pair (1,1): et %g cannot be reached", et);
        EXPECT_NE(out.find(expected), std::string::npos) << out;
        EXPECT_NE(out.find("with limitForce on"), std::string::npos) << out;
    }
    // Table 3.1's beads are reachable: no ERROR
    Case ok = headOn(Geometry::Pair, true, 0.56, 0.46, 10.0);
    ok.exactRestitution = true;
    EXPECT_EQ(outputOf(ok, "contra_lf_exact_ok").find("ERROR"), std::string::npos);
}

// YADE's wall convention halves the meff the coefficients were solved for.
TEST(Contradictions, WallMassAsParticleWithExactSettingsStops)
{
    for (const char* exact : {"exactRestitution on", "exactCollision on"}) {
        Case c = headOn(Geometry::Wall, false, 0.56, 0.46, 10.0);
        c.tangential = Tangential::Pournin;
        const std::string out = outputOf(c, "contra_wallmass", std::string("wallMassAsParticle on ") + exact);
        EXPECT_NE(out.find("ERROR"), std::string::npos) << out;
        EXPECT_NE(out.find("contradicts wallMassAsParticle on"), std::string::npos) << out;
        EXPECT_NE(out.find("sqrt(2) tc"), std::string::npos) << out;
    }
}

TEST(Contradictions, ExactCollisionWithLimitForceBelowTheCutLawsReachStops)
{
    Case c = headOn(Geometry::Pair, true, 0.1, 0.46, 10.0);
    const std::string out = outputOf(c, "contra_collision", "exactCollision on");
    EXPECT_NE(out.find("ERROR"), std::string::npos) << out;
    EXPECT_NE(out.find("asks for en 0.1, but a contact whose attractive end is cut restitutes at least 0.13"),
              std::string::npos) << out;
}

TEST(Contradictions, ExactCollisionNeedsPourninAndExcludesExactRestitution)
{
    Case c = headOn(Geometry::Pair, false, 0.56, 0.46, 10.0);
    c.tangential = Tangential::History;
    EXPECT_NE(outputOf(c, "contra_history", "exactCollision on").find("exactCollision on needs `tangential pournin`"),
              std::string::npos);
    c.tangential = Tangential::Pournin;
    c.exactRestitution = true;
    EXPECT_NE(outputOf(c, "contra_both", "exactCollision on").find("are alternatives"), std::string::npos);
}

// limitForce on moves en: the log says to what, checked against Schwager &
// Poeschel's closed form (restitution.h, independent of the discrete
// solver) to the 4 digits printed; the value at this timestep follows.
TEST(Contradictions, LimitForceSaysTheEnItAchieves)
{
    for (double en : {0.46, 0.05}) {
        const Case c = headOn(Geometry::Pair, true, en, en, 100.0);
        const std::string out = outputOf(c, "contra_lf_log");
        char expected[160];
        std::snprintf(expected, sizeof expected, "limitForce on: type pair (1,1) asks for en %g but, with the attractive "
                      "end of the contact cut, restitutes %.4f", en, viscoelastic::continuousRestitution(1e-4, en, true));
        EXPECT_NE(out.find(expected), std::string::npos) << expected << "\n" << out;
    }
    // and an en the cut does not move says nothing
    EXPECT_EQ(outputOf(headOn(Geometry::Pair, false, 0.46, 0.46, 100.0), "contra_lf_off").find("limitForce on:"),
              std::string::npos);
}
