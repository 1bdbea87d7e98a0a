// The comm problems' baseline plan: what a user would run without optimizing anything.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace ocpb {

/// The speed profile of the baseline plan on N forward-Euler steps of length h from rest: speed
/// up at a for m steps, cruise at a h m, brake at -a for m steps. The Euler distance is
/// h sum_k v_k = a h^2 m (N - m), so a = length / (h^2 m (N - m)) covers `length` exactly and
/// the speed ends at 0; m is the smallest step count (1 <= m <= N/2) with a <= umax, so the
/// cruise is as long as the acceleration bound allows ("constant speed, arriving at tf").
/// Returns the N accelerations (a, 0 or -a); zeros for length 0; nullopt with the reason in
/// *why_not when even m = N/2 needs a > umax (the distance cannot be covered in time).
std::optional<std::vector<double>> BaselineAccelerations(
    double length, double h, int N, double umax, std::string* why_not);

/// The constant rate R = (c - sent) / (tf - t0) that sends the remaining bits by tf (forward
/// Euler sums h R over the steps exactly); nullopt with the reason when R is not in [0, Rmax].
std::optional<double> BaselineRate(
    double bits, double sent, double t0, double tf, double rmax, std::string* why_not);

}  // namespace ocpb
