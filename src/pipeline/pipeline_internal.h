#pragma once
// Internal to the pipeline (pipeline.h): the genus-0 branch of compute_igm (sphere_pipeline.cpp)
// and the certification of a run's outputs shared by both branches (pipeline.cpp).
#include "igm/pipeline/pipeline.h"

namespace igm {

/// compute_igm for input.genus == 0 (options already range-checked by compute_igm).
PipelineResult compute_igm_sphere(const ValidMesh& input, const PipelineOptions& options);

/// Runs the independent certifier on result.igm (checks 1-4) and result.quads (check 5, expected
/// genus `genus`) and stores both reports in `result`.
void certify_outputs(PipelineResult& result, int genus, const PipelineOptions& options);

}  // namespace igm
