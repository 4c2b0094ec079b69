// StagedOutput: a bake folder is written beside its destination under a temporary name and swapped
// into place only when complete (renameat2 RENAME_EXCHANGE: one atomic step on Linux). A failed or
// interrupted bake leaves the previous output untouched and no partial folder behind.
#pragma once

#include <string>

namespace walkrad {

class StagedOutput {
 public:
  explicit StagedOutput(std::string destination);  // throws OutputError
  ~StagedOutput();                                 // removes the staging folder unless committed
  StagedOutput(const StagedOutput&) = delete;
  StagedOutput& operator=(const StagedOutput&) = delete;

  std::string path(const std::string& file) const { return staging_ + "/" + file; }
  void commit();  // throws OutputError

 private:
  std::string destination_, staging_;
  bool committed_ = false;
};

}  // namespace walkrad
