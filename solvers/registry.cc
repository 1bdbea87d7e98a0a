#include "solvers/registry.h"

#include <stdexcept>

namespace ocpb {
namespace {

std::vector<SolverInfo> BuildSolvers() {
  std::vector<SolverInfo> list;
  // [solvers] one push_back per solver, in the order `ocpbench list solvers` prints them.
  return list;
}

std::vector<TranscriptionInfo> BuildTranscriptions() {
  std::vector<TranscriptionInfo> list;
  // [transcriptions] one push_back per transcription.
  return list;
}

template <class Info>
const Info& FindByName(const std::vector<Info>& list, const std::string& name, const char* what) {
  std::string names;
  for (const Info& i : list) {
    if (i.name == name) return i;
    names += (names.empty() ? "" : ", ") + i.name;
  }
  throw std::invalid_argument(std::string("unknown ") + what + " '" + name + "' (valid: " +
                              (names.empty() ? "none" : names) + ")");
}

}  // namespace

const std::vector<SolverInfo>& Solvers() {
  static const std::vector<SolverInfo> list = BuildSolvers();
  return list;
}

const std::vector<TranscriptionInfo>& Transcriptions() {
  static const std::vector<TranscriptionInfo> list = BuildTranscriptions();
  return list;
}

const SolverInfo& FindSolver(const std::string& name) { return FindByName(Solvers(), name, "solver"); }

const TranscriptionInfo& FindTranscription(const std::string& name) {
  return FindByName(Transcriptions(), name, "transcription");
}

}  // namespace ocpb
