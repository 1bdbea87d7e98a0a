#include "transcriptions/sparse_builder.h"

#include <stdexcept>

namespace ocpb {

TripletPattern::TripletPattern(int rows, int cols) : num_rows_(rows), num_cols_(cols) {}

int TripletPattern::Slot(int row, int col) {
  if (row < 0 || row >= num_rows_ || col < 0 || col >= num_cols_) {
    throw std::logic_error("TripletPattern::Slot: entry outside the matrix");
  }
  const std::int64_t key = static_cast<std::int64_t>(row) * num_cols_ + col;
  const auto [it, inserted] = index_.emplace(key, size());
  if (inserted) {
    rows_.push_back(row);
    cols_.push_back(col);
  }
  return it->second;
}

std::vector<int> TripletPattern::Block(const std::vector<int>& rows,
                                       const std::vector<int>& cols,
                                       bool lower_only) {
  std::vector<int> slots;
  slots.reserve(rows.size() * cols.size());
  for (int r : rows) {
    for (int c : cols) slots.push_back(lower_only && r < c ? -1 : Slot(r, c));
  }
  return slots;
}

}  // namespace ocpb
