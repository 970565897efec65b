#pragma once

#include <ros/service_client.h>

#include <chrono>
#include <memory>
#include <string>

#include "ply_slam/common/bounded_call.h"

namespace ply_slam {

// A roscpp service call that gives up: ServiceClient::call waits for ever for a server that
// stopped answering. The server must be up now (as call() wants it; `up_within` > 0 waits that
// long for it) and answer within `timeout` with response.success (every ply_slam service has
// success and message). Returns "" then (the answer copied into `service`), else why not,
// naming the service; a refusal's answer is copied too.
template <class Service>
std::string callService(ros::ServiceClient& client, Service& service,
                        std::chrono::milliseconds timeout, double up_within_s = 0) {
  const std::string name = client.getService();
  const bool up =
      up_within_s > 0 ? client.waitForExistence(ros::Duration(up_within_s)) : client.exists();
  if (!up) return name + " is not up";
  const double seconds = std::chrono::duration<double>(timeout).count();
  auto shared = std::make_shared<Service>(service);
  const std::optional<bool> answered =
      callWithin([client, shared]() mutable { return client.call(*shared); }, timeout);
  if (!answered) return name + " did not answer within " + std::to_string(seconds) + " s";
  if (!*answered) return name + " did not answer";
  service = *shared;
  if (!service.response.success) return name + " refused: " + service.response.message;
  return "";
}

}  // namespace ply_slam
