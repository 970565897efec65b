// CommandLine: what every tool's command line accepts and refuses.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "ply_slam/common/command_line.h"

namespace {

// Parses `words` (the tool's name first) and returns the values given to --sequence.
std::vector<std::string> sequencesOf(std::vector<std::string> words) {
  std::vector<std::string> seen;
  ply_slam::CommandLine line;
  line.flags = {"--live"};
  line.options = {"--sequence", "--out"};
  line.on_flag = [](const std::string&) {};
  line.on_option = [&](const std::string& option, const std::string& value) {
    if (option == "--sequence") seen.push_back(value);
  };
  std::vector<char*> argv;
  for (std::string& word : words) argv.push_back(word.data());
  line.parse(static_cast<int>(argv.size()), argv.data());
  return seen;
}

std::string usageErrorOf(const std::vector<std::string>& words) {
  try {
    sequencesOf(words);
  } catch (const ply_slam::UsageError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(CommandLine, EachOptionOnceIsTaken) {
  EXPECT_EQ(sequencesOf({"tool", "--sequence", "a", "--out", "o", "--live"}),
            std::vector<std::string>{"a"});
}

// Issue #53: "--sequence A --sequence B" ran on B without a word.
TEST(CommandLine, AnOptionGivenTwiceIsAUsageErrorNamingIt) {
  EXPECT_EQ(usageErrorOf({"tool", "--sequence", "a", "--out", "o", "--sequence", "b"}),
            "--sequence is given twice");
  EXPECT_EQ(usageErrorOf({"tool", "--live", "--sequence", "a", "--live"}), "--live is given twice");
}

TEST(CommandLine, UnknownOptionsAndMissingValuesAreNamed) {
  EXPECT_EQ(usageErrorOf({"tool", "--bogus"}), "unknown option --bogus");
  EXPECT_EQ(usageErrorOf({"tool", "--sequence"}), "missing value after --sequence");
}
