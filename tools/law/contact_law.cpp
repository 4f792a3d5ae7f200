// contact_law: every number of the contact law a script needs, from the core
// (so no script re-derives physics) and from a materials file (default:
// inputs/materials.in, Table 3.1; see materials.h for where it is looked for).
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
//   contact_law coefficients [--materials F | --table T | --tc --en --et --mu --d --rho] [--meff M] [--fix]
//       the calculator, for any materials. CSV per type pair: tc, en, et, mu,
//       the pair's meff, kn, cn, kt, ct for it (or for --meff M) and per unit
//       meff, and the timestep guard of `model viscoelastic`; with --fix
//       instead the `fix property/global` lines that ask LIGGGHTS for those
//       materials, and the run's guard. The type pairs: the materials file's
//       (beads and drum); with any of --tc ... --rho one type of beads (the
//       values not given from the file's bead_*); or a --table file:
//           type I D RHO               (a sphere type: diameter [m], density [kg/m^3])
//           type I wall                (a wall, e.g. the drum: no mass)
//           pair I J TC EN ET MU       (every pair of the types once)
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli.h"        // tools/common: --version, usage errors
#include "core/viscoelastic.h"
#include "materials.h"  // tools/common: the one reader of inputs/materials.in
#include "messages.h"

namespace {

using namespace viscoelastic;

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

using tools::check;
using tools::kNonNegative;
using tools::kPositive;
using tools::kRestitution;

std::string text(double v)
{
    char s[32];
    std::snprintf(s, sizeof s, "%.12g", v);
    return s;
}

// Throws "where: name must be ..., not v" unless v follows the rule.
void require(const tools::Rule& rule, double v, const std::string& name, const std::string& where)
{
    if (!rule.ok(v)) throw std::runtime_error(where + ": " + name + " must be " + rule.what + ", not " + text(v));
}

void requireValid(const ContactParameters& p, const std::string& where)
{
    require(kPositive, p.tc, "tc", where);
    require(kRestitution, p.en, "en", where);
    require(kRestitution, p.et, "et", where);
    require(kNonNegative, p.mu, "mu", where);
}

// N types and every pair of them (symmetric, as LIGGGHTS' peratomtypepair
// matrices are).
struct TypePairs {
    int n = 0;
    std::vector<ContactParameters> p;  // n x n, row by row
    std::vector<double> mass;          // per type [kg]; 0: a wall
    std::vector<std::string> what;     // per type, for the --fix lines' comment
    const ContactParameters& operator()(int i, int j) const { return p[i * n + j]; }
};

double beadMass(const Materials& m)
{
    return sphereMass(m["bead_d"], m["bead_rho"]);
}

std::string sphere(double d, double rho)
{
    return "beads of " + text(d) + " m, " + text(rho) + " kg/m^3";
}

// Table 3.1 with the thesis conventions, or en = et = `uniform` everywhere.
TypePairs typePairs(const Materials& m, std::optional<double> uniform)
{
    const ContactParameters bead{m["bead_tc"], m["bead_en"], m["bead_et"], m["bead_mu"]};
    const ContactParameters drum{m["drum_tc"], m["drum_en"], m["drum_et"], m["drum_mu"]};
    requireValid(bead, "bead_*");
    requireValid(drum, "drum_*");
    TypePairs t;
    t.n = 2;
    for (int i = 0; i < t.n; ++i)
        for (int j = 0; j < t.n; ++j) {
            ContactParameters p = (i == 0 && j == 0) ? bead : drum;
            if (uniform) p = {bead.tc, *uniform, *uniform, p.mu};
            t.p.push_back(p);
        }
    t.mass = {beadMass(m), 0.0};
    t.what = {sphere(m["bead_d"], m["bead_rho"]), "the drum (a wall)"};
    return t;
}

// One type of beads: bead-bead contacts alone.
TypePairs oneType(const ContactParameters& p, double d, double rho)
{
    requireValid(p, "beads");
    require(kPositive, d, "d", "beads");
    require(kPositive, rho, "rho", "beads");
    return {1, {p}, {sphereMass(d, rho)}, {sphere(d, rho)}};
}

// A --table file (see the header): `type` and `pair` lines, `#` comments.
TypePairs readTable(const std::string& path)
{
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open the table");
    std::map<int, std::pair<double, std::string>> types;     // number: mass (0: a wall), what
    std::map<std::pair<int, int>, ContactParameters> pairs;  // (i, j), i <= j
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        const std::string where = path + ":" + std::to_string(number);
        std::istringstream words(line.substr(0, line.find('#')));
        std::vector<std::string> w;
        for (std::string x; words >> x;) w.push_back(x);
        if (w.empty()) continue;
        // words 1 to n as numbers (into v); false unless all of them are
        std::vector<double> v;
        const auto numbers = [&](size_t n) {
            for (size_t k = 1; k <= n; ++k) {
                char* end = nullptr;
                v.push_back(std::strtod(w[k].c_str(), &end));
                if (end == w[k].c_str() || *end != '\0') return false;
            }
            return true;
        };
        const bool wall = w.size() == 3 && w[0] == "type" && w[2] == "wall";
        const bool good = (w[0] == "type" && ((wall && numbers(1)) || (w.size() == 4 && numbers(3)))) ||
                          (w[0] == "pair" && w.size() == 7 && numbers(6));
        const auto integer = [](double x) { return x >= 1 && x == std::floor(x); };
        if (!good || !integer(v[0]) || (w[0] == "pair" && !integer(v[1])))
            throw std::runtime_error(where + ": expected `type I D RHO`, `type I wall` or `pair I J TC EN ET MU` "
                                     "(types numbered from 1), got: " + line);
        const int i = static_cast<int>(v[0]);
        if (w[0] == "type") {
            if (!wall) require(kPositive, v[1], "d", where), require(kPositive, v[2], "rho", where);
            const auto type = wall ? std::make_pair(0.0, std::string("a wall"))
                                   : std::make_pair(sphereMass(v[1], v[2]), sphere(v[1], v[2]));
            if (!types.emplace(i, type).second) throw std::runtime_error(where + ": type " + w[1] + " given twice");
            continue;
        }
        const int j = static_cast<int>(v[1]);
        const ContactParameters p{v[2], v[3], v[4], v[5]};
        requireValid(p, where);
        if (!pairs.emplace(std::minmax(i, j), p).second)
            throw std::runtime_error(where + ": pair " + w[1] + " " + w[2] + " given twice");
    }
    TypePairs t;
    t.n = static_cast<int>(types.size());
    if (t.n == 0) throw std::runtime_error(path + ": no `type` lines");
    for (int i = 1; i <= t.n; ++i) {
        if (!types.count(i))
            throw std::runtime_error(path + ": the types must be numbered 1 to " + std::to_string(t.n) +
                                     ": no type " + std::to_string(i));
        t.mass.push_back(types[i].first);
        t.what.push_back(types[i].second);
    }
    for (const auto& [ij, p] : pairs)
        if (ij.second > t.n) throw std::runtime_error(path + ": pair names type " + std::to_string(ij.second) +
                                                      ", which has no `type` line");
    for (int i = 1; i <= t.n; ++i)
        for (int j = 1; j <= t.n; ++j) {
            const auto it = pairs.find(std::minmax(i, j));
            if (it == pairs.end())
                throw std::runtime_error(path + ": no `pair " + std::to_string(std::min(i, j)) + " " +
                                         std::to_string(std::max(i, j)) + " ...` line");
            t.p.push_back(it->second);
        }
    return t;
}

// The laws whose coefficients a contact under way applies.
enum class Law { nominal, exactRestitution, exactCollision };

Law parseLaw(const std::string& s)
{
    if (s == "exactRestitution") return Law::exactRestitution;
    if (s == "exactCollision") return Law::exactCollision;
    return Law::nominal;  // the option's check admits these three only
}

const CLI::Validator kLawCheck(
    [](std::string& s) -> std::string {
        return s == "nominal" || s == "exactRestitution" || s == "exactCollision"
                   ? ""
                   : "must be nominal, exactRestitution or exactCollision, not '" + s + "'";
    },
    "nominal|exactRestitution|exactCollision");

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

int stock(const TypePairs& t, Law law, double dt, bool limitForce)
{
    std::vector<Coefficients> c;
    for (int i = 0; i < t.n; ++i)
        for (int j = 0; j < t.n; ++j) {
            std::string why;
            const std::optional<UnitCoefficients> u = applied(t(i, j), law, dt, limitForce, &why);
            if (!u) {
                std::fprintf(stderr, "contact_law: type pair (%d,%d): %s\n", i + 1, j + 1, why.c_str());
                return 1;
            }
            c.push_back(scaled(*u, effectiveMass(t.mass[i], t.mass[j])));
        }
    auto print = [&](const char* name, double Coefficients::*field) {
        std::printf("fix %s all property/global %s peratomtypepair %d", name, name, t.n);
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

// The calculator: per type pair i <= j, its request, meff, the constants for
// that meff (or `meff`, if > 0) and per unit meff, and the guard (Pournin's
// coefficients per unit meff depend on tc, en, et alone, so the guard does
// not depend on the masses); or, with `fix`, what to paste into an input.
int coefficients(const TypePairs& t, double meff, bool fix)
{
    if (fix) {
        int gi = 0, gj = 0;
        for (int i = 0; i < t.n; ++i)
            for (int j = i; j < t.n; ++j)
                if (stableTimestep(t(i, j)) < stableTimestep(t(gi, gj))) gi = i, gj = j;
        std::printf("# model viscoelastic");
        for (int i = 0; i < t.n; ++i) std::printf("; type %d: %s", i + 1, t.what[i].c_str());
        std::printf("\n");
        auto print = [&](int id, const char* name, double ContactParameters::*field) {
            std::printf("fix m%d all property/global %-32s peratomtypepair %d", id, name, t.n);
            for (const ContactParameters& p : t.p) std::printf(" %.12g", p.*field);
            std::printf("\n");
        };
        print(1, "contactDuration", &ContactParameters::tc);
        print(2, "coefficientRestitution", &ContactParameters::en);
        print(3, "coefficientRestitutionTangential", &ContactParameters::et);
        print(4, "coefficientFriction", &ContactParameters::mu);
        const double guard = stableTimestep(t(gi, gj));
        std::printf("# the model's timestep guard: timestep <= %.6g s (tc/%.4g, type pair (%d,%d))\n", guard,
                    t(gi, gj).tc / guard, gi + 1, gj + 1);
        return 0;
    }
    std::printf("i,j,tc_s,en,et,mu,meff_kg,kn_N_m,cn_N_s_m,kt_N_m,ct_N_s_m,"
                "kn_per_meff_1_s2,cn_per_meff_1_s,kt_per_meff_1_s2,ct_per_meff_1_s,guard_s\n");
    for (int i = 0; i < t.n; ++i)
        for (int j = i; j < t.n; ++j) {
            const ContactParameters& p = t(i, j);
            const double m = meff > 0 ? meff : effectiveMass(t.mass[i], t.mass[j]);
            const UnitCoefficients u = pourninUnitCoefficients(p);
            const Coefficients c = scaled(u, m);
            std::printf("%d,%d,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g\n",
                        i + 1, j + 1, p.tc, p.en, p.et, p.mu, m, c.kn, c.cn, c.kt, c.ct, u.kn, u.cn, u.kt, u.ct,
                        stableTimestep(p));
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
    std::string path;  // empty: findMaterials' lookup
    auto addMaterials = [&](CLI::App* sub) { sub->add_option("--materials", path, materialsHelp()); };
    const auto materials = [&] { return Materials(findMaterials(path)); };

    CLI::App* stockCmd = app.add_subcommand("stock", "stock hooke/stiffness properties with our constants");
    addMaterials(stockCmd);
    double uniform = 0.0, dt = 0.0;
    bool exact = false, limitForce = false;
    CLI::Option* uniformOpt =
        stockCmd->add_option("--uniform", uniform, "en = et = EN for every type pair")->check(check(kRestitution));
    CLI::Option* dtOpt = stockCmd->add_option("--dt", dt, "timestep [s]")->check(check(kPositive));
    std::string stockLaw = "nominal";
    CLI::Option* exactOpt = stockCmd->add_flag("--exact", exact, "the exactRestitution coefficients (--law exactRestitution)")
                                ->needs(dtOpt);
    stockCmd->add_option("--law", stockLaw, "nominal, exactRestitution or exactCollision "
                                            "(its step law: a contact under way)")
        ->check(kLawCheck)->needs(dtOpt)->excludes(exactOpt)->capture_default_str();
    stockCmd->add_flag("--limit-force", limitForce, "limitForce on")->needs(dtOpt);

    CLI::App* limitCmd = app.add_subcommand("limit", "binary stability limit and guard, CSV");
    addMaterials(limitCmd);
    double en = 0.0, et = 0.0, tc = 0.0;
    limitCmd->add_option("--en", en, "normal restitution")->required()->check(check(kRestitution));
    CLI::Option* etOpt = limitCmd->add_option("--et", et, "tangential restitution (default: en)")
                             ->check(check(kRestitution));
    CLI::Option* tcOpt = limitCmd->add_option("--tc", tc, "contact duration [s] (default: bead_tc)")
                             ->check(check(kPositive));
    double at = 0.0;
    CLI::Option* atOpt = limitCmd->add_option("--at", at,
                                              "dt/tc: also the stiffening Z at which the guard's form gives it")
                             ->check(check(kPositive));
    std::string limitLaw = "nominal";
    limitCmd->add_option("--law", limitLaw, "the coefficients applied: nominal, exactRestitution or exactCollision")
        ->check(kLawCheck)->capture_default_str();

    CLI::App* massCmd = app.add_subcommand("bead-mass", "mass of one bead [kg]");
    addMaterials(massCmd);

    CLI::App* coeffCmd = app.add_subcommand(
        "coefficients", "per type pair kn, cn, kt, ct (for the pair's meff and per unit meff) and the timestep "
                        "guard, CSV; or the `fix property/global` lines (--fix). The pairs: the materials file's, "
                        "one type of beads (any of --tc --en --et --mu --d --rho; the rest from the file's bead_*), "
                        "or --table");
    addMaterials(coeffCmd);
    double meff = 0.0;  // 0: each pair's
    coeffCmd->add_option("--meff", meff, "effective mass [kg] instead of each pair's")->check(check(kPositive));
    ContactParameters bead{};
    double beadD = 0.0, beadRho = 0.0;
    std::string table;
    bool fix = false;
    // an option of the one bead type: its value, or the file's variable
    struct BeadOption {
        CLI::Option* option;
        double* value;
        const char* variable;
    };
    const std::vector<BeadOption> beadOptions{
        {coeffCmd->add_option("--tc", bead.tc, "contact duration [s]")->check(check(kPositive)), &bead.tc, "bead_tc"},
        {coeffCmd->add_option("--en", bead.en, "normal restitution")->check(check(kRestitution)), &bead.en, "bead_en"},
        {coeffCmd->add_option("--et", bead.et, "tangential restitution")->check(check(kRestitution)), &bead.et,
         "bead_et"},
        {coeffCmd->add_option("--mu", bead.mu, "friction coefficient")->check(check(kNonNegative)), &bead.mu,
         "bead_mu"},
        {coeffCmd->add_option("--d", beadD, "bead diameter [m]")->check(check(kPositive)), &beadD, "bead_d"},
        {coeffCmd->add_option("--rho", beadRho, "bead density [kg/m^3]")->check(check(kPositive)), &beadRho,
         "bead_rho"}};
    CLI::Option* tableOpt = coeffCmd->add_option(
        "--table", table, "the types and pairs from this file: `type I D RHO`, `type I wall`, `pair I J TC EN ET MU`");
    for (const BeadOption& b : beadOptions) tableOpt->excludes(b.option);
    coeffCmd->add_flag("--fix", fix, "print the `fix property/global` lines for LIGGGHTS instead of the CSV");

    CLI::App* singleCmd = app.add_subcommand("single", "single-collision errors over start phases, CSV");
    addMaterials(singleCmd);
    double sEn = 0.0, sEt = 0.0, sTc = 0.0;
    bool sLimit = false;
    std::vector<double> ratios{4, 5, 7.3, 10, 15, 20, 30, 50, 81, 100};
    int phases = 256;
    singleCmd->add_option("--en", sEn, "normal restitution")->required()->check(check(kRestitution));
    CLI::Option* sEtOpt = singleCmd->add_option("--et", sEt, "tangential restitution (default: en)")
                              ->check(check(kRestitution));
    CLI::Option* sTcOpt = singleCmd->add_option("--tc", sTc, "contact duration [s] (default: bead_tc)")
                              ->check(check(kPositive));
    singleCmd->add_flag("--limit-force", sLimit, "limitForce on");
    singleCmd->add_option("--ratios", ratios, "tc/dt values")->delimiter(',')->capture_default_str();
    singleCmd->add_option("--phases", phases, "start phases (k + 0.5) / N")->check(check(kPositive))
        ->capture_default_str();

    if (const std::optional<int> done = tools::parse(app, "contact_law", argc, argv)) return *done;
    try {
        if (*stockCmd)
            return stock(typePairs(materials(), *uniformOpt ? std::optional<double>(uniform) : std::nullopt),
                         exact ? Law::exactRestitution : parseLaw(stockLaw), dt, limitForce);
        if (*limitCmd)
            return limit(*tcOpt ? tc : materials()["bead_tc"], en, *etOpt ? et : en,
                         *atOpt ? std::optional<double>(at) : std::nullopt, parseLaw(limitLaw));
        if (*singleCmd)
            return single({*sTcOpt ? sTc : materials()["bead_tc"], sEn, *sEtOpt ? sEt : sEn, 0.0}, sLimit, ratios,
                          phases);
        if (*massCmd) {
            std::printf("%.17g\n", beadMass(materials()));
            return 0;
        }
        if (!table.empty()) return coefficients(readTable(table), meff, fix);
        bool anyGiven = false, allGiven = true;
        for (const BeadOption& b : beadOptions) {
            anyGiven = anyGiven || b.option->count() > 0;
            allGiven = allGiven && b.option->count() > 0;
        }
        if (!anyGiven) return coefficients(typePairs(materials(), std::nullopt), meff, fix);
        if (!allGiven) {  // only then is a materials file needed
            const Materials m = materials();
            for (const BeadOption& b : beadOptions)
                if (!b.option->count()) *b.value = m[b.variable];
        }
        return coefficients(oneType(bead, beadD, beadRho), meff, fix);
    } catch (const std::runtime_error& e) {
        std::fprintf(stderr, "contact_law: %s\n", e.what());
        return 1;
    }
}
