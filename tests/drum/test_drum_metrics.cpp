// Drum metrics on synthetic beds whose answers are known by construction.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "metrics.h"

namespace {

// Beads on a square grid (spacing d) filling the drum below the plane
// z = z0 + tan(angle) y, inside radius R - d/2; the ones within d of the
// shell touch it (unit force along -r, plus `drag` along the drum's motion).
drum::Snapshot bed(double angleDeg, double z0, double drag = 0.0)
{
    const double R = 0.225, d = 0.003, slope = std::tan(angleDeg * M_PI / 180.0);
    drum::Snapshot s;
    for (double y = -R; y <= R; y += d)
        for (double z = -R; z <= R; z += d) {
            const double r = std::hypot(y, z);
            if (r > R - d / 2 || z > z0 + slope * y) continue;
            s.position.emplace_back(0.0, y, z);
            s.radius.push_back(d / 2);
            Eigen::Vector3d f = Eigen::Vector3d::Zero();
            if (r > R - 1.5 * d) f = -Eigen::Vector3d(0.0, y, z) / r + drag * Eigen::Vector3d(0.0, -z, y) / r;
            s.wallForce.push_back(f);
        }
    return s;
}

}  // namespace

TEST(DrumMetrics, HeightsOfAFlatBed)
{
    const drum::Snapshot s = bed(0.0, -0.05);
    const drum::Metrics m = drum::measure(s, 1.0);
    double maxZ = -1, sumZ = 0, maxWallZ = -1;
    for (size_t i = 0; i < s.position.size(); ++i) {
        maxZ = std::max(maxZ, s.position[i].z());
        sumZ += s.position[i].z();
        if (s.wallForce[i].norm() > 0) maxWallZ = std::max(maxWallZ, s.position[i].z());
    }
    EXPECT_DOUBLE_EQ(m.head, maxZ);
    EXPECT_DOUBLE_EQ(m.shoulder, maxWallZ);
    EXPECT_NEAR(m.centreOfMass, sumZ / s.position.size(), 1e-12);
    EXPECT_LE(m.shoulder, m.head);
    EXPECT_LT(m.centreOfMass, 0.0);
    EXPECT_NEAR(m.reposeAngle, 0.0, 0.5);
}

// The surface is sampled in bins two beads wide on a grid of spacing d: the
// fitted slope is exact up to the grid's staircase, about d / (bed width).
TEST(DrumMetrics, AngleOfReposeOfAnInclinedBed)
{
    for (double angle : {10.0, 25.0, 35.0}) {
        EXPECT_NEAR(drum::measure(bed(angle, -0.06), 1.0).reposeAngle, angle, 1.0) << angle;
        // the same bed seen with the drum turning the other way tilts the other way
        EXPECT_NEAR(drum::measure(bed(angle, -0.06), -1.0).reposeAngle, -angle, 1.0) << angle;
    }
}

TEST(DrumMetrics, TangentialForceIsTheComponentAlongTheDrumMotion)
{
    const drum::Metrics m = drum::measure(bed(0.0, -0.05, 0.25), 1.0);
    EXPECT_GT(m.wallContacts, 100);
    EXPECT_NEAR(m.tangentialForce, 0.25, 1e-12);  // the radial part does not count
    EXPECT_NEAR(drum::measure(bed(0.0, -0.05, 0.25), -1.0).tangentialForce, -0.25, 1e-12);
}

TEST(SteadyState, DetectsTheEndOfATransientAndRejectsTrends)
{
    std::mt19937 rng(7);
    std::normal_distribution<double> noise(0.0, 0.002);
    std::vector<double> settling, flat, trend;
    for (int i = 0; i < 200; ++i) {
        settling.push_back(-0.1 + 0.05 * std::exp(-i / 15.0) + noise(rng));  // decays over ~15 samples
        flat.push_back(0.3 + noise(rng));
        trend.push_back(0.001 * i + noise(rng));  // drifts 0.2 against noise 0.002
    }
    EXPECT_LT(drum::steadyStart({flat}), 20);  // noise alone: little or nothing to cut
    EXPECT_EQ(drum::steadyStart({trend}), -1);
    const int start = drum::steadyStart({settling, flat});
    // by 5 decay times the transient (0.05 e^-5 = 3e-4) is below the noise
    EXPECT_GT(start, 15);
    EXPECT_LT(start, 75);
    const drum::Average a = drum::average(settling, start);
    EXPECT_NEAR(a.mean, -0.1, 4.0 * a.stdError + 1e-4);
}

// An overshoot (rise, peak, settle) whose two halves have equal means must
// not count as steady from the start: the case a half-means test misses.
TEST(SteadyState, OvershootIsNotSteady)
{
    std::mt19937 rng(11);
    std::normal_distribution<double> noise(0.0, 0.3);
    std::vector<double> angle;
    for (int i = 0; i < 200; ++i) {
        const double t = i / 50.0;  // 0..4 s, the ramp lasts 0.8 s
        const double clean = t < 0.8 ? 28.0 * t / 0.8 : 22.0 + 6.0 * std::exp(-(t - 0.8) / 0.15);
        angle.push_back(clean + noise(rng));
    }
    const int start = drum::steadyStart({angle});
    EXPECT_GE(start, 40);  // not before the peak at 0.8 s (sample 40)
    // and by the time the overshoot is well below the noise: 6 e^-6 = 0.015
    // at 0.8 s + 6 x 0.15 s = 1.7 s (sample 85)
    EXPECT_LE(start, 85);
    // cut at the midpoint the same series has not settled
    EXPECT_EQ(drum::steadyStart({std::vector<double>(angle.begin(), angle.begin() + 100)}), -1);
}

TEST(Compare, MatchesBeadsByIdAndReportsLargestDifferences)
{
    drum::Snapshot a, b;
    a.id = {1, 2, 3};
    b.id = {3, 1, 2};
    a.position = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
    b.position = {{2, 0, 0.003}, {0, 0, 0}, {1, 0.001, 0}};
    a.velocity = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    b.velocity = {{0, 0, 0}, {0.5, 0, 0}, {0, 0, 0}};
    const drum::Difference d = drum::compare(a, b);
    EXPECT_EQ(d.beads, 3);
    EXPECT_DOUBLE_EQ(d.position, 0.003);
    EXPECT_DOUBLE_EQ(d.velocity, 0.5);
    b.id = {4, 1, 2};
    EXPECT_THROW(drum::compare(a, b), std::runtime_error);
}
