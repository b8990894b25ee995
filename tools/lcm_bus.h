/// @file
/// @brief A connection to an LCM bus for the tools that publish or subscribe (publish, live,
/// analyze --publish), with the errors a user can act on.
#pragma once

#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <string>
#include <vector>

#include "io/lcm_messages.h"
#include "pipeline/axis_analysis.h"

namespace imunoise::tools {

/// The default LCM URL (LCM's own default: UDP multicast, TTL 0 = this host only).
inline constexpr const char* kDefaultLcmUrl = "udpm://239.255.76.67:7667?ttl=0";

/// An open LCM instance. Throws InputError naming the URL when LCM cannot start (bad URL, no
/// multicast route for udpm://, unwritable file:// path).
class LcmBus {
 public:
  explicit LcmBus(const std::string& url);
  lcm::LCM& lcm() { return *lcm_; }
  const std::string& url() const { return url_; }

  /// Encodes and publishes `message`; throws InputError when LCM reports a failure.
  template <typename Message>
  void publish(const std::string& channel, const Message& message) {
    if (lcm_->publish(channel, &message) != 0) fail_publish(channel);
  }

 private:
  [[noreturn]] void fail_publish(const std::string& channel) const;
  std::string url_;
  std::unique_ptr<lcm::LCM> lcm_;
};

/// Wall-clock time [µs since the Unix epoch], the utime of published messages.
std::int64_t now_utime_us();

}  // namespace imunoise::tools
