// Uses the installed igm package: a generated genus-1 mesh through the whole pipeline.
// Exit 0 iff both outputs are certified.
#include <cstdio>

#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"
#include "igm/pipeline/pipeline.h"

int main() {
  igm::GenerateOptions g;
  g.genus = 1;
  g.faces = 200;
  const igm::ValidMesh mesh = igm::validate(igm::generate_closed_mesh(g));
  const igm::PipelineResult r = igm::compute_igm(mesh);
  std::printf("genus %d, %d quads, certified: %s\n", r.stats.genus, r.stats.quads, r.certified() ? "yes" : "no");
  return r.certified() && r.stats.genus == 1 ? 0 : 1;
}
