// End-to-end: settings that contradict the request stop with an ERROR naming
// the setting and what it would achieve; limitForce's shift of en is said.
#include <gtest/gtest.h>

#include <cstdio>
#include <stdexcept>

#include "core/restitution.h"
#include "run_options.h"
#include "runner.h"

using namespace collide;

namespace {

// LIGGGHTS' output: the exception's text when it fails, else what it printed.
std::string outputOf(const Case& c, const std::string& tag, const std::string& settings = "",
                     const std::string& wallSettings = "")
{
    collide::RunOptions o = options(tag, settings);
    o.wallSettings = wallSettings;
    try {
        return runScript(collisionInput(c, o, "run 1\n"), o);
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

// YADE's wall convention halves the meff: exactCollision's step laws follow
// Pournin's oscillators, not that law, so the two stop with an ERROR;
// exactRestitution solves for the halved law and runs (its log says so;
// ExactRestitution.YadesFacetMassIsSolvedForOnWalls checks what it gives).
TEST(Contradictions, WallMassAsParticleWithExactCollisionStops)
{
    Case c = headOn(Geometry::Wall, false, 0.56, 0.46, 10.0);
    c.tangential = Tangential::Pournin;
    const std::string out = outputOf(c, "contra_wallmass", "exactCollision on", "wallMassAsParticle on");
    EXPECT_NE(out.find("ERROR"), std::string::npos) << out;
    EXPECT_NE(out.find("fix wall/gran model viscoelastic"), std::string::npos) << out;
    EXPECT_NE(out.find("contradicts wallMassAsParticle on"), std::string::npos) << out;
    EXPECT_NE(out.find("sqrt(2) tc"), std::string::npos) << out;
    const std::string ok = outputOf(c, "contra_wallmass_exact", "exactRestitution on", "wallMassAsParticle on");
    EXPECT_EQ(ok.find("ERROR"), std::string::npos) << ok;
    EXPECT_NE(ok.find("wall contacts at meff/2, wallMassAsParticle"), std::string::npos) << ok;
    EXPECT_NE(ok.find("YADE's law restitutes 0.66"), std::string::npos) << ok;  // en 0.56 halved: 0.6659
}

// wallMassAsParticle is a wall's setting: on pair_style it is an ERROR in
// every mode (it was ignored under exactRestitution and an ERROR under
// exactCollision), and on a wall without an exact mode it runs.
TEST(Contradictions, WallMassAsParticleOnPairStyleStops)
{
    for (const char* mode : {"", "exactRestitution on", "exactCollision on"}) {
        const Case c = headOn(Geometry::Pair, false, 0.56, 0.46, 10.0);
        const std::string out = outputOf(c, "contra_wallmass_pair", std::string("wallMassAsParticle on ") + mode);
        EXPECT_NE(out.find("ERROR: pair gran model viscoelastic: wallMassAsParticle applies to wall contacts only"),
                  std::string::npos)
            << mode << "\n" << out;
    }
    const Case wall = headOn(Geometry::Wall, false, 0.56, 0.46, 10.0);
    EXPECT_EQ(outputOf(wall, "contra_wallmass_wall", "", "wallMassAsParticle on").find("ERROR"), std::string::npos);
}

// tangential no_history has no spring for exactRestitution's tangential
// solve: an ERROR on pairs and walls (it ran, restituting et -0.21 for a
// logged 0.46).
TEST(Contradictions, NoHistoryWithExactRestitutionStops)
{
    for (Geometry g : {Geometry::Pair, Geometry::Wall}) {
        Case c = headOn(g, false, 0.46, 0.46, 10.0);
        c.tangential = Tangential::NoHistory;
        c.exactRestitution = true;
        const std::string out = outputOf(c, "contra_nohistory");
        EXPECT_NE(out.find("ERROR: model viscoelastic tangential no_history: exactRestitution on"), std::string::npos)
            << out;
        c.exactRestitution = false;
        EXPECT_EQ(outputOf(c, "contra_nohistory_plain").find("ERROR"), std::string::npos);
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

// Overlaps past half the smaller radius stop the run naming the atoms (here
// beads created 0.6 r inside each other, and one 0.6 r inside a wall); 0.4 r
// runs on (it pushes them apart).
TEST(Contradictions, OverlapBeyondHalfTheSmallerRadiusStopsNamingTheAtoms)
{
    const auto script = [](double depth, bool wall) {
        const double r = 1.5e-3;
        std::string s = "atom_style granular\natom_modify map array\nboundary f f f\nnewton off\n"
                        "communicate single vel yes\nunits si\n"
                        "region box block -0.01 0.01 -0.01 0.01 -0.01 0.01 units box\ncreate_box 2 box\n";
        char buf[512];
        if (wall) {
            std::snprintf(buf, sizeof buf, "create_atoms 1 single %.17g 0 0 units box\n", r - depth * r);
        } else {
            std::snprintf(buf, sizeof buf, "create_atoms 1 single 0 0 0 units box\ncreate_atoms 1 single %.17g 0 0 units box\n",
                          2 * r - depth * r);
        }
        s += buf;
        s += "set type 1 diameter 3e-3 density 2500\nneighbor 1e-3 bin\n"
             "fix m1 all property/global contactDuration peratomtypepair 2 1e-4 1e-4 1e-4 1e-4\n"
             "fix m2 all property/global coefficientRestitution peratomtypepair 2 0.5 0.5 0.5 0.5\n"
             "fix m3 all property/global coefficientRestitutionTangential peratomtypepair 2 0.5 0.5 0.5 0.5\n"
             "fix m4 all property/global coefficientFriction peratomtypepair 2 0.5 0.5 0.5 0.5\n"
             "pair_style gran model viscoelastic tangential history\npair_coeff * *\ntimestep 1e-6\n";
        if (wall) s += "fix w all wall/gran model viscoelastic tangential history primitive type 2 xplane 0.0\n";
        s += "fix integr all nve/sphere\nrun 2\n";
        return s;
    };
    const auto run = [](const std::string& s, const std::string& tag) {
        try {
            return runScript(s, options(tag));
        } catch (const std::runtime_error& e) {
            return std::string(e.what());
        }
    };
    const std::string pair = run(script(0.6, false), "overlap_pair");
    EXPECT_NE(pair.find("model viscoelastic: atoms 1 and 2 overlap by 0.0009"), std::string::npos) << pair;
    EXPECT_NE(pair.find("more than half the smaller radius"), std::string::npos) << pair;
    const std::string wall = run(script(0.6, true), "overlap_wall");
    EXPECT_NE(wall.find("model viscoelastic: atom 1 and the wall overlap by 0.0009"), std::string::npos) << wall;
    EXPECT_EQ(run(script(0.4, false), "overlap_ok").find("ERROR"), std::string::npos);
}

// exactCollision's guard names the coarsest step it admits, and that step
// runs: the applied law changes with the step, so the bound seen at a
// refused step (1.740e-5 s at 1.786e-5 s for en 0.3 / et 0.8 with limitForce)
// was itself refused.
TEST(Contradictions, ExactCollisionGuardsAdviceIsAdmitted)
{
    Case c = headOn(Geometry::Pair, true, 0.3, 0.8, 5.0);
    c.params.mu = 0.5;
    const std::string out = outputOf(c, "contra_guard", "exactCollision on");
    const std::string key = "use timestep <= ";
    const size_t at = out.find(key);
    ASSERT_NE(at, std::string::npos) << out;
    const double advised = std::stod(out.substr(at + key.size()));
    EXPECT_LT(advised, c.dt);
    c.dt = advised;
    const std::string ok = outputOf(c, "contra_guard_ok", "exactCollision on");
    EXPECT_EQ(ok.find("ERROR"), std::string::npos) << ok;
    c.dt = 1.001 * advised;
    EXPECT_NE(outputOf(c, "contra_guard_over", "exactCollision on").find("exceeds the stable timestep"), std::string::npos);
}
