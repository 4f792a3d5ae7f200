// drum_metrics: drum metrics from LIGGGHTS VTK output (thesis Eq. 3.26-3.28,
// Fig. 3.2-3.6). Every output is generated from the metric table
// (drum::metricTable(), metrics.cpp); `drum_metrics metrics` lists it.
//   drum_metrics series --prefix post/drum_21rpm --dt 1e-5 --rpm 21 [--skip T0] [--until T1]
//                       [--out O] [--average steady|all]
//       O_metrics.csv (time_s,beads,wall_contacts,<metric columns>), O_metrics.png,
//                       [--batch-seconds B] [--cache C]
//       O_average.csv (rpm,beads,steady_from_s,snapshots,batches,<metric column, its _se_ column>...)
//   drum_metrics steady --prefix P --dt DT --rpm RPM --batch-seconds B [--target Hc=0.0003 ...]
//                       [--min-batches 5] [--confidence 0] [--skip T0] [--cache C]
//       the stop rule: one CSV row settled,steady_from_s,snapshots,batches,done,se_factor,<metric>,<metric>_se_<unit>...
//   drum_metrics table --out post/sweep post/drum_*rpm_average.csv
//       the averages by column name, one row per run sorted by rpm: O.csv, O.md, O.png
//   drum_metrics metrics
//       the metric table as CSV (key,column,se_column,unit,label,description)
//   drum_metrics compare a.vtp b.vtp
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "cli.h"
#include "metrics.h"
#include "plot.h"

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
    std::vector<std::string> c = {"rpm", "beads", "steady_from_s", "snapshots", "batches"};
    for (const drum::Metric& m : table()) c.push_back(m.column()), c.push_back(m.seColumn());
    return c;
}

void writeRow(std::ostream& out, const std::vector<std::string>& cells)
{
    for (size_t i = 0; i < cells.size(); ++i) out << (i ? "," : "") << cells[i];
    out << "\n";
}

std::string number(double x, int digits = 10)
{
    if (std::isnan(x)) return "nan";
    std::ostringstream s;
    s.precision(digits);
    s << x;
    return s.str();
}

// The cells of one CSV line (no quoting: every file read here is written by this tool or LIGGGHTS).
std::vector<std::string> cells(const std::string& line)
{
    std::vector<std::string> c;
    std::string cell;
    for (std::stringstream ss(line); std::getline(ss, cell, ',');) c.push_back(cell);
    return c;
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

// The chart of a CSV of this tool (tools/plot.py KIND: drum-series or
// drum-table): one panel per metric, each axis its label and unit from the
// metric table; `options`: plot.py's others. True if drawn (else a warning).
bool plotMetrics(const std::string& kind, const std::string& csv, const std::string& png, const std::string& title,
                 std::vector<std::string> options = {})
{
    options.insert(options.end(), {"--title", title});
    for (const drum::Metric& m : table())
        options.insert(options.end(), {"--label", m.column() + "=" + m.label + " [" + m.unit + "]"});
    return tools::plot("drum_metrics", kind, csv, png, options);
}

// The finite values of v[from:] (a snapshot where a metric is undefined,
// e.g. no zero crossing of the velocity profile, does not count for it).
std::vector<double> finiteTail(const std::vector<double>& v, int from)
{
    std::vector<double> out;
    std::copy_if(v.begin() + from, v.end(), std::back_inserter(out), [](double x) { return std::isfinite(x); });
    return out;
}

// The metrics cache (--cache FILE): one row per snapshot, step,time_s,beads,
// wall_contacts,<metric columns>. A long run re-checks its stop rule after
// every segment without re-reading every snapshot, and a study resumed on
// another machine keeps the series of snapshots it no longer has.
using Cache = std::map<long, drum::BedMetrics>;

std::vector<std::string> cacheColumns()
{
    std::vector<std::string> c = {"step", "time_s", "beads", "wall_contacts"};
    for (const drum::Metric& m : table()) c.push_back(m.column());
    return c;
}

// A cache written before metrics were added to the end of the table is read
// with nan for those; its rows are listed in `older`, to be measured afresh
// where their snapshot is still on disk.
Cache readCache(const std::string& file, std::set<long>& older)
{
    Cache cache;
    std::ifstream in(file);
    if (!in) return cache;  // none yet
    std::string line;
    std::getline(in, line);
    const std::vector<std::string> names = cells(line), columns = cacheColumns();
    const bool prefix = names.size() > 4 && names.size() <= columns.size() &&
                        std::equal(names.begin(), names.end(), columns.begin());
    if (!prefix)
        throw std::runtime_error("metrics cache " + file + " has other columns than this drum_metrics' metric table (" +
                                 line + "); without it the snapshots still on disk are measured afresh, and "
                                 "the series of those that are gone is lost");
    for (int n = 2; std::getline(in, line); ++n) {
        if (line.empty()) continue;
        std::vector<double> v;
        for (const std::string& cell : cells(line)) v.push_back(parseNumber(cell, file));
        if (v.size() != names.size())
            throw std::runtime_error("metrics cache " + file + ", line " + std::to_string(n) + ": " +
                                     std::to_string(v.size()) + " cells, expected " + std::to_string(names.size()));
        drum::BedMetrics m;
        m.time = v[1], m.beads = int(v[2]), m.wallContacts = int(v[3]);
        m.values.assign(v.begin() + 4, v.end());
        m.values.resize(table().size(), NAN);
        cache[std::lround(v[0])] = m;
        if (names.size() < columns.size()) older.insert(std::lround(v[0]));
    }
    return cache;
}

void writeCache(const std::string& file, const Cache& cache)
{
    // all the digits: the cache's values equal freshly measured ones exactly
    const auto exact = [](double x) { return number(x, std::numeric_limits<double>::max_digits10); };
    const std::string tmp = file + ".tmp";  // whole or not at all: a run may be interrupted here
    {
        std::ofstream out(tmp);
        writeRow(out, cacheColumns());
        for (const auto& [step, m] : cache) {
            std::vector<std::string> row = {std::to_string(step), exact(m.time), std::to_string(m.beads),
                                            std::to_string(m.wallContacts)};
            for (double x : m.values) row.push_back(exact(x));
            writeRow(out, row);
        }
        if (!out) throw std::runtime_error("cannot write " + tmp);
    }
    fs::rename(tmp, file);
}

// The metrics of the snapshots of `prefix` between skip and until (at least
// 2); with a cache file, snapshots measured before are read from it (also
// those whose files are gone) and the new ones are added to it.
std::vector<drum::BedMetrics> measureRun(const std::string& prefix, double dt, double rpm, double skip, double until,
                                         const std::string& cacheFile = "")
{
    const double omega = rpm * 2.0 * M_PI / 60.0;
    std::set<long> older;
    Cache cache = cacheFile.empty() ? Cache{} : readCache(cacheFile, older);
    for (const auto& [step, m] : cache)
        if (std::fabs(m.time - step * dt) > 1e-9 * std::fabs(step * dt))
            throw std::runtime_error("metrics cache " + cacheFile + " has step " + std::to_string(step) + " at t = " +
                                     number(m.time) + " s: it was measured with another --dt than " + number(dt));
    bool added = !older.empty();  // rewritten with every column
    std::vector<std::pair<long, fs::path>> files;
    try {
        files = beadFiles(prefix);
    } catch (const std::runtime_error&) {
        if (cache.empty()) throw;  // the cache may hold every snapshot
    }
    for (const auto& [step, file] : files) {
        if (cache.count(step) && !older.count(step)) continue;
        cache[step] = drum::measureBed(drum::readBed(file.string(), step * dt), omega);
        added = true;
    }
    if (added && !cacheFile.empty()) writeCache(cacheFile, cache);
    std::vector<drum::BedMetrics> ms;
    for (const auto& [step, m] : cache) {
        if (m.time < skip || m.time > until) continue;
        ms.push_back(m);
    }
    if (ms.size() < 2)
        throw std::runtime_error("found " + std::to_string(ms.size()) + " snapshot(s) of " + prefix + " between " +
                                 number(skip) + " and " + number(until) +
                                 " s (--skip, --until, --dt); a time series and its averages need at least 2");
    return ms;
}

// --batch-seconds as a whole number of snapshots (0: none given, 5 batches),
// rounded to the nearest: a drum revolution (60/rpm s) is rarely a multiple
// of the snapshot spacing, and a batch a fraction of a spacing short of it
// still spans the revolution's correlations. At least 10 snapshots, so the
// rounding changes the batch by under 5 %.
int batchSamples(double batchSeconds, const std::vector<drum::BedMetrics>& ms)
{
    if (batchSeconds <= 0.0) return 0;
    const double spacing = ms[1].time - ms[0].time;
    const double k = batchSeconds / spacing;
    if (std::round(k) < 10)
        throw std::runtime_error("--batch-seconds " + number(batchSeconds) + " holds " + number(k) +
                                 " snapshots (spacing " + number(spacing) +
                                 " s); a batch needs at least 10: dump more often");
    return static_cast<int>(std::round(k));
}

// The series of the metrics the steady-state detection watches.
std::vector<std::vector<double>> watchedSeries(const std::vector<drum::BedMetrics>& ms)
{
    std::vector<std::vector<double>> watched;
    for (size_t i = 0; i < table().size(); ++i) {
        if (!table()[i].steadiness) continue;
        watched.emplace_back();
        for (const drum::BedMetrics& m : ms) watched.back().push_back(m.values[i]);
    }
    return watched;
}

int series(const std::string& prefix, const std::string& outPrefix, double dt, double rpm, double skip, double until,
           bool steady, double batchSeconds, const std::string& cacheFile)
{
    const std::vector<drum::BedMetrics> ms = measureRun(prefix, dt, rpm, skip, until, cacheFile);
    const int batchSize = batchSamples(batchSeconds, ms);
    const std::string out = outPrefix.empty() ? prefix : outPrefix;
    const std::string csvFile = out + "_metrics.csv";
    std::ofstream csv(csvFile);
    std::vector<std::string> header = {"time_s", "beads", "wall_contacts"};
    for (const drum::Metric& m : table()) header.push_back(m.column());
    writeRow(csv, header);
    std::vector<std::vector<double>> values(table().size());
    for (const drum::BedMetrics& m : ms) {
        std::vector<std::string> row = {number(m.time), std::to_string(m.beads), std::to_string(m.wallContacts)};
        for (size_t i = 0; i < table().size(); ++i) {
            row.push_back(number(m.values[i]));
            values[i].push_back(m.values[i]);
        }
        writeRow(csv, row);
    }
    csv.close();

    std::printf("%s: %zu snapshots, %d beads, %.3f to %.3f s\n", prefix.c_str(), ms.size(), ms.back().beads,
                ms.front().time, ms.back().time);
    int start = 0;
    double tSteady = ms.front().time;
    if (steady) {
        start = drum::steadyStart(watchedSeries(ms));
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
                                    std::to_string(int(ms.size()) - from), ""};
    int batches = std::numeric_limits<int>::max();
    for (size_t i = 0; i < table().size(); ++i) {
        const std::vector<double> tail = finiteTail(values[i], from);
        const drum::Average a = batchSize > 0 ? drum::average(tail, 0, batchSize) : drum::average(tail, 0);
        batches = std::min(batches, a.batches);
        const std::string name = table()[i].label + " [" + table()[i].unit + "]";
        std::printf("  %-36s %12.6g +- %.2g", name.c_str(), a.mean, a.stdError);
        if (tail.size() + from < values[i].size())
            std::printf("  (%zu of %zu snapshots defined)", tail.size(), values[i].size() - from);
        std::printf("\n");
        row.push_back(number(a.mean)), row.push_back(number(a.stdError));
    }
    row[4] = std::to_string(batches);
    std::ofstream avg(out + "_average.csv");
    writeRow(avg, averageColumns());
    writeRow(avg, row);

    const std::string title = fs::path(prefix).filename().string() + ": " + number(rpm) + " rpm" +
                              (!steady ? ", all snapshots averaged"
                                       : start >= 0 ? ", dashed: steady state" : ", not steady yet");
    const bool drawn = plotMetrics("drum-series", csvFile, out + "_metrics.png", title,
                                   steady && start >= 0 ? std::vector<std::string>{"--steady-from", number(tSteady)}
                                                        : std::vector<std::string>{});
    std::printf("wrote %s_metrics.csv, %s%s_average.csv\n", out.c_str(),
                drawn ? (out + "_metrics.png, ").c_str() : "", out.c_str());
    return 0;
}

// The rows of an average file as {column name: value}, by its header.
std::vector<std::map<std::string, double>> readAverages(const std::string& file)
{
    std::ifstream in(file);
    if (!in) throw std::runtime_error("cannot read " + file);
    std::string line;
    std::getline(in, line);
    const std::vector<std::string> names = cells(line);
    std::vector<std::map<std::string, double>> rows;
    while (std::getline(in, line)) {
        if (line.empty()) continue;
        std::map<std::string, double> row;
        const std::vector<std::string> c = cells(line);
        for (size_t i = 0; i < c.size() && i < names.size(); ++i) row[names[i]] = parseNumber(c[i], file);
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
        }
        md << "\n";
    }
    csv.close();
    md.close();
    const bool drawn = plotMetrics("drum-table", out + ".csv", out + ".png",
                                   "time-averaged drum metrics against speed (error bars: standard error)");
    std::printf("wrote %s.csv, %s.md%s\n", out.c_str(), out.c_str(), drawn ? (", " + out + ".png").c_str() : "");
    return 0;
}

// "key=value" targets by metric key (default: Hc 0.3 mm, angle 0.3 deg).
std::vector<std::pair<size_t, double>> parseTargets(const std::vector<std::string>& specs)
{
    const std::vector<std::string> given = specs.empty() ? std::vector<std::string>{"Hc=0.0003", "angle=0.3"} : specs;
    std::vector<std::pair<size_t, double>> targets;
    for (const std::string& s : given) {
        const size_t eq = s.find('=');
        const std::string key = s.substr(0, eq);
        size_t i = 0;
        while (i < table().size() && table()[i].key != key) ++i;
        if (i == table().size()) {
            std::string keys;
            for (const drum::Metric& m : table()) keys += (keys.empty() ? "" : ", ") + m.key;
            throw std::runtime_error("--target " + s + ": unknown metric '" + key + "' (keys: " + keys + ")");
        }
        double se = NAN;
        try {
            se = eq == std::string::npos ? NAN : std::stod(s.substr(eq + 1));
        } catch (const std::exception&) {
        }
        if (!(se > 0.0)) throw std::runtime_error("--target " + s + ": expected " + key + "=<standard error > 0>");
        targets.emplace_back(i, se);
    }
    return targets;
}

// The stop rule on one run: one CSV row on stdout.
int steadyVerdict(const std::string& prefix, double dt, double rpm, double skip, double batchSeconds,
                  const std::vector<std::string>& targetSpecs, int minBatches, double confidence,
                  const std::string& cacheFile)
{
    const std::vector<std::pair<size_t, double>> targeted = parseTargets(targetSpecs);
    drum::checkConfidence(confidence);  // before any snapshot is read
    const std::vector<drum::BedMetrics> ms = measureRun(prefix, dt, rpm, skip, 1e300, cacheFile);
    const int batchSize = batchSamples(batchSeconds, ms);
    std::vector<drum::Target> targets;
    for (const auto& [i, se] : targeted) {
        targets.push_back({{}, se});
        for (const drum::BedMetrics& m : ms) targets.back().series.push_back(m.values[i]);
    }
    const drum::Verdict v = drum::stopRule(watchedSeries(ms), targets, batchSize, minBatches, confidence);
    std::vector<std::string> header = {"settled", "steady_from_s", "snapshots", "batches", "done", "se_factor"};
    std::vector<std::string> row = {v.settled ? "1" : "0", v.settled ? number(ms[v.from].time) : "nan",
                                    std::to_string(int(ms.size()) - v.from), std::to_string(v.batches),
                                    v.done ? "1" : "0", number(v.seFactor)};
    for (size_t k = 0; k < targeted.size(); ++k) {
        const drum::Metric& m = table()[targeted[k].first];
        header.push_back(m.column()), header.push_back(m.seColumn());
        row.push_back(number(v.averages[k].mean)), row.push_back(number(v.averages[k].stdError));
    }
    writeRow(std::cout, header);
    writeRow(std::cout, row);
    return 0;
}

// The metric table as CSV: key,column,se_column,unit,label,description (what
// scripts and documents need to show a metric without listing it again).
int listMetrics()
{
    std::printf("key,column,se_column,unit,label,description\n");
    for (const drum::Metric& m : table())
        std::printf("%s,%s,%s,%s,\"%s\",\"%s\"\n", m.key.c_str(), m.column().c_str(), m.seColumn().c_str(),
                    m.unit.c_str(), m.label.c_str(), m.description.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{"Drum metrics (see `drum_metrics metrics`) from LIGGGHTS VTK output"};
    app.require_subcommand(1);
    std::string prefix, seriesOut, out = "post/sweep", averaging = "steady", cacheFile;
    const std::string cacheHelp = "metrics cache (CSV): snapshots in it are not read again, new ones are added; "
                                  "it keeps the series of snapshots whose files are gone";
    double dt = 1e-5, rpm = 0.0, skip = 0.0, until = 1e300;
    std::vector<std::string> files;
    CLI::App* s = app.add_subcommand("series", "metrics of one run over time");
    s->add_option("--prefix", prefix, "bead files are <prefix>_<step>.vtp")->required();
    s->add_option("--dt", dt, "timestep of the run [s]")->check(tools::check(tools::kPositive))->capture_default_str();
    s->add_option("--rpm", rpm, "drum speed (sign: direction about +x)")->required();
    s->add_option("--skip", skip, "ignore snapshots before this time [s]")->capture_default_str();
    s->add_option("--until", until, "ignore snapshots after this time [s]");
    s->add_option("--out", seriesOut, "output prefix (default: --prefix)");
    s->add_option("--average", averaging,
                  "steady: from the steady-state start (MSER; else the last half, steady_from_s = nan); "
                  "all: every snapshot in [skip, until] (steady_from_s = the first one's time)")
        ->check(CLI::IsMember({"steady", "all"}))
        ->capture_default_str();
    double batchSeconds = 0.0;
    s->add_option("--batch-seconds", batchSeconds,
                  "batch means over batches of this many seconds (e.g. a revolution, 60/rpm; a multiple of the "
                  "snapshot spacing) instead of 5 batches")
        ->check(tools::check(tools::kPositive));
    s->add_option("--cache", cacheFile, cacheHelp);
    std::vector<std::string> targetSpecs;
    int minBatches = 5;
    double confidence = 0.0;
    CLI::App* st = app.add_subcommand("steady", "the stop rule: settled, and the target standard errors reached?");
    st->add_option("--prefix", prefix, "bead files are <prefix>_<step>.vtp")->required();
    st->add_option("--dt", dt, "timestep of the run [s]")->check(tools::check(tools::kPositive))->capture_default_str();
    st->add_option("--rpm", rpm, "drum speed (sign: direction about +x)")->required();
    st->add_option("--batch-seconds", batchSeconds, "batch length [s] (a multiple of the snapshot spacing)")
        ->required()
        ->check(tools::check(tools::kPositive));
    st->add_option("--target", targetSpecs, "KEY=SE in the metric's unit (default: Hc=0.0003 angle=0.3)");
    st->add_option("--min-batches", minBatches, "fewest whole batches for done")->capture_default_str();
    st->add_option("--confidence", confidence,
                   "0: each SE as estimated within its target; e.g. 0.95: its 95 % upper confidence bound (chi-square "
                   "over the batches' degrees of freedom) within it")
        ->check(CLI::Range(0.0, 1.0))  // (1 itself: the library names it)
        ->capture_default_str();
    st->add_option("--skip", skip, "ignore snapshots before this time [s]")->capture_default_str();
    st->add_option("--cache", cacheFile, cacheHelp);
    CLI::App* t = app.add_subcommand("table", "combine runs' averages against speed");
    t->add_option("--out", out, "output prefix")->capture_default_str();
    t->add_option("files", files, "<prefix>_average.csv files")->required();
    CLI::App* l = app.add_subcommand("metrics", "list the metrics (key, columns, unit, label, description) as CSV");
    std::string fileA, fileB;
    CLI::App* c = app.add_subcommand("compare", "largest position and velocity differences of two snapshots (by bead id)");
    c->add_option("a", fileA, "first .vtp")->required();
    c->add_option("b", fileB, "second .vtp")->required();
    if (const std::optional<int> done = tools::parse(app, "drum_metrics", argc, argv)) return *done;
    try {
        if (*c) {
            // a named file that is missing: an error of the work (1), not of the usage
            for (const std::string& f : {fileA, fileB})
                if (!fs::exists(f)) throw std::runtime_error(f + ": no such file");
            const drum::Difference d = drum::compare(drum::readBed(fileA, 0.0), drum::readBed(fileB, 0.0));
            std::printf("beads %d, max position difference %.6g m, max velocity difference %.6g m/s\n", d.beads,
                        d.position, d.velocity);
            return 0;
        }
        if (*l) return listMetrics();
        if (*s) return series(prefix, seriesOut, dt, rpm, skip, until, averaging == "steady", batchSeconds, cacheFile);
        if (*st) return steadyVerdict(prefix, dt, rpm, skip, batchSeconds, targetSpecs, minBatches, confidence, cacheFile);
        return crossSpeedTable(out, files);
    } catch (const std::exception& e) {
        std::cerr << "drum_metrics: " << e.what() << "\n";
        return 1;
    }
}
