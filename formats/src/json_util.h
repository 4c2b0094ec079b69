// Strict JSON field access for walkrad's own schemas: every fault names the file and a JSON pointer.
#pragma once

#include <initializer_list>
#include <string>

#include <nlohmann/json.hpp>

#include "walkrad/formats/vec3.h"

namespace walkrad::json_util {

using nlohmann::json;

// Parses a file; a missing file or a syntax error becomes an InputError naming the file.
json parse_file(const std::string& path);

// Refuses keys not in `allowed` (a misspelt field must not silently fall back to a default).
void check_keys(const json& obj, std::initializer_list<const char*> allowed, const std::string& file,
                const std::string& pointer);
const json& member(const json& obj, const char* key, const std::string& file, const std::string& pointer);
const json* optional_member(const json& obj, const char* key);
// A finite number.
double number(const json& j, const std::string& file, const std::string& pointer);
// A non-negative integer no larger than max.
uint64_t count(const json& j, uint64_t max, const std::string& file, const std::string& pointer);
std::string string(const json& j, const std::string& file, const std::string& pointer);
// [x, y, z] of finite numbers.
Vec3 vec3(const json& j, const std::string& file, const std::string& pointer);
json to_json(const Vec3& v);

}  // namespace walkrad::json_util
