// The contact_law tool, run as scripts run it, against the physics core
// called here directly.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
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

// Runs contact_law in `dir`; stdout and the exit status.
Output run(const std::string& args, const fs::path& dir)
{
    const std::string cmd = "cd '" + dir.string() + "' && '" CONTACT_LAW "' " + args + " 2>&1";
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

    Output run(const std::string& args) const { return ::run(args, dir); }
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
    EXPECT_NE(bad.status, 0);
    EXPECT_NE(bad.out.find("--law must be nominal, exactRestitution or exactCollision, not 'exact'"), std::string::npos)
        << bad.out;
}

TEST_F(ContactLaw, BeadMassHasSeventeenDigits)
{
    const Output o = run("bead-mass");
    ASSERT_EQ(o.status, 0) << o.out;
    EXPECT_EQ(std::stod(o.out), beadMass());
}

TEST_F(ContactLaw, CoefficientsPerTypePairPerUnitOrAbsoluteMass)
{
    for (const double meff : {1.0, 1.767e-5}) {
        const Output o = run(meff == 1.0 ? "coefficients" : "coefficients --meff 1.767e-5");
        ASSERT_EQ(o.status, 0) << o.out;
        const std::vector<std::string> l = lines(o.out);
        ASSERT_EQ(l.size(), 4u) << o.out;
        EXPECT_EQ(l[0].rfind("i,j,tc_s,en,et,mu,kn", 0), 0u) << l[0];
        const ContactParameters pairs[3] = {kBead, kDrum, kDrum};
        for (int r = 0; r < 3; ++r) {
            const std::vector<double> v = numbers(l[r + 1], ',');
            ASSERT_EQ(v.size(), 10u) << l[r + 1];
            const Coefficients c = scaled(pourninUnitCoefficients(pairs[r]), meff);
            const double expected[8] = {pairs[r].tc, pairs[r].en, pairs[r].et, pairs[r].mu, c.kn, c.cn, c.kt, c.ct};
            for (int k = 0; k < 8; ++k) EXPECT_NEAR(v[k + 2], expected[k], 1e-11 * expected[k]) << l[r + 1];
        }
    }
}

TEST_F(ContactLaw, BadMaterialsFileStopsNamingTheLine)
{
    std::ofstream(dir / "bad.in") << "variable bead_tc equal 1e-4\nvariable bead_en equal oops\n";
    const Output o = run("stock --materials bad.in");
    EXPECT_NE(o.status, 0);
    EXPECT_NE(o.out.find("bad.in:2:"), std::string::npos) << o.out;
    fs::remove(dir / "inputs/materials.in");
    EXPECT_NE(run("bead-mass").status, 0);  // the default file is relative to the working directory
}
