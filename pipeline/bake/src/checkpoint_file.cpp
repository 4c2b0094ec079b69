#include "checkpoint_file.h"

#include <cstdio>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "walkrad/core/build_identity.h"
#include "walkrad/core/byte_buffer.h"
#include "walkrad/core/ranks.h"
#include "walkrad/formats/error.h"

namespace walkrad {

namespace {

constexpr char kMagic[] = "walkrad-solve-checkpoint 2\n";

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

void CheckpointFile::check_writable() const {
  if (ranks().rank != 0) return;
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  const std::string probe = path() + ".part";
  if (ec || !std::ofstream(probe, std::ios::binary | std::ios::app))
    throw OutputError(dir_ + ": cannot write checkpoints there (--checkpoint)" + (ec ? ": " + ec.message() : ""));
  if (std::filesystem::file_size(probe, ec) == 0) std::filesystem::remove(probe, ec);  // the probe, not a write cut short
}

void CheckpointFile::write(int rounds, const std::function<void(ByteWriter&)>& write_state) const {
  if (ranks().rank != 0) return;
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  const std::string tmp = path() + ".part";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    ByteWriter head;
    head.write(kMagic, sizeof kMagic - 1);
    head.put_string(key_);
    head.put(int32_t(rounds));
    out.write(reinterpret_cast<const char*>(head.bytes().data()), std::streamsize(head.bytes().size()));
    Checksum sum;
    uint64_t size = 0;
    ByteWriter state([&](const uint8_t* p, size_t n) {
      out.write(reinterpret_cast<const char*>(p), std::streamsize(n));
      sum.add(p, n);
      size += n;
    });
    write_state(state);
    state.flush();
    const uint64_t trailer[2] = {size, sum.value()};
    out.write(reinterpret_cast<const char*>(trailer), sizeof trailer);
    out.flush();
    if (!out) {
      out.close();
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

namespace {

// Rank 0's reading of the header and trailer: the verdict every rank gets (ranks.h: broadcast).
struct Opened {
  uint8_t status = 0;  // 0: none, 1: resumable, 2: refused (why)
  std::string why;
  int32_t rounds = 0;
  uint64_t size = 0, sum = 0;
};

Opened open_on_rank0(const std::string& path, const std::string& key, std::ifstream& in) {
  Opened o;
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return o;
  o.status = 2;
  const uint64_t file_size = std::filesystem::file_size(path, ec);
  in.open(path, std::ios::binary);
  const size_t magic = sizeof kMagic - 1;
  std::string head(magic, '\0');
  if (ec || !in.read(head.data(), std::streamsize(magic)) || head != kMagic) {
    o.why = "not a walkrad solve checkpoint";
    return o;
  }
  uint64_t length = 0;
  std::string saved;
  if (in.read(reinterpret_cast<char*>(&length), 8) && length < (uint64_t(1) << 24)) {
    saved.resize(size_t(length));
    in.read(saved.data(), std::streamsize(length));
  }
  in.read(reinterpret_cast<char*>(&o.rounds), sizeof o.rounds);
  const uint64_t header = magic + 8 + length + sizeof o.rounds;
  uint64_t trailer[2] = {};
  if (in && file_size >= header + sizeof trailer) {
    in.seekg(std::streamoff(file_size - sizeof trailer));
    in.read(reinterpret_cast<char*>(trailer), sizeof trailer);
    in.seekg(std::streamoff(header));
  }
  if (!in || trailer[0] != file_size - header - sizeof trailer) {
    o.why = "damaged checkpoint (truncated)";
    return o;
  }
  try {
    o.why = difference(nlohmann::json::parse(saved), nlohmann::json::parse(key));
    if (!o.why.empty()) o.why = "cannot resume: " + o.why + " (remove it, or bake without --resume)";
  } catch (const nlohmann::json::exception&) {
    o.why = "damaged checkpoint (its header does not parse)";
  }
  if (!o.why.empty()) return o;
  o.status = 1, o.size = trailer[0], o.sum = trailer[1];
  return o;
}

}  // namespace

bool CheckpointFile::open(int& rounds, std::unique_ptr<ByteReader>& state) const {
  auto in = std::make_shared<std::ifstream>();
  Opened o;
  ByteWriter verdict;
  if (ranks().rank == 0) {
    o = open_on_rank0(path(), key_, *in);
    verdict.put(o.status), verdict.put(o.rounds), verdict.put(o.size), verdict.put(o.sum);
    verdict.put_string(o.why);
  }
  broadcast(verdict.bytes());
  ByteReader v(verdict.bytes());
  o.status = v.get<uint8_t>(), o.rounds = v.get<int32_t>(), o.size = v.get<uint64_t>(), o.sum = v.get<uint64_t>();
  o.why = v.get_string();
  if (o.status == 0) return false;
  if (o.status == 2) throw InputError(path(), "", o.why);
  rounds = o.rounds;
  // Each piece: read by rank 0, sent to the others, summed by all; the sum checked at the last byte.
  auto sum = std::make_shared<Checksum>();
  auto left = std::make_shared<uint64_t>(o.size);
  state = std::make_unique<ByteReader>(
      [in, sum, left, expected = o.sum, file = path()](uint8_t* dst, size_t n) {
        if (ranks().rank == 0 && !in->read(reinterpret_cast<char*>(dst), std::streamsize(n)))
          throw InputError(file, "", "cannot read the checkpoint");
        broadcast(dst, n);
        sum->add(dst, n);
        *left -= n;
        if (*left == 0 && sum->value() != expected) throw ByteFormatError("its checksum does not match");
      },
      o.size);
  return true;
}

void CheckpointFile::remove() const {
  if (ranks().rank != 0) return;
  std::error_code ec;
  std::filesystem::remove(path(), ec);
}

}  // namespace walkrad
