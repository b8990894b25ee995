// libFuzzer target: users' LCM type definitions (io/lcm_type_definition.h). The input up to
// its first NUL byte is the text of a .lcm file; the bytes after it are one encoded message.
// Every struct the text defines is fingerprinted and decoded (decode_all) from those bytes,
// and a few field paths are selected and decoded by slot. Parsing may throw only InputError;
// decoding never throws (a malformed message is a false return).
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz/fuzz_support.h"
#include "io/lcm_field_decoder.h"
#include "io/lcm_fingerprint.h"
#include "io/lcm_type_definition.h"

using namespace imunoise;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto* nul = static_cast<const std::uint8_t*>(std::memchr(data, 0, size));
  const std::size_t text_size = nul != nullptr ? static_cast<std::size_t>(nul - data) : size;
  const std::string_view text(reinterpret_cast<const char*>(data), text_size);
  const std::span<const unsigned char> message =
      nul != nullptr ? std::span<const unsigned char>(nul + 1, size - text_size - 1)
                     : std::span<const unsigned char>();

  io::LcmTypeFile file;
  bool parsed = false;
  fuzz::expect_only_typed_errors("parse_lcm_type_definition", [&] {
    file = io::parse_lcm_type_definition(text, "fuzz.lcm");
    parsed = true;
  });
  if (!parsed) return 0;
  fuzz::expect_only_typed_errors("find_struct", [&] { (void)file.find_struct(""); });

  for (std::size_t s = 0; s < file.structs.size() && s < 8; ++s) {
    (void)io::lcm_fingerprint(file, s);
    fuzz::expect_only_typed_errors("LcmFieldDecoder", [&] {
      (void)file.find_struct(file.structs[s].full_name());
      io::LcmFieldDecoder decoder(file, s);
      // The message is decoded with this struct's fingerprint in front of the fuzzed bytes.
      std::vector<unsigned char> encoded(8);
      const std::uint64_t fp = decoder.fingerprint();
      for (int b = 0; b < 8; ++b) encoded[b] = static_cast<unsigned char>(fp >> (56 - 8 * b));
      encoded.insert(encoded.end(), message.begin(), message.end());

      std::vector<io::LcmFieldValue> values;
      std::string error;
      (void)decoder.decode_all(encoded, values, error);

      // Select the members as whole fields and as first elements (most fail: InputError).
      for (const io::LcmMember& m : file.structs[s].members) {
        for (const std::string& field : {m.name, m.name + "[0]", m.name + "[1][0]"}) {
          try {
            (void)decoder.add_field(field);
          } catch (const InputError&) {
          }
        }
        if (decoder.slot_count() > 64) break;
      }
      io::LcmSlotValues slots;
      (void)decoder.decode(encoded, slots, error);
      (void)decoder.decode(std::span<const unsigned char>(encoded).first(8), slots, error);
    });
  }
  return 0;
}
