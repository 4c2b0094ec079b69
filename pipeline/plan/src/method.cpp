#include "walkrad/plan/method.h"

#include "walkrad/formats/error.h"

namespace walkrad {

const char* method_name(Method method) { return method == Method::classic ? "classic" : "hierarchical"; }

Method parse_method(const std::string& word) {
  if (word == "hierarchical") return Method::hierarchical;
  if (word == "classic") return Method::classic;
  throw InputError("--method", "", "unknown method '" + word + "' (available: hierarchical, classic)", kExitBadArguments);
}

}  // namespace walkrad
