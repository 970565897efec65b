#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace ply_slam {

// A run writes its outputs into a folder an earlier run may have filled: an output this run
// does not write (a dense map with too few keyframes, the grid switched off) would stay
// beside the new ones as if it were theirs (issue #53). Removes those of `names` (relative
// to `folder`) that are regular files, and returns them. A link is left: it is the user's, and
// its target is written through.
std::vector<std::string> removeEarlierOutputs(const std::filesystem::path& folder,
                                              const std::vector<std::string>& names);

}  // namespace ply_slam
