// Runs a gnuplot script (charts of the tools); throws if gnuplot fails.
#pragma once

#include <cstdio>
#include <stdexcept>
#include <string>

inline void gnuplot(const std::string& script)
{
    FILE* p = popen("gnuplot", "w");
    if (!p) throw std::runtime_error("cannot start gnuplot");
    fputs(script.c_str(), p);
    if (pclose(p) != 0) throw std::runtime_error("gnuplot failed");
}
