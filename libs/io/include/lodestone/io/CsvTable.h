#pragma once

#include <set>
#include <string>
#include <vector>

namespace lodestone::io {

/** A numeric CSV file read whole: rows of doubles, every row the same width, except the
 * columns named as text (kept as strings, e.g. a label). Errors name the file and the 1-based
 * line: a missing or extra column, or a field that is not a number ("nan" and "inf" are
 * numbers: the sample is kept and judged by whoever uses it). */
class CsvTable {
  public:
    /** Reads `path`. `headerLines` leading lines are skipped (a column-name line);
     * `columns` > 0 demands that width, 0 takes the first data row's. Empty lines are
     * skipped; `textColumns` (0-based) are kept as text (at() gives NaN there). Throws
     * std::runtime_error naming the file and line. */
    static CsvTable read(const std::string& path, std::size_t columns = 0,
                         std::size_t headerLines = 0, const std::set<std::size_t>& textColumns = {});

    const std::string& path() const { return path_; }
    std::size_t rows() const { return values_.size(); }
    std::size_t columns() const { return columns_; }
    double at(std::size_t row, std::size_t column) const { return values_[row][column]; }
    /** A text column's field, as written (empty for a numeric column). */
    const std::string& text(std::size_t row, std::size_t column) const;
    /** The file line a row came from (1-based), for messages about its contents. */
    std::size_t lineOf(std::size_t row) const { return lines_[row]; }

  private:
    std::string path_;
    std::size_t columns_{0};
    std::vector<std::vector<double>> values_;
    std::vector<std::vector<std::string>> texts_;  // empty rows unless text columns were asked
    std::vector<std::size_t> lines_;
};

}  // namespace lodestone::io
