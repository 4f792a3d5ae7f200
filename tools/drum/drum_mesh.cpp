// drum_mesh: writes the drum shell as an ASCII STL triangle mesh: a
// cylinder about the x axis, normals pointing inwards (towards the beads).
#include <CLI/CLI.hpp>

#include <cmath>
#include <fstream>
#include <iostream>

#include "materials.h"

int main(int argc, char** argv)
{
    CLI::App app{"Write a drum shell (cylinder about x) as ASCII STL"};
    double diameter = 0.0, length = 0.024, x0 = 0.0;
    int segments = 360;
    std::string out = "drum.stl", materials = "inputs/materials.in";
    app.add_option("--diameter", diameter, "inner diameter [m] (default: 2 drum_R of --materials)")
        ->check(CLI::PositiveNumber);
    app.add_option("--materials", materials, "Table 3.1 and the scene's constants")->capture_default_str();
    app.add_option("--length", length, "axial length [m]")->check(CLI::PositiveNumber)->capture_default_str();
    app.add_option("--x0", x0, "axial start [m]")->capture_default_str();
    app.add_option("--segments", segments, "facets around the circumference")->check(CLI::Range(3, 100000))->capture_default_str();
    app.add_option("-o,--output", out, "output file")->capture_default_str();
    CLI11_PARSE(app, argc, argv);
    if (diameter <= 0.0) try {
            const auto m = readMaterials(materials);
            if (!m.count("drum_R")) throw std::runtime_error(materials + ": no variable drum_R");
            diameter = 2.0 * m.at("drum_R");
        } catch (const std::exception& e) {
            std::cerr << "drum_mesh: " << e.what() << " (or give --diameter)\n";
            return 2;
        }

    const double r = 0.5 * diameter, pi = std::acos(-1.0);
    std::ofstream f(out);
    f.precision(12);
    f << "solid drum\n";
    auto vertex = [&](double x, double a) { f << "   vertex " << x << " " << r * std::cos(a) << " " << r * std::sin(a) << "\n"; };
    for (int k = 0; k < segments; ++k) {
        const double a0 = 2 * pi * k / segments, a1 = 2 * pi * (k + 1) / segments, am = 0.5 * (a0 + a1);
        for (int t = 0; t < 2; ++t) {
            f << " facet normal 0 " << -std::cos(am) << " " << -std::sin(am) << "\n  outer loop\n";
            // ordered so the right-hand normal points inwards
            if (t == 0) vertex(x0, a0), vertex(x0 + length, a0), vertex(x0 + length, a1);
            else vertex(x0, a0), vertex(x0 + length, a1), vertex(x0, a1);
            f << "  endloop\n endfacet\n";
        }
    }
    f << "endsolid drum\n";
    return f ? 0 : 1;
}
