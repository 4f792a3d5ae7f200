// What every tool's command line does alike: `--version` prints `NAME
// VERSION`; a usage error (unknown option, bad value, missing argument) is
// one line on stderr and exit code 2, the shell's convention for a command
// used wrongly (CLI11's own codes, 100 and up, tell a script nothing it can
// act on). Errors of the work itself (a failed run, a file that cannot be
// read) stay exit code 1, in each tool.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

namespace tools {

constexpr int kUsageError = 2;

// `name: what; see name --help` on stderr; returns kUsageError.
inline int usageError(const std::string& name, std::string what)
{
    for (char& c : what)
        if (c == '\n') c = ' ';
    std::fprintf(stderr, "%s: %s; see %s --help\n", name.c_str(), what.c_str(), name.c_str());
    return kUsageError;
}

// Parses the command line of tool `name`. nullopt: go on; else the exit
// code to return (0 after --help or --version, which print to stdout).
inline std::optional<int> parse(CLI::App& app, const std::string& name, int argc, char** argv)
{
    app.set_version_flag("--version", name + " " + TOOLS_VERSION, "print the version and exit");
    try {
        app.parse(argc, argv);
        return std::nullopt;
    } catch (const CLI::Success& e) {
        return app.exit(e);
    } catch (const CLI::RequiredError& e) {
        // CLI11 checks for a missing subcommand before it looks at the words
        // it did not understand: name those, and the subcommands
        const std::vector<CLI::App*> all = app.get_subcommands({});
        if (all.empty() || !app.get_subcommands().empty()) return usageError(name, e.what());
        const std::vector<std::string> rest = app.remaining();
        std::string what = "a subcommand is required";
        if (!rest.empty() && rest.front()[0] == '-') what = "unknown option " + rest.front() + ", and " + what;
        if (!rest.empty() && rest.front()[0] != '-') what = "'" + rest.front() + "' is not a subcommand";
        for (size_t k = 0; k < all.size(); ++k) what += (k ? ", " : ": one of ") + all[k]->get_name();
        return usageError(name, what);
    } catch (const CLI::ParseError& e) {
        return usageError(name, e.what());
    }
}

// What a number must be: one rule for an option (checked as it is parsed)
// and for the same value read from a file.
struct Rule {
    const char* what;
    bool (*ok)(double);
};
inline const Rule kPositive{"> 0", [](double v) { return v > 0.0; }};
inline const Rule kNonNegative{">= 0", [](double v) { return v >= 0.0; }};
inline const Rule kRestitution{"in (0, 1]", [](double v) { return v > 0.0 && v <= 1.0; }};

// The rule as an option's check: "--tc: must be > 0, not -1" (CLI11 puts the
// option's name in front; its own number checks print the range's bounds to
// 300 digits).
inline CLI::Validator check(const Rule& rule)
{
    return CLI::Validator(
        [rule](std::string& s) -> std::string {
            char* end = nullptr;
            const double v = std::strtod(s.c_str(), &end);
            if (end == s.c_str() || *end != '\0') return "must be a number, not '" + s + "'";
            return rule.ok(v) ? "" : std::string("must be ") + rule.what + ", not " + s;
        },
        rule.what);
}

}  // namespace tools
