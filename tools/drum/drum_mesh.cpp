// drum_mesh: writes the drum shell as an ASCII STL triangle mesh: a
// cylinder about the x axis, normals pointing inwards (towards the beads);
// or, with --ridges, a grooved drum: axial V-grooves cut outwards into the
// cylinder (ridge tips on it, groove bottoms --depth beyond), so a bed that
// fits the smooth drum fits the grooved one too.
#include <CLI/CLI.hpp>

#include <cmath>
#include <fstream>
#include <iostream>
#include <utility>
#include <vector>

#include "cli.h"
#include "materials.h"

int main(int argc, char** argv)
{
    CLI::App app{"Write a drum shell (cylinder about x) as ASCII STL"};
    double diameter = 0.0, length = 0.024, x0 = 0.0;
    int segments = 360, ridges = 0;
    double depth = 0.0;
    std::string out = "drum.stl", materials;  // materials empty: findMaterials' lookup
    app.add_option("--diameter", diameter, "inner diameter [m] (default: 2 drum_R of --materials)")
        ->check(tools::check(tools::kPositive));
    app.add_option("--materials", materials, materialsHelp());
    app.add_option("--length", length, "axial length [m]")
        ->check(tools::check(tools::kPositive))->capture_default_str();
    app.add_option("--x0", x0, "axial start [m]")->capture_default_str();
    app.add_option("--segments", segments, "facets around the circumference")->check(CLI::Range(3, 100000))->capture_default_str();
    app.add_option("--ridges", ridges,
                   "grooved drum: this many axial ridges around the circumference (instead of --segments facets)")
        ->check(CLI::Range(3, 100000));
    app.add_option("--depth", depth, "groove depth beyond the cylinder [m] (with --ridges)")
        ->check(tools::check(tools::kPositive));
    app.add_option("-o,--output", out, "output file")->capture_default_str();
    if (const std::optional<int> done = tools::parse(app, "drum_mesh", argc, argv)) return *done;
    if ((ridges > 0) != (depth > 0.0))
        return tools::usageError("drum_mesh", "--ridges and --depth go together (a grooved drum needs both)");
    if (diameter <= 0.0) try {
            const std::string file = findMaterials(materials);
            const auto m = readMaterials(file);
            if (!m.count("drum_R")) throw std::runtime_error(file + ": no variable drum_R");
            diameter = 2.0 * m.at("drum_R");
        } catch (const std::exception& e) {
            std::cerr << "drum_mesh: " << e.what() << " (or give --diameter)\n";
            return 1;
        }

    const double r = 0.5 * diameter, pi = std::acos(-1.0);
    // the profile around the axis: counter-clockwise (angle, radius) points
    std::vector<std::pair<double, double>> profile;
    if (ridges > 0)
        for (int k = 0; k < 2 * ridges; ++k) profile.emplace_back(pi * k / ridges, k % 2 ? r + depth : r);
    else
        for (int k = 0; k < segments; ++k) profile.emplace_back(2 * pi * k / segments, r);
    std::ofstream f(out);
    f.precision(12);
    f << "solid drum\n";
    auto vertex = [&](double x, double y, double z) { f << "   vertex " << x << " " << y << " " << z << "\n"; };
    for (size_t k = 0; k < profile.size(); ++k) {
        const auto [a0, r0] = profile[k];
        const auto [next, r1] = profile[(k + 1) % profile.size()];
        const double a1 = k + 1 == profile.size() ? 2 * pi : next;
        const double y0 = r0 * std::cos(a0), z0 = r0 * std::sin(a0), y1 = r1 * std::cos(a1), z1 = r1 * std::sin(a1);
        // the strip's normal: the chord turned a quarter counter-clockwise, towards the axis
        const double len = std::hypot(y1 - y0, z1 - z0), ny = -(z1 - z0) / len, nz = (y1 - y0) / len;
        for (int t = 0; t < 2; ++t) {
            f << " facet normal 0 " << ny << " " << nz << "\n  outer loop\n";
            // ordered so the right-hand normal points inwards
            if (t == 0) vertex(x0, y0, z0), vertex(x0 + length, y0, z0), vertex(x0 + length, y1, z1);
            else vertex(x0, y0, z0), vertex(x0 + length, y1, z1), vertex(x0, y1, z1);
            f << "  endloop\n endfacet\n";
        }
    }
    f << "endsolid drum\n";
    return f ? 0 : 1;
}
