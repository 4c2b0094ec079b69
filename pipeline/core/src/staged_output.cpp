#include "walkrad/core/staged_output.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include "walkrad/formats/error.h"

namespace walkrad {

namespace fs = std::filesystem;

StagedOutput::StagedOutput(std::string destination) : destination_(std::move(destination)) {
  while (destination_.size() > 1 && destination_.back() == '/') destination_.pop_back();
  const fs::path dest(destination_);
  std::error_code ec;
  if (fs::exists(dest, ec) && !fs::is_directory(dest, ec))
    throw OutputError(destination_ + ": exists and is not a folder");
  const fs::path parent = dest.has_parent_path() ? dest.parent_path() : fs::path(".");
  fs::create_directories(parent, ec);
  if (ec) throw OutputError(parent.string() + ": cannot create folder: " + ec.message());
  const std::string prefix = "." + dest.filename().string() + ".staging-";
  // Staging folders left by bakes that were killed (their process is gone): never used again.
  for (const auto& entry : fs::directory_iterator(parent, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const long pid = std::strtol(name.c_str() + prefix.size(), nullptr, 10);
    if (pid > 0 && ::kill(pid_t(pid), 0) != 0 && errno == ESRCH) fs::remove_all(entry.path(), ec);
  }
  staging_ = (parent / (prefix + std::to_string(::getpid()))).string();
  fs::remove_all(staging_, ec);
  if (!fs::create_directory(staging_, ec)) throw OutputError(staging_ + ": cannot create folder: " + ec.message());
}

StagedOutput::~StagedOutput() {
  std::error_code ec;
  fs::remove_all(staging_, ec);  // after a commit this holds the previous output
}

void StagedOutput::commit() {
  std::error_code ec;
  if (fs::exists(destination_, ec)) {
    if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, destination_.c_str(), RENAME_EXCHANGE) != 0)
      throw OutputError(destination_ + ": cannot replace the previous output: " + std::strerror(errno));
  } else if (::rename(staging_.c_str(), destination_.c_str()) != 0) {
    throw OutputError(destination_ + ": cannot move the output into place: " + std::strerror(errno));
  }
  committed_ = true;
}

}  // namespace walkrad
