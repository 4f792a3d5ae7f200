// collide: validates the viscoelastic contact law in LIGGGHTS against the
// reference solution of two-body impacts, and is the one tool scripts ask for
// collision-derived numbers.
//   collide case        one impact: reference vs LIGGGHTS, as a table
//   collide sweep-dt    error against tc/dt, with the observed order
//   collide sweep-angle oblique impacts at increasing incidence (Chung & Ooi 2011, test 4)
//   collide recurrence  the integrator's recurrence alone: restitution vs dt/tc
//   collide law-map     the continuous law's tangential restitution vs angle and mu
// Material defaults (tc, en, et, mu, bead size and density) come from the
// `variable` lines of --materials (inputs/materials.in: Table 3.1; where it is
// looked for: findMaterials, materials.h).
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli.h"
#include "materials.h"
#include "messages.h"
#include "plot.h"
#include "runner.h"

using namespace collide;
namespace fs = std::filesystem;

namespace {

using tools::check;
using tools::kNonNegative;
using tools::kPositive;

// en and et: the reference's integration stiffens without bound as e -> 0
const tools::Rule kRestitutionChecked{"in [1e-6, 1]", [](double v) { return v >= 1e-6 && v <= 1.0; }};

// An option whose default is `scale` times a variable of the materials file.
struct MaterialOption {
    CLI::App* command;
    CLI::Option* option;
    double* value;
    std::string variable;
    double scale;
};

struct Options {
    Case c;
    RunOptions run;
    std::string geometry = "pair", tangential = "pournin", limitForce = "off", exact = "off";
    std::string exactCollision = "off";  // `case` only
    double ratio = 100.0;  // tc / dt
    double spin = 0.0;     // z spin of sphere 1 [rad/s]
    int phases = 1;
    std::string csv, png;
    std::string materials;  // empty: findMaterials' lookup
    std::vector<MaterialOption> fromMaterials;

    // Sets the material options of the chosen subcommand that the command
    // line left out from the materials file, which must then exist.
    void readMaterialDefaults()
    {
        std::vector<const MaterialOption*> missing;
        for (const MaterialOption& m : fromMaterials)
            if (m.command->parsed() && m.option->count() == 0) missing.push_back(&m);
        if (missing.empty()) return;
        std::string names;
        for (const MaterialOption* m : missing) names += (names.empty() ? "" : ", ") + m->option->get_name();
        std::string file;
        try {
            file = findMaterials(materials);
        } catch (const std::runtime_error& e) {
            throw std::runtime_error(std::string(e.what()) + ", or give the values of " + names);
        }
        if (!fs::exists(file))
            throw std::runtime_error("materials file " + file + " not found: it gives the defaults of " + names +
                                     " (pass another --materials FILE, or give the values)");
        const std::map<std::string, double> values = readMaterials(file);
        for (const MaterialOption* m : missing) {
            const auto it = values.find(m->variable);
            if (it == values.end())
                throw std::runtime_error(file + ": no variable " + m->variable + " (the default of " +
                                         m->option->get_name() + ")");
            *m->value = m->scale * it->second;
        }
    }

    void finish()
    {
        readMaterialDefaults();
        c.geometry = parseGeometry(geometry);
        c.tangential = parseTangential(tangential);
        c.limitForce = limitForce == "on";
        c.exactRestitution = exact == "on";
        // exactCollision: the model setting, and its continuous law (the
        // spring at the rigid arms) as the reference it converges to
        c.rigidArmSpring = exactCollision == "on";
        if (c.rigidArmSpring) run.settings += (run.settings.empty() ? "" : " ") + std::string("exactCollision on");
        c.spin1 = Vec3(0, 0, spin);
        c.dt = c.params.tc / ratio;
    }
};

template <class Check>
void addMaterialOption(CLI::App* app, Options& o, const std::string& flag, double& value, const std::string& variable,
                       const std::string& help, Check check, double scale = 1.0)
{
    std::ostringstream source;
    if (scale != 1.0) source << scale << " * ";
    source << variable;
    CLI::Option* option =
        app->add_option(flag, value, help + " (default: " + source.str() + " in --materials)")->check(check);
    o.fromMaterials.push_back({app, option, &value, variable, scale});
}

// --tc, --en, --limit-force and --materials: what every subcommand takes
// (`recurrence` takes only these: the normal recurrence needs no et or mu).
void addContactOptions(CLI::App* app, Options& o)
{
    addMaterialOption(app, o, "--tc", o.c.params.tc, "bead_tc", "contact duration [s]", check(kPositive));
    addMaterialOption(app, o, "--en", o.c.params.en, "bead_en", "normal restitution", check(kRestitutionChecked));
    app->add_option("--limit-force", o.limitForce, "forbid attraction: on | off")
        ->check(CLI::IsMember({"on", "off"}))->capture_default_str();
    app->add_option("--materials", o.materials, materialsHelp());
}

void addCaseOptions(CLI::App* app, Options& o)
{
    app->add_option("--geometry", o.geometry, "pair | wall (primitive plane) | mesh (STL plane)")
        ->check(CLI::IsMember({"pair", "wall", "mesh"}))->capture_default_str();
    app->add_option("--tangential", o.tangential, "tangential model: history | pournin")
        ->check(CLI::IsMember({"history", "pournin"}))->capture_default_str();
    app->add_option("--exact-restitution", o.exact,
                    "model setting exactRestitution: coefficients corrected for the timestep: on | off")
        ->check(CLI::IsMember({"on", "off"}))->capture_default_str();
    addContactOptions(app, o);
    addMaterialOption(app, o, "--et", o.c.params.et, "bead_et", "tangential restitution", check(kRestitutionChecked));
    addMaterialOption(app, o, "--mu", o.c.params.mu, "bead_mu", "friction coefficient", check(kNonNegative));
    addMaterialOption(app, o, "--r1", o.c.radius1, "bead_d", "radius of sphere 1 [m]", check(kPositive), 0.5);
    addMaterialOption(app, o, "--r2", o.c.radius2, "bead_d", "radius of sphere 2 [m]", check(kPositive), 0.5);
    addMaterialOption(app, o, "--rho1", o.c.density1, "bead_rho", "density of sphere 1 [kg/m^3]", check(kPositive));
    addMaterialOption(app, o, "--rho2", o.c.density2, "bead_rho", "density of sphere 2 [kg/m^3]", check(kPositive));
    app->add_option("--vn", o.c.normalSpeed, "normal approach speed [m/s]")
        ->check(check(kPositive))->capture_default_str();
    app->add_option("--vt", o.c.tangentialSpeed, "tangential speed of 1 relative to 2 [m/s]")->capture_default_str();
    app->add_option("--spin", o.spin, "spin of sphere 1 about z [rad/s]")->capture_default_str();
    app->add_option("--liggghts", o.run.liggghts, "liggghts executable")->capture_default_str();
    app->add_option("--preload", o.run.preload, "library to LD_PRELOAD into a stock liggghts");
    app->add_option("--np", o.run.ranks, "MPI ranks")->check(check(kPositive))->capture_default_str();
    app->add_option("--workdir", o.run.workdir, "directory for LIGGGHTS inputs and outputs");
    app->add_option("--csv", o.csv, "write results as CSV");
}

double relErr(double value, double ref) { return ref != 0.0 ? value / ref - 1.0 : value; }

// `phases` evenly spread contact-start phases (k + 0.5) / phases; one: the
// run options' phase.
std::vector<double> contactPhases(const Options& o, int phases)
{
    return phases == 1 ? std::vector<double>{o.run.phase} : evenPhases(phases);
}

// LIGGGHTS outcome averaged over the contact-start phases, all in one run.
Outcome runAveraged(const Options& o, int phases)
{
    return meanOutcome(o.c, runLiggghts(o.c, o.run, contactPhases(o, phases)));
}

std::string describe(const Case& c, bool withVelocity = true, bool withDt = true)
{
    std::ostringstream s;
    s << name(c.geometry) << ", tangential " << name(c.tangential) << ", limitForce "
      << (c.limitForce ? "on" : "off") << ", tc " << c.params.tc << " s, en " << c.params.en << ", et "
      << c.params.et << ", mu " << c.params.mu;
    if (c.exactRestitution) s << ", exactRestitution on";
    if (c.rigidArmSpring) s << ", exactCollision on";
    if (withVelocity) s << ", vn " << c.normalSpeed << " m/s, vt " << c.tangentialSpeed << " m/s";
    if (withDt) s << ", tc/dt " << c.params.tc / c.dt;
    return s.str();
}

int runCase(Options& o)
{
    o.finish();
    const Reference ref = reference(o.c);
    const std::optional<ClosedForm> cf = closedForm(o.c);
    const std::vector<double> phases = contactPhases(o, o.phases);
    const std::vector<Trajectory> runs = runLiggghts(o.c, o.run, phases);
    const Outcome lig = meanOutcome(o.c, runs);
    std::vector<Outcome> each;  // per phase
    for (const Trajectory& t : runs) each.push_back(measureTrajectory(o.c, t));
    const bool oblique = o.c.tangentialSpeed != 0.0 || o.spin != 0.0;

    std::printf("case: %s\nreference: %s%s\n", describe(o.c).c_str(), ref.source.c_str(),
                cf && cf->hasTangential ? (" (closed form regime: " + cf->regime + ")").c_str() : "");
    // a single contact's outcome depends on where in a step it starts (by
    // several per cent at tc/10): the mean says what the law does, the worst
    // phase what one contact may see
    if (phases.size() == 1)
        std::printf("LIGGGHTS: 1 contact-start phase (%g of a step)\n\n", phases[0]);
    else
        std::printf("LIGGGHTS: %zu contact-start phases ((k + 0.5)/%zu of a step, in one run): their mean, and the "
                    "single phase farthest from the reference\n\n",
                    phases.size(), phases.size());
    std::printf("%-26s %14s %14s %14s %10s %14s %10s\n", "quantity", "closed form", "reference", "LIGGGHTS mean",
                "rel. err", "worst phase", "rel. err");
    struct Quantity {
        const char *label, *key;
        double Outcome::*field;
        bool tangential;  // shown for oblique impacts only
    };
    const Quantity quantities[] = {{"restitution", "restitution", &Outcome::restitution, false},
                                   {"duration [s]", "duration", &Outcome::duration, false},
                                   {"peak overlap [m]", "peak_overlap", &Outcome::peakOverlap, false},
                                   {"tangential restitution", "tangential_restitution",
                                    &Outcome::tangentialRestitution, true},
                                   {"rebound spin [rad/s]", "rebound_spin", &Outcome::spin1, true},
                                   {"rebound angle [deg]", "rebound_angle", &Outcome::reboundAngle, true}};
    std::ostringstream csv;
    csv << "quantity,reference,liggghts,liggghts_worst_phase\n";
    for (const Quantity& q : quantities) {
        const double r = ref.outcome.*q.field, mean = lig.*q.field;
        double worst = each.front().*q.field;
        for (const Outcome& x : each)
            if (std::fabs(relErr(x.*q.field, r)) > std::fabs(relErr(worst, r))) worst = x.*q.field;
        csv << q.key << "," << r << "," << mean << "," << worst << "\n";
        if (q.tangential && !oblique) continue;
        char cfs[32] = "-";
        if (cf && (!q.tangential || cf->hasTangential)) std::snprintf(cfs, sizeof cfs, "%.6g", cf->outcome.*q.field);
        std::printf("%-26s %14s %14.6g %14.6g %+9.3f%% %14.6g %+9.3f%%\n", q.label, cfs, r, mean,
                    100.0 * relErr(mean, r), worst, 100.0 * relErr(worst, r));
    }
    std::printf("duration difference: %.2f steps\n", (lig.duration - ref.outcome.duration) / o.c.dt);
    if (!o.csv.empty()) std::ofstream(o.csv) << csv.str();
    return 0;
}

// Least-squares slope of y against x (an observed order from logs); NaN below two points.
double slope(const std::vector<double>& x, const std::vector<double>& y)
{
    if (x.size() < 2) return NAN;
    double mx = 0, my = 0;
    for (size_t i = 0; i < x.size(); ++i) mx += x[i], my += y[i];
    mx /= x.size(), my /= x.size();
    double sxy = 0, sxx = 0;
    for (size_t i = 0; i < x.size(); ++i) sxy += (x[i] - mx) * (y[i] - my), sxx += (x[i] - mx) * (x[i] - mx);
    return sxy / sxx;
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
    std::vector<double> logDt, logErr, logDtT, logErrT;
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
            if (!x.ok()) throw std::runtime_error(viscoelastic::failureText(x));
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
        if (oblique && tErr != 0.0) logDtT.push_back(std::log(o.c.dt)), logErrT.push_back(std::log(std::fabs(tErr)));
    }
    std::printf("observed order of the restitution error: %.2f\n", slope(logDt, logErr));
    if (oblique) std::printf("observed order of the tangential restitution error: %.2f\n", slope(logDtT, logErrT));
    const std::string csvFile = o.csv.empty() ? "sweep_dt.csv" : o.csv;
    std::ofstream(csvFile) << csv.str();
    // tools/plot.py sweep-dt: the |relative errors| against tc/dt, log-log
    if (!o.png.empty() && tools::plot("collide", "sweep-dt", csvFile, o.png,
                                      {"--title", describe(o.c, true, false), "--tangential", oblique ? "on" : "off"}))
        std::printf("chart: %s\n", o.png.c_str());
    return 0;
}

Case atIncidence(Case c, double angle, double speed);

// What the continuous law (the reference, no LIGGGHTS) restitutes
// tangentially against the incidence angle, one line per friction
// coefficient: et holds only where the contact sticks and et = en.
int runLawMap(Options& o, const std::vector<double>& mus, const std::vector<double>& angles, double speed)
{
    o.finish();
    const std::string csvFile = o.csv.empty() ? "law_map.csv" : o.csv;
    std::ofstream csv(csvFile);
    csv << "mu,angle,tangential_restitution,requested_et\n";
    std::printf("%8s %8s %12s\n", "mu", "angle", "et (law)");
    for (double mu : mus)
        for (double a : angles) {
            Case c = atIncidence(o.c, a, speed);
            c.params.mu = mu;
            const double et = reference(c).outcome.tangentialRestitution;
            std::printf("%8g %8g %12.4f\n", mu, a, et);
            csv << mu << "," << a << "," << et << "," << c.params.et << "\n";
        }
    csv.close();
    if (!o.png.empty()) {
        // tools/plot.py law-map: a line per mu against the angle, the requested et dashed
        std::ostringstream title;
        title << "the continuous law: " << name(o.c.geometry) << ", tangential " << name(o.c.tangential)
              << ", limitForce " << (o.c.limitForce ? "on" : "off") << ", en " << o.c.params.en << ", et "
              << o.c.params.et << ", |v| = " << speed << " m/s";
        if (tools::plot("collide", "law-map", csvFile, o.png, {"--title", title.str()}))
            std::printf("chart: %s\n", o.png.c_str());
    }
    return 0;
}

// The case at `speed` [m/s] and `angle` [deg] from the normal.
Case atIncidence(Case c, double angle, double speed)
{
    const double rad = angle * viscoelastic::kPi / 180.0;
    c.normalSpeed = speed * std::cos(rad);
    c.tangentialSpeed = speed * std::sin(rad);
    return c;
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
        o.c = atIncidence(o.c, a, speed);
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
            const Outcome r = reference(atIncidence(o.c, a, speed)).outcome;
            fine << a << "," << r.tangentialRestitution << "," << r.spin1 << "," << r.reboundAngle << "\n";
        }
        fine.close();
        // tools/plot.py sweep-angle: et, spin and rebound angle, LIGGGHTS' points on the reference's line
        std::ostringstream title;
        title << describe(o.c, false) << ", |v| = " << speed << " m/s";
        if (tools::plot("collide", "sweep-angle", csvFile, o.png, {"--reference", fineFile, "--title", title.str()}))
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
    one->add_option("--ratio", o.ratio, "tc / dt")->check(check(kPositive))->capture_default_str();
    int casePhases = 16;
    one->add_option("--phases", casePhases, "contact-start phases: their mean and the worst single one")
        ->check(check(kPositive))->capture_default_str();
    one->add_option("--exact-collision", o.exactCollision,
                    "model setting exactCollision: every collision restitutes en and et (needs --tangential "
                    "pournin): on | off")
        ->check(CLI::IsMember({"on", "off"}))->capture_default_str();

    std::vector<double> ratios{5, 10, 20, 50, 100};
    CLI::App* dt = app.add_subcommand("sweep-dt", "error against tc/dt and the observed order");
    addCaseOptions(dt, o);
    dt->add_option("--ratios", ratios, "tc/dt values")->delimiter(',')->capture_default_str();
    dt->add_option("--phases", o.phases, "contact-start phases to average over")->check(check(kPositive))
        ->capture_default_str();
    dt->add_option("--png", o.png, "write the chart as PNG");

    std::vector<double> angles{5, 15, 25, 35, 45, 55, 65, 75, 85};
    double speed = 1.0;
    CLI::App* ang = app.add_subcommand("sweep-angle", "oblique impacts, Chung & Ooi (2011) test 4");
    addCaseOptions(ang, o);
    ang->add_option("--angles", angles, "incidence angles from the normal [deg]")->delimiter(',')->capture_default_str();
    ang->add_option("--speed", speed, "impact speed [m/s]")->capture_default_str();
    ang->add_option("--ratio", o.ratio, "tc / dt")->check(check(kPositive))->capture_default_str();
    ang->add_option("--phases", o.phases, "contact-start phases to average over")->check(check(kPositive))
        ->capture_default_str();
    ang->add_option("--png", o.png, "write the chart as PNG");

    std::vector<double> mus{0.1, 0.2, 0.5, 0.95, 10};
    std::vector<double> mapAngles{2, 5, 10, 15, 20, 25, 30, 35, 40, 45, 50, 60, 70, 80};
    CLI::App* map = app.add_subcommand("law-map", "the continuous law's tangential restitution vs angle and mu (no LIGGGHTS)");
    addCaseOptions(map, o);
    map->add_option("--mus", mus, "friction coefficients")->delimiter(',')->capture_default_str();
    map->add_option("--angles", mapAngles, "incidence angles from the normal [deg]")->delimiter(',')->capture_default_str();
    map->add_option("--speed", speed, "impact speed [m/s]")->capture_default_str();
    map->add_option("--png", o.png, "write the chart as PNG");

    std::vector<double> fractions{0.1, 0.2, 0.3, 0.4, 0.5, 0.6};
    CLI::App* rec = app.add_subcommand("recurrence", "the integrator's recurrence only: restitution vs dt/tc, CSV");
    addContactOptions(rec, o);
    rec->add_option("--dt-over-tc", fractions, "dt/tc values")->delimiter(',')->capture_default_str();

    if (const std::optional<int> done = tools::parse(app, "collide", argc, argv)) return *done;
    // what the model would stop on at init, said before a run is set up
    if (*one && o.exactCollision == "on") {
        if (o.tangential != "pournin")
            return tools::usageError("collide", "--exact-collision on needs --tangential pournin");
        if (o.exact == "on")
            return tools::usageError("collide", "--exact-collision on and --exact-restitution on are alternatives");
    }
    try {
        if (*rec) { o.finish(); return runRecurrence(o, fractions); }
        if (*one) { o.phases = casePhases; return runCase(o); }
        if (*map) return runLawMap(o, mus, mapAngles, speed);
        if (*dt) return runSweepDt(o, ratios);
        return runSweepAngle(o, angles, speed);
    } catch (const std::exception& e) {
        std::cerr << "collide: " << e.what() << "\n";
        return 1;
    }
}
