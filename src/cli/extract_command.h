#pragma once
// `igm extract`: the quad mesh of the integer isolines of any IGM file (extract/isolines.h).
#include <string_view>
#include <vector>

namespace igm_cli {

/// igm extract IGM.obj|IGM.exact [-o QUAD.obj] [--json REPORT.json]. Reads the IGM with the
/// certifier's reader (exact UVs), extracts its isoline quads, certifies them (check 5, the IGM's
/// genus) and writes them (default NAME.quad.obj in the current folder). Exit 0 the quads are
/// certified; 1 the certifier rejected the IGM (its witnesses printed and in the JSON; nothing
/// written but the JSON) or the extracted quads (written anyway, for inspection); 2 unreadable
/// input or usage; 3 internal error.
int extract_command(const std::vector<std::string_view>& args);

}  // namespace igm_cli
