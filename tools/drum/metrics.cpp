#include "metrics.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>

#include <Eigen/Dense>

#include <vtkDataArray.h>
#include <vtkDataSetReader.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataReader.h>

namespace drum {

Metrics measure(const Snapshot& s, double omegaSign)
{
    Metrics m;
    m.time = s.time;
    m.beads = static_cast<int>(s.position.size());
    if (m.beads == 0) return m;
    m.head = -1e300;
    m.shoulder = -1e300;
    double zsum = 0.0, ftsum = 0.0;
    for (size_t i = 0; i < s.position.size(); ++i) {
        const Eigen::Vector3d& x = s.position[i];
        m.head = std::max(m.head, x.z());
        zsum += x.z();
        const Eigen::Vector3d& f = s.wallForce[i];
        if (f.squaredNorm() > 0.0) {
            ++m.wallContacts;
            m.shoulder = std::max(m.shoulder, x.z());
            // direction of the drum surface's motion at the bead: omega x r
            const Eigen::Vector3d along = omegaSign * Eigen::Vector3d(0.0, -x.z(), x.y()).normalized();
            ftsum += f.dot(along);
        }
    }
    m.centreOfMass = zsum / m.beads;
    if (m.wallContacts == 0) m.shoulder = NAN;
    m.tangentialForce = m.wallContacts ? ftsum / m.wallContacts : NAN;

    // Free surface: in 2-diameter wide bins across the drum, the height of
    // the third-highest bead (robust to a couple of flying beads); a line
    // through the central half of the bed gives the angle.
    const double width = 4.0 * s.radius.front();
    std::map<long, std::vector<double>> bins;
    double ymin = 1e300, ymax = -1e300;
    for (const Eigen::Vector3d& x : s.position) {
        bins[std::lround(std::floor(x.y() / width))].push_back(x.z());
        ymin = std::min(ymin, x.y()), ymax = std::max(ymax, x.y());
    }
    const double yc = 0.5 * (ymin + ymax), half = 0.25 * (ymax - ymin);
    std::vector<double> ys, zs;
    for (auto& [k, z] : bins) {
        const double y = (k + 0.5) * width;
        if (z.size() < 5 || std::fabs(y - yc) > half) continue;
        std::nth_element(z.begin(), z.begin() + 2, z.end(), std::greater<double>());
        ys.push_back(y), zs.push_back(z[2]);
    }
    if (ys.size() >= 3) {
        Eigen::MatrixXd A(ys.size(), 2);
        Eigen::VectorXd b(ys.size());
        for (size_t i = 0; i < ys.size(); ++i) A(i, 0) = 1.0, A(i, 1) = ys[i], b(i) = zs[i];
        const Eigen::Vector2d fit = A.colPivHouseholderQr().solve(b);
        // the bed rises on the side the drum carries it to
        m.reposeAngle = std::atan(omegaSign * fit(1)) * 180.0 / M_PI;
    } else {
        m.reposeAngle = NAN;
    }
    return m;
}

Snapshot readSnapshot(const std::string& file, double time)
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

    Snapshot s;
    s.time = time;
    const vtkIdType n = data->GetNumberOfPoints();
    s.position.resize(n), s.radius.resize(n), s.wallForce.resize(n);
    if (id && v) s.id.resize(n), s.velocity.resize(n);
    for (vtkIdType i = 0; i < n; ++i) {
        double p[3], f[3];
        data->GetPoint(i, p);
        force->GetTuple(i, f);
        s.position[i] = Eigen::Vector3d(p[0], p[1], p[2]);
        s.radius[i] = radius->GetTuple1(i);
        s.wallForce[i] = Eigen::Vector3d(f[0], f[1], f[2]);
        if (id && v) {
            double w[3];
            v->GetTuple(i, w);
            s.id[i] = static_cast<long>(id->GetTuple1(i));
            s.velocity[i] = Eigen::Vector3d(w[0], w[1], w[2]);
        }
    }
    return s;
}

Difference compare(const Snapshot& a, const Snapshot& b)
{
    if (a.id.empty() || b.id.empty()) throw std::runtime_error("compare needs the arrays 'id' and 'v'");
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

// MSER (White 1997): the truncation d that minimises the squared standard
// error of the remaining mean, sum((x_i - mean_d)^2) / (n - d)^2. Removing a
// ramp or an overshoot lowers it; removing noise does not.
int mserTruncation(const std::vector<double>& v)
{
    const int n = static_cast<int>(v.size());
    int best = 0;
    double bestValue = 1e300;
    for (int d = 0; d < n - 1; ++d) {
        const double mu = mean(v, d, n);
        double sse = 0.0;
        for (int i = d; i < n; ++i) sse += (v[i] - mu) * (v[i] - mu);
        const double value = sse / (double(n - d) * double(n - d));
        if (value < bestValue) bestValue = value, best = d;
    }
    return best;
}

}  // namespace

int steadyStart(const std::vector<std::vector<double>>& series, int minSamples)
{
    int start = 0;
    for (const std::vector<double>& v : series) {
        const int n = static_cast<int>(v.size());
        if (n < 2 * minSamples) return -1;
        const int d = mserTruncation(v);
        // an optimum in the second half means the series never settled
        if (d > n / 2) return -1;
        start = std::max(start, d);
    }
    return start;
}

Average average(const std::vector<double>& v, int from)
{
    if (from < 0 || from >= static_cast<int>(v.size())) return {NAN, NAN};
    return {mean(v, from, v.size()), stdErrorOfMean(v, from, v.size())};
}

}  // namespace drum
