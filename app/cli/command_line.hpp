#pragma once
// The whole command line: parses argv, runs the command, and gives the exit status (README's exit
// statuses). main.cpp calls it, and so does the test build's rcsim_killable (tests/hooks/).
namespace rcsim::cli {

int run_command_line(int argc, char** argv);

}  // namespace rcsim::cli
