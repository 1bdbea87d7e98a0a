// The solvers and transcriptions OCPBench knows by name.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "solvers/solver.h"
#include "transcriptions/transcription.h"

namespace ocpb {

struct SolverInfo {
  std::string name;
  std::string description;
  std::function<std::unique_ptr<Solver>()> make;
  bool uses_transcription = false;  ///< solves an NLP from a transcription
};

struct TranscriptionInfo {
  std::string name;
  std::string description;
  std::function<std::unique_ptr<Transcription>()> make;
};

const std::vector<SolverInfo>& Solvers();
const std::vector<TranscriptionInfo>& Transcriptions();
/// Throw std::invalid_argument listing the valid names when `name` is unknown.
const SolverInfo& FindSolver(const std::string& name);
const TranscriptionInfo& FindTranscription(const std::string& name);

}  // namespace ocpb
