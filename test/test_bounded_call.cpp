// callWithin: roscpp's service calls had no time-out (issue #53); a call that never returns
// must not hold its caller beyond the time-out.
#include <gtest/gtest.h>

#include <chrono>
#include <future>
#include <memory>
#include <stdexcept>

#include "ply_slam/common/bounded_call.h"

namespace ply_slam {
namespace {

using std::chrono::milliseconds;

TEST(BoundedCall, AQuickCallGivesItsResult) {
  EXPECT_EQ(callWithin([] { return true; }, milliseconds(5000)), std::optional<bool>(true));
  EXPECT_EQ(callWithin([] { return false; }, milliseconds(5000)), std::optional<bool>(false));
}

TEST(BoundedCall, ACallThatDoesNotReturnIsLeftAfterTheTimeOut) {
  auto release = std::make_shared<std::promise<void>>();
  std::shared_future<void> released = release->get_future().share();
  const auto start = std::chrono::steady_clock::now();
  const std::optional<bool> answer = callWithin(
      [released] {
        released.wait();
        return true;
      },
      milliseconds(200));
  const double waited_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_FALSE(answer.has_value());
  EXPECT_GE(waited_s, 0.19);
  EXPECT_LT(waited_s, 5.0);
  release->set_value();  // the call's thread ends
}

TEST(BoundedCall, AnExceptionOfTheCallReachesTheCaller) {
  EXPECT_THROW(callWithin([]() -> bool { throw std::runtime_error("no"); }, milliseconds(5000)),
               std::runtime_error);
}

}  // namespace
}  // namespace ply_slam
