// The text of the records as a reader sees it: a column of doubles reads as reals in every
// file, whatever its values, and a problem file's nodes and obstacles keep their own names.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/csv.h"
#include "run_example.h"

namespace {

using cb::test_support::RunExample;

using cb::FormatReal;

TEST(FormatRealTest, AnIntegralValueIsMarkedAsReal) {
  EXPECT_EQ(FormatReal(1.0), "1.0");
  EXPECT_EQ(FormatReal(0.0), "0.0");
  EXPECT_EQ(FormatReal(-0.0), "-0.0");
  EXPECT_EQ(FormatReal(-40.0), "-40.0");
  EXPECT_EQ(FormatReal(1e22), "1e+22");  // an exponent reads as a real already
  EXPECT_EQ(FormatReal(0.5), "0.5");
  EXPECT_EQ(FormatReal(std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(FormatReal(-std::numeric_limits<double>::infinity()), "-inf");
}

TEST(FormatRealTest, EveryTextReadsBackToTheSameValue) {
  for (double v : {1.0, -0.0, 3.0e15, 123456789.0, 0.1, 1.0 / 3.0, 1e-300, 6.02214076e23}) {
    const std::string text = FormatReal(v);
    EXPECT_EQ(std::strtod(text.c_str(), nullptr), v) << text;
    EXPECT_EQ(std::signbit(std::strtod(text.c_str(), nullptr)), std::signbit(v)) << text;
    EXPECT_NE(text.find_first_of(".e"), std::string::npos) << text;
  }
}

// The rows of a CSV file without quoted fields, by column name.
std::vector<std::map<std::string, std::string>> ReadCsv(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> fields;
    std::stringstream s(line);
    for (std::string f; std::getline(s, f, ',');) fields.push_back(f);
    if (header.empty()) {
      header = fields;
      continue;
    }
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < fields.size(); ++i) row[header[i]] = fields[i];
    rows.push_back(row);
  }
  return rows;
}

TEST(RecordsFormatTest, AProblemFilesNodesAndObstaclesKeepTheirIds) {
  // bar-wall: nodes 1, 2, 3 (node 3 against the obstacle "wall").
  const auto dir = RunExample("truss-2d-bar-wall.json", "records_ids", "--save-every 20");
  std::set<std::string> nodes;
  for (const auto& row : ReadCsv(dir / "solution.csv")) nodes.insert(row.at("node"));
  EXPECT_EQ(nodes, (std::set<std::string>{"1", "2", "3"}));
  for (const char* file : {"contacts.csv", "snapshot_contacts.csv"}) {
    const auto rows = ReadCsv(dir / file);
    ASSERT_FALSE(rows.empty()) << file;
    for (const auto& row : rows) {
      EXPECT_EQ(row.at("node"), "3") << file;
      EXPECT_EQ(row.at("obstacle"), "wall") << file;
    }
  }
  std::set<std::string> corners;
  for (const auto& row : ReadCsv(dir / "cells.csv")) corners.insert(row.at("node"));
  EXPECT_EQ(corners, nodes);
  std::filesystem::remove_all(dir);
}

TEST(RecordsFormatTest, AGmshMeshsNodesKeepTheirTags) {
  const auto dir = RunExample("q4-block-gmsh.json", "records_tags");
  std::set<std::string> nodes;
  for (const auto& row : ReadCsv(dir / "solution.csv")) nodes.insert(row.at("node"));
  // The mesh's node tags are 1-6.
  EXPECT_EQ(nodes, (std::set<std::string>{"1", "2", "3", "4", "5", "6"}));
  for (const auto& row : ReadCsv(dir / "contacts.csv")) EXPECT_EQ(row.at("obstacle"), "floor");
  std::filesystem::remove_all(dir);
}

TEST(RecordsFormatTest, ColumnsOfDoublesReadAsRealsEvenWhenIntegral) {
  // A fixed-load LCP: lambda, control_disp, feas_res, step_res and w are exactly 0, and the
  // scales 2 and 6, each of which was written as an integer.
  const auto dir = RunExample("lcp-dense-2x2.json", "records_reals");
  const auto rows = ReadCsv(dir / "steps.csv");
  ASSERT_EQ(rows.size(), 1u);
  for (const char* column : {"lambda", "control_disp", "time_s", "eq_res", "comp_res",
                             "length_scale", "force_scale", "tolerance"}) {
    EXPECT_NE(rows[0].at(column).find_first_of(".en"), std::string::npos)
        << column << " = " << rows[0].at(column);
  }
  for (const char* column : {"step", "iterations", "attempt", "n_contact"}) {
    EXPECT_EQ(rows[0].at(column).find_first_not_of("-0123456789"), std::string::npos)
        << column << " = " << rows[0].at(column);
  }
  EXPECT_EQ(rows[0].at("lambda"), "0.0");
  EXPECT_EQ(rows[0].at("force_scale"), "6.0");
  for (const auto& row : ReadCsv(dir / "solution.csv")) EXPECT_EQ(row.at("w"), "0.0");
  std::filesystem::remove_all(dir);
}

}  // namespace
