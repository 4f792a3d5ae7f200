// exactCollision's friction over the whole parameter range: random wall
// collisions (en, et, mu, vt/vn, tc/dt, limitForce) stepped by the physics
// core at random start phases, against the continuous law solved
// independently (collide::wallFrictionAgainstTheLaw). One CSV row per case: its worst
// phase, in units of vt. The tests check fixed cases and a few hundred random
// ones; this looks further.
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "reference.h"

int main(int argc, char** argv)
{
    CLI::App app{"exactCollision's friction against the continuous law on random wall collisions"};
    int cases = 20000, phases = 256;
    unsigned seed = 1;
    app.add_option("--cases", cases, "random cases")->check(CLI::PositiveNumber);
    app.add_option("--phases", phases, "random start phases per case")->check(CLI::PositiveNumber);
    app.add_option("--seed", seed, "seed of the cases (each case's phases: seed + its index)");
    CLI11_PARSE(app, argc, argv);

    std::mt19937 g(seed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    std::printf("case,en,et,mu,vt_over_vn,tc_over_dt,limitForce,law_exit,worst_err,worst_phase\n");
    for (int i = 0; i < cases; ++i) {
        // log-uniform where the range spans decades
        const double en = 0.05 + 0.93 * U(g), et = 0.1 + 0.88 * U(g), mu = 0.05 * std::pow(60.0, U(g));
        const double vt = 0.02 * std::pow(300.0, U(g)), ratio = 4.2 * std::pow(40.0 / 4.2, U(g));
        const bool limitForce = U(g) < 0.5;
        std::mt19937 gp(seed + i);
        std::vector<double> starts;
        for (int k = 0; k < phases; ++k) starts.push_back(1.0 - U(gp));
        const auto r = collide::wallFrictionAgainstTheLaw({1e-4, en, et, mu}, vt, ratio, limitForce, starts);
        if (!r) {  // limitForce with an en a cut contact cannot restitute: drawn again
            --i;
            continue;
        }
        const double exit = r->exit, worst = r->worst, worstPhase = r->worstPhase;  // NaN: the law did not finish
        std::printf("%d,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%.17g,%.3e,%.17g\n", i, en, et, mu, vt, ratio, int(limitForce),
                    exit, worst, worstPhase);
        if ((i + 1) % 1000 == 0) std::fprintf(stderr, "friction_sweep: %d of %d cases\n", i + 1, cases), std::fflush(stdout);
    }
}
