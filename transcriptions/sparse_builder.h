// Assembly of a fixed sparsity pattern from (possibly overlapping) dense blocks.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace ocpb {

/// A set of unique (row, col) entries, each with a slot: its position in the value array.
///
/// Transcriptions register every dense block a derivative may touch, once, at construction;
/// Slot() returns the same slot for the same (row, col), so overlapping blocks share entries and
/// the final triplet list has no duplicates. Evaluation then zeroes the value array and adds
/// each block's contribution through the stored slots (values of shared entries are summed).
class TripletPattern {
 public:
  TripletPattern(int rows, int cols);

  /// The slot of (row, col), created on first use. Requires 0 <= row < rows, 0 <= col < cols.
  int Slot(int row, int col);
  /// The slots of the dense block rows x cols, row-major: out[i * cols.size() + j] is the slot of
  /// (rows[i], cols[j]). When `lower_only`, entries with row < col get slot -1 instead.
  std::vector<int> Block(const std::vector<int>& rows,
                         const std::vector<int>& cols,
                         bool lower_only = false);

  int size() const { return static_cast<int>(rows_.size()); }
  const std::vector<int>& rows() const { return rows_; }
  const std::vector<int>& cols() const { return cols_; }

 private:
  int num_rows_;
  int num_cols_;
  std::vector<int> rows_, cols_;
  std::unordered_map<std::int64_t, int> index_;
};

}  // namespace ocpb
