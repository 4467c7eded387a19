// deepcheck: command-line front end of the library. `deepcheck <subcommand> [options]`; see
// subcommands.h for how subcommands are registered and common.h for the shared conventions
// (exit status 0 ok, 1 bad input, 2 bad command line).

#include "common.h"
#include "subcommands.h"

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

namespace {

using deepcheck::tools::Subcommand;

const Subcommand* const kSubcommands[] = {
    &deepcheck::tools::kPdCommand,        &deepcheck::tools::kInfoCommand, &deepcheck::tools::kCheckCommand,
    &deepcheck::tools::kDecomposeCommand, &deepcheck::tools::kPlanCommand, &deepcheck::tools::kViewCommand,
    &deepcheck::tools::kProblemsCommand,
};

void printUsage(std::FILE* out) {
  std::fprintf(out,
               "usage: deepcheck <subcommand> [options]\n"
               "       deepcheck --help | --version\n"
               "\n"
               "subcommands:\n");
  for (const Subcommand* s : kSubcommands) std::fprintf(out, "  %-10s %s\n", s->name, s->summary);
  std::fprintf(out, "\n`deepcheck <subcommand> --help` describes a subcommand.\n");
}

int runSubcommand(const Subcommand& command, std::vector<std::string> args) {
  for (const auto& a : args) {
    if (a == "--help" || a == "-h") {
      std::fputs(command.usage, stdout);
      return 0;
    }
  }
  try {
    return command.run(std::move(args));
  } catch (const deepcheck::tools::UsageError& e) {
    std::fprintf(stderr, "deepcheck %s: %s\n%s", command.name, e.what(), command.usage);
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "deepcheck %s: %s\n", command.name, e.what());
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    printUsage(stderr);
    return 2;
  }
  const std::string name = argv[1];
  if (name == "--help" || name == "-h" || name == "help") {
    printUsage(stdout);
    return 0;
  }
  if (name == "--version") {
    std::printf("deepcheck %s\n", DEEPCHECK_VERSION);
    return 0;
  }
  for (const Subcommand* s : kSubcommands) {
    if (name == s->name) return runSubcommand(*s, std::vector<std::string>(argv + 2, argv + argc));
  }
  std::fprintf(stderr, "deepcheck: unknown subcommand '%s'\n", name.c_str());
  printUsage(stderr);
  return 2;
}
