// The exit status of a contact2d run, shared by the program (src/cli) and
// the layers that hand a status to it (report/runs.hpp: the extreme cases
// record the status `contact2d simulate` exits with). docs/cli.md lists them.
#pragma once

namespace contact2d {

constexpr int kExitOk = 0;
constexpr int kExitBadInput = 2;  // one line on stderr, before any run
constexpr int kExitDiverged = 3;  // a run failed: an engine diverged, a tool failed

}  // namespace contact2d
