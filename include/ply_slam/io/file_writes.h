#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace ply_slam {

// A file that could not be written: the message names it ("cannot write PATH: why"), path()
// is the file (AtomicFile's errors are these).
class FileWriteError : public std::runtime_error {
 public:
  FileWriteError(const std::string& path, const std::string& why)
      : std::runtime_error("cannot write " + path + ": " + why), path_(path) {}
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// One failure per file not written, in the order tried.
struct FileWriteFailure {
  std::string file;     // empty when the writer did not say which (then `message` does)
  std::string message;  // names the file
};

// Several outputs written one after another: one that fails (a full disk, a folder in its
// place) does not keep the others off the disk. Each file that fails is kept, so that what
// is reported counts and names the files, not the attempts (one attempt may write several).
class FileWrites {
 public:
  // Runs `write`; returns false and keeps the failures when it throws.
  bool attempt(const std::function<void()>& write);
  const std::vector<FileWriteFailure>& failures() const { return failures_; }
  std::vector<std::string> messages() const;
  // The files not written, for a message ("a, b and c"); the message where a file is unknown.
  std::string namesText() const;
  // "N output(s) not written: " and namesText().
  std::string summaryText() const;
  // Every failure's message, "; " between them.
  std::string reasonsText() const;
  // The failures as one FileWriteErrors, when there are any.
  void throwFailures() const;

 private:
  std::vector<FileWriteFailure> failures_;
};

// What FileWrites::throwFailures throws: every failure, so that an outer FileWrites keeps
// each file of an inner one.
class FileWriteErrors : public std::runtime_error {
 public:
  explicit FileWriteErrors(std::vector<FileWriteFailure> failures);
  const std::vector<FileWriteFailure>& failures() const { return failures_; }

 private:
  std::vector<FileWriteFailure> failures_;
};

}  // namespace ply_slam
