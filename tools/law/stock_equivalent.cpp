// stock_equivalent: the absolute constants kn, kt, gamman, gammat [N/m, N s/m]
// that `model viscoelastic` uses for each type pair, written as the
// `fix property/global` lines of stock `model hooke/stiffness` with
// `absolute_damping on`. With one mass per type (a wall type: 0) every
// contact of a type pair has one meff, so the stock model then computes the
// same forces; benchmarks use it to time our model against the stock one.
//
//   stock_equivalent --tc 1e-4,1e-4,1e-4,1e-4 --en 0.56,0.46,0.46,0.46 \
//       --et 0.46,0.46,0.46,0.46 --mass 3.534e-5,0 [--exact --dt 1e-5 --limit-force]
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <vector>

#include "core/discrete.h"

int main(int argc, char** argv)
{
    CLI::App app{"Print model viscoelastic's constants as hooke/stiffness properties"};
    std::vector<double> tc, en, et, mass;
    bool exact = false, limitForce = false;
    double dt = 0.0;
    app.add_option("--tc", tc, "contactDuration matrix, row by row")->required()->delimiter(',');
    app.add_option("--en", en, "coefficientRestitution matrix")->required()->delimiter(',');
    app.add_option("--et", et, "coefficientRestitutionTangential matrix")->required()->delimiter(',');
    app.add_option("--mass", mass, "particle mass per type [kg]; 0 for a wall type")->required()->delimiter(',');
    app.add_flag("--exact", exact, "the exactRestitution coefficients (needs --dt)");
    app.add_option("--dt", dt, "timestep [s]")->check(CLI::PositiveNumber);
    app.add_flag("--limit-force", limitForce, "limitForce on (matters with --exact only)");
    CLI11_PARSE(app, argc, argv);

    const size_t n = mass.size();
    for (auto* m : {&tc, &en, &et})
        if (m->size() != n * n) {
            std::fprintf(stderr, "stock_equivalent: each matrix needs %zu values (%zu types)\n", n * n, n);
            return 2;
        }
    if (exact && dt <= 0.0) {
        std::fprintf(stderr, "stock_equivalent: --exact needs --dt\n");
        return 2;
    }
    std::vector<double> kn(n * n), kt(n * n), gn(n * n), gt(n * n);
    for (size_t i = 0; i < n; ++i)
        for (size_t j = 0; j < n; ++j) {
            const size_t k = i * n + j;
            const viscoelastic::ContactParameters p{tc[k], en[k], et[k], 0.0};
            viscoelastic::UnitCoefficients u = viscoelastic::pourninUnitCoefficients(p);
            if (exact) {
                const viscoelastic::ExactSolution s = viscoelastic::exactUnitCoefficients(p, dt, limitForce);
                if (!s.ok()) {
                    std::fprintf(stderr, "stock_equivalent: type pair (%zu,%zu): %s\n", i + 1, j + 1, s.failure.c_str());
                    return 1;
                }
                u = s.unit;
            }
            double meff;
            if (mass[i] > 0 && mass[j] > 0) meff = mass[i] * mass[j] / (mass[i] + mass[j]);
            else meff = mass[i] > 0 ? mass[i] : mass[j];  // sphere-wall; wall-wall never touch
            const viscoelastic::Coefficients c = viscoelastic::scaled(u, meff);
            kn[k] = c.kn, kt[k] = c.kt, gn[k] = c.cn, gt[k] = c.ct;
        }
    auto print = [&](const char* name, const std::vector<double>& v) {
        std::printf("fix %s all property/global %s peratomtypepair %zu", name, name, n);
        for (double x : v) std::printf(" %.17g", x);
        std::printf("\n");
    };
    print("kn", kn);
    print("kt", kt);
    print("gamman_abs", gn);
    print("gammat_abs", gt);
    return 0;
}
