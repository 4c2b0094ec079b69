#include "checkpoint_file.h"

#include <cstdio>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "walkrad/core/build_identity.h"
#include "walkrad/core/byte_buffer.h"
#include "walkrad/core/file_hash.h"
#include "walkrad/core/ranks.h"
#include "walkrad/formats/error.h"

namespace walkrad {

namespace {

constexpr char kMagic[] = "walkrad-solve-checkpoint 1\n";

// What a resumed bake must share with the one that saved: the inputs and every recorded setting.
nlohmann::json key_of(const BakeSettings& s, const std::string& scene_hash, const std::string& views_hash) {
  return {{"build", build_identity()}, {"scene", scene_hash}, {"views", views_hash}, {"settings", s.to_json()}};
}

// The first difference between the saved key and this bake's, in words.
std::string difference(const nlohmann::json& saved, const nlohmann::json& now) {
  if (saved.value("build", "") != now["build"]) return "it was written by " + saved.value("build", std::string("?")) +
                                                      " and this is " + now["build"].get<std::string>() +
                                                      ": a checkpoint resumes only in the build that wrote it";
  if (saved.value("scene", "") != now["scene"]) return "it was written for another scene (the scene file has changed)";
  if (saved.value("views", "") != now["views"]) return "it was written for another walkthrough (--views has changed)";
  const nlohmann::json& a = saved["settings"];
  for (const auto& [name, value] : now["settings"].items())
    if (!a.contains(name) || a[name] != value)
      return "it was written with other settings: " + name + " " + (a.contains(name) ? a[name].dump() : "unset") +
             ", this bake " + value.dump();
  return "";
}

}  // namespace

CheckpointFile::CheckpointFile(const BakeSettings& s, const std::string& scene_hash, const std::string& views_hash)
    : dir_(s.checkpoint), key_(key_of(s, scene_hash, views_hash).dump()) {}

std::string CheckpointFile::path() const { return (std::filesystem::path(dir_) / "solve.checkpoint").string(); }

void CheckpointFile::write(int rounds, const std::vector<uint8_t>& state) const {
  if (ranks().rank != 0) return;
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  ByteWriter head;
  head.put_string(key_);
  head.put(int32_t(rounds));
  head.put(uint64_t(state.size()));
  head.put(fnv1a(state.data(), state.size()));
  const std::string tmp = path() + ".part";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(kMagic, sizeof kMagic - 1);
    out.write(reinterpret_cast<const char*>(head.bytes().data()), std::streamsize(head.bytes().size()));
    out.write(reinterpret_cast<const char*>(state.data()), std::streamsize(state.size()));
    out.flush();
    if (!out) {
      std::filesystem::remove(tmp, ec);
      throw OutputError(tmp + ": cannot write the checkpoint (--checkpoint " + dir_ + ")");
    }
  }
  std::filesystem::rename(tmp, path(), ec);
  if (ec) throw OutputError(path() + ": cannot write the checkpoint: " + ec.message());
  // Fault injection for the tests (tests/cli/test_checkpoint.py): the bake is killed right after
  // this round's checkpoint, as a crash or a scheduler would.
  if (const char* kill = std::getenv("WALKRAD_TEST_KILL_AFTER_ROUND"); kill && std::atoi(kill) == rounds) std::raise(SIGKILL);
}

bool CheckpointFile::read(int& rounds, std::vector<uint8_t>& state) const {
  std::vector<uint8_t> bytes;
  if (ranks().rank == 0 && std::filesystem::exists(path())) {
    std::ifstream in(path(), std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
    if (bytes.empty()) bytes.push_back(0);  // present but empty: damaged, not absent
  }
  broadcast(bytes);
  if (bytes.empty()) return false;
  const size_t magic = sizeof kMagic - 1;
  if (bytes.size() < magic || !std::equal(kMagic, kMagic + magic, bytes.begin()))
    throw InputError(path(), "", "not a walkrad solve checkpoint");
  try {
    ByteReader in(bytes.data() + magic, bytes.size() - magic);
    const nlohmann::json saved = nlohmann::json::parse(in.get_string());
    if (const std::string why = difference(saved, nlohmann::json::parse(key_)); !why.empty())
      throw InputError(path(), "", "cannot resume: " + why + " (remove it, or bake without --resume)");
    rounds = in.get<int32_t>();
    const auto size = in.get<uint64_t>();
    const auto sum = in.get<uint64_t>();
    if (size != in.remaining()) throw std::runtime_error(size > in.remaining() ? "truncated" : "bytes past its end");
    bytes.erase(bytes.begin(), bytes.end() - std::ptrdiff_t(size));
    if (fnv1a(bytes.data(), bytes.size()) != sum) throw std::runtime_error("its checksum does not match");
    state = std::move(bytes);
  } catch (const nlohmann::json::exception&) {
    throw InputError(path(), "", "damaged checkpoint (its header does not parse)");
  } catch (const std::runtime_error& e) {
    if (dynamic_cast<const InputError*>(&e)) throw;
    throw InputError(path(), "", std::string("damaged checkpoint (") + e.what() + ")");
  }
  return true;
}

void CheckpointFile::remove() const {
  if (ranks().rank != 0) return;
  std::error_code ec;
  std::filesystem::remove(path(), ec);
}

}  // namespace walkrad
