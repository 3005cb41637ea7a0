// The record schemas (bench/harness/record_schemas.h): one table per record file gives its
// header, its rows and docs/records.md, so the documentation must be the generated text, every
// file a run writes must be documented with the header it has, and a cell must be formatted as
// CsvWriter formats its type.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "harness/record_schemas.h"
#include "harness/records_doc.h"
#include "source_tree.h"

namespace cb::harness {
namespace {

const std::filesystem::path kRepository = ::cb::testing_support::SourceRoot();

std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

std::string FirstLine(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

std::string Joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ",") + n;
  return out;
}

// The header a documented file has for a body of dimension `dimension`.
std::string DocumentedHeader(const RecordDoc& doc, int dimension) {
  std::vector<std::string> names;
  for (const ColumnDoc& c : doc.columns) {
    if (ColumnWritten(c.only_3d, dimension)) names.push_back(c.name);
  }
  return Joined(names);
}

TEST(RecordsSchemaTest, DocsRecordsMdHoldsTheGeneratedTables) {
  const std::string text = ReadText(kRepository / "docs" / "records.md");
  const std::string begin = "<!-- BEGIN contactbench schema -->\n";
  const std::string end = "<!-- END contactbench schema -->";
  const auto from = text.find(begin);
  const auto to = text.find(end);
  ASSERT_NE(from, std::string::npos);
  ASSERT_NE(to, std::string::npos);
  ASSERT_LT(from, to);
  EXPECT_EQ(text.substr(from + begin.size(), to - from - begin.size()), RecordsMarkdown())
      << "docs/records.md is out of date: run scripts/update_records_doc.sh "
         "build/bin/contactbench";
}

TEST(RecordsSchemaTest, EveryColumnIsNamedOnceAndExplained) {
  for (const RecordDoc& doc : RecordDocs()) {
    EXPECT_FALSE(doc.one_row_per.empty()) << doc.file;
    EXPECT_FALSE(doc.written_by.empty()) << doc.file;
    std::set<std::string> names;
    for (const ColumnDoc& c : doc.columns) {
      EXPECT_TRUE(names.insert(c.name).second) << doc.file << ": " << c.name << " twice";
      EXPECT_FALSE(c.meaning.empty()) << doc.file << ": " << c.name;
      // A '|' would end the markdown table's cell.
      EXPECT_EQ(c.meaning.find('|'), std::string::npos) << doc.file << ": " << c.name;
    }
  }
}

// Runs the suite driver; its exit status.
int Contactbench(const std::string& arguments) {
  const std::string command =
      std::string(CONTACTBENCH_BINARY) + " " + arguments + " >/dev/null 2>&1";
  const int raw = std::system(command.c_str());
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

// Every CSV file in `dir` is documented, with the header the file has.
void ExpectDocumented(const std::filesystem::path& dir, int dimension) {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".csv") continue;
    ++files;
    const std::string file = entry.path().filename().string();
    const std::string header = FirstLine(entry.path());
    std::vector<std::string> documented;
    for (const RecordDoc& doc : RecordDocs()) {
      if (doc.file == file) documented.push_back(DocumentedHeader(doc, dimension));
    }
    ASSERT_FALSE(documented.empty()) << dir << ": " << file << " is not documented";
    EXPECT_NE(std::find(documented.begin(), documented.end(), header), documented.end())
        << dir << ": " << file << " has the header " << header
        << ", documented: " << documented.front();
  }
  EXPECT_GT(files, 0) << dir;
}

TEST(RecordsSchemaTest, EveryFileOfARunOrAComparisonIsDocumentedWithItsHeader) {
  const auto root = std::filesystem::temp_directory_path() / "contactbench_records_schema";
  std::filesystem::remove_all(root);
  const auto examples = kRepository / "examples";
  struct Case {
    std::string name;
    std::string arguments;
    int dimension;
  } cases[] = {
      {"body-2d",
       "run --problem two-bar-obstacle --formulation implicit-fb --steps 20 --save-every 10", 2},
      {"body-3d",
       "run --problem-file " + (examples / "truss-3d-tripod.json").string() +
           " --formulation implicit-fb --save-every 1",
       3},
      {"lcp",
       "run --problem-file " + (examples / "lcp-dense-2x2.json").string() +
           " --formulation implicit-fb",
       0},
      {"compare", "compare --problem two-bar-obstacle --formulations implicit-fb --steps 5", 2},
  };
  for (const Case& c : cases) {
    const auto out = root / c.name;
    ASSERT_EQ(Contactbench(c.arguments + " --out " + out.string()), 0) << c.arguments;
    SCOPED_TRACE(c.name);
    ExpectDocumented(out, c.dimension);
  }
  std::filesystem::remove_all(root);
}

// A row of one cell of each kind, written through a schema and read back.
struct Sample {
  int integer;
  double real;
  bool flag;
  std::string text;
};

TEST(RecordsSchemaTest, CellsAreFormattedAsTheirTypeAndQuotedOnlyWhenNeeded) {
  const RecordSchema<Sample> schema{
      "sample.csv",
      "",
      "sample",
      {"test"},
      {
          {"integer", "an int", [](const Sample& s) -> Cell { return s.integer; }},
          {"real", "a double", [](const Sample& s) -> Cell { return s.real; }},
          {"flag", "a bool", [](const Sample& s) -> Cell { return s.flag; }},
          {"text", "a string", [](const Sample& s) -> Cell { return s.text; }},
          {"z", "3-D only", [](const Sample& s) -> Cell { return s.real; }, true},
      }};
  const auto dir = std::filesystem::temp_directory_path() / "contactbench_records_cells";
  std::filesystem::create_directories(dir);
  {
    RecordWriter<Sample> two_d(dir.string(), schema, 2);
    two_d.Write({-3, 0.1, true, "plain"});
    two_d.Write({7, 1e300, false, "a,\"b\""});
  }
  EXPECT_EQ(ReadText(dir / "sample.csv"),
            "integer,real,flag,text\n-3,0.1,true,plain\n7,1e+300,false,\"a,\"\"b\"\"\"\n");
  {
    RecordWriter<Sample> three_d(dir.string(), schema, 3);
    three_d.Write({0, -2.5, false, ""});
  }
  EXPECT_EQ(ReadText(dir / "sample.csv"), "integer,real,flag,text,z\n0,-2.5,false,,-2.5\n");
  std::filesystem::remove_all(dir);
}

// The records kept in memory (the Python module without an output directory) are the bytes the
// file gets, and no file is made.
TEST(RecordsSchemaTest, RecordsInMemoryAreTheFileSBytes) {
  const RecordSchema<Sample> schema{
      "sample.csv",
      "",
      "sample",
      {"test"},
      {
          {"real", "a double", [](const Sample& s) -> Cell { return s.real; }},
          {"text", "a string", [](const Sample& s) -> Cell { return s.text; }},
      }};
  const std::vector<Sample> rows{
      {0, 1.0, false, "x,y"}, {0, -0.0, false, ""}, {0, 1e-7, true, "q"}};
  const auto dir = std::filesystem::temp_directory_path() / "contactbench_records_memory";
  std::filesystem::create_directories(dir);
  std::map<std::string, std::string> memory{{"sample.csv", "an earlier run's text"}};
  {
    RecordWriter<Sample> file(dir.string(), schema);
    RecordWriter<Sample> kept(RecordTarget(&memory), schema);
    for (const Sample& row : rows) {
      file.Write(row);
      kept.Write(row);
    }
  }
  EXPECT_EQ(memory.at("sample.csv"), ReadText(dir / "sample.csv"));
  EXPECT_EQ(memory.size(), 1u);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  {
    RecordWriter<Sample> kept(RecordTarget(&memory), schema);
    kept.Write(rows[0]);
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir));
  EXPECT_EQ(memory.at("sample.csv"), "real,text\n1.0,\"x,y\"\n");  // emptied first, as O_TRUNC
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cb::harness
