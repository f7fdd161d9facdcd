#include "common/number_format.h"

#include <charconv>

namespace plateball::tools {

std::string FormatNumber(double value) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof(buf), value);
  return std::string(buf, res.ptr);
}

}  // namespace plateball::tools
