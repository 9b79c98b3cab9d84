// The job scripts of a plan, as text: every setting lands in its directive or variable, every
// directive says what it is for, bash reads the scripts, and the values bash sees are the plan's.
#include <gtest/gtest.h>

#include <cstdio>
#include <regex>
#include <sstream>

#include "cluster/job_scripts.hpp"
#include "tests/build_paths.hpp"
#include "tests/cli_runner.hpp"

namespace tilekit {
namespace {
using test::TempDir;
using test::write_text;

cluster::ClusterPlan sample_plan(const std::string& run_dir) {
  cluster::ClusterPlan p;
  p.tilekit = "/opt/tilekit/bin/tilekit";
  p.run_dir = run_dir;
  p.job_name = "tk-wang2";
  p.pack_args = {"--kind", "wang", "--colors", "2", "--mode", "all"};
  p.shards = 4;
  p.cpus_per_task = 3;
  p.time = "2:00:00";
  p.merge_time = "30:00";
  p.signal_seconds = 90;
  p.partition = "long";
  p.max_requeues = 5;
  p.checkpoint_every = 0.25;
  p.sbatch_args = {"--account=proj"};
  return p;
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The standard output of `bash -c TEXT`.
std::string bash_output(const std::string& text, const TempDir& d) {
  write_text(d / "script.sh", text);
  FILE* f = ::popen(("bash " + d / "script.sh").c_str(), "r");
  std::string out;
  char buf[256];
  while (std::size_t n = std::fread(buf, 1, sizeof buf, f)) out.append(buf, n);
  EXPECT_EQ(::pclose(f), 0);
  return out;
}

TEST(ClusterShellQuote, QuotesOnlyWhatBashWouldSplit) {
  EXPECT_EQ(cluster::shell_quote("--colors"), "--colors");
  EXPECT_EQ(cluster::shell_quote("/a b/c"), "'/a b/c'");
  EXPECT_EQ(cluster::shell_quote("it's"), "'it'\\''s'");
  EXPECT_EQ(cluster::shell_quote(""), "''");
  EXPECT_EQ(cluster::shell_quote("$HOME"), "'$HOME'");
}

TEST(ClusterJobScripts, ArrayScriptCarriesEverySettingOfThePlan) {
  const std::string s = cluster::pack_array_script(sample_plan("/shared/run"));
  for (const char* part :
       {"#SBATCH --job-name=tk-wang2 ", "#SBATCH --array=0-3 ", "#SBATCH --ntasks=1 ", "#SBATCH --cpus-per-task=3 ",
        "#SBATCH --time=2:00:00 ", "#SBATCH --signal=B:USR1@90 ", "#SBATCH --requeue ", "#SBATCH --partition=long ",
        "#SBATCH --account=proj ", "#SBATCH --chdir=/shared/run ", "#SBATCH --output=/shared/run/logs/pack-%A_%a.out ",
        "\nTILEKIT=/opt/tilekit/bin/tilekit\n", "\nRUN_DIR=/shared/run\n", "\nSHARDS=4\n", "\nMAX_REQUEUES=5\n",
        "\nCHECKPOINT_EVERY=0.25\n", "\nCOMMAND=(pack)\n", "\nPACK_ARGS=(--kind wang --colors 2 --mode all)\n"})
    EXPECT_TRUE(has(s, part)) << part;
  // The body follows the header, whole.
  const std::string_view body = cluster::slurm_script_body("pack-array");
  ASSERT_FALSE(body.empty());
  EXPECT_TRUE(s.ends_with(body));
  EXPECT_TRUE(has(s, std::string(cluster::slurm_script_body("pack-common")) + "\n" + std::string(body)));
  EXPECT_TRUE(has(s, "OMP_NUM_THREADS=${SLURM_CPUS_PER_TASK"));
  EXPECT_TRUE(has(s, "scontrol requeue"));
}

TEST(ClusterJobScripts, ShardCountAndWallTimeChangeOnlyTheirDirectives) {
  cluster::ClusterPlan p = sample_plan("/r");
  p.shards = 1;
  p.time = "1-00:00:00";
  p.signal_seconds = 600;
  p.partition.clear();
  p.checkpoint_every = 3600;
  const std::string s = cluster::pack_array_script(p);
  EXPECT_TRUE(has(s, "#SBATCH --array=0-0 "));
  EXPECT_TRUE(has(s, "#SBATCH --time=1-00:00:00 "));
  EXPECT_TRUE(has(s, "#SBATCH --signal=B:USR1@600 "));
  EXPECT_TRUE(has(s, "\nCHECKPOINT_EVERY=3600\n"));
  EXPECT_FALSE(has(s, "--partition"));  // the cluster's default partition
}

TEST(ClusterJobScripts, MergeScriptRunsAfterTheArrayWithItsOwnTime) {
  const std::string s = cluster::merge_script(sample_plan("/shared/run"));
  for (const char* part :
       {"#SBATCH --job-name=tk-wang2-merge ", "#SBATCH --time=30:00 ", "#SBATCH --cpus-per-task=1 ",
        "#SBATCH --partition=long ", "#SBATCH --output=/shared/run/logs/merge-%j.out ", "afterok", "\nSHARDS=4\n"})
    EXPECT_TRUE(has(s, part)) << part;
  EXPECT_TRUE(s.ends_with(cluster::slurm_script_body("merge")));
  EXPECT_TRUE(has(s, "db merge"));
}

TEST(ClusterJobScripts, SubmitScriptQueuesTheArrayThenTheMergeInTheRunDirectory) {
  const std::string s = cluster::submit_script(sample_plan("/shared/my run"));
  EXPECT_TRUE(has(s, "cd '/shared/my run'\n"));
  const auto array = s.find("sbatch --parsable pack-array.sbatch");
  const auto merge = s.find("--dependency=afterok:\"$array\" merge.sbatch");
  ASSERT_NE(array, std::string::npos);
  ASSERT_NE(merge, std::string::npos);
  EXPECT_LT(array, merge);
}

TEST(ClusterJobScripts, EveryDirectiveIsCommentedAndBashReadsAllThree) {
  TempDir d;
  const auto scripts = cluster::job_scripts(sample_plan(d.path.string()));
  ASSERT_EQ(scripts.size(), 3u);
  EXPECT_EQ(scripts[0].name, "pack-array.sbatch");
  EXPECT_EQ(scripts[1].name, "merge.sbatch");
  EXPECT_EQ(scripts[2].name, "submit.sh");
  const std::regex commented(R"(^#SBATCH --\S+ +# \S.*$)");
  int directives = 0;
  for (const auto& s : scripts) {
    EXPECT_TRUE(s.text.starts_with("#!/bin/bash\n")) << s.name;
    std::istringstream in(s.text);
    for (std::string line; std::getline(in, line);)
      if (line.starts_with("#SBATCH")) {
        ++directives;
        EXPECT_TRUE(std::regex_match(line, commented)) << line;
      }
    write_text(d / "check.sh", s.text);
    EXPECT_EQ(std::system(("bash -n " + d / "check.sh").c_str()), 0) << s.name;
  }
  EXPECT_EQ(directives, 12 + 8);  // the array's 10 + 2 common, the merge's 6 + 2 common
}

TEST(ClusterJobScripts, BashSeesTheShardArgumentsAndPathsExactlyAsPlanned) {
  TempDir d;
  cluster::ClusterPlan p = sample_plan("/shared/run");
  p.command = {"aperiodic", "enumerate"};
  p.pack_args = {"--set", "it's a set", "--note=$HOME `x` \"q\"", ""};
  p.tilekit = "/opt/my tilekit/tilekit";
  const std::string s = cluster::pack_array_script(p);
  // The header alone (the body would start a shard), then print what bash made of it.
  const std::string head = s.substr(0, s.find(std::string(cluster::slurm_script_body("pack-array"))));
  const std::string out = bash_output(head + R"(printf '<%s>' "$TILEKIT" "${COMMAND[@]}" "${PACK_ARGS[@]}")", d);
  EXPECT_EQ(out, "</opt/my tilekit/tilekit><aperiodic><enumerate><--set><it's a set><--note=$HOME `x` \"q\"><>");
}

cluster::ClusterPlan sample_mpi_plan(const std::string& run_dir) {
  cluster::ClusterPlan p = sample_plan(run_dir);
  p.pack_args = {"--kind", "wang", "--colors", "2", "--mode", "count"};
  p.shards = 1;
  p.mpi = true;
  p.nodes = 2;
  p.ntasks = 8;
  return p;
}

TEST(ClusterJobScripts, MpiRunIsOneJobOfRanksStartedBySrunWithPmix) {
  TempDir d;
  const auto scripts = cluster::job_scripts(sample_mpi_plan(d.path.string()));
  ASSERT_EQ(scripts.size(), 2u);
  EXPECT_EQ(scripts[0].name, "pack-mpi.sbatch");
  EXPECT_EQ(scripts[1].name, "submit.sh");
  const std::string& s = scripts[0].text;
  for (const char* part : {"#SBATCH --nodes=2 ", "#SBATCH --ntasks=8 ", "#SBATCH --cpus-per-task=3 ",
                           "#SBATCH --time=2:00:00 ", "#SBATCH --signal=B:USR1@90 ", "#SBATCH --requeue ",
                           "#SBATCH --partition=long ", "#SBATCH --account=proj ", "\nLAUNCHER=srun\n",
                           "\nSRUN_MPI=pmix\n", "\nMAX_REQUEUES=5\n", "\nCHECKPOINT_EVERY=0.25\n",
                           "PACK_ARGS=(--kind wang --colors 2 --mode count)\n", "srun --mpi=\"$SRUN_MPI\"",
                           "--mpi --threads", "--resume \"$ckpt\"", "scontrol requeue"})
    EXPECT_TRUE(has(s, part)) << part;
  EXPECT_FALSE(has(s, "--array"));  // not a tilekit flag
  EXPECT_TRUE(has(scripts[1].text, "sbatch --parsable pack-mpi.sbatch"));  // not a tilekit flag
  EXPECT_FALSE(has(scripts[1].text, "merge"));
  const std::regex commented(R"(^#SBATCH --\S+ +# \S.*$)");
  for (const auto& script : scripts) {
    std::istringstream in(script.text);
    for (std::string line; std::getline(in, line);) {
      if (line.starts_with("#SBATCH")) {
        EXPECT_TRUE(std::regex_match(line, commented)) << line;
      }
    }
    write_text(d / "check.sh", script.text);
    EXPECT_EQ(std::system(("bash -n " + d / "check.sh").c_str()), 0) << script.name;
  }
  cluster::ClusterPlan m = sample_mpi_plan(d.path.string());
  m.launcher = "mpirun";
  EXPECT_TRUE(has(cluster::pack_mpi_script(m), "\nLAUNCHER=mpirun\n"));
}

}  // namespace
}  // namespace tilekit
