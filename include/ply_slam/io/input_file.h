#pragma once

#include <optional>
#include <string>

namespace ply_slam {

// Why something in the place of an input file cannot be read as one: a directory, a named pipe
// (opening it waits for a writer for ever), a device (/dev/zero never ends), a socket. Nothing
// for a regular file, a link to one, or a path where nothing is (each reader names that its
// own way).
std::optional<std::string> specialFileProblem(const std::string& path);

// Throws std::runtime_error "PATH: <problem>" when specialFileProblem finds one.
void refuseSpecialFile(const std::string& path);

}  // namespace ply_slam
