// Per-contact cost of the physics core (Google Benchmark): what one contact
// costs the LIGGGHTS model beyond LIGGGHTS' own bookkeeping. Contacts are
// drawn at random (seeded) so nothing folds to a constant; the baseline is
// the same arithmetic with absolute constants, as stock hooke/stiffness
// (absolute_damping on) does it, in the same binary and invocation. The
// tangential laws step a copy of each contact's state, so every iteration
// sees the same contacts (a state stepped without dynamics would drift
// differently under each law and change which branches run).
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "core/collision.h"
#include "core/law.h"

namespace {

using namespace viscoelastic;

struct Contact {
    double meff, overlap, rate;
    Vec3 n, vt, spinI, spinJ;
    TangentialState state;
    CollisionState collision{CollisionPhase::touching, 0.0};  // a contact under way
};

std::vector<Contact> contacts(size_t count)
{
    std::mt19937_64 rng(15485863);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<Contact> c(count);
    for (Contact& k : c) {
        k.meff = 1.767e-5 * (1.0 + 0.1 * u(rng));
        k.overlap = 1e-5 * (1.0 + 0.5 * u(rng));
        k.rate = 0.1 * u(rng);
        k.n = Vec3(u(rng), u(rng), u(rng)).normalized();
        k.vt = Vec3(u(rng), u(rng), u(rng)) * 0.05;
        k.vt -= k.vt.dot(k.n) * k.n;
        k.spinI = Vec3(u(rng), u(rng), u(rng)) * 30.0;
        k.spinJ = Vec3(u(rng), u(rng), u(rng)) * 30.0;
        // a contact under way: a spring of the size a sticking step gives
        k.state.xi = Vec3(u(rng), u(rng), u(rng)) * 1e-7;
        k.state.xi -= k.state.xi.dot(k.n) * k.n;
        k.state.normal = k.n;
        k.state.normalForce = 0.1;
    }
    return c;
}

constexpr size_t kContacts = 4096;

// The contact's state as the step finds it, copied member by member: a
// whole-struct copy is stored in pieces that the step then reloads whole (a
// store-forwarding stall of the harness, not of the law, that cost about half
// a step and hid the laws' own difference).
TangentialState fresh(const TangentialState& from)
{
    TangentialState s;
    s.xi = from.xi, s.normal = from.normal, s.normalForce = from.normalForce;
    return s;
}
const UnitCoefficients kUnit = pourninUnitCoefficients(1e-4, 0.56, 0.46);

void NormalViscoelastic(benchmark::State& state)
{
    std::vector<Contact> c = contacts(kContacts);
    for (auto _ : state)
        for (Contact& k : c) {
            const Coefficients co = scaled(kUnit, k.meff);
            benchmark::DoNotOptimize(normalForce(co, k.overlap, k.rate, false));
        }
    state.SetItemsProcessed(state.iterations() * kContacts);
}

void NormalAbsoluteConstants(benchmark::State& state)
{
    std::vector<Contact> c = contacts(kContacts);
    const Coefficients abs = scaled(kUnit, 1.767e-5);
    for (auto _ : state)
        for (Contact& k : c) benchmark::DoNotOptimize(abs.kn * k.overlap + abs.cn * k.rate);
    state.SetItemsProcessed(state.iterations() * kContacts);
}

void ContactPournin(benchmark::State& state)
{
    std::vector<Contact> c = contacts(kContacts);
    for (auto _ : state)
        for (Contact& k : c) {
            const Coefficients co = scaled(kUnit, k.meff);
            const double fn = normalForce(co, k.overlap, k.rate, false);
            TangentialState s = fresh(k.state);
            const Vec3 ft = pourninTangentialForce(s, k.n, k.vt, co.kt, co.ct, frictionLimit(0.5, fn), 1e-5, true, fn,
                                                   1e-5);
            benchmark::DoNotOptimize(ft);
        }
    state.SetItemsProcessed(state.iterations() * kContacts);
}

// The same contacts under exactCollision: the normal step law and the
// tangential one, with what LIGGGHTS' glue adds per step: the pull on the
// overlap between two spheres (|vt|^2 / d; the glue's |vi - vj|^2 - vn^2
// times LIGGGHTS' 1/r, here the contact point's |vt|^2 times a constant
// 1/d), the spring's drive from the contact point's velocity and the spins,
// and the mass it sees (springDrive; lever arms R - overlap/2). Its
// per-contact cost against ContactPournin's is the price of exactCollision in
// the core.
void ContactExactCollision(benchmark::State& state)
{
    std::vector<Contact> c = contacts(kContacts);
    const double dt = 1e-5, r = 1.5e-3;
    const auto osc = exactCollisionOscillators({1e-4, 0.56, 0.46, 0.5}, false);
    const StepLaw normal = stepLaw(osc->normal.k, osc->normal.c, dt, false);
    const StepLaw tangential = stepLaw(osc->tangential.k, osc->tangential.c, dt, false);
    for (auto _ : state)
        for (Contact& k : c) {
            CollisionState collision = k.collision;
            TangentialState s = fresh(k.state);
            const double arm = r - 0.5 * k.overlap;
            const SpringDrive drive =
                springDrive(k.vt, k.n, k.overlap, k.meff, 2.0 * k.meff, r, arm, k.spinI, 2.0 * k.meff, r, arm, k.spinJ);
            const CollisionStep step =
                exactPairStep(normal, tangential, collision, k.overlap, k.rate, k.vt.squaredNorm() * (1.0 / (2.0 * r)), 2.0 * r,
                              [&] { return PairAtTouch{drive, k.vt, k.meff, 0.5, 1.0 / (2.0 * r)}; });
            const Vec3 ft = pourninExactTangentialForce(s, k.n, drive.rate, drive.mass, tangential, step,
                                                        frictionLimit(0.5, k.meff * step.friction), true);
            benchmark::DoNotOptimize(ft);
        }
    state.SetItemsProcessed(state.iterations() * kContacts);
}

}  // namespace

BENCHMARK(NormalViscoelastic);
BENCHMARK(NormalAbsoluteConstants);
BENCHMARK(ContactPournin);
BENCHMARK(ContactExactCollision);
BENCHMARK_MAIN();
