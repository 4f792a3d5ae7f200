// exactCollision's friction over the whole parameter range: random wall
// collisions (en, et, mu, vt/vn, tc/dt, limitForce) stepped by the physics
// core at random start phases, against the continuous law solved
// independently: without limitForce by tools/collide/continuous_law (written
// from the equations, nothing of contact_models/); with it, where
// exactCollision follows a solved cut law of its own, by
// collide::wallFrictionAgainstTheLaw. One CSV row per case: its worst phase,
// in units of vt, and whether any phase left faster than it came (a flat
// wall's tangential motion can only lose energy). The tests check a few
// thousand random cases; this looks further.
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "continuous_law.h"
#include "core/stability.h"
#include "reference.h"

namespace {

struct Worst {
    double exit, worst, phase;
    int gains;
};

// limitForce off: every phase against the independent law, and the invariant
Worst againstIndependentLaw(const viscoelastic::ContactParameters& p, double vt, double ratio,
                            const std::vector<double>& starts)
{
    using namespace viscoelastic;
    const auto o = exactCollisionOscillators(p, false);
    const double dt = p.tc / ratio;
    const StepLaw normal = stepLaw(o->normal.k, o->normal.c, dt, false);
    const StepLaw tangential = stepLaw(o->tangential.k, o->tangential.c, dt, false);
    const double law = continuous::wallImpact({p.tc, p.en, p.et, p.mu}, {1.0, vt, false}).vt;
    Worst w{law, 0.0, 0.0, 0};
    for (double phase : starts) {
        const FrictionalExit e =
            exactWallCollisionAtPhase(normal, tangential, phase, vt, p.mu, [](double) { return 2.0 / 7.0; });
        const double err = std::fabs(e.tangential - law) / vt;
        if (!(err <= w.worst)) w.worst = err, w.phase = phase;
        if (std::fabs(e.tangential) > vt * (1.0 + 1e-9)) ++w.gains;
    }
    return w;
}

}  // namespace

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
    std::printf("case,en,et,mu,vt_over_vn,tc_over_dt,limitForce,reference,law_exit,worst_err,worst_phase,gains\n");
    for (int i = 0; i < cases; ++i) {
        // log-uniform where the range spans decades; et = en in a third (the oscillators are then the same,
        // and the spring's force and the cap vanish together at the normal force's zero)
        const double en = 0.05 + 0.93 * U(g), etDrawn = 0.1 + 0.88 * U(g), mu = 0.05 * std::pow(2e7, U(g));
        const double et = U(g) < 0.33 ? std::max(en, 0.1) : etDrawn;
        const double vt = 0.02 * std::pow(300.0, U(g)), ratio = 4.2 * std::pow(40.0 / 4.2, U(g));
        const bool limitForce = U(g) < 0.5;
        std::mt19937 gp(seed + i);
        std::vector<double> starts;
        for (int k = 0; k < phases; ++k) starts.push_back(1.0 - U(gp));
        const viscoelastic::ContactParameters p{1e-4, en, et, mu};
        Worst w{};
        if (!limitForce) {
            w = againstIndependentLaw(p, vt, ratio, starts);
        } else {
            const auto r = collide::wallFrictionAgainstTheLaw(p, vt, ratio, limitForce, starts);
            if (!r) {  // an en a cut contact cannot restitute: drawn again
                --i;
                continue;
            }
            w = {r->exit, r->worst, r->worstPhase, 0};  // NaN: the law did not finish
        }
        std::printf("%d,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%s,%.17g,%.3e,%.17g,%d\n", i, en, et, mu, vt, ratio,
                    int(limitForce), limitForce ? "cut law" : "independent", w.exit, w.worst, w.phase, w.gains);
        if ((i + 1) % 1000 == 0) std::fprintf(stderr, "friction_sweep: %d of %d cases\n", i + 1, cases), std::fflush(stdout);
    }
}
