#include "ply_slam/common/number_text.h"

#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>

namespace ply_slam {

namespace {
// strtol/strtod skip leading white space; a user's " 5" is as suspect as "5 ".
bool startsWithSpace(const std::string& text) {
  return !text.empty() && std::isspace(static_cast<unsigned char>(text.front()));
}
}  // namespace

std::string exactText(double value) {
  std::array<char, 32> text;
  const auto end = std::to_chars(text.data(), text.data() + text.size(), value).ptr;
  return std::string(text.data(), end);
}

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

std::optional<std::pair<int, int>> parseImageSize(const std::string& text) {
  const size_t x = text.find('x');
  if (x == std::string::npos) return std::nullopt;
  const auto width = parseWholeNumber(text.substr(0, x), 1, 100000);
  const auto height = parseWholeNumber(text.substr(x + 1), 1, 100000);
  if (!width || !height) return std::nullopt;
  return std::make_pair(static_cast<int>(*width), static_cast<int>(*height));
}

}  // namespace ply_slam
