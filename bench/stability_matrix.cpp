// SPDX-License-Identifier: MIT
// Stability matrix (issue 8): the cases where collision methods fail, each run against
// SmartCollision (core pair API per rotation mode, Bullet plugin per contact model)
// and the peers (FCL, libccd, Bullet GJK-EPA, btBoxShape, GImpact). Every cell is a
// measurement of this program. Writes the CSV and the markdown page.
// Usage: stability_matrix [--csv=FILE] [--md=FILE]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "sc_support/csv.h"
#include "stability_common.h"
#include "stability_dynamics.h"
#include "stability_pairs.h"
#include "stability_text.h"

namespace {

using stab::Cell;

std::string number(double x) {
  if (std::isnan(x)) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

void writeCsv(const std::string& path, const std::vector<Cell>& cells) {
  using sc::support::csvField;
  sc::support::CsvFile f(path, "row,column,outcome,value,error,note");
  for (const Cell& c : cells)
    f.row("%s,%s,%s,%s,%s,%s", csvField(c.row).c_str(), csvField(c.column).c_str(),
          csvField(c.outcome).c_str(), number(c.value).c_str(), number(c.error).c_str(),
          csvField(c.note).c_str());
}

/// What a table cell shows: the outcome and its figure (n/a with its reason).
std::string shown(const Cell& c) {
  if (c.outcome == "n/a") return c.note.rfind("n/a", 0) == 0 ? c.note : "n/a (" + c.note + ")";
  char buf[96];
  if (c.column == stab::kTruth) {
    std::snprintf(buf, sizeof buf, "%.6g (%s)", c.value + 0.0, c.note.c_str());
    return buf;
  }
  if (!std::isnan(c.value) && !std::isnan(c.error))
    std::snprintf(buf, sizeof buf, "%s %.4g (err %.2g)", c.outcome.c_str(), c.value + 0.0, c.error + 0.0);
  else if (!std::isnan(c.value))
    std::snprintf(buf, sizeof buf, "%s %.4g", c.outcome.c_str(), c.value + 0.0);
  else
    std::snprintf(buf, sizeof buf, "%s", c.outcome.c_str());
  return buf;
}

bool isSmartCollision(const std::string& column) { return column.rfind("SC ", 0) == 0; }
bool isPeer(const std::string& column) { return !isSmartCollision(column) && column != stab::kTruth; }

void writeMarkdown(const std::string& path, const std::vector<Cell>& cells, double seconds) {
  std::vector<std::string> rows, columns;
  std::map<std::pair<std::string, std::string>, const Cell*> at;
  for (const Cell& c : cells) {
    if (std::find(rows.begin(), rows.end(), c.row) == rows.end()) rows.push_back(c.row);
    if (std::find(columns.begin(), columns.end(), c.column) == columns.end()) columns.push_back(c.column);
    at[{c.row, c.column}] = &c;
  }
  std::ofstream out(path);
  out << stab::kIntro << "\nThis run: " << cells.size() << " cells in " << number(seconds) << " s.\n\n";
  out << "## Matrix\n\n| case |";
  for (const auto& col : columns) out << ' ' << col << " |";
  out << "\n|---|";
  for (std::size_t i = 0; i < columns.size(); ++i) out << "---|";
  out << '\n';
  for (const auto& r : rows) {
    out << "| " << r << " |";
    for (const auto& col : columns) {
      const auto it = at.find({r, col});
      out << ' ' << (it == at.end() ? std::string("MISSING") : shown(*it->second)) << " |";
    }
    out << '\n';
  }
  out << "\n## Cases\n\n";
  for (const auto& r : rows) out << "- **" << r << "**: " << stab::rowDescription(r) << '\n';
  out << "\n## SmartCollision cells that do not pass\n\n";
  int open = 0;
  for (const Cell& c : cells) {
    if (!isSmartCollision(c.column) || c.outcome == "pass" || c.outcome == "n/a") continue;
    ++open;
    out << "- **" << c.row << " / " << c.column << "** (" << c.outcome << "; " << c.note
        << "): " << stab::explanation(c.row, c.column, c.outcome) << '\n';
  }
  if (open == 0) out << "None in this run.\n";
  out << "\n## Measured details of the peers' failures\n\n";
  for (const Cell& c : cells)
    if (isPeer(c.column) && c.outcome != "pass" && c.outcome != "n/a")
      out << "- " << c.row << " / " << c.column << ": " << c.outcome
          << (c.note.empty() ? "" : " - " + c.note) << '\n';
  out << '\n' << stab::kFooter;
}

std::string argument(int argc, char** argv, const char* name, const std::string& fallback) {
  const std::size_t n = std::strlen(name);
  for (int i = 1; i < argc; ++i)
    if (std::strncmp(argv[i], name, n) == 0 && argv[i][n] == '=') return argv[i] + n + 1;
  return fallback;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string root = SC_BENCH_SOURCE_DIR;
  const std::string csv = argument(argc, argv, "--csv", root + "/docs/benchmarks/stability.csv");
  const std::string md = argument(argc, argv, "--md", root + "/docs/stability.md");
  const auto start = std::chrono::steady_clock::now();
  std::printf("pair-level rows\n");
  std::vector<Cell> cells = stab::runPairRows();
  std::printf("dynamics rows\n");
  for (Cell& c : stab::runDynamicsRows()) cells.push_back(std::move(c));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  writeCsv(csv, cells);
  writeMarkdown(md, cells, std::round(seconds));
  std::printf("%zu cells in %.1f s; wrote %s and %s\n", cells.size(), seconds, csv.c_str(), md.c_str());
  return 0;
}
