// exactCollision between two spheres over a seeded random sweep, further
// than the tests go: two glass beads stepped as LIGGGHTS steps them
// (tests/contact_models/pair_stepper.h), each draw against the same mode at
// tc/1000 from the same touch. One CSV row per draw: the draw, the pull
// |vt|^2 / d at touch and its largest over the fine step's contact, each
// against the contact's force scale pi vn / tc (per unit mass), the normal's
// turn per step vt dt / d, how far the outcome lies from the fine step (of
// the incoming speed) and the energy change.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "pair_stepper.h"

int main(int argc, char** argv)
{
    CLI::App app{"exactCollision's pair collisions over random draws, against the same mode at tc/1000"};
    int draws = 10000, seed = 1;
    pairstepper::Ranges r;
    app.add_option("--draws", draws, "random collisions");
    app.add_option("--seed", seed, "seed of the draws");
    app.add_option("--spin", r.spin, "largest spin of a bead about a random axis, in vn / R (in half the draws)");
    app.add_option("--slope-min", r.slopeMin, "vt/vn uniform from this to 5");
    app.add_option("--vn-min", r.vnMin, "vn log-uniform from this to 2 m/s");
    app.add_option("--ratio-max", r.ratioMax, "tc/dt from 5 to this");
    app.add_option("--mu-min", r.muMin, "mu log-uniform from this to 100 (80 %) or 1e6");
    int phases = 1;
    app.add_option("--phases", phases,
                   "each draw at this many evenly spread start phases, its worst reported (phase, off, "
                   "energy change); 1: at its drawn phase")
        ->check(CLI::PositiveNumber);
    CLI11_PARSE(app, argc, argv);
    std::mt19937 g(seed);
    std::printf("en,et,mu,vn,vt_over_vn,spin_i,spin_j,limitForce,tc_over_dt,phase,pull_fraction,largest_pull_fraction,"
                "turn_per_step,off,energy_change\n");
    for (int i = 0; i < draws; ++i) {
        pairstepper::Setup c = pairstepper::drawPair(g, r);
        double off = -1.0, gain = -1.0, at = c.phase, largestPull = 0.0;
        for (int k = 0; k < phases; ++k) {
            if (phases > 1) c.phase = (k + 0.5) / phases;
            const auto runs = pairstepper::coarseAndFine(c);
            if (!runs) break;  // a step the model refuses
            const double o = pairstepper::apart(runs->coarse, runs->fine, c);
            if (o > off) off = o, at = c.phase;
            gain = std::max(gain, runs->coarse.energyOut / runs->coarse.energyIn - 1.0);
            largestPull = std::max(largestPull, runs->fine.largestPull);
        }
        if (off < 0.0) continue;
        const double d = 2.0 * pairstepper::kRadius, scale = viscoelastic::kPi * c.vn / c.p.tc;
        std::printf("%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%d,%.4g,%.4g,%.3g,%.3g,%.3g,%.3e,%.3e\n", c.p.en, c.p.et, c.p.mu,
                    c.vn, c.vt / c.vn, c.spinI.norm(), c.spinJ.norm(), c.limitForce ? 1 : 0, c.ratio, at,
                    c.vt * c.vt / d / scale, largestPull / scale, c.vt * c.p.tc / c.ratio / d, off, gain);
    }
}
