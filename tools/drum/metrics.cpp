#include "metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>
#include <utility>

#include <Eigen/Dense>
#include <boost/math/distributions/chi_squared.hpp>

#include <vtkDataArray.h>
#include <vtkDataSetReader.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataReader.h>

namespace drum {

namespace {

bool touching(const Bed& b, size_t i) { return b.wallForce[i].squaredNorm() > 0.0; }

FreeSurface fitFreeSurface(const Bed& s)
{
    FreeSurface fs;
    const double width = 4.0 * s.radius.front();
    std::map<long, std::vector<double>> bins;
    double ymin = 1e300, ymax = -1e300;
    for (const Eigen::Vector3d& x : s.position) {
        bins[std::lround(std::floor(x.y() / width))].push_back(x.z());
        ymin = std::min(ymin, x.y()), ymax = std::max(ymax, x.y());
    }
    fs.midY = 0.5 * (ymin + ymax);
    const double half = 0.25 * (ymax - ymin);
    std::vector<double> ys, zs;
    for (auto& [k, z] : bins) {
        const double y = (k + 0.5) * width;
        if (z.size() < 5 || std::fabs(y - fs.midY) > half) continue;
        std::nth_element(z.begin(), z.begin() + 2, z.end(), std::greater<double>());
        ys.push_back(y), zs.push_back(z[2]);
    }
    if (ys.size() < 3) return fs;
    Eigen::MatrixXd A(ys.size(), 2);
    Eigen::VectorXd b(ys.size());
    for (size_t i = 0; i < ys.size(); ++i) A(i, 0) = 1.0, A(i, 1) = ys[i], b(i) = zs[i];
    const Eigen::Vector2d fit = A.colPivHouseholderQr().solve(b);
    fs.found = true;
    fs.intercept = fit(0), fs.slope = fit(1);
    return fs;
}

// The flowing layer at mid-chord (Orpe & Khakhar 2001, Jain et al. 2002
// measure the same quantities by particle tracking). With the free surface
// z = a + b y of `angle` (FreeSurface) and d the bead diameter:
//  - mid-chord P = (y_m, a + b y_m), the point of the line above the centre
//    y_m of the bed's extent across y;
//  - t: the unit vector along the line in the y-z plane pointing downhill
//    (t_z < 0; on a level line, -y for a drum turning counter-clockwise);
//    n: the unit normal pointing into the bed (n_z < 0);
//  - the beads whose centre lies within 2 d of the normal through P
//    (|(p - P).t| <= 2 d, any x) are binned by their depth h = (p - P).n,
//    bin k = floor(h / d); beads above the line by less than d (the line
//    passes through the third-highest bead of each surface bin, so the top
//    layer's crests lie above it) count in bin 0, beads higher up (in flight)
//    in none;
//  - per bin: the mean depth and the mean streamwise velocity u = v.t.
// Surface velocity: u of bin 0 (depths 0-1 d). Flowing-layer thickness: the
// depth where the binned u first changes sign from positive (the layer flows
// downhill) to negative or zero (the bed beneath turns with the drum and
// moves uphill), by linear interpolation between the two bins' mean depths;
// nan without such a crossing. Both nan without velocities.
std::vector<DepthBin> velocityProfile(const Bed& s, const FreeSurface& fs, double d, double omegaSign)
{
    std::vector<DepthBin> profile;
    if (!fs.found || s.velocity.size() != s.position.size()) return profile;
    const double norm = std::hypot(1.0, fs.slope);
    Eigen::Vector3d t(0.0, 1.0 / norm, fs.slope / norm);
    if (t.z() > 0.0 || (t.z() == 0.0 && omegaSign > 0.0)) t = -t;
    const Eigen::Vector3d n(0.0, fs.slope / norm, -1.0 / norm);
    const Eigen::Vector3d P(0.0, fs.midY, fs.intercept + fs.slope * fs.midY);
    // The strip's beads not in flight: their depth below the line and their
    // streamwise velocity, in bead order.
    std::vector<std::pair<double, double>> strip;
    for (size_t i = 0; i < s.position.size(); ++i) {
        Eigen::Vector3d r = s.position[i] - P;
        r.x() = 0.0;
        const double h = r.dot(n);
        if (std::fabs(r.dot(t)) <= 2.0 * d && h >= -d) strip.emplace_back(h, s.velocity[i].dot(t));
    }
    if (strip.size() < 3) return profile;
    // A curved surface (fast or steep flows) can pass more than d below the
    // fitted line at mid-chord, which leaves the top bin empty: depths are then
    // measured from the strip's third-highest bead below the line (the rule
    // that places the line in each surface bin) instead. Where the top bin has
    // beads, nothing changes.
    std::vector<double> depths;
    for (const auto& [h, u] : strip) depths.push_back(h);
    std::nth_element(depths.begin(), depths.begin() + 2, depths.end());
    const bool top = std::any_of(strip.begin(), strip.end(), [d](const auto& e) { return e.first < d; });
    const double origin = top ? 0.0 : depths[2];
    std::map<int, DepthBin> bins;
    for (const auto& [depth, u] : strip) {
        const double h = depth - origin;
        if (h < -d) continue;
        const int k = static_cast<int>(std::floor(std::max(h, 0.0) / d));
        DepthBin& b = bins[k];
        b.index = k, ++b.beads, b.depth += h, b.u += u;
    }
    for (auto& [k, b] : bins) {
        b.depth /= b.beads, b.u /= b.beads;
        profile.push_back(b);
    }
    return profile;
}

double head(const BedAnalysis& a)
{
    double z = -INFINITY;
    for (const Eigen::Vector3d& x : a.bed.position) z = std::max(z, x.z());
    return a.bed.position.empty() ? NAN : z;
}

double shoulder(const BedAnalysis& a)
{
    double z = -INFINITY;
    for (size_t i = 0; i < a.bed.position.size(); ++i)
        if (touching(a.bed, i)) z = std::max(z, a.bed.position[i].z());
    return a.wallContacts ? z : NAN;
}

double centreOfMass(const BedAnalysis& a)
{
    double z = 0.0;
    for (const Eigen::Vector3d& x : a.bed.position) z += x.z();
    return a.bed.position.empty() ? NAN : z / a.bed.position.size();
}

double drumForce(const BedAnalysis& a)
{
    double f = 0.0;
    for (size_t i = 0; i < a.bed.position.size(); ++i) {
        if (!touching(a.bed, i)) continue;
        // direction of the drum surface's motion at the bead: omega x r
        const Eigen::Vector3d& x = a.bed.position[i];
        f += a.bed.wallForce[i].dot(a.omegaSign() * Eigen::Vector3d(0.0, -x.z(), x.y()).normalized());
    }
    return a.wallContacts ? f / a.wallContacts : NAN;
}

double reposeAngle(const BedAnalysis& a)
{
    // the bed rises on the side the drum carries it to
    return a.surface.found ? std::atan(a.omegaSign() * a.surface.slope) * 180.0 / M_PI : NAN;
}

double surfaceVelocity(const BedAnalysis& a)
{
    return !a.profile.empty() && a.profile.front().index == 0 ? a.profile.front().u : NAN;
}

double layerThickness(const BedAnalysis& a)
{
    const std::vector<DepthBin>& p = a.profile;
    if (std::isnan(surfaceVelocity(a)) || p.front().u <= 0.0) return NAN;
    for (size_t i = 1; i < p.size(); ++i)
        if (p[i].u <= 0.0) return p[i - 1].depth + (p[i].depth - p[i - 1].depth) * p[i - 1].u / (p[i - 1].u - p[i].u);
    return NAN;
}

// Does the drum carry the bed, or does the bed slip on it? A bead at distance
// rho from the axis turns about it at (e_theta . v) / rho, e_theta = (0, -z, y)
// / rho (counter-clockwise). A touching bead's contact point (its outermost
// point, at rho + r) moves along the drum at e_theta . v + spin_x r, where
// the drum's surface moves at omega (rho + r). Three fractions of the drum's
// own motion tell the cases apart: a bed carried as a solid body turns at 1
// with no slip at the wall and no roll; a bed on a layer of beads rolling
// like a ball bearing turns at well under 1 with no slip either (the wall
// beads' spin carries the difference); a bed sliding on the drum turns below
// 1 with slip at the wall.
struct Ring {
    double rho, etheta;  // distance from the axis, velocity component along e_theta
};
Ring ring(const Bed& b, size_t i, const Eigen::Vector3d& v)
{
    const Eigen::Vector3d& x = b.position[i];
    const double rho = std::hypot(x.y(), x.z());
    return {rho, (-x.z() * v.y() + x.y() * v.z()) / rho};
}

// The drum's radius as the touching beads give it: their largest rho + r.
double wallRadius(const Bed& b)
{
    double R = NAN;
    for (size_t i = 0; i < b.position.size(); ++i)
        if (touching(b, i)) R = std::fmax(R, std::hypot(b.position[i].y(), b.position[i].z()) + b.radius[i]);
    return R;
}

// Bed turn: the mean angular velocity about the axis of the beads whose
// centres lie 1.5 to 6 diameters inside the drum and within 30 degrees of its
// lowest point (deep under the free surface at 40 % fill: the part of the
// bed a carrying drum turns with it), over omega; nan without velocities,
// touching beads or such beads.
double bedTurn(const BedAnalysis& a)
{
    const Bed& b = a.bed;
    const double R = wallRadius(b), d = a.diameter;
    if (b.velocity.size() != b.position.size() || std::isnan(R) || a.omega == 0.0) return NAN;
    double sum = 0.0;
    int n = 0;
    for (size_t i = 0; i < b.position.size(); ++i) {
        const Ring c = ring(b, i, b.velocity[i]);
        const double depth = R - c.rho;
        if (depth < 1.5 * d || depth > 6.0 * d || -b.position[i].z() < c.rho * std::cos(M_PI / 6.0)) continue;
        sum += c.etheta / c.rho, ++n;
    }
    return n ? sum / n / a.omega : NAN;
}

// Over the touching beads: the mean velocity of the drum's surface past their
// contact points along its motion (slip; signed, so slips either way cancel)
// and the mean contribution of their spin to the contact point's motion
// (roll), each over the drum surface's speed there;
// nan without velocities and spins, or touching beads.
double wallFraction(const BedAnalysis& a, bool slip)
{
    const Bed& b = a.bed;
    if (b.velocity.size() != b.position.size() || b.spin.size() != b.position.size() || a.omega == 0.0) return NAN;
    double sum = 0.0;
    for (size_t i = 0; i < b.position.size(); ++i) {
        if (!touching(b, i)) continue;
        const Ring c = ring(b, i, b.velocity[i]);
        const double drum = a.omega * (c.rho + b.radius[i]), roll = b.spin[i].x() * b.radius[i];
        sum += (slip ? drum - c.etheta - roll : roll) / drum;
    }
    return a.wallContacts ? sum / a.wallContacts : NAN;
}
double wallSlip(const BedAnalysis& a) { return wallFraction(a, true); }
double wallRoll(const BedAnalysis& a) { return wallFraction(a, false); }

std::string unitTag(std::string unit)
{
    std::replace(unit.begin(), unit.end(), '/', 'p');
    return unit;
}

}  // namespace

std::string Metric::column() const { return key + "_" + unitTag(unit); }
std::string Metric::seColumn() const { return key + "_se_" + unitTag(unit); }

const std::vector<Metric>& metricTable()
{
    static const std::vector<Metric> table = {
        {"Hh", "m", "head Hh", "head (Eq. 3.27): height of the highest bead centre above the drum axis", false, head},
        {"Hd", "m", "departure shoulder Hd",
         "departure shoulder (Eq. 3.26): height of the highest bead touching the drum above the axis", true, shoulder},
        {"Hc", "m", "centre of mass Hc", "centre of mass (Eq. 3.28): mean height of the bead centres above the axis",
         true, centreOfMass},
        {"drum_force", "N", "drum force per touching bead",
         "mean force of the drum on a touching bead along the drum's motion (Fig. 3.6)", false, drumForce},
        {"angle", "deg", "dynamic angle of repose",
         "dynamic angle of repose: slope of a line through the free surface over the central half of the bed", true,
         reposeAngle},
        {"layer_thickness", "m", "flowing-layer thickness",
         "depth below the free surface at mid-chord where the mean streamwise velocity changes sign", false,
         layerThickness},
        {"surface_velocity", "m/s", "surface velocity",
         "mean downhill velocity along the free surface of the beads within one diameter of it at mid-chord", false,
         surfaceVelocity},
        {"bed_turn", "1", "bed turn (1: carried by the drum)",
         "angular velocity about the axis of the beads 1.5-6 diameters inside the drum within 30 degrees of its "
         "lowest point, over the drum's",
         false, bedTurn},
        {"wall_slip", "1", "slip at the drum (0: none)",
         "mean velocity of the drum's surface past the touching beads' contact points along its motion "
         "(signed) over its speed", false,
         wallSlip},
        {"wall_roll", "1", "roll at the drum",
         "mean speed of the touching beads' contact points from their spin (spin_x r), over the drum surface's speed",
         false, wallRoll},
    };
    return table;
}

BedAnalysis analyseBed(const Bed& bed, double omega)
{
    BedAnalysis a{bed, omega, 0.0, 0, FreeSurface{}, {}};
    if (bed.position.empty()) return a;
    a.diameter = 2.0 * bed.radius.front();
    for (size_t i = 0; i < bed.position.size(); ++i) a.wallContacts += touching(bed, i);
    a.surface = fitFreeSurface(bed);
    a.profile = velocityProfile(bed, a.surface, a.diameter, a.omegaSign());
    return a;
}

double BedMetrics::operator[](const std::string& key) const
{
    const std::vector<Metric>& t = metricTable();
    for (size_t i = 0; i < t.size(); ++i)
        if (t[i].key == key) return values.at(i);
    throw std::invalid_argument("no drum metric '" + key + "'");
}

BedMetrics measureBed(const Bed& bed, double omega)
{
    const BedAnalysis a = analyseBed(bed, omega);
    BedMetrics m;
    m.time = bed.time;
    m.beads = static_cast<int>(bed.position.size());
    m.wallContacts = a.wallContacts;
    for (const Metric& metric : metricTable()) m.values.push_back(metric.value(a));
    return m;
}

Bed readBed(const std::string& file, double time)
{
    vtkSmartPointer<vtkPointSet> data;
    if (file.size() > 4 && file.substr(file.size() - 4) == ".vtp") {
        auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
        r->SetFileName(file.c_str());
        r->Update();
        data = r->GetOutput();
    } else {
        auto r = vtkSmartPointer<vtkDataSetReader>::New();
        r->SetFileName(file.c_str());
        r->ReadAllFieldsOn();
        r->Update();
        data = vtkPointSet::SafeDownCast(r->GetOutput());
    }
    if (!data || data->GetNumberOfPoints() == 0) throw std::runtime_error("no beads in " + file);
    vtkPointData* pd = data->GetPointData();
    vtkDataArray* radius = pd->GetArray("radius");
    vtkDataArray* force = pd->GetArray("f_force_shell[1-3]");
    if (!radius) throw std::runtime_error(file + " has no array 'radius'");
    if (!force) throw std::runtime_error(file + " has no array 'f_force_shell[1-3]' (wall force; use store_force yes)");

    vtkDataArray* id = pd->GetArray("id");
    vtkDataArray* v = pd->GetArray("v");
    if (v && v->GetNumberOfComponents() != 3) v = nullptr;
    vtkDataArray* spin = pd->GetArray("omega");
    if (spin && spin->GetNumberOfComponents() != 3) spin = nullptr;

    Bed s;
    s.time = time;
    const vtkIdType n = data->GetNumberOfPoints();
    s.position.resize(n), s.radius.resize(n), s.wallForce.resize(n);
    if (id) s.id.resize(n);
    if (v) s.velocity.resize(n);
    if (spin) s.spin.resize(n);
    for (vtkIdType i = 0; i < n; ++i) {
        double p[3], f[3];
        data->GetPoint(i, p);
        force->GetTuple(i, f);
        s.position[i] = Eigen::Vector3d(p[0], p[1], p[2]);
        s.radius[i] = radius->GetTuple1(i);
        s.wallForce[i] = Eigen::Vector3d(f[0], f[1], f[2]);
        if (id) s.id[i] = static_cast<long>(id->GetTuple1(i));
        if (v) {
            double w[3];
            v->GetTuple(i, w);
            s.velocity[i] = Eigen::Vector3d(w[0], w[1], w[2]);
        }
        if (spin) {
            double w[3];
            spin->GetTuple(i, w);
            s.spin[i] = Eigen::Vector3d(w[0], w[1], w[2]);
        }
    }
    return s;
}

Difference compare(const Bed& a, const Bed& b)
{
    if (a.id.empty() || b.id.empty() || a.velocity.empty() || b.velocity.empty()) throw std::runtime_error("compare needs the arrays 'id' and 'v'");
    std::map<long, size_t> index;
    for (size_t i = 0; i < b.id.size(); ++i) index[b.id[i]] = i;
    if (a.id.size() != b.id.size()) throw std::runtime_error("the snapshots hold different numbers of beads");
    Difference d;
    for (size_t i = 0; i < a.id.size(); ++i) {
        const auto it = index.find(a.id[i]);
        if (it == index.end()) throw std::runtime_error("bead " + std::to_string(a.id[i]) + " is missing in one snapshot");
        Eigen::Vector3d dx = a.position[i] - b.position[it->second];
        d.position = std::max(d.position, dx.norm());
        d.velocity = std::max(d.velocity, (a.velocity[i] - b.velocity[it->second]).norm());
    }
    d.beads = static_cast<int>(a.id.size());
    return d;
}

namespace {

double mean(const std::vector<double>& v, size_t from, size_t to)
{
    return std::accumulate(v.begin() + from, v.begin() + to, 0.0) / double(to - from);
}

// Standard error of the mean of v[from:to] by batch means (5 batches), which
// accounts for the correlation between successive snapshots; never below the
// naive estimate.
double stdErrorOfMean(const std::vector<double>& v, size_t from, size_t to)
{
    const size_t n = to - from;
    const double mu = mean(v, from, to);
    double var = 0.0;
    for (size_t i = from; i < to; ++i) var += (v[i] - mu) * (v[i] - mu);
    var /= std::max<size_t>(n - 1, 1);
    const double naive = std::sqrt(var / n);
    const size_t batches = 5, size = n / batches;
    if (size < 2) return naive;
    double bvar = 0.0;
    for (size_t b = 0; b < batches; ++b) {
        const double bm = mean(v, from + b * size, from + (b + 1) * size);
        bvar += (bm - mu) * (bm - mu);
    }
    return std::max(naive, std::sqrt(bvar / (batches - 1) / batches));
}

// MSER (White 1997): the truncation d <= last that minimises the squared
// standard error of the remaining mean, sum((x_i - mean_d)^2) / (n - d)^2.
// Removing a ramp or an overshoot lowers it; removing noise does not.
int mserTruncation(const std::vector<double>& v, int last)
{
    const int n = static_cast<int>(v.size());
    int best = 0;
    double bestValue = 1e300;
    if (n < 2) return 0;
    // running sums from the end, about the overall mean (O(n), not O(n^2))
    const double c = mean(v, 0, n);
    double s1 = (v[n - 1] - c), s2 = s1 * s1;
    std::vector<double> value(n, 0.0);
    for (int d = n - 2; d >= 0; --d) {
        const double y = v[d] - c;
        s1 += y, s2 += y * y;
        const double k = double(n - d);
        value[d] = std::max(0.0, s2 - s1 * s1 / k) / (k * k);
    }
    for (int d = 0; d <= std::min(last, n - 2); ++d)
        if (value[d] < bestValue) bestValue = value[d], best = d;
    return best;
}

}  // namespace

int steadyStart(const std::vector<std::vector<double>>& series, int minSamples)
{
    int start = 0;
    for (const std::vector<double>& whole : series) {
        // from its first finite sample (a grid start has no shoulder at t = 0,
        // and one NaN made every MSER value NaN: the series never counted)
        int first = 0;
        while (first < static_cast<int>(whole.size()) && !std::isfinite(whole[first])) ++first;
        const std::vector<double> v(whole.begin() + first, whole.end());
        const int n = static_cast<int>(v.size());
        if (n < 2 * minSamples) return -1;
        // MSER's optimum, its last tenth left out of the search: there the
        // statistic of a few samples can be near zero by chance (two equal
        // samples give zero), and a steady series was "never settled" (the
        // 7 rpm study's Hc, flat over 20 s to 0.1 mm, had its optimum at its
        // next-to-last sample). An optimum in the second half means the series
        // has not settled (White 1997). (Searching the first half only let
        // linear trends of 16 standard deviations under AR(1) noise pass as
        // settled in 11 of 40 series: TrendsUnderCorrelatedNoise...)
        const int d = mserTruncation(v, n - 1 - std::max(1, n / 10));
        if (d > n / 2) return -1;
        start = std::max(start, first + d);
    }
    return start;
}

Average average(const std::vector<double>& v, int from)
{
    const int n = static_cast<int>(v.size());
    if (from < 0 || from >= n) return {NAN, NAN, 0};
    // one sample has no error estimate
    if (n - from < 2) return {mean(v, from, n), NAN, 0};
    return {mean(v, from, n), stdErrorOfMean(v, from, n), (n - from) / 5 >= 2 ? 5 : 0};
}

Average average(const std::vector<double>& v, int from, int batchSize)
{
    const int n = static_cast<int>(v.size());
    if (batchSize < 1) throw std::invalid_argument("average: batch size " + std::to_string(batchSize) + " < 1");
    if (from < 0 || from >= n) return {NAN, NAN, 0};
    const int nb = (n - from) / batchSize;
    if (nb == 0) return {mean(v, from, n), NAN, 0};
    const int first = n - nb * batchSize;  // the oldest remainder is dropped
    std::vector<double> bm(nb);
    for (int b = 0; b < nb; ++b) bm[b] = mean(v, first + b * batchSize, first + (b + 1) * batchSize);
    const double mu = mean(bm, 0, nb);
    if (nb < 2) return {mu, NAN, nb};
    double var = 0.0;
    for (double x : bm) var += (x - mu) * (x - mu);
    return {mu, std::sqrt(var / (nb - 1) / nb), nb};
}

void checkConfidence(double confidence)
{
    if (!(confidence >= 0.0 && confidence < 1.0))
        throw std::invalid_argument("confidence " + std::to_string(confidence) + ": must be in [0, 1)");
}

double seUpperBound(int batches, double confidence)
{
    checkConfidence(confidence);
    if (confidence == 0.0) return 1.0;
    if (batches < 2) throw std::invalid_argument("an SE bound needs 2 batches at least, not " + std::to_string(batches));
    const double dof = batches - 1;
    return std::sqrt(dof / boost::math::quantile(boost::math::chi_squared(dof), 1.0 - confidence));
}

Verdict stopRule(const std::vector<std::vector<double>>& watched, const std::vector<Target>& targets, int batchSize,
                 int minBatches, double confidence)
{
    checkConfidence(confidence);  // whatever the data (a bound is computed only from 2 batches)
    Verdict r;
    const int start = steadyStart(watched);
    r.settled = start >= 0;
    size_t n = 0;
    for (const auto& w : watched) n = std::max(n, w.size());
    r.from = r.settled ? start : int(n) / 2;
    r.done = r.settled;
    r.batches = targets.empty() ? 0 : std::numeric_limits<int>::max();
    for (const Target& t : targets) {
        const Average a = average(t.series, r.from, batchSize);
        r.averages.push_back(a);
        r.batches = std::min(r.batches, a.batches);
    }
    r.done = r.done && r.batches >= std::max(minBatches, 2);
    if (r.batches >= 2 && r.batches < std::numeric_limits<int>::max()) r.seFactor = seUpperBound(r.batches, confidence);
    if (r.done) {
        for (size_t k = 0; k < targets.size(); ++k)
            r.done = r.done && std::isfinite(r.averages[k].stdError) &&
                     r.averages[k].stdError * r.seFactor <= targets[k].stdError;
    }
    return r;
}

}  // namespace drum
