// The drum tools' command line: --version, usage errors (exit code 2, one
// line), errors of the work (exit code 1), and where drum_mesh finds the
// materials file (drum_R) outside a checkout. No LIGGGHTS.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "../shell.h"

namespace fs = std::filesystem;

namespace {

// Runs `command` in `dir` (with `env`, e.g. "NAME=value").
Result run(const std::string& command, const fs::path& dir, const std::string& env = "")
{
    return runShell("cd '" + dir.string() + "' && " + env + " " + command);
}

std::string contents(const fs::path& file)
{
    std::ifstream f(file);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

// An empty directory of this test process.
class DrumCli : public ::testing::Test {
protected:
    void SetUp() override
    {
        dir = fs::temp_directory_path() / ("drum_cli_" + std::to_string(::getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    fs::path dir;
};

const std::string kMesh = "'" DRUM_MESH "'", kMetrics = "'" DRUM_METRICS "'";

}  // namespace

TEST_F(DrumCli, VersionAndHelpExitZero)
{
    for (const auto& [tool, name] : {std::pair{kMesh, "drum_mesh"}, std::pair{kMetrics, "drum_metrics"}}) {
        const Result v = run(tool + " --version", dir);
        EXPECT_EQ(v.status, 0) << name;
        EXPECT_EQ(v.output, std::string(name) + " " TOOLS_VERSION "\n");
        const Result h = run(tool + " --help", dir);
        EXPECT_EQ(h.status, 0) << name;
        EXPECT_NE(h.output.find("--version"), std::string::npos) << h.output;
    }
}

TEST_F(DrumCli, UsageErrorsAreOneLineWithExitCodeTwo)
{
    const std::pair<std::string, const char*> bad[] = {
        {kMesh + " --frobnicate", "--frobnicate"},
        {kMesh + " --ridges 12", "--ridges and --depth go together"},
        {kMesh + " --segments 2", "--segments"},
        {kMesh + " --length -1", "--length: must be > 0, not -1"},
        {kMetrics, "a subcommand is required: one of series, steady, table, metrics, compare"},
        {kMetrics + " series", "--prefix is required"},
        {kMetrics + " series --prefix x --rpm 21 --dt 0", "--dt: must be > 0, not 0"},
        {kMetrics + " bogus", "'bogus' is not a subcommand"},
        {kMetrics + " --bogus", "unknown option --bogus"}};
    for (const auto& [command, what] : bad) {
        const Result r = run(command, dir);
        const std::string name = command.find("drum_mesh") != std::string::npos ? "drum_mesh" : "drum_metrics";
        EXPECT_EQ(r.status, 2) << command << ": " << r.output;
        EXPECT_TRUE(std::regex_match(r.output, std::regex(name + ": [^\n]+; see " + name + " --help\n")))
            << command << ": " << r.output;
        EXPECT_NE(r.output.find(what), std::string::npos) << command << ": " << r.output;
    }
}

// A file that was named and is missing is not a usage error: exit code 1.
TEST_F(DrumCli, MissingNamedFileIsAnErrorOfTheWork)
{
    const Result c = run(kMetrics + " compare a.vtp b.vtp", dir);
    EXPECT_EQ(c.status, 1);
    EXPECT_EQ(c.output, "drum_metrics: a.vtp: no such file\n");
    const Result m = run(kMesh + " --materials nope.in", dir);
    EXPECT_EQ(m.status, 1);
    EXPECT_NE(m.output.find("nope.in: cannot open the materials file"), std::string::npos) << m.output;
}

// Outside a checkout drum_mesh takes drum_R from the installed materials file
// ($LIGGGHTS_VISCOELASTIC_DATADIR stands in for the install here, pointing at
// the source tree's inputs/); without one, an error naming every place tried.
TEST_F(DrumCli, MeshFindsTheInstalledMaterials)
{
    const Result r = run(kMesh + " -o found.stl", dir, "LIGGGHTS_VISCOELASTIC_DATADIR='" SOURCE_DIR "/inputs'");
    ASSERT_EQ(r.status, 0) << r.output;
    ASSERT_EQ(run(kMesh + " --diameter 0.45 -o given.stl", dir).status, 0);  // drum_R 0.225 in inputs/materials.in
    EXPECT_EQ(contents(dir / "found.stl"), contents(dir / "given.stl"));
    const Result none = run(kMesh + " -o none.stl", dir, "LIGGGHTS_VISCOELASTIC_DATADIR=/nonexistent");
    EXPECT_EQ(none.status, 1);
    EXPECT_NE(none.output.find("inputs/materials.in (in the working directory)"), std::string::npos) << none.output;
    EXPECT_NE(none.output.find("/nonexistent/materials.in (installed)"), std::string::npos) << none.output;
}
