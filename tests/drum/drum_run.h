// What the drum's end-to-end suites share: running a command in a fresh work
// directory (with inputs/ linked, as a user runs from the repository root).
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace drum_test {

struct Result {
    int status;
    std::string output;
};

// Runs `command` in `dir`, its output in dir/out.
inline Result shell(const std::string& command, const std::filesystem::path& dir, const std::string& out = "run.out")
{
    const std::string full = "cd '" + dir.string() + "' && " + command + " > " + out + " 2>&1";
    const int status = std::system(full.c_str());
    std::ifstream f(dir / out);
    std::stringstream ss;
    ss << f.rdbuf();
    return {status, ss.str()};
}

// TEST_WORK_DIR/tag, emptied, with inputs/ linked from the source tree.
inline std::filesystem::path freshDir(const std::string& tag)
{
    const std::filesystem::path dir = std::filesystem::path(TEST_WORK_DIR) / tag;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    std::filesystem::create_directory_symlink(std::filesystem::path(SOURCE_DIR) / "inputs", dir / "inputs");
    return dir;
}

}  // namespace drum_test
