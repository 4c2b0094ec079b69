#include "json_util.h"

#include "input_limits.h"
#include "walkrad/formats/error.h"

namespace walkrad::json_util {

json parse_file(const std::string& path) {
  const std::vector<unsigned char> text = input_limits::read_file(path, input_limits::kMaxJsonBytes, "JSON file");
  input_limits::check_json_depth(reinterpret_cast<const char*>(text.data()), text.size(), path);
  try {
    return json::parse(text.begin(), text.end());
  } catch (const json::parse_error& e) {
    throw InputError(path, "byte " + std::to_string(e.byte), "not valid JSON");
  } catch (const json::out_of_range&) {
    // A number too large for a double (e.g. 1e99999): nlohmann reports it as out_of_range 406.
    throw InputError(path, "", "not valid JSON: a number is out of range");
  }
}

void check_keys(const json& obj, std::initializer_list<const char*> allowed, const std::string& file,
                const std::string& pointer) {
  if (!obj.is_object()) throw InputError(file, pointer.empty() ? "/" : pointer, "expected an object");
  for (const auto& item : obj.items()) {
    bool known = false;
    for (const char* a : allowed) known = known || item.key() == a;
    if (!known) {
      std::string list;
      for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      throw InputError(file, pointer + "/" + item.key(), "unknown field (expected one of: " + list + ")");
    }
  }
}

const json& member(const json& obj, const char* key, const std::string& file, const std::string& pointer) {
  if (!obj.is_object()) throw InputError(file, pointer.empty() ? "/" : pointer, "expected an object");
  const auto it = obj.find(key);
  if (it == obj.end()) throw InputError(file, pointer + "/" + key, "missing required field");
  return *it;
}

const json* optional_member(const json& obj, const char* key) {
  const auto it = obj.find(key);
  return it == obj.end() ? nullptr : &*it;
}

double number(const json& j, const std::string& file, const std::string& pointer) {
  if (!j.is_number()) throw InputError(file, pointer, "expected a number");
  const double v = j.get<double>();
  if (!std::isfinite(v)) throw InputError(file, pointer, "not a finite number");
  return v;
}

uint64_t count(const json& j, uint64_t max, const std::string& file, const std::string& pointer) {
  if (!j.is_number_unsigned() && !(j.is_number_integer() && j.get<int64_t>() >= 0))
    throw InputError(file, pointer, "expected a non-negative integer");
  const uint64_t v = j.get<uint64_t>();
  if (v > max) throw InputError(file, pointer, std::to_string(v) + " exceeds the limit of " + std::to_string(max), kExitLimitReached);
  return v;
}

std::string string(const json& j, const std::string& file, const std::string& pointer) {
  if (!j.is_string()) throw InputError(file, pointer, "expected a string");
  return j.get<std::string>();
}

Vec3 vec3(const json& j, const std::string& file, const std::string& pointer) {
  if (!j.is_array() || j.size() != 3) throw InputError(file, pointer, "expected an array of 3 numbers");
  return {number(j[0], file, pointer + "/0"), number(j[1], file, pointer + "/1"), number(j[2], file, pointer + "/2")};
}

json to_json(const Vec3& v) { return json::array({v.x, v.y, v.z}); }

}  // namespace walkrad::json_util
