// collide's command line: the material defaults come from the `variable`
// lines of inputs/materials.in, and a missing or malformed file stops with an
// error naming it (the reader itself, tools/common/materials.h, is tested in
// tests/contact_models/test_materials.cpp). `collide recurrence` needs no
// LIGGGHTS; the last test runs two impacts in it.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace fs = std::filesystem;

namespace {

struct Result {
    int status;
    std::string output;  // stdout and stderr
};

// Runs collide with `args` in `dir`.
Result collide(const fs::path& dir, const std::string& args)
{
    const std::string command = "cd '" + dir.string() + "' && '" COLLIDE "' " + args + " 2>&1";
    FILE* p = popen(command.c_str(), "r");
    if (!p) throw std::runtime_error("cannot run " + command);
    Result r;
    char buf[4096];
    while (size_t n = fread(buf, 1, sizeof buf, p)) r.output.append(buf, n);
    r.status = pclose(p);
    return r;
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
    const Result r = collide(dir, "recurrence --dt-over-tc 0.1 --en 0.56");
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.output.find("inputs/materials.in"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("--tc"), std::string::npos) << r.output;
    const Result c = collide(dir, "case --materials other.in");
    EXPECT_NE(c.status, 0);
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
