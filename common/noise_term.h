/// @file
/// @brief The five IEEE-952 power-law terms of a sensor axis (theory.md §4.1) — the one term
/// enum of every layer — and PerTerm, the one container of a value per term.
#pragma once

#include <array>
#include <cstddef>
#include <string_view>

namespace imunoise {

/// The five IEEE-952 power-law terms, in the order of theory.md §4.3's c = (Q², N², B², K², R²)
/// and of the fields of NoiseCoefficients.
enum class NoiseTerm { quantization, white_noise, bias_instability, random_walk, ramp };

/// All terms in their fixed order; index i of a PerTerm refers to kNoiseTerms[i].
inline constexpr std::array<NoiseTerm, 5> kNoiseTerms = {
    NoiseTerm::quantization, NoiseTerm::white_noise, NoiseTerm::bias_instability,
    NoiseTerm::random_walk, NoiseTerm::ramp};

/// "quantization", "white_noise", "bias_instability", "random_walk" or "ramp": the key of the
/// term in model.yaml and in every output that names it.
constexpr std::string_view term_name(NoiseTerm term) {
  switch (term) {
    case NoiseTerm::quantization:
      return "quantization";
    case NoiseTerm::white_noise:
      return "white_noise";
    case NoiseTerm::bias_instability:
      return "bias_instability";
    case NoiseTerm::random_walk:
      return "random_walk";
    case NoiseTerm::ramp:
      return "ramp";
  }
  return "unknown";
}

/// "Q", "N", "B", "K" or "R": the symbol of the term in theory.md and in every header, label
/// and message that abbreviates it.
constexpr const char* term_symbol(NoiseTerm term) {
  switch (term) {
    case NoiseTerm::quantization:
      return "Q";
    case NoiseTerm::white_noise:
      return "N";
    case NoiseTerm::bias_instability:
      return "B";
    case NoiseTerm::random_walk:
      return "K";
    case NoiseTerm::ramp:
      return "R";
  }
  return "?";
}

/// One T per term in kNoiseTerms order, indexed by the term or by its position: a std::array
/// (aggregate, value-initialised by `{}`) that also takes a NoiseTerm as index.
template <class T>
struct PerTerm : std::array<T, kNoiseTerms.size()> {
  using Base = std::array<T, kNoiseTerms.size()>;
  using Base::operator[];
  constexpr T& operator[](NoiseTerm term) {
    return Base::operator[](static_cast<std::size_t>(term));
  }
  constexpr const T& operator[](NoiseTerm term) const {
    return Base::operator[](static_cast<std::size_t>(term));
  }
};

}  // namespace imunoise
