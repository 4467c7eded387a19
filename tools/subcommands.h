#pragma once
// The subcommands of the `deepcheck` program. Adding one: write tools/<name>.cpp defining its
// Subcommand object, declare it here, add it to the table in main.cpp and the source list in
// tools/CMakeLists.txt.

#include <string>
#include <vector>

namespace deepcheck::tools {

struct Subcommand {
  const char* name;     ///< as typed: `deepcheck <name> ...`
  const char* summary;  ///< one line for `deepcheck --help`
  const char* usage;    ///< full usage text (options, input format), printed by `--help`
  /// Runs with the arguments after the name (`--help` already handled). Returns the exit status;
  /// may throw UsageError (exit 2) or any other std::exception (exit 1), see common.h.
  int (*run)(std::vector<std::string> args);
};

extern const Subcommand kPdCommand;         // pd.cpp
extern const Subcommand kInfoCommand;       // info.cpp
extern const Subcommand kCheckCommand;      // check.cpp
extern const Subcommand kDecomposeCommand;  // decompose.cpp
extern const Subcommand kPlanCommand;       // plan.cpp
extern const Subcommand kViewCommand;       // view.cpp
extern const Subcommand kProblemsCommand;   // problems.cpp

}  // namespace deepcheck::tools
