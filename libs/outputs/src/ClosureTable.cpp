#include <lodestone/io/CsvTable.h>
#include <lodestone/outputs/ClosureTable.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace lodestone::outputs {

namespace {
constexpr const char* kHeader =
    "from_node,to_node,from_time,to_time,source,match_id,score,strong,hypothesis,kept,"
    "x,y,z,yaw,pitch,roll,cov_xx,cov_xy,cov_xz,cov_yy,cov_yz,cov_zz";
constexpr std::size_t kColumnsBeforeCovariance = 16;  // logs written before 2026-11-27
constexpr std::size_t kColumns = 22;
constexpr std::size_t kSourceColumn = 4;
}  // namespace

void writeClosureTable(const std::string& path, const std::vector<ClosureRow>& rows) {
    std::ofstream out(path);
    if (!out) throw std::runtime_error(path + ": cannot write the closure log");
    out << kHeader << "\n";
    char line[768];
    for (const auto& r : rows) {
        const auto& m = r.measured;
        const auto& C = r.translationCovariance;
        std::snprintf(line, sizeof line,
                      "%llu,%llu,%.6f,%.6f,%s,%zu,%.6g,%d,%d,%d,%.6f,%.6f,%.6f,%.8f,%.8f,%.8f,"
                      "%.6g,%.6g,%.6g,%.6g,%.6g,%.6g\n",
                      static_cast<unsigned long long>(r.fromNode),
                      static_cast<unsigned long long>(r.toNode), r.fromTime, r.toTime,
                      r.source.c_str(), r.matchId, r.score, r.strong ? 1 : 0,
                      r.hypothesis ? 1 : 0, r.kept ? 1 : 0, m.x(), m.y(), m.z(), m.yaw(),
                      m.pitch(), m.roll(), C(0, 0), C(0, 1), C(0, 2), C(1, 1), C(1, 2), C(2, 2));
        out << line;
    }
    if (!out) throw std::runtime_error(path + ": write failed");
}

std::vector<ClosureRow> readClosureTable(const std::string& path) {
    {
        std::ifstream in(path);
        std::string header;
        if (!in) throw std::runtime_error(path + ": cannot open closure log");
        if (!std::getline(in, header) || header.rfind("from_node,to_node,", 0) != 0)
            throw std::runtime_error(path + ": line 1: not a lodestone-slam closures.csv header");
    }
    // (the width of the first data row: either format; every row must match it)
    const auto table = io::CsvTable::read(path, 0, 1, {kSourceColumn});
    if (table.rows() > 0 && table.columns() != kColumns &&
        table.columns() != kColumnsBeforeCovariance) {
        throw std::runtime_error(path + ": line " + std::to_string(table.lineOf(0)) + ": " +
                                 std::to_string(table.columns()) + " columns, expected " +
                                 std::to_string(kColumns) + " (or " +
                                 std::to_string(kColumnsBeforeCovariance) +
                                 " in a log without covariances)");
    }
    std::vector<ClosureRow> out;
    for (std::size_t i = 0; i < table.rows(); ++i) {
        const auto v = [&](std::size_t column) {
            const double x = table.at(i, column);
            if (!std::isfinite(x)) {
                throw std::runtime_error(path + ": line " + std::to_string(table.lineOf(i)) +
                                         ": column " + std::to_string(column + 1) +
                                         " is not a finite number");
            }
            return x;
        };
        ClosureRow r;
        r.fromNode = static_cast<long long>(v(0));
        r.toNode = static_cast<long long>(v(1));
        r.fromTime = v(2);
        r.toTime = v(3);
        r.source = table.text(i, kSourceColumn);
        r.matchId = static_cast<std::size_t>(v(5));
        r.score = v(6);
        r.strong = v(7) != 0;
        r.hypothesis = v(8) != 0;
        r.kept = v(9) != 0;
        r.measured = mrpt::poses::CPose3D(v(10), v(11), v(12), v(13), v(14), v(15));
        if (table.columns() == kColumns) {
            // (a closure whose information could not be inverted wrote NaN: kept as unknown)
            const auto c = [&](std::size_t column) { return table.at(i, column); };
            r.translationCovariance << c(16), c(17), c(18), c(17), c(19), c(20), c(18), c(20),
                c(21);
        }
        out.push_back(r);
    }
    return out;
}

}  // namespace lodestone::outputs
