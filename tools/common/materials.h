// Reads the `variable NAME equal VALUE  # comment` lines of a LIGGGHTS include
// file (inputs/materials.in: Table 3.1 and the drum scene), so the tools take
// their defaults from the file the simulations include. Blank lines and `#`
// comments are skipped; any other line (another command, another variable
// style, an expression instead of a number, trailing words) is an error
// naming the file and the line.
//
// Which file: findMaterials() below (the one named, else the working
// directory's inputs/materials.in, else the installed copy).
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <istream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>

// `source` names the stream in errors (the file's path).
inline std::map<std::string, double> readMaterials(std::istream& in, const std::string& source)
{
    std::map<std::string, double> values;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        std::istringstream words(line.substr(0, line.find('#')));
        std::string command, name, style, value, extra;
        if (!(words >> command)) continue;  // blank or comment only
        char* end = nullptr;
        double v = 0.0;
        const bool good = command == "variable" && (words >> name >> style >> value) && style == "equal" &&
                          !(words >> extra) && (v = std::strtod(value.c_str(), &end), *end == '\0');
        if (!good)
            throw std::runtime_error(source + ":" + std::to_string(number) +
                                     ": expected `variable NAME equal NUMBER`, got: " + line);
        values[name] = v;
    }
    return values;
}

inline std::map<std::string, double> readMaterials(const std::string& path)
{
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open the materials file");
    return readMaterials(in, path);
}

// Where the installed copy lies: TOOLS_DATADIR (share/<project>/ under the
// install prefix, compiled in), or $LIGGGHTS_VISCOELASTIC_DATADIR for an
// installation moved elsewhere (and for tests, which must not need one).
inline std::string installedMaterials()
{
    const char* moved = std::getenv("LIGGGHTS_VISCOELASTIC_DATADIR");
    return std::string(moved && *moved ? moved : TOOLS_DATADIR) + "/materials.in";
}

// The materials file: `named` (from --materials) if given, whether it exists
// or not (reading it says so); else inputs/materials.in in the working
// directory (a checkout, run from its root); else the installed copy. Throws
// naming every place tried.
inline std::string findMaterials(const std::string& named)
{
    if (!named.empty()) return named;
    const std::string local = "inputs/materials.in", installed = installedMaterials();
    for (const std::string& path : {local, installed})
        if (std::filesystem::exists(path)) return path;
    throw std::runtime_error("no materials file: not " + local + " (in the working directory) nor " + installed +
                             " (installed); give --materials FILE");
}

// The help of a --materials option.
inline std::string materialsHelp()
{
    return "LIGGGHTS include of `variable NAME equal VALUE` lines (default: inputs/materials.in in the working "
           "directory, else " + installedMaterials() + ")";
}
