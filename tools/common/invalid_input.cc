#include "common/invalid_input.h"

#include <stdexcept>

namespace plateball::tools {

void ThrowInvalidInput(const std::string& field, const std::string& value, const std::string& what) {
  throw std::invalid_argument(field + ": value " + value + ": " + what);
}

}  // namespace plateball::tools
