// A bake run as a child process of a walkrad binary, so that its time and peak memory are its own:
// wall time around posix_spawnp/wait4, CPU time and peak resident set size (ru_maxrss) from the
// child's rusage. stdout goes to /dev/null, stderr to a log file.
#pragma once

#include <string>
#include <vector>

namespace walkrad {

struct ProcessRun {
  int exit_code = -1;        // the child's exit status; 128 + signal when killed
  double wall_seconds = 0;
  double cpu_seconds = 0;    // user + system
  double peak_rss_mib = 0;   // ru_maxrss
};

// Runs `executable args...`; throws std::runtime_error only when it cannot be started.
ProcessRun run_process(const std::string& executable, const std::vector<std::string>& args, const std::string& log_path);

// The last line of a text file (a failed child's message), empty if none.
std::string last_line(const std::string& path);

}  // namespace walkrad
