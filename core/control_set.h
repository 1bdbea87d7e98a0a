// The admissible control set U: a product of boxes and Euclidean balls.
#pragma once

#include <string>
#include <vector>

#include "core/types.h"

namespace ocpb {

/// U = B_1 x B_2 x ... where each block acts on a contiguous slice of u and is
///   a box   {v : lower <= v <= upper} (infinite bounds allowed), or
///   a ball  {v : |v - center|_2 <= radius}.
/// Projection onto U is the blockwise projection (exact for products).
class ControlSet {
 public:
  enum class Kind { kBox, kBall };
  struct Block {
    Kind kind = Kind::kBox;
    int offset = 0;  ///< first component of u in this block
    int size = 0;    ///< number of components
    Vec lower;       ///< box only
    Vec upper;       ///< box only
    Vec center;      ///< ball only
    double radius = 0.0;  ///< ball only
  };

  /// An unconstrained set R^n.
  static ControlSet Unbounded(int n);
  /// A single box.
  static ControlSet Box(const Vec& lower, const Vec& upper);

  /// Appends a box block on the next `lower.size()` components.
  ControlSet& AddBox(const Vec& lower, const Vec& upper);
  /// Appends a ball block of dimension `size` centered at 0 (or `center`).
  ControlSet& AddBall(int size, double radius);
  ControlSet& AddBall(const Vec& center, double radius);

  int dimension() const { return dimension_; }
  const std::vector<Block>& blocks() const { return blocks_; }
  /// True when every block is a box (the set is then given by bounds alone).
  bool IsBox() const;
  /// Componentwise bounds that contain U (a ball contributes center +- radius).
  void BoundingBox(Vec* lower, Vec* upper) const;

  /// Euclidean projection onto U.
  void Project(VecRef u) const;
  /// max over blocks of the distance-like violation: box max(lower - u, u - upper, 0);
  /// ball max(|u - c| - r, 0).
  double Violation(ConstVecRef u) const;

 private:
  int dimension_ = 0;
  std::vector<Block> blocks_;
};

}  // namespace ocpb
