// One wall collision with friction in LIGGGHTS under each exactness mode
// (nominal, exactRestitution, exactCollision; tangential pournin), against
// dt/tc: the worst start phase and the mean over phases, each against the same
// mode at tc/2000 (what the mode's own law gives, LIGGGHTS' lever arm
// included: a dt-independence measure). Table 3.1's beads (en 0.56, et 0.46)
// sticking at first on a flat wall (vn 0.2 m/s, vt/vn 0.2), friction mu 0.5, 5
// and 1e6, random start phases. One CSV row per (mode, mu, tc/dt).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "runner.h"

using namespace collide;

int main(int argc, char** argv)
{
    CLI::App app{"single wall collisions with friction under nominal, exactRestitution and exactCollision"};
    std::string liggghts = "liggghts", workdir = "post/exact_modes";
    int phases = 64;
    std::vector<double> ratios{5, 6, 7.3, 10, 15, 20, 40, 81};
    app.add_option("--liggghts", liggghts, "liggghts executable");
    app.add_option("--workdir", workdir, "where the runs go");
    app.add_option("--phases", phases, "random start phases per run")->check(CLI::PositiveNumber);
    app.add_option("--ratios", ratios, "tc/dt")->delimiter(',');
    CLI11_PARSE(app, argc, argv);

    std::printf("mode,mu,tc_over_dt,phases,mean_en,mean_et,ref_en,ref_et,worst_en_err,worst_et_err,mean_en_err,mean_et_err\n");
    std::mt19937 g(2026);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (const char* mode : {"nominal", "exactRestitution", "exactCollision"})
        for (double mu : {0.5, 5.0, 1e6}) {
            Case c;
            c.geometry = Geometry::Wall;
            c.params = {1e-4, 0.56, 0.46, mu};
            c.normalSpeed = 0.2;
            c.tangentialSpeed = 0.04;
            RunOptions o;
            o.liggghts = liggghts;
            o.settings = std::string(mode) == "nominal" ? "" : std::string(mode) + " on";
            const auto outcomes = [&](double ratio, const std::vector<double>& starts) {
                c.dt = c.params.tc / ratio;
                o.workdir = workdir + "/" + mode + "_" + std::to_string(mu) + "_" + std::to_string(ratio);
                std::vector<Outcome> r;
                for (const Trajectory& t : runLiggghts(c, o, starts)) r.push_back(measureTrajectory(c, t));
                return r;
            };
            const Outcome ref = outcomes(2000.0, {0.5})[0];
            for (double ratio : ratios) {
                std::vector<double> starts;
                for (int k = 0; k < phases; ++k) starts.push_back(1.0 - u(g));
                std::vector<Outcome> runs;
                try {
                    runs = outcomes(ratio, starts);
                } catch (const std::exception&) {  // the mode's guard refused the step
                    std::fprintf(stderr, "exact_modes: %s mu %g tc/dt %g refused by the guard\n", mode, mu, ratio);
                    continue;
                }
                double men = 0, met = 0, wen = 0, wet = 0;
                for (const Outcome& x : runs) {
                    men += x.restitution / runs.size(), met += x.tangentialRestitution / runs.size();
                    wen = std::max(wen, std::fabs(x.restitution / ref.restitution - 1.0));
                    wet = std::max(wet, std::fabs(x.tangentialRestitution / ref.tangentialRestitution - 1.0));
                }
                std::printf("%s,%g,%g,%d,%.9f,%.9f,%.9f,%.9f,%.4e,%.4e,%.4e,%.4e\n", mode, mu, ratio, phases, men, met,
                            ref.restitution, ref.tangentialRestitution, wen, wet,
                            std::fabs(men / ref.restitution - 1.0), std::fabs(met / ref.tangentialRestitution - 1.0));
                std::fflush(stdout);
            }
        }
}
