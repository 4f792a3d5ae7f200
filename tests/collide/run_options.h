// The LIGGGHTS runs of the end-to-end collide tests: our launcher, one work
// directory per tag under the build's test_runs, extra model settings.
#pragma once

#include <filesystem>
#include <string>

#include "runner.h"

inline collide::RunOptions options(const std::string& tag, const std::string& settings = "")
{
    collide::RunOptions o;
    o.liggghts = LIGGGHTS_LAUNCHER;
    o.workdir = (std::filesystem::path(TEST_WORK_DIR) / tag).string();
    o.settings = settings;
    return o;
}
