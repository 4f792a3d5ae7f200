// Draws the tools' charts: runs tools/plot.py (matplotlib, the style of every
// chart of the project) on a CSV file a tool wrote,
//   /usr/bin/python3 plot.py KIND CSV PNG [options]
// (python3 on PATH where Debian's is missing). A chart that cannot be drawn
// is a WARNING on stderr, not a failure of the tool: its numbers are in the
// CSV, and `plot.py KIND CSV PNG` draws it again.
#pragma once

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

extern char** environ;

namespace tools {

// The script: the source tree's tools/plot.py (TOOLS_PLOT_SOURCE, compiled
// in) for a binary that runs from the build tree (TOOLS_BUILD_DIR); else the
// copy installed with the tools beside the harness it imports,
// TOOLS_DATADIR/python/plot.py ($LIGGGHTS_VISCOELASTIC_DATADIR for an
// installation moved elsewhere, as for materials.in).
inline std::string plotScript()
{
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    const fs::path build = fs::weakly_canonical(TOOLS_BUILD_DIR, ec);
    if (!exe.empty() && !build.empty() &&
        std::mismatch(build.begin(), build.end(), exe.begin(), exe.end()).first == build.end() &&
        fs::exists(TOOLS_PLOT_SOURCE))
        return TOOLS_PLOT_SOURCE;
    const char* moved = std::getenv("LIGGGHTS_VISCOELASTIC_DATADIR");
    return std::string(moved && *moved ? moved : TOOLS_DATADIR) + "/python/plot.py";
}

// Draws chart `kind` of `csv` into `png` (`options`: plot.py's, e.g.
// {"--title", "..."}); true if drawn, else a WARNING naming `tool` and why.
inline bool plot(const std::string& tool, const std::string& kind, const std::string& csv, const std::string& png,
                 const std::vector<std::string>& options = {})
{
    const std::string script = plotScript();
    const auto warn = [&](const std::string& why) {
        std::fprintf(stderr, "%s: WARNING: chart %s not drawn: %s (its data: %s)\n", tool.c_str(), png.c_str(),
                     why.c_str(), csv.c_str());
        return false;
    };
    if (!std::filesystem::exists(script)) return warn("no " + script + " (installed with the tools)");
    const bool debian = access("/usr/bin/python3", X_OK) == 0;
    std::vector<std::string> words = {debian ? "/usr/bin/python3" : "python3", script, kind, csv, png};
    words.insert(words.end(), options.begin(), options.end());
    std::vector<char*> argv;
    for (std::string& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    std::fflush(stdout);  // what the tool printed so far comes before the script's messages
    std::fflush(stderr);
    pid_t pid = 0;
    const int err = debian ? posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ)
                           : posix_spawnp(&pid, argv[0], nullptr, nullptr, argv.data(), environ);
    if (err != 0) return warn("cannot start " + words[0] + ": " + std::strerror(err));
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) return warn(std::string("waiting for ") + words[0] + ": " + std::strerror(errno));
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        return warn(words[0] + " " + script + " " + kind + " " +
                    (WIFEXITED(status) ? "exited with status " + std::to_string(WEXITSTATUS(status))
                                       : std::string("was killed")));
    return true;
}

}  // namespace tools
