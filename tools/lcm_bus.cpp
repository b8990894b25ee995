#include "tools/lcm_bus.h"

#include <chrono>

#include "common/errors.h"

namespace imunoise::tools {

LcmBus::LcmBus(const std::string& url) : url_(url), lcm_(std::make_unique<lcm::LCM>(url)) {
  if (!lcm_->good()) {
    std::string hint;
    if (url.rfind("udpm://", 0) == 0 || url.empty()) {
      hint =
          " (for udpm:// the host needs a multicast route, e.g. 'ip route add 224.0.0.0/4 "
          "dev lo' for traffic that stays on this machine; or use file://LOG?mode=w)";
    } else if (url.rfind("file://", 0) == 0) {
      hint = " (check the path and mode=r|w|a)";
    }
    throw InputError("--lcm-url '" + url + "': LCM could not start" + hint);
  }
}

void LcmBus::fail_publish(const std::string& channel) const {
  throw InputError("--lcm-url '" + url_ + "': publishing on channel '" + channel +
                   "' failed (LCM rejects channel names of 64 bytes or more and messages it "
                   "cannot send)");
}

std::int64_t now_utime_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace imunoise::tools
