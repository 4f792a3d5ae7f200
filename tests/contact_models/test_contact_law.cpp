// The contact_law tool, run as scripts run it, against the physics core
// called here directly, and its calculator against values derived by hand;
// its command line (--version, usage errors, where the materials file is
// found).
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "core/viscoelastic.h"

using namespace viscoelastic;
namespace fs = std::filesystem;

namespace {

// Table 3.1, written here so the test does not depend on the repository's file.
const char* kMaterials = "# Table 3.1\n"
                         "variable bead_tc equal 1e-4  # [s]\n"
                         "variable bead_en equal 0.56\n"
                         "variable bead_et equal 0.46\n"
                         "variable bead_mu equal 0.5\n"
                         "\n"
                         "variable drum_tc equal 1e-4\n"
                         "variable drum_en equal 0.46\n"
                         "variable drum_et equal 0.46\n"
                         "variable drum_mu equal 0.95\n"
                         "variable bead_d equal 0.003\n"
                         "variable bead_rho equal 2500\n";
const ContactParameters kBead{1e-4, 0.56, 0.46, 0.5}, kDrum{1e-4, 0.46, 0.46, 0.95};

struct Output {
    std::string out;
    int status;
};

// Runs contact_law in `dir` (with `env`, e.g. "NAME=value"); stdout and
// stderr, and the exit status.
Output run(const std::string& args, const fs::path& dir, const std::string& env = "")
{
    const std::string cmd = "cd '" + dir.string() + "' && " + env + " '" CONTACT_LAW "' " + args + " 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    std::string out;
    char buf[4096];
    for (size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
    const int status = pclose(p);
    return {out, WIFEXITED(status) ? WEXITSTATUS(status) : -1};
}

class ContactLaw : public ::testing::Test {
protected:
    void SetUp() override
    {
        dir = fs::temp_directory_path() / ("contact_law_" + std::to_string(::getpid()));
        fs::create_directories(dir / "inputs");
        std::ofstream(dir / "inputs/materials.in") << kMaterials;
    }
    void TearDown() override { fs::remove_all(dir); }

    Output run(const std::string& args, const std::string& env = "") const { return ::run(args, dir, env); }
    fs::path dir;
};

double beadMass() { return 4.0 / 3.0 * kPi * std::pow(1.5e-3, 3) * 2500.0; }

std::vector<std::string> lines(const std::string& text)
{
    std::vector<std::string> v;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) v.push_back(l);
    return v;
}

std::vector<double> numbers(const std::string& text, char separator)
{
    std::vector<double> v;
    std::istringstream in(text);
    for (std::string field; std::getline(in, field, separator);) v.push_back(std::stod(field));
    return v;
}

// The four `fix property/global` lines: name -> the 2x2 matrix.
void expectStock(const std::string& out, const UnitCoefficients (&unit)[4])
{
    const double m = beadMass();
    const double meff[4] = {m / 2, m, m, 0.0};  // bead-bead, bead-drum (a wall), drum-drum
    const std::vector<std::string> l = lines(out);
    ASSERT_EQ(l.size(), 4u) << out;
    const char* names[4] = {"kn", "kt", "gamman_abs", "gammat_abs"};
    for (int k = 0; k < 4; ++k) {
        const std::string head = std::string("fix ") + names[k] + " all property/global " + names[k] +
                                 " peratomtypepair 2 ";
        ASSERT_EQ(l[k].rfind(head, 0), 0u) << l[k];
        const std::vector<double> v = numbers(l[k].substr(head.size()), ' ');
        ASSERT_EQ(v.size(), 4u) << l[k];
        for (int p = 0; p < 4; ++p) {
            const Coefficients c = scaled(unit[p], meff[p]);
            const double expected[4] = {c.kn, c.kt, c.cn, c.ct};
            EXPECT_DOUBLE_EQ(v[p], expected[k]) << names[k] << " pair " << p;
        }
    }
}

}  // namespace

TEST_F(ContactLaw, StockIsTheCoreConstantsWithTheThesisConventions)
{
    const Output o = run("stock");
    ASSERT_EQ(o.status, 0) << o.out;
    const UnitCoefficients bead = pourninUnitCoefficients(kBead), drum = pourninUnitCoefficients(kDrum);
    expectStock(o.out, {bead, drum, drum, drum});
}

TEST_F(ContactLaw, StockUniformSetsEnAndEtOfEveryPair)
{
    const Output o = run("stock --uniform 0.3 --materials inputs/materials.in");
    ASSERT_EQ(o.status, 0) << o.out;
    const UnitCoefficients u = pourninUnitCoefficients(1e-4, 0.3, 0.3);
    expectStock(o.out, {u, u, u, u});
}

TEST_F(ContactLaw, StockExactUsesTheExactRestitutionCoefficients)
{
    const Output o = run("stock --exact --dt 1e-5 --limit-force");
    ASSERT_EQ(o.status, 0) << o.out;
    const UnitCoefficients bead = exactUnitCoefficients(kBead, 1e-5, true).unit;
    const UnitCoefficients drum = exactUnitCoefficients(kDrum, 1e-5, true).unit;
    expectStock(o.out, {bead, drum, drum, drum});
}

TEST_F(ContactLaw, StockExactStopsOnAnUnreachableRequest)
{
    const Output o = run("stock --uniform 0.1 --exact --dt 1e-5 --limit-force");
    EXPECT_NE(o.status, 0);
    EXPECT_NE(o.out.find("contact_law: type pair (1,1): no normal coefficients reach en 0.1"), std::string::npos)
        << o.out;
}

TEST_F(ContactLaw, LimitIsTheBinaryJuryLimitAndTheGuard)
{
    const Output o = run("limit --en 0.56 --et 0.46");
    ASSERT_EQ(o.status, 0) << o.out;
    const std::vector<std::string> l = lines(o.out);
    ASSERT_EQ(l.size(), 2u) << o.out;
    EXPECT_EQ(l[0], "tc_s,en,et,binary_limit_s,guard_s,binary_limit_tc,guard_tc");
    const std::vector<double> v = numbers(l[1], ',');
    ASSERT_EQ(v.size(), 7u);
    const double binary = criticalTimestep(kBead);
    const double guard = stableTimestep(kBead);
    const double expected[7] = {1e-4, 0.56, 0.46, binary, guard, binary / 1e-4, guard / 1e-4};
    for (int k = 0; k < 7; ++k) EXPECT_NEAR(v[k], expected[k], 1e-11 * expected[k]) << k;

    // et defaults to en, tc to bead_tc unless given
    const std::vector<double> w = numbers(lines(run("limit --en 0.9 --tc 2e-4").out).at(1), ',');
    EXPECT_EQ(w[2], 0.9);
    EXPECT_NEAR(w[3], criticalTimestep(2e-4, 0.9), 1e-11 * w[3]);

    // --at: the stiffening Z whose guard form gives that dt. At the guard's
    // own dt it is the guard's factor; at another dt the binary (Jury) limit
    // of the stiffer oscillator scaled by Z is that dt.
    const Output a = run("limit --en 0.56 --et 0.46 --at " + std::to_string(guard / 1e-4));
    ASSERT_EQ(a.status, 0) << a.out;
    EXPECT_EQ(lines(a.out).at(0), "tc_s,en,et,binary_limit_s,guard_s,binary_limit_tc,guard_tc,at_tc,stiffening_at");
    EXPECT_NEAR(numbers(lines(a.out).at(1), ',').at(8), kCoordinationFactor, 1e-5);
    const std::vector<double> z = numbers(lines(run("limit --en 0.3 --at 0.2").out).at(1), ',');
    const UnitCoefficients u = pourninUnitCoefficients(1e-4, 0.3, 0.3);
    EXPECT_NEAR(criticalTimestepOf(z.at(8) * u.kn, z.at(8) * u.cn), 0.2e-4, 1e-9 * 0.2e-4);
}

TEST_F(ContactLaw, StockLawExactCollisionIsItsStepLaw)
{
    // the force of a contact under way: the step laws' kStep, cStep
    // (tangential per unit m_t = 2/7 meff), which depend on dt
    const Output o = run("stock --law exactCollision --dt 2e-5");
    ASSERT_EQ(o.status, 0) << o.out;
    const auto applied = [](const ContactParameters& p) {
        const auto osc = exactCollisionOscillators(p, false);
        return appliedCoefficients(stepLaw(osc->normal.k, osc->normal.c, 2e-5, false),
                                   stepLaw(osc->tangential.k, osc->tangential.c, 2e-5, false));
    };
    const UnitCoefficients bead = applied(kBead), drum = applied(kDrum);
    expectStock(o.out, {bead, drum, drum, drum});
    // softer than Pournin's (the undamped step law: (2 sin(w dt / 2) / dt)^2 < w^2)
    EXPECT_LT(bead.kn, pourninUnitCoefficients(kBead).kn);
    const Output same = run("stock --law exactRestitution --dt 1e-5 --limit-force");
    EXPECT_EQ(same.out, run("stock --exact --dt 1e-5 --limit-force").out);
}

TEST_F(ContactLaw, LimitOfAnExactLawIsTheGuardOnItsOwnCoefficients)
{
    // The applied coefficients depend on dt: the guard is the dt at which the
    // guard of those coefficients is dt itself; just below it admits, just
    // above not. Z at the guard is the guard's factor.
    for (const char* law : {"exactRestitution", "exactCollision"}) {
        const Output o = run(std::string("limit --en 0.3 --law ") + law);
        ASSERT_EQ(o.status, 0) << o.out;
        const double guard = numbers(lines(o.out).at(1), ',').at(4);
        const auto stable = [&](double dt) {
            if (std::string(law) == "exactRestitution") return stableTimestep(exactUnitCoefficients({1e-4, 0.3, 0.3, 0}, dt, false).unit);
            const auto osc = exactCollisionOscillators({1e-4, 0.3, 0.3, 0}, false);
            return stableTimestep(appliedCoefficients(stepLaw(osc->normal.k, osc->normal.c, dt, false),
                                                      stepLaw(osc->tangential.k, osc->tangential.c, dt, false)));
        };
        EXPECT_LE(0.999 * guard, stable(0.999 * guard)) << law;
        EXPECT_GT(1.001 * guard, stable(1.001 * guard)) << law;
        // softer coefficients: a larger guard than the nominal law's
        EXPECT_GT(guard, stableTimestep(ContactParameters{1e-4, 0.3, 0.3, 0})) << law;
        const Output z = run(std::string("limit --en 0.3 --law ") + law + " --at " + std::to_string(guard / 1e-4));
        EXPECT_NEAR(numbers(lines(z.out).at(1), ',').at(8), kCoordinationFactor, 1e-4) << law;
    }
    const Output bad = run("limit --en 0.3 --law exact");
    EXPECT_EQ(bad.status, 2);
    EXPECT_NE(bad.out.find("--law: must be nominal, exactRestitution or exactCollision, not 'exact'"),
              std::string::npos)
        << bad.out;
}

TEST_F(ContactLaw, BeadMassHasSeventeenDigits)
{
    const Output o = run("bead-mass");
    ASSERT_EQ(o.status, 0) << o.out;
    EXPECT_EQ(std::stod(o.out), beadMass());
}

TEST_F(ContactLaw, CoefficientsPerTypePairForTheirMassAndPerUnitMass)
{
    const double m = beadMass();
    for (const double given : {0.0, 1.767e-5}) {
        const Output o = run(given == 0.0 ? "coefficients" : "coefficients --meff 1.767e-5");
        ASSERT_EQ(o.status, 0) << o.out;
        const std::vector<std::string> l = lines(o.out);
        ASSERT_EQ(l.size(), 4u) << o.out;
        EXPECT_EQ(l[0], "i,j,tc_s,en,et,mu,meff_kg,kn_N_m,cn_N_s_m,kt_N_m,ct_N_s_m,kn_per_meff_1_s2,cn_per_meff_1_s,"
                        "kt_per_meff_1_s2,ct_per_meff_1_s,guard_s");
        const ContactParameters pairs[3] = {kBead, kDrum, kDrum};
        const double meff[3] = {m / 2, m, 0.0};  // bead-bead, bead-drum (a wall), drum-drum
        for (int r = 0; r < 3; ++r) {
            const std::vector<double> v = numbers(l[r + 1], ',');
            ASSERT_EQ(v.size(), 16u) << l[r + 1];
            const UnitCoefficients u = pourninUnitCoefficients(pairs[r]);
            const double mass = given > 0 ? given : meff[r];
            const Coefficients c = scaled(u, mass);
            const double expected[14] = {pairs[r].tc, pairs[r].en, pairs[r].et, pairs[r].mu, mass,
                                         c.kn,        c.cn,        c.kt,        c.ct,        u.kn,
                                         u.cn,        u.kt,        u.ct,        stableTimestep(pairs[r])};
            for (int k = 0; k < 14; ++k)
                EXPECT_NEAR(v[k + 2], expected[k], 1e-11 * std::fabs(expected[k])) << l[r + 1] << " column " << k + 2;
        }
    }
}

// The calculator for one type of beads, all given (no materials file needed):
// Table 3.1's glass beads, tc 1e-4 s, en 0.56, et 0.46, mu 0.5, d 3 mm, rho
// 2500 kg/m^3, checked against values derived by hand (python3, doubles):
//   m    = pi/6 d^3 rho = 3.534291735288517e-05 kg; bead-bead meff = m/2 = 1.7671458676442585e-05 kg
//   ln en = -0.579818495252942, ln et = -0.7765287894989963
//   kn/meff = (pi^2 + ln^2 en)/tc^2      = 1020579388.8526744 1/s^2  -> kn = 18035.126496139063 N/m
//   cn/meff = -2 ln(en)/tc               = 11596.36990505884 1/s     -> cn = 0.20492477157398972 N s/m
//   kt/meff = 2/7 (pi^2 + ln^2 et)/tc^2  = 299217181.7717181 1/s^2   -> kt = 5287.604062960526 N/m
//   ct/meff = 2/7 (-2 ln(et)/tc)         = 4437.307368565693 1/s     -> ct = 0.07841369379828284 N s/m
//     (tangential per unit m_t = 2/7 meff: solid spheres)
//   guard: the binary (Jury) limit dt = 2 (sqrt(b^2 + k) - b)/k of each oscillator per unit of its mass
//     made Z = 3.5 times stiffer and more damped (k = Z (pi^2 + ln^2 e)/tc^2, b = Z (-ln e)/tc):
//     normal 2.3977516706987473e-05 s, tangential 2.1380824149789207e-05 s; the guard is the smaller,
//     2.1380824149789207e-05 s = tc/4.677
TEST_F(ContactLaw, CalculatorGivesTheHandDerivedValuesForTableThreeOneBeads)
{
    fs::remove_all(dir / "inputs");  // with every value given, no materials file is needed
    const Output o = run("coefficients --tc 1e-4 --en 0.56 --et 0.46 --mu 0.5 --d 0.003 --rho 2500",
                         "LIGGGHTS_VISCOELASTIC_DATADIR=/nonexistent");
    ASSERT_EQ(o.status, 0) << o.out;
    const std::vector<std::string> l = lines(o.out);
    ASSERT_EQ(l.size(), 2u) << o.out;
    const std::vector<double> v = numbers(l[1], ',');
    const double expected[16] = {1, 1, 1e-4, 0.56, 0.46, 0.5, 1.7671458676442585e-05,
                                 18035.126496139063, 0.20492477157398972, 5287.604062960526, 0.07841369379828284,
                                 1020579388.8526744, 11596.36990505884, 299217181.7717181, 4437.307368565693,
                                 2.1380824149789207e-05};
    ASSERT_EQ(v.size(), 16u) << l[1];
    for (int k = 0; k < 16; ++k) EXPECT_NEAR(v[k], expected[k], 1e-9 * expected[k]) << "column " << k;

    // the same request as LIGGGHTS input lines, and the run's guard
    const Output fix = run("coefficients --tc 1e-4 --en 0.56 --et 0.46 --mu 0.5 --d 0.003 --rho 2500 --fix");
    ASSERT_EQ(fix.status, 0) << fix.out;
    EXPECT_EQ(fix.out, "# model viscoelastic; type 1: beads of 0.003 m, 2500 kg/m^3\n"
                       "fix m1 all property/global contactDuration                  peratomtypepair 1 0.0001\n"
                       "fix m2 all property/global coefficientRestitution           peratomtypepair 1 0.56\n"
                       "fix m3 all property/global coefficientRestitutionTangential peratomtypepair 1 0.46\n"
                       "fix m4 all property/global coefficientFriction              peratomtypepair 1 0.5\n"
                       "# the model's timestep guard: timestep <= 2.13808e-05 s (tc/4.677, type pair (1,1))\n");
}

// Values not given come from the materials file's bead_*; a table gives any
// number of types, walls among them, and every pair's request.
TEST_F(ContactLaw, CalculatorTakesTheFileForWhatIsNotGivenOrATable)
{
    const Output some = run("coefficients --en 0.9");
    ASSERT_EQ(some.status, 0) << some.out;
    EXPECT_EQ(some.out, run("coefficients --tc 1e-4 --en 0.9 --et 0.46 --mu 0.5 --d 0.003 --rho 2500").out);

    std::ofstream(dir / "pairs.txt") << "# beads, larger beads, the drum\n"
                                        "type 1 0.003 2500\ntype 2 0.006 2500\ntype 3 wall\n"
                                        "pair 1 1 1e-4 0.56 0.46 0.5\npair 2 1 1e-4 0.5 0.4 0.3  # either order\n"
                                        "pair 2 2 2e-4 0.6 0.5 0.4\npair 1 3 1e-4 0.46 0.46 0.95\n"
                                        "pair 2 3 1e-4 0.46 0.46 0.95\npair 3 3 1e-4 0.46 0.46 0.95\n";
    const Output t = run("coefficients --table pairs.txt");
    ASSERT_EQ(t.status, 0) << t.out;
    const std::vector<std::string> l = lines(t.out);
    ASSERT_EQ(l.size(), 7u) << t.out;  // pairs (1,1) (1,2) (1,3) (2,2) (2,3) (3,3)
    const double m1 = beadMass(), m2 = 8 * m1, m12 = m1 * m2 / (m1 + m2);
    const double kn12 = m12 * pourninUnitCoefficients(1e-4, 0.5, 0.4).kn;
    EXPECT_NEAR(numbers(l[2], ',').at(6), m12, 1e-11 * m12) << l[2];
    EXPECT_NEAR(numbers(l[2], ',').at(7), kn12, 1e-11 * kn12) << l[2];
    EXPECT_NEAR(numbers(l[5], ',').at(6), m2, 1e-11 * m2) << l[5];  // bead-wall: the bead's mass
    const Output f = run("coefficients --table pairs.txt --fix");
    EXPECT_NE(f.out.find("coefficientRestitution           peratomtypepair 3 0.56 0.5 0.46 0.5 0.6 0.46 0.46 0.46 "
                         "0.46\n"),
              std::string::npos)
        << f.out;

    std::ofstream(dir / "short.txt") << "type 1 0.003 2500\ntype 2 wall\npair 1 1 1e-4 0.56 0.46 0.5\n";
    const Output missing = run("coefficients --table short.txt");
    EXPECT_EQ(missing.status, 1);
    EXPECT_NE(missing.out.find("short.txt: no `pair 1 2 ...` line"), std::string::npos) << missing.out;
    std::ofstream(dir / "bad.txt") << "type 1 0.003 2500\npair 1 1 1e-4 0.56 1.2 0.5\n";
    const Output bad = run("coefficients --table bad.txt");
    EXPECT_EQ(bad.status, 1);
    EXPECT_NE(bad.out.find("bad.txt:2: et must be in (0, 1], not 1.2"), std::string::npos) << bad.out;
}

// en, et in (0, 1], tc > 0, mu >= 0: a value outside is a usage error naming it.
TEST_F(ContactLaw, CalculatorChecksTheRangeOfEachParameter)
{
    const std::pair<const char*, const char*> bad[] = {{"--en 0", "--en: must be in (0, 1], not 0"},
                                                       {"--en 1.5", "--en: must be in (0, 1], not 1.5"},
                                                       {"--et -0.1", "--et: must be in (0, 1], not -0.1"},
                                                       {"--tc 0", "--tc: must be > 0, not 0"},
                                                       {"--mu -1", "--mu: must be >= 0, not -1"},
                                                       {"--d 0", "--d: must be > 0, not 0"},
                                                       {"--rho x", "--rho: must be a number, not 'x'"}};
    for (const auto& [args, message] : bad) {
        const Output o = run(std::string("coefficients ") + args);
        EXPECT_EQ(o.status, 2) << args;
        EXPECT_EQ(o.out, std::string("contact_law: ") + message + "; see contact_law --help\n") << args;
    }
    EXPECT_EQ(run("coefficients --en 1 --et 1 --mu 0").status, 0);  // the bounds that belong to the range
}

TEST_F(ContactLaw, VersionAndHelpExitZero)
{
    const Output v = run("--version");
    EXPECT_EQ(v.status, 0);
    EXPECT_EQ(v.out, "contact_law " TOOLS_VERSION "\n");
    const Output h = run("coefficients --help");
    EXPECT_EQ(h.status, 0);
    EXPECT_NE(h.out.find("--table"), std::string::npos) << h.out;
}

// A usage error: exit code 2 and one line; an error of the work (a file
// named that cannot be read): exit code 1.
TEST_F(ContactLaw, UsageErrorsAreOneLineWithExitCodeTwo)
{
    const std::regex oneLine("contact_law: [^\n]+; see contact_law --help\n");
    for (const char* args : {"", "bogus", "limit --en 0.5 --frobnicate", "limit", "limit --en half",
                             "stock --law exact --dt 1e-5", "single --en 0.5 --phases 0"}) {
        const Output o = run(args);
        EXPECT_EQ(o.status, 2) << args << ": " << o.out;
        EXPECT_TRUE(std::regex_match(o.out, oneLine)) << args << ": " << o.out;
    }
    const Output missing = run("bead-mass --materials nope.in");
    EXPECT_EQ(missing.status, 1);
    EXPECT_EQ(missing.out, "contact_law: nope.in: cannot open the materials file\n");
}

// Without inputs/materials.in in the working directory, the installed copy
// ($LIGGGHTS_VISCOELASTIC_DATADIR stands in for the install here); without
// either, an error naming both places.
TEST_F(ContactLaw, MaterialsFallBackToTheInstalledCopy)
{
    fs::remove_all(dir / "inputs");
    const Output o = run("bead-mass", "LIGGGHTS_VISCOELASTIC_DATADIR='" SOURCE_DIR "/inputs'");
    ASSERT_EQ(o.status, 0) << o.out;
    EXPECT_EQ(std::stod(o.out), beadMass());
    const Output none = run("bead-mass", "LIGGGHTS_VISCOELASTIC_DATADIR=/nonexistent");
    EXPECT_EQ(none.status, 1);
    EXPECT_NE(none.out.find("inputs/materials.in (in the working directory)"), std::string::npos) << none.out;
    EXPECT_NE(none.out.find("/nonexistent/materials.in (installed)"), std::string::npos) << none.out;
}

TEST_F(ContactLaw, BadMaterialsFileStopsNamingTheLine)
{
    std::ofstream(dir / "bad.in") << "variable bead_tc equal 1e-4\nvariable bead_en equal oops\n";
    const Output o = run("stock --materials bad.in");
    EXPECT_EQ(o.status, 1);
    EXPECT_NE(o.out.find("bad.in:2:"), std::string::npos) << o.out;
}
