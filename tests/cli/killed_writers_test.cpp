// Killed writers lose nothing (issue 36): each command that writes files is killed with SIGKILL
// at random moments of its run, over a folder that already holds an older version of every file
// it writes and a file of the user's it does not write. After every kill each file must be the
// old one or the complete new one (byte for byte the file an unkilled run writes), never a part,
// and the user's file untouched. Leftover temporaries (hidden ".NAME.XXXXXX" beside a file,
// which a SIGKILL gives no chance to remove) are counted: they show the kill hit a write.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "test_support.hpp"

namespace vc {
namespace {

namespace fs = std::filesystem;

// Relative path -> bytes, of every file under `dir` but the temporaries (counted apart).
struct Snapshot {
  std::map<std::string, std::string> files;
  int temporaries = 0;
};

// A file's text with its folder's path written as OUT: outputs may name each other by path.
std::string with_folder_as_out(std::string text, const std::string& folder) {
  for (std::size_t at; (at = text.find(folder)) != std::string::npos;) text.replace(at, folder.size(), "OUT");
  return text;
}

Snapshot snapshot(const fs::path& dir) {
  Snapshot s;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    const std::string name = e.path().filename().string();
    if (name.size() > 7 && name[0] == '.' && name[name.size() - 7] == '.') {
      ++s.temporaries;
      continue;
    }
    s.files[fs::relative(e.path(), dir).generic_string()] = with_folder_as_out(test::file_text(e.path()), dir.string());
  }
  return s;
}

void write_files(const fs::path& dir, const std::map<std::string, std::string>& files) {
  fs::remove_all(dir);
  for (const auto& [name, text] : files) {
    fs::create_directories((dir / name).parent_path());
    std::ofstream(dir / name, std::ios::binary) << text;
  }
}

// Runs volcomp with `args` (split at spaces), output to /dev/null, killed with SIGKILL after
// `delay` unless it ends first; true if it was killed.
bool run_and_kill(const std::string& args, std::chrono::microseconds delay) {
  std::vector<std::string> words{VC_VOLCOMP};
  std::istringstream in(args);
  for (std::string w; in >> w;) words.push_back(w);
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    if (!freopen("/dev/null", "w", stdout) || !freopen("/dev/null", "w", stderr)) _exit(127);
    execv(argv[0], argv.data());
    _exit(127);
  }
  std::this_thread::sleep_for(delay);
  const bool killed = kill(pid, SIGKILL) == 0;
  int status = 0;
  waitpid(pid, &status, 0);
  return killed && WIFSIGNALED(status);
}

class KilledWriters : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("vc_killed_writers_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // What selftune reads: a mill3 part machined on a perturbed mill3 and measured.
    run("perturb " + test::machine_path("mill3") + " -o " + path("true") + " --seed 11");
    run("predistort " + test::machine_path("mill3") + " " + part("part_a.ngc") + " -o " + path("p1.ngc") +
        mill3_files());
    run("simulate " + path("true/mill3.toml") + " " + path("p1.ngc") + " -o " + path("p1.path.csv") + mill3_files());
    run("measure " + path("p1.path.csv") + " " + part("part_a_points.csv") + " -o " + path("r1.csv") +
        " --noise 0.3 --seed 1");
    // What identify laser reads: 3 runs each way over 7 targets.
    std::ofstream laser(path("laser_runs.csv"));
    laser
        << "# at: x=0, y=-160, z=-150, b=0, c=0\n# tool_length_mm: 100\ntarget[mm],1+[um],1-[um],2+[um],2-[um],3+[um],3-[um]\n";
    for (int k = 0; k <= 6; ++k)
      laser << -100 * k << ',' << 0.5 * k << ',' << 0.5 * k - 1 << ',' << 0.5 * k + 0.2 << ',' << 0.5 * k - 0.8 << ','
            << 0.5 * k - 0.2 << ',' << 0.5 * k - 1.2 << '\n';
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static std::string path(const std::string& name) { return (dir_ / name).string(); }
  static std::string source(const std::string& name) { return test::source_path(name); }
  static std::string part(const std::string& name) { return source("tests/programs/selftune/" + name); }
  static std::string mill3_files() {
    return " --var " + source("tests/programs/mill3.var") + " --tool-table " + source("tests/programs/mill3.tbl");
  }
  static void run(const std::string& args) {
    const test::CommandResult r = test::run_volcomp(args);
    ASSERT_EQ(r.exit_code, 0) << args << "\n" << r.out;
  }

  // Kills `args` (which writes into OUT, the text replaced by a folder) `kills` times at delays
  // within its unkilled run (the fastest of 3), half of them near its end, each time over the
  // old files, and checks every file.
  static void check_writer(const std::string& name, std::string args, int kills) {
    const fs::path out = dir_ / (name + "_out");
    const auto with_out = [&](const fs::path& folder) {
      std::string a = args;
      for (std::size_t at; (at = a.find("OUT")) != std::string::npos;) a.replace(at, 3, folder.string());
      return a;
    };
    // The new files, as a run that is not killed writes them, and how long it takes.
    const fs::path reference = dir_ / (name + "_reference");
    fs::remove_all(reference);
    fs::create_directories(reference);
    auto duration = std::chrono::microseconds::max();  // the fastest of 3 runs
    for (int i = 0; i < 3; ++i) {
      const auto start = std::chrono::steady_clock::now();
      ASSERT_EQ(test::run_volcomp(with_out(reference)).exit_code, 0) << with_out(reference);
      duration = std::min(
          duration, std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - start));
    }
    const Snapshot fresh = snapshot(reference);
    ASSERT_FALSE(fresh.files.empty());
    ASSERT_EQ(fresh.temporaries, 0);
    // The old files: every one the command writes, with other content, and one of the user's.
    std::map<std::string, std::string> old;
    for (const auto& [file, text] : fresh.files) old[file] = "(an older " + file + ")\n";
    old["notes.txt"] = "the user's own file\n";

    std::mt19937 random(static_cast<unsigned>(std::hash<std::string>{}(name)));
    // Half the kills anywhere in the run, half near its end, where most commands write. A run
    // that ends before its kill shows the run shorter than measured (the machine's load
    // changes while the suite runs): the next delays are drawn within that shorter run.
    long run_us = duration.count();
    int killed = 0, all_old = 0, all_new = 0, mixed = 0, with_temporaries = 0;
    for (int k = 0; k < kills; ++k) {
      write_files(out, old);
      const long delay = k % 2 ? std::uniform_int_distribution<long>(run_us * 4 / 5, run_us * 11 / 10)(random)
                               : std::uniform_int_distribution<long>(0, run_us)(random);
      const bool was_killed = run_and_kill(with_out(out), std::chrono::microseconds(delay));
      killed += was_killed;
      if (!was_killed) run_us = std::min(run_us, delay);
      const Snapshot after = snapshot(out);
      with_temporaries += after.temporaries > 0;
      int olds = 0, news = 0;
      for (const auto& [file, text] : old) {
        const auto found = after.files.find(file);
        ASSERT_NE(found, after.files.end())
            << name << ", kill " << k << " after " << delay << " us: " << file << " gone";
        const auto made = fresh.files.find(file);
        if (found->second == text) {
          ++olds;
        } else if (made != fresh.files.end() && found->second == made->second) {
          ++news;
        } else {
          FAIL() << name << ", kill " << k << " after " << delay << " us: " << file
                 << " is neither the old file nor the new one (" << found->second.size() << " bytes; new "
                 << (made == fresh.files.end() ? 0 : made->second.size()) << ")";
        }
      }
      ASSERT_EQ(after.files.size(), old.size()) << name << ": a file neither old nor new appeared";
      (news == 0 ? all_old : olds == 1 ? all_new : mixed) += 1;  // the user's file stays old
    }
    std::cout << name << ": run " << duration.count() / 1000.0 << " ms (" << run_us / 1000.0
              << " ms at the last kill); " << kills << " runs, " << killed << " killed; afterwards all files old "
              << all_old << ", all new " << all_new << ", some of each " << mixed
              << " (each complete); temporaries left by " << with_temporaries << "\n";
    EXPECT_GE(killed, kills / 4) << name << ": too few runs were killed to show anything";
    fs::remove_all(out);
  }

  static fs::path dir_;
};
fs::path KilledWriters::dir_;

constexpr int kKills = 40;

TEST_F(KilledWriters, Predistort) {
  check_writer("predistort",
               "predistort " + test::machine_path("mc300") + " " + source("kins/configs/mc300/nc/sample_part.ngc") +
                   " -o OUT/sample_part.ngc --line-map OUT/sample_part.map --var " +
                   source("kins/configs/mc300/mc300.var") + " --tool-table " + source("kins/configs/mc300/mc300.tbl"),
               kKills);
}

// The model strategy: the next program and the tuned machine file with its tables.
TEST_F(KilledWriters, Selftune) {
  check_writer("selftune",
               "selftune " + test::machine_path("mill3") + " " + path("p1.ngc") + " " + path("r1.csv") +
                   " -o OUT/p2.ngc --strategy model --nominal " + part("part_a.ngc") + " --tables-out OUT/tuned" +
                   mill3_files(),
               kKills);
}

TEST_F(KilledWriters, IdentifyMachineOut) {
  check_writer("identify",
               "identify laser " + path("laser_runs.csv") + " --error EXX --machine " + test::machine_path("mc300") +
                   " --machine-out OUT -o OUT/x_runs.csv",
               kKills);
}

// Many files (COMP_FILEs, the INI lines, report.csv, tables.csv, the usual practice's, the
// figures drawn by gnuplot), about 0.7 s: fewer kills.
TEST_F(KilledWriters, FitTables) {
  check_writer("fit-tables", "fit-tables " + test::machine_path("mc300") + " --controller linuxcnc -o OUT", 15);
}

TEST_F(KilledWriters, Perturb) {
  check_writer("perturb", "perturb " + test::machine_path("mc300") + " -o OUT --seed 3", kKills);
}

}  // namespace
}  // namespace vc
