#include "solvers/descent_rate.h"
#include "solvers/message_number.h"

#include <cmath>

namespace ocpb {

std::optional<DescentRate> MeasureDescentRate(const std::vector<IterationRecord>& history,
                                              std::size_t begin,
                                              double target,
                                              int window) {
  // The rows of the request's grid only (a grid-sequenced solve's coarse rows are another
  // problem), newest first, up to `window` steps back.
  const IterationRecord* last = nullptr;
  const IterationRecord* first = nullptr;
  for (std::size_t i = history.size(); i > begin; --i) {
    const IterationRecord& row = history[i - 1];
    if (row.intervals != -1 || !std::isfinite(row.theta)) continue;
    if (last == nullptr) {
      last = &row;
    } else if (last->iteration - row.iteration <= window) {
      first = &row;
    } else {
      break;
    }
  }
  if (first == nullptr || last->iteration <= first->iteration || first->theta == 0.0) {
    return std::nullopt;
  }
  DescentRate rate;
  rate.steps = last->iteration - first->iteration;
  rate.last_theta = std::abs(last->theta);
  rate.factor = std::pow(rate.last_theta / std::abs(first->theta), 1.0 / rate.steps);
  if (target > 0.0 && rate.last_theta > target && rate.factor < 1.0 && rate.factor > 0.0) {
    rate.steps_to_target = std::log(target / rate.last_theta) / std::log(rate.factor);
  }
  return rate;
}

std::string DescentRateNote(const std::optional<DescentRate>& rate, double target) {
  if (!rate) return "";
  const std::string over = "; over its last " + std::to_string(rate->steps) + " steps |theta| ";
  if (!(rate->factor < 1.0)) {
    return over + "did not fall (" + MessageNumber(rate->last_theta, 3) + " at the end)";
  }
  // Near 1 the factor's digits are in 1 - factor.
  const std::string factor = rate->factor > 0.99 ? "1 - " + MessageNumber(1.0 - rate->factor, 3)
                                                 : MessageNumber(rate->factor, 3);
  std::string note = over + "fell by a factor " + factor + " per step (linear)";
  if (rate->steps_to_target >= 0.0) {
    const double steps = std::ceil(rate->steps_to_target);
    note +=
        ": about " +
        (steps < 1e5 ? std::to_string(static_cast<long long>(steps)) : MessageNumber(steps, 3)) +
        " more to |theta| <= " + MessageNumber(target, 3) + " at that rate";
  }
  return note + "; a Newton end game (polish=true) needs far fewer steps where it converges";
}

}  // namespace ocpb
