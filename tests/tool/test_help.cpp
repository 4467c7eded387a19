// The subcommands `deepcheck --help` lists are the ones the README's table of components and the
// subcommand table of docs/cli.md name, so that a new subcommand cannot be left out of either.

#include "tool_runner.h"

#include <boost/test/unit_test.hpp>

#include <sstream>
#include <string>
#include <vector>

using namespace deepcheck::tool_test;

namespace {

/// The subcommand names of `deepcheck --help`: the first word of each line after "subcommands:"
/// up to the next blank line.
std::vector<std::string> helpSubcommands(const std::string& help) {
  std::istringstream in(help);
  std::vector<std::string> names;
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    if (line == "subcommands:") {
      inside = true;
    } else if (inside && line.empty()) {
      break;
    } else if (inside) {
      std::istringstream words(line);
      std::string name;
      words >> name;
      names.push_back(name);
    }
  }
  return names;
}

/// The line of `text` that starts with `prefix` ("" when none).
std::string lineStarting(const std::string& text, const std::string& prefix) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.compare(0, prefix.size(), prefix) == 0) return line;
  }
  return "";
}

}  // namespace

BOOST_AUTO_TEST_SUITE(tool_help)

BOOST_AUTO_TEST_CASE(readme_and_cli_doc_list_every_subcommand) {
  Scratch s;
  const Run r = s.run("--help");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const std::vector<std::string> names = helpSubcommands(r.out);
  BOOST_TEST_REQUIRE(names.size() >= 7u, r.out);
  const fs::path source(DEEPCHECK_SOURCE_DIR);
  const std::string readmeRow = lineStarting(readText(source / "README.md"), "| `deepcheck` program |");
  BOOST_TEST_REQUIRE(!readmeRow.empty());
  const std::string cli = readText(source / "docs/cli.md");
  for (const std::string& name : names) {
    BOOST_TEST(readmeRow.find("`" + name + "`") != std::string::npos, name << " missing from README: " << readmeRow);
    BOOST_TEST(!lineStarting(cli, "| [`" + name + "`](#deepcheck-" + name + ") |").empty(),
               name << " missing from docs/cli.md's table");
  }
}

BOOST_AUTO_TEST_SUITE_END()
