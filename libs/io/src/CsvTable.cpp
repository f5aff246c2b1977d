#include <lodestone/io/CsvTable.h>

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace lodestone::io {

namespace {
std::string where(const std::string& path, std::size_t line) {
    return path + ": line " + std::to_string(line) + ": ";
}

// One field as a double: the whole field (spaces around allowed) must be a number.
double parseField(const std::string& field, const std::string& path, std::size_t line,
                  std::size_t column) {
    const char* begin = field.c_str();
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(begin, &end);
    const auto blank = [](const char* p) {
        while (*p == ' ' || *p == '\t' || *p == '\r') ++p;
        return *p == '\0';
    };
    if (end == begin || !blank(end) || blank(begin)) {
        throw std::runtime_error(where(path, line) + "column " + std::to_string(column + 1) +
                                 ": '" + field + "' is not a number");
    }
    return v;  // ERANGE gives +-HUGE_VAL or 0: an out-of-range reading, kept as infinite
}
}  // namespace

CsvTable CsvTable::read(const std::string& path, std::size_t columns, std::size_t headerLines,
                        const std::set<std::size_t>& textColumns) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open");
    CsvTable t;
    t.path_ = path;
    t.columns_ = columns;
    std::string text;
    for (std::size_t line = 1; std::getline(in, text); ++line) {
        if (line <= headerLines) continue;
        if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
        std::vector<double> row;
        std::vector<std::string> texts;
        std::size_t start = 0;
        for (;;) {
            const auto comma = text.find(',', start);
            const std::string field =
                text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
            if (textColumns.count(row.size())) {
                texts.resize(row.size() + 1);
                texts.back() = field;
                row.push_back(std::numeric_limits<double>::quiet_NaN());
            } else {
                row.push_back(parseField(field, path, line, row.size()));
            }
            if (comma == std::string::npos) break;
            start = comma + 1;
        }
        if (t.columns_ == 0) t.columns_ = row.size();
        if (row.size() != t.columns_) {
            throw std::runtime_error(where(path, line) + "expected " + std::to_string(t.columns_) +
                                     " columns, found " + std::to_string(row.size()));
        }
        if (!textColumns.empty()) texts.resize(row.size());
        t.values_.push_back(std::move(row));
        t.texts_.push_back(std::move(texts));
        t.lines_.push_back(line);
    }
    if (in.bad()) throw std::runtime_error(path + ": read error");
    return t;
}

const std::string& CsvTable::text(std::size_t row, std::size_t column) const {
    static const std::string none;
    const auto& t = texts_.at(row);
    return column < t.size() ? t[column] : none;
}

}  // namespace lodestone::io
