// collide: validates the viscoelastic contact law in LIGGGHTS against the
// reference solution of two-body impacts.
//   collide case        one impact: reference vs LIGGGHTS, as a table
//   collide sweep-dt    error against tc/dt, with the observed order
//   collide sweep-angle oblique impacts at increasing incidence (Chung & Ooi 2011, test 4)
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "liggghts_run.h"
#include "gnuplot.h"

using namespace impact;
namespace fs = std::filesystem;

namespace {

struct Options {
    Case c;
    RunOptions run;
    std::string geometry = "pair", tangential = "pournin", limitForce = "off", exact = "off";
    double ratio = 100.0;  // tc / dt
    double spin = 0.0;     // z spin of sphere 1 [rad/s]
    int phases = 1;
    std::string csv, png;

    void finish()
    {
        c.geometry = parseGeometry(geometry);
        c.tangential = parseTangential(tangential);
        c.limitForce = limitForce == "on";
        c.exactRestitution = exact == "on";
        c.spin1 = Vec3(0, 0, spin);
        c.dt = c.params.tc / ratio;
    }
};

void addCaseOptions(CLI::App* app, Options& o)
{
    app->add_option("--geometry", o.geometry, "pair | wall (primitive plane) | mesh (STL plane)")
        ->check(CLI::IsMember({"pair", "wall", "mesh"}))->capture_default_str();
    app->add_option("--tangential", o.tangential, "tangential model: history | pournin")
        ->check(CLI::IsMember({"history", "pournin"}))->capture_default_str();
    app->add_option("--limit-force", o.limitForce, "forbid attraction: on | off")
        ->check(CLI::IsMember({"on", "off"}))->capture_default_str();
    app->add_option("--exact-restitution", o.exact,
                    "model setting exactRestitution: coefficients corrected for the timestep: on | off")
        ->check(CLI::IsMember({"on", "off"}))->capture_default_str();
    app->add_option("--tc", o.c.params.tc, "contact duration [s]")->check(CLI::PositiveNumber)->capture_default_str();
    app->add_option("--en", o.c.params.en, "normal restitution")->check(CLI::Range(1e-6, 1.0))->capture_default_str();
    app->add_option("--et", o.c.params.et, "tangential restitution")->check(CLI::Range(1e-6, 1.0))->capture_default_str();
    app->add_option("--mu", o.c.params.mu, "friction coefficient")->check(CLI::NonNegativeNumber)->capture_default_str();
    app->add_option("--r1", o.c.radius1, "radius of sphere 1 [m]")->check(CLI::PositiveNumber)->capture_default_str();
    app->add_option("--r2", o.c.radius2, "radius of sphere 2 [m]")->check(CLI::PositiveNumber)->capture_default_str();
    app->add_option("--rho1", o.c.density1, "density of sphere 1 [kg/m^3]")->check(CLI::PositiveNumber)->capture_default_str();
    app->add_option("--rho2", o.c.density2, "density of sphere 2 [kg/m^3]")->check(CLI::PositiveNumber)->capture_default_str();
    app->add_option("--vn", o.c.normalSpeed, "normal approach speed [m/s]")->check(CLI::PositiveNumber)->capture_default_str();
    app->add_option("--vt", o.c.tangentialSpeed, "tangential speed of 1 relative to 2 [m/s]")->capture_default_str();
    app->add_option("--spin", o.spin, "spin of sphere 1 about z [rad/s]")->capture_default_str();
    app->add_option("--liggghts", o.run.liggghts, "liggghts executable")->capture_default_str();
    app->add_option("--preload", o.run.preload, "library to LD_PRELOAD into a stock liggghts");
    app->add_option("--np", o.run.ranks, "MPI ranks")->check(CLI::PositiveNumber)->capture_default_str();
    app->add_option("--workdir", o.run.workdir, "directory for LIGGGHTS inputs and outputs");
    app->add_option("--csv", o.csv, "write results as CSV");
}

double relErr(double value, double ref) { return ref != 0.0 ? value / ref - 1.0 : value; }

// LIGGGHTS outcome averaged over `phases` evenly spread contact-start phases
// (p + 0.5) / phases, all in one run.
Outcome runAveraged(const Options& o, int phases)
{
    std::vector<double> ph;
    for (int p = 0; p < phases; ++p) ph.push_back(phases == 1 ? o.run.phase : (p + 0.5) / phases);
    const std::vector<Trajectory> runs = runLiggghts(o.c, o.run, ph);
    Outcome sum;
    for (const Trajectory& t : runs) {
        const Outcome x = measure(o.c, t);
        sum.restitution += x.restitution / phases;
        sum.duration += x.duration / phases;
        sum.peakOverlap += x.peakOverlap / phases;
        sum.tangentialRestitution += x.tangentialRestitution / phases;
        sum.spin1 += x.spin1 / phases;
        sum.reboundAngle += x.reboundAngle / phases;
    }
    return sum;
}

std::string describe(const Case& c, bool withVelocity = true, bool withDt = true)
{
    std::ostringstream s;
    s << name(c.geometry) << ", tangential " << name(c.tangential) << ", limitForce "
      << (c.limitForce ? "on" : "off") << ", tc " << c.params.tc << " s, en " << c.params.en << ", et "
      << c.params.et << ", mu " << c.params.mu;
    if (c.exactRestitution) s << ", exactRestitution on";
    if (withVelocity) s << ", vn " << c.normalSpeed << " m/s, vt " << c.tangentialSpeed << " m/s";
    if (withDt) s << ", tc/dt " << c.params.tc / c.dt;
    return s.str();
}

int runCase(Options& o)
{
    o.finish();
    const Reference ref = reference(o.c);
    const std::optional<ClosedForm> cf = closedForm(o.c);
    const Outcome lig = runAveraged(o, o.phases);
    const bool oblique = o.c.tangentialSpeed != 0.0 || o.spin != 0.0;

    std::printf("case: %s\nreference: %s%s\n\n", describe(o.c).c_str(), ref.source.c_str(),
                cf && cf->hasTangential ? (" (closed form regime: " + cf->regime + ")").c_str() : "");
    std::printf("%-26s %14s %14s %14s %10s\n", "quantity", "closed form", "reference", "LIGGGHTS", "rel. err");
    auto row = [&](const char* q, double cfv, bool hasCf, double r, double l) {
        char cfs[32] = "-";
        if (hasCf) std::snprintf(cfs, sizeof cfs, "%.6g", cfv);
        std::printf("%-26s %14s %14.6g %14.6g %+9.3f%%\n", q, cfs, r, l, 100.0 * relErr(l, r));
    };
    const bool cfN = cf.has_value(), cfT = cf && cf->hasTangential;
    const Outcome cfo = cf ? cf->outcome : Outcome{};
    row("restitution", cfo.restitution, cfN, ref.outcome.restitution, lig.restitution);
    row("duration [s]", cfo.duration, cfN, ref.outcome.duration, lig.duration);
    row("peak overlap [m]", cfo.peakOverlap, cfN, ref.outcome.peakOverlap, lig.peakOverlap);
    if (oblique) {
        row("tangential restitution", cfo.tangentialRestitution, cfT, ref.outcome.tangentialRestitution,
            lig.tangentialRestitution);
        row("rebound spin [rad/s]", cfo.spin1, cfT, ref.outcome.spin1, lig.spin1);
        row("rebound angle [deg]", cfo.reboundAngle, cfT, ref.outcome.reboundAngle, lig.reboundAngle);
    }
    std::printf("duration difference: %.2f steps\n", (lig.duration - ref.outcome.duration) / o.c.dt);
    if (!o.csv.empty()) {
        std::ofstream f(o.csv);
        f << "quantity,reference,liggghts\n"
          << "restitution," << ref.outcome.restitution << "," << lig.restitution << "\n"
          << "duration," << ref.outcome.duration << "," << lig.duration << "\n"
          << "peak_overlap," << ref.outcome.peakOverlap << "," << lig.peakOverlap << "\n"
          << "tangential_restitution," << ref.outcome.tangentialRestitution << "," << lig.tangentialRestitution << "\n"
          << "rebound_spin," << ref.outcome.spin1 << "," << lig.spin1 << "\n"
          << "rebound_angle," << ref.outcome.reboundAngle << "," << lig.reboundAngle << "\n";
    }
    return 0;
}

int runSweepDt(Options& o, const std::vector<double>& ratios)
{
    o.finish();
    const Reference ref = reference(o.c);
    const bool oblique = o.c.tangentialSpeed != 0.0 || o.spin != 0.0;
    std::printf("case: %s\nreference: %s; LIGGGHTS averaged over %d contact-start phases\n\n",
                describe(o.c).c_str(), ref.source.c_str(), o.phases);
    std::printf("%8s %12s %12s %12s %14s %14s\n", "tc/dt", "e", "e err", "e predicted", "duration err",
                oblique ? "et err" : "");
    std::ostringstream csv;
    csv << "tc_over_dt,dt,restitution,restitution_rel_err,predicted_restitution,duration_err_steps,"
           "duration_rel_err,tangential_restitution,tangential_rel_err\n";
    std::vector<double> logDt, logErr;
    for (double ratio : ratios) {
        o.c.dt = o.c.params.tc / ratio;
        const Outcome lig = runAveraged(o, o.phases);
        const double eErr = relErr(lig.restitution, ref.outcome.restitution);
        const double tErr = relErr(lig.tangentialRestitution, ref.outcome.tangentialRestitution);
        // the normal recurrence is mass-independent: valid for every geometry;
        // same start phases as the LIGGGHTS runs
        viscoelastic::UnitCoefficients u = viscoelastic::pourninUnitCoefficients(o.c.params);
        if (o.c.exactRestitution) {
            const viscoelastic::ExactSolution x = viscoelastic::exactUnitCoefficients(o.c.params, o.c.dt, o.c.limitForce);
            if (!x.ok()) throw std::runtime_error(x.failure);
            u = x.unit;
        }
        const double predicted = viscoelastic::sampledCollision(u, o.c.dt, o.c.limitForce, o.phases).restitution;
        std::printf("%8.1f %12.6f %+11.3f%% %12.6f %+11.2f st", ratio, lig.restitution, 100 * eErr, predicted,
                    (lig.duration - ref.outcome.duration) / o.c.dt);
        if (oblique) std::printf(" %+13.3f%%", 100 * tErr);
        std::printf("\n");
        csv << ratio << "," << o.c.dt << "," << lig.restitution << "," << eErr << "," << predicted << ","
            << (lig.duration - ref.outcome.duration) / o.c.dt << ","
            << relErr(lig.duration, ref.outcome.duration) << "," << lig.tangentialRestitution << "," << tErr
            << "\n";
        if (eErr != 0.0) logDt.push_back(std::log(o.c.dt)), logErr.push_back(std::log(std::fabs(eErr)));
    }
    // least-squares slope of log|error| against log dt
    double order = NAN;
    if (logDt.size() >= 2) {
        double mx = 0, my = 0;
        for (size_t i = 0; i < logDt.size(); ++i) mx += logDt[i], my += logErr[i];
        mx /= logDt.size(), my /= logDt.size();
        double sxy = 0, sxx = 0;
        for (size_t i = 0; i < logDt.size(); ++i)
            sxy += (logDt[i] - mx) * (logErr[i] - my), sxx += (logDt[i] - mx) * (logDt[i] - mx);
        order = sxy / sxx;
    }
    std::printf("observed order of the restitution error: %.2f\n", order);
    const std::string csvFile = o.csv.empty() ? "sweep_dt.csv" : o.csv;
    std::ofstream(csvFile) << csv.str();
    if (!o.png.empty()) {
        std::ostringstream gp;
        gp << "set terminal pngcairo size 900,600\nset output '" << o.png << "'\nset datafile separator ','\n"
           << "set logscale xy\nset xlabel 'tc / dt'\nset ylabel '|relative error|'\nset grid\n"
           << "set title \"" << describe(o.c, true, false) << "\" font ',9'\nset key top right\n"
           << "plot '" << csvFile << "' every ::1 using 1:(abs($4)) with linespoints lw 2 title 'restitution (LIGGGHTS)', "
           << "'' every ::1 using 1:(abs($5/" << ref.outcome.restitution
           << "-1)) with lines dt 2 title 'restitution (predicted recurrence)', "
           << "'' every ::1 using 1:(abs($7)) with linespoints lw 2 title 'contact duration'";
        if (oblique) gp << ", '' every ::1 using 1:(abs($9)) with linespoints lw 2 title 'tangential restitution'";
        gp << "\n";
        gnuplot(gp.str());
        std::printf("chart: %s\n", o.png.c_str());
    }
    return 0;
}

int runSweepAngle(Options& o, const std::vector<double>& angles, double speed)
{
    o.finish();
    std::printf("case: %s\nimpact speed %g m/s\n\n", describe(o.c).c_str(), speed);
    std::printf("%6s %10s %10s %10s %10s %10s %10s %10s %10s\n", "angle", "et ref", "et lig", "spin ref",
                "spin lig", "rebound ref", "rebound lig", "e ref", "e lig");
    std::ostringstream csv;
    csv << "angle,tangential_restitution_ref,tangential_restitution_liggghts,spin_ref,spin_liggghts,"
           "rebound_angle_ref,rebound_angle_liggghts,restitution_ref,restitution_liggghts,closed_form_regime\n";
    for (double a : angles) {
        const double rad = a * viscoelastic::kPi / 180.0;
        o.c.normalSpeed = speed * std::cos(rad);
        o.c.tangentialSpeed = speed * std::sin(rad);
        const Reference ref = reference(o.c);
        const std::optional<ClosedForm> cf = closedForm(o.c);
        const Outcome lig = runAveraged(o, o.phases);
        std::printf("%6.1f %10.4f %10.4f %10.2f %10.2f %11.3f %11.3f %10.4f %10.4f\n", a,
                    ref.outcome.tangentialRestitution, lig.tangentialRestitution, ref.outcome.spin1, lig.spin1,
                    ref.outcome.reboundAngle, lig.reboundAngle, ref.outcome.restitution, lig.restitution);
        csv << a << "," << ref.outcome.tangentialRestitution << "," << lig.tangentialRestitution << ","
            << ref.outcome.spin1 << "," << lig.spin1 << "," << ref.outcome.reboundAngle << "," << lig.reboundAngle
            << "," << ref.outcome.restitution << "," << lig.restitution << ","
            << (cf && cf->hasTangential ? cf->regime : "none") << "\n";
    }
    const std::string csvFile = o.csv.empty() ? "sweep_angle.csv" : o.csv;
    std::ofstream(csvFile) << csv.str();
    if (!o.png.empty()) {
        // the reference is cheap: draw it on a 1 degree grid
        const std::string fineFile = csvFile + ".reference.csv";
        std::ofstream fine(fineFile);
        fine << "angle,tangential_restitution,spin,rebound_angle\n";
        for (double a = std::max(1.0, angles.front()); a <= std::min(89.0, angles.back()); a += 1.0) {
            Case c = o.c;
            c.normalSpeed = speed * std::cos(a * viscoelastic::kPi / 180.0);
            c.tangentialSpeed = speed * std::sin(a * viscoelastic::kPi / 180.0);
            const Outcome r = reference(c).outcome;
            fine << a << "," << r.tangentialRestitution << "," << r.spin1 << "," << r.reboundAngle << "\n";
        }
        fine.close();
        std::ostringstream gp;
        gp << "set terminal pngcairo size 1500,500\nset output '" << o.png << "'\nset datafile separator ','\n"
           << "set multiplot layout 1,3 title \"" << describe(o.c, false) << ", |v| = " << speed
           << " m/s\" font ',10'\nset grid\nset xlabel 'incidence angle from the normal [deg]'\nset key top center\n";
        const char* panels[][3] = {{"tangential restitution", "2", "3"},
                                   {"rebound spin [rad/s]", "3", "5"},
                                   {"rebound angle [deg]", "4", "7"}};
        for (auto& p : panels)
            gp << "set ylabel '" << p[0] << "'\nplot '" << fineFile << "' every ::1 using 1:" << p[1]
               << " with lines lw 2 title 'reference', '" << csvFile << "' every ::1 using 1:" << p[2]
               << " with points pt 7 ps 1.3 title 'LIGGGHTS'\n";
        gp << "unset multiplot\n";
        gnuplot(gp.str());
        std::printf("chart: %s\n", o.png.c_str());
    }
    return 0;
}

// The integrator's recurrence alone (no LIGGGHTS): restitution averaged over
// the contact-start phase and its largest single-phase value, against dt/tc,
// up to and past the stability limit (e > 1: the contact creates energy).
int runRecurrence(const Options& o, const std::vector<double>& ratios)
{
    const viscoelastic::ContactParameters& p = o.c.params;
    std::printf("dt_over_tc,restitution_mean,restitution_max,duration_steps,stability_limit_dt_over_tc\n");
    for (double r : ratios) {
        const double dt = p.tc * r;
        const viscoelastic::UnitCoefficients u = viscoelastic::pourninUnitCoefficients(p);
        const viscoelastic::DiscreteCollision mean = viscoelastic::phaseAveragedCollision(u, dt, o.c.limitForce);
        double emax = 0.0;
        for (int k = 0; k < 256; ++k)
            emax = std::max(emax, viscoelastic::discreteCollisionAtPhase(u, dt, o.c.limitForce, (k + 0.5) / 256)
                                      .outcome.restitution);
        std::printf("%.4f,%.6f,%.6f,%.3f,%.4f\n", r, mean.restitution, emax, mean.duration / dt,
                    viscoelastic::criticalTimestep(p.tc, p.en) / p.tc);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{"Validate the viscoelastic contact law in LIGGGHTS against two-body impact references"};
    app.require_subcommand(1);
    Options o;

    CLI::App* one = app.add_subcommand("case", "one impact: reference vs LIGGGHTS");
    addCaseOptions(one, o);
    one->add_option("--ratio", o.ratio, "tc / dt")->check(CLI::PositiveNumber)->capture_default_str();
    one->add_option("--phases", o.phases, "contact-start phases to average over")->capture_default_str();

    std::vector<double> ratios{5, 10, 20, 50, 100};
    CLI::App* dt = app.add_subcommand("sweep-dt", "error against tc/dt and the observed order");
    addCaseOptions(dt, o);
    dt->add_option("--ratios", ratios, "tc/dt values")->delimiter(',')->capture_default_str();
    dt->add_option("--phases", o.phases, "contact-start phases to average over")->capture_default_str();
    dt->add_option("--png", o.png, "write the chart as PNG");

    std::vector<double> angles{5, 15, 25, 35, 45, 55, 65, 75, 85};
    double speed = 1.0;
    CLI::App* ang = app.add_subcommand("sweep-angle", "oblique impacts, Chung & Ooi (2011) test 4");
    addCaseOptions(ang, o);
    ang->add_option("--angles", angles, "incidence angles from the normal [deg]")->delimiter(',')->capture_default_str();
    ang->add_option("--speed", speed, "impact speed [m/s]")->capture_default_str();
    ang->add_option("--ratio", o.ratio, "tc / dt")->check(CLI::PositiveNumber)->capture_default_str();
    ang->add_option("--phases", o.phases, "contact-start phases to average over")->capture_default_str();
    ang->add_option("--png", o.png, "write the chart as PNG");

    std::vector<double> fractions{0.1, 0.2, 0.3, 0.4, 0.5, 0.6};
    CLI::App* rec = app.add_subcommand("recurrence", "the integrator's recurrence only: restitution vs dt/tc, CSV");
    rec->add_option("--en", o.c.params.en, "normal restitution")->check(CLI::Range(1e-6, 1.0))->capture_default_str();
    rec->add_option("--tc", o.c.params.tc, "contact duration [s]")->check(CLI::PositiveNumber)->capture_default_str();
    rec->add_option("--limit-force", o.limitForce, "forbid attraction: on | off")
        ->check(CLI::IsMember({"on", "off"}))->capture_default_str();
    rec->add_option("--dt-over-tc", fractions, "dt/tc values")->delimiter(',')->capture_default_str();

    CLI11_PARSE(app, argc, argv);
    try {
        if (*rec) { o.finish(); return runRecurrence(o, fractions); }
        if (*one) return runCase(o);
        if (*dt) { o.phases = std::max(o.phases, 1); return runSweepDt(o, ratios); }
        return runSweepAngle(o, angles, speed);
    } catch (const std::exception& e) {
        std::cerr << "collide: " << e.what() << "\n";
        return 1;
    }
}
