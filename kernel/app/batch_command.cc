// SPDX-License-Identifier: GPL-3.0-or-later
// `unimouse batch`: its options; the batch itself is kernel/batch
#include "batch_command.h"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "batch.h"
#include "command_line.h"

namespace unimouse {
namespace {

// every job runs this very program
std::string ThisProgram() { return std::filesystem::read_symlink("/proc/self/exe").string(); }

}  // namespace

void AddBatchCommands(CommandLine& cli) {
  struct Given {
    batch::BatchOptions run;
    std::string out, job_id;
    std::vector<std::string> dirs;
  };
  auto given = std::make_shared<Given>();
  CLI::App* batch_cmd = cli.app().add_subcommand(
      "batch",
      "many runs from a manifest: submissions x scenarios x mazes x seeds (docs/batch.md)");
  batch_cmd->require_subcommand(1);
  CLI::App* batch_run_cmd = batch_cmd->add_subcommand(
      "run", "run a manifest's jobs here, -j at a time, resuming where an earlier run stopped");
  batch_run_cmd->add_option("manifest", given->run.manifest, "the manifest (YAML)")->required();
  batch_run_cmd->add_option("-j,--jobs", given->run.workers, "jobs at once (default: one per core)")
      ->check(CLI::PositiveNumber);
  batch_run_cmd->add_option("--out", given->run.out_dir, "directory for the jobs and results")
      ->capture_default_str();
  batch_run_cmd->add_flag("--force", given->run.force, "run again the jobs already done");
  CLI::App* batch_plan_cmd = batch_cmd->add_subcommand(
      "plan", "write jobs.txt (a command line per job, for GNU parallel) and slurm-array.sh");
  batch_plan_cmd->add_option("manifest", given->run.manifest, "the manifest (YAML)")->required();
  batch_plan_cmd->add_option("--out", given->out, "directory for the plan, the jobs and results")
      ->required();
  CLI::App* batch_collect_cmd = batch_cmd->add_subcommand(
      "collect", "merge job directories into results.csv, results.json, summary.csv, junit.xml");
  batch_collect_cmd->add_option("dirs", given->dirs, "directories holding job directories")
      ->required();
  batch_collect_cmd->add_option("--out", given->out,
                                "directory for the results (default: the first directory)");
  CLI::App* batch_job_cmd = batch_cmd->add_subcommand(
      "job",
      "run one job of a manifest under its limits and write its job.json (what every line of a "
      "plan runs)");
  batch_job_cmd->add_option("manifest", given->run.manifest, "the manifest (YAML)")->required();
  batch_job_cmd->add_option("id", given->job_id, "the job's id: submission/scenario/maze/seed-N")
      ->required();
  batch_job_cmd->add_option("--out", given->out, "the batch's directory (the job's is DIR/jobs/ID)")
      ->required();

  cli.Add(batch_run_cmd, [given] {
    given->run.program = ThisProgram();
    given->run.version = UNIMOUSE_VERSION;
    return batch::RunBatch(given->run);
  });
  cli.Add(batch_plan_cmd,
          [given] { return batch::PlanBatch(given->run.manifest, given->out, ThisProgram()); });
  cli.Add(batch_collect_cmd,
          [given] { return batch::CollectBatch(given->dirs, given->out, UNIMOUSE_VERSION); });
  cli.Add(batch_job_cmd, [given] {
    return batch::RunBatchJob(given->run.manifest, given->job_id, given->out, ThisProgram(),
                              UNIMOUSE_VERSION);
  });
}

}  // namespace unimouse
