// ocpbench: the command-line program (subcommands live in bench/cli/*_command.cc).
#include "bench/cli/app.h"

int main(int argc, char** argv) { return ocpb::RunOcpbench(argc, argv); }
