// Eigen aliases shared by every OCPBench module.
#pragma once

#include <Eigen/Core>

namespace ocpb {

using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;
using VecRef = Eigen::Ref<Eigen::VectorXd>;
using MatRef = Eigen::Ref<Eigen::MatrixXd>;
using ConstVecRef = const Eigen::Ref<const Eigen::VectorXd>&;
using ConstMatRef = const Eigen::Ref<const Eigen::MatrixXd>&;

template <typename T, int N>
using VecT = Eigen::Matrix<T, N, 1>;

}  // namespace ocpb
