#include "ply_slam/io/file_writes.h"

#include <exception>

namespace ply_slam {
namespace {

std::string joined(const std::vector<FileWriteFailure>& failures) {
  std::string all;
  for (const auto& failure : failures) all += (all.empty() ? "" : "; ") + failure.message;
  return all;
}

}  // namespace

FileWriteErrors::FileWriteErrors(std::vector<FileWriteFailure> failures)
    : std::runtime_error(joined(failures)), failures_(std::move(failures)) {}

bool FileWrites::attempt(const std::function<void()>& write) {
  try {
    write();
    return true;
  } catch (const FileWriteErrors& e) {
    failures_.insert(failures_.end(), e.failures().begin(), e.failures().end());
  } catch (const FileWriteError& e) {
    failures_.push_back({e.path(), e.what()});
  } catch (const std::exception& e) {
    failures_.push_back({"", e.what()});
  }
  return false;
}

std::vector<std::string> FileWrites::messages() const {
  std::vector<std::string> out;
  for (const auto& failure : failures_) out.push_back(failure.message);
  return out;
}

std::string FileWrites::namesText() const {
  std::string text;
  for (size_t i = 0; i < failures_.size(); ++i) {
    const FileWriteFailure& f = failures_[i];
    text += (i == 0                      ? ""
             : i + 1 == failures_.size() ? " and "
                                         : ", ") +
            (f.file.empty() ? "(" + f.message + ")" : f.file);
  }
  return text;
}

std::string FileWrites::summaryText() const {
  return std::to_string(failures_.size()) + " output(s) not written: " + namesText();
}

std::string FileWrites::reasonsText() const { return joined(failures_); }

void FileWrites::throwFailures() const {
  if (!failures_.empty()) throw FileWriteErrors(failures_);
}

}  // namespace ply_slam
