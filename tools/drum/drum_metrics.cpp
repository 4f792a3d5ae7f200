// drum_metrics: drum metrics from LIGGGHTS VTK output (thesis Eq. 3.26-3.28,
// Fig. 3.2-3.6).
//   drum_metrics series --prefix post/drum_21rpm --dt 1e-5 --rpm 21
//       time series (CSV, PNG), steady-state start, time averages
//   drum_metrics table --out post/sweep post/drum_*rpm_average.csv
//       one row per run, and the metrics against drum speed (CSV, Markdown, PNG)
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>

#include "metrics.h"
#include "gnuplot.h"

namespace fs = std::filesystem;

namespace {

// Bead files <prefix>_<step>.vtp (or .vtk), in step order.
std::vector<std::pair<long, fs::path>> beadFiles(const std::string& prefix)
{
    const fs::path p(prefix);
    const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
    const std::regex name(std::regex_replace(p.filename().string(), std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)") +
                          R"(_(\d+)\.(vtp|vtk))");
    std::vector<std::pair<long, fs::path>> files;
    for (const auto& e : fs::directory_iterator(dir)) {
        std::smatch m;
        const std::string f = e.path().filename().string();
        if (std::regex_match(f, m, name)) files.emplace_back(std::stol(m[1]), e.path());
    }
    std::sort(files.begin(), files.end());
    if (files.empty()) throw std::runtime_error("no files " + prefix + "_<step>.vtp");
    return files;
}

int series(const std::string& prefix, const std::string& outPrefix, double dt, double rpm, double skip, double until)
{
    const double omegaSign = rpm >= 0 ? 1.0 : -1.0;
    std::vector<drum::Metrics> ms;
    for (const auto& [step, file] : beadFiles(prefix)) {
        const double t = step * dt;
        if (t < skip || t > until) continue;
        ms.push_back(drum::measure(drum::readSnapshot(file.string(), t), omegaSign));
    }
    if (ms.empty()) throw std::runtime_error("no snapshots of " + prefix + " between --skip and --until");
    const std::string out = outPrefix.empty() ? prefix : outPrefix;
    const std::string csvFile = out + "_metrics.csv";
    std::ofstream csv(csvFile);
    csv << "time,beads,head,shoulder,centre_of_mass,wall_contacts,tangential_force,repose_angle\n";
    std::vector<double> Hh, Hd, Hc, ft, angle;
    for (const drum::Metrics& m : ms) {
        csv << m.time << "," << m.beads << "," << m.head << "," << m.shoulder << "," << m.centreOfMass << ","
            << m.wallContacts << "," << m.tangentialForce << "," << m.reposeAngle << "\n";
        Hh.push_back(m.head), Hd.push_back(m.shoulder), Hc.push_back(m.centreOfMass);
        ft.push_back(m.tangentialForce), angle.push_back(m.reposeAngle);
    }
    csv.close();
    const int start = drum::steadyStart({Hc, Hd, angle});
    const double tSteady = start >= 0 ? ms[start].time : NAN;

    std::printf("%s: %zu snapshots, %d beads, %.3f to %.3f s\n", prefix.c_str(), ms.size(), ms.back().beads,
                ms.front().time, ms.back().time);
    if (start < 0)
        std::printf("no steady state yet: the metrics still drift at the end of the run; averages over the last half\n");
    else
        std::printf("steady from t = %.3f s (%d of %zu snapshots averaged)\n", tSteady, int(ms.size()) - start, ms.size());
    const int from = start >= 0 ? start : int(ms.size()) / 2;
    const drum::Average a[] = {drum::average(Hh, from), drum::average(Hd, from), drum::average(Hc, from),
                               drum::average(ft, from), drum::average(angle, from)};
    const char* names[] = {"head Hh [m]", "shoulder Hd [m]", "centre of mass Hc [m]",
                           "drum tangential force per bead [N]", "angle of repose [deg]"};
    for (int i = 0; i < 5; ++i) std::printf("  %-36s %12.6g +- %.2g\n", names[i], a[i].mean, a[i].stdError);

    std::ofstream avg(out + "_average.csv");
    avg << "rpm,beads,steady_from,snapshots,head,head_err,shoulder,shoulder_err,centre_of_mass,centre_of_mass_err,"
           "tangential_force,tangential_force_err,repose_angle,repose_angle_err\n";
    avg << rpm << "," << ms.back().beads << "," << tSteady << "," << int(ms.size()) - from;
    for (const drum::Average& x : a) avg << "," << x.mean << "," << x.stdError;
    avg << "\n";

    std::ostringstream gp;
    gp << "set terminal pngcairo size 1400,900 noenhanced\nset output '" << out << "_metrics.png'\n"
       << "set datafile separator ','\nset multiplot layout 2,2 title '" << fs::path(prefix).filename().string()
       << ": " << rpm << " rpm" << (start >= 0 ? ", dashed: steady state" : ", not steady yet") << "'\n"
       << "set grid\nset xlabel 'time [s]'\n";
    if (start >= 0) gp << "set arrow 1 from " << tSteady << ", graph 0 to " << tSteady << ", graph 1 nohead dt 2\n";
    gp << "set ylabel 'height above the axis [m]'\nplot '" << csvFile
       << "' every ::1 using 1:3 with lines title 'head Hh', '' every ::1 using 1:4 with lines title 'shoulder Hd'\n"
       << "set ylabel 'centre of mass Hc [m]'\nplot '" << csvFile << "' every ::1 using 1:5 with lines notitle\n"
       << "set ylabel 'drum force along its motion, per touching bead [N]'\nplot '" << csvFile
       << "' every ::1 using 1:7 with lines notitle\n"
       << "set ylabel 'dynamic angle of repose [deg]'\nplot '" << csvFile << "' every ::1 using 1:8 with lines notitle\n"
       << "unset multiplot\n";
    gnuplot(gp.str());
    std::printf("wrote %s_metrics.csv, %s_metrics.png, %s_average.csv\n", out.c_str(), out.c_str(), out.c_str());
    return 0;
}

int table(const std::string& out, const std::vector<std::string>& files)
{
    std::vector<std::vector<double>> rows;
    std::string header;
    for (const std::string& f : files) {
        std::ifstream in(f);
        std::string line;
        std::getline(in, header);
        while (std::getline(in, line)) {
            std::vector<double> r;
            std::stringstream ss(line);
            std::string cell;
            while (std::getline(ss, cell, ',')) r.push_back(cell == "nan" || cell == "-nan" ? NAN : std::stod(cell));
            rows.push_back(r);
        }
    }
    std::sort(rows.begin(), rows.end());
    std::ofstream csv(out + ".csv"), md(out + ".md");
    csv << header << "\n";
    md << "| rpm | beads | steady from [s] | snapshots averaged | head Hh [m] | shoulder Hd [m] | centre of mass Hc [m] | "
          "drum force per bead [N] | angle of repose [deg] |\n|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& r : rows) {
        for (size_t i = 0; i < r.size(); ++i) csv << (i ? "," : "") << r[i];
        csv << "\n";
        char steady[64] = "not steady: last half";
        if (!std::isnan(r[2])) std::snprintf(steady, sizeof steady, "%.2f", r[2]);
        char buf[512];
        std::snprintf(buf, sizeof buf,
                      "| %g | %g | %s | %g | %.4f ± %.4f | %.4f ± %.4f | %.5f ± %.5f | %.3g ± %.2g | %.1f ± %.1f |\n",
                      r[0], r[1], steady, r[3], r[4], r[5], r[6], r[7], r[8], r[9], r[10], r[11], r[12], r[13]);
        md << buf;
    }
    csv.close();
    std::ostringstream gp;
    gp << "set terminal pngcairo size 1400,900 noenhanced\nset output '" << out << ".png'\nset datafile separator ','\n"
       << "set multiplot layout 2,2 title 'time-averaged drum metrics against speed (error bars: standard error)'\n"
       << "set grid\nset xlabel 'drum speed [rpm]'\nset key top left\n"
       << "set ylabel 'height above the axis [m]'\nplot '" << out
       << ".csv' every ::1 using 1:5:6 with yerrorlines title 'head Hh', '' every ::1 using 1:7:8 with yerrorlines title 'shoulder Hd'\n"
       << "set ylabel 'centre of mass Hc [m]'\nplot '" << out << ".csv' every ::1 using 1:9:10 with yerrorlines notitle\n"
       << "set ylabel 'drum force per touching bead [N]'\nplot '" << out
       << ".csv' every ::1 using 1:11:12 with yerrorlines notitle\n"
       << "set ylabel 'dynamic angle of repose [deg]'\nplot '" << out << ".csv' every ::1 using 1:13:14 with yerrorlines notitle\n"
       << "unset multiplot\n";
    gnuplot(gp.str());
    std::printf("wrote %s.csv, %s.md, %s.png\n", out.c_str(), out.c_str(), out.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{"Drum metrics (head, departure shoulder, centre of mass, drum force, angle of repose) from LIGGGHTS VTK output"};
    app.require_subcommand(1);
    std::string prefix, seriesOut, out = "post/sweep";
    double dt = 1e-5, rpm = 0.0, skip = 0.0, until = 1e300;
    std::vector<std::string> files;
    CLI::App* s = app.add_subcommand("series", "metrics of one run over time");
    s->add_option("--prefix", prefix, "bead files are <prefix>_<step>.vtp")->required();
    s->add_option("--dt", dt, "timestep of the run [s]")->check(CLI::PositiveNumber)->capture_default_str();
    s->add_option("--rpm", rpm, "drum speed (sign: direction about +x)")->required();
    s->add_option("--skip", skip, "ignore snapshots before this time [s]")->capture_default_str();
    s->add_option("--until", until, "ignore snapshots after this time [s]");
    s->add_option("--out", seriesOut, "output prefix (default: --prefix)");
    CLI::App* t = app.add_subcommand("table", "combine runs' averages against speed");
    t->add_option("--out", out, "output prefix")->capture_default_str();
    t->add_option("files", files, "<prefix>_average.csv files")->required();
    std::string fileA, fileB;
    CLI::App* c = app.add_subcommand("compare", "largest position and velocity differences of two snapshots (by bead id)");
    c->add_option("a", fileA, "first .vtp")->required()->check(CLI::ExistingFile);
    c->add_option("b", fileB, "second .vtp")->required()->check(CLI::ExistingFile);
    CLI11_PARSE(app, argc, argv);
    try {
        if (*c) {
            const drum::Difference d = drum::compare(drum::readSnapshot(fileA, 0.0), drum::readSnapshot(fileB, 0.0));
            std::printf("beads %d, max position difference %.6g m, max velocity difference %.6g m/s\n", d.beads,
                        d.position, d.velocity);
            return 0;
        }
        return *s ? series(prefix, seriesOut, dt, rpm, skip, until) : table(out, files);
    } catch (const std::exception& e) {
        std::cerr << "drum_metrics: " << e.what() << "\n";
        return 1;
    }
}
