#include "io/table_data.h"

#include <algorithm>

namespace imunoise::io {

void LineMap::add(std::int64_t row, std::int64_t line) {
  if (breaks_.empty() || row != next_row_ || line != next_line_) breaks_.emplace_back(row, line);
  next_row_ = row + 1;
  next_line_ = line + 1;
}

void LineMap::add_run(std::int64_t row, std::int64_t line, std::int64_t count) {
  if (count <= 0) return;
  add(row, line);  // the rest of the run continues it: add() would record nothing for them
  next_row_ = row + count;
  next_line_ = line + count;
}

std::int64_t LineMap::line_of(std::size_t row) const {
  const auto r = static_cast<std::int64_t>(row);
  auto it = std::upper_bound(breaks_.begin(), breaks_.end(), r,
                             [](std::int64_t value, const auto& b) { return value < b.first; });
  if (it == breaks_.begin()) return 0;
  --it;
  return it->second + (r - it->first);
}

}  // namespace imunoise::io
