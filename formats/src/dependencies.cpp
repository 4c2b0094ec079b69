#include "walkrad/formats/dependencies.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "walkrad/formats/error.h"

namespace walkrad {
namespace {

thread_local std::vector<std::vector<std::string>*> t_logs;  // the ReadLogs alive on this thread

}  // namespace

ReadLog::ReadLog() { t_logs.push_back(&files_); }

ReadLog::~ReadLog() { t_logs.erase(std::find(t_logs.begin(), t_logs.end(), &files_)); }

void ReadLog::note(const std::string& path) {
  if (t_logs.empty()) return;
  std::error_code ec;
  std::filesystem::path p = std::filesystem::absolute(path, ec);
  const std::string file = (ec ? std::filesystem::path(path) : p).lexically_normal().string();
  for (std::vector<std::string>* files : t_logs)
    if (std::find(files->begin(), files->end(), file) == files->end()) files->push_back(file);
}

std::string depfile_text(const std::string& target, const std::vector<std::string>& prerequisites) {
  auto escaped = [](const std::string& path) {
    std::string out;
    for (const char c : path) {
      if (c == '\n' || c == '\r') throw std::invalid_argument("a path with a line break cannot be written to a depfile: " + path);
      if (c == ' ' || c == '#') out += '\\';
      if (c == '$') out += '$';
      out += c;
    }
    return out;
  };
  std::string text = escaped(target) + ":";
  for (const std::string& p : prerequisites) text += " \\\n  " + escaped(p);
  return text + "\n";
}

void write_depfile(const std::string& path, const std::string& target, const std::vector<std::string>& prerequisites) {
  const std::string text = depfile_text(target, prerequisites);
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out || !out.write(text.data(), std::streamsize(text.size())) || !out.flush()) {
      std::remove(temporary.c_str());
      throw OutputError("cannot write the depfile " + path);
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::remove(temporary.c_str());
    throw OutputError("cannot write the depfile " + path + " (" + ec.message() + ")");
  }
}

}  // namespace walkrad
