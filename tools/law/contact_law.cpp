// contact_law: every number of the contact law a script needs, from the core
// (so no script re-derives physics) and from inputs/materials.in (Table 3.1).
// Type 1 is the beads (mass from bead_d, bead_rho), type 2 the drum (a wall,
// mass 0). Thesis conventions: bead-bead pairs take bead_*, pairs with the
// drum take drum_*.
//
//   contact_law stock [--materials F] [--uniform EN] [--law L --dt DT [--limit-force]]
//       `fix property/global` lines of stock hooke/stiffness (absolute_damping
//       on) with the constants `model viscoelastic` uses: with one mass per
//       type every contact of a type pair has one meff, so the stock model
//       computes the same forces. --uniform EN: en = et = EN for every pair.
//       --law exactRestitution: its coefficients at DT; --law exactCollision:
//       its step law's, the force of a contact under way (not its first and
//       last steps). (--exact: --law exactRestitution.)
//   contact_law limit --en E [--et E2] [--tc T] [--at DT_OVER_TC] [--law L]
//       CSV: the binary stability limit (Jury) and the run's guard; with --at,
//       the stiffening Z at which the guard's form gives that dt. With --law,
//       the guard and Z on the coefficients that law applies (they depend on
//       dt: the guard is the largest dt it admits, by bisection).
//   contact_law bead-mass [--materials F]
//       the mass of one bead [kg].
//   contact_law single --en E [--et E2] [--tc T] [--limit-force] [--ratios R,...] [--phases N]
//       CSV: single binary collisions over N start phases at each tc/dt,
//       plain Pournin coefficients, exactRestitution and exactCollision:
//       the worst and the mean relative error of en and (sticking) et.
//   contact_law coefficients [--materials F] [--meff M]
//       CSV per type pair: tc, en, et, mu and kn, cn, kt, ct per unit meff
//       (or for the effective mass M).
#include <CLI/CLI.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/viscoelastic.h"
#include "materials.h"  // tools/common: the one reader of inputs/materials.in
#include "messages.h"

namespace {

using namespace viscoelastic;

constexpr int kTypes = 2;  // 1 beads, 2 the drum

// The variables of a materials file, and where they came from.
class Materials {
public:
    explicit Materials(const std::string& path) : path_(path), values_(readMaterials(path)) {}
    double operator[](const std::string& name) const
    {
        const auto it = values_.find(name);
        if (it == values_.end()) throw std::runtime_error(path_ + ": no variable " + name);
        return it->second;
    }

private:
    std::string path_;
    std::map<std::string, double> values_;
};

struct TypePairs {
    std::array<ContactParameters, kTypes * kTypes> p;  // row by row
    std::array<double, kTypes> mass;                   // per type [kg]; 0: a wall
    const ContactParameters& operator()(int i, int j) const { return p[i * kTypes + j]; }
};

double beadMass(const Materials& m)
{
    return sphereMass(m["bead_d"], m["bead_rho"]);
}

// Table 3.1 with the thesis conventions, or en = et = `uniform` everywhere.
TypePairs typePairs(const Materials& m, std::optional<double> uniform)
{
    const ContactParameters bead{m["bead_tc"], m["bead_en"], m["bead_et"], m["bead_mu"]};
    const ContactParameters drum{m["drum_tc"], m["drum_en"], m["drum_et"], m["drum_mu"]};
    TypePairs t;
    for (int i = 0; i < kTypes; ++i)
        for (int j = 0; j < kTypes; ++j) {
            ContactParameters p = (i == 0 && j == 0) ? bead : drum;
            if (uniform) p = {bead.tc, *uniform, *uniform, p.mu};
            t.p[i * kTypes + j] = p;
        }
    t.mass = {beadMass(m), 0.0};
    return t;
}

// The laws whose coefficients a contact under way applies.
enum class Law { nominal, exactRestitution, exactCollision };

Law parseLaw(const std::string& s)
{
    if (s == "nominal") return Law::nominal;
    if (s == "exactRestitution") return Law::exactRestitution;
    if (s == "exactCollision") return Law::exactCollision;
    throw std::runtime_error("--law must be nominal, exactRestitution or exactCollision, not '" + s + "'");
}

// What `law` applies for type pair p at dt, per unit meff; nullopt where the
// law has no solution (`why` says why).
std::optional<UnitCoefficients> applied(const ContactParameters& p, Law law, double dt, bool limitForce,
                                        std::string* why = nullptr)
{
    if (law == Law::nominal) return pourninUnitCoefficients(p);
    if (law == Law::exactRestitution) {
        const ExactSolution s = exactUnitCoefficients(p, dt, limitForce);
        if (s.ok()) return s.unit;
        if (why) *why = failureText(s);
        return std::nullopt;
    }
    const auto osc = exactCollisionOscillators(p, limitForce);
    if (!osc) {
        if (why) *why = "exactCollision with limitForce: en below the cut law's reach";
        return std::nullopt;
    }
    return appliedCoefficients(stepLaw(osc->normal.k, osc->normal.c, dt, limitForce),
                               stepLaw(osc->tangential.k, osc->tangential.c, dt, false));
}

int stock(const Materials& m, std::optional<double> uniform, Law law, double dt, bool limitForce)
{
    const TypePairs t = typePairs(m, uniform);
    std::array<Coefficients, kTypes * kTypes> c;
    for (int i = 0; i < kTypes; ++i)
        for (int j = 0; j < kTypes; ++j) {
            std::string why;
            const std::optional<UnitCoefficients> u = applied(t(i, j), law, dt, limitForce, &why);
            if (!u) {
                std::fprintf(stderr, "contact_law: type pair (%d,%d): %s\n", i + 1, j + 1, why.c_str());
                return 1;
            }
            c[i * kTypes + j] = scaled(*u, effectiveMass(t.mass[i], t.mass[j]));
        }
    auto print = [&](const char* name, double Coefficients::*field) {
        std::printf("fix %s all property/global %s peratomtypepair %d", name, name, kTypes);
        for (const Coefficients& k : c) std::printf(" %.17g", k.*field);
        std::printf("\n");
    };
    print("kn", &Coefficients::kn);
    print("kt", &Coefficients::kt);
    print("gamman_abs", &Coefficients::cn);
    print("gammat_abs", &Coefficients::ct);
    return 0;
}

int limit(double tc, double en, double et, std::optional<double> at, Law law)
{
    const ContactParameters p{tc, en, et, 0.0};
    const double binary = criticalTimestep(p);
    double guard = stableTimestep(p);
    if (law != Law::nominal) {
        // the largest dt the guard admits on the coefficients applied at that dt
        const auto admits = [&](double dt) {
            const auto u = applied(p, law, dt, false);  // past a law's reach: not admitted
            return u && dt <= stableTimestep(*u);
        };
        double lo = 0.01 * tc, hi = binary;
        if (!admits(lo)) throw std::runtime_error("the guard admits no timestep down to tc/100");
        while (admits(hi)) hi *= 2.0;
        for (int k = 0; k < 60; ++k) (admits(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
        guard = lo;
    }
    std::printf("tc_s,en,et,binary_limit_s,guard_s,binary_limit_tc,guard_tc%s\n", at ? ",at_tc,stiffening_at" : "");
    std::printf("%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g", tc, en, et, binary, guard, binary / tc, guard / tc);
    if (at) {
        const auto u = applied(p, law, *at * tc, false);
        std::printf(",%.17g,%.17g", *at, u ? stiffeningAt(*u, *at * tc) : NAN);
    }
    std::printf("\n");
    return 0;
}

int coefficients(const Materials& m, std::optional<double> meff)
{
    const TypePairs t = typePairs(m, std::nullopt);
    std::printf("i,j,tc_s,en,et,mu,%s\n", meff ? "kn_N_m,cn_N_s_m,kt_N_m,ct_N_s_m"
                                             : "kn_per_meff_1_s2,cn_per_meff_1_s,kt_per_meff_1_s2,ct_per_meff_1_s");
    for (int i = 0; i < kTypes; ++i)
        for (int j = i; j < kTypes; ++j) {
            const ContactParameters& p = t(i, j);
            const Coefficients c = scaled(pourninUnitCoefficients(p), meff ? *meff : 1.0);
            std::printf("%d,%d,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g\n", i + 1, j + 1, p.tc, p.en, p.et,
                        p.mu, c.kn, c.cn, c.kt, c.ct);
        }
    return 0;
}

// One mode's errors over the phases: worst |e/en - 1| and mean (e/en - 1).
struct PhaseErrors {
    double worstEn = 0, meanEn = 0, worstEt = 0, meanEt = 0;
    void add(double en, double et, const ContactParameters& p, int n)
    {
        const double a = en / p.en - 1.0, b = et / p.et - 1.0;
        worstEn = std::max(worstEn, std::fabs(a)), meanEn += a / n;
        worstEt = std::max(worstEt, std::fabs(b)), meanEt += b / n;
    }
};

int single(const ContactParameters& p, bool limitForce, const std::vector<double>& ratios, int phases)
{
    std::printf("tc_over_dt,mode,worst_en_err,mean_en_err,worst_et_err,mean_et_err\n");
    const auto osc = exactCollisionOscillators(p, limitForce);
    for (double ratio : ratios) {
        const double dt = p.tc / ratio;
        const ExactSolution exact = exactUnitCoefficients(p, dt, limitForce);
        std::map<std::string, PhaseErrors> e;
        for (int k = 0; k < phases; ++k) {
            const double phase = (k + 0.5) / phases;
            const DiscreteCollision n =
                discreteCollisionAtPhase(pourninUnitCoefficients(p), dt, limitForce, phase).outcome;
            e["nominal"].add(n.restitution, n.tangentialRestitution, p, phases);
            if (exact.ok()) {
                const DiscreteCollision x = discreteCollisionAtPhase(exact.unit, dt, limitForce, phase).outcome;
                e["exactRestitution"].add(x.restitution, x.tangentialRestitution, p, phases);
            }
            if (osc) {
                const SteppedCollision c = exactCollisionAtPhase(stepLaw(osc->normal.k, osc->normal.c, dt, limitForce),
                                                                 stepLaw(osc->tangential.k, osc->tangential.c, dt, false),
                                                                 phase);
                e["exactCollision"].add(c.restitution, c.tangentialRestitution, p, phases);
            }
        }
        for (const auto& [mode, x] : e)
            std::printf("%.6g,%s,%.6e,%.6e,%.6e,%.6e\n", ratio, mode.c_str(), x.worstEn, x.meanEn, x.worstEt, x.meanEt);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{"Numbers of the viscoelastic contact law (Pournin coefficients, Table 3.1)"};
    app.require_subcommand(1);
    std::string path = "inputs/materials.in";
    auto addMaterials = [&](CLI::App* sub) {
        sub->add_option("--materials", path, "LIGGGHTS file of `variable NAME equal VALUE` lines")
            ->capture_default_str();
    };

    CLI::App* stockCmd = app.add_subcommand("stock", "stock hooke/stiffness properties with our constants");
    addMaterials(stockCmd);
    double uniform = 0.0, dt = 0.0;
    bool exact = false, limitForce = false;
    CLI::Option* uniformOpt =
        stockCmd->add_option("--uniform", uniform, "en = et = EN for every type pair")->check(CLI::Range(1e-300, 1.0));
    CLI::Option* dtOpt = stockCmd->add_option("--dt", dt, "timestep [s]")->check(CLI::PositiveNumber);
    std::string stockLaw = "nominal";
    CLI::Option* exactOpt = stockCmd->add_flag("--exact", exact, "the exactRestitution coefficients (--law exactRestitution)")
                                ->needs(dtOpt);
    stockCmd->add_option("--law", stockLaw, "nominal, exactRestitution or exactCollision "
                                                                  "(its step law: a contact under way)")
                              ->needs(dtOpt)->excludes(exactOpt)->capture_default_str();
    stockCmd->add_flag("--limit-force", limitForce, "limitForce on")->needs(dtOpt);

    CLI::App* limitCmd = app.add_subcommand("limit", "binary stability limit and guard, CSV");
    addMaterials(limitCmd);
    double en = 0.0, et = 0.0, tc = 0.0;
    limitCmd->add_option("--en", en, "normal restitution")->required()->check(CLI::Range(1e-300, 1.0));
    CLI::Option* etOpt = limitCmd->add_option("--et", et, "tangential restitution (default: en)")
                             ->check(CLI::Range(1e-300, 1.0));
    CLI::Option* tcOpt = limitCmd->add_option("--tc", tc, "contact duration [s] (default: bead_tc)")
                             ->check(CLI::PositiveNumber);
    double at = 0.0;
    CLI::Option* atOpt = limitCmd->add_option("--at", at,
                                              "dt/tc: also the stiffening Z at which the guard's form gives it")
                             ->check(CLI::PositiveNumber);
    std::string limitLaw = "nominal";
    limitCmd->add_option("--law", limitLaw, "the coefficients applied: nominal, exactRestitution or exactCollision")
        ->capture_default_str();

    CLI::App* massCmd = app.add_subcommand("bead-mass", "mass of one bead [kg]");
    addMaterials(massCmd);

    CLI::App* coeffCmd = app.add_subcommand("coefficients", "kn, cn, kt, ct per type pair, CSV");
    addMaterials(coeffCmd);
    double meff = 0.0;
    CLI::Option* meffOpt = coeffCmd->add_option("--meff", meff, "effective mass [kg]: absolute constants")
                               ->check(CLI::PositiveNumber);

    CLI::App* singleCmd = app.add_subcommand("single", "single-collision errors over start phases, CSV");
    addMaterials(singleCmd);
    double sEn = 0.0, sEt = 0.0, sTc = 0.0;
    bool sLimit = false;
    std::vector<double> ratios{4, 5, 7.3, 10, 15, 20, 30, 50, 81, 100};
    int phases = 256;
    singleCmd->add_option("--en", sEn, "normal restitution")->required()->check(CLI::Range(1e-300, 1.0));
    CLI::Option* sEtOpt = singleCmd->add_option("--et", sEt, "tangential restitution (default: en)")
                              ->check(CLI::Range(1e-300, 1.0));
    CLI::Option* sTcOpt = singleCmd->add_option("--tc", sTc, "contact duration [s] (default: bead_tc)")
                              ->check(CLI::PositiveNumber);
    singleCmd->add_flag("--limit-force", sLimit, "limitForce on");
    singleCmd->add_option("--ratios", ratios, "tc/dt values")->delimiter(',')->capture_default_str();
    singleCmd->add_option("--phases", phases, "start phases (k + 0.5) / N")->check(CLI::PositiveNumber)
        ->capture_default_str();

    CLI11_PARSE(app, argc, argv);
    try {
        if (*stockCmd)
            return stock(Materials(path), *uniformOpt ? std::optional<double>(uniform) : std::nullopt,
                         exact ? Law::exactRestitution : parseLaw(stockLaw), dt, limitForce);
        if (*limitCmd)
            return limit(*tcOpt ? tc : Materials(path)["bead_tc"], en, *etOpt ? et : en,
                         *atOpt ? std::optional<double>(at) : std::nullopt, parseLaw(limitLaw));
        if (*singleCmd)
            return single({*sTcOpt ? sTc : Materials(path)["bead_tc"], sEn, *sEtOpt ? sEt : sEn, 0.0}, sLimit, ratios,
                          phases);
        if (*massCmd) {
            std::printf("%.17g\n", beadMass(Materials(path)));
            return 0;
        }
        return coefficients(Materials(path), *meffOpt ? std::optional<double>(meff) : std::nullopt);
    } catch (const std::runtime_error& e) {
        std::fprintf(stderr, "contact_law: %s\n", e.what());
        return 2;
    }
}
