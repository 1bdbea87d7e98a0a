// ocpbench: the command-line program (subcommands live in bench/cli/*_command.cc).
#include "bench/cli/main.h"

int main(int argc, char** argv) { return ocpb::Main(argc, argv); }
