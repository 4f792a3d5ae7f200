// The reader of inputs/materials.in (tools/common/materials.h) that the
// tools use, and where they look for the file.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "materials.h"

TEST(Materials, ReadsVariablesSkippingCommentsAndBlankLines)
{
    std::istringstream in("# Table 3.1\n"
                          "\n"
                          "variable bead_tc        equal 1e-4     # contact duration [s]\n"
                          "   variable bead_en equal 0.56\n"
                          "\t# indented comment\n"
                          "variable bead_rho equal 2500#no space before the comment\n");
    const auto m = readMaterials(in, "test.in");
    EXPECT_EQ(m.at("bead_tc"), 1e-4);
    EXPECT_EQ(m.at("bead_en"), 0.56);
    EXPECT_EQ(m.at("bead_rho"), 2500.0);
    EXPECT_EQ(m.size(), 3u);
}

TEST(Materials, BadLineIsAnErrorNamingTheLine)
{
    const char* bad[] = {"variable bead_tc equal\n", "variable bead_tc string 1e-4\n", "variable bead_tc equal 1e-4x\n",
                         "variable bead_tc equal 1e-4 2\n", "region box block 0 1 0 1 0 1\n",
                         "variable bead_tc equal ${other}\n"};
    for (const char* line : bad) {
        std::istringstream in(std::string("# header\n\nvariable ok equal 1\n") + line);
        try {
            readMaterials(in, "test.in");
            ADD_FAILURE() << "accepted: " << line;
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find("test.in:4:"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(std::string(line, std::strlen(line) - 1)), std::string::npos)
                << e.what();
        }
    }
}

TEST(Materials, MissingFileIsAnError)
{
    EXPECT_THROW(readMaterials("/nonexistent/materials.in"), std::runtime_error);
}

TEST(Materials, ReadsTheRepositoryFile)
{
    const std::string path = std::string(SOURCE_DIR) + "/inputs/materials.in";
    ASSERT_TRUE(std::filesystem::exists(path)) << "no " << path;
    const auto m = readMaterials(path);
    for (const char* name : {"bead_tc", "bead_en", "bead_et", "bead_mu", "drum_tc", "drum_en", "drum_et", "drum_mu",
                             "bead_d", "bead_rho"})
        EXPECT_EQ(m.count(name), 1u) << name;
}

// Where the tools find the file (findMaterials): the one named, else the
// working directory's inputs/materials.in, else the installed copy; each test
// in an empty directory of its own.
class MaterialsLookup : public ::testing::Test {
protected:
    void SetUp() override
    {
        home = std::filesystem::current_path();
        dir = std::filesystem::temp_directory_path() / ("materials_lookup_" + std::to_string(::getpid()));
        std::filesystem::create_directories(dir);
        std::filesystem::current_path(dir);
        ::unsetenv(kVariable);
    }
    void TearDown() override
    {
        std::filesystem::current_path(home);
        std::filesystem::remove_all(dir);
        ::unsetenv(kVariable);
    }
    static constexpr const char* kVariable = "LIGGGHTS_VISCOELASTIC_DATADIR";
    std::filesystem::path home, dir;
};

TEST_F(MaterialsLookup, TheNamedFileWhetherItExistsOrNot)
{
    EXPECT_EQ(findMaterials("glass.in"), "glass.in");  // reading it says it is missing
}

TEST_F(MaterialsLookup, TheWorkingDirectoryBeforeTheInstalledCopy)
{
    std::filesystem::create_directories("inputs");
    std::ofstream("inputs/materials.in") << "variable bead_tc equal 2e-4\n";
    ::setenv(kVariable, SOURCE_DIR "/inputs", 1);
    EXPECT_EQ(findMaterials(""), "inputs/materials.in");
}

TEST_F(MaterialsLookup, TheInstalledCopyFromAnyDirectory)
{
    // compiled in: share/<project>/ under the install prefix
    EXPECT_EQ(installedMaterials(), TOOLS_DATADIR "/materials.in");
    EXPECT_NE(installedMaterials().find("/share/liggghts_viscoelastic/materials.in"), std::string::npos);
    // moved (here: to the source tree, so the test needs no installation)
    ::setenv(kVariable, SOURCE_DIR "/inputs", 1);
    EXPECT_EQ(findMaterials(""), SOURCE_DIR "/inputs/materials.in");
    EXPECT_EQ(readMaterials(findMaterials("")).at("bead_en"), 0.56);
}

TEST_F(MaterialsLookup, NoFileAnywhereNamesEveryPlaceTried)
{
    ::setenv(kVariable, (dir / "nowhere").c_str(), 1);
    try {
        findMaterials("");
        ADD_FAILURE() << "found a file";
    } catch (const std::runtime_error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("inputs/materials.in (in the working directory)"), std::string::npos) << what;
        EXPECT_NE(what.find((dir / "nowhere/materials.in").string() + " (installed)"), std::string::npos) << what;
        EXPECT_NE(what.find("--materials"), std::string::npos) << what;
    }
}
