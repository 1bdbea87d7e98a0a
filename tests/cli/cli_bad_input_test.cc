// Table-driven: every bad input gets exit code 2 and one clear line on stderr naming the field.
#include <algorithm>
#include <filesystem>

#include <gtest/gtest.h>

#include "tests/cli/run_ocpbench.h"

namespace ocpb {
namespace {

using testing::ProgramRun;
using testing::RunOcpbenchProgram;

struct BadInput {
  const char* name;
  std::vector<std::string> args;  // "@SUITE" is replaced by the path of `suite`
  const char* suite;              // suite file text, or nullptr
  const char* expected;           // a substring of the one-line error
};

// A valid case object to mutate.
#define CASE_OK R"("problem": "double-integrator", "solver": "hamiltonian")"

// One row per bad input (clang-format would put every argument on its own line).
// clang-format off
const BadInput kBadInputs[] = {
    {"unknown subcommand", {"frobnicate"}, nullptr, "unknown command 'frobnicate' (valid: list, describe, solve, run"},
    {"list of nothing", {"list", "foo"}, nullptr, "foo not in {problems,solvers,transcriptions,tags}"},
    {"unknown problem", {"solve", "--problem", "nope", "--solver", "hamiltonian"}, nullptr,
     "unknown problem 'nope' (valid: "},
    {"unknown solver", {"solve", "--problem", "double-integrator", "--solver", "nope"}, nullptr,
     "unknown solver 'nope' (valid: "},
    {"unknown transcription",
     {"solve", "--problem", "double-integrator", "--solver", "ipopt", "--transcription", "nope"}, nullptr,
     "unknown transcription 'nope' (valid: "},
    {"transcription for the Hamiltonian solver",
     {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--transcription", "euler"},
     nullptr, "solver 'hamiltonian' takes no transcription"},
    {"unknown terminal form",
     {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--terminal", "soft"}, nullptr,
     "--terminal: unknown form 'soft' (valid: penalty, hard)"},
    {"unknown integrator",
     {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--integrator", "rk45"},
     nullptr, "unknown integrator 'rk45' (valid: euler, rk4)"},
    {"malformed --set",
     {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--set", "tf"}, nullptr,
     "malformed --set 'tf': expected key=value"},
    {"unknown parameter",
     {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--set", "gamma=1"}, nullptr,
     "unknown parameter 'gamma' (valid: "},
    {"NaN parameter",
     {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--set", "C=nan"}, nullptr,
     "malformed --set 'C=nan': 'nan' is not a number"},
    {"infinite parameter",
     {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--set", "C=inf"}, nullptr,
     "parameter 'C' must be finite"},
    {"negative horizon",
     {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--set", "tf=-5"}, nullptr,
     "parameter 'tf' = -5 out of range"},
    {"zero umax",
     {"solve", "--problem", "double-integrator-bounded", "--solver", "hamiltonian", "--set", "umax=0"},
     nullptr, "parameter 'umax' = 0 out of range"},
    {"wrong vector size",
     {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--set", "x0=1"}, nullptr,
     "parameter 'x0' takes 2 value(s), got 1"},
    {"not a number",
     {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--set", "C=1e3x"}, nullptr,
     "'1e3x' is not a number"},
    {"zero intervals", {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--N", "0"},
     nullptr, "N: must be >= 1"},
    {"N beyond memory",
     {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--N", "900000000"}, nullptr,
     "beyond this machine's memory budget"},
    {"malformed --option",
     {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--option", "alpha"}, nullptr,
     "malformed --option 'alpha': expected key=value"},
    {"zero repeats",
     {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--repeats", "0"}, nullptr,
     "repeats: must be in 1..1000"},
    {"missing suite file", {"run", "/nonexistent/suite.json"}, nullptr,
     "/nonexistent/suite.json: cannot read this suite file: No such file or directory"},
    {"continuation without the hard form",
     {"solve", "--problem", "double-integrator", "--solver", "ipopt", "--transcription", "euler",
      "--continuation", "penalty"}, nullptr,
     "continuation: 'penalty' starts the hard form from the penalty solution, so it needs terminal = hard"},
    {"unknown continuation",
     {"solve", "--problem", "double-integrator", "--solver", "ipopt", "--transcription", "euler",
      "--terminal", "hard", "--continuation", "homotopy"}, nullptr,
     "continuation: unknown 'homotopy' (valid: penalty, or none)"},
    {"suite continuation without the hard form", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{"problem": "double-integrator", "methods": [{"solver": "ipopt", "transcription": "euler", "continuation": "penalty"}]}]})",
     "continuation: 'penalty' starts the hard form from the penalty solution, so it needs terminal = hard"},
    {"suite is not JSON", {"run", "@SUITE"}, "{ not json", "not valid JSON"},
    {"suite is a list", {"run", "@SUITE"}, "[1, 2]", "a suite must be a JSON object"},
    {"suite without name", {"run", "@SUITE"}, R"({"groups": [{"methods": [{}]}]})", "name: required"},
    {"suite name with a slash", {"run", "@SUITE"}, R"({"name": "a/b", "groups": [{"methods": [{}]}]})",
     "name: only letters, digits"},
    {"suite unknown top-level key", {"run", "@SUITE"}, R"({"name": "s", "groups": [], "gruops": 1})",
     "unknown key 'gruops'"},
    {"suite without groups", {"run", "@SUITE"}, R"({"name": "s", "groups": []})", "groups: required non-empty list"},
    {"group without methods", {"run", "@SUITE"}, R"({"name": "s", "groups": [{"problem": "x"}]})",
     "groups[0].methods: required non-empty list"},
    {"case unknown key", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "methods": [{"sovler": "x"}]}]})", "unknown key 'sovler'"},
    {"case unknown problem", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{"problem": "nope", "methods": [{"solver": "hamiltonian"}]}]})",
     "groups[0].methods[0]: unknown problem 'nope'"},
    {"case unknown solver", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{"problem": "double-integrator", "methods": [{"solver": "nope"}]}]})",
     "groups[0].methods[0]: unknown solver 'nope'"},
    {"case missing solver", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{"problem": "double-integrator", "methods": [{}]}]})", "solver: required"},
    {"seed of the wrong type", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "seeds": ["one"], "methods": [{}]}]})",
     "seed: must be an integer"},
    {"negative seed", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "seeds": [-1], "methods": [{}]}]})",
     "seed: must be an integer from 0 to 18446744073709551615 (got -1)"},
    {"zero N in a suite", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "N": [0], "methods": [{}]}]})", "N: 0 out of range"},
    {"fractional N", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "N": 10.5, "methods": [{}]}]})", "N: must be an integer"},
    {"parameter of the wrong type", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "set": {"tf": "long"}, "methods": [{}]}]})",
     "set.tf: must be a number or a list of numbers"},
    {"negative horizon in a suite", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "set": {"tf": -1}, "methods": [{}]}]})",
     "parameter 'tf' = -1 out of range"},
    {"unknown parameter in a suite", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "set": {"Rmax": 1}, "methods": [{}]}]})",
     "unknown parameter 'Rmax'"},
    {"options not an object", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "options": [1], "methods": [{}]}]})",
     "options: must be an object"},
    {"option value an object", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "options": {"alpha": {}}, "methods": [{}]}]})",
     "options.alpha: must be a number, boolean, text or list of numbers"},
    {"unknown terminal form in a suite", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "terminal": "soft", "methods": [{}]}]})",
     "unknown form 'soft'"},
    {"transcription missing for ipopt", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{"problem": "double-integrator", "methods": [{"solver": "ipopt"}]}]})",
     "solver 'ipopt' needs a transcription"},
    {"duplicate case", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "methods": [{}, {}]}]})", "duplicate case"},
    {"bad shard", {"run", "@SUITE", "--shard", "3/2"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "methods": [{}]}]})", "--shard '3/2': expected i/n"},
    {"resume and overwrite", {"run", "@SUITE", "--resume", "--overwrite"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "methods": [{}]}]})", "--resume and --overwrite exclude"},
    {"0-based shard", {"run", "@SUITE", "--shard", "0/8"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "methods": [{}]}]})",
     "--shard '0/8': shards are numbered from 1, 1 <= i <= n (as Slurm's --array=1-8"},
    {"malformed shard", {"run", "@SUITE", "--shard", "2of8"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "methods": [{}]}]})",
     "--shard '2of8': expected i/n with 1 <= i <= n"},
    {"no shards", {"run", "@SUITE", "--shard", "1/0"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "methods": [{}]}]})",
     "--shard '1/0': expected i/n with 1 <= i <= n"},
    {"zero jobs", {"run", "@SUITE", "--jobs", "0"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "methods": [{}]}]})",
     "--jobs 0: must be an integer from 1 to 256 (worker processes)"},
    {"too many jobs", {"run", "@SUITE", "--jobs", "1000"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "methods": [{}]}]})",
     "--jobs 1000: must be an integer from 1 to 256"},
    {"merge of a missing directory", {"merge", "/nonexistent/dir"}, nullptr, "merge: no such directory"},
    {"merge without a suite", {"merge", "."}, nullptr,
     "merge: . has no shards.json (written by `ocpbench run --shard`): pass --suite SUITE.json"},
    {"status of a missing directory", {"status", "/nonexistent/dir"}, nullptr, "status: no such directory"},
    {"merge of a suite without shards", {"merge", ".", "--suite", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "methods": [{}]}]})",
     "merge: no records.shard-*.jsonl files in ."},
    // Problem parameters and the problems' own rules (checked before any channel is simulated).
    {"zero Rmax", {"solve", "--problem", "comm-path2d", "--solver", "hamiltonian", "--set", "Rmax=0"},
     nullptr, "parameter 'Rmax' = 0 out of range: need > 0"},
    {"negative Rmax", {"solve", "--problem", "comm-fixed-path", "--solver", "hamiltonian", "--set", "Rmax=-1"},
     nullptr, "parameter 'Rmax' = -1 out of range: need > 0"},
    {"negative bits", {"solve", "--problem", "comm-path2d", "--solver", "hamiltonian", "--set", "c=-150"},
     nullptr, "parameter 'c' = -150 out of range: need >= 0"},
    {"negative bits already sent",
     {"solve", "--problem", "comm-path2d", "--solver", "hamiltonian", "--set", "x3_0=-1"}, nullptr,
     "parameter 'x3_0' = -1 out of range: need >= 0"},
    {"S outside the workspace",
     {"solve", "--problem", "comm-path2d", "--solver", "hamiltonian", "--set", "S=60,10"}, nullptr,
     "comm-path2d: S must lie in the workspace [0, 50]^2"},
    {"D outside the workspace",
     {"solve", "--problem", "comm-path2d", "--solver", "hamiltonian", "--set", "D=10,-5"}, nullptr,
     "parameter 'D' = -5 out of range: need >= 0 and <= 10000"},
    {"S outside a smaller workspace",
     {"solve", "--problem", "comm-path2d", "--solver", "hamiltonian", "--set", "workspace=30"},
     nullptr, "comm-path2d: S must lie in the workspace [0, 30]^2"},
    {"channel grid too coarse",
     {"solve", "--problem", "comm-path2d", "--solver", "hamiltonian", "--set", "grid_step=20"},
     nullptr, "grid_step: workspace / grid_step = 2.5 points per side; need 4 to 4000"},
    {"unknown estimator",
     {"solve", "--problem", "comm-path2d", "--solver", "hamiltonian", "--set", "estimator=3"},
     nullptr, "parameter 'estimator' = 3 out of range: need >= 0 and <= 2"},
    {"base outside the workspace",
     {"solve", "--problem", "comm-path2d", "--solver", "hamiltonian", "--set", "base=500,500"}, nullptr,
     "base must lie in the workspace [0, 50]^2"},
    {"t0 at tf", {"solve", "--problem", "comm-path2d", "--solver", "hamiltonian", "--set", "t0=40"}, nullptr,
     "comm-path2d: t0 must satisfy 0 <= t0 < tf"},
    {"trailing comma in --set",
     {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--set", "tf=1,"}, nullptr,
     "malformed --set 'tf=1,': value 2 is empty"},
    {"empty item in a vector --set",
     {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--set", "x0=1,,0"}, nullptr,
     "malformed --set 'x0=1,,0': value 2 is empty"},
    // Solver options and algorithms.
    {"unknown --option key",
     {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--option", "bogus=1"}, nullptr,
     "hamiltonian: unknown option 'bogus' (valid: "},
    {"unknown ipopt --option key",
     {"solve", "--problem", "double-integrator", "--solver", "ipopt", "--transcription", "euler",
      "--option", "max_iterations=5"}, nullptr,
     "options: ipopt: unknown option 'max_iterations' (valid: tol, max_iter, "},
    {"unknown algorithm",
     {"solve", "--problem", "double-integrator", "--solver", "nlopt", "--transcription", "single-shooting",
      "--algorithm", "NOPE"}, nullptr,
     "algorithm: nlopt option 'algorithm': must be one of: LD_SLSQP, "},
    {"algorithm for the Hamiltonian solver",
     {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--algorithm", "LD_MMA"}, nullptr,
     "algorithm: solver 'hamiltonian' has no option 'algorithm' (it takes none)"},
    // Channel commands: positions outside the simulated workspace.
    {"channel base outside the workspace", {"channel", "simulate", "--base", "500", "500", "--width", "10"},
     nullptr, "--base: (500, 500) lies outside the workspace [0, 10] x [0, 50] (--width, --height)"},
    {"measurement outside the workspace",
     {"channel", "predict", "--measurements", "@SUITE", "--width", "10", "--resolution", "0.5"},
     "x_m,y_m,gain_db\n1,1,-60\n2,2,-62\n60,5,-70\n",
     "measurement 3 at (60, 5) lies outside the workspace [0, 10] x [0, 50]"},
    // Suites: everything is validated before anything runs.
    {"infinite number in a suite", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "set": {"C": 1e999}, "methods": [{}]}]})",
     "suite.json:1: not valid JSON at column 97: number overflow parsing '1e999'"},
    {"infinite N in a suite", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "N": 1e999, "methods": [{}]}]})",
     "number overflow parsing '1e999'"},
    {"unknown option key in a suite", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "methods": [{"options": {"bogus": 1}}]}]})",
     "groups[0].methods[0]: options: hamiltonian: unknown option 'bogus' (valid: alpha, "},
    {"bad option value in a suite", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "methods": [{"options": {"alpha": "fast"}}]}]})",
     "groups[0].methods[0]: options: hamiltonian option 'alpha': must be a number in (0, 1) (got 'fast')"},
    {"unknown ipopt option in a suite", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{"problem": "double-integrator", "methods": [{"solver": "ipopt",
          "transcription": "euler", "options": {"bogus": 1}}]}]})",
     "groups[0].methods[0]: options: ipopt: unknown option 'bogus'"},
    {"unknown algorithm in a suite", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{"problem": "double-integrator", "methods": [{"solver": "nlopt",
          "transcription": "single-shooting", "algorithm": "NOPE"}]}]})",
     "groups[0].methods[0]: algorithm: nlopt option 'algorithm': must be one of: "},
    {"t0 at tf in a suite", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{"problem": "comm-path2d", "set": {"t0": 50},
          "methods": [{"solver": "hamiltonian"}]}]})",
     "groups[0].methods[0]: comm-path2d: t0 must satisfy 0 <= t0 < tf"},
    {"channel rule in a suite", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{"problem": "comm-path2d", "set": {"xi": 0},
          "methods": [{"solver": "hamiltonian"}]}]})",
     "groups[0].methods[0]: channel: xi must be finite and > 0 (dB)"},
    {"sigma_min above sigma_max in a suite", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{"problem": "brachistochrone", "set": {"sigma_min": 2, "sigma_max": 1},
          "methods": [{"solver": "hamiltonian"}]}]})",
     "groups[0].methods[0]: brachistochrone: sigma_min must be < sigma_max"},
    {"N beyond memory in a suite", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "N": 900000000, "methods": [{}]}]})",
     "groups[0].methods[0]: N: 900000000 intervals need about"},
    // Seeds: 0 to 2^64 - 1, never wrapped or saturated, printed as given.
    {"negative --seed", {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--seed", "-1"},
     nullptr, "--seed: must be an integer from 0 to 18446744073709551615 (got '-1')"},
    {"--seed beyond 64 bits",
     {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--seed", "18446744073709551616"},
     nullptr, "--seed: must be an integer from 0 to 18446744073709551615 (got '18446744073709551616')"},
    {"--seed in scientific notation",
     {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--seed", "1e3"}, nullptr,
     "--seed: must be an integer from 0 to 18446744073709551615 (got '1e3')"},
    {"negative --seed of online", {"online", "--problem", "comm-path2d", "--solver", "hamiltonian", "--seed", "-1"},
     nullptr, "--seed: must be an integer from 0 to 18446744073709551615 (got '-1')"},
    {"negative --seed of channel", {"channel", "simulate", "--seed", "-2"}, nullptr,
     "--seed: must be an integer from 0 to 18446744073709551615 (got '-2')"},
    {"suite seed beyond 64 bits", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "seeds": [18446744073709551616], "methods": [{}]}]})",
     "seed: must be an integer from 0 to 18446744073709551615 (got 1.8446744073709552e+19)"},
    {"suite seed 2^63 is not wrapped", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "N": 9223372036854775808, "methods": [{}]}]})",
     "N: 9223372036854775808 out of range [1, 2147483647]"},
    // Nulls are no values: omitting a key takes its default.
    {"null seeds at group level", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "seeds": null, "methods": [{}]}]})",
     "groups[0].seeds: null is not a value (omit the key for the default)"},
    {"null N at group level", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "N": null, "methods": [{}]}]})",
     "groups[0].N: null is not a value"},
    {"null in a seed list", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "seeds": [1, null], "methods": [{}]}]})",
     "groups[0].seeds[1]: null is not a value"},
    {"null terminal at group level", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "terminal": null, "methods": [{}]}]})",
     "groups[0].methods[0].terminal: null is not a value"},
    // Messages name the field, and quote the input on one line.
    {"unknown --evaluate-with",
     {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--evaluate-with", "rk45"},
     nullptr, "--evaluate-with: unknown integrator 'rk45' (valid: euler, rk4)"},
    {"free-time lower bound above tf",
     {"solve", "--problem", "double-integrator-free-time", "--solver", "ipopt", "--transcription", "euler",
      "--set", "tf_min=3"}, nullptr, "tf_min: 3 must be <= tf = 1 (a free final time needs 0 < tf_min"},
    {"free-time upper bound below tf",
     {"solve", "--problem", "double-integrator-free-time", "--solver", "ipopt", "--transcription", "euler",
      "--set", "tf=2", "--set", "tf_max=1.5"}, nullptr, "tf_max: 1.5 must be >= tf = 2"},
    {"newline in an unknown problem name",
     {"solve", "--problem", "double\nintegrator", "--solver", "hamiltonian"}, nullptr,
     "unknown problem 'double\\nintegrator'"},
    {"newline in a suite key", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "methods": [{"a\nb": 1}]}]})", "unknown key 'a\\nb'"},
    // Hostile documents: nesting, sizes, lines.
    {"deeply nested suite", {"run", "@SUITE"},
     R"({"name": "s", "groups": [[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]})",
     "suite.json:1: nesting deeper than 64 levels at column 88"},
    {"suite error on its line", {"run", "@SUITE"},
     "{\"name\": \"s\",\n \"groups\": [{\"problem\": \"double-integrator\",\n  \"seeds\": [1,\n   \"two\"],\n  \"methods\": [{\"solver\": \"hamiltonian\"}]}]}",
     "suite.json:4: groups[0].methods[0].seed: must be an integer from 0"},
    {"suite of too many cases", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "seeds": [1, 2, 3], "N": [1, 2, 3], "methods": [)"
     R"({}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}]},)"
     R"({"problem": "lqr", "solver": "hamiltonian", "seeds": [)"
     "0,1,2,3,4,5,6,7,8,9,0,1,2,3,4,5,6,7,8,9,0,1,2,3,4,5,6,7,8,9,0,1,2,3,4,5,6,7,8,9,0,1,2,3,4,5,6,7,8,9,"
     "0,1,2,3,4,5,6,7,8,9,0,1,2,3,4,5,6,7,8,9,0,1,2,3,4,5,6,7,8,9,0,1,2,3,4,5,6,7,8,9,0,1,2,3,4,5,6,7,8,9"
     R"(], "N": [)"
     "0,1,2,3,4,5,6,7,8,9,0,1,2,3,4,5,6,7,8,9,0,1,2,3,4,5,6,7,8,9,0,1,2,3,4,5,6,7,8,9,0,1,2,3,4,5,6,7,8,9,"
     "0,1,2,3,4,5,6,7,8,9,0,1,2,3,4,5,6,7,8,9,0,1,2,3,4,5,6,7,8,9,0,1,2,3,4,5,6,7,8,9,0,1,2,3,4,5,6,7,8,9"
     R"(], "methods": [{}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, )"
     R"({}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, )"
     R"({}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, )"
     R"({}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, )"
     R"({}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}]}]})",
     "groups: 1160180 cases (seeds x N x methods over the groups); a suite may hold at most 1000000"},
    {"suite read from an endless device", {"run", "/dev/zero"}, nullptr,
     "/dev/zero: more input than allowed (reading stopped there); a suite file may hold at most 16 MiB"},
    // What would fail only at run time is found before running.
    {"scale of the wrong size in a suite", {"run", "@SUITE"},
     R"({"name": "s", "groups": [{"problem": "double-integrator", "methods": [{"solver": "ipopt",
          "transcription": "euler", "options": {"state_scale": [1, 2, 3]}}]}]})",
     "options: euler scaling: state scales (state_scale) must be empty or of size nx = 2 (got 3)"},
    {"more samples than the channel grid has",
     {"solve", "--problem", "comm-path2d", "--solver", "hamiltonian", "--set", "grid_step=2.5"}, nullptr,
     "samples: 500 measurements need 1000 grid points beyond the distance floor"},
    {"samples beyond memory",
     {"solve", "--problem", "comm-path2d", "--solver", "hamiltonian", "--set", "samples=100000"}, nullptr,
     "samples: 100000 measurements (the GP prediction's covariance and its factor, and the channel grid) need "
     "about 320 GB by OCPBench's estimate, beyond this machine's memory budget"},
    {"channel samples beyond memory", {"channel", "predict", "--samples", "100000"}, nullptr,
     "--samples: 100000 measurements (the GP prediction's covariance and its factor, and the channel grid) need"},
    {"online measurements beyond memory",
     {"online", "--problem", "comm-path2d", "--solver", "hamiltonian", "--workspace", "200",
      "--truth-resolution", "0.1", "--initial-measurements", "1000000"}, nullptr,
     "online.initial_measurements, online.measurements_per_update: 1000300 measurements (the GP"},
    // Output places, checked before anything runs.
    {"--json is a directory",
     {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--json", "."}, nullptr,
     "--json .: is a directory, not a file"},
    {"--json under a file",
     {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--json", "@SUITE"},
     "placeholder: replaced below by a path under this file", "is a file, not a folder"},
    {"--json name too long",
     {"solve", "--problem", "double-integrator", "--solver", "hamiltonian", "--json",
      "aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa"
      "aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa"
      "aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa.json"},
     nullptr, "is longer than the 255 characters the file system allows"},
    {"--out is a file", {"run", "@SUITE", "--out", "@SUITE"},
     R"({"name": "s", "groups": [{)" CASE_OK R"(, "methods": [{}]}]})", "is a file, not a folder"},
    {"online --json is a directory",
     {"online", "--problem", "comm-path2d", "--solver", "hamiltonian", "--json", "."}, nullptr,
     "--json .: is a directory, not a file"},
    {"channel --out is a file", {"channel", "simulate", "--out", "@SUITE"}, "not a folder", "is a file, not a folder"},
};
// clang-format on

class CliBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(CliBadInput, ExitsWithCode2AndOneClearLine) {
  const BadInput& bad = GetParam();
  const std::string dir = testing::FreshDirectory("bad-input");
  std::vector<std::string> args = bad.args;
  if (bad.suite) {
    testing::WriteText(dir + "/suite.json", bad.suite);
    for (size_t i = 0; i < args.size(); ++i) {
      // A --json given as @SUITE names a file inside the suite file (which is not a folder).
      const bool json = i > 0 && args[i - 1] == "--json";
      if (args[i] == "@SUITE") args[i] = dir + "/suite.json" + (json ? "/record.json" : "");
    }
  }
  const ProgramRun run = RunOcpbenchProgram(args, dir);
  EXPECT_EQ(run.exit_code, 2) << bad.name << "\nstderr: " << run.err;
  EXPECT_NE(run.err.find(bad.expected), std::string::npos)
      << bad.name << ": expected '" << bad.expected << "' in stderr: " << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << bad.name << ": " << run.err;
  EXPECT_EQ(run.err.rfind("ocpbench: error: ", 0), 0u) << run.err;
  // Nothing was written: the only file in the directory is the suite itself.
  int files = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    files += e.is_regular_file();
  EXPECT_EQ(files, bad.suite ? 1 : 0) << bad.name;
}

INSTANTIATE_TEST_SUITE_P(Table,
                         CliBadInput,
                         ::testing::ValuesIn(kBadInputs),
                         [](const ::testing::TestParamInfo<BadInput>& info) {
                           std::string n = info.param.name;
                           for (char& c : n) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return n;
                         });

TEST(CliBadInput, TableHasAtLeastThirtyCases) { EXPECT_GE(std::size(kBadInputs), 30u); }

}  // namespace
}  // namespace ocpb
