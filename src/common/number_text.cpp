#include "ply_slam/common/number_text.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace ply_slam {

namespace {
// strtol/strtod skip leading white space; a user's " 5" is as suspect as "5 ".
bool startsWithSpace(const std::string& text) {
  return !text.empty() && std::isspace(static_cast<unsigned char>(text.front()));
}
}  // namespace

std::optional<long> parseWholeNumber(const std::string& text, long min, long max) {
  if (text.empty() || startsWithSpace(text)) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const long value = std::strtol(text.c_str(), &end, 10);
  if (*end != '\0' || errno == ERANGE || value < min || value > max) return std::nullopt;
  return value;
}

std::optional<double> parseRealNumber(const std::string& text) {
  if (text.empty() || startsWithSpace(text)) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (*end != '\0' || errno == ERANGE || !std::isfinite(value)) return std::nullopt;
  return value;
}

}  // namespace ply_slam
