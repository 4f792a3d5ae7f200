// Drum metrics from bead snapshots (thesis section 3.4.3): heights relative
// to the drum axis (x axis), gravity along -z.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace drum {

// One snapshot: bead centres, radii and the force of the drum on each bead
// (zero for beads not touching it).
struct Snapshot {
    double time = 0.0;
    std::vector<Eigen::Vector3d> position;
    std::vector<double> radius;
    std::vector<Eigen::Vector3d> wallForce;
    std::vector<long> id;                     // when the file has them
    std::vector<Eigen::Vector3d> velocity;    // likewise
};

struct Metrics {
    double time = 0.0;
    int beads = 0;
    double head = 0.0;            // Hh, Eq. 3.27: highest bead [m]
    double shoulder = 0.0;        // Hd, Eq. 3.26: highest bead touching the drum [m]
    double centreOfMass = 0.0;    // Hc, Eq. 3.28 (z) [m]
    int wallContacts = 0;         // beads touching the drum
    double tangentialForce = 0.0; // mean force of the drum on a touching bead along the drum's motion [N]
    double reposeAngle = 0.0;     // dynamic angle of repose of the free surface [deg]
};

// `omegaSign`: +1 if the drum turns counter-clockwise about +x (y towards z).
Metrics measure(const Snapshot& s, double omegaSign);

// Reads a LIGGGHTS custom/vtk bead file (.vtp or legacy .vtk) with arrays
// radius and f_force_shell[1-3].
Snapshot readSnapshot(const std::string& file, double time);

// Largest position and velocity differences between the beads of two
// snapshots, matched by id (both need ids and velocities); throws if their
// bead sets differ.
struct Difference {
    int beads = 0;
    double position = 0.0, velocity = 0.0;  // [m], [m/s]
};
Difference compare(const Snapshot& a, const Snapshot& b);

// Steady state: the sample index from which every metric has settled, by
// the MSER rule (White 1997) applied to each series; -1 when a series'
// optimal truncation lies in its second half (it never settled) or it has
// fewer than 2 minSamples samples.
int steadyStart(const std::vector<std::vector<double>>& series, int minSamples = 10);

struct Average {
    double mean = 0.0, stdError = 0.0;
};
// Mean and standard error of v[from:], by batch means (autocorrelation included).
Average average(const std::vector<double>& v, int from);

}  // namespace drum
