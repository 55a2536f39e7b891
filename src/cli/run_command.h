#pragma once
// `igm run` and the no-argument default: the whole pipeline with progress per stage.
#include <string_view>
#include <vector>

namespace igm_cli {

/// igm run MESH [-o DIR] [--resolution N] [--root V]. Exit 0 certified, 1 the certifier rejected
/// an output (written anyway, for inspection), 2 invalid input or usage, 3 internal error.
int run_command(const std::vector<std::string_view>& args);

/// The built-in default: the pipeline on a generated genus-2 mesh, outputs in ./out.
int run_default();

}  // namespace igm_cli
