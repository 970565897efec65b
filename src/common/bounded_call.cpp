#include "ply_slam/common/bounded_call.h"

#include <future>
#include <memory>
#include <thread>

namespace ply_slam {

std::optional<bool> callWithin(std::function<bool()> call, std::chrono::milliseconds timeout) {
  auto result = std::make_shared<std::promise<bool>>();
  std::future<bool> answer = result->get_future();
  // Detached, so that a call that never returns does not hold this one (a std::async future
  // would wait for it in its destructor).
  std::thread([call = std::move(call), result] {
    try {
      result->set_value(call());
    } catch (...) {
      result->set_exception(std::current_exception());
    }
  }).detach();
  if (answer.wait_for(timeout) != std::future_status::ready) return std::nullopt;
  return answer.get();
}

}  // namespace ply_slam
