#include "ply_slam/io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "ply_slam/io/file_writes.h"

namespace ply_slam {
namespace fs = std::filesystem;
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& why) {
  throw FileWriteError(path, why);
}

// Where the content ends up (a link's target, so that links stay links) and the temporary
// file beside it.
struct Destination {
  fs::path final_path, temp_path;
};

Destination prepare(const std::string& path) {
  Destination d{path, {}};
  std::error_code error;
  if (fs::is_symlink(fs::symlink_status(d.final_path, error))) {
    const fs::path target = fs::weakly_canonical(d.final_path, error);
    if (!error) d.final_path = target;
  }
  const fs::file_status status = fs::status(d.final_path, error);
  if (fs::exists(status) && fs::is_directory(status)) fail(path, "it is a directory");
  if (fs::exists(status) && !fs::is_regular_file(status))
    fail(path, "it is not a regular file (" + d.final_path.string() + ")");
  // Unique within the process too: threads may write files of the same name.
  static std::atomic<unsigned> counter{0};
  const std::string prefix =
      ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + "-";
  d.temp_path = d.final_path.parent_path() / (prefix + d.final_path.filename().string());
  return d;
}

// The data on the disk before the rename: after a crash the file is either old or whole.
bool syncToDisk(const fs::path& file) {
  const int fd = ::open(file.c_str(), O_RDONLY);
  if (fd < 0) return false;
  const bool synced = ::fsync(fd) == 0;
  return ::close(fd) == 0 && synced;
}

void putInPlace(const Destination& d, const std::string& path) {
  std::error_code error;
  if (!fs::is_regular_file(d.temp_path, error)) fail(path, "the writer produced no file");
  if (!syncToDisk(d.temp_path)) {
    const std::string why = std::strerror(errno);
    fs::remove(d.temp_path, error);
    fail(path, "cannot flush it to disk: " + why);
  }
  fs::rename(d.temp_path, d.final_path, error);
  if (error) {
    std::error_code ignored;
    fs::remove(d.temp_path, ignored);
    fail(path, error.message());
  }
}

}  // namespace

AtomicFile::AtomicFile(const std::string& path, std::ios::openmode mode) : path_(path) {
  const Destination d = prepare(path);
  final_ = d.final_path.string();
  temp_ = d.temp_path.string();
  out_.open(temp_, mode | std::ios::out | std::ios::trunc);
  if (!out_) fail(path_, std::string("cannot create ") + temp_ + ": " + std::strerror(errno));
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  out_.close();
  std::error_code ignored;
  fs::remove(temp_, ignored);
}

void AtomicFile::commit() {
  out_.close();
  committed_ = true;  // from here the temporary file is either renamed or removed
  if (out_.fail()) {
    std::error_code ignored;
    fs::remove(temp_, ignored);
    fail(path_, "writing failed (disk full?)");
  }
  putInPlace({final_, temp_}, path_);
}

void writeFileAtomically(const std::string& path,
                         const std::function<bool(const std::string& temp_path)>& write,
                         const std::function<std::string(const std::string& temp_path)>& check) {
  const Destination d = prepare(path);
  bool written = false;
  std::string why = "the writer reported a failure";
  try {
    written = write(d.temp_path.string());
  } catch (const std::exception& e) {
    why = e.what();
  }
  if (written && check) {
    const std::string problem = check(d.temp_path.string());
    if (!problem.empty()) written = false, why = problem;
  }
  if (!written) {
    std::error_code ignored;
    fs::remove(d.temp_path, ignored);
    fail(path, why);
  }
  putInPlace(d, path);
}

void writeTextFileAtomically(const std::string& path, const std::string& text) {
  AtomicFile file(path);
  file.stream() << text;
  file.commit();
}

}  // namespace ply_slam
