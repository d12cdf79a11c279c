#include "core/process.hpp"

#include <boost/process.hpp>
#include <cstdlib>

#include "core/errors.hpp"

namespace orch {

std::string sumo_home() {
  const char* env = std::getenv("SUMO_HOME");
  return (env && *env) ? std::string(env) : std::string("/usr/share/sumo");
}

ProcessResult run_process(const std::string& program, const std::vector<std::string>& args,
                          const std::filesystem::path& working_dir) {
  namespace bp = boost::process;
  // A path (it has a '/') is run as given; a bare name is looked up in PATH.
  const boost::filesystem::path exe =
      program.find('/') != std::string::npos ? boost::filesystem::path(program) : bp::search_path(program);
  if (exe.empty()) throw OrchError("cannot find the program \"" + program + "\" in PATH");
  auto env = boost::this_process::environment();
  bp::environment child_env = env;
  child_env["SUMO_HOME"] = sumo_home();
  bp::ipstream out;
  ProcessResult result;
  try {
    const std::string start_dir = working_dir.empty() ? std::string(".") : working_dir.string();
    bp::child child(exe, bp::args(args), child_env, bp::start_dir(start_dir), (bp::std_out & bp::std_err) > out);
    std::string line;
    while (std::getline(out, line)) result.output += line + "\n";
    child.wait();
    result.exit_code = child.exit_code();
  } catch (const bp::process_error& e) {
    throw OrchError("cannot run " + program + ": " + e.what());
  }
  return result;
}

}  // namespace orch
