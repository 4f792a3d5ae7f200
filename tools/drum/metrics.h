// Drum metrics from bead snapshots (thesis section 3.4.3): heights relative
// to the drum axis (x axis), gravity along -z.
//
// Every metric is defined once, as an entry of metricTable(): its key, unit,
// labels and the function that computes it from one bed. The per-snapshot
// CSV, the time averages, the charts and the cross-speed table of
// drum_metrics are all generated from that table.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace drum {

// One snapshot of the bed: bead centres, radii and the force of the drum on
// each bead (zero for beads not touching it).
struct Bed {
    double time = 0.0;
    std::vector<Eigen::Vector3d> position;
    std::vector<double> radius;
    std::vector<Eigen::Vector3d> wallForce;
    std::vector<long> id;                     // when the file has them, else empty
    std::vector<Eigen::Vector3d> velocity;    // likewise (VTP array `v`)
    std::vector<Eigen::Vector3d> spin;        // likewise (VTP array `omega`) [rad/s]
};

// The free surface: a straight line z = intercept + slope y fitted, over the
// central half of the bed's extent across y, to the height of the
// third-highest bead centre in bins two diameters wide (robust to a couple of
// flying beads). `midY`: the centre of the bed's extent across y (the chord).
struct FreeSurface {
    bool found = false;
    double intercept = NAN, slope = NAN, midY = NAN;
};

// Streamwise velocity against depth at mid-chord (see analyseBed): one entry
// per non-empty depth bin, top down.
struct DepthBin {
    int index = 0;        // bin k holds depths [k d, (k+1) d); bin 0 also the beads up to d above the line
    int beads = 0;
    double depth = 0.0;   // mean depth of its beads [m]
    double u = 0.0;       // their mean streamwise velocity [m/s]
};

// What the metric functions read from one bed, each part computed once.
struct BedAnalysis {
    const Bed& bed;
    double omega = 1.0;      // the drum's angular velocity about +x [rad/s] (> 0: counter-clockwise, y towards z)
    double diameter = 0.0;   // bead diameter d (from the first bead) [m]
    int wallContacts = 0;    // beads touching the drum
    FreeSurface surface;
    std::vector<DepthBin> profile;  // empty without velocities or a free surface
    double omegaSign() const { return omega >= 0.0 ? 1.0 : -1.0; }
};
BedAnalysis analyseBed(const Bed& bed, double omega);

// One row of the metric table. Column names: key + "_" + unit tag, standard
// error key + "_se_" + unit tag, where the tag is the unit with '/' written
// 'p' (m/s -> mps).
struct Metric {
    std::string key, unit;
    std::string label;        // short, for chart axes and table headers
    std::string description;  // one sentence, for `drum_metrics metrics`
    bool steadiness;          // one of the series the steady-state detection watches
    double (*value)(const BedAnalysis&);
    std::string column() const;
    std::string seColumn() const;
};
const std::vector<Metric>& metricTable();

// The metrics of one bed, in table order.
struct BedMetrics {
    double time = 0.0;
    int beads = 0, wallContacts = 0;
    std::vector<double> values;
    double operator[](const std::string& key) const;  // throws for a key not in the table
};
// omega: the drum's angular velocity about +x [rad/s] (its sign: the direction).
BedMetrics measureBed(const Bed& bed, double omega);

// Reads a LIGGGHTS custom/vtk bead file (.vtp or legacy .vtk) with arrays
// radius and f_force_shell[1-3] (and id, v, omega when present).
Bed readBed(const std::string& file, double time);

// Largest position and velocity differences between the beads of two
// snapshots, matched by id (both need ids and velocities); throws if their
// bead sets differ.
struct Difference {
    int beads = 0;
    double position = 0.0, velocity = 0.0;  // [m], [m/s]
};
Difference compare(const Bed& a, const Bed& b);

// Steady state: the sample index from which every metric has settled, by
// the MSER rule (White 1997) applied to each series from its first finite
// sample, its truncation searched over all but the last tenth; -1 when a
// series' optimum lies in its second half (it never settled) or it has fewer
// than 2 minSamples samples.
int steadyStart(const std::vector<std::vector<double>>& series, int minSamples = 10);

struct Average {
    double mean = 0.0, stdError = 0.0;
    int batches = 0;  // batches behind stdError (0: none, or the naive estimate)
};
// Mean and standard error of v[from:], by batch means (autocorrelation
// included): 5 batches of equal count, never below the naive estimate.
Average average(const std::vector<double>& v, int from);
// The same by batches of `batchSize` samples (e.g. one drum revolution): the
// last floor((n - from) / batchSize) whole batches of v[from:] are used (the
// oldest remainder dropped), mean over them, SE = sd(batch means) / sqrt(nb);
// nb < 2 gives a NaN SE.
Average average(const std::vector<double>& v, int from, int batchSize);

// The stop rule of a run segment: has the run settled (MSER on `watched`, as
// steadyStart), and do the batch-means averages of the `targets` from the
// steady start reach their target standard errors?
struct Target {
    std::vector<double> series;
    double stdError;  // the target SE, in the series' unit
};
struct Verdict {
    bool settled = false;  // steadyStart found a start in the first half
    bool done = false;     // settled, batches >= minBatches, every SE (times seFactor) <= its target
    int from = -1;         // first sample averaged (the last half when not settled)
    int batches = 0;       // whole batches averaged (the fewest over the targets)
    std::vector<Average> averages;  // one per target
    double seFactor = 1.0;          // what the SEs were multiplied by before the comparison
};
// `confidence` 0: each SE as estimated must be within its target. Above 0:
// its upper confidence bound must be (seUpperBound), so that a few batches,
// whose SE estimate scatters widely, stop only where even the bound is small.
Verdict stopRule(const std::vector<std::vector<double>>& watched, const std::vector<Target>& targets, int batchSize,
                 int minBatches = 5, double confidence = 0.0);

// The factor from a batch-means SE over `batches` batches to its upper
// confidence bound at `confidence`, for independent, normal batch means:
// (nb - 1) s^2 / sigma^2 is chi-square with nb - 1 degrees of freedom, so
// sigma <= s sqrt((nb - 1) / chi2_{1 - confidence}(nb - 1)) with that
// probability (3 batches at 0.95: 4.42; 5: 2.37; 20: 1.37). 1 for confidence
// 0; throws std::invalid_argument outside [0, 1) or for fewer than 2 batches.
double seUpperBound(int batches, double confidence);
// Throws std::invalid_argument, naming it, for a confidence outside [0, 1).
void checkConfidence(double confidence);

}  // namespace drum
