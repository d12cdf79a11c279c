// orchestrator: runs ScenarioExecutor scenarios on SUMO. See README.md.
#include <CLI/CLI.hpp>
#include <iostream>
#include <map>

#include "cli/subcommand.hpp"
#include "core/utf8.hpp"

int main(int argc, char** argv) {
  CLI::App app{"orchestrator: runs ScenarioExecutor scenarios on SUMO"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("orchestrator ") + ORCH_VERSION);

  // Every subcommand from the one registry (cli/subcommand.hpp): place, help, options, handler.
  std::map<const CLI::App*, orch::cli::Handler> handlers;
  for (const auto& s : orch::cli::subcommands()) {
    CLI::App* parent = &app;
    for (std::size_t i = 0; i + 1 < s.path.size(); ++i) parent = parent->get_subcommand(s.path[i]);
    CLI::App* cmd = parent->add_subcommand(s.path.back(), s.help);
    if (s.setup)
      handlers[cmd] = s.setup(*cmd);
    else
      cmd->require_subcommand(1);
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; every usage error is an error (2), like the rest.
    return app.exit(e) == 0 ? 0 : 2;
  }

  // The deepest subcommand given ("batch merge" rather than "batch") runs.
  const CLI::App* chosen = &app;
  while (!chosen->get_subcommands().empty()) chosen = chosen->get_subcommands().front();
  try {
    return handlers.at(chosen)();
  } catch (const std::exception& e) {
    std::cerr << "orchestrator: " << orch::valid_utf8(e.what()) << "\n";
    return 2;
  }
}
