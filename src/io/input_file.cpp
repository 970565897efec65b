#include "ply_slam/io/input_file.h"

#include <sys/stat.h>

#include <stdexcept>

namespace ply_slam {

std::optional<std::string> specialFileProblem(const std::string& path) {
  struct stat s {};
  if (::stat(path.c_str(), &s) != 0 || S_ISREG(s.st_mode)) return std::nullopt;
  const char* kind = S_ISDIR(s.st_mode)    ? "a directory"
                     : S_ISFIFO(s.st_mode) ? "a named pipe (FIFO)"
                     : S_ISSOCK(s.st_mode) ? "a socket"
                                           : "a device";
  return std::string("is ") + kind + ", not a regular file";
}

void refuseSpecialFile(const std::string& path) {
  if (const auto problem = specialFileProblem(path))
    throw std::runtime_error(path + ": " + *problem);
}

}  // namespace ply_slam
