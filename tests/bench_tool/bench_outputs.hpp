#pragma once

// Running luxel-bench from a test and reading what it wrote (CSV with RFC 4180 quoting, text).

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "run_command.hpp"
#include "test_paths.hpp"

namespace luxel::testing {

inline CommandResult luxel_bench(const std::string& arguments) {
    return run_command(luxel::testing::program("luxel-bench"), arguments);
}

using CsvRows = std::vector<std::vector<std::string>>;

inline CsvRows read_csv(const std::filesystem::path& path) {
    CsvRows rows;
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) {
        // RFC 4180 cells: quoted ones may hold commas and doubled quotes.
        std::vector<std::string> cells(1);
        bool quoted_cell = false;
        for (std::size_t i = 0; i < line.size(); ++i) {
            const char c = line[i];
            if (quoted_cell && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
                cells.back() += '"';
                ++i;
            } else if (c == '"') {
                quoted_cell = !quoted_cell;
            } else if (c == ',' && !quoted_cell) {
                cells.emplace_back();
            } else {
                cells.back() += c;
            }
        }
        rows.push_back(cells);
    }
    return rows;
}

/// The index of `column` in the header row, or the row's size when it has none.
inline std::size_t column_index(const CsvRows& rows, const std::string& column) {
    const auto& header = rows.at(0);
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), column) -
                                    header.begin());
}

/// The cell as a number; NaN when it is not one (so a finiteness check fails on it).
inline double cell_number(const std::string& cell) {
    try {
        std::size_t used = 0;
        const double v = std::stod(cell, &used);
        return used == cell.size() ? v : std::nan("");
    } catch (const std::exception&) {
        return std::nan("");
    }
}

inline std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
        ++n;
    }
    return n;
}

inline std::string read_text(const std::filesystem::path& path) {
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace luxel::testing
