#include "stable32_tables.h"

#include <map>

#include "test_support.h"

namespace imunoise::test {

std::optional<analysis::DeviationType> stable32_type(const std::string& sigma_type) {
  using analysis::DeviationType;
  static const std::map<std::string, DeviationType> kTypes = {
      {"Allan", DeviationType::adev},          {"Overlapping Allan", DeviationType::oadev},
      {"Modified Allan", DeviationType::mdev}, {"Time", DeviationType::tdev},
      {"Hadamard", DeviationType::hdev},       {"Overlapping Hadamard", DeviationType::ohdev},
      {"Total", DeviationType::totdev}};
  const auto it = kTypes.find(sigma_type);
  if (it == kTypes.end()) return std::nullopt;
  return it->second;
}

std::vector<Stable32Row> load_stable32_rows(const std::filesystem::path& csv,
                                            const std::string& source_file) {
  std::vector<Stable32Row> rows;
  const auto raw = read_csv_rows(csv);
  // Header: sigma_type, source_file, stable32_input_file, stable32_version, af, tau_s, n,
  // alpha, sigma_min, sigma, sigma_max, ci_given.
  for (std::size_t i = 1; i < raw.size(); ++i) {
    const auto& r = raw[i];
    if (r.size() < 12) continue;
    if (!source_file.empty() && r[1] != source_file) continue;
    const auto type = stable32_type(r[0]);
    if (!type) continue;
    rows.push_back({r[1], *type, std::stoll(r[4]), std::stod(r[5]), std::stoll(r[6]),
                    std::stoi(r[7]), std::stod(r[8]), std::stod(r[9]), std::stod(r[10]),
                    r[11] == "yes"});
  }
  return rows;
}

}  // namespace imunoise::test
