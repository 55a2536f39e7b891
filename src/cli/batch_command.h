#pragma once
// `igm batch`: `igm run` over a data set, every mesh in its own process with a wall-time and a
// memory limit, one JSON line per mesh in OUT/results.jsonl, resumable, safe to run several at
// once on the same OUT (GNU parallel). Usage and the line's fields: batch_command.cpp's top.
#include <string_view>
#include <vector>

namespace igm_cli {

/// igm batch DIR|LIST|MESH -o OUT [-j N] [--timeout S] [--memory-mb M] [-- RUN OPTIONS]
/// igm batch --summary -o OUT
/// Exit 0 when every mesh of the job has its line (whatever the verdicts), 2 on a usage error,
/// an unreadable input or an unwritable OUT.
int batch_command(const std::vector<std::string_view>& args);

}  // namespace igm_cli
