// A command line run as a script would run it: its exit status and what it
// printed (stdout and stderr together), for the tools' command-line tests.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <stdexcept>
#include <string>

struct Result {
    int status;          // the exit code
    std::string output;  // stdout and stderr
};

inline Result runShell(const std::string& command)
{
    FILE* p = popen((command + " 2>&1").c_str(), "r");
    if (!p) throw std::runtime_error("cannot run " + command);
    Result r;
    char buf[4096];
    while (size_t n = fread(buf, 1, sizeof buf, p)) r.output.append(buf, n);
    const int status = pclose(p);
    r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}
