// drum_metrics: drum metrics from LIGGGHTS VTK output (thesis Eq. 3.26-3.28,
// Fig. 3.2-3.6). Every output is generated from the metric table
// (drum::metricTable(), metrics.cpp); `drum_metrics metrics` lists it.
//   drum_metrics series --prefix post/drum_21rpm --dt 1e-5 --rpm 21 [--skip T0] [--until T1]
//                       [--out O] [--average steady|all]
//       O_metrics.csv (time_s,beads,wall_contacts,<metric columns>), O_metrics.png,
//       O_average.csv (rpm,beads,steady_from_s,snapshots,<metric column, its _se_ column>...)
//   drum_metrics table --out post/sweep post/drum_*rpm_average.csv
//       the averages by column name, one row per run sorted by rpm: O.csv, O.md, O.png
//   drum_metrics metrics
//       the metric table as CSV (column,unit,description)
//   drum_metrics compare a.vtp b.vtp
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <regex>
#include <sstream>

#include "gnuplot.h"
#include "metrics.h"

namespace fs = std::filesystem;

namespace {

const std::vector<drum::Metric>& table() { return drum::metricTable(); }

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

// The columns of an average file (and of the cross-speed table): the run,
// then each metric's time average and its standard error.
std::vector<std::string> averageColumns()
{
    std::vector<std::string> c = {"rpm", "beads", "steady_from_s", "snapshots"};
    for (const drum::Metric& m : table()) c.push_back(m.column()), c.push_back(m.seColumn());
    return c;
}

void writeRow(std::ostream& out, const std::vector<std::string>& cells)
{
    for (size_t i = 0; i < cells.size(); ++i) out << (i ? "," : "") << cells[i];
    out << "\n";
}

std::string number(double x)
{
    if (std::isnan(x)) return "nan";
    std::ostringstream s;
    s.precision(10);
    s << x;
    return s.str();
}

// One chart panel per metric of the table: column `x` of `csv` against the
// metric's column, with its standard-error column as error bars when
// `errors`. `hasData[i]`: metric i has a finite value (gnuplot refuses to plot
// a column of nan). `extra`: gnuplot commands before the panels.
void plotMetrics(const std::string& png, const std::string& csv, const std::string& title, const std::string& x,
                 const std::string& xlabel, bool errors, const std::vector<bool>& hasData, const std::string& extra)
{
    const int cols = 3, rows = (static_cast<int>(table().size()) + cols - 1) / cols;
    std::ostringstream gp;
    gp << "set terminal pngcairo size " << 600 * cols << "," << 400 * rows << " noenhanced\nset output '" << png
       << "'\nset datafile separator ','\nset multiplot layout " << rows << "," << cols << " title '" << title
       << "'\nset grid\nset key off\nset xlabel '" << xlabel << "'\n"
       << (errors ? "set offsets graph 0.05, graph 0.05, graph 0.1, graph 0.1\n" : "") << extra;
    for (size_t i = 0; i < table().size(); ++i) {
        const drum::Metric& m = table()[i];
        gp << "set ylabel '" << m.label << " [" << m.unit << "]'\n";
        if (!hasData[i]) {
            gp << "set label 1 'no values' at graph 0.5,0.5 center\nplot [0:1][0:1] 2\nunset label 1\n";
            continue;
        }
        gp << "plot '" << csv << "' using '" << x << "':'" << m.column() << "'";
        gp << (errors ? ":'" + m.seColumn() + "' with yerrorlines pt 7\n" : std::string(" with lines\n"));
    }
    gp << "unset multiplot\n";
    gnuplot(gp.str());
}

// The finite values of v[from:] (a snapshot where a metric is undefined,
// e.g. no zero crossing of the velocity profile, does not count for it).
std::vector<double> finiteTail(const std::vector<double>& v, int from)
{
    std::vector<double> out;
    std::copy_if(v.begin() + from, v.end(), std::back_inserter(out), [](double x) { return std::isfinite(x); });
    return out;
}

int series(const std::string& prefix, const std::string& outPrefix, double dt, double rpm, double skip, double until,
           bool steady)
{
    const double omegaSign = rpm >= 0 ? 1.0 : -1.0;
    std::vector<drum::BedMetrics> ms;
    for (const auto& [step, file] : beadFiles(prefix)) {
        const double t = step * dt;
        if (t < skip || t > until) continue;
        ms.push_back(drum::measureBed(drum::readBed(file.string(), t), omegaSign));
    }
    if (ms.size() < 2)
        throw std::runtime_error("found " + std::to_string(ms.size()) + " snapshot(s) of " + prefix + " between " +
                                 number(skip) + " and " + number(until) +
                                 " s (--skip, --until, --dt); a time series and its averages need at least 2");
    const std::string out = outPrefix.empty() ? prefix : outPrefix;
    const std::string csvFile = out + "_metrics.csv";
    std::ofstream csv(csvFile);
    std::vector<std::string> header = {"time_s", "beads", "wall_contacts"};
    for (const drum::Metric& m : table()) header.push_back(m.column());
    writeRow(csv, header);
    std::vector<std::vector<double>> values(table().size());
    std::vector<bool> hasData(table().size(), false);
    for (const drum::BedMetrics& m : ms) {
        std::vector<std::string> row = {number(m.time), std::to_string(m.beads), std::to_string(m.wallContacts)};
        for (size_t i = 0; i < table().size(); ++i) {
            row.push_back(number(m.values[i]));
            values[i].push_back(m.values[i]);
            hasData[i] = hasData[i] || std::isfinite(m.values[i]);
        }
        writeRow(csv, row);
    }
    csv.close();

    std::printf("%s: %zu snapshots, %d beads, %.3f to %.3f s\n", prefix.c_str(), ms.size(), ms.back().beads,
                ms.front().time, ms.back().time);
    int start = 0;
    double tSteady = ms.front().time;
    if (steady) {
        std::vector<std::vector<double>> watched;
        for (size_t i = 0; i < table().size(); ++i)
            if (table()[i].steadiness) watched.push_back(values[i]);
        start = drum::steadyStart(watched);
        tSteady = start >= 0 ? ms[start].time : NAN;
        if (start < 0)
            std::printf("no steady state yet: the metrics still drift at the end of the run; averages over the last half\n");
        else
            std::printf("steady from t = %.3f s (%d of %zu snapshots averaged)\n", tSteady, int(ms.size()) - start,
                        ms.size());
    } else {
        std::printf("averages over all %zu snapshots\n", ms.size());
    }
    const int from = start >= 0 ? start : int(ms.size()) / 2;
    std::vector<std::string> row = {number(rpm), std::to_string(ms.back().beads), number(tSteady),
                                    std::to_string(int(ms.size()) - from)};
    for (size_t i = 0; i < table().size(); ++i) {
        const std::vector<double> tail = finiteTail(values[i], from);
        const drum::Average a = drum::average(tail, 0);
        const std::string name = table()[i].label + " [" + table()[i].unit + "]";
        std::printf("  %-36s %12.6g +- %.2g", name.c_str(), a.mean, a.stdError);
        if (tail.size() + from < values[i].size())
            std::printf("  (%zu of %zu snapshots defined)", tail.size(), values[i].size() - from);
        std::printf("\n");
        row.push_back(number(a.mean)), row.push_back(number(a.stdError));
    }
    std::ofstream avg(out + "_average.csv");
    writeRow(avg, averageColumns());
    writeRow(avg, row);

    const std::string title = fs::path(prefix).filename().string() + ": " + number(rpm) + " rpm" +
                              (!steady ? ", all snapshots averaged"
                                       : start >= 0 ? ", dashed: steady state" : ", not steady yet");
    const std::string arrow =
        steady && start >= 0 ? "set arrow 1 from " + number(tSteady) + ", graph 0 to " + number(tSteady) +
                                   ", graph 1 nohead dt 2\n"
                             : "";
    plotMetrics(out + "_metrics.png", csvFile, title, "time_s", "time [s]", false, hasData, arrow);
    std::printf("wrote %s_metrics.csv, %s_metrics.png, %s_average.csv\n", out.c_str(), out.c_str(), out.c_str());
    return 0;
}

double parseNumber(const std::string& cell, const std::string& file)
{
    if (cell == "nan" || cell == "-nan" || cell.empty()) return NAN;
    try {
        return std::stod(cell);
    } catch (const std::exception&) {
        throw std::runtime_error(file + ": '" + cell + "' is not a number");
    }
}

// The rows of an average file as {column name: value}, by its header.
std::vector<std::map<std::string, double>> readAverages(const std::string& file)
{
    std::ifstream in(file);
    if (!in) throw std::runtime_error("cannot read " + file);
    std::string line, cell;
    std::vector<std::string> names;
    std::getline(in, line);
    for (std::stringstream ss(line); std::getline(ss, cell, ',');) names.push_back(cell);
    std::vector<std::map<std::string, double>> rows;
    while (std::getline(in, line)) {
        if (line.empty()) continue;
        std::map<std::string, double> row;
        size_t i = 0;
        for (std::stringstream ss(line); std::getline(ss, cell, ','); ++i)
            if (i < names.size()) row[names[i]] = parseNumber(cell, file);
        if (!row.count("rpm")) throw std::runtime_error(file + " has no column 'rpm'");
        rows.push_back(row);
    }
    for (const std::string& c : averageColumns())
        if (std::find(names.begin(), names.end(), c) == names.end())
            std::fprintf(stderr, "drum_metrics: %s has no column %s (left nan)\n", file.c_str(), c.c_str());
    return rows;
}

// "mean ± se" with se to two significant digits and the mean to the same place.
std::string withError(double mean, double se)
{
    char buf[96];
    if (!std::isfinite(se) || se <= 0.0 || !std::isfinite(mean)) {
        std::snprintf(buf, sizeof buf, "%.4g", mean);
    } else {
        const int decimals = std::clamp(1 - static_cast<int>(std::floor(std::log10(se))), 0, 12);
        std::snprintf(buf, sizeof buf, "%.*f ± %.*f", decimals, mean, decimals, se);
    }
    return buf;
}

int crossSpeedTable(const std::string& out, const std::vector<std::string>& files)
{
    std::vector<std::map<std::string, double>> rows;
    for (const std::string& f : files)
        for (const auto& r : readAverages(f)) rows.push_back(r);
    std::stable_sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.at("rpm") < b.at("rpm"); });
    auto get = [](const std::map<std::string, double>& r, const std::string& c) {
        const auto it = r.find(c);
        return it == r.end() ? NAN : it->second;
    };
    std::ofstream csv(out + ".csv"), md(out + ".md");
    const std::vector<std::string> columns = averageColumns();
    writeRow(csv, columns);
    md << "| rpm | beads | steady from [s] | snapshots averaged |";
    for (const drum::Metric& m : table()) md << " " << m.label << " [" << m.unit << "] |";
    md << "\n|---|---|---|---|";
    for (size_t i = 0; i < table().size(); ++i) md << "---|";
    md << "\n";
    std::vector<bool> hasData(table().size(), false);
    for (const auto& r : rows) {
        std::vector<std::string> cells;
        for (const std::string& c : columns) cells.push_back(number(get(r, c)));
        writeRow(csv, cells);
        const double steady = get(r, "steady_from_s");
        md << "| " << number(get(r, "rpm")) << " | " << number(get(r, "beads")) << " | "
           << (std::isnan(steady) ? std::string("not steady: last half") : withError(steady, NAN)) << " | "
           << number(get(r, "snapshots")) << " |";
        for (size_t i = 0; i < table().size(); ++i) {
            const double mean = get(r, table()[i].column());
            md << " " << withError(mean, get(r, table()[i].seColumn())) << " |";
            hasData[i] = hasData[i] || std::isfinite(mean);
        }
        md << "\n";
    }
    csv.close();
    plotMetrics(out + ".png", out + ".csv", "time-averaged drum metrics against speed (error bars: standard error)",
                "rpm", "drum speed [rpm]", true, hasData, "");
    std::printf("wrote %s.csv, %s.md, %s.png\n", out.c_str(), out.c_str(), out.c_str());
    return 0;
}

// The metric table as CSV: column,unit,description.
int listMetrics()
{
    std::printf("column,unit,description\n");
    for (const drum::Metric& m : table())
        std::printf("%s,%s,\"%s\"\n", m.column().c_str(), m.unit.c_str(), m.description.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{"Drum metrics (see `drum_metrics metrics`) from LIGGGHTS VTK output"};
    app.require_subcommand(1);
    std::string prefix, seriesOut, out = "post/sweep", averaging = "steady";
    double dt = 1e-5, rpm = 0.0, skip = 0.0, until = 1e300;
    std::vector<std::string> files;
    CLI::App* s = app.add_subcommand("series", "metrics of one run over time");
    s->add_option("--prefix", prefix, "bead files are <prefix>_<step>.vtp")->required();
    s->add_option("--dt", dt, "timestep of the run [s]")->check(CLI::PositiveNumber)->capture_default_str();
    s->add_option("--rpm", rpm, "drum speed (sign: direction about +x)")->required();
    s->add_option("--skip", skip, "ignore snapshots before this time [s]")->capture_default_str();
    s->add_option("--until", until, "ignore snapshots after this time [s]");
    s->add_option("--out", seriesOut, "output prefix (default: --prefix)");
    s->add_option("--average", averaging,
                  "steady: from the steady-state start (MSER; else the last half, steady_from_s = nan); "
                  "all: every snapshot in [skip, until] (steady_from_s = the first one's time)")
        ->check(CLI::IsMember({"steady", "all"}))
        ->capture_default_str();
    CLI::App* t = app.add_subcommand("table", "combine runs' averages against speed");
    t->add_option("--out", out, "output prefix")->capture_default_str();
    t->add_option("files", files, "<prefix>_average.csv files")->required();
    CLI::App* l = app.add_subcommand("metrics", "list the metrics (column, unit, description) as CSV");
    std::string fileA, fileB;
    CLI::App* c = app.add_subcommand("compare", "largest position and velocity differences of two snapshots (by bead id)");
    c->add_option("a", fileA, "first .vtp")->required()->check(CLI::ExistingFile);
    c->add_option("b", fileB, "second .vtp")->required()->check(CLI::ExistingFile);
    CLI11_PARSE(app, argc, argv);
    try {
        if (*c) {
            const drum::Difference d = drum::compare(drum::readBed(fileA, 0.0), drum::readBed(fileB, 0.0));
            std::printf("beads %d, max position difference %.6g m, max velocity difference %.6g m/s\n", d.beads,
                        d.position, d.velocity);
            return 0;
        }
        if (*l) return listMetrics();
        if (*s) return series(prefix, seriesOut, dt, rpm, skip, until, averaging == "steady");
        return crossSpeedTable(out, files);
    } catch (const std::exception& e) {
        std::cerr << "drum_metrics: " << e.what() << "\n";
        return 1;
    }
}
