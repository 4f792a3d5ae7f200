#include "runner.h"

#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace collide {

namespace fs = std::filesystem;

namespace {

std::string shellQuote(const std::string& s)
{
    std::string q = "'";
    for (char ch : s) q += (ch == '\'') ? std::string("'\\''") : std::string(1, ch);
    return q + "'";
}

std::string num(double v)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

// Gap that makes the first overlap occur `phase` of a step after step
// `steps`, so runs at different dt start their contact at the same phase.
double initialGap(const Case& c, double phase, int steps)
{
    return (steps + phase - 1.0) * c.normalSpeed * c.dt;
}

// Copies of the impact (one per contact-start phase) sit side by side along
// z, far enough apart never to touch.
double copySpacing(const Case& c) { return 3.0 * (c.radius1 + c.radius2); }
double copyOffset(const Case& c, int copy, int copies) { return (copy - 0.5 * (copies - 1)) * copySpacing(c); }

constexpr int kApproachSteps = 3;

std::string typePair(const char* name, double v)
{
    return "fix " + std::string(name) + " all property/global " + name + " peratomtypepair 2 " + num(v) +
           " " + num(v) + " " + num(v) + " " + num(v) + "\n";
}

std::string modelArgs(const Case& c)
{
    return "model viscoelastic tangential " + name(c.tangential);
}

// wall/gran reads model settings only after the wall geometry
std::string modelSettings(const Case& c, const RunOptions& o, bool wall = false)
{
    const std::string own = wall && !o.wallSettings.empty() ? " " + o.wallSettings : "";
    return std::string("limitForce ") + (c.limitForce ? "on" : "off") +
           (c.exactRestitution ? " exactRestitution on" : "") + (o.settings.empty() ? "" : " " + o.settings) + own;
}

// A rectangle of two triangles in the plane x = 0, normal +x.
void writePlaneStl(const fs::path& file, double halfY, double halfZ)
{
    std::ofstream f(file);
    const std::string h = num(halfY), m = num(-halfY), hz = num(halfZ), mz = num(-halfZ);
    auto facet = [&](const std::string& a, const std::string& b, const std::string& cc) {
        f << "facet normal 1 0 0\n outer loop\n  vertex " << a << "\n  vertex " << b << "\n  vertex " << cc
          << "\n endloop\nendfacet\n";
    };
    f << "solid plane\n";
    facet("0 " + m + " " + mz, "0 " + h + " " + mz, "0 " + h + " " + hz);
    facet("0 " + m + " " + mz, "0 " + h + " " + hz, "0 " + m + " " + hz);
    f << "endsolid plane\n";
}

std::string setup(const Case& c, const RunOptions& o, int copies)
{
    const double L = 10.0 * std::max(c.radius1, c.radius2);
    const double Lz = L + 0.5 * (copies - 1) * copySpacing(c);
    std::ostringstream s;
    s << "atom_style granular\natom_modify map array\nboundary f f f\nnewton off\n"
         "communicate single vel yes\nunits si\n";
    if (o.ranks > 1) s << "processors " << o.ranks << " 1 1\n";
    return s.str() + "region box block " + num(-L) + " " + num(L) + " " + num(-L) + " " + num(L) + " " +
           num(-Lz) + " " + num(Lz) + " units box\n";
}

std::string physics(const Case& c, const RunOptions& o)
{
    std::ostringstream s;
    s << "neighbor " << num(0.5 * std::min(c.radius1, c.radius2)) << " bin\nneigh_modify delay 0\n";
    s << typePair("contactDuration", c.params.tc) << typePair("coefficientRestitution", c.params.en)
      << typePair("coefficientRestitutionTangential", c.params.et)
      << typePair("coefficientFriction", c.params.mu);
    s << "pair_style gran " << modelArgs(c) << " " << modelSettings(c, o) << "\npair_coeff * *\n";
    s << "timestep " << num(c.dt) << "\n";
    if (c.geometry == Geometry::Wall)
        s << "fix wall all wall/gran " << modelArgs(c) << " primitive type 2 xplane 0.0 " << modelSettings(c, o, true) << "\n";
    if (c.geometry == Geometry::MeshWall)
        s << "fix plane all mesh/surface file plane.stl type 2\n"
          << "fix wall all wall/gran " << modelArgs(c) << " mesh n_meshes 1 meshes plane " << modelSettings(c, o, true) << "\n";
    s << "fix integr all nve/sphere\n";
    s << "dump traj all custom 1 traj.dump id x y z vx vy vz omegax omegay omegaz\n"
         "dump_modify traj sort id format \"%d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"\n";
    s << "thermo_style custom step atoms\nthermo 1000\n";
    return s.str();
}

int totalSteps(const Case& c)
{
    // approach, contact (a little more than tc with limitForce), and a margin
    return kApproachSteps + static_cast<int>(std::ceil(2.0 * c.params.tc / c.dt)) + 5;
}

void run(const std::string& command, const fs::path& dir, const std::string& what)
{
    const std::string full = "cd " + shellQuote(dir.string()) + " && " + command + " > " + what + ".out 2>&1";
    const int status = std::system(full.c_str());
    if (status != 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        std::ifstream out(dir / (what + ".out"));
        std::string text((std::istreambuf_iterator<char>(out)), std::istreambuf_iterator<char>());
        if (text.size() > 3000) text = "..." + text.substr(text.size() - 3000);
        throw std::runtime_error("liggghts failed (" + command + ") in " + dir.string() + ":\n" + text);
    }
}

std::string launcher(const RunOptions& o)
{
    const std::string env = o.preload.empty() ? "" : "LD_PRELOAD=" + shellQuote(o.preload) + " ";
    if (o.ranks <= 1) return env + shellQuote(o.liggghts);
    return env + "mpirun --allow-run-as-root --oversubscribe -np " + std::to_string(o.ranks) +
           (o.preload.empty() ? "" : " -x LD_PRELOAD") + " " + shellQuote(o.liggghts);
}

// Frames of every copy: copy k holds atoms k*perCopy+1 .. (k+1)*perCopy,
// shifted back to z = 0.
std::vector<Trajectory> readDump(const fs::path& file, const Case& c, int copies)
{
    std::ifstream f(file);
    if (!f) throw std::runtime_error("no dump file " + file.string());
    const int perCopy = c.isWall() ? 1 : 2;
    std::vector<Trajectory> out(copies);
    std::string line;
    long step = 0;
    while (std::getline(f, line)) {
        if (line.rfind("ITEM: TIMESTEP", 0) == 0) {
            f >> step;
        } else if (line.rfind("ITEM: ATOMS", 0) == 0) {
            std::vector<BodyStates> frame(copies);
            for (int a = 0; a < copies * perCopy; ++a) {
                int id;
                double v[9];
                f >> id;
                for (double& x : v) f >> x;
                const int copy = (id - 1) / perCopy;
                if (!f || copy < 0 || copy >= copies) throw std::runtime_error("bad dump " + file.string());
                BodyStates& s = frame[copy];
                s.time = step * c.dt;
                Vec3 x(v[0], v[1], v[2] - copyOffset(c, copy, copies)), vel(v[3], v[4], v[5]), w(v[6], v[7], v[8]);
                if ((id - 1) % perCopy == 0) s.x1 = x, s.v1 = vel, s.w1 = w;
                else s.x2 = x, s.v2 = vel, s.w2 = w;
            }
            for (int k = 0; k < copies; ++k) out[k].frames.push_back(frame[k]);
        }
    }
    return out;
}

// o.workdir (default: collide/ in the temporary directory), created.
fs::path workDirectory(const RunOptions& o)
{
    const fs::path dir = o.workdir.empty() ? fs::temp_directory_path() / "collide" : fs::path(o.workdir);
    fs::create_directories(dir);
    return dir;
}

}  // namespace

std::string runScript(const std::string& script, const RunOptions& o)
{
    const fs::path dir = workDirectory(o);
    std::ofstream(dir / "in.script") << script;
    run(launcher(o) + " -in in.script -log log.script", dir, "script");
    std::ifstream out(dir / "script.out");
    return std::string((std::istreambuf_iterator<char>(out)), std::istreambuf_iterator<char>());
}

std::string collisionInput(const Case& c, const RunOptions& o, const std::string& extra,
                           const std::vector<double>& phases)
{
    const std::vector<double> ph = phases.empty() ? std::vector<double>{o.phase} : phases;
    const int copies = static_cast<int>(ph.size());
    std::ostringstream in;
    in << setup(c, o, copies) << "create_box 2 box\n";
    int id = 0;
    auto atom = [&](const Vec3& x, const Vec3& v, const Vec3& w, double r, double rho) {
        in << "create_atoms 1 single " << num(x.x()) << " " << num(x.y()) << " " << num(x.z()) << " units box\n"
           << "set atom " << ++id << " diameter " << num(2 * r) << " density " << num(rho) << " vx " << num(v.x())
           << " vy " << num(v.y()) << " vz " << num(v.z()) << " omegax " << num(w.x()) << " omegay "
           << num(w.y()) << " omegaz " << num(w.z()) << "\n";
    };
    for (int k = 0; k < copies; ++k) {
        const BodyStates s = initialState(c, initialGap(c, ph[k], kApproachSteps));
        const Vec3 shift(0, 0, copyOffset(c, k, copies));
        atom(s.x1 + shift, s.v1, s.w1, c.radius1, c.density1);
        if (!c.isWall()) atom(s.x2 + shift, s.v2, s.w2, c.radius2, c.density2);
    }
    in << physics(c, o) << extra;
    return in.str();
}

std::vector<Trajectory> runLiggghts(const Case& c, const RunOptions& o, const std::vector<double>& phases)
{
    const fs::path dir = workDirectory(o);
    fs::remove(dir / "traj.dump");
    const int copies = static_cast<int>(phases.size());
    if (c.geometry == Geometry::MeshWall)
        writePlaneStl(dir / "plane.stl", 5.0 * c.radius1, 5.0 * c.radius1 + 0.5 * copies * copySpacing(c));

    const int steps = totalSteps(c);
    if (o.restartAfterContactSteps < 0) {
        std::ofstream(dir / "in.collision") << collisionInput(c, o, "run " + std::to_string(steps) + "\n", phases);
        run(launcher(o) + " -in in.collision -log log.collision", dir, "collision");
        return readDump(dir / "traj.dump", c, copies);
    }
    if (copies != 1) throw std::invalid_argument("a restart check runs one copy");

    // Interrupted run: stop mid-contact, write a restart, continue from it.
    const int first = kApproachSteps + o.restartAfterContactSteps;
    std::ofstream(dir / "in.first") << collisionInput(
        c, o, "run " + std::to_string(first) + "\nwrite_restart collision.restart\n", phases);
    run(launcher(o) + " -in in.first -log log.first", dir, "first");
    std::vector<BodyStates> frames = readDump(dir / "traj.dump", c, 1)[0].frames;

    std::ostringstream second;
    second << setup(c, o, 1) << "read_restart collision.restart\n" << physics(c, o);
    second << "run " << steps - first << "\n";
    std::ofstream(dir / "in.second") << second.str();
    fs::rename(dir / "traj.dump", dir / "traj.first.dump");
    run(launcher(o) + " -in in.second -log log.second", dir, "second");
    std::vector<BodyStates> rest = readDump(dir / "traj.dump", c, 1)[0].frames;
    // the continuation's first frame repeats the restart state
    if (!rest.empty()) rest.erase(rest.begin());
    frames.insert(frames.end(), rest.begin(), rest.end());
    return {Trajectory{frames}};
}

Trajectory runLiggghts(const Case& c, const RunOptions& o) { return runLiggghts(c, o, {o.phase})[0]; }

Outcome measureTrajectory(const Case& c, const Trajectory& t)
{
    // Normal and tangential directions turn with the line of centres even
    // after separation, so the outcome is read at the first frame after
    // the contact (as the reference does), not at the end of the run.
    if (t.frames.size() < 3) throw std::runtime_error("trajectory too short");
    int touching = 0;
    double peak = 0.0;
    size_t before = 0, after = 0;
    for (size_t i = 0; i < t.frames.size() && after == 0; ++i) {
        const double overlap = kinematics(c, t.frames[i]).overlap;
        if (overlap > 0.0) ++touching, peak = std::max(peak, overlap);
        else if (touching == 0) before = i;
        else after = i;
    }
    if (touching == 0) throw std::runtime_error("the bodies never touched");
    if (after == 0) throw std::runtime_error("the bodies were still in contact at the end of the run");
    return outcomeOf(c, t.frames[before], t.frames[after], touching * c.dt, peak);
}

std::vector<double> evenPhases(int count)
{
    std::vector<double> phases;
    for (int k = 0; k < count; ++k) phases.push_back((k + 0.5) / count);
    return phases;
}

Outcome meanOutcome(const Case& c, const std::vector<Trajectory>& runs)
{
    const double n = static_cast<double>(runs.size());
    Outcome sum;
    for (const Trajectory& t : runs) {
        const Outcome x = measureTrajectory(c, t);
        sum.restitution += x.restitution / n;
        sum.duration += x.duration / n;
        sum.peakOverlap += x.peakOverlap / n;
        sum.tangentialRestitution += x.tangentialRestitution / n;
        sum.spin1 += x.spin1 / n;
        sum.reboundAngle += x.reboundAngle / n;
    }
    return sum;
}

}  // namespace collide
