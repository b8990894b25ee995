// The house rules of docs/architecture.md, checked on the source tree itself: the layers
// include only the layers below them, no header includes itself through others, the pure
// layers spell no command-line flag and touch no file or terminal, no source file outside
// tests/ passes 800 lines, tests never compile or include tools/, and tools/ stays a thin
// layer of flag parsing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace imunoise {
namespace {

namespace fs = std::filesystem;

const fs::path kRoot = IMUNOISE_SOURCE_DIR;

/// The source folders, lowest first, and the folders each may include from (itself included).
const std::map<std::string, std::set<std::string>>& allowed_includes() {
  static const std::map<std::string, std::set<std::string>> allowed{
      {"common", {"common"}},
      {"analysis", {"common", "analysis"}},
      {"models", {"common", "models"}},
      {"ins", {"common", "models", "ins"}},
      {"pipeline", {"common", "analysis", "models", "ins", "pipeline"}},
      {"io", {"common", "analysis", "models", "ins", "pipeline", "io"}},
      {"report", {"common", "analysis", "models", "ins", "pipeline", "io", "report"}},
      {"tools", {"common", "analysis", "models", "ins", "pipeline", "io", "report", "tools"}},
      // The Python module: bindings over the layers below report, like a second front end.
      {"python", {"common", "analysis", "models", "ins", "pipeline", "io", "python"}},
  };
  return allowed;
}

const std::set<std::string> kPureLayers{"common", "analysis", "models", "ins", "pipeline"};

std::vector<fs::path> sources_in(const std::string& folder) {
  std::vector<fs::path> out;
  for (const auto& entry : fs::directory_iterator(kRoot / folder)) {
    const std::string ext = entry.path().extension().string();
    if (entry.is_regular_file() && (ext == ".cpp" || ext == ".h")) out.push_back(entry.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::string> lines_of(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// The project headers FILE includes with quotes ("io/recording.h" → folder/name).
std::vector<std::string> quoted_includes(const fs::path& file) {
  static const std::regex include(R"re(^\s*#\s*include\s+"([a-z_]+/[A-Za-z0-9_./]+)")re");
  std::vector<std::string> out;
  for (const std::string& line : lines_of(file)) {
    std::smatch m;
    if (std::regex_search(line, m, include)) out.push_back(m[1]);
  }
  return out;
}

std::string repo_path(const fs::path& p) { return fs::relative(p, kRoot).generic_string(); }

TEST(Layering, EachLayerIncludesOnlyTheLayersBelowIt) {
  for (const auto& [folder, allowed] : allowed_includes()) {
    for (const fs::path& file : sources_in(folder)) {
      for (const std::string& header : quoted_includes(file)) {
        const std::string from = header.substr(0, header.find('/'));
        EXPECT_TRUE(allowed.count(from)) << repo_path(file) << " includes " << header;
      }
    }
  }
}

/// A depth-first search of GRAPH; one test failure per cycle found, naming it.
void expect_no_cycle(const std::map<std::string, std::set<std::string>>& graph,
                     const std::string& what) {
  std::map<std::string, int> state;  // 0 new, 1 on the path, 2 done
  std::vector<std::string> path;
  const std::function<void(const std::string&)> visit = [&](const std::string& node) {
    state[node] = 1;
    path.push_back(node);
    if (const auto it = graph.find(node); it != graph.end()) {
      for (const std::string& next : it->second) {
        if (state[next] == 1) {
          std::string cycle;
          for (auto p = std::find(path.begin(), path.end(), next); p != path.end(); ++p) {
            cycle += *p + " -> ";
          }
          ADD_FAILURE() << what << " cycle: " << cycle << next;
        } else if (state[next] == 0) {
          visit(next);
        }
      }
    }
    path.pop_back();
    state[node] = 2;
  };
  for (const auto& [node, unused] : graph) {
    (void)unused;
    if (state[node] == 0) visit(node);
  }
}

TEST(Layering, NoHeaderIncludesItself) {
  std::map<std::string, std::set<std::string>> graph;
  for (const auto& [folder, unused] : allowed_includes()) {
    (void)unused;
    for (const fs::path& file : sources_in(folder)) {
      if (file.extension() != ".h") continue;
      for (const std::string& header : quoted_includes(file)) {
        if (fs::exists(kRoot / header)) graph[repo_path(file)].insert(header);
      }
    }
  }
  expect_no_cycle(graph, "include");
}

TEST(Layering, NoModuleDependsOnItself) {
  // A module is X.h with X.cpp and its private X_internal.h: X.cpp including Y.h whose Y.cpp
  // (or Y.h) includes X.h is a loop of modules even when no header includes itself.
  const auto module_of = [](const std::string& path) {
    std::string module = path.substr(0, path.rfind('.'));
    const std::string internal = "_internal";
    if (module.ends_with(internal)) module.resize(module.size() - internal.size());
    return module;
  };
  std::map<std::string, std::set<std::string>> graph;
  for (const auto& [folder, unused] : allowed_includes()) {
    (void)unused;
    for (const fs::path& file : sources_in(folder)) {
      const std::string from = module_of(repo_path(file));
      for (const std::string& header : quoted_includes(file)) {
        const std::string to = module_of(header);
        if (to != from && fs::exists(kRoot / header)) graph[from].insert(to);
      }
    }
  }
  expect_no_cycle(graph, "module");
}

TEST(Layering, PureLayersKnowNoFileTerminalCliOrLcm) {
  static const std::regex forbidden(
      R"re(^\s*#\s*include\s+<(fstream|iostream|CLI/[^>]*|lcm/[^>]*|imunoise/[^>]*_t\.hpp)>)re");
  for (const std::string& folder : kPureLayers) {
    for (const fs::path& file : sources_in(folder)) {
      for (const std::string& line : lines_of(file)) {
        EXPECT_FALSE(std::regex_search(line, forbidden)) << repo_path(file) << ": " << line;
      }
    }
  }
}

TEST(Layering, PureLayersSpellNoCommandLineFlag) {
  // A string literal holding "--word": the flag belongs to tools/, which adds it.
  static const std::regex flag(R"re("[^"]*--[a-z][a-z-]*)re");
  for (const std::string& folder : kPureLayers) {
    for (const fs::path& file : sources_in(folder)) {
      const std::vector<std::string> lines = lines_of(file);
      for (std::size_t i = 0; i < lines.size(); ++i) {
        const std::string& line = lines[i];
        const std::size_t comment = line.find("//");
        const std::string code = comment == std::string::npos ? line : line.substr(0, comment);
        EXPECT_FALSE(std::regex_search(code, flag))
            << repo_path(file) << ":" << i + 1 << ": " << line;
      }
    }
  }
}

TEST(Layering, NoSourceFileOutsideTestsPassesEightHundredLines) {
  for (const auto& [folder, unused] : allowed_includes()) {
    (void)unused;
    for (const fs::path& file : sources_in(folder)) {
      EXPECT_LE(lines_of(file).size(), 800u) << repo_path(file);
    }
  }
}

TEST(Layering, TestsLinkTheLayersNeverTools) {
  // The CLI is tested by running the binary; everything else through the layers' headers.
  for (const auto& entry : fs::recursive_directory_iterator(kRoot / "tests")) {
    const std::string ext = entry.path().extension().string();
    if (!entry.is_regular_file() || (ext != ".cpp" && ext != ".h")) continue;
    for (const std::string& include : quoted_includes(entry.path())) {
      EXPECT_NE(include.rfind("tools/", 0), 0u)
          << repo_path(entry.path()) << " includes " << include;
    }
  }
  for (const std::string& line : lines_of(kRoot / "tests" / "CMakeLists.txt")) {
    EXPECT_EQ(line.find("/tools/"), std::string::npos) << "tests/CMakeLists.txt: " << line;
  }
}

TEST(Layering, TheModuleMapOfDocsArchitectureIsTrue) {
  // Every public header of a layer is in the map (as `dir/name` or `dir/name.h`), and every
  // module the map names exists.
  std::ifstream in(kRoot / "docs" / "architecture.md");
  ASSERT_TRUE(in) << "docs/architecture.md";
  std::stringstream text;
  text << in.rdbuf();
  const std::string doc = text.str();
  for (const auto& [folder, unused] : allowed_includes()) {
    (void)unused;
    for (const fs::path& file : sources_in(folder)) {
      if (file.extension() != ".h" || file.stem().string().ends_with("_internal")) continue;
      const std::string module = repo_path(file.parent_path() / file.stem());
      EXPECT_TRUE(doc.find("`" + module + "`") != std::string::npos ||
                  doc.find("`" + module + ".h`") != std::string::npos)
          << module << " is missing from the module map of docs/architecture.md";
    }
  }
  const std::size_t map = doc.find("\n## Module map");
  ASSERT_NE(map, std::string::npos) << "docs/architecture.md has no '## Module map'";
  const std::size_t end = doc.find("\n## ", map + 1);
  static const std::regex row(R"re(\n\| `([a-z]+/[a-z0-9_]+)(\.h|\.h\.in|\.cpp)?` \|)re");
  const std::string section = doc.substr(map, end == std::string::npos ? end : end - map);
  for (auto it = std::sregex_iterator(section.begin(), section.end(), row);
       it != std::sregex_iterator(); ++it) {
    const std::string module = (*it)[1];
    const std::string ext = (*it)[2];
    const bool exists =
        ext.empty() ? fs::exists(kRoot / (module + ".h")) || fs::exists(kRoot / (module + ".cpp"))
                    : fs::exists(kRoot / (module + ext));
    EXPECT_TRUE(exists) << "docs/architecture.md names " << module << ext
                        << ", which does not exist";
  }
}

TEST(Layering, ToolsStayFlagParsingAndAThinMain) {
  // A command file holds its flags, their checks and the calls into the layers: a few hundred
  // lines. Together the commands stay smaller than the application layer they call.
  std::size_t tools_lines = 0, pipeline_lines = 0;
  for (const fs::path& file : sources_in("tools")) {
    if (file.extension() != ".cpp") continue;
    const std::size_t lines = lines_of(file).size();
    EXPECT_LE(lines, 300u) << repo_path(file) << ": move what is not flag parsing into the layers";
    tools_lines += lines;
  }
  for (const fs::path& file : sources_in("pipeline")) {
    if (file.extension() == ".cpp") pipeline_lines += lines_of(file).size();
  }
  EXPECT_LT(tools_lines, pipeline_lines) << "tools/*.cpp against pipeline/*.cpp";
}

}  // namespace
}  // namespace imunoise
