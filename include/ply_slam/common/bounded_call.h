#pragma once

#include <chrono>
#include <functional>
#include <optional>

namespace ply_slam {

// Runs `call` on a thread of its own and waits at most `timeout` for its result: std::nullopt
// when it did not return in time (it then goes on alone, on what it captured). For calls that
// can block for ever, such as a roscpp service call to a node that stopped answering.
std::optional<bool> callWithin(std::function<bool()> call, std::chrono::milliseconds timeout);

}  // namespace ply_slam
