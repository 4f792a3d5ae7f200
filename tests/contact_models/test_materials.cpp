// The reader of inputs/materials.in (tools/common/materials.h) that
// contact_law uses.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
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
