// libFuzzer target: the bytes as an imunoise binary recording (io/binary_recording.h) through
// io::read_binary_header and io::read_binary_recording. Only InputError / AnalysisError may
// escape; a file that reads must write back (io::write_binary_recording) and read again to the
// same samples, bit for bit.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz/fuzz_support.h"
#include "io/binary_recording.h"

using namespace imunoise;

namespace {

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::bit_cast<std::uint64_t>(a[i]) != std::bit_cast<std::uint64_t>(b[i])) return false;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static fuzz::ScratchFile file("recording.imnb");
  static fuzz::ScratchFile copy("copy.imnb");
  const std::string& path = file.write(data, size);
  fuzz::expect_only_typed_errors("read_binary_header", [&] { (void)io::read_binary_header(path); });
  pipeline::Recording rec;
  bool ok = false;
  fuzz::expect_only_typed_errors("read_binary_recording", [&] {
    rec = io::read_binary_recording(path);
    ok = true;
  });
  if (!ok) return 0;
  pipeline::Recording again;
  fuzz::expect_only_typed_errors("write and read back", [&] {
    io::write_binary_recording(copy.path(), rec);
    again = io::read_binary_recording(copy.path());
  });
  bool same = same_bits(rec.time_s, again.time_s) && rec.channels.size() == again.channels.size();
  for (std::size_t c = 0; same && c < rec.channels.size(); ++c) {
    same = rec.channels[c].name == again.channels[c].name &&
           same_bits(rec.channels[c].values, again.channels[c].values);
  }
  if (!same) fuzz::property_failed("binary round trip", "the rewritten file reads differently");
  return 0;
}
