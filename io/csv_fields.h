/// @file
/// @brief Internal to io/'s result CSV files (fleet.csv, plan.csv): one field written with
/// RFC 4180 quoting and one line split back into its fields, so names holding a comma or a
/// quote (unit and axis names) round-trip.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace imunoise::io {

/// FIELD as a CSV field: quoted (with doubled quotes) when it holds a comma, a quote or a line
/// break.
inline std::string csv_field(const std::string& field) {
  if (field.find_first_of(",\"\r\n") == std::string::npos) return field;
  std::string out = "\"";
  for (char c : field) {
    if (c == '"') out.push_back('"');
    out.push_back(c);
  }
  out.push_back('"');
  return out;
}

/// The fields of LINE (RFC 4180 quoting); false when a quote is not closed.
inline bool split_csv_fields(const std::string& line, std::vector<std::string>& fields) {
  fields.clear();
  std::string field;
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        field.push_back('"');
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        field.push_back(c);
      }
    } else if (c == '"' && field.empty()) {
      quoted = true;
    } else if (c == ',') {
      fields.push_back(field);
      field.clear();
    } else {
      field.push_back(c);
    }
  }
  fields.push_back(field);
  return !quoted;
}

}  // namespace imunoise::io
