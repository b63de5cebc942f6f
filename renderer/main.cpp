#include "renderer/cli/cli.h"

int main(int argc, char** argv) { return kappa::run_cli(argc, argv); }
