// collide's command line: the material defaults come from the `variable`
// lines of inputs/materials.in (else the installed copy), and a missing or
// malformed file stops with an error naming it (the reader itself,
// tools/common/materials.h, is tested in
// tests/contact_models/test_materials.cpp); --version; usage errors.
// `collide recurrence` needs no LIGGGHTS; the last tests run impacts in it.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>

#include "../shell.h"
#include <vector>

namespace fs = std::filesystem;

namespace {


// Where no installed materials file is: the tests that need none to be found
// must not depend on whether the project is installed.
const std::string kNoInstall = "LIGGGHTS_VISCOELASTIC_DATADIR=/nonexistent";

// Runs collide with `args` in `dir` (with `env`, e.g. "NAME=value").
Result collide(const fs::path& dir, const std::string& args, const std::string& env = "")
{
    return runShell("cd '" + dir.string() + "' && " + env + " '" COLLIDE "' " + args);
}

// An empty directory for one test.
fs::path scratch(const std::string& tag)
{
    const fs::path dir = fs::temp_directory_path() / ("collide_cli_" + tag);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

}  // namespace

// The defaults read from inputs/materials.in (relative to the working
// directory) give what the same values on the command line give.
TEST(CollideCli, DefaultsComeFromInputsMaterialsIn)
{
    const Result fromFile = collide(SOURCE_DIR, "recurrence --dt-over-tc 0.1,0.3");
    const Result given = collide(scratch("given"), "recurrence --dt-over-tc 0.1,0.3 --tc 1e-4 --en 0.56");
    EXPECT_EQ(fromFile.status, 0) << fromFile.output;
    EXPECT_EQ(given.status, 0) << given.output;
    EXPECT_EQ(fromFile.output, given.output);
    EXPECT_EQ(fromFile.output.rfind("dt_over_tc,restitution_mean,", 0), 0u) << fromFile.output;
}

TEST(CollideCli, MaterialsOptionChoosesTheFile)
{
    const fs::path dir = scratch("option");
    std::ofstream(dir / "glass.in") << "variable bead_tc equal 2e-4\nvariable bead_en equal 0.8\n";
    const Result fromFile = collide(dir, "recurrence --dt-over-tc 0.1 --materials glass.in");
    const Result given = collide(dir, "recurrence --dt-over-tc 0.1 --tc 2e-4 --en 0.8");
    EXPECT_EQ(fromFile.status, 0) << fromFile.output;
    EXPECT_EQ(fromFile.output, given.output);
}

TEST(CollideCli, MissingFileIsNamedUnlessEveryValueIsGiven)
{
    const fs::path dir = scratch("missing");
    const Result r = collide(dir, "recurrence --dt-over-tc 0.1 --en 0.56", kNoInstall);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("inputs/materials.in (in the working directory)"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("/nonexistent/materials.in (installed)"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("--tc"), std::string::npos) << r.output;
    EXPECT_EQ(collide(dir, "recurrence --dt-over-tc 0.1 --en 0.56 --tc 1e-4", kNoInstall).status, 0);
    const Result c = collide(dir, "case --materials other.in");
    EXPECT_EQ(c.status, 1);
    EXPECT_NE(c.output.find("other.in"), std::string::npos) << c.output;
}

TEST(CollideCli, MalformedFileAndMissingVariableAreNamed)
{
    const fs::path dir = scratch("malformed");
    std::ofstream(dir / "bad.in") << "variable bead_tc equal 1e-4\nvariable bead_en equals 0.5\n";
    const Result r = collide(dir, "recurrence --materials bad.in");
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.output.find("bad.in:2:"), std::string::npos) << r.output;
    std::ofstream(dir / "short.in") << "variable bead_tc equal 1e-4\n";
    const Result s = collide(dir, "recurrence --materials short.in");
    EXPECT_NE(s.status, 0);
    EXPECT_NE(s.output.find("short.in: no variable bead_en"), std::string::npos) << s.output;
}

// Outside a checkout (no inputs/ in the working directory) the defaults come
// from the installed copy; $LIGGGHTS_VISCOELASTIC_DATADIR stands in for the
// install here, pointing at the source tree's inputs/.
TEST(CollideCli, MaterialsFallBackToTheInstalledCopy)
{
    const Result installed = collide(scratch("installed"), "recurrence --dt-over-tc 0.1,0.3",
                                     "LIGGGHTS_VISCOELASTIC_DATADIR='" SOURCE_DIR "/inputs'");
    EXPECT_EQ(installed.status, 0) << installed.output;
    EXPECT_EQ(installed.output, collide(SOURCE_DIR, "recurrence --dt-over-tc 0.1,0.3").output);
}

TEST(CollideCli, VersionAndHelpExitZero)
{
    const Result v = collide(scratch("version"), "--version");
    EXPECT_EQ(v.status, 0);
    EXPECT_EQ(v.output, "collide " TOOLS_VERSION "\n");
    const Result h = collide(scratch("version"), "case --help");
    EXPECT_EQ(h.status, 0);
    EXPECT_NE(h.output.find("--exact-collision"), std::string::npos) << h.output;
}

// A usage error: exit code 2 and one line naming what is wrong (not CLI11's
// codes 105-109 and its usage text).
TEST(CollideCli, UsageErrorsAreOneLineWithExitCodeTwo)
{
    const std::pair<const char*, const char*> bad[] = {
        {"", "a subcommand is required: one of case, sweep-dt, sweep-angle, law-map, recurrence"},
        {"frobnicate", "'frobnicate' is not a subcommand"},
        {"case --frobnicate", "--frobnicate"},
        {"case --phases 0", "--phases: must be > 0, not 0"},
        {"case --tc -1", "--tc: must be > 0, not -1"},
        {"recurrence --en 2", "--en: must be in [1e-6, 1], not 2"},
        {"case --exact-collision maybe", "--exact-collision"},
        {"case --exact-collision on --tangential history", "--exact-collision on needs --tangential pournin"},
        {"case --exact-collision on --exact-restitution on", "are alternatives"}};
    const std::regex oneLine("collide: [^\n]+; see collide --help\n");
    for (const auto& [args, what] : bad) {
        const Result r = collide(scratch("usage"), args);
        EXPECT_EQ(r.status, 2) << args << ": " << r.output;
        EXPECT_TRUE(std::regex_match(r.output, oneLine)) << args << ": " << r.output;
        EXPECT_NE(r.output.find(what), std::string::npos) << args << ": " << r.output;
    }
}

namespace {

// The numbers of a row of `collide case`'s table ("restitution  -  0.56 ...").
std::vector<double> row(const std::string& output, const std::string& quantity)
{
    std::istringstream in(output);
    for (std::string line; std::getline(in, line);)
        if (line.rfind(quantity + "  ", 0) == 0) {
            std::istringstream words(line.substr(quantity.size()));
            std::vector<double> v;
            for (std::string w; words >> w;) v.push_back(w == "-" ? NAN : std::stod(w));
            return v;  // closed form, reference, mean, error %, worst phase, error %
        }
    return {};
}

}  // namespace

// `case` says over how many contact-start phases it ran (default 16) and
// shows the worst single phase beside their mean; --exact-collision on
// reaches the model: every phase then restitutes what the continuous law does.
TEST(CollideCli, CaseReportsItsPhasesAndTheWorstOne)
{
    const std::string run = "case --ratio 10 --vt 0.3 --liggghts '" LIGGGHTS_LAUNCHER "' --workdir ";
    const fs::path dir = scratch("phases");
    const Result plain = collide(SOURCE_DIR, run + "'" + (dir / "plain").string() + "' --phases 8");
    ASSERT_EQ(plain.status, 0) << plain.output;
    EXPECT_NE(plain.output.find("LIGGGHTS: 8 contact-start phases"), std::string::npos) << plain.output;
    const std::vector<double> e = row(plain.output, "restitution");
    ASSERT_EQ(e.size(), 6u) << plain.output;
    EXPECT_GE(std::fabs(e[5]), std::fabs(e[3])) << plain.output;  // the worst: at least as far as the mean
    EXPECT_GT(std::fabs(e[5]), 1.0) << plain.output;              // at tc/10: per cents off [%]

    const Result exact =
        collide(SOURCE_DIR, run + "'" + (dir / "exact").string() + "' --phases 8 --exact-collision on");
    ASSERT_EQ(exact.status, 0) << exact.output;
    EXPECT_NE(exact.output.find("exactCollision on"), std::string::npos) << exact.output;
    const std::vector<double> x = row(exact.output, "restitution");
    ASSERT_EQ(x.size(), 6u) << exact.output;
    EXPECT_LT(std::fabs(x[5]), 0.01) << exact.output;  // [%]

    const Result byDefault = collide(SOURCE_DIR, run + "'" + (dir / "default").string() + "'");
    ASSERT_EQ(byDefault.status, 0) << byDefault.output;
    EXPECT_NE(byDefault.output.find("LIGGGHTS: 16 contact-start phases"), std::string::npos) << byDefault.output;
}

// Every material default of an impact (et, mu, bead size and density too):
// an oblique pair impact in LIGGGHTS, from the file and from the values.
TEST(CollideCli, ImpactDefaultsAreTable31)
{
    const std::string run = "case --geometry pair --vt 0.3 --ratio 20 --liggghts '" LIGGGHTS_LAUNCHER "' --workdir ";
    const fs::path dir = scratch("impact");
    const Result fromFile = collide(SOURCE_DIR, run + "'" + (dir / "file").string() + "'");
    const Result given = collide(dir, run + "given --tc 1e-4 --en 0.56 --et 0.46 --mu 0.5 --r1 1.5e-3 --r2 1.5e-3 "
                                            "--rho1 2500 --rho2 2500");
    EXPECT_EQ(fromFile.status, 0) << fromFile.output;
    EXPECT_EQ(fromFile.output, given.output);
}
