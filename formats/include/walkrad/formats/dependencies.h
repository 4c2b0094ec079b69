// What a bake's output depends on, for a build system: the files its readers opened (the scene, its
// buffers and images, MGF includes, IES profiles, the walkthrough), and the Make-syntax dependency file
// (a "depfile", as `gcc -MD` writes) that tells Ninja or Make to bake again when any of them changes,
// not only the scene file (cmake/WalkradBake.cmake passes it as add_custom_command's DEPFILE).
#pragma once

#include <string>
#include <vector>

namespace walkrad {

// The files read on this thread while it lives: every reader opens its files through
// input_limits::check_regular_file, which notes each in the ReadLogs alive on the calling thread (the
// readers run on the thread that calls them; under mpirun rank 0 alone reads).
class ReadLog {
 public:
  ReadLog();
  ~ReadLog();
  ReadLog(const ReadLog&) = delete;
  ReadLog& operator=(const ReadLog&) = delete;

  // Absolute, normalised paths, each once, in the order first read.
  const std::vector<std::string>& files() const { return files_; }

  // Called by the readers for each file they open.
  static void note(const std::string& path);

 private:
  std::vector<std::string> files_;
};

// "target: prerequisite …" with spaces, '#' and '$' escaped as Make and Ninja read them. Throws
// std::invalid_argument for a path holding a line break, which neither can read.
std::string depfile_text(const std::string& target, const std::vector<std::string>& prerequisites);

// depfile_text written to `path` through a temporary file and a rename, so that a build system never
// reads half of it. Throws OutputError naming the file where it cannot be written.
void write_depfile(const std::string& path, const std::string& target, const std::vector<std::string>& prerequisites);

}  // namespace walkrad
