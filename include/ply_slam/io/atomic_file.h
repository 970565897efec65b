#pragma once

#include <fstream>
#include <functional>
#include <string>

namespace ply_slam {

// A file that is never seen half written: everything goes to a temporary file beside it,
// which replaces the file only once writing it succeeded. A full disk or a crash leaves the
// old file (or none), never a truncated one that looks whole. Every failure throws an error
// naming the file (a FileWriteError, file_writes.h). A symbolic link is followed to its target; a
// target that is not a regular file (a directory, a device such as /dev/full) is refused.
class AtomicFile {
 public:
  explicit AtomicFile(const std::string& path, std::ios::openmode mode = std::ios::out);
  ~AtomicFile();  // not committed: the temporary file is removed, the old file stays
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return out_; }
  // Closes and checks the stream, then puts the file in place.
  void commit();

 private:
  std::string path_, final_, temp_;  // as given, where it goes, where it is written
  std::ofstream out_;
  bool committed_ = false;
};

// For writers that take a path: `write` writes the temporary file it is given and returns
// false (or throws) when that failed; the file then replaces `path`. The temporary file keeps
// the extension, which some writers go by. Such writers may report success on a full disk
// (PCL's PLY writer never checks its stream): `check`, when given, reads the temporary file
// back and returns what is wrong with it ("" when whole). Where the bytes can be made in
// memory, write them through AtomicFile instead.
void writeFileAtomically(
    const std::string& path, const std::function<bool(const std::string& temp_path)>& write,
    const std::function<std::string(const std::string& temp_path)>& check = nullptr);

// A whole text file at once.
void writeTextFileAtomically(const std::string& path, const std::string& text);

}  // namespace ply_slam
