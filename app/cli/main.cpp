// rcsim: automotive radar target list simulation by reflection centers (see README.md).
#include "cli/command_line.hpp"

int main(int argc, char** argv) { return rcsim::cli::run_command_line(argc, argv); }
