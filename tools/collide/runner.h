// collide's LIGGGHTS side: writes the input script of a two-body impact (and
// a plane STL for mesh walls), launches liggghts serially or under mpirun,
// reads the per-step dump back into body states, and measures the outcome
// with the reference's definitions (reference.h).
#pragma once

#include <string>
#include <vector>

#include "reference.h"

namespace collide {

struct RunOptions {
    std::string liggghts = "liggghts";  // executable (our launcher, or the stock one with LD_PRELOAD)
    std::string preload;                // library to LD_PRELOAD (for the stock /usr/bin/liggghts)
    int ranks = 1;                      // > 1 runs `mpirun -np ranks`, split across the contact
    std::string workdir;                // where inputs and outputs go (created)
    double phase = 0.5;                 // fraction of a step at which the first overlap occurs
    std::string settings;               // more model settings for pair and wall, e.g. "exactCollision on"
    std::string wallSettings;           // more model settings for the wall alone, e.g. "wallMassAsParticle on"
    // Restart check: write a restart file this many steps into the
    // contact, then finish the run from it in a second invocation.
    int restartAfterContactSteps = -1;
};

// The LIGGGHTS input for a case: one independent copy of the impact per
// contact-start phase (default: o.phase alone), side by side along z.
std::string collisionInput(const Case& c, const RunOptions& o, const std::string& extra = "",
                           const std::vector<double>& phases = {});

struct Trajectory {
    std::vector<BodyStates> frames;  // one per step, first frame before contact
};

// Runs LIGGGHTS; throws std::runtime_error with the tail of its output on failure.
Trajectory runLiggghts(const Case& c, const RunOptions& o);

// All phases in one run: one trajectory per phase, in their order.
std::vector<Trajectory> runLiggghts(const Case& c, const RunOptions& o, const std::vector<double>& phases);

// Outcome measured from a LIGGGHTS trajectory, with the same definitions as
// the reference (duration = steps with positive overlap times dt).
Outcome measureTrajectory(const Case& c, const Trajectory& t);

// `count` evenly spread contact-start phases, (k + 0.5) / count.
std::vector<double> evenPhases(int count);

// The outcome averaged over runs of the same case (one per contact-start
// phase, as runLiggghts returns them).
Outcome meanOutcome(const Case& c, const std::vector<Trajectory>& runs);

// Runs an arbitrary input script in o.workdir and returns LIGGGHTS' output;
// throws std::runtime_error carrying the output's tail if LIGGGHTS fails.
std::string runScript(const std::string& script, const RunOptions& o);

}  // namespace collide
