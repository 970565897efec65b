#pragma once

#include <cstddef>
#include <string>

namespace ply_slam {

// The word a config file uses for one value of an enum: modes are parsed into enums once, when
// the config is loaded, and written back as the same words (summary.json, logs).
template <typename Enum>
struct EnumWord {
  Enum value;
  const char* word;
};

template <typename Enum, std::size_t N>
const char* wordOf(const EnumWord<Enum> (&words)[N], Enum value) {
  for (const auto& w : words)
    if (w.value == value) return w.word;
  return "?";
}

// False, `value` untouched, for a word not in the table.
template <typename Enum, std::size_t N>
bool valueOf(const EnumWord<Enum> (&words)[N], const std::string& word, Enum& value) {
  for (const auto& w : words) {
    if (word != w.word) continue;
    value = w.value;
    return true;
  }
  return false;
}

}  // namespace ply_slam
