// The two methods a bake can run (walkrad bake --method), parsed once from the command line's word.
#pragma once

#include <cstdint>
#include <string>

namespace walkrad {

enum class Method : uint8_t {
  hierarchical,  // hierarchical radiosity with clustering, driven by importance from the viewpoints
  classic,       // uniform elements, the full form factor matrix: the baseline
};

// "hierarchical" or "classic", as the command line and the manifest spell it.
const char* method_name(Method method);
// Throws InputError (exit 2, naming --method and the choices) for another word.
Method parse_method(const std::string& word);

}  // namespace walkrad
