// A first-order stationarity check for NLP points that come without multipliers (NLopt).
#pragma once

#include "core/nlp.h"
#include "core/types.h"

namespace ocpb {

/// The stationarity residual of `nlp` at z with least-squares multipliers, relative to the
/// gradient:
///
///   F = the variables more than active_tol max(1, |bound|) inside both bounds,
///   A = the constraint rows with g_l = g_u (equalities) or within active_tol max(1, |bound|) of
///       a bound (or beyond it),
///   lambda = argmin || grad_F f + (J_A,F)^T lambda ||_2,
///   residual = || grad_F f + (J_A,F)^T lambda ||_inf / max(1, || grad f ||_inf).
///
/// A necessary condition only: the multipliers' signs and the variables at their bounds are not
/// checked, so a point that fails it is not a KKT point, and one that passes need not be a
/// minimum. A looser active_tol can only lower the residual (more rows, fewer free variables),
/// so erring loose avoids false alarms near constraints approached from the feasible side.
/// lambda comes from the normal equations (J J^T + delta I) lambda = -J grad (sparse LDL^T,
/// delta = 1e-12 of the largest diagonal entry, one step of iterative refinement); the ridge keeps
/// redundant active rows factorable and biases the residual by about sqrt(delta) |lambda|. NaN when
/// the gradient, the constraints or their Jacobian cannot be evaluated (or the factorization
/// fails).
double NlpStationarity(const Nlp& nlp, ConstVecRef z, double active_tol);

}  // namespace ocpb
