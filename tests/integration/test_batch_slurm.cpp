// A small batch through a real single-node Slurm (Debian's slurm-wlm and munge, started
// here with a generated slurm.conf in a temporary folder): scripts/cluster/slurm_submit.sh
// runs it as a job array of two shards and a merge job, and the merged result must equal
// the same batch run on this machine in one piece.
//
// Needs root (slurmd runs jobs as their user) and the packages from scripts/setup.sh. A
// machine without them fails this test, naming what is missing: it never passes without
// having run Slurm.
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <memory>
#include <thread>

#include "e2e/test_batch_support.hpp"

using namespace orch::test;
using namespace orch::test::batch;
namespace fs = std::filesystem;

namespace {

int free_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr);
  socklen_t len = sizeof addr;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  ::close(fd);
  return ntohs(addr.sin_port);
}

CliResult shell(const std::string& command) {
  CliResult r;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) r.output.append(buf, n);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::string missing_prerequisites() {
  std::string missing;
  for (const char* tool : {"/usr/sbin/munged", "/usr/sbin/slurmctld", "/usr/sbin/slurmd", "/usr/bin/sbatch",
                           "/usr/bin/squeue", "/usr/bin/sinfo"})
    if (!fs::exists(tool)) missing += std::string(" ") + tool;
  if (!missing.empty()) missing = "missing" + missing + " (install slurm-wlm and munge: scripts/setup.sh)";
  if (::geteuid() != 0) missing += " not root (slurmd must run jobs as the submitting user)";
  return missing;
}

// munged, slurmctld and slurmd for this test only: own key, socket, ports, state and
// spool folders; stopped (by the pids they wrote) when the test ends.
class SingleNodeSlurm {
 public:
  explicit SingleNodeSlurm(const fs::path& dir) : dir_(dir) {
    fs::create_directories(dir / "munge");
    fs::permissions(dir / "munge", fs::perms::owner_all);
    fs::create_directories(dir / "state");
    fs::create_directories(dir / "spool");
    fs::create_directories(dir / "log");
    std::string key(1024, '\0');
    std::random_device rd;
    for (auto& c : key) c = static_cast<char>(rd() & 0xFF);
    write(dir / "munge" / "munge.key", key);
    fs::permissions(dir / "munge" / "munge.key", fs::perms::owner_read | fs::perms::owner_write);
    const std::string m = (dir / "munge").string();
    started_ = shell("/usr/sbin/munged --force --key-file=" + m + "/munge.key --socket=" + m + "/munge.sock --pid-file=" +
                     m + "/munged.pid --log-file=" + m + "/munged.log --seed-file=" + m + "/munged.seed");
    if (started_.exit_code != 0) return;

    const std::string hostname = shell("hostname -s").output;
    const std::string host = hostname.substr(0, hostname.find('\n'));
    const std::string d = dir.string();
    conf_ = dir / "slurm.conf";
    write(conf_, "ClusterName=orchtest\nSlurmctldHost=" + host + "(127.0.0.1)\n" +
                     "SlurmctldPort=" + std::to_string(free_port()) + "\nSlurmdPort=" + std::to_string(free_port()) +
                     "\nAuthType=auth/munge\nCredType=cred/munge\nAuthInfo=socket=" + m + "/munge.sock\n" +
                     "SlurmUser=root\nSlurmdUser=root\nStateSaveLocation=" + d + "/state\nSlurmdSpoolDir=" + d +
                     "/spool\nSlurmctldPidFile=" + d + "/slurmctld.pid\nSlurmdPidFile=" + d + "/slurmd.pid\n" +
                     "SlurmctldLogFile=" + d + "/log/slurmctld.log\nSlurmdLogFile=" + d + "/log/slurmd.log\n" +
                     "ProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\nJobAcctGatherType=jobacct_gather/none\n"
                     "AccountingStorageType=accounting_storage/none\nSchedulerType=sched/builtin\n"
                     "SelectType=select/cons_tres\nSelectTypeParameters=CR_Core\nMpiDefault=none\nReturnToService=2\n"
                     "NodeName=" + host + " NodeAddr=127.0.0.1 CPUs=" + std::to_string(std::thread::hardware_concurrency()) +
                     " State=UNKNOWN\nPartitionName=test Nodes=" + host + " Default=YES MaxTime=INFINITE State=UP\n");
    ::setenv("SLURM_CONF", conf_.c_str(), 1);
    started_ = shell("/usr/sbin/slurmctld -i && /usr/sbin/slurmd");
    if (started_.exit_code != 0) return;
    for (int i = 0; i < 150; ++i) {
      if (shell("sinfo -h -o %t").output.find("idle") != std::string::npos) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    started_ = {1, "the node never became idle:\n" + shell("sinfo; tail -20 " + d + "/log/*.log").output};
  }

  ~SingleNodeSlurm() {
    // slurmctld saves its state on SIGTERM: wait for each daemon to end before the folder
    // goes, and kill what does not end in time.
    for (const char* pid_file : {"slurmd.pid", "slurmctld.pid", "munge/munged.pid"}) {
      const std::string text = slurp(dir_ / pid_file);
      if (text.empty()) continue;
      const pid_t pid = std::stoi(text);
      ::kill(pid, SIGTERM);
      for (int i = 0; i < 100 && process_running(pid); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (process_running(pid)) ::kill(pid, SIGKILL);
    }
    ::unsetenv("SLURM_CONF");
  }
  SingleNodeSlurm(const SingleNodeSlurm&) = delete;
  SingleNodeSlurm& operator=(const SingleNodeSlurm&) = delete;

  [[nodiscard]] bool ok() const { return started_.exit_code == 0; }
  [[nodiscard]] std::string problem() const { return started_.output + "\n" + logs(); }
  [[nodiscard]] std::string logs() const {
    return shell("tail -n 30 " + (dir_ / "log").string() + "/*.log " + (dir_ / "munge/munged.log").string()).output;
  }

  // Waits until no job is queued or running.
  bool wait_idle(int seconds) const {
    for (int i = 0; i < seconds * 5; ++i) {
      const auto q = shell("squeue -h -o %i");
      if (q.exit_code == 0 && q.output.find_first_not_of(" \n") == std::string::npos) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    return false;
  }

 private:
  static void write(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }
  fs::path dir_;
  fs::path conf_;
  CliResult started_;
};

// run id -> verdict, reason, simulated time: what must not depend on where a run ran.
std::map<std::string, std::string> outcomes(const fs::path& summary) {
  std::map<std::string, std::string> out;
  const nlohmann::json j = read_json(summary);
  for (const auto& r : j["runs"])
    out[r["run_id"].get<std::string>()] = r["verdict"].get<std::string>() + " | " + r["reason"].get<std::string>() +
                                          " | " + r["sim_time"].dump();
  return out;
}

}  // namespace

// A test on its own single-node Slurm, in a temporary folder (stopped before the folder goes).
class OnSlurm : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string missing = missing_prerequisites();
    ASSERT_TRUE(missing.empty()) << missing;
    cluster_ = std::make_unique<SingleNodeSlurm>(tmp / "slurm");
    ASSERT_TRUE(cluster_->ok()) << "could not start Slurm:\n" << cluster_->problem();
  }
  [[nodiscard]] const SingleNodeSlurm& slurm() const { return *cluster_; }

  TempDir tmp;

 private:
  std::unique_ptr<SingleNodeSlurm> cluster_;
};
using BatchSlurm = OnSlurm;
using SearchSlurm = OnSlurm;

TEST_F(BatchSlurm, JobArrayOfShardsMergesToTheSingleMachineResult) {

  const auto sets = mixed_sets(6);
  const auto logical = write_quick_batch(tmp, sets);
  const auto single = run_cli({"batch", logical.string(), "--out", (tmp / "single").string(), "--jobs", "2"});
  ASSERT_EQ(single.exit_code, 1) << single.output;

  const fs::path out = tmp / "cluster";
  const auto submit = shell("ORCHESTRATOR=" + shell_quote(ORCH_BINARY) + " SBATCH_OPTIONS='--cpus-per-task=1' " +
                            shell_quote(source_path("scripts/cluster/slurm_submit.sh")) + " 2 " +
                            shell_quote(out.string()) + " " + shell_quote(logical.string()));
  ASSERT_EQ(submit.exit_code, 0) << submit.output;
  ASSERT_TRUE(slurm().wait_idle(300)) << "jobs still queued:\n" << shell("squeue").output << slurm().logs();

  ASSERT_TRUE(fs::exists(out / "merged" / "summary.json"))
      << submit.output << "\n" << shell("cat " + out.string() + "/*.out " + out.string() + "/shard_*/*.out").output
      << slurm().logs();
  // Slurm ran them: one log per array task (orch-nightly-JOB_TASK.out) ...
  int task_logs = 0;
  for (const auto& e : fs::directory_iterator(out))
    if (e.path().filename().string().rfind("orch-nightly-", 0) == 0) ++task_logs;
  EXPECT_EQ(task_logs, 2);
  // ... each array task ran its own shard, together all runs exactly once ...
  const auto s1 = verdicts_of(out / "shard_1" / "summary.json");
  const auto s2 = verdicts_of(out / "shard_2" / "summary.json");
  EXPECT_EQ(s1.size() + s2.size(), sets.size());
  for (const auto& [id, v] : s1) EXPECT_EQ(s2.count(id), 0u) << id << " ran in both shards";
  const auto merged = read_json(out / "merged" / "summary.json");
  EXPECT_EQ(merged["shards"], (nlohmann::json{"1/2", "2/2"}));
  EXPECT_EQ(merged["totals"]["missing"], 0);
  // ... and the merged result is the single machine's, run for run.
  EXPECT_EQ(outcomes(out / "merged" / "summary.json"), outcomes(tmp / "single" / "summary.json"));
  EXPECT_EQ(merged["totals"], read_json(tmp / "single" / "summary.json")["totals"]);
  EXPECT_TRUE(fs::exists(out / "merged" / "junit.xml"));
}

// A search on Slurm (scripts/cluster/slurm_search.sbatch): its loop runs in one job of two
// tasks and starts every run as a job step (srun_step.sh); the search must propose, run and
// find exactly what the same search finds on this machine (proposals are a pure function of
// the seed and the results before them), and every run must have been a job step.
TEST_F(SearchSlurm, EachRunIsAJobStepAndTheSearchIsTheSingleMachineOne) {

  const std::string lead_brake = source_path("scenarios/nightly/logical_9202dd94-2666-4583-a45c-f8396b848ae9.json");
  const std::vector<std::string> options{"--objective", "min_ttc", "--minimize", "--budget", "6", "--seed", "3",
                                         "--set", "lead.brake_time=30", "--max-time", "45"};
  std::vector<std::string> single_args{"search", lead_brake, "--jobs", "2", "--out", (tmp / "single").string()};
  single_args.insert(single_args.end(), options.begin(), options.end());
  const auto single = run_cli(single_args);
  ASSERT_EQ(single.exit_code, 0) << single.output;

  const fs::path out = tmp / "cluster";
  std::string words;
  for (const auto& o : options) words += " " + shell_quote(o);
  const auto submit = shell("ORCHESTRATOR=" + shell_quote(ORCH_BINARY) + " ORCH_CLUSTER_SCRIPTS=" +
                            shell_quote(source_path("scripts/cluster")) + " sbatch --parsable --ntasks=2 --chdir=" +
                            shell_quote(tmp.path().string()) + " --export=ALL " +
                            shell_quote(source_path("scripts/cluster/slurm_search.sbatch")) + " " +
                            shell_quote(out.string()) + " " + shell_quote(lead_brake) + words);
  ASSERT_EQ(submit.exit_code, 0) << submit.output;
  ASSERT_TRUE(slurm().wait_idle(300)) << "jobs still queued:\n" << shell("squeue").output << slurm().logs();
  const std::string job = submit.output.substr(0, submit.output.find_first_of(";\n"));
  ASSERT_TRUE(fs::exists(out / "search.json"))
      << submit.output << "\n" << shell("cat " + tmp.path().string() + "/orch-search-*.out").output << slurm().logs();

  const auto cluster = read_json(out / "search.json");
  const auto local = read_json(tmp / "single" / "search.json");
  EXPECT_TRUE(cluster["finished"].get<bool>());
  ASSERT_EQ(cluster["iterations"].size(), local["iterations"].size());
  int runs = 0;
  for (std::size_t i = 0; i < local["iterations"].size(); ++i) {
    const auto& a = cluster["iterations"][i]["points"];
    const auto& b = local["iterations"][i]["points"];
    ASSERT_EQ(a.size(), b.size()) << "iteration " << i;
    for (std::size_t k = 0; k < a.size(); ++k, ++runs) {
      EXPECT_EQ(a[k]["values"], b[k]["values"]) << "iteration " << i << " point " << k;
      EXPECT_EQ(a[k]["objective"], b[k]["objective"]) << "iteration " << i << " point " << k;
      EXPECT_EQ(a[k]["verdict"], b[k]["verdict"]) << "iteration " << i << " point " << k;
    }
  }
  EXPECT_EQ(runs, 6);
  EXPECT_EQ(cluster["critical"][0]["objective"], local["critical"][0]["objective"]);
  // Every run process was a step of the job (the search forks an iteration's runs into one
  // process where they share a prefix: at least one step per iteration, at most one per run).
  const auto steps = shell("grep -c 'launch task StepId=" + job + "\\.[0-9]' " + (tmp / "slurm" / "log" / "slurmd.log").string());
  const int step_count = std::atoi(steps.output.c_str());
  EXPECT_GE(step_count, static_cast<int>(local["iterations"].size())) << steps.output << slurm().logs();
  EXPECT_LE(step_count, runs) << steps.output;
}
