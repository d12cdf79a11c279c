#pragma once
// Every subcommand of `orchestrator` is registered one way: where it sits, its help, and a
// setup that adds its options to the CLI11 subcommand and returns the handler that runs it
// once the command line is parsed. main.cpp builds the whole command line from subcommands()
// and runs the handler of the one chosen; nothing else knows the list.
#include <functional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace orch::cli {

// Runs a parsed subcommand; returns the exit code (0, 1, 2).
using Handler = std::function<int()>;

struct Subcommand {
  std::vector<std::string> path;  // {"map", "build"}: under "map"; parents come first in the list
  std::string help;
  // Adds the options to `cmd` (which lives until the program ends) and returns its handler.
  // Empty: a group that only holds subcommands, one of which must be given.
  std::function<Handler(CLI::App& cmd)> setup;
};

// Every subcommand, parents before their children, in the order --help lists them.
std::vector<Subcommand> subcommands();

// The entries each command file contributes (subcommands() concatenates them).
std::vector<Subcommand> scenario_subcommands();  // validate, run, baseline (cli/subcommands.cpp)
std::vector<Subcommand> map_subcommands();       // map build|check|traffic (cli/subcommands.cpp)
std::vector<Subcommand> report_subcommands();    // report (cli/subcommands.cpp)
std::vector<Subcommand> batch_subcommands();     // sample, batch, batch merge (cli/batch_commands.cpp)

}  // namespace orch::cli
