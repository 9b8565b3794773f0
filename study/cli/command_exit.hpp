// A subcommand that has said everything it had to say and must end the program with
// a particular exit status (main.cpp returns it): `ballast study` with failed or
// interrupted runs, `ballast merge` with runs missing.
#pragma once

namespace ballast {

struct CommandExit {
  int code;
};

}  // namespace ballast
